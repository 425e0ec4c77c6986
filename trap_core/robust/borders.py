"""Tracks at the image border (ours): boxes continued while an object crosses it, and none
after the object has left through it.

An object that leaves the view is cut by the border frame after frame; its regions shrink and
change, its patterns stop being found while part of it is still visible, and the track ends
early (the mirror image for an object that enters). The part still in view is where the object
would be had it kept its motion: its box when last fully in view moved at its velocity over
those frames, clipped to the image. A track is continued so when its box reaches the border
(:func:`reaches_border`) where it ends (starts), or would a few frames on at its velocity, for
as long as that box overlaps the image, at most ``max_frames``, and never into frames the track
already covers. Such frames have no patterns of their own (:func:`with_inferred`). Once an
object has left, the boxes its track goes on with inside the view are something else
(:func:`end_at_exits`).
"""
from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from trap_core.clustering import Track, border_sides, box_centres, in_rows, reaches_border, track_pieces
from trap_core.robust.gaps import with_inferred

SIZE_RATIO = 1.25  # a box in view this much smaller than the track's usual one may be of a cut part


def continue_to_border(track: Track, n_frames: int, width: float, height: float, span: int = 12,
                       max_frames: int = 50, lead: int = 0) -> Track:
    """The track with boxes for the frames where its object, leaving or entering the view at
    a run's end or start, is still partly visible.

    Parameters
    ----------
    track : Track
    n_frames, width, height :
        Video length and frame size (boxes are clipped to ``[0, width) x [0, height)``).
    span : int
        Frames, fully in view, whose box centres give the velocity (a straight-line fit) and
        whose median box is the object's size; at least 3 are needed.
    max_frames : int
        Frames at most added at one end of a run.
    lead : int
        A run's end (start) whose box is whole and of about the object's size also counts as at
        the border where its velocity brings it there within this many frames: a fast object's
        patterns can stop a few frames before its box touches the border (the background
        regions between them vanish first), and its track would end unseen leaving. A box
        already cut by the border keeps the test on its own size.

    Returns
    -------
    Track
    """
    frames = track.frames
    if frames.size < 3:
        return track
    boxes = track.boxes.astype(float)
    whole = ~reaches_border(boxes, width, height, margin=0.0)  # fully in view
    if not whole.any():
        return track
    ratio = boxes[:, 2:] / np.median(boxes[whole, 2:], axis=0)
    whole &= np.all((ratio > 1 / SIZE_RATIO) & (ratio < SIZE_RATIO), axis=1)  # not a part cut by the border
    at_border = reaches_border(boxes, width, height)
    breaks = np.flatnonzero(np.diff(frames) > 1)
    starts, ends = np.r_[0, breaks + 1], np.r_[breaks, frames.size - 1]
    added_frames, added_boxes = [], []
    taken = set(frames.tolist())
    for run, (first, last) in enumerate(zip(starts, ends)):
        before = frames[ends[run - 1]] if run > 0 else -1
        after = frames[starts[run + 1]] if run + 1 < starts.size else n_frames
        for edge, step, limit in ((last, 1, after), (first, -1, before)):
            if not (at_border[edge] or lead and whole[edge]):  # off the border: a whole box, its velocity read below
                continue
            inward = np.arange(edge, first - 1, -1) if step == 1 else np.arange(edge, last + 1)
            reference = inward[whole[inward]][:span]
            if reference.size < 3:
                continue
            centre = box_centres(boxes[reference])
            velocity, intercept = np.polyfit(frames[reference], centre, 1)
            size = np.median(boxes[reference, 2:], axis=0)
            ahead = boxes[edge] + np.r_[velocity * step * lead, 0.0, 0.0]
            if not (at_border[edge] or reaches_border(ahead[None], width, height)[0]):
                continue
            continued = []
            for frame in range(frames[edge] + step, frames[edge] + step * (max_frames + 2), step):
                x, y = velocity * frame + intercept - size / 2
                x0, y0 = max(x, 0.0), max(y, 0.0)
                x1, y1 = min(x + size[0], width), min(y + size[1], height)
                if x1 - x0 < 1 or y1 - y0 < 1:
                    break
                continued.append((frame, (x0, y0, x1 - x0, y1 - y0)))
            else:
                continue  # the motion does not take the object out of view soon: not a crossing
            stop = next((k for k, (frame, _) in enumerate(continued)
                         if frame in taken or (frame - limit) * step >= 0), len(continued))
            continued = continued[:stop]  # not into the next run, the other end's frames or past the video
            taken.update(frame for frame, _ in continued)
            added_frames += [frame for frame, _ in continued]
            added_boxes += [box for _, box in continued]
    if not added_frames:
        return track
    return with_inferred(track, np.array(added_frames), np.array(added_boxes))


def end_at_exits(track: Track, width: float, height: float, min_gap: int, leaving: int = 3) -> Track:
    """The track without the boxes that follow its object's exit from the view until it comes
    back through the border.

    An exit: the box was clear of every border earlier in its run (a run starts after a gap of
    more than ``min_gap`` frames), then over ``leaving`` frames it lies on one image border,
    shrinking across it, and ends less than half the track's usual extent across it (the median
    of its boxes fully in view), and the next box is off that border. A body mostly out of view
    cannot be clear of the border a frame later unless it moves half its size in a frame: the
    patterns went on with something else (noise, a neighbour) once the object was gone. Where
    its boxes hold parts of it that jump on and off the border, an exit is also seen before a
    gap, in a box half out of view and moving out (:func:`_gone_out`). Nor can it come back
    but through the border: boxes are dropped up to a piece (after a gap of more than
    ``min_gap`` frames, or a jump of the box by more than its size: a continuation through the
    gap, :func:`trap_core.robust.continue_tracks`, can run up to the return) whose first box
    reaches the border (:func:`reaches_border`, within a quarter of the object's usual extent:
    that box may be a sliver of it) or lies within its extent of a border and moves away from it
    (:func:`_coming_in`, after a gap), or up to an entry: a box that comes onto a border and grows
    across it over ``leaving`` frames (a filled gap can run from something else into the return
    with no jump).

    Parameters
    ----------
    track : Track
    width, height : float
        Frame size.
    min_gap : int
        A gap of more than this many frames starts a new run of the track.
    leaving : int
        Frames the box must lie on the border, shrinking, before it is seen off it.

    Returns
    -------
    Track
    """
    boxes = track.boxes.astype(float)
    w, h = boxes[:, 2], boxes[:, 3]
    sides = border_sides(boxes, width, height, 0.5, 0.5)
    whole = ~sides.any(axis=1)
    if not whole.any() or boxes.shape[0] <= leaving:
        return track
    extent = np.column_stack([w, h, w, h])
    usual = np.median(extent[whole], axis=0)
    frames = track.frames
    starts = np.r_[True, np.diff(frames) > min_gap]
    # a continuation can fill the gap up to the object's return: it comes back with a jump then
    piece_rows = track_pieces(frames, min_gap, boxes)
    pieces = np.zeros(frames.size, dtype=bool)
    pieces[[rows[0] for rows in piece_rows]] = True
    # a piece's first box may be a sliver of the object at the border: reach measured at its usual size
    entering = pieces & reaches_border(boxes, width, height, size=usual[:2])
    after_gap = [rows for rows in piece_rows if rows[0] and starts[rows[0]]]
    entering[_coming_in(boxes, after_gap, width, height, usual[:2], min_gap)] = True
    # an object coming into view lies on the border, its boxes as noisy as its patterns: seen whole first, it can leave
    whole_before = _seen_whole_in_run(whole, starts)
    keep = np.ones(frames.size, dtype=bool)
    row = leaving - 1
    entering[_entries(frames, sides, extent, usual, leaving)] = True
    exits = np.union1d(_exits(frames, sides, extent, usual, whole_before, leaving),
                       _gone_out(boxes, sides, extent, usual, starts, whole_before, leaving,
                                 _clear_of_borders(boxes, width, height, usual[:2])))
    for exit_row in exits.tolist():
        if exit_row < row:  # among the boxes dropped after an earlier exit
            continue
        back = np.flatnonzero(entering[exit_row + 1:])
        stop = exit_row + 1 + (back[0] if back.size else frames.size)
        keep[exit_row + 1:stop] = False
        row = stop + leaving - 1
    return track if keep.all() else in_rows(track, keep)


def _exits(frames: np.ndarray, sides: np.ndarray, extent: np.ndarray, usual: np.ndarray, whole_before: np.ndarray,
           leaving: int) -> np.ndarray:
    """Rows (increasing) whose box ends an exit on some side (:func:`end_at_exits`): over the
    ``leaving`` consecutive frames up to it the box lies on that border (``sides``, (n, 4)) and
    its ``extent`` across it does not grow, ending under half the ``usual`` one, the next box
    is off that border, and a whole box came before in the run (``whole_before``)."""
    rows = np.arange(leaving - 1, frames.size - 1)
    first = rows - leaving + 1  # each exit's first frame on the border
    consecutive = sliding_window_view(np.diff(frames) == 1, leaving)[first].all(axis=-1)
    on_border = sliding_window_view(sides, leaving, axis=0)[first].all(axis=-1)
    shrinking = (sliding_window_view(np.diff(extent, axis=0) <= 0, leaving - 1, axis=0)[first].all(axis=-1)
                 if leaving > 1 else np.ones(on_border.shape, dtype=bool))
    exit_side = ((whole_before[first] & consecutive)[:, None] & on_border & ~sides[rows + 1]
                 & (extent[rows] < usual / 2) & shrinking)
    return rows[exit_side.any(axis=1)]


def _gone_out(boxes: np.ndarray, sides: np.ndarray, extent: np.ndarray, usual: np.ndarray, starts: np.ndarray,
              whole_before: np.ndarray, leaving: int, inside: np.ndarray) -> np.ndarray:
    """Rows (increasing) whose box ends an exit seen through noisy boxes (:func:`end_at_exits`):
    a gap follows (the next row ``starts`` a run), the box lies on a border with under half the
    ``usual`` extent across it, its centre has moved toward that border since the box ``leaving``
    rows before (in the same run), a whole box came before in the run (``whole_before``), and
    the box after the gap lies ``inside`` the view (per row: clear of every border by the usual
    extent; nearer, it may be the object coming back). Boxes of parts of an object (its legs,
    its head) jump on and off the border as it leaves, so the shrinking run of :func:`_exits`
    is not seen, but an object half out of view and moving out is gone when its patterns are."""
    run = np.cumsum(starts)
    rows = np.flatnonzero(starts[1:])
    rows = rows[(rows >= leaving) & whole_before[rows] & inside[rows + 1]]
    rows = rows[run[rows - leaving] == run[rows]]
    earlier = rows - leaving
    step = box_centres(boxes[rows]) - box_centres(boxes[earlier])
    outward = _toward_sides(step)
    gone = sides[rows] & (extent[rows] < usual / 2) & outward
    return rows[gone.any(axis=1)]


def _coming_in(boxes: np.ndarray, piece_rows: list[np.ndarray], width: float, height: float, usual: np.ndarray,
               ahead: int) -> np.ndarray:
    """First rows of the pieces (``piece_rows``: those after a gap) whose first box lies within
    the object's extent (its own or the ``usual`` one, the larger) of a border and whose box
    centre moves away from that border over the piece's next ``ahead`` rows: an object that came
    in through the border unseen (:func:`end_at_exits`). Its patterns form once its structures
    are in view, by then clear of the border by a few px to its whole size. (Right after an exit,
    with no gap, a box that near and moving in is what the patterns went on with.)"""
    if not piece_rows:
        return np.zeros(0, dtype=np.int64)
    first = np.array([rows[0] for rows in piece_rows], dtype=np.int64)
    later = np.array([rows[min(ahead, rows.size - 1)] for rows in piece_rows], dtype=np.int64)
    near = border_sides(boxes[first], width, height, np.maximum(boxes[first, 2], usual[0]),
                        np.maximum(boxes[first, 3], usual[1]))
    away = _toward_sides(box_centres(boxes[first]) - box_centres(boxes[later]))
    return first[(near & away).any(axis=1)]


def _toward_sides(step: np.ndarray) -> np.ndarray:
    """(n, 4) bool: per (dx, dy) ``step``, whether it goes toward the left, top, right and bottom
    border (the columns of :func:`~trap_core.clustering.border_sides`)."""
    return np.column_stack([-step[:, 0], -step[:, 1], step[:, 0], step[:, 1]]) > 0


def _clear_of_borders(boxes: np.ndarray, width: float, height: float, margin: np.ndarray) -> np.ndarray:
    """(n,) bool: whether boxes ``(x, y, w, h)`` lie at least ``margin`` (x, y) px from every border."""
    x, y, w, h = boxes.T
    return (x >= margin[0]) & (y >= margin[1]) & (x + w <= width - margin[0]) & (y + h <= height - margin[1])


def _entries(frames: np.ndarray, sides: np.ndarray, extent: np.ndarray, usual: np.ndarray,
             leaving: int) -> np.ndarray:
    """Rows (increasing) whose box starts an entry on some side (:func:`end_at_exits`): the
    box before is off that border, and over the ``leaving`` consecutive frames from it the box
    lies on that border (``sides``, (n, 4)), its ``extent`` across it never shrinks and grows,
    and it is never larger than ``SIZE_RATIO`` times the ``usual`` extents (an object coming in
    shows a part of itself; a box on much of the view is not one). None with ``leaving`` 1:
    one frame shows no growth."""
    rows = np.arange(1, frames.size - leaving + 1) if leaving > 1 else np.zeros(0, dtype=np.int64)
    consecutive = sliding_window_view(np.diff(frames) == 1, leaving - 1)[rows].all(axis=-1)
    on_border = sliding_window_view(sides, leaving, axis=0)[rows].all(axis=-1)
    growing = (sliding_window_view(np.diff(extent, axis=0) >= 0, leaving - 1, axis=0)[rows].all(axis=-1)
               & (extent[rows + leaving - 1] > extent[rows]))
    small = np.all(extent[:, :2] <= SIZE_RATIO * usual[:2], axis=1)
    small = sliding_window_view(small, leaving)[rows].all(axis=-1)
    entry = (consecutive & small)[:, None] & on_border & ~sides[rows - 1] & growing
    return rows[entry.any(axis=1)]


def _seen_whole_in_run(whole: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """(n,) bool: whether a box before row i in row i's run (``starts``: where runs begin) is ``whole``."""
    run = np.cumsum(starts) - 1
    seen = np.cumsum(whole)  # whole boxes up to and including each row
    before_run = np.r_[0, seen][np.flatnonzero(starts)][run]  # whole boxes before the row's run
    return np.r_[0, seen[:-1]] - before_run > 0
