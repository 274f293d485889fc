"""The C++ exception family as Python exceptions: types, bases, attributes and the one-line
messages that name the file or the argument."""

import pathlib
import re
import threading

import numpy as np
import pytest

import patchwork as pw


def test_hierarchy() -> None:
    assert issubclass(pw.InvalidInput, pw.Error) and issubclass(pw.InvalidInput, ValueError)
    assert issubclass(pw.TopologyError, pw.InvalidInput)
    assert issubclass(pw.ParseError, pw.Error) and issubclass(pw.ParseError, ValueError)
    assert issubclass(pw.IoError, pw.Error) and issubclass(pw.IoError, OSError)
    assert issubclass(pw.NumericalError, pw.Error) and issubclass(pw.NumericalError, ArithmeticError)


def test_io_error_names_the_file(tmp_path: pathlib.Path) -> None:
    missing = str(tmp_path / "missing.bpt")
    with pytest.raises(pw.IoError) as caught:
        pw.read_bpt(missing)
    assert caught.value.path == missing and caught.value.filename == missing
    assert str(caught.value).startswith(missing + ": ")
    # Paths as os.PathLike too.
    with pytest.raises(pw.IoError):
        pw.read_bpt(tmp_path / "missing.bpt")
    assert "\n" not in str(caught.value)


def test_parse_error_has_path_line_and_column(tmp_path: pathlib.Path) -> None:
    path = tmp_path / "bad.bpt"
    path.write_text("1\n3 3\n0 0 0\n0 0 x\n")
    with pytest.raises(pw.ParseError) as caught:
        pw.read_bpt(str(path))
    error = caught.value
    assert error.path == str(path)
    assert error.line == 4 and error.column >= 1
    assert str(error).startswith(f"{path}:4:{error.column}: ")


def test_invalid_input_names_the_argument(teapot: pw.PatchSet) -> None:
    with pytest.raises(pw.InvalidInput, match="exactly one"):
        pw.tessellate(teapot, tolerance=0.1, relative_tolerance=0.1)
    with pytest.raises(pw.InvalidInput, match=r"control_points: expected an array of shape \(n, 2\) or \(n, 3\), got \(3, 4\)"):
        pw.BezierCurve(np.zeros((3, 4)))
    with pytest.raises(pw.InvalidInput, match=r"weights: expected an array of shape \(n,\)"):
        pw.RationalBezierCurve(np.zeros((3, 2)), np.ones((3, 1)))
    with pytest.raises(pw.InvalidInput, match="uv: expected 'none', 'patch' or 'atlas', got 'planar'"):
        pw.tessellate(teapot, segments=2, uv="planar")
    with pytest.raises(pw.InvalidInput, match="point"):
        pw.closest_point(teapot, [0.0, float("nan"), 0.0])
    with pytest.raises(pw.InvalidInput, match="direction"):
        pw.ray_cast(teapot, [0, 0, 10], [0, 0, 0])
    with pytest.raises(ValueError):  # InvalidInput is a ValueError for code that knows no patchwork
        pw.PatchSet([])


def test_topology_error_for_a_non_manifold_cage() -> None:
    # Three quads on one edge: no subdivision surface.
    fan = pw.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0], [0, 0, 1], [1, 0, 1], [0, -1, 0], [1, -1, 0]],
                  [[0, 1, 3, 2], [1, 0, 4, 5], [0, 1, 7, 6]])
    with pytest.raises(pw.TopologyError, match="edge"):
        pw.subdivide(fan, 1)


def test_wrong_types_are_type_errors() -> None:
    with pytest.raises(TypeError):
        pw.tessellate("teapot.bpt", tolerance=0.1)  # type: ignore[call-overload]


def test_numerical_error_for_a_patch_without_a_normal() -> None:
    point = pw.BezierPatch(np.ones((2, 2, 3)))  # every control point the same: no tangent plane
    with pytest.raises(pw.NumericalError, match=r"unit_normal: the patch is degenerate around \(0.5, 0.5\)"):
        point.normal(0.5, 0.5)
    with pytest.raises(ArithmeticError):
        point.normal(0.25, 0.5)


def test_indices_are_never_wrapped_or_truncated() -> None:
    positions = np.eye(3)
    bad = {
        "faces: index 4294967298 is not in [0, 2^32)": np.array([[0, 1, 2**32 + 2]]),
        "faces: expected integer indices, got an array of dtype float64": np.array([[0.2, 1.9, 2.99]]),
        "faces[1]: index -1 is not in [0, 2^32)": [[0, 1, 2], [-1, 2, 0]],
        "faces[1]: expected integer indices": [[0, 1, 2], [1.5, 2, 0]],
        "faces: expected an": "abc",
    }
    for message, faces in bad.items():
        with pytest.raises(pw.InvalidInput, match=re.escape(message)):
            pw.Mesh(positions, faces)
    assert pw.Mesh(positions, np.array([[0, 1, 2]], dtype=np.uint64)).face_count == 1
    surface = pw.LimitSurface(pw.Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]]))
    with pytest.raises(pw.InvalidInput, match="faces: expected integer indices"):
        surface.evaluate([0.9], [0.5], [0.5])


def test_views_of_checked_data_are_read_only() -> None:
    """A mesh's indices and a patch's net were checked once, by their constructors: Python may
    not change them behind that check."""
    mesh = pw.Mesh(np.eye(3), [[0, 1, 2]])
    for array in (mesh.positions, mesh.face_sizes, mesh.face_indices):
        with pytest.raises(ValueError, match="read-only"):
            array[0] = 7
    patch = pw.BezierPatch(np.zeros((2, 2, 3)))
    with pytest.raises(ValueError, match="read-only"):
        patch.control_points[1, 1] = [np.nan, np.inf, 1e308]


def test_derivative_orders_are_bounded() -> None:
    patch = pw.BezierPatch(np.arange(12, dtype=float).reshape(2, 2, 3))
    with pytest.raises(pw.InvalidInput, match="ku \\+ kv <= 64, got 2147483647 and 1"):
        patch.derivative(0.5, 0.5, 2**31 - 1, 1)
    assert np.array_equal(patch.derivative(0.5, 0.5, 5, 0), [0, 0, 0])  # beyond the degree


def test_queries_from_many_threads() -> None:
    """Every query's answer becomes Python objects only with the GIL held (pytest runs with -X
    dev, whose allocator aborts otherwise)."""
    a = pw.BezierCurve([[0, 0], [1, 3], [2, -3], [3, 0]])
    b = pw.BezierCurve([[0, 0.5], [3, -0.5]])
    loop = pw.BezierCurve([[0, 0], [3, 3], [-2, 3], [1, 0]])
    counts: list[tuple[int, int]] = []

    def work() -> None:
        for _ in range(50):
            counts.append((len(pw.intersect_curves(a, b).points), len(pw.self_intersections(loop).points)))

    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert counts == [(3, 1)] * 200
