"""Curves from Python against independent computations: Bernstein sums and hodographs in numpy,
the exact circle, closed-form closest points and intersections."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import patchwork as pw

coordinates = st.floats(-10, 10, allow_nan=False)


def bernstein_sum(points: np.ndarray, t: np.ndarray) -> np.ndarray:
    """sum_i B_i^n(t) P_i, computed directly (not by de Casteljau)."""
    n = len(points) - 1
    basis = np.array([math.comb(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)])
    return basis.T @ points


@settings(max_examples=50, deadline=None)
@given(hnp.arrays(np.float64, st.tuples(st.integers(1, 7), st.sampled_from([2, 3])), elements=coordinates),
       hnp.arrays(np.float64, st.integers(1, 20), elements=st.floats(0, 1)))
def test_evaluate_is_the_bernstein_sum(points: np.ndarray, t: np.ndarray) -> None:
    curve = pw.BezierCurve(points)
    values = curve.evaluate(t)
    assert values.shape == (len(t), points.shape[1])
    scale = 1 + np.abs(points).max()
    assert np.abs(values - bernstein_sum(points, t)).max() <= 1e-13 * scale * len(points)
    # The derivative is the hodograph n (P_{i+1} - P_i).
    if len(points) > 1:
        hodograph = (len(points) - 1) * np.diff(points, axis=0)
        assert np.abs(curve.derivative(t) - bernstein_sum(hodograph, t)).max() <= 1e-12 * scale * len(points) ** 2


@settings(max_examples=30, deadline=None)
@given(hnp.arrays(np.float64, st.tuples(st.integers(2, 6), st.just(3)), elements=coordinates), st.floats(0.05, 0.95))
def test_split_halves_are_the_curve_and_join_smoothly(points: np.ndarray, t: float) -> None:
    curve = pw.BezierCurve(points)
    left, right = curve.split(t)
    assert left.interval == (0.0, t) and right.interval == (t, 1.0)
    s = np.linspace(0, t, 7)
    assert np.allclose(left.evaluate(s), curve.evaluate(s), atol=1e-12 * (1 + np.abs(points).max()))
    join = pw.continuity(left, right, max_order=len(points) - 1, relative_tolerance=1e-8)
    assert join.ck == len(points) - 1
    # A curve that is one point has no tangent; one that is regular at t (not one point to the
    # check's relative tolerance) has its tangent there on both sides. Where c'(t) = 0 the first
    # derivative that does not vanish decides: of even order the curve turns back (a cusp, not
    # G1), as in test_folded_curve_split_at_its_turn_is_not_g1.
    spread = np.ptp(points, axis=0).max()
    if spread == 0:
        assert not join.g1
    elif spread > 1e-6 and np.linalg.norm(curve.derivative(np.array([t]))) > 1e-6 * spread:
        assert join.g1


def test_folded_curve_split_at_its_turn_is_not_g1() -> None:
    # The quadratic (1, 0, 1) in x runs back along itself after t = 1/2, where c' = 0 and
    # c'' != 0: the halves meet with opposite tangents (hypothesis found it).
    curve = pw.BezierCurve(np.array([[1.0, 1.0, 1.0], [0.0, 1.0, 1.0], [1.0, 1.0, 1.0]]))
    left, right = curve.split(0.5)
    join = pw.continuity(left, right, max_order=2, relative_tolerance=1e-8)
    assert join.ck == 2 and not join.g1


def test_parameter_arrays_of_any_shape_and_dtype() -> None:
    curve = pw.BezierCurve(np.array([[0, 0, 0], [1, 2, 3]], dtype=np.int32))  # converted once
    grid = np.linspace(0, 1, 12, dtype=np.float32).reshape(3, 4)
    assert curve.evaluate(grid).shape == (3, 4, 3)
    assert curve(0.5).shape == (3,)
    assert np.array_equal(curve(0.5), [0.5, 1.0, 1.5])
    fortran = np.asfortranarray(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]))
    assert np.array_equal(pw.BezierCurve(fortran).control_points, fortran)


def test_rational_quarter_circle_is_exact() -> None:
    w = math.sqrt(0.5)
    arc = pw.RationalBezierCurve([[1, 0], [1, 1], [0, 1]], [1, w, 1])
    points = arc.evaluate(np.linspace(0, 1, 101))
    assert np.abs(np.linalg.norm(points, axis=1) - 1).max() < 1e-15 * 4
    assert np.array_equal(arc.weights, [1, w, 1])
    foot = pw.closest_point(arc, [2.0, 2.0])
    assert abs(foot.distance - (2 * math.sqrt(2) - 1)) <= 1e-12
    assert foot.lower_bound <= 2 * math.sqrt(2) - 1 <= foot.distance
    assert abs(foot.t - 0.5) < 1e-9


def test_nurbs_circle_and_knot_insertion() -> None:
    w = math.sqrt(0.5)
    points = [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0]]
    circle = pw.NurbsCurve(2, [0, 0, 0, 1, 1, 2, 2, 2], points, [1, w, 1, w, 1])
    t = np.linspace(0, 2, 51)
    assert np.abs(np.linalg.norm(circle.evaluate(t), axis=1) - 1).max() < 1e-15 * 4
    refined = circle.insert_knot(0.5)
    assert len(refined.knots) == 9
    assert np.abs(refined.evaluate(t) - circle.evaluate(t)).max() < 1e-15 * 8
    assert len(circle.bezier_pieces()) == 2


def test_line_intersections_in_closed_form() -> None:
    a = pw.BezierCurve([[0, 0], [4, 4]])
    b = pw.BezierCurve([[0, 4], [4, 0]])
    x = pw.intersect_curves(a, b)
    assert len(x.points) == 1 and not x.overlaps
    p = x.points[0]
    assert abs(p.t - 0.5) <= p.t_bound + 1e-15 and abs(p.s - 0.5) <= p.s_bound + 1e-15
    assert np.allclose(p.point, [2, 2])
    # A parabola touching its tangent line: one tangential point.
    parabola = pw.BezierCurve([[-1, 1], [0, -1], [1, 1]])
    tangent = pw.BezierCurve([[-2, 0], [2, 0]])
    touch = pw.intersect_curves(parabola, tangent)
    assert len(touch.points) == 1 and touch.points[0].tangential
    # A sub-arc of a line: one overlap, not points.
    overlap = pw.intersect_curves(a, pw.BezierCurve([[1, 1], [3, 3]]))
    assert len(overlap.overlaps) == 1 and not overlap.points
    # Space curves need a tolerance.
    space = pw.BezierCurve([[0, 0, 0], [1, 1, 1]])
    assert len(pw.intersect_curves(space, pw.BezierCurve([[1, 0, 0], [0, 1, 1]]), 1e-9).points) == 1


def test_self_intersection_of_a_loop() -> None:
    loop = pw.BezierCurve([[0, 0], [3, 3], [-2, 3], [1, 0]])
    x = pw.self_intersections(loop)
    assert len(x.points) == 1
    p = x.points[0]
    assert np.allclose(loop(p.t), loop(p.s), atol=1e-12)
