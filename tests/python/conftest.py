"""Fixtures of the Python module's tests: the repository's data and the C++ reference program
(tests/python/CMakeLists.txt sets the environment)."""

import os
import pathlib

import pytest

import patchwork as pw


@pytest.fixture(scope="session")
def source_dir() -> pathlib.Path:
    return pathlib.Path(os.environ["PATCHWORK_SOURCE_DIR"])


@pytest.fixture(scope="session")
def teapot_path(source_dir: pathlib.Path) -> str:
    return str(source_dir / "data" / "teapot.bpt")


@pytest.fixture(scope="session")
def teapot(teapot_path: str) -> pw.PatchSet:
    return pw.read_bpt(teapot_path)


@pytest.fixture(scope="session")
def reference_program() -> str:
    return os.environ["PATCHWORK_TESSELLATE_REFERENCE"]
