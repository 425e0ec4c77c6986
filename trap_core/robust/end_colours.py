"""What a fragment's object looks like where it ends and where another starts: the mean colours
of its core regions there (ours).

Fragments that an object's motion cannot link (one surely left the view and the other surely
enters it, or the gap between them is long) are continued by their shared structures, and
structures are made of discretised colours (``colour_bins`` levels a channel): objects of
different colours whose colours fall in the same bins show the same structures. In footage
where objects pass through the view one after another (traffic), each one that left was
continued by the next that came in with the same bins, hundreds of frames later. The regions'
mean colours are not discretised: an object's parts keep theirs across the gap, but for the
light, which may change while it is away (a cloud, the camera's exposure) and scales every
colour by one factor.
"""
from __future__ import annotations

import numpy as np

from trap_core.clustering.tracks import frame_cores
from trap_core.mining import MiningResult
from trap_core.rag.stacked import StackedGraphs

END_FRAMES = 10  # frames at a fragment's end (or start) whose core regions are its colours there
# brightness ratios tried between the two ends (light and exposure change while an object is away)
GAINS = np.exp(np.linspace(np.log(0.8), np.log(1.25), 19))
MIN_MATCH = 0.5  # share of one end's area in colours the other end has, for one object


class EndColours:
    """Per fragment (cluster ``0..C-1`` of ``labels`` over ``patterns``), the colours of its core
    regions (:func:`trap_core.clustering.tracks.core_regions`, ``share``) in its first and last
    ``END_FRAMES`` frames, read on first use: only fragments in a pair across an exit or a long
    gap are compared."""

    def __init__(self, result: MiningResult, patterns: np.ndarray, labels: np.ndarray, stacked: StackedGraphs,
                 share: float, reach: float) -> None:
        self._result, self._patterns, self._labels = result, patterns, labels
        self._stacked, self._share, self._reach = stacked, share, reach
        self._ends: dict[int, tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]] = {}

    def _colours(self, cluster: int) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
        """(colours, areas) of the core regions of ``cluster``'s first, then last frames."""
        if cluster not in self._ends:
            cores = list(frame_cores(self._result, self._patterns[self._labels == cluster], self._stacked,
                                     self._share, END_FRAMES))
            ends = []
            for chosen in cores[:END_FRAMES], cores[-END_FRAMES:]:
                rows = np.concatenate([self._stacked.node_offsets[frame] + core for frame, core, _ in chosen]
                                      or [np.zeros(0, dtype=np.int64)])
                ends.append((self._stacked.colour[rows].astype(np.float64),
                             self._stacked.area[rows].astype(np.float64)))
            self._ends[cluster] = (ends[0], ends[1])
        return self._ends[cluster]

    def match(self, earlier: int, later: int) -> float:
        """:func:`colours_match` of ``earlier``'s last colours and ``later``'s first."""
        return colours_match(*self._colours(earlier)[1], *self._colours(later)[0], self._reach)


def colours_match(colours: np.ndarray, areas: np.ndarray, others: np.ndarray, other_areas: np.ndarray,
                  reach: float) -> float:
    """How alike two sets of region colours ((K, 3) RGB, with their areas) are: the larger, over
    both ways, of the share of one set's area in colours within ``reach`` of a colour of the
    other, at the brightness ratio (``GAINS``) that matches most. Either way, not both: the two
    ends may show different parts of one object besides those they share. 1 where either set
    is empty (nothing tells them apart)."""
    if areas.sum() <= 0 or other_areas.sum() <= 0:
        return 1.0
    # |g c - o|^2 = g^2 |c|^2 - 2 g c.o + |o|^2, for every brightness ratio g at once
    gains = GAINS[:, None, None]
    squared = (gains ** 2 * (colours ** 2).sum(axis=1)[:, None] - 2 * gains * (colours @ others.T)
               + (others ** 2).sum(axis=1)[None, :])
    near = squared <= reach ** 2
    return float(max((near.any(axis=2) @ areas).max() / areas.sum(),
                     (near.any(axis=1) @ other_areas).max() / other_areas.sum()))
