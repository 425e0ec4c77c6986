"""An object that leaves the view and comes back keeps its track (ours).

Fragments of an object cut by an exit are rejoined as clusters
(:func:`trap_core.robust.rejoin_fragments`), but only where neither has already been joined to
another fragment that overlaps the other. Where look-alikes cross, a cluster can take one
object's fragment before the crossing and the other's after it; the track rules later give each
object's stretch back to its own track (:func:`trap_core.robust.drop_shared_stretches`), and the
object that left the view is then two tracks: one that ends at the border and one that enters
later (an identical person that left twice, in quality.py "blind": 4 tracks for 3 objects).
:func:`join_returns` makes such tracks one where nothing else could have come back.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence

import numpy as np

from trap_core.clustering import Track, reaches_border, with_frames
from trap_core.robust.borders import continue_to_border


def join_returns(tracks: Sequence[Track], width: float, height: float, alike: np.ndarray) -> list[Track]:
    """Tracks where one whose object left the view is continued by the track that brings it back.

    A track leaves the view where its last box reaches the border (:func:`reaches_border`), and
    enters it where its first box does. Taken in the order they end, a track that left is
    continued by the first track that enters after its last frame and looks alike to it
    (``alike``, (T, T): :func:`trap_core.robust.lookalike_tracks`), unless another track that
    left and is not continued, alike to that one too, was out of view then: with two
    look-alikes out at once, nothing tells which came back. The earlier track keeps its id; ids
    are renumbered 1.. in order.
    """
    out = list(tracks)
    leaves, enters = _at_border(out, -1, width, height), _at_border(out, 0, width, height)
    follows = _returns(out, leaves, enters, alike)
    for left in sorted(follows, key=lambda k: -out[k].frames[-1]):  # latest first: a returned track can leave again
        later = out[follows[left]]
        out[left] = with_frames(out[left], later.frames, later.boxes, later.score, later.points)
    joined = set(follows.values())
    return [dataclasses.replace(t, track_id=i) for i, t in enumerate((t for k, t in enumerate(out) if k not in joined),
                                                                      start=1)]


def join_spare_returns(tracks: Sequence[Track], spares_after: Callable[[int, np.ndarray], Sequence[Track]],
                       alike: Callable[[Sequence[Track]], np.ndarray], width: float, height: float,
                       n_frames: int, span: int, max_frames: int) -> list[Track]:
    """Tracks whose object left the view continued, as by :func:`join_returns`, by the spare
    tracks (of clusters left out) that bring it back; spares that bring nothing back are left out.

    An object that comes back late in the video is seen for less than ``min_track_length``: its
    cluster is not selected, and where the view changed its structures (a zoom, a turn) it is not
    rejoined either. A track whose object's patterns stopped before it reached the border leaves
    too where its motion takes its whole box there within ``max_frames`` frames
    (:func:`trap_core.robust.continue_to_border` with that lead, over the last ``span`` frames);
    a track that is continued gets those boxes to the border as well. ``spares_after(frame,
    size)`` gives the spares that start after ``frame`` (the first track's exit) within ``size``
    (width, height: the largest usual size of the tracks that left) of the border (building them
    costs), and ``alike(tracks + spares)`` whether two of them may be look-alikes; only a spare
    that enters the view continues a track.
    """
    reaching = [continue_to_border(t, n_frames, width, height, span, max_frames, lead=max_frames) for t in tracks]
    left = _at_border(reaching, -1, width, height)
    if not left.any():
        return list(tracks)
    gone = [t for t, out in zip(reaching, left) if out]
    size = np.max([np.median(t.boxes[:, 2:], axis=0) for t in gone], axis=0)
    spares = list(spares_after(min(int(t.frames[-1]) for t in gone), size))
    if not spares:
        return list(tracks)
    every = reaching + spares
    leaves = np.r_[left, np.zeros(len(spares), dtype=bool)]
    enters = np.r_[np.zeros(len(tracks), dtype=bool), _at_border(spares, 0, width, height)]
    out = list(tracks)
    for slot, back in _returns(every, leaves, enters, alike(list(tracks) + spares)).items():
        spare = every[back]
        out[slot] = with_frames(reaching[slot], spare.frames, spare.boxes, spare.score, spare.points)
    return out


def _at_border(tracks: Sequence[Track], row: int, width: float, height: float) -> np.ndarray:
    """Per track: whether its box in ``row`` (0: its first, -1: its last) reaches the border
    (:func:`reaches_border`): the object enters (leaves) the view there."""
    return reaches_border(np.array([t.boxes[row] for t in tracks]).reshape(-1, 4), width, height)


def _returns(tracks: Sequence[Track], leaves: np.ndarray, enters: np.ndarray, alike: np.ndarray) -> dict[int, int]:
    """Index of each track that left the view (``leaves``) -> index of the track that brings its
    object back (``enters``), as :func:`join_returns` pairs them."""
    alike = np.asarray(alike, dtype=bool)
    ends = np.array([t.frames[-1] for t in tracks])
    starts = np.array([t.frames[0] for t in tracks])
    follows: dict[int, int] = {}
    for left in sorted(np.flatnonzero(leaves), key=lambda k: ends[k]):
        taken = set(follows.values())
        back = [k for k in np.flatnonzero(enters) if starts[k] > ends[left] and alike[left, k] and k not in taken]
        if not back:
            continue
        first = min(back, key=lambda k: starts[k])
        out_too = [k for k in np.flatnonzero(leaves) if k != left and k not in follows
                   and ends[k] < starts[first] and alike[k, first]]
        if not out_too:
            follows[left] = first
    return follows
