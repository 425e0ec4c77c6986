"""``make_synthetic``: write an Anim1/Anim2-like benchmark bag and its ground truth."""
from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

from trap_core.bagio import COMPRESSED_FORMATS, STORAGES, SUPPORTED_ENCODINGS
from trap_core.cli import run_main
from trap_core.synthetic.scene import CELLS, MIXED, PHOTOS, PRESETS, ROAD, SHAPES, SceneConfig
from trap_core.synthetic.video import write_synthetic


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="make_synthetic", description=(
        "Render a synthetic moving-camera video (paper's Anim1/Anim2 analogues) into a bag, "
        "with MOTChallenge ground truth in NAME.gt.txt beside it."))
    parser.add_argument("bag", type=Path, help="bag to create (a folder for mcap/sqlite3, a .bag file for ros1)")
    parser.add_argument("--preset", choices=sorted(PRESETS), default="anim2",
                        help="anim1: identical objects; anim2: objects of different colours")
    defaults = SceneConfig()
    for name in ("frames", "width", "height", "objects", "regions", "seed"):
        parser.add_argument(f"--{name}", type=int, default=getattr(defaults, name))
    for name in ("fps", "noise", "illumination", "object_scale", "rotation", "zoom"):
        parser.add_argument(f"--{name.replace('_', '-')}", dest=name, type=float, default=getattr(defaults, name))
    parser.add_argument("--shape", choices=[*SHAPES, MIXED], default=defaults.shape,
                        help="object shape; mixed: object i has the i-th shape, cycling")
    parser.add_argument("--background", choices=[CELLS, ROAD, *PHOTOS], default=defaults.background,
                        help="cells: coloured Voronoi cells (the paper's Anim videos); road: asphalt with lane "
                             "markings; or a scikit-image photograph the camera pans over (other scenes)")
    parser.add_argument("--no-exits", action="store_true", help="no object leaves the field of view")
    parser.add_argument("--passing", action="store_true",
                        help="objects pass through the view once each, entering and leaving at their own times")
    spelled = {name.lower(): name for name in SUPPORTED_ENCODINGS}
    parser.add_argument("--encoding", choices=SUPPORTED_ENCODINGS, default="rgb8",
                        type=lambda name: spelled.get(name.lower(), name), help="as ROS spells it (any case)")
    parser.add_argument("--sample-bits", dest="sample_bits", type=int, choices=range(8, 33), metavar="8..32",
                        help="integer encodings wider than 8 bits: significant bits of each sample (12: a 12-bit "
                             "camera's 0..4095 in 16-bit samples; default: the full width)")
    parser.add_argument("--compressed", choices=COMPRESSED_FORMATS,
                        help="write sensor_msgs/CompressedImage (compressedDepth: the frames' grey as depth)")
    parser.add_argument("--storage", choices=STORAGES, default="mcap")
    parser.add_argument("--topic", default="/camera/image_raw")
    return parser


def _main() -> int:
    args = build_parser().parse_args()
    fields = {f.name for f in dataclasses.fields(SceneConfig)}
    options = {k: v for k, v in vars(args).items() if k in fields}
    cfg = SceneConfig(**{**options, **PRESETS[args.preset], "exits": not args.no_exits})
    bag, gt = write_synthetic(cfg, args.bag, encoding=args.encoding, compressed=args.compressed,
                              storage=args.storage, topic=args.topic, progress=True,
                              sample_bits=args.sample_bits)
    print(f"wrote {cfg.frames} frames to {bag}, ground truth {gt}")
    return 0


def main() -> None:
    sys.exit(run_main(_main, "make_synthetic"))
