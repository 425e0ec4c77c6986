"""The faces a pattern is made of, and their canonical codes (TRAP_SPEC section 3).

A pattern is a connected set of inner faces of a frame's plane graph (faces that do not touch
the outside of the image), connected through shared edges. Its canonical code describes it up
to isomorphism of *plane* graphs: labels match and the embedding is respected, so a pattern
and its mirror image have different codes.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from trap_core.rag import PlaneGraph

# Token kinds of a traversal code; the order makes codes comparable as integer tuples.
_NEW_NODE, _SEEN_NODE, _FACE, _OPEN, _END = 0, 1, 2, 3, 4


@dataclass(frozen=True)
class FaceTable:
    """Inner faces of one frame: their half-edges and which faces share an edge."""

    graph: PlaneGraph
    inner: np.ndarray                # ids of the inner faces (graph face ids)
    neighbours: dict[int, tuple[int, ...]]  # inner face -> inner faces sharing an edge

    def nodes(self, faces: frozenset[int]) -> np.ndarray:
        """Graph nodes of a face set (sorted, unique)."""
        return np.unique(np.concatenate([self.graph.face_nodes(f) for f in faces]))


def face_table(graph: PlaneGraph) -> FaceTable:
    """Index the inner faces of ``graph`` (faces with at least three distinct nodes, off the border)."""
    outer = graph.outer_faces()
    inner = [f for f in range(graph.n_faces)
             if not outer[f] and np.unique(graph.face_nodes(f)).size >= 3]
    inner_set = set(inner)
    neighbours: dict[int, tuple[int, ...]] = {}
    for f in inner:
        ring = graph.face_half_edges[graph.face_offsets[f]:graph.face_offsets[f + 1]]
        across = {int(graph.face_of[graph.he_twin[h]]) for h in ring}
        neighbours[f] = tuple(sorted(g for g in across if g in inner_set and g != f))
    return FaceTable(graph, np.array(inner, dtype=np.int64), neighbours)


def _traversal_code(graph: PlaneGraph, faces: frozenset[int], start: int) -> tuple[int, ...]:
    """Code of ``faces`` read from half-edge ``start``: faces breadth first, each walked from
    the half-edge it was entered by; nodes numbered in order of first visit."""
    face_index = {int(graph.face_of[start]): 0}
    node_index: dict[int, int] = {}
    queue = [start]
    tokens: list[int] = []
    for entry in queue:
        h = entry
        while True:
            node = int(graph.he_origin[h])
            if node in node_index:
                tokens += (_SEEN_NODE, node_index[node])
            else:
                node_index[node] = len(node_index)
                tokens += (_NEW_NODE, int(graph.label[node]))
            twin = int(graph.he_twin[h])
            across = int(graph.face_of[twin])
            if across in faces:
                if across not in face_index:
                    face_index[across] = len(face_index)
                    queue.append(twin)
                tokens += (_FACE, face_index[across])
            else:
                tokens += (_OPEN, 0)
            h = int(graph.he_next[twin])
            if h == entry:
                break
        tokens += (_END, 0)
    return tuple(tokens)


def canonical_code(graph: PlaneGraph, faces: frozenset[int]) -> tuple[int, ...]:
    """The smallest traversal code over every starting half-edge of every face of the set."""
    best: tuple[int, ...] | None = None
    for f in faces:
        for h in graph.face_half_edges[graph.face_offsets[f]:graph.face_offsets[f + 1]]:
            code = _traversal_code(graph, faces, int(h))
            if best is None or code < best:
                best = code
    assert best is not None
    return best
