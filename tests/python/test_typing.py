"""The typed example code runs, and the example script writes its PNG."""

import os
import pathlib
import subprocess
import sys

import typing_check


def test_typed_code_runs(teapot_path: str) -> None:
    positions, indices, bound, measured = typing_check.teapot_summary(teapot_path)
    assert positions[1] == 3 and indices[1] == 3 and 0 < measured <= bound
    assert typing_check.nearest(teapot_path, [0.0, 0.0, 10.0]) > 0
    assert typing_check.curve_values().shape == (5, 2)


def test_example_plot_writes_a_png(source_dir: pathlib.Path, teapot_path: str, tmp_path: pathlib.Path) -> None:
    output = tmp_path / "speed.png"
    subprocess.run([sys.executable, str(source_dir / "python" / "examples" / "plot_speed_vs_error.py"), teapot_path, str(output)],
                   check=True, env=os.environ)
    assert output.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_readme_python_lines_work_as_written(source_dir: pathlib.Path) -> None:
    """The README's Python block, run as written from the repository's root."""
    readme = (source_dir / "README.md").read_text()
    block = readme.split("## Python", 1)[1].split("```python\n", 1)[1].split("```", 1)[0]
    assert "pw.tessellate" in block
    result = subprocess.run([sys.executable, "-c", block + "print(repr((" + block.strip().splitlines()[-1] + ")))"],
                            cwd=source_dir, env=os.environ, check=True, capture_output=True, text=True).stdout
    positions, indices, bound, measured = eval(result)
    assert positions == (4547, 3) and indices == (7667, 3)
    assert f"{bound:.5f}" == "0.00820" and 0 < measured <= bound
