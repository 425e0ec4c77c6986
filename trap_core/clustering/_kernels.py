"""Compiled kernel of the pattern distance (numba): all pairs, only over shared frames."""
from __future__ import annotations

import numba as nb
import numpy as np

from trap_core.mining._kernels import _root  # union-find root with path halving, shared with occurrence linking


@nb.njit(cache=True, nogil=True, parallel=False)
def pairwise_distance(start: np.ndarray, end: np.ndarray, offsets: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Condensed matrix of d(A, B) = d_traj * (2 - d_ov) (TRAP_SPEC section 5), inf where two
    trajectories share fewer than two frames.

    Trajectory i covers frames ``start[i]..end[i]``; its points are
    ``points[offsets[i]:offsets[i + 1]]`` (one per frame, gaps already interpolated).
    """
    n = start.size
    out = np.empty(n * (n - 1) // 2, dtype=np.float64)
    k = 0
    for a in range(n):
        for b in range(a + 1, n):
            fs = max(start[a], start[b])
            fe = min(end[a], end[b])
            if fe - fs <= 0:
                out[k] = np.inf
            else:
                total = 0.0
                pa = offsets[a] + fs - start[a]
                pb = offsets[b] + fs - start[b]
                for t in range(fe - fs + 1):
                    dx = points[pa + t, 0] - points[pb + t, 0]
                    dy = points[pa + t, 1] - points[pb + t, 1]
                    total += np.sqrt(dx * dx + dy * dy)
                overlap = (fe - fs + 1) / (max(end[a], end[b]) - min(start[a], start[b]) + 1)
                out[k] = total / (fe - fs + 1) * (2.0 - overlap)
            k += 1
    return out


@nb.njit(cache=True, nogil=True)
def sharing_components(nodes: np.ndarray, ends: np.ndarray, n_nodes: int) -> np.ndarray:
    """Component (numbered 0.. in the order of each one's root set) of each set of nodes (set
    ``i`` is ``nodes[ends[i - 1]:ends[i]]``), sets that share a node being linked: the places
    of one frame's occurrences (:func:`trap_core.clustering.one_place`)."""
    n_sets = ends.size
    first_holder = np.full(n_nodes, -1, dtype=np.int64)
    parent = np.arange(n_sets)
    start = 0
    for item in range(n_sets):
        for j in range(start, ends[item]):
            node = nodes[j]
            if first_holder[node] < 0:
                first_holder[node] = item
            parent[_root(parent, item)] = _root(parent, first_holder[node])
        start = ends[item]
    is_root = np.zeros(n_sets, dtype=np.int64)
    roots = np.empty(n_sets, dtype=np.int64)
    for item in range(n_sets):
        roots[item] = _root(parent, item)
        is_root[roots[item]] = 1
    number = np.cumsum(is_root) - 1
    return number[roots]
