"""Boxes through a meeting of look-alikes put back on the object's path (ours).

Where two look-alikes touch or overlap, their regions merge and every pattern on either lies on
the pair: :func:`trap_core.robust.separate_groups` can only place each object's box where its
patterns are, and their mean drifts to the middle of the pair, so in a meeting each box leans
onto the other object. Before the track rules have sorted out which object is which, that is
all one can do. Afterwards, each track's path is known on both sides of the meeting, and a
short meeting (up to ``max_gap`` frames between the last box before it and the first after it)
is crossed on the straight line between them, at the placed box's size, shifted only as far as
keeps it inside the box observed there (the pair's box, which holds the object). Longer
meetings keep their placement: over many frames an object may turn inside the group.

The rules between the two steps move boxes from track to track, drop some and resize a few:
:class:`GroupBoxes` finds the observed box behind a placed box they left as it was by its frame
and its value; one they changed counts as not placed.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from trap_core.clustering import Track, box_centres


@dataclass(frozen=True)
class GroupBoxes:
    """The box observed behind each box that :func:`trap_core.robust.separate_groups` placed
    elsewhere (in a group, or at the usual size outside one), keyed by frame and the placed
    box's value."""

    observed: dict[tuple[int, bytes], np.ndarray]

    @classmethod
    def placed(cls, before: Sequence[Track], after: Sequence[Track]) -> GroupBoxes:
        """The boxes ``separate_groups`` changed: ``after`` is its output for ``before`` (same
        tracks, same order; frames it added to follow a hidden object have no observed box)."""
        observed = {}
        for seen, placed in zip(before, after):
            _, rows, seen_rows = np.intersect1d(placed.frames, seen.frames, assume_unique=True, return_indices=True)
            changed = np.any(placed.boxes[rows] != seen.boxes[seen_rows], axis=1)
            for row, seen_row in zip(rows[changed].tolist(), seen_rows[changed].tolist()):
                observed[(int(placed.frames[row]), placed.boxes[row].tobytes())] = seen.boxes[seen_row]
        return cls(observed)

    def behind(self, track: Track) -> np.ndarray:
        """(len(track), 4): the observed box behind each of the track's boxes, NaN where it
        was not placed."""
        out = np.full(track.boxes.shape, np.nan)
        for row, (frame, box) in enumerate(zip(track.frames.tolist(), track.boxes)):
            out[row] = self.observed.get((frame, box.tobytes()), np.nan)
        return out


def through_groups(track: Track, groups: GroupBoxes, max_gap: int) -> Track:
    """The track with its placed boxes moved onto the straight path between the nearest boxes
    that were not placed, at most ``max_gap`` frames apart, and kept within the observed box.

    Parameters
    ----------
    track : Track
        A track whose identity the rules have settled.
    groups : GroupBoxes
        The boxes placed in groups, and what was observed there.
    max_gap : int
        Frames between the two boxes around a meeting beyond which its boxes stay placed.

    Returns
    -------
    Track
    """
    observed = groups.behind(track)
    placed = ~np.isnan(observed[:, 0])
    free = np.flatnonzero(~placed)
    if not placed.any() or free.size < 2:
        return track
    rows = np.flatnonzero(placed)
    after = np.searchsorted(free, rows)
    inside = (after > 0) & (after < free.size)
    rows, before, after = rows[inside], free[after[inside] - 1], free[after[inside]]
    frames = track.frames
    short = frames[after] - frames[before] <= max_gap
    rows, before, after = rows[short], before[short], after[short]
    if rows.size == 0:
        return track
    share = ((frames[rows] - frames[before]) / (frames[after] - frames[before]))[:, None]
    centres = box_centres(track.boxes)
    path = (1 - share) * centres[before] + share * centres[after]
    boxes = track.boxes.copy()
    size = boxes[rows, 2:]
    seen = observed[rows]
    low, high = seen[:, :2], seen[:, :2] + seen[:, 2:] - size  # high < low: the box is larger than the observed one
    boxes[rows, :2] = np.clip(path - size / 2, np.minimum(low, high), np.maximum(low, high))
    return dataclasses.replace(track, boxes=boxes)
