"""Meshes from Python: files in every format, topology, orientation, normals, subdivision."""

import pathlib

import numpy as np
import pytest

import patchwork as pw

# A unit cube, faces outward (vertex x + 2 y + 4 z).
CUBE_POSITIONS = [[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)]
CUBE_FACES = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [1, 3, 7, 5], [3, 2, 6, 7], [2, 0, 4, 6]]


def cube() -> pw.Mesh:
    return pw.Mesh(CUBE_POSITIONS, np.array(CUBE_FACES))


def test_construction_and_views() -> None:
    mesh = cube()
    assert mesh.vertex_count == 8 and mesh.face_count == 6
    assert mesh.positions.base is mesh and mesh.positions.dtype == np.float64
    assert np.array_equal(mesh.face_sizes, [4] * 6)
    assert np.array_equal(mesh.face_indices.reshape(6, 4), CUBE_FACES)
    mixed = pw.Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]], [[0, 1, 2, 3], [1, 4, 2]])
    assert np.array_equal(mixed.face_sizes, [4, 3])


def test_topology_orientation_volume_normals() -> None:
    report = pw.topology(cube())
    assert (report["vertices"], report["edges"], report["faces"]) == (8, 12, 6)
    assert report["euler"] == 2 and report["genus"] == 0 and report["closed"] and report["manifold"]
    assert pw.signed_volume(cube()) == pytest.approx(1.0, abs=1e-15)
    flipped_faces = [list(reversed(f)) if k == 3 else f for k, f in enumerate(CUBE_FACES)]
    oriented, flipped = pw.orient(pw.Mesh(CUBE_POSITIONS, flipped_faces), outward=True)
    assert list(flipped) == [3] and flipped.dtype == np.uint32
    assert pw.signed_volume(oriented) == pytest.approx(1.0)
    normals = pw.face_normals(cube())
    assert np.array_equal(normals, [[0, 0, -1], [0, 0, 1], [0, -1, 0], [1, 0, 0], [0, 1, 0], [-1, 0, 0]])
    corner = pw.vertex_normals(cube())[0]
    assert np.allclose(corner, -np.ones(3) / np.sqrt(3))


@pytest.mark.parametrize("extension", ["obj", "off", "ply", "glb"])
def test_file_round_trip(tmp_path: pathlib.Path, extension: str) -> None:
    path = str(tmp_path / f"cube.{extension}")
    pw.write_mesh(path, cube())
    back = pw.read_mesh(path)
    if extension == "glb":  # triangles over the welded corners
        assert back.face_count == 12 and back.vertex_count == 8
        assert pw.topology(back)["euler"] == 2
    else:
        assert np.array_equal(back.positions, cube().positions)
        assert np.array_equal(back.face_indices, cube().face_indices)


def test_subdivision_counts_and_limit_surface() -> None:
    # Catmull-Clark: F' = 4 F per level for quads; V' = V + E + F.
    once = pw.subdivide(cube(), 1)
    assert (once.vertex_count, once.face_count) == (8 + 12 + 6, 24)
    twice = pw.subdivide(cube(), 2)
    assert twice.face_count == 96
    triangles = pw.Mesh(CUBE_POSITIONS, [[f[0], f[1], f[2]] for f in CUBE_FACES] + [[f[0], f[2], f[3]] for f in CUBE_FACES])
    loop = pw.subdivide(triangles, 1, scheme="loop")
    assert loop.face_count == 48
    surface = pw.LimitSurface(cube())
    assert surface.face_count == 6
    centers = surface.evaluate(np.arange(6, dtype=np.uint32), np.full(6, 0.5), np.full(6, 0.5))
    # The Catmull-Clark limit of a cube is symmetric: face centres at one distance from the centre.
    radii = np.linalg.norm(centers - 0.5, axis=1)
    assert np.ptp(radii) < 1e-12 and 0.3 < radii[0] < 0.5
    patches = surface.patch_set()
    assert patches.report()["closed"]
