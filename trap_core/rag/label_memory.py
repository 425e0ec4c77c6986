"""Node labels that follow a region from frame to frame (ours).

A node's label is its mean colour cut into ``colour_bins`` levels per channel. When the light
changes slowly (clouds, a camera's automatic exposure), every colour drifts and, one after
another, regions cross a level boundary: their label flips, and every pattern holding them is
broken from that frame on. Here a region that continues one of the previous frame (its
barycentre within half the square root of its area plus 3 px, its area within a factor 1.5,
each colour channel within ``COLOUR_STEP`` of 256) keeps that region's label, so a label
changes only when a region appears, or when its colour jumps. Labels are passed on from the
previous frame's labels as kept, so a slow drift never flips one.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from scipy.spatial import cKDTree

from trap_core.rag.plane_graph import PlaneGraph

AREA_RATIO = 1.5
REACH_PX = 3.0
COLOUR_STEP = 16.0  # per frame and channel: light changes far more slowly, a different region more


class LabelMemory:
    """Call it on each frame's graph in order; it returns the graph with remembered labels."""

    def __init__(self) -> None:
        self._previous: PlaneGraph | None = None

    def __call__(self, graph: PlaneGraph) -> PlaneGraph:
        self._previous = self._remembered(graph)
        return self._previous

    def _remembered(self, graph: PlaneGraph) -> PlaneGraph:
        """``graph`` with the labels of the previous frame's regions it continues."""
        previous = self._previous
        if previous is None or graph.n_nodes == 0 or previous.n_nodes == 0:
            return graph
        distance, nearest = cKDTree(previous.centroid).query(graph.centroid, k=1)
        area = graph.area.astype(float)
        their_area = previous.area[nearest].astype(float)
        same = ((distance <= 0.5 * np.sqrt(area) + REACH_PX) & (their_area < AREA_RATIO * area)
                & (their_area * AREA_RATIO > area)
                & (np.abs(graph.colour - previous.colour[nearest]).max(axis=1) <= COLOUR_STEP))
        if not same.any():
            return graph
        label = graph.label.copy()
        label[same] = previous.label[nearest[same]]
        return dataclasses.replace(graph, label=label)
