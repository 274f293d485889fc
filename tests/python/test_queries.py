"""Queries from Python against closed forms: the sphere's closest points and ray hits."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import patchwork as pw

CENTER = np.array([0.5, -0.25, 1.0])
RADIUS = 1.5


def sphere() -> pw.PatchSet:
    return pw.NurbsSurface.sphere(CENTER, RADIUS).patch_set()


SPHERE = sphere()
SPHERE_BVH = pw.PatchBvh(SPHERE)


@settings(max_examples=40, deadline=None)
@given(st.tuples(*[st.floats(-4, 4)] * 3).filter(lambda q: np.linalg.norm(np.array(q) - CENTER) > 1e-3))
def test_closest_point_on_the_sphere(q: tuple[float, float, float]) -> None:
    point = np.array(q)
    truth = abs(np.linalg.norm(point - CENTER) - RADIUS)
    c = pw.closest_point(SPHERE_BVH, point)
    assert c.lower_bound - 1e-12 <= truth <= c.distance + 1e-12
    assert c.distance - c.lower_bound <= 1e-9
    assert np.linalg.norm(c.point - pw.closest_point(SPHERE, point).point) < 1e-9
    assert np.allclose(SPHERE[c.patch](c.u, c.v), c.point, atol=1e-12)


def test_closest_points_is_closest_point_for_each_row() -> None:
    rng = np.random.default_rng(7)
    points = rng.uniform(-3, 3, (20, 3))
    many = pw.closest_points(SPHERE_BVH, points)
    assert many["point"].shape == (20, 3) and many["patch"].dtype == np.uint32
    for k, p in enumerate(points):
        one = pw.closest_point(SPHERE_BVH, p)
        assert many["distance"][k] == one.distance and many["patch"][k] == one.patch
    # The centre is equidistant from the whole sphere.
    centre = pw.closest_point(SPHERE_BVH, CENTER)
    assert centre.attained_more_than_once and abs(centre.distance - RADIUS) < 1e-12


def test_rays_through_the_sphere() -> None:
    hits = pw.ray_cast(SPHERE_BVH, CENTER + [0, 0, 5], [0, 0, -2])
    assert [round(h.t, 12) for h in hits] == [round((5 - RADIUS) / 2, 12), round((5 + RADIUS) / 2, 12)]
    top = hits[0]
    assert np.allclose(top.point, CENTER + [0, 0, RADIUS], atol=1e-12)
    assert abs(abs(top.normal[2]) - 1) < 1e-12
    grazing = pw.ray_cast(SPHERE, CENTER + [RADIUS, -5, 0], [0, 1, 0])
    assert len(grazing) == 1 and grazing[0].grazing
    assert pw.ray_cast(SPHERE, CENTER + [0, 0, 5], [0, 0, 1]) == []


def test_curve_meets_the_sphere_and_plane_sections() -> None:
    line = pw.BezierCurve([CENTER - [3, 0, 0], CENTER + [3, 0, 0]])
    hits = pw.intersect_curve_surface(line, SPHERE).hits
    assert sorted(round(h.t, 12) for h in hits) == [round(0.5 - RADIUS / 6, 12), round(0.5 + RADIUS / 6, 12)]
    section = pw.plane_section(SPHERE, CENTER, [0, 0, 1], 1e-6)
    assert len(section.polylines) == 1 and section.polylines[0].closed
    ring = section.polylines[0].points
    assert np.abs(np.linalg.norm(ring - CENTER, axis=1) - RADIUS).max() <= section.error_bound + 1e-12
    assert section.error_bound <= 1e-6
    assert math.isclose(np.linalg.norm(ring[0] - CENTER), RADIUS, abs_tol=1e-6)
