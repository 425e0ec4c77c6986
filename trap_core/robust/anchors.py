"""Clusters whose own region stays with the scene are background (ours).

A cluster moves relative to the camera when its patterns do (:mod:`trap_core.robust.camera`),
but over a noisy or textured scene patterns are chains: noise makes and unmakes structures
between the stones of gravel or the grain of a smooth photograph, and the linking chains one to
the next, so a chain drifts across the scene while every region it holds stays where it is
(README, "Noisy gravel": chains of such structures were 3-4 extra tracks). An object is the
opposite: its regions go with it. So each frame's anchor of a cluster (the regions most of its
occurrences hold, :func:`~trap_core.clustering.core_regions`: the object itself for a track)
is looked for again ``lag`` frames before and after, as :mod:`trap_core.robust.still` looks
for the background in a box: found again at most half as far from where the cluster's own
motion puts it as from where the camera's does, it goes with the cluster; the other way round,
it stays with the scene. A cluster whose anchors stay with the scene more often than they go
with it is background. Only decided cases count, so a slow object (both predictions close) or
one whose regions noise keeps remaking (found again nowhere) is not judged by them. The
camera's motion must be right for this: read from the images, it is within a tenth of a pixel
a frame on every benchmark scene (:mod:`trap_core.robust.image_steps`).
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from trap_core.clustering import core_regions, frame_face_sets
from trap_core.mining import MiningResult
from trap_core.rag import PlaneGraph
from trap_core.robust.still import found_again


def stays_with_scene(result: MiningResult, patterns: np.ndarray, positions: np.ndarray,
                     graphs: Sequence[PlaneGraph], transforms: np.ndarray, share: float, lag: int) -> bool:
    """Whether the cluster of ``patterns`` (spatio-temporal pattern ids of ``result``) is background:
    its anchors, ``lag`` frames before and after, stay with the scene more often than they go with it.

    Parameters
    ----------
    result : MiningResult
    patterns : (P,) int array
        The cluster's spatio-temporal patterns.
    positions : (n_frames, 2) array
        The cluster's mean path (NaN in frames it does not cover).
    graphs : sequence of PlaneGraph
        Plane graph of every frame of the video.
    transforms : (n_frames, 3, 3) array
        Camera motion, frame 0 to frame ``t`` (:func:`trap_core.robust.camera_transforms`).
    share : float
        ``core_share``: the anchor is found among the regions of the core boxes.
    lag : int
        Frames before and after where an anchor is looked for again; it is looked at in one frame
        of every ``lag`` (frames closer than that tell nearly the same, at ``lag`` times the cost).
    """
    with_cluster = with_scene = 0
    for frame, face_sets, lifetimes in frame_face_sets(result, patterns):
        if frame % lag or np.isnan(positions[frame]).any():  # frames closer than lag tell nearly the same
            continue
        anchor = core_regions(graphs[frame], face_sets, share, lifetimes)[1]
        for other in (frame - lag, frame + lag):
            if not 0 <= other < len(graphs) or np.isnan(positions[other]).any():
                continue
            near_cluster, near_scene = found_again(graphs, transforms, frame, other, anchor,
                                                   positions[other] - positions[frame])
            with_cluster += int((2 * near_cluster < near_scene).sum())
            with_scene += int((2 * near_scene < near_cluster).sum())
    return with_scene > with_cluster
