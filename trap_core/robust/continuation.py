"""A track cut short is continued by the cluster that goes on where it ended (ours).

Where an object passes behind a look-alike, its patterns' paths can go on with the other
object; :func:`trap_core.robust.drop_shared_stretches` then ends its track there. The object's
own patterns after the meeting often make a cluster of their own that starts where the track
ended but is too short to be selected, and overlaps the track's cluster in time too much to be
rejoined to it. :func:`continue_tracks` appends it, after the track's last frame or in a gap
between two of its pieces (where a stretch on another object was dropped from the middle); and
the same way back in time, before a track's first frame, where the object's first patterns made
such a cluster. Where the object stays behind the other for longer than its motion can be
carried on, the cluster starts later, out of the other's box, and is taken from there.

When such a cluster was long enough to be selected, the object's path after the meeting is a
track of its own, often starting on the other object (for as long as the two are in one place,
a few frames where they cross, longer where they travel together) before it follows its own:
:func:`join_handovers` makes the two tracks one. It also cuts a track at a gap after which it
jumps to a look-alike, where another track goes on with its object from there.

A track's cluster can also hold one object before such a meeting and the other after it (or the
reverse): over a stretch it repeats the other object's track, while its own object has no track.
A cluster left out that holds the track's object beside the stretch and, during it, is elsewhere
saw where that object went: :func:`mend_shared_stretches` takes its boxes for the stretch.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence

import numpy as np

from trap_core.clustering import (ClusterSummary, Track, box_centres, box_iou, box_path, centre_path, in_rows,
                                  points_in_boxes, reaches_border, with_frames)
from trap_core.robust._kernels import away_from_boxes
from trap_core.robust.duplicates import repeats_others, same_boxes, shared_stretches
from trap_core.robust.motion import straight_line

# An IoU above zero: boxes that overlap at all. Where look-alikes meet, a box placed on one of
# them can end up shifted off it, beside the other track's box rather than on it.
ANY_OVERLAP = float(np.finfo(float).tiny)
# Where clusters mend both tracks of a stretch, the track whose menders held its object this many
# times longer beside the stretch (summed, :func:`_held_beside`) is mended: look-alikes that meet
# send some clusters on with the other object, but most go on with their own.
SUPPORT_RATIO = 3.0


def continue_tracks(tracks: Sequence[Track], summary: ClusterSummary, candidates: np.ndarray, n_frames: int,
                    width: float, height: float, window: int, reach: float, build: Callable[[int], Track],
                    min_iou: float = 0.5) -> list[Track]:
    """Tracks whose pieces that end more than ``window`` frames before the track's next one (or
    the video's end) are each continued by at most one of the clusters ``candidates``; then,
    the same way back in time, pieces that start more than ``window`` frames after the track's
    previous one (or the video's start).

    A candidate continues a piece if it covers at least ``window`` frames not used up (below) after
    the piece's last one and before the next piece, the first of them at most ``window`` frames
    after it, and there its mean position is at most ``reach`` px from where the piece's motion (a
    straight line through its last ``window`` box centres) puts it, or it held the piece's object
    up to there (:func:`_held_up_to`: the object may have turned); or, where the piece's last box
    overlaps another track's (its object went behind that one, or merged with it) and that track
    stays in view, the first of them any number of frames later, at most ``reach`` px from that
    track's box centre there (a hidden object comes out of what hid it, however long that took,
    and its motion behind it is unknown). The closest one is taken, and
    its boxes (``build(cluster)``) between the two pieces are appended, except where they repeat
    another track's box (IoU at least ``min_iou``, or the centre of the smaller box lies in the
    other: boxes around an object tracked already). A candidate's frames in the gap it fills are
    used up (a cluster that hops between objects can continue one track with its early frames and
    another with its late ones), and a piece it makes is continued in turn. Where the piece's last
    box reaches the border of the ``width`` x ``height`` frames (its object is leaving), the
    candidate's first box appended must reach it too: one that starts clear of the border is
    something else the patterns found once the object was gone; and where the piece's motion
    takes it out of the view within ``window`` frames, only the candidate's boxes up to the first
    one clear of the border are appended (the object is gone after that, and the piece so made is
    not continued in turn: a chain of short continuations, each at the border, would walk into
    whatever the patterns found there once it was gone). Back in time, read
    first for last: a track whose cluster began late (its object's first patterns went to a
    cluster too short to be selected) gets that cluster's boxes before its start, unless another
    track ends within ``window`` frames before that start, within ``reach`` of where the piece's
    motion read back puts it: the object was tracked up to there (a handover, which
    :func:`join_handovers` joins), and a spare cluster before the start holds something else;
    forward the same where another track starts within ``window`` frames after the end, near the
    piece's line or its last box (:func:`_taken_on`).
    """
    out = list(tracks)
    lent = np.zeros(summary.covered.shape, dtype=bool)  # (cluster, frame) whose box went to a track
    for slot in range(len(out)):
        for backward in (False, True):
            gone: set[int] = set()  # edges of pieces beyond which the object is out of view
            grown = True
            while grown:  # a continuation makes a new piece, whose own edge may be continued in turn
                grown = False
                frames = out[slot].frames
                # (the piece's edge frame, the track's other piece or the video's end beyond the gap)
                bounds = np.r_[-1, frames] if backward else np.append(frames, n_frames)
                gaps = np.flatnonzero(np.diff(bounds) > window)
                edges = bounds[gaps + 1] if backward else bounds[gaps]
                limits = bounds[gaps] if backward else bounds[gaps + 1]
                for edge, limit in zip(edges.tolist(), limits.tolist()):
                    if edge in gone:
                        continue
                    found = _continuation(out, slot, edge, limit, summary, candidates, lent, (width, height),
                                          window, reach, build, min_iou)
                    if found is not None:
                        follow, cluster, out_of_view = found
                        out[slot] = with_frames(out[slot], follow.frames, follow.boxes, follow.score, follow.points)
                        lent[cluster, slice(limit + 1, edge) if backward else slice(edge + 1, limit)] = True
                        grown |= len(follow) > 0
                        if out_of_view and len(follow):
                            gone.add(int(follow.frames[0] if backward else follow.frames[-1]))
    return out


def _continuation(tracks: list[Track], slot: int, edge: int, limit: int, summary: ClusterSummary,
                  candidates: np.ndarray, lent: np.ndarray, view: tuple[float, float], window: int, reach: float,
                  build: Callable[[int], Track], min_iou: float) -> tuple[Track, int, bool] | None:
    """The boxes of the closest candidate that continues track ``slot``'s piece beyond its
    frame ``edge`` up to (not including) frame ``limit`` (after its last frame; before its
    first where ``limit < edge``), that candidate, and whether the piece's object is out of view
    beyond those boxes (they were cut where they leave the border); None if none continues it
    (see :func:`continue_tracks`)."""
    backward = limit < edge
    current = tracks[slot]
    line = _line_through(current, np.arange(edge, edge + window)) if backward else _motion_at(current, edge, window)
    if line is None:
        return None
    velocity, origin = line
    lo, hi = (limit + 1, edge) if backward else (edge + 1, limit)
    others = [t for k, t in enumerate(tracks) if k != slot]
    edge_box = current.boxes[current.frames == edge]
    handed = (_handed_over(others, edge, line, window, reach) if backward
              else _taken_on(others, current, edge, line, window, reach))
    if handed:
        return None
    hiding = [t for t in others if box_iou(edge_box, box_path(t, summary.covered.shape[1])[edge])[0] > 0]
    own = box_path(current, summary.covered.shape[1])  # read against every candidate
    near = []
    close: list[tuple[int, float]] = []  # candidates that go on within window frames, their error off the line
    free = summary.covered[candidates, lo:hi] & ~lent[candidates, lo:hi]  # the frames each may lend
    enough = np.count_nonzero(free, axis=1) >= window
    nearest_free = (hi - 1 - np.argmax(free[:, ::-1], axis=1)) if backward else (lo + np.argmax(free, axis=1))
    for cluster, nearest in zip(candidates[enough].tolist(), nearest_free[enough].tolist()):
        position = summary.paths.at(cluster, nearest)
        if abs(nearest - edge) <= window:
            close.append((cluster, float(np.linalg.norm(position - (origin + velocity * nearest)))))
            continue
        error = _out_from_hiding(hiding, position, edge, nearest, window)
        if error <= reach:
            near.append((error, cluster))
    held = _held_up_to(own, edge, summary, np.array([cluster for cluster, _ in close], dtype=np.int64), window,
                       backward)
    for (cluster, off_line), held_error in zip(close, held.tolist()):
        if min(off_line, held_error) <= reach:
            near.append((min(off_line, held_error), cluster))
    crossing = reaches_border(edge_box, *view)[0]
    beyond = origin + velocity * (edge - window if backward else edge + window)  # where its motion goes
    outward = crossing and not (0 <= beyond[0] <= view[0] and 0 <= beyond[1] <= view[1])
    for _, cluster in sorted(near):
        follow = build(cluster)
        follow = in_rows(follow, (follow.frames >= lo) & (follow.frames < hi))
        follow = in_rows(follow, ~lent[cluster, follow.frames])
        follow = in_rows(follow, ~repeats_others(follow, others, min_iou, centred=True))
        if crossing and not (len(follow) and reaches_border(follow.boxes[-1:] if backward else follow.boxes[:1],
                                                            *view)[0]):
            continue
        if outward:  # out of view once off the border: the boxes inside after that are something else
            at_border = reaches_border(follow.boxes, *view)
            if backward:  # the run at the border read from the end
                follow = in_rows(follow, np.logical_and.accumulate(at_border[::-1])[::-1])
            else:
                follow = in_rows(follow, np.logical_and.accumulate(at_border))
        return follow, cluster, outward
    return None


def _taken_on(others: Sequence[Track], track: Track, end: int, line: tuple[np.ndarray, np.ndarray], window: int,
              reach: float) -> bool:
    """Whether one of the ``others`` tracks starts at most ``window`` frames after ``end`` (a
    piece of ``track``'s last frame) with its first box centre at most ``reach`` px from where the
    piece's motion ``line`` puts it, or from the piece's last box centre (an object that turned as
    it met a look-alike): that track took the object on, and :func:`join_handovers` joins the
    two; a spare cluster after the end would repeat it or hold something else."""
    last = box_centres(track.boxes[track.frames == end])[0]
    for other in others:
        if end < int(other.frames[0]) <= end + window:
            first = box_centres(other.boxes[:1])[0]
            if min(_off_line(other, np.array([0]), line)[0], float(np.linalg.norm(first - last))) <= reach:
                return True
    return False


def _handed_over(others: Sequence[Track], start: int, line: tuple[np.ndarray, np.ndarray], window: int,
                 reach: float) -> bool:
    """Whether one of the ``others`` tracks ends at most ``window`` frames before ``start`` (a
    piece's first frame) with its last box centre at most ``reach`` px from where the piece's
    motion ``line``, read back, puts it: the piece's object was tracked up to there, and
    :func:`join_handovers` joins the two."""
    return any(start - window <= int(t.frames[-1]) < start and _off_line(t, np.array([-1]), line)[0] <= reach
               for t in others)


def join_handovers(tracks: Sequence[Track], n_frames: int, window: int, reach: float, min_iou: float = 0.5,
                   max_gap: int = 0) -> list[Track]:
    """Tracks where a track that ends more than ``window`` frames before the video is followed by
    another that takes its object over: the later one is appended to the earlier and dropped.

    The later track must start at most ``window`` frames after the earlier one ends (``max_gap``
    where more: an object whose regions merged with the ground for a while, or that passed behind
    another, comes back where its motion puts it; only that motion is then asked), and where it
    starts more than ``window`` frames before that end, hold an object tracked already there (its
    box overlaps another track's, :data:`ANY_OVERLAP`) until then: it began on another object and
    stayed with it while the two were in one place, or on the earlier track's own object (a second
    cluster on it that goes on where the first ends). Of its frames after that end, those where it
    repeats a third track's box (IoU at least ``min_iou``: it is still on the other object) do
    not count; it must keep at least ``window`` of them, the first at most ``window`` (or
    ``max_gap``) frames after the end, and over the first ``window`` of them be at most
    ``reach`` px (median) from where the earlier track's motion (a straight line through its
    last ``window`` box centres) puts it: where look-alikes part, its first boxes may still lie
    between the two. The closest such track is taken; its counted frames are appended.

    Where no track is that close to the motion, the one track whose first counted box is at most
    ``reach`` px from the earlier track's last box, within ``window`` frames of it, takes over:
    where the object turned as it met a look-alike, the earlier track's last boxes wander between
    the two and their line points nowhere. The earlier track then ends where its wandering
    began: of its last ``window`` frames before the later one starts, those after the last box
    within ``reach`` of the later track's line (through its first ``window`` centres, extended
    back) go. The later track's boxes (but those on a third track's object) are appended from its
    start.

    A track also ends, for this rule, before a gap where it jumps (:func:`_handover_ends`): where
    a later track takes its object over there, it is cut at the gap, continued by that track,
    and its part after the gap is a track of its own (at most as many cuts as tracks), unless the
    track so continued ends before that part starts, near its first box (:func:`_back_after_gap`).
    Not where the later track repeats a box of that part (IoU at least ``min_iou``): its object
    turned while its patterns were missed, and the track came back on it. Ids are renumbered 1..
    in order.
    """
    out = list(tracks)
    cuts_left = len(out)  # a cut adds a track that a later join may cut again: bounded
    slot = 0
    while slot < len(out):
        joined = None
        for end in _handover_ends(out[slot], window, reach, cuts_left > 0):
            before, after = in_rows(out[slot], out[slot].frames <= end), in_rows(out[slot], out[slot].frames > end)
            trial = out[:slot] + [before] + out[slot + 1:] + ([after] if len(after) else [])
            joined, taker, continued = _taken_over(trial, slot, n_frames, window, reach, min_iou, max_gap)
            if joined is not None and len(after) and repeats_others(taker, [after], min_iou).any():
                joined = None  # the track after its gap is on the object taken over: one object all along
            if joined is not None:
                if len(after):
                    cuts_left -= 1
                    joined = _back_after_gap(joined, continued, reach)
                break
        if joined is None:
            slot += 1
            continue
        out = joined
        slot = 0  # the joined track may now be followed by another
    return [dataclasses.replace(t, track_id=i) for i, t in enumerate(out, start=1)]


def _back_after_gap(tracks: list[Track], continued: int, reach: float) -> list[Track]:
    """``tracks`` whose last one, the part after the gap where a track was cut
    (:func:`join_handovers`), is appended back to that track (``continued``: where it is, now
    continued by the track that took its object over) where it now ends before that part starts
    and its last box centre is at most ``reach`` px from the part's first: the object was lost
    there for a while and came back where it had been (it turned while its patterns were
    missed), as the cluster had it."""
    track, part = tracks[continued], tracks[-1]
    if track.frames[-1] >= part.frames[0] or _centre_distance(track.boxes[-1], part.boxes[0]) > reach:
        return tracks
    out = list(tracks[:-1])
    out[continued] = with_frames(track, part.frames, part.boxes, part.score, part.points)
    return out


def _handover_ends(track: Track, window: int, reach: float, with_gaps: bool) -> list[int]:
    """Frames where :func:`join_handovers` looks for a track that takes the ``track``'s object
    over: its last frame and, ``with_gaps``, the last frame before each gap of more than
    ``window`` frames after which it jumps: its first ``window`` boxes after the gap are over
    ``reach`` px (median) from where its motion before the gap puts them, and the first over
    ``reach`` px from its last box before (a look-alike's cluster can hold one object up to the
    gap and the other after it, while a track of its own carries each object's motion on)."""
    ends = []
    gaps = np.flatnonzero(np.diff(track.frames) > window) if with_gaps else np.zeros(0, dtype=int)
    for row in gaps.tolist():
        end = int(track.frames[row])
        line = _motion_at(track, end, window)  # a gap end is over window frames before the video's end
        if line is None:
            continue
        resumed = np.arange(row + 1, min(row + 1 + window, len(track)))
        if (np.median(_off_line(track, resumed, line)) > reach
                and _centre_distance(track.boxes[row + 1], track.boxes[row]) > reach):
            ends.append(end)
    return ends + [int(track.frames[-1])]


def _taken_over(out: list[Track], slot: int, n_frames: int, window: int, reach: float, min_iou: float,
                max_gap: int) -> tuple[list[Track] | None, Track | None, int]:
    """``out`` with the track ``slot`` continued by the track that takes its object over where it
    ends, as :func:`join_handovers` tells it, and that track dropped; that track; and where the
    continued track now is in the list. None, None and -1 where none takes it over."""
    current = out[slot]
    end = int(current.frames[-1])
    line = _motion_at(current, end, window) if end < n_frames - window else None
    if line is None:
        return None, None, -1
    best, best_error, best_rows = None, reach, None
    nearby = []  # (track, its rows from its start) whose first counted box is near the last box
    latest = end + max(window, max_gap)  # where a later track's first counted frame may be at most
    for other, later in enumerate(out):
        if other == slot or int(later.frames[0]) > latest:
            continue
        thirds = [t for k, t in enumerate(out) if k not in (slot, other)]
        on_known = repeats_others(later, [t for k, t in enumerate(out) if k != other], ANY_OVERLAP)
        if np.any(~on_known & (later.frames < end - window)):
            continue
        own = ~repeats_others(later, thirds, min_iou)
        rows = (later.frames > end) & own
        after = np.flatnonzero(rows)
        if after.size < window or later.frames[after[0]] > latest:
            continue
        error = float(np.median(_off_line(later, after[:window], line)))
        if error <= best_error:
            best, best_error, best_rows = other, error, rows
        elif (later.frames[after[0]] <= end + window
              and _centre_distance(later.boxes[after[0]], current.boxes[-1]) <= reach):
            nearby.append((other, own))
    if best is None and len(nearby) == 1:
        best, best_rows = nearby[0]
        current = in_rows(current, current.frames < _wandering_from(current, in_rows(out[best], best_rows),
                                                                     window, reach))
    if best is None:
        return None, None, -1
    follow = in_rows(out[best], best_rows)
    joined = list(out)
    joined[slot] = with_frames(current, follow.frames, follow.boxes, follow.score, follow.points)
    del joined[best]
    return joined, out[best], slot - int(best < slot)


def mend_shared_stretches(tracks: Sequence[Track], summary: ClusterSummary, candidates: np.ndarray, n_frames: int,
                          min_frames: int, build: Callable[[Sequence[int]], list[Track]], min_iou: float = 0.5,
                          min_inside: float = 0.9, min_share: float = 0.8, window: int = 12) -> list[Track]:
    """Tracks whose stretch on another track's object is replaced by the boxes of a cluster of
    ``candidates`` that held their own object meanwhile.

    A stretch is shared by two tracks as in :func:`trap_core.robust.drop_shared_stretches` (boxes
    matching for at least ``min_frames`` frames). A candidate mends one of the two tracks if,
    in the ``min_frames`` frames before or after the stretch, it holds that track's object (in
    ``min_share`` of at least half of them where the track has a box, the test of
    :func:`trap_core.robust.merge_duplicates`: IoU at least ``min_iou``, or one box at least
    ``min_inside`` inside the other, as where the candidate's box takes in a look-alike still
    touching the object; its boxes from ``build``, which gives the tracks of several clusters at
    once), and in the stretch it has boxes that repeat no track's in at least
    half its frames: the object was elsewhere, where nothing tracked it. The track's boxes in
    the stretch are replaced by those, and the other track keeps the stretch. Where candidates mend both
    tracks, the one whose menders held its object beside the stretch ``SUPPORT_RATIO`` times longer
    (frames summed over them, :func:`_held_beside`) is mended, if one of them goes on where the
    track's motion puts its object (within the median side of its boxes, :func:`_motion_error`
    over ``window`` frames), and otherwise neither: where look-alikes touch, some of their
    clusters go on with the other object, but most go on with their own, as it moved.
    """
    out = list(tracks)
    boxes = np.array([box_path(t, n_frames) for t in out]).reshape(len(out), n_frames, 4)
    built: dict[int, tuple[Track, np.ndarray]] = {}  # per candidate: its track, its box per frame

    def boxes_of(clusters: list[int]) -> list[np.ndarray]:
        missing = [cluster for cluster in clusters if cluster not in built]
        for cluster, track in zip(missing, build(missing)):
            built[cluster] = (track, box_path(track, n_frames))
        return [built[cluster][1] for cluster in clusters]

    for a in range(len(out)):
        for b in range(a + 1, len(out)):
            for start, end in shared_stretches(boxes[a], boxes[b], min_frames, min_iou, min_inside):
                menders = {slot: _menders(boxes, slot, (start, end), summary, candidates, min_frames, boxes_of,
                                          (min_iou, min_inside, min_share)) for slot in (a, b)}
                if not (menders[a] or menders[b]):
                    continue
                slot = a if menders[a] else b
                if menders[a] and menders[b]:  # the weightier menders, if they go on as the object moved
                    held = {slot: sum(_held_beside(boxes[slot], (start, end), summary, cluster)
                                      for cluster in menders[slot]) for slot in (a, b)}
                    if max(held.values()) < SUPPORT_RATIO * min(held.values()):
                        continue
                    slot = a if held[a] > held[b] else b
                    if (_motion_error(out[slot], (start, end), summary, menders[slot], window)
                            > np.median(out[slot].boxes[:, 2:4])):
                        continue
                cluster, frames = max(menders[slot].items(), key=lambda item: item[1].size)
                lent = in_rows(built[cluster][0], np.isin(built[cluster][0].frames, frames))
                kept = in_rows(out[slot], (out[slot].frames < start) | (out[slot].frames > end))
                out[slot] = with_frames(kept, lent.frames, lent.boxes, lent.score, lent.points)
                boxes[slot, start:end + 1] = np.nan
                boxes[slot, lent.frames] = lent.boxes
    return out


def _menders(boxes: np.ndarray, slot: int, stretch_ends: tuple[int, int], summary: ClusterSummary,
             candidates: np.ndarray, window: int, boxes_of: Callable[[list[int]], list[np.ndarray]],
             thresholds: tuple[float, float, float]) -> dict[int, np.ndarray]:
    """The candidates that mend track ``slot``'s stretch (first and last frame ``stretch_ends``)
    given the ``window`` frames beside it and ``thresholds`` ``min_iou, min_inside, min_share``
    (see :func:`mend_shared_stretches`), each with the stretch frames it lends. The tests on
    the candidates' mean positions come first, for all of them (the first, in the stretch, in one
    compiled pass: :func:`away_from_boxes`): only those that pass have their boxes built
    (``boxes_of``, per video frame), all at once."""
    start, end = stretch_ends
    min_iou, min_inside, min_share = thresholds
    n_frames = boxes.shape[1]
    stretch = np.arange(start, end + 1)
    own = boxes[slot]
    seen = np.flatnonzero(~np.isnan(own[:, 0]))
    sides = (seen[seen < start][::-1], seen[seen > end])  # nearest the stretch first
    others = np.delete(boxes, slot, axis=0)
    near: dict[int, list[np.ndarray]] = {}  # per candidate that passes: its frames beside the stretch
    paths = summary.paths
    elsewhere = away_from_boxes(candidates.astype(np.int64), start, end, summary.covered, paths.start, paths.offsets,
                                paths.points, others)
    for cluster in candidates[elsewhere].tolist():
        beside = [common for common in (side[summary.covered[cluster, side]] for side in sides)
                  if common.size >= window / 2 and min(abs(common[0] - start), abs(common[0] - end)) <= window]
        beside = [common for common in beside  # its patterns' mean position in the track's box
                  if np.mean(points_in_boxes(summary.paths.at(cluster, common), own[common])) >= min_share]
        if beside:
            near[cluster] = beside
    menders = {}
    for (cluster, beside), lent in zip(near.items(), boxes_of(list(near))):
        if not any(np.mean(same_boxes(lent[common], own[common], min_iou, min_inside)) >= min_share
                   for common in beside):
            continue
        inside = stretch[~np.isnan(lent[stretch, 0])]
        inside = inside[~np.any(box_iou(lent[inside][None], others[:, inside]) >= min_iou, axis=0)]
        if inside.size >= stretch.size / 2:
            menders[cluster] = inside
    return menders


def _held_beside(own: np.ndarray, stretch_ends: tuple[int, int], summary: ClusterSummary, cluster: int) -> int:
    """Frames outside the stretch (first and last frame ``stretch_ends``) where ``cluster``'s mean
    position lies in the track's box (``own``, one per video frame, NaN where none): how long the
    cluster held the track's object, the weight of its word on where that object went."""
    start, end = stretch_ends
    frames = np.flatnonzero(summary.covered[cluster])
    frames = frames[(frames < start) | (frames > end)]
    return int(np.count_nonzero(points_in_boxes(summary.paths.at(cluster, frames), own[frames])))


def _held_up_to(own: np.ndarray, edge: int, summary: ClusterSummary, clusters: np.ndarray, window: int,
                backward: bool) -> np.ndarray:
    """Per cluster of ``clusters``: the median distance from its mean positions to the track's box
    centres over the piece's last ``window`` frames up to its ``edge`` (first, back in time;
    ``own``: the track's box in each video frame, NaN where none), where the cluster held the
    piece's object: seen in at least half of those frames, each time inside the track's box; inf
    where it did not. Such a cluster goes on with the object past the edge wherever it turns (the
    piece's straight line would lose it there). The frames seen, and whether the positions there
    lie in the boxes, are read for all of them at once."""
    length = summary.covered.shape[1]
    frames = np.arange(edge, min(edge + window, length)) if backward else np.arange(max(edge - window + 1, 0), edge + 1)
    boxes = own[frames]
    seen = summary.covered[np.ix_(clusters, frames)] & ~np.isnan(boxes[:, 0])
    points = summary.paths.dense(clusters, frames)  # a cluster is seen only within its span
    inside = points_in_boxes(points, boxes[None]) | ~seen
    out = np.full(clusters.size, np.inf)
    for row in np.flatnonzero((np.count_nonzero(seen, axis=1) >= window / 2) & inside.all(axis=1)):
        out[row] = np.median(np.linalg.norm(points[row, seen[row]] - box_centres(boxes[seen[row]]), axis=1))
    return out


def _motion_error(track: Track, stretch_ends: tuple[int, int], summary: ClusterSummary,
                  menders: dict[int, np.ndarray], window: int) -> float:
    """Least, over the ``menders`` (each with the stretch frames it lends), of the median distance
    from its positions in the first (last) ``window`` of those frames to where the track's motion
    before the stretch (after it, read back: a straight line through its ``window`` box centres
    beside it) puts them; inf where the track has no such motion on either side."""
    start, end = stretch_ends
    lines = []  # (velocity and origin of a motion beside the stretch, the lent frames it predicts)
    if start > track.frames[0]:
        lines.append((_motion_at(track, start - 1, window), slice(None, window)))
    if end < track.frames[-1]:
        lines.append((_line_through(track, np.arange(end + 1, end + 1 + window)), slice(-window, None)))
    errors = [np.inf]
    for cluster, frames in menders.items():
        for (velocity, origin), near in ((line, near) for line, near in lines if line is not None):
            lent = frames[near]
            errors.append(float(np.median(np.linalg.norm(summary.paths.at(cluster, lent)
                                                         - (origin + velocity * lent[:, None]), axis=1))))
    return min(errors)


def _wandering_from(ending: Track, later: Track, window: int, reach: float) -> int:
    """First frame of the ``ending`` track's wandering tail before ``later`` starts: the frames
    (at most ``window`` of them) just before that start whose box centres lie more than ``reach``
    px from the straight line through the later track's first ``window`` centres, extended back."""
    start = int(later.frames[0])
    line = _line_through(later, np.arange(start, start + window))
    if line is None:
        return start
    before = np.flatnonzero((ending.frames < start) & (ending.frames >= start - window))[::-1]
    off = _off_line(ending, before, line) > reach
    kept = np.flatnonzero(~off)  # the first box (going back) near the line ends the tail
    tail = before[:kept[0]] if kept.size else before
    return int(ending.frames[tail[-1]]) if tail.size else start


def _out_from_hiding(hiding: Sequence[Track], position: np.ndarray, edge: int, nearest: int, window: int) -> float:
    """Distance from ``position`` (a candidate's, in frame ``nearest``) to the nearest box centre
    there of the tracks ``hiding`` a piece at its ``edge`` frame (their boxes overlapped) that
    stayed in view all along (no gap over ``window`` frames between the two frames): an object
    hidden behind another, or merged with it, comes out of it however long it stayed there; inf
    where none."""
    first, last = min(edge, nearest), max(edge, nearest)
    distances = [np.inf]
    for track in hiding:
        frames = track.frames[(track.frames >= first) & (track.frames <= last)]
        in_view = (frames.size > 0 and frames[0] - first <= window and last - frames[-1] <= window
                   and np.diff(frames).max(initial=0) <= window)
        if in_view and nearest in frames:
            centre = box_centres(track.boxes[np.searchsorted(track.frames, nearest)][None])[0]
            distances.append(float(np.linalg.norm(position - centre)))
    return min(distances)


def _centre_distance(box: np.ndarray, other: np.ndarray) -> float:
    """Distance between the centres of two boxes ``(x, y, w, h)``."""
    return float(np.linalg.norm(box_centres(box) - box_centres(other)))


def _off_line(track: Track, rows: np.ndarray, line: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
    """Per row of ``rows``: how far the track's box centre lies from where the straight ``line``
    (velocity, origin: :func:`_line_through`) puts it in that row's frame."""
    velocity, origin = line
    return np.linalg.norm(box_centres(track.boxes[rows]) - (origin + velocity * track.frames[rows][:, None]), axis=1)


def _motion_at(track: Track, end: int, window: int) -> tuple[np.ndarray, np.ndarray] | None:
    """:func:`_line_through` the track's box centres in the ``window`` frames up to ``end``."""
    return _line_through(track, np.arange(max(end + 1 - window, 0), end + 1))


def _line_through(track: Track, frames: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """Velocity and origin of the straight line through the track's box centres in ``frames``
    (increasing; those without a box are skipped: :func:`straight_line`), None where too few."""
    return straight_line(centre_path(track, max(int(track.frames[-1]), int(frames[-1])) + 1), frames)
