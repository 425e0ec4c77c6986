"""Distance between spatio-temporal patterns (TRAP_SPEC section 5)."""
from __future__ import annotations

import numpy as np

from trap_core.clustering._kernels import pairwise_distance
from trap_core.clustering.trajectory import Trajectories
from trap_core.ordered import each_on_threads


def pattern_distances(tracks: Trajectories, threads: int = 1) -> np.ndarray:
    """Condensed (scipy order) matrix of ``d(A, B) = d_traj(A, B) * (2 - d_ov(A, B))``.

    ``d_traj`` is the mean distance between the trajectories over their common frames and
    ``d_ov`` the share of the union of their frames that they have in common; the distance is
    ``inf`` when they share fewer than two frames. The matrix is filled in ``threads`` bands of
    rows holding as many pairs each (:func:`row_bands`), at once: the same values as one pass.
    """
    n = len(tracks)
    out = np.empty(n * (n - 1) // 2, dtype=np.float64)
    inputs = (tracks.start, tracks.end, tracks.offsets, np.ascontiguousarray(tracks.points))
    bounds = row_bands(n, threads)
    each_on_threads(lambda band: pairwise_distance(*inputs, bounds[band], bounds[band + 1], out),
                    range(bounds.size - 1), threads)
    return out


def row_bands(n: int, bands: int) -> np.ndarray:
    """First row of each of at most ``bands`` bands of the condensed matrix of ``n`` items, then
    ``n``: bands of consecutive rows with about the same number of pairs (row ``a`` holds
    ``n - 1 - a``), none empty."""
    if n < 2:
        return np.array([0, n], dtype=np.int64)
    rows = np.arange(n + 1, dtype=np.int64)
    before = rows * (2 * n - rows - 1) // 2  # pairs in the rows before each row
    wanted = np.arange(1, bands) * before[-1] / bands
    return np.unique(np.r_[0, np.searchsorted(before, wanted), n]).astype(np.int64)
