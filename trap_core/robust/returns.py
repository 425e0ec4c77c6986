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
from collections.abc import Sequence

import numpy as np

from trap_core.clustering import Track, reaches_border, with_frames


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
    alike = np.asarray(alike, dtype=bool)
    leaves = reaches_border(np.array([t.boxes[-1] for t in out]).reshape(-1, 4), width, height)
    enters = reaches_border(np.array([t.boxes[0] for t in out]).reshape(-1, 4), width, height)
    ends = np.array([t.frames[-1] for t in out])
    starts = np.array([t.frames[0] for t in out])
    follows: dict[int, int] = {}  # index of a track that left -> index of the track that brings its object back
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
    for left in sorted(follows, key=lambda k: -ends[k]):  # latest first: a returned track can leave again
        later = out[follows[left]]
        out[left] = with_frames(out[left], later.frames, later.boxes, later.score, later.points)
    joined = set(follows.values())
    return [dataclasses.replace(t, track_id=i) for i, t in enumerate((t for k, t in enumerate(out) if k not in joined),
                                                                      start=1)]
