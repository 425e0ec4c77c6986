#!/usr/bin/env python3
"""Benchmark: how far the label memory's light gain is from the light's true gain.

Node labels follow the light (:mod:`trap_core.rag.label_memory`): a region that appears is
labelled from its colour divided by the gain the memory measures, so an error of a few per cent
moves colours near a level boundary into the next label, and an object that comes back under
other light shows other structures than before (its fragments are then not rejoined). For each
video of the chosen ``quality.py`` sets whose light swings (``illumination``; the synthetic
gain is then the truth, :func:`trap_core.synthetic.light_gain`), prints the largest and the
90th percentile over the frames of the gain's error (the worst channel, relative); with
``--steady``, also the largest error over the videos of steady light. Graphs come from
``quality.py``'s cache. Run: ``.venv/bin/python benchmarks/label_gain.py [--sets later] [--steady]``.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import quality  # noqa: E402  (the benchmark sets and their graph cache)

from trap_core.pipeline import TrapParams  # noqa: E402
from trap_core.rag import LabelMemory  # noqa: E402
from trap_core.synthetic import light_gain  # noqa: E402


def gain_errors(scene: dict, segmentation: str, cache: Path) -> np.ndarray:
    """Per frame of the video: the relative error of the memory's gain in its worst channel."""
    graphs, _ = quality._graphs(scene, segmentation, cache)
    config = quality._scene_config(scene)[0]
    memory = LabelMemory(TrapParams.from_mapping({"segmentation": segmentation}).colour_bins)
    errors = np.empty(len(graphs))
    for t, graph in enumerate(graphs):
        memory(graph)
        errors[t] = np.abs(memory.gain / light_gain(config, t) - 1).max()
    return errors


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sets", default=",".join(quality.SETS))
    parser.add_argument("--cache", type=Path, default=Path.home() / ".cache/trap_ros/quality")
    parser.add_argument("--steady", action="store_true", help="also the videos of steady light")
    args = parser.parse_args()
    print("| set | video | light swing | largest error | 90th percentile |")
    print("|---|---|---|---|---|")
    largest, steady = [], []
    for set_name in args.sets.split(","):
        for label, scene, segmentation in quality.SETS[set_name]:
            swing = scene.get("illumination", 0.0)
            if not swing and not args.steady:
                continue
            errors = gain_errors(scene, segmentation, args.cache)
            if not swing:
                steady.append(errors.max())
                continue
            largest.append(errors.max())
            print(f"| {set_name} | {label} | {100 * swing:.0f} % | {100 * errors.max():.1f} % "
                  f"| {100 * np.percentile(errors, 90):.1f} % |", flush=True)
    if largest:
        print(f"\n{len(largest)} videos of swinging light: largest error {100 * min(largest):.1f}-"
              f"{100 * max(largest):.1f} %, median {100 * np.median(largest):.1f} %")
    if steady:
        print(f"{len(steady)} videos of steady light: largest error at most {100 * max(steady):.2f} %")


if __name__ == "__main__":
    main()
