"""``ros2 run trap_ros process_bag BAG``: track the objects of a camera bag with TRAP."""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import yaml

from trap_core.cli import UsageError, run_main
from trap_core.pipeline import ParameterError, TrapParams, run_bag


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="process_bag", description="Track objects in a camera bag with TRAP.")
    parser.add_argument("bag", type=Path, help="ROS 2 bag folder, .mcap, .db3 or ROS 1 .bag")
    parser.add_argument("--topic", help="image topic (default: the only image topic of the bag)")
    parser.add_argument("--out", type=Path, default=Path("results"), help="output folder (default: results)")
    parser.add_argument("--objects", type=int, help="number of objects to track (default: found without supervision)")
    return parser


def parse_ros_args(words: list[str]) -> dict[str, object]:
    """Parameters from ``--ros-args --params-file FILE -p name:=value`` (files first, then -p)."""
    values: dict[str, object] = {}
    overrides: dict[str, object] = {}
    i = 0
    while i < len(words):
        word = words[i]
        if word in ("--params-file", "-p") and i + 1 >= len(words):
            raise UsageError(f"{word} needs a value")
        if word == "--params-file":
            values.update(_params_file(Path(words[i + 1])))
            i += 2
        elif word == "-p":
            name, sep, text = words[i + 1].partition(":=")
            if not sep:
                raise UsageError(f"-p takes name:=value, not {words[i + 1]!r}")
            overrides[name] = yaml.safe_load(text)
            i += 2
        else:
            i += 1  # other ROS arguments (remappings, log levels) are for rclpy
    return {**values, **overrides}


def _params_file(path: Path) -> dict[str, object]:
    """Parameters of a ROS 2 parameter file: the ``/**`` section, then trap_ros nodes' sections."""
    try:
        content = yaml.safe_load(path.read_text()) or {}
    except (OSError, yaml.YAMLError) as error:
        raise UsageError(f"cannot read parameter file {path}: {' '.join(str(error).split())}") from None
    merged: dict[str, object] = {}
    for section, body in content.items():
        if isinstance(body, dict) and isinstance(body.get("ros__parameters"), dict):
            merged.update(body["ros__parameters"])
    return merged


def _main() -> int:
    argv = sys.argv[1:]
    ros_args = argv[argv.index("--ros-args") + 1:] if "--ros-args" in argv else []
    own = argv[:argv.index("--ros-args")] if "--ros-args" in argv else argv
    args = build_parser().parse_args(own)
    values = parse_ros_args(ros_args)
    if args.objects is not None:
        values["n_objects"] = args.objects
    try:
        params = TrapParams.from_mapping(values)
    except (ParameterError, TypeError) as error:
        raise UsageError(str(error)) from None
    run = run_bag(args.bag, args.out, params, args.topic)
    print(f"{len(run.result.tracks) if run.result else 0} tracks over {run.frames} frames; results in {args.out}: "
          + ", ".join(Path(p).name for p in run.outputs.values()))
    return 0


def main() -> None:
    sys.exit(run_main(_main, "process_bag"))
