"""Which clusters are tracks (TRAP_SPEC section 7)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from trap_core.clustering.trajectory import Trajectories


@dataclass(frozen=True)
class ClusterSummary:
    """Per cluster: frames covered by its patterns, pattern and occurrence counts, mean path."""

    covered: np.ndarray       # (C, n_frames) bool
    n_patterns: np.ndarray    # (C,)
    n_occurrences: np.ndarray  # (C,)
    paths: Trajectories       # mean trajectory of each cluster's patterns, per covered frame

    @property
    def length(self) -> np.ndarray:
        return self.covered.sum(axis=1)


def summarise(labels: np.ndarray, tracks: Trajectories, occurrences_per_pattern: np.ndarray,
              n_frames: int) -> ClusterSummary:
    """Length, counts and mean path of each cluster (labels 0..C-1 over the patterns)."""
    n_clusters = int(labels.max()) + 1 if labels.size else 0
    covered = np.zeros((n_clusters, n_frames), dtype=bool)
    sums = np.zeros((n_clusters, n_frames, 2))
    counts = np.zeros((n_clusters, n_frames))
    for pattern, cluster in enumerate(labels):
        span = slice(tracks.start[pattern], tracks.end[pattern] + 1)
        covered[cluster, span] = True
        sums[cluster, span] += tracks.of(pattern)
        counts[cluster, span] += 1
    samples = []
    for cluster in range(n_clusters):
        frames = np.flatnonzero(covered[cluster])
        samples.append((frames, sums[cluster, frames] / counts[cluster, frames, None]))
    paths = Trajectories.from_samples(samples)
    return ClusterSummary(covered, np.bincount(labels, minlength=n_clusters),
                          np.bincount(labels, weights=occurrences_per_pattern, minlength=n_clusters).astype(np.int64),
                          paths)


def _longest(summary: ClusterSummary, candidates: np.ndarray, tolerance_frames: float) -> int:
    """The paper's "longest": within ``tolerance_frames`` of the longest, most patterns, then most occurrences."""
    lengths = summary.length[candidates]
    near = candidates[lengths >= lengths.max() - tolerance_frames]
    order = np.lexsort((-summary.n_occurrences[near], -summary.n_patterns[near]))
    return int(near[order[0]])


def select_clusters(summary: ClusterSummary, n_frames: int, n_objects: int | None = None,
                    tolerance: float = 0.1, min_length: float = 0.25, separation: float = 40.0,
                    max_objects: int = 20, eligible: np.ndarray | None = None) -> list[int]:
    """Clusters that are tracks, in order of selection.

    ``eligible``: per cluster, whether it may be a track at all (ours: clusters that move
    relative to the camera); by default every cluster.

    With ``n_objects``: the ``n_objects`` longest clusters, one after another (the paper).
    Without (ours, unsupervised): keep taking the next longest cluster while it covers at
    least ``min_length`` of the video, skipping any cluster that is, in most of the frames it
    covers, within ``separation`` pixels of a cluster already kept: "the longest clusters that
    are far enough from each other". Counting frames against every kept cluster (not a mean
    distance to each) also rejects a chain of fragments that follows one object, then
    another.
    """
    remaining = np.arange(summary.length.size)
    if eligible is not None:
        remaining = remaining[eligible]
    chosen: list[int] = []
    limit = n_objects if n_objects is not None else max_objects
    while remaining.size and len(chosen) < limit:
        best = _longest(summary, remaining, tolerance * n_frames)
        remaining = remaining[remaining != best]
        if n_objects is None:
            if summary.length[best] < min_length * n_frames:
                break
            if chosen and _share_near(summary, best, chosen, separation) > 0.5:
                continue
        chosen.append(best)
    return chosen


def _share_near(summary: ClusterSummary, cluster: int, others: list[int], separation: float) -> float:
    """Share of the frames ``cluster`` covers where its mean position is within ``separation``
    pixels of the mean position of one of ``others`` covering that frame."""
    frames = np.flatnonzero(summary.covered[cluster])
    paths = summary.paths
    here = paths.of(cluster)[frames - paths.start[cluster]]
    near = np.zeros(frames.size, dtype=bool)
    for other in others:
        both = summary.covered[other, frames]
        there = paths.of(other)[frames[both] - paths.start[other]]
        near[both] |= np.linalg.norm(here[both] - there, axis=1) <= separation
    return float(near.mean()) if frames.size else 0.0
