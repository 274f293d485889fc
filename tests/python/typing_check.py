"""Code that uses the module as a script would, checked by mypy --strict against the stubs
(ctest python.mypy); it also runs (the last part of tests/python/test_typing.py)."""

import numpy as np
import numpy.typing as npt

import patchwork as pw


def teapot_summary(path: str) -> tuple[tuple[int, ...], tuple[int, ...], float, float]:
    s = pw.read_bpt(path)
    t = pw.tessellate(s, relative_tolerance=1e-3)
    return t.positions.shape, t.indices.shape, t.error_bound, t.measured_error


def nearest(path: str, point: npt.ArrayLike) -> float:
    bvh = pw.PatchBvh(pw.read_patches(path))
    foot: pw.SurfaceClosestPoint = pw.closest_point(bvh, point)
    hits: list[pw.RayHit] = pw.ray_cast(bvh, [0.0, 0.0, 10.0], [0.0, 0.0, -1.0])
    return foot.distance + sum(h.t for h in hits)


def curve_values() -> npt.NDArray[np.float64]:
    c = pw.BezierCurve(np.array([[0.0, 0.0], [1.0, 1.0]]))
    foot: pw.CurveClosestPoint = pw.closest_point(c, [1.0, 0.0])
    return c.evaluate(np.linspace(0.0, 1.0, 5)) + foot.distance
