"""Rejoin the fragments of one object separated by an occlusion or an exit (ours, TRAP_SPEC
section 10 "fragments never rejoin").

The pattern distance is infinite between patterns that share no frames, so an object that
disappears for a while comes back as another cluster. Two clusters are joined when they do
not overlap in time (at most ``max_overlap`` shared frames), are made of the same structures
(Jaccard similarity of their plane patterns at least ``min_similarity``), and, among all such
pairs, the later one starts closest to where the earlier one's motion predicts; pairs are
joined greedily, closest first, and a joined cluster can no longer take a fragment that
overlaps it, which keeps look-alike objects apart.
"""
from __future__ import annotations

import numpy as np

from trap_core.clustering import Trajectories, summarise


def _signature(labels: np.ndarray, st_pattern: np.ndarray, cluster: int) -> set[int]:
    return set(st_pattern[labels == cluster].tolist())


def rejoin_fragments(labels: np.ndarray, paths: Trajectories, st_pattern: np.ndarray, n_frames: int,
                     min_similarity: float = 0.3, max_overlap: int = 25) -> np.ndarray:
    """Cluster labels (0..C'-1) after joining fragments of the same object."""
    labels = np.unique(labels, return_inverse=True)[1]
    occurrences = np.ones(labels.size)
    while True:
        summary = summarise(labels, paths, occurrences, n_frames)
        n_clusters = summary.length.size
        signatures = [_signature(labels, st_pattern, c) for c in range(n_clusters)]
        best: tuple[float, int, int] | None = None
        for a in range(n_clusters):
            for b in range(n_clusters):
                if a == b or summary.paths.start[a] >= summary.paths.start[b]:
                    continue
                overlap = int((summary.covered[a] & summary.covered[b]).sum())
                if overlap > max_overlap:
                    continue
                union = signatures[a] | signatures[b]
                if not union or len(signatures[a] & signatures[b]) / len(union) < min_similarity:
                    continue
                cost = _prediction_error(summary.paths, a, b)
                if best is None or cost < best[0]:
                    best = (cost, a, b)
        if best is None:
            return labels
        _, a, b = best
        labels = np.unique(np.where(labels == b, a, labels), return_inverse=True)[1]


def _prediction_error(paths: Trajectories, earlier: int, later: int) -> float:
    """Distance between where ``later`` starts and where ``earlier``'s last motion would put it."""
    before = paths.of(earlier)
    tail = before[-min(len(before), 10):]
    velocity = (tail[-1] - tail[0]) / max(len(tail) - 1, 1)
    gap = paths.start[later] - paths.end[earlier]
    predicted = before[-1] + velocity * gap
    return float(np.linalg.norm(paths.of(later)[0] - predicted))
