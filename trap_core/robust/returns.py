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

from trap_core.clustering import (ClusterSummary, Track, box_path, in_rows, points_in_boxes, reaches_border,
                                  with_frames)
from trap_core.robust.borders import continue_to_border
from trap_core.robust.duplicates import repeats_others


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
    size)`` gives the spares' parts that may bring an object back after ``frame`` (the first
    track's exit), near the border by ``size`` (width, height: the largest usual size of the
    tracks that left; :func:`spare_entries`, :func:`entering_part`), and ``alike(tracks +
    spares)`` whether two of them may be look-alikes; only a spare that enters the view
    continues a track.
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


def spare_entries(summary: ClusterSummary, spare: np.ndarray, tracks: Sequence[Track], frame: int, size: np.ndarray,
                  width: float, height: float, min_frames: int) -> dict[int, int]:
    """Spare clusters that may bring back an object that left the view at ``frame``, each with
    the frame from which it may: its first frame after the exit where its mean position lies on
    no track's box, within twice ``size`` (width, height) of the border, with at least
    ``min_frames`` such frames from there on.

    A cluster that started after the exit is read from its start; one that hopped between
    look-alikes all along can go on with the object's return, read from where it is off the
    tracked objects at the border. A box that reaches the border is centred within 3/4 of its
    size of it, and the patterns' mean can be off the centre by half of it (a part); twice the
    size leaves room for a zoom. Building a cluster's track costs: only these are built.
    """
    frames = np.arange(frame + 1, summary.covered.shape[1])
    if not (spare.size and frames.size):
        return {}
    points = summary.paths.dense(spare, frames)
    free = summary.covered[spare, frame + 1:] & ~_on_tracks(points, tracks, frame + 1)
    x, y = np.moveaxis(points, -1, 0)
    near = (np.minimum(x, width - x) <= 2 * size[0]) | (np.minimum(y, height - y) <= 2 * size[1])
    ahead = np.cumsum(free[:, ::-1], axis=1)[:, ::-1]  # free frames from each frame on
    entry = free & near & (ahead >= min_frames)
    found = entry.any(axis=1)
    if not found.any():
        return {}
    return dict(zip(spare[found].tolist(), (frame + 1 + np.argmax(entry[found], axis=1)).tolist()))


def entering_part(spare: Track, start: int, tracks: Sequence[Track], width: float, height: float) -> Track:
    """The ``spare`` track's frames from ``start`` on that repeat no track's box (it holds a
    tracked object there), from the first whose box reaches the border: where it may be an
    object coming into the view. Empty if none, or if those frames are under half of the ones
    they span (sparse sightings: a chain of background at the border)."""
    own = (spare.frames >= start) & ~repeats_others(spare, tracks, 0.5, centred=True)
    entering = np.flatnonzero(own & reaches_border(spare.boxes, width, height))
    own[:entering[0] if entering.size else len(spare)] = False
    frames = spare.frames[own]
    sparse = frames.size == 0 or frames.size < (frames[-1] - frames[0] + 1) / 2
    return in_rows(spare, np.zeros_like(own) if sparse else own)


def _on_tracks(points: np.ndarray, tracks: Sequence[Track], start: int) -> np.ndarray:
    """(clusters, frames) whether each of the clusters' mean ``points`` (clusters, frames from
    ``start``, 2) lies in one of the ``tracks``' boxes there (it holds a tracked object)."""
    on = np.zeros(points.shape[:2], dtype=bool)
    for track in tracks:
        box = box_path(track, start + points.shape[1])[start:]
        on |= points_in_boxes(points, box)
    return on
