"""Track boxes through short gaps (ours, TRAP_SPEC section 4: trajectories are interpolated).

A track has a box only in the frames where one of its patterns has an occurrence. With noisy
regions the patterns are missed here and there for a frame or a few, and the track flickers
although the object never left. Occurrence linking already treats gaps of up to ``tau`` frames
as one path; the boxes do the same: in a gap of at most ``max_gap`` frames each box side is
interpolated linearly between the boxes on either side. Such frames have no patterns of their
own (``points`` NaN) and half the track's lowest observed confidence. A gap whose two sides lie
farther apart than the object goes in that time is not its object hidden for a while but two
things the track's boxes hold: a line between them would cross the frame on nothing. Nor is a
gap through which the object's motion takes it out of view: a box at the border moving out has
nothing of its object inside the view after it, and what the track holds next is something else
or the object back; either way the object was out of view in between.
"""
from __future__ import annotations

import numpy as np

from trap_core.clustering import (Track, border_sides, centre_path, centre_steps, reaches_border, usual_box,
                                  usual_size, with_frames)
from trap_core.robust.motion import straight_line


def fill_gaps(track: Track, max_gap: int, pace: float = 3.0, view: tuple[float, float] | None = None) -> Track:
    """The track with a box in every frame of its gaps of at most ``max_gap`` frames whose
    sides are no farther apart than its object goes at ``pace`` times its usual speed (median
    centre step between consecutive frames), plus half its usual size (box jitter), and, given
    the ``view`` (width, height), through which its object stays in view
    (:func:`_out_of_view_between`)."""
    frames = track.frames
    gap = np.diff(frames) - 1
    short = (gap > 0) & (gap <= max_gap)
    if short.any():
        step = centre_steps(track.boxes)
        speed = float(np.median(step[gap == 0])) if np.any(gap == 0) else np.inf
        short &= step <= pace * speed * (gap + 1) + 0.5 * usual_size(track)
    if short.any() and view is not None:
        short[short] = ~_out_of_view_between(track, np.flatnonzero(short), view, max(3, max_gap // 2))
    if not short.any():
        return track
    missing = np.concatenate([np.arange(a + 1, b) for a, b in zip(frames[:-1][short], frames[1:][short])])
    boxes = np.column_stack([np.interp(missing, frames, track.boxes[:, k]) for k in range(4)])
    return with_inferred(track, missing, boxes)


def with_inferred(track: Track, frames: np.ndarray, boxes: np.ndarray) -> Track:
    """The track with boxes added in ``frames`` (which it does not cover), where the object is
    inferred, not seen: no patterns of their own (``points`` NaN), half the track's lowest
    observed confidence."""
    return with_frames(track, frames, boxes, np.full(len(frames), 0.5 * float(track.score.min())),
                       np.full((len(frames), 2), np.nan))


def _out_of_view_between(track: Track, rows: np.ndarray, view: tuple[float, float], window: int) -> np.ndarray:
    """Per gap after ``rows``: whether the box on one side of it reaches the border of the
    ``view``, the object's motion there (the straight line through its box centres over
    ``window`` frames on that side, :func:`straight_line`) takes its usual box wholly out of view
    before the other side, and the box on the other side is clear of the border: an exit (an
    entry) within the gap, and something inside the view beyond it. Where both sides are at the
    border, the track may hold the object leaving and coming back, or a box of something at the
    border whose jitter reads as a motion out: nothing is said."""
    width, height = view
    frames = track.frames
    centres = centre_path(track, int(frames[-1]) + 1)
    half = usual_box(track) / 2
    at_border = reaches_border(track.boxes, width, height)
    out = np.zeros(rows.size, dtype=bool)
    for k, row in enumerate(rows.tolist()):
        before, after = int(frames[row]), int(frames[row + 1])
        sides = ((row, row + 1, np.arange(max(before - window + 1, 0), before + 1), after - 1),  # an exit
                 (row + 1, row, np.arange(after, min(after + window, centres.shape[0])), before + 1))  # an entry
        for edge, other, seen, far in sides:
            line = straight_line(centres, seen) if at_border[edge] and not at_border[other] else None
            if line is not None:
                velocity, origin = line
                box = np.r_[origin + velocity * far - half, 2 * half]
                out[k] |= border_sides(box[None], width, height, -box[2], -box[3]).any()
    return out
