"""Trajectories of spatio-temporal patterns (TRAP_SPEC section 4)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from trap_core.mining import MiningResult


@dataclass(frozen=True)
class Trajectories:
    """One point per frame for each pattern, from its first to its last frame.

    Pattern ``i`` covers frames ``start[i]..end[i]``; its points are
    ``points[offsets[i]:offsets[i + 1]]``: the mean position of its occurrences in each frame,
    linearly interpolated across frames without occurrence.
    """

    start: np.ndarray
    end: np.ndarray
    offsets: np.ndarray
    points: np.ndarray

    def of(self, index: int) -> np.ndarray:
        return self.points[self.offsets[index]:self.offsets[index + 1]]

    def __len__(self) -> int:
        return int(self.start.size)

    def subset(self, index: np.ndarray) -> Trajectories:
        """The trajectories of patterns ``index``, renumbered 0..len(index)-1."""
        sizes = self.end[index] - self.start[index] + 1
        points = np.concatenate([self.of(i) for i in index]) if len(index) else np.empty((0, 2))
        return Trajectories(self.start[index], self.end[index], np.r_[0, np.cumsum(sizes)].astype(np.int64), points)


def trajectories(result: MiningResult) -> Trajectories:
    """Build the trajectory of every spatio-temporal pattern of ``result``."""
    starts, ends, pieces = [], [], []
    for s in range(result.n_st):
        rows = result.st(s)
        frames = result.occ_frame[rows]
        known, inverse = np.unique(frames, return_inverse=True)
        counts = np.bincount(inverse)
        mean = np.column_stack([np.bincount(inverse, weights=result.occ_position[rows, axis]) / counts
                                for axis in (0, 1)])
        span = np.arange(known[0], known[-1] + 1)
        pieces.append(np.column_stack([np.interp(span, known, mean[:, axis]) for axis in (0, 1)]))
        starts.append(known[0])
        ends.append(known[-1])
    sizes = np.array([len(p) for p in pieces], dtype=np.int64)
    return Trajectories(np.array(starts, dtype=np.int64), np.array(ends, dtype=np.int64),
                        np.r_[0, np.cumsum(sizes)].astype(np.int64),
                        np.concatenate(pieces) if pieces else np.empty((0, 2)))
