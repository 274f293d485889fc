#!/usr/bin/python3
"""intersect_curves on random planar cubics with small integer control points (many repeated and
collinear points: cusps at the ends, folded curves), counting errors and slow pairs.

    bench/intersection_stress.py BUILD_DIR [PAIRS_PER_RANGE]

Coordinates are randint(-R, R) / 4 for R = 1, 2, 4, 8 (seed 5). Prints, per R, the errors
(NumericalError), the pairs over 0.1 s, the total and the slowest time, and every pair over 0.3 s.
"""

import pathlib
import random
import sys
import time


def main() -> None:
    sys.path.insert(0, str(pathlib.Path(sys.argv[1]) / "python"))
    import numpy as np
    import patchwork as pw

    pairs = int(sys.argv[2]) if len(sys.argv) > 2 else 15000
    for R in (1, 2, 4, 8):
        rng = random.Random(5)
        slow = errors = 0
        total = worst = 0.0
        for _ in range(pairs):
            a = np.array([[rng.randint(-R, R), rng.randint(-R, R)] for _ in range(4)]) / 4.0
            b = np.array([[rng.randint(-R, R), rng.randint(-R, R)] for _ in range(4)]) / 4.0
            start = time.perf_counter()
            try:
                pw.intersect_curves(pw.BezierCurve(a), pw.BezierCurve(b))
            except pw.NumericalError:
                errors += 1
                print("    error", a.tolist(), b.tolist())
            seconds = time.perf_counter() - start
            total += seconds
            worst = max(worst, seconds)
            if seconds > 0.1:
                slow += 1
                if seconds > 0.3:
                    print("   ", round(seconds, 2), a.tolist(), b.tolist())
        print(f"R = {R}: {pairs} pairs, {errors} errors, {slow} over 0.1 s, total {total:.1f} s, slowest {worst:.2f} s")


if __name__ == "__main__":
    main()
