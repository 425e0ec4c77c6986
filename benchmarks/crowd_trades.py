#!/usr/bin/env python3
"""Benchmark: how often the trades at crossings put look-alikes that crowd back on their own tracks.

Where look-alikes overlap, the paths of the mining can leave a meeting each on another object
(README, one track per object). ``trap_core.robust.swap_at_crossings`` exchanges continuations
back where the motions say so. This measures the rule alone, on boxes with no noise: per crowd,
three 40x30 look-alikes on straight lines (speeds drawn up to 3 px a frame each way) pass within
12 px of one point in frame 50 of 100; their tracks trade objects one to three times, between
pairs and at frames (42-58) drawn at random. A crowd is put right when, in every frame where no
two objects are within 45 px (where any box would do), each track holds its own object again.
Prints, over the crowds whose trades changed what a track holds, how many the rule puts right,
by number of trades.
Run: ``.venv/bin/python benchmarks/crowd_trades.py [--crowds 3000] [--generator 1]``.
"""
from __future__ import annotations

import argparse
from collections import Counter

import numpy as np

from trap_core.clustering import Track, box_centres
from trap_core.robust import swap_at_crossings

FRAMES = 100
SIZE = (40.0, 30.0)
APART = 45.0  # px between every two objects' centres: a frame where each box tells its object


def crowd(rng: np.random.Generator) -> tuple[list[np.ndarray], list[np.ndarray], int]:
    """Three look-alikes' true box paths (FRAMES, 4), their tracks' paths after one to three
    trades, and the number of trades."""
    t = np.arange(FRAMES, dtype=float)[:, None]
    velocity, offset = rng.uniform(-3, 3, (3, 2)), rng.uniform(-12, 12, (3, 2))
    size = np.tile(SIZE, (FRAMES, 1))
    truth = [np.hstack([250.0 + offset[k] + velocity[k] * (t - 50) - size / 2, size]) for k in range(3)]
    traded = [path.copy() for path in truth]
    trades = int(rng.integers(1, 4))
    for _ in range(trades):
        a, b = rng.choice(3, 2, replace=False)
        at = int(rng.integers(42, 59))
        traded[a][at:], traded[b][at:] = traded[b][at:].copy(), traded[a][at:].copy()
    return truth, traded, trades


def own_objects(paths: list[np.ndarray], truth: list[np.ndarray], apart: np.ndarray) -> bool:
    """Whether each path holds its own object in every frame ``apart``."""
    return all(np.allclose(path[apart], own[apart]) for path, own in zip(paths, truth))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--crowds", type=int, default=3000, help="crowds drawn (default 3000)")
    parser.add_argument("--generator", type=int, default=1, help="seed of the draws (default 1)")
    args = parser.parse_args()
    rng = np.random.default_rng(args.generator)
    counted, right_after = Counter(), Counter()
    alike = np.ones((3, 3), dtype=bool)
    frames = np.arange(FRAMES)
    for _ in range(args.crowds):
        truth, traded, trades = crowd(rng)
        centres = [box_centres(path) for path in truth]
        apart = np.min([np.linalg.norm(centres[i] - centres[j], axis=1) for i, j in ((0, 1), (1, 2), (0, 2))],
                       axis=0) > APART
        if apart.sum() < 40 or own_objects(traded, truth, apart):  # too crowded to judge, or no change
            continue
        tracks = [Track(k + 1, frames, path, np.ones(FRAMES), k + 1) for k, path in enumerate(traded)]
        out = swap_at_crossings(tracks, FRAMES, 8, alike)
        counted[trades] += 1
        right_after[trades] += own_objects([track.boxes for track in out], truth, apart)
    print("| trades | crowds | every track on its own object after the rule |")
    print("|---|---|---|")
    for trades in sorted(counted):
        print(f"| {trades} | {counted[trades]} | {right_after[trades]} ({right_after[trades] / counted[trades]:.0%}) |")
    total = sum(counted.values())
    print(f"| all | {total} | {sum(right_after.values())} ({sum(right_after.values()) / max(total, 1):.0%}) |")


if __name__ == "__main__":
    main()
