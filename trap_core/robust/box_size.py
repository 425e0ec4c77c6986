"""Steady track boxes: an object does not double in size from one frame to the next (ours).

When two look-alike objects touch, their same-coloured regions become one region, and every
pattern on either object then spans both: the box around the track's regions covers the
pair. Such frames show as a box much larger than the track's usual size. There the box is
replaced by one of the usual size, centred where the neighbouring normal frames put the
object (linear interpolation of their centres) and kept inside the observed box, which
does hold the object. "Usual" is a running median over a window, so objects that grow or
shrink steadily (coming closer, zooming) are left alone.
"""
from __future__ import annotations

import numpy as np


def steady_boxes(frames: np.ndarray, boxes: np.ndarray, factor: float = 1.5, window: int = 50) -> np.ndarray:
    """Track boxes ``(x, y, w, h)`` per frame with the oversized ones replaced.

    Parameters
    ----------
    frames : (N,) int array, increasing
    boxes : (N, 4) array
        ``x, y, w, h`` in each frame.
    factor : float
        A box wider or taller than ``factor`` times the running median is oversized; 0 = off.
    window : int
        Frames on each side of the running median.

    Returns
    -------
    (N, 4) float array
    """
    boxes = np.asarray(boxes, dtype=float).copy()
    if factor <= 0 or len(frames) < 3:
        return boxes
    lo = np.searchsorted(frames, frames - window)
    hi = np.searchsorted(frames, frames + window, side="right")
    usual = np.array([np.median(boxes[a:b, 2:4], axis=0) for a, b in zip(lo, hi)])
    oversized = (boxes[:, 2] > factor * usual[:, 0]) | (boxes[:, 3] > factor * usual[:, 1])
    normal = ~oversized
    if oversized.all() or not oversized.any():
        return boxes
    centre = boxes[:, :2] + boxes[:, 2:4] / 2
    for axis in (0, 1):
        guess = np.interp(frames[oversized], frames[normal], centre[normal, axis])
        size = usual[oversized, axis]
        start = boxes[oversized, axis]
        stop = start + boxes[oversized, 2 + axis] - size  # the usual box stays inside the observed one
        boxes[oversized, axis] = np.clip(guess - size / 2, start, stop)
        boxes[oversized, 2 + axis] = size
    return boxes
