"""Trajectories of spatio-temporal patterns (TRAP_SPEC section 4)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from trap_core.clustering._kernels import interpolate_samples
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

    def at(self, index: int, frames: np.ndarray | int) -> np.ndarray:
        """Points of trajectory ``index`` in ``frames`` (within its span)."""
        return self.of(index)[np.asarray(frames) - self.start[index]]

    def dense(self, rows: np.ndarray, frames: np.ndarray) -> np.ndarray:
        """(len(rows), len(frames), 2): the points of trajectories ``rows`` in ``frames``, NaN
        outside their spans; for comparing many trajectories frame by frame (one gather for all
        of them: the continuation rules ask it of hundreds of candidates at a time)."""
        rows, frames = np.asarray(rows, dtype=np.int64), np.asarray(frames, dtype=np.int64)
        start = self.start[rows, None]
        inside = (frames >= start) & (frames <= self.end[rows, None])
        out = np.full((len(rows), len(frames), 2), np.nan)
        out[inside] = self.points[(self.offsets[rows, None] + frames - start)[inside]]
        return out

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
    def interpolated(frames: np.ndarray, points: np.ndarray, bounds: np.ndarray) -> Trajectories:
        """One trajectory per sample ``frames[bounds[i]:bounds[i + 1]]`` (int64, sorted and
        distinct in each, never empty) with ``points`` (float64) there: linearly interpolated
        across the frames between them (TRAP_SPEC section 4)."""
        bounds = np.asarray(bounds, dtype=np.int64)
        if np.any(np.diff(bounds) <= 0):
            raise ValueError("every trajectory needs at least one sample")
        offsets, interpolated = interpolate_samples(frames, points, bounds)
        start = frames[bounds[:-1]]
        return Trajectories(start, start + np.diff(offsets) - 1, offsets, interpolated)


@dataclass(frozen=True)
class ObservedPaths:
    """Per spatio-temporal pattern and observed frame: the mean position of its occurrences."""

    pattern: np.ndarray   # (K,) sorted by pattern then frame
    frame: np.ndarray     # (K,)
    position: np.ndarray  # (K, 2)


def observed_paths(result: MiningResult) -> ObservedPaths:
    """Mean position of each spatio-temporal pattern in each frame where it occurs.

    Each pattern's rows are sorted by frame, so the (pattern, frame) groups are runs: summed
    with one ``reduceat``, without sorting millions of keys (memory at the end of a long bag).
    """
    frames = result.occ_frame[result.st_rows]
    new_group = np.ones(frames.size, dtype=bool)
    new_group[1:] = frames[1:] != frames[:-1]
    new_group[result.st_offsets[1:-1]] = True  # a new pattern starts a new group
    starts = np.flatnonzero(new_group)
    counts = np.diff(np.r_[starts, frames.size])
    position = np.add.reduceat(result.occ_position[result.st_rows].astype(np.float64), starts, axis=0) \
        if starts.size else np.empty((0, 2))
    pattern = np.searchsorted(result.st_offsets, starts, side="right") - 1
    return ObservedPaths(pattern, frames[starts].astype(np.int64), position / counts[:, None])


def trajectories(observed: ObservedPaths, patterns: np.ndarray) -> Trajectories:
    """Trajectory of each of ``patterns`` (in that order) from its mean position per observed
    frame (TRAP_SPEC section 4)."""
    bounds = np.searchsorted(observed.pattern, np.stack([patterns, np.asarray(patterns) + 1]))
    lengths = bounds[1] - bounds[0]
    ends = np.cumsum(lengths)
    rows = np.arange(ends[-1] if ends.size else 0) + np.repeat(bounds[0] - (ends - lengths), lengths)
    return Trajectories.interpolated(observed.frame[rows], observed.position[rows], np.r_[0, ends])
