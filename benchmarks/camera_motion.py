#!/usr/bin/env python3
"""Benchmark: how far the camera's motion read from the patterns is from the true pan.

For each video of the chosen ``quality.py`` sets that only pans (no turn, no zoom: the
synthetic camera path is then the truth), prints the median and 90th percentile over 12-frame
windows of the error of the estimated pan, in px per frame, read from the patterns' positions
as they are, as the tracker reads it without the images (:func:`trap_core.robust.camera_paths`:
patterns without the backdrop, and the regions matched from frame to frame; ``image_motion``
false) and with them (the steps read from the images, :mod:`trap_core.robust.image_steps`,
where there is one), the share of frames with a step read from the images, and the share of
the frame its largest region covers. 0.0012 image widths per frame (0.77 px at 640) is the
speed that makes background. Graphs come from ``quality.py``'s cache.
Run: ``.venv/bin/python benchmarks/camera_motion.py [--sets photos,analogues]``.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import quality  # noqa: E402  (the benchmark sets and their graph cache)

from trap_core.clustering import observed_paths  # noqa: E402
from trap_core.pipeline import PatternMiner, TrapParams  # noqa: E402
from trap_core.rag import StackedGraphs  # noqa: E402
from trap_core.robust import camera_paths, camera_transforms, without_backdrop  # noqa: E402
from trap_core.synthetic import SceneConfig  # noqa: E402
from trap_core.synthetic.scene import build_world  # noqa: E402

WINDOW = 12  # frames over which an estimated pan is compared with the true one


def _errors(transforms: np.ndarray, pan: np.ndarray) -> np.ndarray:
    """Per window of ``WINDOW`` frames: distance between the estimated and the true pan, px a frame."""
    shift = -transforms[:, :2, 2]
    return np.linalg.norm((shift[WINDOW:] - shift[:-WINDOW]) - (pan[WINDOW:] - pan[:-WINDOW]), axis=1) / WINDOW


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sets", default="photos,analogues")
    parser.add_argument("--cache", type=Path, default=Path.home() / ".cache/trap_ros/quality")
    args = parser.parse_args()
    print("| set | video | largest region | patterns as they are, median / p90 | without the images, median / p90 "
          "| with them, median / p90 | frames read from the images |")
    print("|---|---|---|---|---|---|---|")
    for set_name in args.sets.split(","):
        for label, scene, segmentation in quality.SETS[set_name]:
            if scene.get("rotation") or scene.get("zoom"):
                continue
            graphs, _ = quality._graphs(scene, segmentation, args.cache)
            params = TrapParams.from_mapping({"segmentation": segmentation})
            miner = PatternMiner(params, len(graphs))
            for graph in graphs:
                miner.add(graph)
            mined = miner.finish()
            width, height = graphs[0].frame_size
            largest = max(float(g.area.max()) for g in graphs) / (width * height)
            pan = build_world(SceneConfig(**scene)).camera.astype(float)
            cells = []
            with_backdrop = observed_paths(mined)
            stacked = StackedGraphs.of(graphs)
            read = camera_paths(stacked, observed_paths(without_backdrop(mined, stacked)), params.eps)
            steps = np.stack([graph.camera_step for graph in graphs])
            for paths, image_steps in ((with_backdrop, None), (read, None), (read, steps)):
                errors = _errors(camera_transforms(paths, len(graphs), image_steps), pan)
                cells.append(f"{np.median(errors):.2f} / {np.percentile(errors, 90):.2f}")
            from_images = np.mean([graph.has_camera_step for graph in graphs[1:]])
            print(f"| {set_name} | {label} | {largest:.2f} | {' | '.join(cells)} | {from_images:.2f} |", flush=True)


if __name__ == "__main__":
    main()
