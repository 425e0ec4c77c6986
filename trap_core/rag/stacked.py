"""Every frame's plane graph stacked into flat arrays, for compiled kernels that read many frames
in one call (a track's boxes in every frame it covers) instead of one Python call per frame."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from trap_core.rag._kernels import stacked_nodes_boxes
from trap_core.rag.plane_graph import PlaneGraph, edge_line_limits


@dataclass(frozen=True)
class StackedGraphs:
    """The plane graphs of a video's frames, one frame's after the other's.

    Frame ``t``'s regions are rows ``node_offsets[t]:node_offsets[t + 1]`` of the region arrays
    (each a :class:`PlaneGraph` attribute of that name, ``nearest_in_colour`` and ``by_place``
    numbered within the frame). Its faces are ``face_base[t]:face_base[t + 1]`` of
    ``face_offsets``, which point into ``face_half_edges``, which point into ``he_origin``: a
    frame's face ``f`` is face ``face_base[t] + f`` here, and its nodes are numbered within the
    frame. Made once per video: a video of look-alikes has hundreds of clusters whose tracks
    read every frame's regions.
    """

    node_offsets: np.ndarray  # (n_frames + 1,)
    bbox: np.ndarray
    centroid: np.ndarray
    area: np.ndarray
    label: np.ndarray
    colour: np.ndarray
    backdrop: np.ndarray
    thickness: np.ndarray
    nearest_in_colour: np.ndarray
    by_place: np.ndarray      # each frame's regions ordered by label, then x: look-alikes side by side, by place
    face_base: np.ndarray     # (n_frames + 1,)
    face_offsets: np.ndarray  # (faces + 1,)
    face_half_edges: np.ndarray
    he_origin: np.ndarray

    @classmethod
    def of(cls, graphs: Sequence[PlaneGraph]) -> StackedGraphs:
        """The plane graphs ``graphs`` of every frame, stacked."""
        def stacked(name: str) -> np.ndarray:
            return np.concatenate([getattr(g, name) for g in graphs])

        def starts(sizes: list[int]) -> np.ndarray:
            return np.r_[0, np.cumsum(sizes)].astype(np.int64)

        half_edge_base = starts([g.he_origin.size for g in graphs])
        listed_base = starts([g.face_half_edges.size for g in graphs])
        face_base = starts([g.face_offsets.size - 1 for g in graphs])
        face_offsets = np.concatenate([g.face_offsets[:-1] + base for g, base in zip(graphs, listed_base)]
                                      + [listed_base[-1:]]).astype(np.int64)
        face_half_edges = np.concatenate([g.face_half_edges + base for g, base in zip(graphs, half_edge_base)])
        return cls(starts([g.n_nodes for g in graphs]), stacked("bbox"), stacked("centroid"), stacked("area"),
                   stacked("label"), stacked("colour"), stacked("backdrop"), stacked("thickness"),
                   stacked("nearest_in_colour"),
                   np.concatenate([np.lexsort((g.centroid[:, 0], g.label)) for g in graphs]).astype(np.int64), face_base,
                   face_offsets, face_half_edges.astype(np.int64), stacked("he_origin").astype(np.int64))

    def __len__(self) -> int:
        """Frames."""
        return self.node_offsets.size - 1

    def nodes_boxes(self, frames: np.ndarray, nodes: np.ndarray, ends: np.ndarray, pixel: float = 0.0) -> np.ndarray:
        """(K, 4) :meth:`PlaneGraph.nodes_box` of each of ``frames`` around its nodes
        ``nodes[ends[k - 1]:ends[k]]`` (numbered within the frame), edge lines left out as there
        with ``pixel``."""
        return stacked_nodes_boxes(self.node_offsets, self.bbox, self.thickness, self.nearest_in_colour,
                                   np.asarray(frames, dtype=np.int64), np.asarray(nodes, dtype=np.int64),
                                   np.asarray(ends, dtype=np.int64), *edge_line_limits(pixel))
