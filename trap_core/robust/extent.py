"""Track boxes grown over the regions that move with the object (ours).

A track's box surrounds the regions of its frequent patterns. Where the segmentation splits an
object differently from frame to frame (noise, textured objects), only a few of its parts are in
frequent patterns and the box covers those parts, not the object. Around the box, a region is
taken as part of the object when it moves with it: ``lag`` frames before or ``lag`` frames after,
the track's displacement brings it onto a region of the same label and about the same area
(within 25 %: a background region the object passes over changes area as it is hidden), within
``tolerance`` times the square root of its area, and the camera's motion does not bring it
anywhere nearly as close (background regions move with the camera). Either direction suffices:
noisy regions are often found again on one side only. Over a textured ground the parts a
person's patterns hold can be one arm and one leg, and the head and the other side are further
than the search reaches: the box grows again from the grown box, for up to ``rounds`` rounds, but
a region it takes then must be found again on both sides (it is further from what the patterns
hold). A noisy object's patterns are also
missed for a few frames here and there, so the track's displacement is measured against its box
interpolated through short gaps (:func:`fill_gaps`) where it has none of its own in that frame:
else a sparse track's boxes never grow and stay on the one part its patterns hold. The track's
displacement is read two ways, and a region found again with either moves with it: between its
boxes as built, and between their centres put on the least-squares line through the centres
within ``lag`` frames. Where the patterns hop between look-alike parts of one object (a walker's
two legs), the box hops by their distance and the first is off by as much; where the object turns
sharply, the line is off and the first is exact.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from trap_core.clustering import Track, box_centres
from trap_core.rag import StackedGraphs
from trap_core.rag.plane_graph import edge_line_limits
from trap_core.robust._kernels import grow_boxes as _grow_boxes
from trap_core.robust.camera import camera_moves
from trap_core.robust.gaps import fill_gaps

# Regions larger than this times the box are background, whatever their motion, unless they
# enclose the box: a box on a small part of the object is inside the body around that part. The
# backdrop encloses every box and is never taken: over a panning camera its barycentre stays in
# the middle of the view, and can sit where the track's motion puts it (988: boxes of the whole frame).
MAX_AREA = 4.0


def grow_boxes(track: Track, regions: StackedGraphs, transforms: np.ndarray, lag: int = 5,
               reach: float = 0.5, tolerance: float = 0.3, max_gap: int = 0, rounds: int = 3,
               pixel: float = 0.0) -> Track:
    """The track with each box grown over the nearby regions that move with it.

    Parameters
    ----------
    track : Track
    regions : StackedGraphs
        The plane graphs of every frame of the video, stacked.
    transforms : (n_frames, 3, 3) array
        Camera motion: ``transforms[t]`` maps frame-0 coordinates to frame ``t``
        (:func:`trap_core.robust.camera_transforms`).
    lag : int
        Frames before and after a frame where a region's motion is checked (either will do).
    reach : float
        Regions that touch the box grown by this share of its size on each side are candidates.
    tolerance : float
        A region is found again if a region of the same label and area within 25 % lies
        within ``tolerance`` times the square root of its area (plus 1 px) of where a motion
        puts it.
    max_gap : int
        Where the track has no box ``lag`` frames away, its box interpolated through a gap
        of at most this many frames stands in. Only frames with a box of their own grow.
    rounds : int
        Times a box grows: each round searches around the box the previous one grew, and after
        the first a region must be found again both ``lag`` frames before and after.
    pixel : float
        Frame pixels per pixel of the segmentation's size: edge lines alone do not grow a box
        by their width (:meth:`~trap_core.rag.PlaneGraph.nodes_box`); 0: they do.

    Returns
    -------
    Track
    """
    reference = fill_gaps(track, max_gap)  # motions are measured between the boxes as built, not as grown
    slot = np.full(len(regions), -1, dtype=np.int64)
    slot[reference.frames] = np.arange(len(reference))
    frames = track.frames.astype(np.int64)
    cameras = camera_moves(transforms, frames, lag)
    searched = track.boxes.astype(float)  # each round searches around what the rounds before took in
    boxes = searched.copy()  # and the box grows as far, but for the edge lines outside it (``pixel``)
    _grow_boxes(regions.node_offsets, regions.bbox, regions.centroid, regions.area, regions.label, regions.backdrop,
                regions.thickness, regions.nearest_in_colour, regions.by_place, frames, slot,
                reference.boxes.astype(float), _line_centred(reference, lag), searched, boxes, cameras, lag, reach,
                tolerance, MAX_AREA, rounds, *edge_line_limits(pixel))
    return dataclasses.replace(track, boxes=boxes)


def _line_centred(track: Track, half: int) -> np.ndarray:
    """(n, 4) the track's boxes moved so that each centre lies on the least-squares line of the
    centres within ``half`` frames of it (its own where it has no neighbour): the second reading
    of the track's displacement (module docstring). Sums over the window's offsets, a dense
    frame axis: O(n ``half``)."""
    boxes = track.boxes.astype(float)  # a copy: moved in place below
    if not len(track):
        return boxes
    frames = track.frames.astype(np.int64)
    centres = box_centres(boxes)
    start, span = frames[0], frames[-1] - frames[0] + 1
    dense = np.full((span + 2 * half, 2), np.nan)
    dense[frames - start + half] = centres
    sums = np.zeros((5, span, 2))  # count, sum d, sum d^2, sum c, sum d c
    for d in range(-half, half + 1):
        values = dense[half + d:half + d + span]
        there = ~np.isnan(values)
        known = np.where(there, values, 0.0)
        sums[0] += there
        sums[1] += there * d
        sums[2] += there * d * d
        sums[3] += known
        sums[4] += known * d
    n, sd, sdd, sc, sdc = sums[:, frames - start]
    det = n * sdd - sd * sd
    fitted = np.where(det > 0, (sc * sdd - sd * sdc) / np.where(det > 0, det, 1), centres)
    boxes[:, :2] += fitted - centres
    return boxes
