"""One track per object: tracks that hold the same object at the same time are merged (ours).

The lifetime cut can leave one object's patterns in two clusters that overlap in time (with
noisy regions each holds a different subset of its structures, and each may have been
rejoined to another fragment of the object). Both are then selected and the object gets two
tracks with the same box, one of them a false positive in every frame they share. Two tracks
are taken for one object when, over at least ``min_common`` frames both cover, their boxes
match in at least ``min_share`` of those frames: IoU at least ``min_iou``, or the smaller box
at least ``min_inside`` inside the other (a fragment on part of the object, rejoined to a later
fragment of it, makes a track that holds part of the object where it overlaps the object's other
track). Over *all* the frames they share, not only some: look-alikes that travel overlapped for
a while and then part keep their own tracks.

A track can also end up on another track's object: where look-alikes cross, a pattern's path can
go on with the other object, and its track then repeats that object's boxes for a while: to its
end, or until the path comes back to its own object. :func:`drop_shared_stretches` takes such a
stretch away from the track whose motion turns where the two meet or part (the other went on as
it was going).

An object's track can lack frames that another cluster of the same object holds (its return,
rejoined to that cluster only): :func:`extend_from_twins` lends them. Where the object's body
blends with the ground, two of its parts can each have a track whose boxes never match:
:func:`merge_parts` joins those that lie close and move as one.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence

import numpy as np

from trap_core.clustering import (Track, box_centres, box_containment, box_iou, box_path, centre_inside, in_rows,
                                  reaches_border, seen_rows, track_pieces, usual_box, with_frames)

TURN = 0.1  # a velocity change of this share of the box size per frame is a turn, not jitter
HOLE = 3  # frames in a row where jitter may part two boxes that hold the same object
# Two parts of one object: boxes at most this share of their joint box's larger side apart (a
# frame between them that blends with the ground can stand a third of it) ...
PART_GAP = 0.35
# ... whose centres' offset stays within this share of it of its median (they move as one) ...
PART_SHIFT = 0.15
# ... and whose joint box's larger and smaller sides are no larger than the largest of the tracks'
# usual larger and smaller sides by more than this share (two whole objects side by side make a box
# twice one's size; sides, not width and height, as a wide object and a tall one are both objects).
PART_FIT = 0.1


def merge_duplicates(tracks: Sequence[Track], min_common: int, min_iou: float = 0.5, min_inside: float = 0.9,
                     min_share: float = 0.8) -> list[Track]:
    """Tracks with duplicates merged: each group keeps its longest track's boxes and id order,
    and takes the others' frames where it has none. Ids are renumbered 1.. in order."""
    return _merged(tracks, lambda kept, other: _union(kept, other)
                   if _same_object(kept, other, min_common, min_iou, min_inside, min_share) else None)


def merge_parts(tracks: Sequence[Track], min_common: int, min_share: float = 0.8) -> list[Track]:
    """Tracks that hold two parts of one object merged, their boxes joined (ours).

    Where an object's body is one region with the ground around it, its parts that stand apart
    (a person's arms, a car's windows) can each be a cluster of its own, farther apart than
    ``separation`` and each on too little of the object to match the other's box. What tells
    them from two objects side by side is that they move as one for as long as they are both
    seen: in at least ``min_share`` of the frames both cover (at least ``min_common``, and
    ``min_share`` of the shorter track's), their boxes are close (:data:`PART_GAP`), the offset
    between their centres stays put (:data:`PART_SHIFT`), and the box that holds both is of an
    object's size (:data:`PART_FIT`). Those frames are the ones where both tracks' patterns are
    seen, if at least ``min_common``: a box inferred through a gap is a straight line between
    the boxes beside it, and where the object turned there it says nothing of how the two parts
    move. The longer track keeps its id and takes the joint box where both are seen and the
    other's box where only that one is. Ids are renumbered 1.. in order."""
    if len(tracks) < 2:
        return list(tracks)
    largest = np.max([_sides(usual_box(t)) for t in tracks if len(t)], axis=0)
    return _merged(tracks, lambda kept, other: _joined_parts(kept, other, min_common, min_share, largest))


def _merged(tracks: Sequence[Track], join: Callable[[Track, Track], Track | None]) -> list[Track]:
    """Tracks, longest first, each joined to the first track kept so far that ``join`` takes it
    into (the joined track; None where it does not), or kept. Ids are renumbered 1.. in the
    order of the kept tracks' ids."""
    merged: list[Track] = []
    for candidate in sorted(tracks, key=len, reverse=True):
        for k, kept in enumerate(merged):
            joined = join(kept, candidate)
            if joined is not None:
                merged[k] = joined
                break
        else:
            merged.append(candidate)
    merged.sort(key=lambda t: t.track_id)
    return [dataclasses.replace(t, track_id=i) for i, t in enumerate(merged, start=1)]


def _joined_parts(kept: Track, other: Track, min_common: int, min_share: float, largest: np.ndarray) -> Track | None:
    """``kept`` with the joint boxes of the two where both are seen and ``other``'s frames it
    lacks, if the two hold parts of one object (:func:`merge_parts`); None if not."""
    common, in_kept, in_other = np.intersect1d(kept.frames, other.frames, assume_unique=True, return_indices=True)
    if common.size < max(min_common, min_share * min(len(kept), len(other))):
        return None
    seen = seen_rows(kept)[in_kept] & seen_rows(other)[in_other]
    judged = seen if np.count_nonzero(seen) >= min_common else np.ones(common.size, dtype=bool)
    a, b = kept.boxes[in_kept], other.boxes[in_other]
    a_end, b_end = a[:, :2] + a[:, 2:4], b[:, :2] + b[:, 2:4]
    low, high = np.minimum(a[:, :2], b[:, :2]), np.maximum(a_end, b_end)
    joint_size = np.median((high - low)[judged], axis=0)
    if np.any(_sides(joint_size) > (1 + PART_FIT) * largest):
        return None
    side = joint_size.max()
    gap = np.max(np.maximum(a[:, :2], b[:, :2]) - np.minimum(a_end, b_end), axis=1)
    offset = box_centres(b) - box_centres(a)
    shift = np.linalg.norm(offset - np.median(offset[judged], axis=0), axis=1)
    if np.mean(((gap <= PART_GAP * side) & (shift <= PART_SHIFT * side))[judged]) < min_share:
        return None
    boxes = kept.boxes.copy()
    boxes[in_kept] = np.column_stack([low, high - low])
    return _union(dataclasses.replace(kept, boxes=boxes), other)


def _sides(size: np.ndarray) -> np.ndarray:
    """(2,) a box's (width, height) ``size`` as (larger side, smaller side)."""
    return np.sort(size)[::-1]


def extend_from_twins(tracks: Sequence[Track], twins: Sequence[Track], min_common: int, size_jump: float,
                      min_iou: float = 0.5, min_inside: float = 0.9, min_share: float = 0.8,
                      view: tuple[float, float] | None = None) -> list[Track]:
    """Tracks with frames they lack taken from twin tracks (those of
    :func:`trap_core.clustering.twin_clusters`).

    A twin lends frames to the one track it holds the same object as (the test of
    :func:`merge_duplicates`), and only frames where that track has no box, where its box is
    at most ``size_jump`` times the track's usual width and height (0: any size; a twin on two
    look-alikes moving together has the pair's box) and where it does not repeat another
    track's box (IoU at least ``min_iou``: a twin that followed a look-alike for a while).
    With the ``view``'s width and height, an object that left it comes back at its border: in a
    gap after a track's box at the border, a twin lends nothing before its first box there, nor,
    from there on, a box whose centre (or the other's, for the smaller) lies in another track's
    box: having followed the object out, it holds another object; and in a gap before a box at
    the border, nothing after its last (:func:`_back_through_border`).
    """
    out = list(tracks)
    for twin in twins:
        same = [k for k, t in enumerate(out) if _same_object(t, twin, min_common, min_iou, min_inside, min_share)]
        if len(same) != 1:
            continue
        kept = out[same[0]]
        lend = ~np.isin(twin.frames, kept.frames)
        if size_jump:
            lend &= np.all(twin.boxes[:, 2:4] <= size_jump * usual_box(kept), axis=1)
        others = [t for k, t in enumerate(out) if k != same[0]]
        lend &= ~repeats_others(twin, others, min_iou)
        if view is not None:
            fine, gone = _back_through_border(kept, twin, view)
            lend &= fine & ~(gone & repeats_others(twin, others, min_iou, centred=True))
        out[same[0]] = _union(kept, in_rows(twin, lend))
    return out


def _back_through_border(kept: Track, twin: Track, view: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    """Per frame of ``twin``: whether it may hold ``kept``'s object as far as the border goes,
    and whether it follows that object out of the view. In a gap of ``kept`` that follows a box
    at the border (the object left the view), no frame before the twin's first box at the border
    there, and the frames from that box on follow the object out; in a gap that precedes such a
    box (it came in), no frame after the twin's last box at the border."""
    fine = np.ones(len(twin), dtype=bool)
    gone = np.zeros(len(twin), dtype=bool)
    own_border = reaches_border(kept.boxes, *view)
    twin_border = reaches_border(twin.boxes, *view)
    slot = np.searchsorted(kept.frames, twin.frames)  # the kept frames before a twin frame: slot - 1
    starts = np.r_[0, np.flatnonzero(np.diff(slot)) + 1]  # each gap's twin rows are a run (frames increase)
    stops = np.r_[starts[1:], slot.size]
    gaps = slot[starts]
    by_border = np.r_[False, own_border][gaps] | np.r_[own_border, False][gaps]  # after or before such a box
    for start, stop, gap in zip(starts[by_border].tolist(), stops[by_border].tolist(), gaps[by_border].tolist()):
        rows = np.arange(start, stop)
        at_border = rows[twin_border[rows]]
        if gap > 0 and own_border[gap - 1]:
            out_from = at_border[0] if at_border.size else rows[-1] + 1
            fine[rows[rows < out_from]] = False
            gone[rows[rows >= out_from]] = True
        if gap < len(kept) and own_border[gap]:
            fine[rows[rows > (at_border[-1] if at_border.size else rows[0] - 1)]] = False
    return fine, gone


def repeats_others(track: Track, others: Sequence[Track], min_iou: float, min_inside: float | None = None,
                   centred: bool = False) -> np.ndarray:
    """Per frame of ``track``: whether its box repeats one of ``others``' there (IoU at least
    ``min_iou``; with ``min_inside``, or the test of :func:`same_boxes`; ``centred``, or the
    centre of the smaller box lies in the other: :func:`trap_core.clustering.centre_inside`)."""
    repeated = np.zeros(len(track), dtype=bool)
    for other in others:
        _, mine, theirs = np.intersect1d(track.frames, other.frames, assume_unique=True, return_indices=True)
        boxes, other_boxes = track.boxes[mine], other.boxes[theirs]
        same = (box_iou(boxes, other_boxes) >= min_iou if min_inside is None
                else same_boxes(boxes, other_boxes, min_iou, min_inside))
        if centred:
            same |= centre_inside(boxes, other_boxes)
        repeated[mine[same]] = True
    return repeated


def _same_object(a: Track, b: Track, min_common: int, min_iou: float, min_inside: float, min_share: float) -> bool:
    common, in_a, in_b = np.intersect1d(a.frames, b.frames, assume_unique=True, return_indices=True)
    if common.size < min_common:
        return False
    return float(np.mean(same_boxes(a.boxes[in_a], b.boxes[in_b], min_iou, min_inside))) >= min_share


def same_boxes(boxes: np.ndarray, other: np.ndarray, min_iou: float, min_inside: float) -> np.ndarray:
    """Per box: whether the two hold the same object, IoU at least ``min_iou`` or the smaller at
    least ``min_inside`` inside the other (a box on part of it, or one on it and a look-alike
    it touches); False where either is NaN."""
    return (box_iou(boxes, other) >= min_iou) | (box_containment(boxes, other) >= min_inside)


def _union(kept: Track, other: Track) -> Track:
    """``kept`` with ``other``'s frames that it does not cover."""
    extra = ~np.isin(other.frames, kept.frames)
    return with_frames(kept, other.frames[extra], other.boxes[extra], other.score[extra],
                       None if other.points is None else other.points[extra])


def drop_shared_stretches(tracks: Sequence[Track], n_frames: int, min_frames: int, window: int,
                          min_iou: float = 0.5) -> list[Track]:
    """Tracks without stretches that repeat another track's boxes; tracks left empty are dropped.

    A stretch is shared when two tracks' boxes match (IoU at least ``min_iou``, or one inside the
    other: :func:`shared_stretches`) in every frame of it but up to ``HOLE`` frames at a time
    (box jitter), for at least ``min_frames`` frames. It begins where a track's box is first
    inside the other's, not where the two first match: an object passing behind another leaves
    a part of itself in view, and by the time the boxes match its track already moves with the
    other, so its turn would be missed.
    A track loses it if its motion turns where the stretch begins or where it ends (not at the
    track's own first or last frame): the mean velocity of its box centre over ``window``
    frames after differs from the one over ``window`` frames before by more than the other
    track's does, and by more than ``TURN`` times its box size per frame. Look-alikes that go
    on together, or travel together and part, keep both tracks: neither turns. The frames on
    either side of a stretch so lost where the track's box was inferred, not seen, up to the
    stretch go with it: a gap filled towards the stretch is a line drawn from its object to the
    other, and the track's motion at its new end would be read from it.
    """
    out = list(tracks)
    boxes = np.array([box_path(t, n_frames) for t in out]).reshape(len(out), n_frames, 4)
    for a in range(len(out)):
        for b in range(len(out)):
            if a == b or len(out[a]) == 0:
                continue
            first, last = int(out[a].frames[0]), int(out[a].frames[-1])
            least = TURN * float(np.nanmedian(boxes[a, :, 2:4]))
            for start, end in shared_stretches(boxes[a], boxes[b], min_frames, min_iou):
                ends = [at for at, inside in ((start, start > first), (end + 1, end < last)) if inside]
                if any(_turns(boxes[a], boxes[b], at, window, least) for at in ends):
                    lost = _filled_up_to(out[a], start, end)
                    boxes[a, out[a].frames[lost]] = np.nan
                    out[a] = in_rows(out[a], ~lost)
    return [t for t in out if len(t)]


def drop_repeated_pieces(tracks: Sequence[Track], min_gap: int, min_iou: float = 0.5, min_inside: float = 0.9,
                         min_share: float = 0.8, min_frames: int = 0) -> list[Track]:
    """Tracks without pieces that repeat other tracks' boxes; tracks left empty are dropped.

    A piece is a run of a track's frames without a gap of more than ``min_gap`` frames, nor a
    jump of its box by more than its size from one box to the next (where a box borrowed for a
    stretch, :func:`trap_core.robust.mend_shared_stretches`, meets the track's own). Where a
    piece's boxes hold another track's object (:func:`same_boxes`, or the centre of the smaller
    box lies in the other: a piece on part of it, or off it by less than half a size) in at
    least ``min_share`` of its frames, its object is tracked already there: a path that went on
    with a look-alike and came back with it after a gap, which no turn shows
    (:func:`drop_shared_stretches` needs the track's motion on both sides). Runs of up to
    ``HOLE`` frames where jitter parts the boxes count as held, as in a shared stretch: a track
    that held one object and then, with no jump, another (two objects it went along with, each
    tracked) was kept at 78 % of its frames held. Once every track's pieces are judged, a piece
    that does not repeat others as a whole is judged again in parts, cut at its runs of more than
    ``min_gap`` frames where its patterns are not seen (boxes inferred, :attr:`Track.points`
    NaN): a track whose object turned can go on in a straight line through nothing onto a
    look-alike's track, and a part on it goes together with the unseen run that led there. Tracks
    are taken in order, each against the others as left. A dropped piece spanning ``min_frames``
    frames or more (0: none) that held the whole of an object another track holds a part of gives
    that track its boxes (:func:`_lend_whole`). Last, a track that ends while another goes on
    loses the tail of its last piece that repeats those others (:func:`_repeating_tail`): two
    look-alikes met, and it went on with the other's object until its patterns ran out there,
    which a judge of the whole piece, mostly on its own object, lets stand; cut back to its own
    object, it can be joined to the track that took that over (a handover).
    """
    out = list(tracks)
    for in_parts in (False, True):  # parts once whole pieces are gone: a piece to go may repeat a part to stay
        for slot, track in enumerate(out):
            repeated = repeats_others(track, out[:slot] + out[slot + 1:], min_iou, min_inside, centred=True)
            keep = np.ones(len(track), dtype=bool)
            for piece in track_pieces(track.frames, min_gap, track.boxes):
                for rows, seen in _repeating_rows(track, piece, repeated, min_gap, min_share, in_parts):
                    keep[rows] = False
                    if seen and min_frames and track.frames[rows[-1]] - track.frames[rows[0]] >= min_frames:
                        _lend_whole(out, slot, rows)
            out[slot] = in_rows(track, keep)
        out = [t for t in out if len(t)]
    for slot, track in enumerate(out):
        later = [t for k, t in enumerate(out) if k != slot and len(t) and t.frames[-1] > track.frames[-1]]
        if later:
            repeated = repeats_others(track, later, min_iou, min_inside, centred=True)
            out[slot] = in_rows(track, np.arange(len(track)) < _repeating_tail(track, repeated, min_gap, min_share))
    return [t for t in out if len(t)]


def _repeating_tail(track: Track, repeated: np.ndarray, min_gap: int, min_share: float) -> int:
    """The first row of the longest tail of ``track``'s last piece (at least ``2 * min_gap``
    frames, from a repeated frame on) that repeats other tracks' boxes (``repeated``, per row, as
    :func:`_repeats` counts them) in ``min_share`` of its frames; ``len(track)`` if none does."""
    piece = track_pieces(track.frames, min_gap, track.boxes)[-1]
    backwards = _holes_bridged(repeated[piece])[::-1]
    length = np.arange(1, piece.size + 1)
    tails = np.flatnonzero(backwards & (length >= 2 * min_gap) & (np.cumsum(backwards) >= min_share * length))
    return int(piece[piece.size - 1 - tails.max()]) if tails.size else len(track)


def _repeating_rows(track: Track, piece: np.ndarray, repeated: np.ndarray, min_gap: int, min_share: float,
                    in_parts: bool) -> list[tuple[np.ndarray, bool]]:
    """The rows of a track's ``piece`` that go (:func:`drop_repeated_pieces`), each with whether
    its patterns are seen there: the whole piece where it repeats others (``repeated``, per row of
    the track) in ``min_share`` of its frames; otherwise, ``in_parts``, each of its
    :func:`_seen_parts` that does, and the unseen runs beside those (not seen: no lending)."""
    if _repeats(repeated[piece], min_share):
        return [(piece, True)]
    if not in_parts:
        return []
    parts = _seen_parts(track, piece, min_gap)
    gone = [_repeats(repeated[rows], min_share) for rows in parts[::2]]
    return ([(rows, True) for rows, went in zip(parts[::2], gone) if went]
            + [(rows, False) for at, rows in enumerate(parts[1::2]) if gone[at] or gone[at + 1]])


def _repeats(repeated: np.ndarray, min_share: float) -> bool:
    """Whether a piece whose frames ``repeated`` another track's boxes does so in at least
    ``min_share`` of them, runs of up to ``HOLE`` frames between counted as repeated."""
    return bool(np.mean(_holes_bridged(repeated)) >= min_share)


def _seen_parts(track: Track, rows: np.ndarray, min_gap: int) -> list[np.ndarray]:
    """``rows`` of a track cut at its runs of more than ``min_gap`` frames where its patterns are
    not seen (boxes inferred): seen stretch, unseen run, seen stretch, ... (odd count). A run at
    either end of ``rows`` leads nowhere and is not cut off."""
    begins, stops = flag_runs(~seen_rows(track)[rows])
    long_runs = [(begin, stop) for begin, stop in zip(begins.tolist(), stops.tolist())
                 if stop - begin > min_gap and begin > 0 and stop < rows.size]
    parts, at = [], 0
    for begin, stop in long_runs:
        parts += [rows[at:begin], rows[begin:stop]]
        at = stop
    return parts + [rows[at:]]


# A dropped piece whose boxes are this many times the area of those it repeats (both ends
# included) holds the whole of their object; larger, it holds a stretch of the scene around it.
WHOLE_AREA = (1.5, 4.0)


def _lend_whole(tracks: list[Track], slot: int, rows: np.ndarray) -> None:
    """Where another track holds a part of what a dropped piece (``rows`` of track ``slot``)
    holds, in at least half the piece's frames (its box's centre in the piece's box, which is
    :data:`WHOLE_AREA` times larger), that track takes the piece's boxes in those frames (in
    place; of the tracks so placed, the one with most such frames): the piece held the whole
    object, the track a part of it."""
    piece = tracks[slot]
    frames, boxes = piece.frames[rows], piece.boxes[rows]
    best, best_part = -1, np.zeros(0, dtype=bool)
    for other, track in enumerate(tracks):
        if other == slot:
            continue
        _, mine, theirs = np.intersect1d(frames, track.frames, assume_unique=True, return_indices=True)
        with np.errstate(divide="ignore", invalid="ignore"):  # a box of no area holds no part
            ratio = boxes[mine, 2] * boxes[mine, 3] / (track.boxes[theirs, 2] * track.boxes[theirs, 3])
        part = np.zeros(frames.size, dtype=bool)
        part[mine] = (centre_inside(boxes[mine], track.boxes[theirs]) & (ratio >= WHOLE_AREA[0])
                      & (ratio <= WHOLE_AREA[1]))
        if part.sum() > best_part.sum():
            best, best_part = other, part
    if best < 0 or np.mean(best_part) < 0.5:
        return
    other = tracks[best]
    lent = other.boxes.copy()
    lent[np.searchsorted(other.frames, frames[best_part])] = boxes[best_part]
    tracks[best] = dataclasses.replace(other, boxes=lent)


def _filled_up_to(track: Track, start: int, end: int) -> np.ndarray:
    """(len(track),) the rows of frames ``start``..``end`` and of the runs of inferred (unseen)
    rows on consecutive frames that reach them from either side."""
    frames = track.frames
    unseen = ~seen_rows(track)
    lost = (frames >= start) & (frames <= end)
    before = np.flatnonzero(frames < start)[::-1]
    after = np.flatnonzero(frames > end)
    lost[before] = np.logical_and.accumulate(unseen[before] & (frames[before] == start - 1 - np.arange(before.size)))
    lost[after] = np.logical_and.accumulate(unseen[after] & (frames[after] == end + 1 + np.arange(after.size)))
    return lost


def shared_stretches(boxes: np.ndarray, other: np.ndarray, min_frames: int, min_iou: float,
                     min_inside: float = 0.9) -> list[tuple[int, int]]:
    """First and last frame of each stretch where two tracks' boxes (per frame, NaN where none)
    hold the same object (:func:`same_boxes`: IoU at least ``min_iou``, or one at least
    ``min_inside`` inside the other, as the part of an object left in view behind another),
    holes of up to ``HOLE`` frames bridged, of at least ``min_frames`` frames."""
    begins, stops = flag_runs(_holes_bridged(same_boxes(boxes, other, min_iou, min_inside)))
    return [(begin, stop - 1) for begin, stop in zip(begins.tolist(), stops.tolist()) if stop - begin >= min_frames]


def _holes_bridged(flags: np.ndarray) -> np.ndarray:
    """``flags`` (bool) with each run of at most ``HOLE`` False between two True set True: frames
    in a row where jitter parts two boxes that hold the same object."""
    begins, stops = flag_runs(flags)
    out = flags.copy()
    for stop, begin in zip(stops[:-1].tolist(), begins[1:].tolist()):
        if begin - stop <= HOLE:
            out[stop:begin] = True
    return out


def flag_runs(flags: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """First index and index past the last of each run of True in ``flags``."""
    edges = np.diff(np.concatenate(([0], flags.astype(np.int8), [0])))
    return np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)


def _turns(own: np.ndarray, other: np.ndarray, at: int, window: int, least: float) -> bool:
    """Whether the track with boxes ``own`` turns at frame ``at`` and the one with ``other`` does
    not as much: its velocity change is larger than the other's and than ``least`` or, for a
    slow track, than its own speed (a slow object that goes back turns by less than ``least``).
    Where either track's turn is not known (it ends or starts there) nothing is said: a track
    that ends with the stretch does not show that it went straight on."""
    mine, theirs = _turn(own, at, window), _turn(other, at, window)
    if mine is None or theirs is None:
        return False
    change, speed = mine
    return change > max(theirs[0], min(least, speed))


def _turn(boxes: np.ndarray, at: int, window: int) -> tuple[float, float] | None:
    """Change of the box centre's mean velocity at frame ``at`` (over ``window`` frames after
    against ``window`` frames before) and the larger of the two speeds, in px per frame; None
    where a side has fewer than two boxes."""
    centres = box_centres(boxes)
    velocities = []
    for frames in (np.arange(max(at - window, 0), at), np.arange(at, min(at + window, len(boxes)))):
        seen = frames[~np.isnan(centres[frames, 0])]
        if seen.size < 2:
            return None
        velocities.append(np.polyfit(seen, centres[seen], 1)[0])
    return (float(np.linalg.norm(velocities[1] - velocities[0])),
            float(max(np.linalg.norm(velocities[0]), np.linalg.norm(velocities[1]))))
