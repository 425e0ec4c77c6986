"""What every command-line entry point shares: one-line errors, exit codes, interrupt handling."""
from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

import yaml

from trap_core.bagio import BagError

EXIT_ERROR = 1
EXIT_INTERRUPTED = 130


class UsageError(Exception):
    """A parameter is out of range or inconsistent; the message is one line for the user."""


def parameter_assignment(item: str) -> tuple[str, object]:
    """``name:=value`` (as after ROS's ``-p``) -> ``(name, value)``, the value read as YAML."""
    name, sep, text = item.partition(":=")
    if not sep:
        raise UsageError(f"-p takes name:=value, not {item!r}")
    return name, yaml.safe_load(text)


def results_folder(path: Path) -> Path:
    """``--out``: made if missing; a file there is refused in one line, not as ``[Errno 17]``."""
    if path.exists() and not path.is_dir():
        raise UsageError(f"--out {path} is a file: give a folder for the results")
    path.mkdir(parents=True, exist_ok=True)
    return path


def run_main(main: Callable[[], int | None], name: str) -> int:
    """Run ``main``; turn expected failures into ``name: error: ...`` and a non-zero exit code."""
    try:
        return int(main() or 0)
    except (BagError, UsageError, ValueError, OSError) as error:
        print(f"{name}: error: {error}", file=sys.stderr)
        return EXIT_ERROR
    except KeyboardInterrupt:
        print(f"{name}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
