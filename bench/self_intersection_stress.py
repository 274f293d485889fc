#!/usr/bin/python3
"""self_intersections on random planar cubics with small integer control points (many repeated and
collinear points: cusps at the ends, loops, curves folded back along a line), timing each and
checking every answer on the curve.

    bench/self_intersection_stress.py BUILD_DIR [CURVES_PER_RANGE]

Coordinates are randint(-R, R) / 4 for R = 1, 2, 4 (seed 5), as bench/intersection_stress.py draws
them for pairs. Prints, per R, the errors (NumericalError), the curves over 0.01 s, the total and
the slowest time with its control points, and the answers that fail the check: a point with
|C(t) - C(s)| > 1e-9, or an overlap without t0 < t1, s0 != s1 and C(t0) = C(s0), C(t1) = C(s1)
within 1e-9.
"""

import pathlib
import random
import sys
import time


def main() -> None:
    sys.path.insert(0, str(pathlib.Path(sys.argv[1]) / "python"))
    import numpy as np
    import patchwork as pw

    curves = int(sys.argv[2]) if len(sys.argv) > 2 else 5000
    for R in (1, 2, 4):
        rng = random.Random(5)
        slow = errors = wrong = 0
        total = worst = 0.0
        worst_points = None
        for _ in range(curves):
            P = np.array([[rng.randint(-R, R), rng.randint(-R, R)] for _ in range(4)]) / 4.0
            curve = pw.BezierCurve(P)
            start = time.perf_counter()
            try:
                result = pw.self_intersections(curve)
            except pw.NumericalError:
                errors += 1
                print("    error", P.tolist())
                result = None
            seconds = time.perf_counter() - start
            total += seconds
            if seconds > worst:
                worst, worst_points = seconds, P.tolist()
            slow += seconds > 0.01
            if result is None:
                continue
            gaps = [np.linalg.norm(curve(x.t) - curve(x.s)) for x in result.points]
            for o in result.overlaps:
                if not (o.t0 < o.t1 and o.s0 != o.s1):
                    gaps.append(np.inf)
                gaps += [np.linalg.norm(curve(o.t0) - curve(o.s0)), np.linalg.norm(curve(o.t1) - curve(o.s1))]
            if any(not gap <= 1e-9 for gap in gaps):
                wrong += 1
                print("    wrong", P.tolist(), max(gaps))
        print(f"R = {R}: {curves} curves, {errors} errors, {wrong} wrong, {slow} over 0.01 s, total {total:.2f} s, "
              f"slowest {worst:.4f} s {worst_points}")


if __name__ == "__main__":
    main()
