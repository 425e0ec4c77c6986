"""Patterns the video's ends cut short: kept only for objects no longer pattern follows (ours).

The miner keeps a pattern seen in fewer than ``freq_st_min`` frames when it lies within ``tau``
of the video's first or last frame (:attr:`~trap_core.mining.MiningParams.freq_st_cut`): an
object that enters the view in the video's last second, or leaves it in the first, shows no
longer pattern. Most such patterns, though, lie on objects that longer patterns already follow
(an object's structures come and go, and at the ends every short piece of them is kept): over
four look-alikes in 721 frames, three times as many as the long ones. They add nothing but
fragments for rejoining to chain wrongly, start to end. A short pattern is kept only where no
long one goes along with it: within half the smaller of their sizes (each centre inside the
other's extent) in at least half of its frames. Half the sum, the most two patterns of one
object can be apart (:mod:`trap_core.robust.mixed`), is no test of going along: over gravel,
every short pattern lay that close to some long face with a sprawling region.
"""
from __future__ import annotations

import numpy as np

from trap_core.clustering import Trajectories
from trap_core.robust._kernels import goes_along


def alone_at_ends(paths: Trajectories, short: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """Which patterns are ``short`` and go along with no pattern that is not.

    Parameters
    ----------
    paths : Trajectories
        The patterns' trajectories.
    short : (n,) bool
        Patterns kept only as the video's ends cut them short.
    sizes : (n,) array
        Each pattern's size (:func:`~trap_core.robust.mixed.pattern_sizes`).

    Returns
    -------
    (n,) bool
    """
    alone = short.copy()
    short_rows, long_rows = np.flatnonzero(short), np.flatnonzero(~short)
    if not short_rows.size or not long_rows.size:
        return alone
    alone[short_rows] = ~goes_along(short_rows, long_rows, np.asarray(sizes, dtype=np.float64), paths.start, paths.end,
                                    paths.offsets, paths.points)
    return alone
