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
        return Trajectories.pack(self.start[index], [self.of(i) for i in index])

    @staticmethod
    def pack(starts: np.ndarray | list[int], pieces: list[np.ndarray]) -> Trajectories:
        """Trajectories from each one's first frame and its points, one per frame from there on."""
        sizes = np.array([len(p) for p in pieces], dtype=np.int64)
        starts = np.asarray(starts, dtype=np.int64).reshape(-1)
        return Trajectories(starts, starts + sizes - 1, np.r_[0, np.cumsum(sizes)].astype(np.int64),
                            np.concatenate(pieces) if pieces else np.empty((0, 2)))

    @staticmethod
    def from_samples(samples: list[tuple[np.ndarray, np.ndarray]]) -> Trajectories:
        """One trajectory per ``(frames, points)``: points at those (sorted, distinct) frames,
        linearly interpolated across the frames between them (TRAP_SPEC section 4)."""
        pieces = []
        for frames, points in samples:
            span = np.arange(frames[0], frames[-1] + 1)
            pieces.append(np.column_stack([np.interp(span, frames, points[:, axis]) for axis in (0, 1)]))
        return Trajectories.pack([frames[0] for frames, _ in samples], pieces)


def trajectories(result: MiningResult, patterns: np.ndarray | None = None) -> Trajectories:
    """Build the trajectory of each spatio-temporal pattern of ``result`` (of ``patterns`` only,
    in that order, when given)."""
    samples = []
    for s in (range(result.n_st) if patterns is None else patterns):
        rows = result.st(s)
        known, inverse = np.unique(result.occ_frame[rows], return_inverse=True)
        counts = np.bincount(inverse)
        mean = np.column_stack([np.bincount(inverse, weights=result.occ_position[rows, axis]) / counts
                                for axis in (0, 1)])
        samples.append((known, mean))
    return Trajectories.from_samples(samples)
