"""One object keeps its size from one piece of its track to the next (ours).

Rejoining and selection can chain pieces of background into one track: large regions that seem
to move while the camera turns, one stretch after another, each of its own size. The pieces of
an object's track, apart where it was occluded or out of view, keep its size, up to the camera's
zoom and the object's own approach, or shrink to a part of it while the rest of it blends into
the background (a brown disc over brown tissue keeps only its inner rectangles apart).
:func:`keep_one_size` keeps, of a track whose pieces differ in box area by more than a factor,
only the pieces of the sizes it holds long enough for a track.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from trap_core.clustering import Track, in_rows, track_pieces


def keep_one_size(tracks: Sequence[Track], min_gap: int, min_frames: int, factor: float = 4.0) -> list[Track]:
    """Tracks whose pieces keep one size; ids are renumbered 1.. in order.

    Parameters
    ----------
    tracks : sequence of Track
    min_gap : int
        A piece is a run of a track's frames without a gap of more than this many frames.
    min_frames : int
        A track left with fewer frames is dropped: too short to be a track.
    factor : float
        Where the largest piece's median box area exceeds the smallest's by more than this, the
        track keeps only the pieces whose area is within the square root of it (twice the side
        for a factor 4) of a piece whose such pieces hold at least ``min_frames`` frames: a size
        held that long is a track's worth of one object (its whole, or a part of it where the
        rest blends into the background), while a chain of background regions holds each size
        only for a while.

    Returns
    -------
    list of Track
    """
    out = []
    for track in tracks:
        pieces = track_pieces(track.frames, min_gap)
        areas = np.array([np.median(track.boxes[rows, 2] * track.boxes[rows, 3]) for rows in pieces])
        if areas.max() <= factor * areas.min():
            out.append(track)
            continue
        alike = np.abs(np.log(areas[:, None] / areas[None, :])) <= 0.5 * np.log(factor)
        held = alike @ np.array([len(rows) for rows in pieces])
        kept = alike[held >= min_frames].any(axis=0)
        if kept.any():
            out.append(in_rows(track, np.concatenate([pieces[k] for k in np.flatnonzero(kept)])))
    return [dataclasses.replace(t, track_id=i) for i, t in enumerate(out, start=1)]
