"""Box edges that leave their track's lines for a few frames put back between them (ours).

A track's box surrounds the regions its patterns hold, grown over those that move with the
object (:func:`trap_core.robust.grow_boxes`). Where the segmentation merges the object with a
neighbouring region for a frame or two, or loses one of its parts, one side of the box jumps out
(in) and comes back: an object's outline does not move so, and such frames put the box partly on
the background or off part of the object. Each edge of the box (left, top, right, bottom) is
read against the same edge in the boxes just before it and in those just after it: where it
lies far from the straight line of both, it is put between them. The other edges stay: a box
that took in a neighbour on one side is still right on the others. An edge that moves for good
lies on the line of the side it moved to, and stays; a single line through both sides would
put the frames beside such a step halfway between its two places.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from trap_core.clustering import Track
from trap_core.robust._kernels import side_lines

MIN_SIDE = 3  # boxes on a side of a frame that make a line there


def steady_edges(track: Track, half: int, width: float, height: float, share: float = 0.2) -> Track:
    """The track with each box edge that jumps off its neighbours' lines put back between them.

    Parameters
    ----------
    track : Track
    half : int
        The neighbours of a box are the track's boxes within this many frames before it, and
        those within as many after it; at least ``MIN_SIDE`` are needed on each side. An edge
        away from their lines for fewer frames than about half of that is put back; where the
        edge moved for good, the frames on either side of the step agree with one side's line
        and stay.
    width, height : float
        Frame size: an edge put back stays in ``[0, width] x [0, height]`` (the lines of a box
        cut by the border can run out of the image).
    share : float
        An edge is off a line where it lies further from it than this share of the track's
        median box width (left and right edges) or height (top and bottom edges).

    Returns
    -------
    Track
        With the same frames; an edge off both lines is put midway between them.

    Notes
    -----
    The line of an edge on each side is the Theil-Sen fit over those neighbours (the median of
    the slopes between pairs of them, and the median intercept): a frame or two that jump do not
    move it, and an edge that moves steadily (the object's motion, a zoom, an object crossing the
    border) lies on both. A track's first and last boxes have one side only, and stay.
    """
    if len(track) < 2 * MIN_SIDE + 1 or half < MIN_SIDE:
        return track
    boxes = track.boxes.astype(float)
    edges = np.column_stack([boxes[:, :2], boxes[:, :2] + boxes[:, 2:4]])  # x0, y0, x1, y1
    frames = track.frames.astype(np.int64)
    before, after = (side_lines(frames, edges, half, step, MIN_SIDE) for step in (-1, 1))
    size = np.median(boxes[:, 2:4], axis=0)
    limit = share * np.r_[size, size]
    off = (np.abs(edges - before) > limit) & (np.abs(edges - after) > limit)  # False where a side has no line
    if not off.any():
        return track
    steady = np.where(off, np.clip((before + after) / 2, 0.0, [width, height, width, height]), edges)
    steady_boxes = np.column_stack([steady[:, :2], steady[:, 2:] - steady[:, :2]])
    flipped = np.any(steady_boxes[:, 2:4] < 1, axis=1)  # two opposite edges crossed: keep the box
    steady_boxes[flipped] = boxes[flipped]
    return dataclasses.replace(track, boxes=steady_boxes)
