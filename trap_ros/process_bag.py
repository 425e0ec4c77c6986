"""``ros2 run trap_ros process_bag BAG``: read a bag's image topic and report what it holds."""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from trap_core.bagio import open_image_stream
from trap_core.cli import run_main
from trap_core.progress import Progress


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="process_bag", description="Track objects in a camera bag with TRAP.")
    parser.add_argument("bag", type=Path, help="ROS 2 bag folder, .mcap, .db3 or ROS 1 .bag")
    parser.add_argument("--topic", help="image topic (default: the only image topic of the bag)")
    parser.add_argument("--out", type=Path, default=Path("results"), help="output folder")
    return parser


def _main() -> int:
    args = build_parser().parse_args()
    with open_image_stream(args.bag, args.topic) as stream:
        meter = Progress(stream.count, f"reading {stream.topic}")
        sizes: set[tuple[int, int]] = set()
        for frame in stream:
            sizes.add(frame.rgb.shape[:2])
            meter.advance()
        elapsed = meter.finish()
    args.out.mkdir(parents=True, exist_ok=True)
    summary = {"bag": str(args.bag), "topic": stream.topic, "frames": meter.done,
               "frame_sizes": sorted(f"{w}x{h}" for h, w in sizes), "read_s": round(elapsed, 3)}
    (args.out / "summary.json").write_text(json.dumps(summary, indent=2))
    print(f"read {meter.done} frames of {stream.topic}; summary in {args.out / 'summary.json'}")
    return 0


def main() -> None:
    sys.exit(run_main(_main, "process_bag"))
