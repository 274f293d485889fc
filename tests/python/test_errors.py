"""The C++ exception family as Python exceptions: types, bases, attributes and the one-line
messages that name the file or the argument."""

import pathlib

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
    assert caught.value.path == missing
    assert str(caught.value).startswith(missing + ": ")
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
