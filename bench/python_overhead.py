#!/usr/bin/python3
"""What calling the tessellator from Python costs over calling it from C++ (issue: at most 5%).

    bench/python_overhead.py BUILD_DIR [FILE] [RELATIVE_TOLERANCE] [ROUNDS]

Both sides tessellate the same file with the same options (one thread, no measuring: the
smallest call, where a fixed overhead weighs most), warm, in alternating rounds of 50 runs each
(C++: bench/tessellate_repeat, timed inside its own process; Python: pw.tessellate timed with
perf_counter around the call, the result's arrays included as views). Prints the medians, their
ratio, and the median of the rounds' ratios (each round's two sides run next to each other in
time, which the load of a shared machine changes less between); only ratios of one run count.
"""

import pathlib
import statistics
import subprocess
import sys
import time


def main() -> None:
    build = pathlib.Path(sys.argv[1])
    source = pathlib.Path(__file__).resolve().parent.parent
    path = sys.argv[2] if len(sys.argv) > 2 else str(source / "data" / "teapot.bpt")
    tolerance = float(sys.argv[3]) if len(sys.argv) > 3 else 1e-3
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 5
    sys.path.insert(0, str(build / "python"))
    import patchwork as pw

    runs = 50
    surface = pw.read_patches(path)
    cpp: list[float] = []
    python: list[float] = []
    round_ratios: list[float] = []
    for _ in range(rounds):
        out = subprocess.run([str(build / "bench" / "tessellate_repeat"), path, repr(tolerance), str(runs + 1)],
                             check=True, capture_output=True, text=True).stdout
        cpp_round = [float(line) for line in out.split()][1:]
        pw.tessellate(surface, relative_tolerance=tolerance, threads=1, measure=False)  # warm
        python_round = []
        for _ in range(runs):
            start = time.perf_counter()
            t = pw.tessellate(surface, relative_tolerance=tolerance, threads=1, measure=False)
            python_round.append(time.perf_counter() - start)
        cpp += cpp_round
        python += python_round
        round_ratios.append(statistics.median(python_round) / statistics.median(cpp_round))
    cpp_median, python_median = statistics.median(cpp), statistics.median(python)
    print(f"{path} at relative tolerance {tolerance:g}: {t.triangle_count} triangles, one thread, no measuring")
    print(f"C++    median {cpp_median * 1e3:.3f} ms over {len(cpp)} runs")
    print(f"Python median {python_median * 1e3:.3f} ms over {len(python)} runs")
    print(f"Python / C++ = {python_median / cpp_median:.3f} (target <= 1.05); "
          f"per round (neighbouring in time) median {statistics.median(round_ratios):.3f}, "
          f"range {min(round_ratios):.3f} to {max(round_ratios):.3f}")


if __name__ == "__main__":
    main()
