"""Track boxes through short gaps (ours, TRAP_SPEC section 4: trajectories are interpolated).

A track has a box only in the frames where one of its patterns has an occurrence. With noisy
regions the patterns are missed here and there for a frame or a few, and the track flickers
although the object never left. Occurrence linking already treats gaps of up to ``tau`` frames
as one path; the boxes do the same: in a gap of at most ``max_gap`` frames each box side is
interpolated linearly between the boxes on either side. Such frames have no patterns of their
own (``points`` NaN) and half the track's lowest observed confidence.
"""
from __future__ import annotations

import numpy as np

from trap_core.clustering import Track, with_frames


def fill_gaps(track: Track, max_gap: int) -> Track:
    """The track with a box in every frame of its gaps of at most ``max_gap`` frames."""
    frames = track.frames
    gap = np.diff(frames) - 1
    short = (gap > 0) & (gap <= max_gap)
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
