"""Track boxes through short gaps (ours, TRAP_SPEC section 4: trajectories are interpolated).

A track has a box only in the frames where one of its patterns has an occurrence. With noisy
regions the patterns are missed here and there for a frame or a few, and the track flickers
although the object never left. Occurrence linking already treats gaps of up to ``tau`` frames
as one path; the boxes do the same: in a gap of at most ``max_gap`` frames each box side is
interpolated linearly between the boxes on either side. Such frames have no patterns of their
own (``points`` NaN) and half the track's lowest observed confidence. A gap whose two sides lie
farther apart than the object goes in that time is not its object hidden for a while but two
things the track's boxes hold: a line between them would cross the frame on nothing.
"""
from __future__ import annotations

import numpy as np

from trap_core.clustering import Track, centre_steps, usual_size, with_frames


def fill_gaps(track: Track, max_gap: int, pace: float = 3.0) -> Track:
    """The track with a box in every frame of its gaps of at most ``max_gap`` frames whose
    sides are no farther apart than its object goes at ``pace`` times its usual speed (median
    centre step between consecutive frames), plus half its usual size (box jitter)."""
    frames = track.frames
    gap = np.diff(frames) - 1
    short = (gap > 0) & (gap <= max_gap)
    if short.any():
        step = centre_steps(track.boxes)
        speed = float(np.median(step[gap == 0])) if np.any(gap == 0) else np.inf
        short &= step <= pace * speed * (gap + 1) + 0.5 * usual_size(track)
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
