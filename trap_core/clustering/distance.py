"""Distance between spatio-temporal patterns (TRAP_SPEC section 5)."""
from __future__ import annotations

import numpy as np

from trap_core.clustering._kernels import pairwise_distance
from trap_core.clustering.trajectory import Trajectories


def pattern_distances(tracks: Trajectories) -> np.ndarray:
    """Condensed (scipy order) matrix of ``d(A, B) = d_traj(A, B) * (2 - d_ov(A, B))``.

    ``d_traj`` is the mean distance between the trajectories over their common frames and
    ``d_ov`` the share of the union of their frames that they have in common; the distance is
    ``inf`` when they share fewer than two frames.
    """
    return pairwise_distance(tracks.start, tracks.end, tracks.offsets, np.ascontiguousarray(tracks.points))
