"""Agglomerative clustering of patterns and the lifetime cut (TRAP_SPEC section 6)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.cluster.hierarchy import linkage

from trap_core.clustering.errors import ClusteringError

LINKAGES = ("average", "single", "complete", "weighted")


@dataclass(frozen=True)
class Hierarchy:
    """A dendrogram over ``n`` patterns (scipy linkage matrix) and where it was cut."""

    n: int
    linkage: np.ndarray    # (n-1, 4) scipy linkage matrix
    cut_level: int         # number of clusters at the cut
    labels: np.ndarray     # (n,) cluster of each pattern at the cut, 0..cut_level-1


def labels_after_merges(matrix: np.ndarray, n: int, merges: int) -> np.ndarray:
    """Partition after the first ``merges`` rows of a linkage matrix, clusters numbered 0.. by first member."""
    parent = np.arange(2 * n - 1)
    for row in range(merges):
        a, b = int(matrix[row, 0]), int(matrix[row, 1])
        parent[a] = parent[b] = n + row
    root = parent[:n].copy()
    # Follow parents to the newest cluster formed so far (each step only moves to larger ids).
    while True:
        nxt = parent[root]
        if np.array_equal(nxt, root):
            break
        root = nxt
    _, labels = np.unique(root, return_inverse=True)
    first = np.full(labels.max() + 1 if n else 0, n)
    np.minimum.at(first, labels, np.arange(n))
    return np.argsort(np.argsort(first))[labels]


def lifetime_cut(matrix: np.ndarray, n: int, ignore_top: float = 0.1) -> int:
    """Level (number of clusters) where the cluster of highest lifetime was created.

    Lifetime = height at which a cluster is merged into another minus height at which it was
    formed. Clusters created in the top ``ignore_top`` share of levels (levels 1..0.1n, where
    outliers merge last) are ignored, and so are single patterns (ours: a cluster must be
    formed by a merge).
    """
    if n < 3:
        return 1
    heights = matrix[:, 2]
    merged_at = np.full(2 * n - 1, np.nan)
    merged_at[matrix[:, 0].astype(int)] = heights
    merged_at[matrix[:, 1].astype(int)] = heights
    rows = np.arange(n - 1)
    lifetime = merged_at[n + rows] - heights
    created_level = n - rows - 1
    candidate = (created_level > ignore_top * n) & np.isfinite(lifetime)
    if not candidate.any():
        return 1
    best = rows[candidate][np.argmax(lifetime[candidate])]
    return int(n - best - 1)


def cluster_patterns(condensed: np.ndarray, n: int, method: str = "average", ignore_top: float = 0.1) -> Hierarchy:
    """Cluster ``n`` patterns from their condensed distance matrix and cut at the lifetime level.

    Infinite distances (patterns sharing no frames) become one finite stand-in, twice the
    largest finite distance plus one, so they merge last.
    """
    if method not in LINKAGES:
        raise ClusteringError(f"linkage must be one of {LINKAGES}, not {method!r}")
    if n < 2:
        return Hierarchy(n, np.empty((0, 4)), n, np.zeros(n, dtype=np.int64))
    finite = condensed[np.isfinite(condensed)]
    stand_in = 2.0 * (finite.max() if finite.size else 1.0) + 1.0
    matrix = linkage(np.where(np.isfinite(condensed), condensed, stand_in), method=method)
    level = lifetime_cut(matrix, n, ignore_top)
    return Hierarchy(n, matrix, level, labels_after_merges(matrix, n, n - level))
