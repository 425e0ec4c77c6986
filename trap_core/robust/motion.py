"""Straight-line motion of a track's box centres, robust to a stray box (ours)."""
from __future__ import annotations

import numpy as np


def straight_line(centres: np.ndarray, frames: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Velocity and position at frame 0 of the Theil-Sen line through the centres seen in
    ``frames`` (None with fewer than three): medians of the pairwise slopes and of the offsets,
    so that one stray box does not make a turn."""
    seen = frames[~np.isnan(centres[frames, 0])]
    if seen.size < 3:
        return None
    first, second = np.triu_indices(seen.size, k=1)
    slopes = (centres[seen[second]] - centres[seen[first]]) / (seen[second] - seen[first])[:, None]
    velocity = np.median(slopes, axis=0)
    return velocity, np.median(centres[seen] - velocity * seen[:, None], axis=0)
