"""Straight-line motion of a track's box centres, robust to a stray box (ours)."""
from __future__ import annotations

import numpy as np

from trap_core.robust._kernels import theil_sen


def straight_line(centres: np.ndarray, frames: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Velocity and position at frame 0 of the Theil-Sen line through the centres seen in
    ``frames`` (None with fewer than three): medians of the pairwise slopes and of the offsets,
    so that one stray box does not make a turn. Compiled: crossings and strays ask for lines
    around every frame of every track."""
    seen = frames[~np.isnan(centres[frames, 0])]
    if seen.size < 3:
        return None
    return theil_sen(np.ascontiguousarray(centres[seen], dtype=np.float64), seen.astype(np.float64))
