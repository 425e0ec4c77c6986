#!/usr/bin/env python3
"""Benchmark: tracking quality on synthetic videos drawn at random, tracked as they come.

The sets of ``quality.py`` are fixed, and every rule of the robust method was checked on them:
they measure what was looked at. This draws new videos each time it is given a new generator
seed, as the set "later" was drawn (README, drawn at random after every rule): any frame size from
320x240 to 1280x720, 300 to 500 frames, 2 to 5 identical or distinct objects of any shape and
scale, over the cells, a road or any bundled photograph, with noise, swinging light, zoom and turn
drawn or not, and a delivery drawn with each video (raw, the bag encodings ``bgra8`` and
``yuv422``, or JPEG); every video is segmented with Felzenszwalb, as ``process_bag`` does. A seed
no rule was made on is a measure of how the tracker does on footage it has not seen. Prints the
``quality.py`` table and summary; graphs are cached as ``quality.py`` caches them.
Run: ``.venv/bin/python benchmarks/fresh_draws.py --generator N [--videos 12] [--pictures DIR] [-p name:=value]``
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import quality  # noqa: E402  (scoring, pictures and the graph cache)

from trap_core.synthetic.scene import CELLS, MIXED, PHOTOS, ROAD, SHAPES  # noqa: E402

SIZES = ((320, 240), (400, 300), (640, 360), (640, 480), (800, 600), (960, 540), (1280, 720))
DELIVERIES = ({}, {"encoding": "bgra8"}, {"encoding": "yuv422"}, {"compressed": "jpeg"})


def drawn_scenes(generator: int, videos: int, enlarged: float = 1.0) -> list[tuple[str, dict]]:
    """``videos`` scenes (label, ``quality.py`` scene) drawn with the random generator ``generator``,
    their objects ``enlarged`` times the drawn scale (the same draw otherwise)."""
    rng = np.random.default_rng(generator)
    scenes = []
    for _ in range(videos):
        width, height = SIZES[rng.integers(len(SIZES))]
        scene = dict(seed=int(rng.integers(1_000_000)), identical=bool(rng.random() < 0.5),
                     shape=str(rng.choice([*SHAPES, MIXED])), objects=int(rng.integers(2, 6)),
                     object_scale=round(enlarged * float(rng.choice([0.8, 1.0, 1.2])), 3), width=width, height=height,
                     frames=int(rng.choice([300, 400, 500])), zoom=float(rng.choice([0.0, 0.0, 0.05, 0.1, 0.15])),
                     rotation=float(rng.choice([0.0, 0.0, 5.0, 10.0, 15.0])),
                     illumination=float(rng.choice([0.0, 0.0, 0.05, 0.1])),
                     noise=float(rng.choice([0.0, 0.5, 1.0, 1.5, 2.0])),
                     background=str(rng.choice([CELLS, ROAD, *PHOTOS])))
        scene.update(DELIVERIES[rng.integers(len(DELIVERIES))])
        scenes.append((scene_label(scene), scene))
    return scenes


def scene_label(scene: dict) -> str:
    """A drawn scene in the words of ``quality.py``'s labels."""
    shape = "mixed shapes" if scene["shape"] == MIXED else scene["shape"]
    scale = "" if scene["object_scale"] == 1.0 else f" {scene['object_scale']:g}x"
    parts = [("identical" if scene["identical"] else "distinct"), shape, f"{scene['objects']} objects{scale}",
             f"{scene['width']}x{scene['height']}", f"{scene['frames']} frames"]
    parts += [f"zoom {100 * scene['zoom']:.0f} %"] if scene["zoom"] else []
    parts += [f"turn {scene['rotation']:.0f} deg"] if scene["rotation"] else []
    parts += [f"illumination {100 * scene['illumination']:.0f} %"] if scene["illumination"] else []
    parts += [f"noise {scene['noise']:g}"] if scene["noise"] else []
    parts.append(scene["background"])
    parts += ["JPEG"] if scene.get("compressed") else [scene["encoding"]] if "encoding" in scene else []
    return ", ".join(parts)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--generator", type=int, required=True,
                        help="seed of the draw: a new one for videos no rule was made on")
    parser.add_argument("--videos", type=int, default=12, help="how many videos to draw (default 12)")
    parser.add_argument("--enlarged", type=float, default=1.0,
                        help="objects this many times their drawn scale (0.8-1.2), e.g. 2.5 for objects large in "
                             "the view (default 1)")
    quality.add_run_arguments(parser)
    args = parser.parse_args()
    if args.videos < 1:
        parser.error(f"--videos must be at least 1, not {args.videos}")
    if not 0.2 <= args.enlarged <= 5:
        parser.error(f"--enlarged must be within 0.2..5, not {args.enlarged}")
    quality.check_overrides(parser, args.overrides)
    name = f"drawn with generator {args.generator}" + (f", objects {args.enlarged:g} times larger"
                                                       if args.enlarged != 1 else "")
    print(f"### {name}\n")
    videos = [(label, scene, "felzenszwalb")
              for label, scene in drawn_scenes(args.generator, args.videos, args.enlarged)]
    quality.score_set(name, videos, args, lambda index, label: f"{args.generator}_{index}_{quality.slug(label)}")


if __name__ == "__main__":
    main()
