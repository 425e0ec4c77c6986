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

import numpy as np

from trap_core.clustering import Trajectories, frame_cores
from trap_core.mining import MiningResult
from trap_core.rag import StackedGraphs
from trap_core.robust._kernels import anchors_found_again
from trap_core.robust.camera import camera_moves
from trap_core.robust.still import AREA_FACTOR


def stays_with_scene(result: MiningResult, patterns: np.ndarray, positions: np.ndarray,
                     graphs: StackedGraphs, transforms: np.ndarray, share: float, lag: int) -> bool:
    """Whether the cluster of ``patterns`` (spatio-temporal pattern ids of ``result``) is background:
    its anchors, ``lag`` frames before and after, stay with the scene more often than they go with it.

    Parameters
    ----------
    result : MiningResult
    patterns : (P,) int array
        The cluster's spatio-temporal patterns.
    positions : (n_frames, 2) array
        The cluster's mean path (NaN in frames it does not cover).
    graphs : StackedGraphs
        Plane graph of every frame of the video, stacked.
    transforms : (n_frames, 3, 3) array
        Camera motion, frame 0 to frame ``t`` (:func:`trap_core.robust.camera_transforms`).
    share : float
        ``core_share``: the anchor is found among the regions of the core boxes.
    lag : int
        Frames before and after where an anchor is looked for again; it is looked at in one frame
        of every ``lag`` (frames closer than that tell nearly the same, at ``lag`` times the cost).

    Returns
    -------
    bool
        Read in one compiled pass (:func:`trap_core.robust._kernels.anchors_found_again`) from
        the cluster's core regions in every frame (:func:`trap_core.clustering.frame_cores`).
    """
    cores = frame_cores(result, patterns, graphs, share)
    frames = cores.frames.astype(np.int64)
    with_cluster, with_scene = anchors_found_again(
        graphs.node_offsets, graphs.centroid, graphs.area, graphs.label, frames, cores.top, cores.top_ends,
        np.asarray(positions, dtype=np.float64), camera_moves(transforms, frames, lag), lag, AREA_FACTOR)
    return with_scene > with_cluster


def scene_patterns(result: MiningResult, patterns: np.ndarray, paths: Trajectories, n_frames: int,
                   graphs: StackedGraphs, transforms: np.ndarray, share: float, lag: int) -> np.ndarray:
    """(P,) bool: which of a selected cluster's ``patterns`` are background on their own, by the
    test :func:`stays_with_scene` makes of a whole cluster: their own anchors stay with the
    scene more often than they go with them. A cluster that moves as a whole can still hold a
    few chains of noise structures that its object's patterns passed near (cells under noise:
    two such patterns, mid-view while the object was out of view, gave its track 45 frames of
    background); their boxes are not the object's. ``paths``: the patterns' trajectories, in
    the order of ``patterns``, over a video of ``n_frames``."""
    frames = np.arange(n_frames)
    return np.array([stays_with_scene(result, patterns[k:k + 1], paths.dense(np.array([k]), frames)[0], graphs,
                                      transforms, share, lag) for k in range(patterns.size)], dtype=bool)
