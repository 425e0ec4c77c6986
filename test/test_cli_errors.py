"""Command-line entry points: bad input gives one line on stderr and a non-zero exit, no traceback."""
from __future__ import annotations

import subprocess
from pathlib import Path

import pytest


def _run(venv_bin: Path, *args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([str(venv_bin / args[0]), *args[1:]], capture_output=True, text=True, cwd=cwd, timeout=120)


def _assert_one_line_error(done: subprocess.CompletedProcess, pattern: str) -> None:
    assert done.returncode != 0
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, done.stderr
    assert "Traceback" not in done.stderr and pattern in lines[0], lines[0]


def test_process_bag_missing_path(venv_bin: Path, tmp_path: Path) -> None:
    _assert_one_line_error(_run(venv_bin, "process_bag", str(tmp_path / "nope"), cwd=tmp_path), "bag not found")


def test_process_bag_not_a_bag(venv_bin: Path, tmp_path: Path) -> None:
    (tmp_path / "x.mcap").write_bytes(b"\x00" * 100)
    _assert_one_line_error(_run(venv_bin, "process_bag", str(tmp_path / "x.mcap"), cwd=tmp_path), "not a readable")


def test_process_bag_wrong_topic(venv_bin: Path, tmp_path: Path, small_bag: Path) -> None:
    done = _run(venv_bin, "process_bag", str(small_bag), "--topic", "/nope", "--out", str(tmp_path / "o"), cwd=tmp_path)
    _assert_one_line_error(done, "no image topic '/nope'")


@pytest.mark.parametrize("command", ["process_bag", "evaluate"])
def test_out_is_a_file(venv_bin: Path, tmp_path: Path, small_bag: Path, command: str) -> None:
    (tmp_path / "results").write_text("")
    done = _run(venv_bin, command, str(small_bag), "--out", str(tmp_path / "results"), cwd=tmp_path)
    _assert_one_line_error(done, "is a file: give a folder")


@pytest.mark.parametrize("args,pattern", [(["--width", "8"], "too small"), (["--frames", "0"], "frames >= 1")])
def test_make_synthetic_absurd_parameters(venv_bin: Path, tmp_path: Path, args: list[str], pattern: str) -> None:
    _assert_one_line_error(_run(venv_bin, "make_synthetic", str(tmp_path / "b"), *args, cwd=tmp_path), pattern)


def test_every_parameter_is_in_the_parameter_file_at_its_default_and_in_the_readme() -> None:
    """``config/trap.yaml`` is the paper's defaults as a ROS parameter file and the README's table
    says what each parameter does: a parameter added to one and not the others would be unset
    from the file or undocumented."""
    import re

    import yaml

    from trap_core.pipeline import TrapParams
    top = Path(__file__).resolve().parents[1]
    defaults = TrapParams().as_dict()
    in_file = yaml.safe_load((top / "config" / "trap.yaml").read_text())["/**"]["ros__parameters"]
    assert in_file == defaults
    in_readme = re.findall(r"^\| `(\w+)` \|", (top / "README.md").read_text(), re.MULTILINE)
    assert sorted(set(in_readme) & set(defaults)) == sorted(defaults)
