#!/usr/bin/python3
"""Speed against error for the teapot, as a picture: patchwork's tessellation time and triangle
count against the measured error, for tolerances from 1e-1 to 1e-5 of the box diagonal.

    PYTHONPATH=build/release/python /usr/bin/python3 python/examples/plot_speed_vs_error.py data/teapot.bpt speed.png

Each time is the best of five runs of one tessellation (one thread, no measuring); the measured
error comes from a separate run with measuring on.
"""

import sys
import time

# Debian 12's matplotlib (3.6) ships no type information: its imports are not checked.
import matplotlib  # type: ignore[import]

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # type: ignore[import]  # noqa: E402
import numpy as np  # noqa: E402

import patchwork as pw  # noqa: E402


def best_seconds(surface: pw.PreparedSurface, relative_tolerance: float, runs: int = 5) -> float:
    """The fastest of `runs` tessellations, seconds."""
    best = float("inf")
    for _ in range(runs):
        start = time.perf_counter()
        pw.tessellate(surface, relative_tolerance=relative_tolerance, measure=False, threads=1)
        best = min(best, time.perf_counter() - start)
    return best


def main(path: str, output: str) -> None:
    patches = pw.read_patches(path)
    surface = pw.PreparedSurface(patches)
    tolerances = np.logspace(-1, -5, 9)
    seconds, errors, triangles = [], [], []
    for tolerance in tolerances:
        measured = pw.tessellate(surface, relative_tolerance=float(tolerance), threads=1)
        errors.append(measured.measured_error)
        triangles.append(measured.triangle_count)
        seconds.append(best_seconds(surface, float(tolerance)))
    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    left.loglog(errors, np.array(seconds) * 1e3, "o-")
    left.set_xlabel("measured error (model units)")
    left.set_ylabel("tessellation time (ms, one thread)")
    left.grid(True, which="both", alpha=0.3)
    right.loglog(errors, triangles, "o-")
    right.set_xlabel("measured error (model units)")
    right.set_ylabel("triangles")
    right.grid(True, which="both", alpha=0.3)
    figure.suptitle(f"patchwork: {path}, {len(patches)} patches")
    figure.tight_layout()
    figure.savefig(output, dpi=120)
    for t, e, n, s in zip(tolerances, errors, triangles, seconds):
        print(f"relative tolerance {t:.1e}: measured error {e:.3e}, {n} triangles, {s * 1e3:.3f} ms")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_speed_vs_error.py FILE.bpt OUTPUT.png")
    main(sys.argv[1], sys.argv[2])
