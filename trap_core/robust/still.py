"""Background out of core boxes: regions that stay where the camera puts them (ours).

A track's core box surrounds the regions most of its occurrences in a frame contain
(:func:`trap_core.clustering.core_regions`). A face of the plane graph is bounded by the object
and by the regions around it, so where an object crosses a background region of about its own
size, nearly every pattern on the object also holds that region, and the box takes it in for as
long as the crossing lasts (400x300: a box 73 px wide on an object 40 px wide for 95 frames;
too long for the usual-size rule of ``size_jump``, whose running median it shifts). The object
itself is the region the most occurrences hold. Each other core region is tested the way grown
boxes test their candidates, but for the opposite evidence: ``lag`` frames before and after,
is it found again (same label, area within a factor 2, as the object hides more or less of it)
at most half as far from where the camera's motion puts it as from where the track's motion
does (the mirror of the grown boxes' test: in between, nothing is decided)? A region that stays
with the background in every frame tested leaves the box. Regions split by noise that cannot be
found again at all are kept: only evidence of standing still removes one, and an object that
moves slowly relative to the background, where the two predictions are close, keeps its parts.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from trap_core.clustering import FrameCores, Track
from trap_core.rag import StackedGraphs
from trap_core.rag.plane_graph import edge_line_limits
from trap_core.robust._kernels import still_core_boxes as _still_core_boxes
from trap_core.robust.camera import camera_moves

AREA_FACTOR = 2.0  # a background region the object passes over loses or regains what it hides


def drop_still_regions(track: Track, cores: FrameCores, graphs: StackedGraphs, transforms: np.ndarray, lag: int,
                       pixel: float = 0.0) -> Track:
    """The track with each core box rebuilt without the core regions that stand still.

    Parameters
    ----------
    track : Track
        As built from its cluster (:func:`trap_core.clustering.build_track`), with its points.
    cores : FrameCores
        Per frame, the core regions of the track's cluster and the most shared ones
        (:func:`trap_core.clustering.frame_cores`, at the track's ``core_share``).
    graphs : StackedGraphs
        Plane graph of every frame of the video, stacked.
    transforms : (n_frames, 3, 3) array
        Camera motion, frame 0 to frame ``t`` (:func:`trap_core.robust.camera_transforms`).
    lag : int
        Frames before and after where a region is looked for again.
    pixel : float
        Frame pixels per pixel of the segmentation's size: edge lines alone do not widen the
        rebuilt boxes (:meth:`~trap_core.rag.PlaneGraph.nodes_box`); 0: they do.

    Returns
    -------
    Track
    """
    slot = np.full(len(graphs), -1, dtype=np.int64)
    slot[track.frames] = np.arange(len(track))
    frames = cores.frames.astype(np.int64)
    cameras = camera_moves(transforms, frames, lag)
    boxes = track.boxes.astype(float)
    _still_core_boxes(graphs.node_offsets, graphs.bbox, graphs.centroid, graphs.area, graphs.label, graphs.thickness,
                      graphs.nearest_in_colour, frames, cores.core, cores.core_ends, cores.top, cores.top_ends, slot,
                      track.points.astype(float), cameras, boxes, lag, AREA_FACTOR, *edge_line_limits(pixel))
    return dataclasses.replace(track, boxes=boxes)
