"""Patches, NURBS surfaces and patch sets from Python, against tensor Bernstein sums in numpy,
the exact sphere and torus, and the files they come from."""

import math
import pathlib

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import patchwork as pw


def bernstein(n: int, t: np.ndarray) -> np.ndarray:
    return np.array([math.comb(n, i) * t**i * (1 - t) ** (n - i) for i in range(n + 1)])


@settings(max_examples=40, deadline=None)
@given(hnp.arrays(np.float64, st.tuples(st.integers(1, 5), st.integers(1, 5), st.just(3)),
                  elements=st.floats(-5, 5, allow_nan=False)),
       st.floats(0, 1), st.floats(0, 1))
def test_patch_is_the_tensor_bernstein_sum(net: np.ndarray, u: float, v: float) -> None:
    patch = pw.BezierPatch(net)
    n, m = net.shape[0] - 1, net.shape[1] - 1
    expected = np.einsum("i,j,ijk->k", bernstein(n, np.array(u)), bernstein(m, np.array(v)), net)
    assert np.abs(patch(u, v) - expected).max() <= 1e-13 * (1 + np.abs(net).max()) * (n + m + 2)
    assert patch.degree == (n, m)
    # The net is a view of the patch in [i, j] order.
    assert np.array_equal(patch.control_points, net) and patch.control_points.base is patch


def test_sphere_and_torus_are_exact() -> None:
    sphere = pw.NurbsSurface.sphere([1, 2, 3], 2.0)
    u, v = np.meshgrid(np.linspace(0, 1, 9), np.linspace(0, 1, 9))
    lo_u, lo_v = sphere.evaluate(0, 0), sphere.evaluate(1, 1)
    assert lo_u.shape == (3,) and lo_v.shape == (3,)
    patches = sphere.patch_set()
    report = patches.report()
    assert report["closed"] and report["open_edges"] == 0
    for k in range(len(patches)):
        points = patches[k].evaluate(u, v)
        assert points.shape == (9, 9, 3)
        assert np.abs(np.linalg.norm(points - [1, 2, 3], axis=-1) - 2.0).max() < 1e-14 * 8
    curvature = patches[0].curvature(0.3, 0.6)
    assert abs(curvature.gaussian - 0.25) < 1e-12 and curvature.umbilic
    torus = pw.NurbsSurface.torus([0, 0, 0], 3.0, 1.0)
    ts = torus.patch_set()
    assert ts.report()["closed"]
    # On the outer equator K = 1 / (r (R + r)).
    x = pw.closest_point(ts, [5.0, 0.0, 0.0])
    assert abs(x.distance - 1.0) < 1e-12
    patch = ts[x.patch]
    assert abs(patch.curvature(x.u, x.v).gaussian - 1 / (1 * 4)) < 1e-9


def test_patch_set_from_patches_and_files(teapot: pw.PatchSet, tmp_path: pathlib.Path, source_dir: pathlib.Path) -> None:
    assert len(teapot) == 32 and teapot.rational_count == 0
    report = teapot.report()
    assert report["patches"] == 32 and report["collapsed_edges"] > 0
    rebuilt = pw.PatchSet([teapot[k] for k in range(len(teapot))])
    assert rebuilt.report() == report
    path = tmp_path / "copy.bpt"
    pw.write_bpt(str(path), teapot)
    again = pw.read_bpt(str(path))
    assert all(again[k] == teapot[k] for k in range(32))
    lo, hi = teapot.bounding_box(1e-9)
    assert np.all(lo < hi)
    freeform = sorted((source_dir / "data").glob("*.obj"))
    patch_files = [f for f in freeform if "cstype" in f.read_text(errors="ignore")]
    for f in patch_files:
        s = pw.read_patches(str(f))
        assert len(s) > 0
        assert pw.tessellate(s, relative_tolerance=1e-3).error_bound > 0
    assert len(pw.read_patches(str(path))) == 32


def test_mixed_patch_set() -> None:
    octant = pw.RationalBezierPatch.sphere_octant([0, 0, 0], 1.0)
    flat = pw.BezierPatch(np.array([[[2, 0, 0], [2, 0, 1]], [[3, 0, 0], [3, 0, 1]]], dtype=float))
    s = pw.PatchSet([octant, flat])
    assert len(s) == 2 and s.rational_count == 1
    assert isinstance(s[0], pw.RationalBezierPatch) and isinstance(s[-1], pw.BezierPatch)
    assert octant.weights.shape == (3, 3) and octant.control_points.shape == (3, 3, 3)
    normals = octant.normal(np.array([0.2, 0.7]), np.array([0.4, 0.1]))
    points = octant.evaluate(np.array([0.2, 0.7]), np.array([0.4, 0.1]))
    # On the unit sphere the outward or inward normal is the point itself.
    assert np.allclose(np.abs(np.einsum("ij,ij->i", normals, points)), 1.0, atol=1e-14)


@settings(max_examples=30, deadline=None)
@given(st.integers(1, 4), st.integers(1, 4), st.data())
def test_rational_and_nurbs_weights_are_laid_out_as_the_net(n: int, m: int, data: st.DataObject) -> None:
    """The rational sum over the (n + 1, m + 1) net and weights, computed in numpy, for a patch
    and for the NURBS surface with the same (clamped, one-span) knots: the weight w_ij belongs to P_ij."""
    net = data.draw(hnp.arrays(np.float64, (n + 1, m + 1, 3), elements=st.floats(-5, 5)))
    weights = data.draw(hnp.arrays(np.float64, (n + 1, m + 1), elements=st.floats(0.25, 4)))
    u, v = data.draw(st.floats(0, 1)), data.draw(st.floats(0, 1))
    bu, bv = bernstein(n, np.array(u)), bernstein(m, np.array(v))
    numerator = np.einsum("i,j,ij,ijk->k", bu, bv, weights, net)
    expected = numerator / np.einsum("i,j,ij->", bu, bv, weights)
    patch = pw.RationalBezierPatch(net, weights)
    # The points come back from the homogeneous form (w P) / w: equal to rounding.
    assert np.array_equal(patch.weights, weights)
    assert np.allclose(patch.control_points, net, rtol=1e-15, atol=1e-300)
    assert np.abs(patch(u, v) - expected).max() <= 1e-12 * (1 + np.abs(net).max())
    surface = pw.NurbsSurface(n, m, [0] * (n + 1) + [1] * (n + 1), [0] * (m + 1) + [1] * (m + 1), net, weights)
    assert np.abs(surface(u, v) - expected).max() <= 1e-12 * (1 + np.abs(net).max())
    # Equal weights make a polynomial surface (all 1): the weights agree up to one factor.
    assert np.allclose(surface.weights * weights[0, 0], weights * surface.weights[0, 0])
