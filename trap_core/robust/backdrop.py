"""Over a plain scene (ours): the backdrop left out of occurrences, and clusters judged so.

Over sky, sea, asphalt or a smooth photograph one region, the backdrop
(:attr:`trap_core.rag.PlaneGraph.backdrop`), covers most of the view. Its barycentre stays near
the middle of the view and its box is the frame's wherever the camera goes. An object made of
one or two regions (a disc, a boat) has no face without it: every pattern on it holds the
backdrop, so it is seen cut by the view and moving partly with the camera, like the background.
Without the backdrop it is whole and moves. :func:`trap_core.pipeline.track` looks again at the
clusters that fail as they are but mostly hold the backdrop (:func:`held_share`): placed and
boxed without it (:func:`without_backdrop`), one is taken if it moves, is mostly whole, is
mostly made of patterns that move steadily (without the backdrop the specks of a textured
ground jitter), and no cluster that moves as it is already follows the same path
(:func:`shadowed`: objects with faces of their own have patterns that hold the backdrop too, and
those must not make second tracks). Such clusters are clustered again on their own, placed so.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from trap_core.clustering import ClusterSummary
from trap_core.mining import MiningResult
from trap_core.rag import StackedGraphs
from trap_core.robust._kernels import backdrop_free_geometry, near_paths

HELD_SHARE = 0.5  # a cluster with more of its occurrences holding the backdrop may be an object seen only through it
SHADOWED_SHARE = 0.5  # a cluster seen again without the backdrop is taken where at most this share of it is shadowed


def without_backdrop(result: MiningResult, graphs: StackedGraphs) -> MiningResult:
    """``result`` with each occurrence that holds the backdrop (:attr:`PlaneGraph.backdrop`) and
    other regions placed at the mean barycentre of the others and boxed around them
    (``result`` itself where no frame has a backdrop). ``graphs``: the video's, stacked.

    The backdrop's barycentre stays near the middle of the view and its box is the frame's,
    wherever the camera goes: where it is in, an occurrence's position moves partly with the
    view and its box reaches the image's edge whatever the rest does."""
    if not graphs.backdrop.any():
        return result
    position = result.occ_position.copy()
    box = result.occ_box.copy()
    backdrop_free_geometry(result.occ_frame, result.occ_faces, graphs.node_offsets, graphs.face_base,
                           graphs.face_offsets, graphs.face_half_edges, graphs.he_origin, graphs.centroid, graphs.bbox,
                           graphs.backdrop, position, box)
    return dataclasses.replace(result, occ_position=position, occ_box=box)


def shadowed(summary: ClusterSummary, clusters: np.ndarray, others: np.ndarray, reach: float) -> np.ndarray:
    """Per cluster of ``clusters``: the share of the frames it covers where one of ``others`` is
    seen too, its mean path within ``reach`` px (``summary`` holds both)."""
    near = near_paths(_dense_paths(summary, clusters), _dense_paths(summary, others), np.float32(reach))
    return near.sum(axis=1) / np.maximum(summary.covered[clusters].sum(axis=1), 1)


def _dense_paths(summary: ClusterSummary, clusters: np.ndarray) -> np.ndarray:
    """(len(clusters), n_frames, 2) the clusters' mean paths, NaN in the frames they do not cover."""
    dense = np.full((clusters.size, summary.covered.shape[1], 2), np.nan, dtype=np.float32)
    for k, cluster in enumerate(clusters):
        frames = np.flatnonzero(summary.covered[cluster])
        dense[k, frames] = summary.paths.at(int(cluster), frames)
    return dense


def held_share(result: MiningResult, free: MiningResult, patterns: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """(C,) share of each cluster's occurrences (``labels``: cluster of each of ``patterns``) that
    hold the backdrop and other regions: those :func:`without_backdrop` boxed anew (``free``)."""
    rows, owner = result.rows_of(patterns)
    held = np.any(free.occ_box[rows] != result.occ_box[rows], axis=1)
    n_clusters = int(labels.max()) + 1 if labels.size else 0
    return (np.bincount(labels[owner], weights=held, minlength=n_clusters)
            / np.maximum(np.bincount(labels[owner], minlength=n_clusters), 1))
