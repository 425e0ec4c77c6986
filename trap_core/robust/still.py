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
from collections.abc import Sequence

import numpy as np

from trap_core.clustering import FrameCores, Track
from trap_core.rag import PlaneGraph
from trap_core.robust.camera import map_points

AREA_FACTOR = 2.0  # a background region the object passes over loses or regains what it hides


def drop_still_regions(track: Track, cores: FrameCores, graphs: Sequence[PlaneGraph], transforms: np.ndarray,
                       lag: int, pixel: float = 0.0) -> Track:
    """The track with each core box rebuilt without the core regions that stand still.

    Parameters
    ----------
    track : Track
        As built from its cluster (:func:`trap_core.clustering.build_track`), with its points.
    cores : FrameCores
        Per frame, the core regions of the track's cluster and the most shared ones
        (:func:`trap_core.clustering.frame_cores`, at the track's ``core_share``).
    graphs : sequence of PlaneGraph
        Plane graph of every frame of the video.
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
    slot = np.full(len(graphs), -1)
    slot[track.frames] = np.arange(len(track))
    boxes = track.boxes.astype(float)
    for frame, core, anchor in cores:
        i = slot[frame]
        if i < 0:
            continue
        others = core[(core[:, None] != anchor).all(axis=1)]  # the anchor is among the core regions
        if others.size == 0:
            continue
        still = _standing_still(graphs, transforms, track.points, slot, frame, others, lag)
        if still.any():
            boxes[i] = graphs[frame].nodes_box(np.r_[anchor, others[~still]], pixel)
    return dataclasses.replace(track, boxes=boxes)


def _standing_still(graphs: Sequence[PlaneGraph], transforms: np.ndarray, points: np.ndarray, slot: np.ndarray,
                    frame: int, regions: np.ndarray, lag: int) -> np.ndarray:
    """Mask of ``regions`` of ``frame`` found again at most half as far from where the camera puts
    them as from where the track's points move, in every frame ``lag`` away (before, after) that
    the track covers."""
    still = np.ones(regions.size, dtype=bool)
    tested = False
    for other in (frame - lag, frame + lag):
        j = slot[other] if 0 <= other < len(graphs) else -1
        if j < 0:
            continue
        shift = points[j] - points[slot[frame]]
        if np.isnan(shift).any():
            continue
        tested = True
        with_track, with_camera = found_again(graphs, transforms, frame, other, regions, shift)
        still &= 2 * with_camera < with_track
    return still & tested


def found_again(graphs: Sequence[PlaneGraph], transforms: np.ndarray, frame: int, other: int, regions: np.ndarray,
                shift: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per region of ``regions`` (nodes of ``graphs[frame]``): the distance from where ``shift``
    (a track's motion from ``frame`` to ``other``) puts it, and from where the camera's motion
    (``transforms``) puts it, to the nearest region of ``graphs[other]`` that looks like it (same
    label, area within ``AREA_FACTOR``); inf for both where none does."""
    here, there = graphs[frame], graphs[other]
    moved = map_points(transforms[other] @ np.linalg.inv(transforms[frame]), here.centroid[regions])
    with_track, with_camera = np.full(regions.size, np.inf), np.full(regions.size, np.inf)
    for k, region in enumerate(regions.tolist()):
        look_alike = ((there.label == here.label[region]) & (there.area < AREA_FACTOR * here.area[region])
                      & (AREA_FACTOR * there.area > here.area[region]))
        if look_alike.any():
            candidates = there.centroid[look_alike]
            with_track[k] = np.hypot(*(candidates - (here.centroid[region] + shift)).T).min()
            with_camera[k] = np.hypot(*(candidates - moved[k]).T).min()
    return with_track, with_camera
