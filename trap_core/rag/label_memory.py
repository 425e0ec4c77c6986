"""Node labels that follow a region from frame to frame, and the light (ours).

A node's label is its mean colour cut into ``colour_bins`` levels per channel. When the light
changes slowly (clouds, a camera's automatic exposure), every colour drifts and, one after
another, regions cross a level boundary: their label flips, and every pattern holding them is
broken from that frame on. Here a region that continues one of the previous frame (its
barycentre within half the square root of its area plus 3 px, its area within a factor 1.5,
each colour channel within ``COLOUR_STEP`` of 256) keeps that region's label, so a label
changes only when a region appears, or when its colour jumps.

A region that appears (an object entering the view, or coming back) is labelled from its colour
under the light of the first frame: each region carries its colour divided by the light's gain
when it appeared, and the gain of a frame (per channel) is the median, over the regions it
continues, of their colour over that carried colour (kept while within 1 % of the last one, so
noise does not move the labels of regions that appear). The gain is measured against colours
carried since regions appeared, not multiplied frame to frame, so its error does not
accumulate while the scene stays; an object seen again under other light gets its former
labels back, and its patterns are the same structures (what rejoining fragments needs).
Where the camera moves, regions come and go and those that appear are carried under a gain
that lags the light by up to 1 %: the error then grows (README, label memory;
``benchmarks/label_gain.py``).
"""
from __future__ import annotations

import dataclasses

import numpy as np
from scipy.spatial import cKDTree

from trap_core.rag._kernels import remembered_labels
from trap_core.rag.plane_graph import PlaneGraph

AREA_RATIO = 1.5
REACH_PX = 3.0
COLOUR_STEP = 16.0  # per frame and channel: light changes far more slowly, a different region more
STEADY = 0.01  # a gain within 1 % of the current one is noise, not a change of the light
DARK = 16.0  # channels darker than this say little about the gain (noise, clipping)


class LabelMemory:
    """Call it on each frame's graph in order; it returns the graph with remembered labels.

    ``colour_bins``: levels per channel of the labels (as the graphs were built with).
    """

    def __init__(self, colour_bins: int = 4) -> None:
        self._bins = colour_bins
        self._previous: PlaneGraph | None = None
        self._carried = np.empty((0, 3))  # per region of the previous graph: its colour under the first light
        self.gain = np.ones(3)

    def __call__(self, graph: PlaneGraph) -> PlaneGraph:
        previous = self._previous
        distance, nearest = np.zeros(0), np.zeros(0, dtype=np.int64)
        if previous is not None and graph.n_nodes and previous.n_nodes:
            distance, nearest = cKDTree(previous.centroid).query(graph.centroid, k=1)
        if previous is None:
            previous = graph  # nothing is matched to it
        label, carried, self.gain = remembered_labels(
            graph.colour.astype(float), graph.area.astype(float), distance, nearest.astype(np.int64),
            previous.colour.astype(float), previous.area.astype(float), self._carried, previous.label.astype(np.int64),
            self.gain, self._bins, REACH_PX, AREA_RATIO, COLOUR_STEP, STEADY, DARK)
        graph = dataclasses.replace(graph, label=label)
        self._previous, self._carried = graph, carried
        return graph
