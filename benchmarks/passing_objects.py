#!/usr/bin/env python3
"""Benchmark: tracking quality where objects pass through the view, each for a while.

Every video of ``quality.py`` keeps its objects in view nearly throughout (only one leaves, and
comes back), as the paper's do. Footage of traffic or passers-by is otherwise: an object enters,
crosses and is gone, and a long video holds many such short tracks. These videos
(``SceneConfig.passing``: each object enters once, at a time drawn over the video, and leaves
for good) are 1000 to 4000 frames long, with 6 to 30 objects; each object is in view for 110 to
730 frames, 4 to 46 % of its video (the first seven; the last three were made later). Prints the
``quality.py`` table and summary; graphs are cached as ``quality.py`` caches them.
Run: ``.venv/bin/python benchmarks/passing_objects.py [--pictures DIR] [-p name:=value]``
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import quality  # noqa: E402  (scoring, pictures and the graph cache)

PASSING = [
    ("distinct, 8 objects, 2000 frames, Felzenszwalb", dict(seed=7001, objects=8, frames=2000, passing=True),
     "felzenszwalb"),
    ("identical, 10 objects, 2000 frames, noise 1, road",
     dict(seed=7002, identical=True, objects=10, frames=2000, noise=1.0, background="road", passing=True),
     "felzenszwalb"),
    ("distinct, person, 10 objects, 2000 frames, grass",
     dict(seed=7003, shape="person", objects=10, frames=2000, background="grass", passing=True), "felzenszwalb"),
    ("distinct, mixed shapes, 8 objects, 960x540, 1500 frames, zoom 10 %, turn 10 deg, astronaut",
     dict(seed=7004, shape="mixed", objects=8, width=960, height=540, frames=1500, zoom=0.1, rotation=10.0,
          background="astronaut", passing=True), "felzenszwalb"),
    ("distinct, disc, 12 objects, 3000 frames, noise 1, JPEG",
     dict(seed=7005, shape="disc", objects=12, frames=3000, noise=1.0, compressed="jpeg", passing=True),
     "felzenszwalb"),
    ("distinct, car, 6 objects, 1000 frames, road", dict(seed=7006, objects=6, frames=1000, background="road",
                                                         passing=True), "felzenszwalb"),
    ("distinct, mixed shapes, 30 objects, 4000 frames", dict(seed=7007, shape="mixed", objects=30, frames=4000,
                                                             passing=True), "felzenszwalb"),
    # made in session 61, after the colours across exits (rejoin_colour_reach), which the 30 objects led to
    ("distinct, car, 12 objects, 2500 frames, noise 1, road",
     dict(seed=7101, objects=12, frames=2500, noise=1.0, background="road", passing=True), "felzenszwalb"),
    ("distinct, person, 15 objects, 3000 frames, zoom 10 %, grass",
     dict(seed=7102, shape="person", objects=15, frames=3000, zoom=0.1, background="grass", passing=True),
     "felzenszwalb"),
    ("distinct, mixed shapes, 10 objects, 2000 frames, illumination 10 %, JPEG",
     dict(seed=7103, shape="mixed", objects=10, frames=2000, illumination=0.1, compressed="jpeg", passing=True),
     "felzenszwalb"),
]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    quality.add_run_arguments(parser)
    args = parser.parse_args()
    quality.check_overrides(parser, args.overrides)
    print("### passing\n")
    quality.score_set("passing", PASSING, args, lambda _, label: f"passing_{quality.slug(label)}")


if __name__ == "__main__":
    main()
