#!/usr/bin/env python3
"""Benchmark: tracking time of the robust method against the paper's, on the same graphs.

Issue 8 asks the robust method to be no slower than the paper's by more than 1.5x. For each
video (by default Anim1, Anim2, four identical objects with a turning camera and noise, seed
161, and the two videos of ``quality.py`` where the ratio is highest: look-alike people over a
road and over the colour wheel, whose rules build the most spare clusters' tracks, while the
paper's method finds little to cluster there), prints ``track()``'s time after the graphs
(mining included), best of ``--repeat`` runs, for ``method: paper`` and ``method: robust``,
and their ratio. Graphs come from ``quality.py``'s cache (made there on first use). With
``--graphs`` it also times the graph stage of each method on the video's frames (rendered into
memory first; least of ``--graph-repeat`` runs), and gives the ratio of the whole run after
decoding, graphs and tracking: what a user waits for per bag.
Run: ``.venv/bin/python benchmarks/method_speed.py [--graphs] [--videos "analogues:anim1 seed 0;..."]``.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import quality  # noqa: E402  (the benchmark sets and their graph cache)

from trap_core.pipeline import TrapParams, graphs_of, synthetic_frames, track  # noqa: E402

VIDEOS = ("analogues:anim1 seed 0;analogues:anim2 seed 0;newest:identical, 4 objects, turn 10 deg, noise 1, Felzenszwalb;"
          "random:identical, person, 5 objects, 640x480, 721 frames, noise 2, road;"
          "random:identical, person, 4 objects 1.2x, 960x540, 721 frames, zoom 10 %, colorwheel")


def _best_time(graphs: list, params: TrapParams, repeat: int) -> float:
    """Least seconds of ``repeat`` runs of :func:`track` on ``graphs``."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        track(graphs, params)
        best = min(best, time.perf_counter() - start)
    return best


def _graph_seconds(frames: list, params: TrapParams, repeat: int) -> float:
    """Least seconds of ``repeat`` runs of :func:`graphs_of` over the video's ``frames`` (in
    memory: a bag's decoding is left out) with ``params``' method: the robust one also reads the
    camera's step from each frame. One run can be seconds off (two threads on two cores)."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        for _ in graphs_of(frames, params):
            pass
        best = min(best, time.perf_counter() - start)
    return best


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--videos", default=VIDEOS, help="set:label pairs of quality.py, separated by ';'")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--graphs", action="store_true",
                        help="also time the graph stage of each method (segmentation, plane graphs, the robust "
                             "method's camera steps; --graph-repeat runs, the least counts) and give the whole "
                             "run's ratio (~1 min a video more a run)")
    parser.add_argument("--graph-repeat", type=int, default=1,
                        help="runs of each graph stage, the least counts (~20 s a run at 640x480, 721 frames)")
    parser.add_argument("--cache", type=Path, default=Path.home() / ".cache" / "trap_ros" / "quality")
    args = parser.parse_args()
    if args.graphs:
        print("| video | paper s | robust s | robust / paper | graphs paper s | graphs robust s "
              "| whole run robust / paper |\n|---|---|---|---|---|---|---|")
    else:
        print("| video | paper s | robust s | robust / paper |\n|---|---|---|---|")
    for video in args.videos.split(";"):
        set_name, label = video.split(":", 1)
        scene, segmentation = next((s, g) for name, s, g in quality.SETS[set_name] if name == label)
        graphs, _ = quality._graphs(scene, segmentation, args.cache)
        params = {method: TrapParams.from_mapping({"segmentation": segmentation, "method": method})
                  for method in ("paper", "robust")}
        paper, robust = (_best_time(graphs, params[method], args.repeat) for method in ("paper", "robust"))
        row = f"| {label} | {paper:.2f} | {robust:.2f} | {robust / paper:.2f} |"
        if args.graphs:
            config, delivery = quality._scene_config(scene)
            frames = list(synthetic_frames(config, **delivery))  # rendered, compressed or encoded as the scene says
            graphs_paper, graphs_robust = (_graph_seconds(frames, params[method], args.graph_repeat)
                                           for method in ("paper", "robust"))
            row += (f" {graphs_paper:.2f} | {graphs_robust:.2f} |"
                    f" {(graphs_robust + robust) / (graphs_paper + paper):.2f} |")
        print(row, flush=True)


if __name__ == "__main__":
    main()
