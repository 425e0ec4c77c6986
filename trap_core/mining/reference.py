"""Readable reference miner (pure Python): the compiled miner is tested against it, and it
against a brute-force oracle. Slow; use :func:`trap_core.mining.mine`.

DYPLAGRAM_ST: frequent plane patterns of faces and their spatio-temporal patterns.

TRAP_SPEC section 3. A pattern P (a connected set of faces, up to ``max_faces``) is frequent
when ``freq(P)``, the number of frames holding an occurrence, reaches ``freq_min``. Its
occurrences are linked when they are in different frames at most ``tau`` apart and their
positions are at most ``eps`` pixels apart; each connected component of that occurrence graph
is a spatio-temporal pattern, kept when it spans at least ``freq_st_min`` distinct frames.
"""
from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree

from trap_core.mining.params import MiningParams
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
        return self.graph.faces_nodes(faces)


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


@dataclass(frozen=True)
class Occurrences:
    """Occurrences of one pattern: parallel arrays, one row per occurrence."""

    frame: np.ndarray     # (k,) int: frame index
    position: np.ndarray  # (k, 2) float: mean barycentre of the occurrence's nodes (x, y)
    box: np.ndarray       # (k, 4) float: x0, y0, x1, y1 of the nodes' regions (inclusive)
    nodes: tuple[tuple[int, ...], ...]  # graph nodes of each occurrence in its frame

    def subset(self, rows: np.ndarray) -> Occurrences:
        return Occurrences(self.frame[rows], self.position[rows], self.box[rows],
                           tuple(self.nodes[i] for i in rows))


@dataclass(frozen=True)
class SpatioTemporalPattern:
    """A connected component of a pattern's occurrence graph."""

    pattern: int                  # index of the plane pattern P in :attr:`MiningResult.codes`
    occurrences: Occurrences

    @property
    def freq_st(self) -> int:
        """Number of distinct frames of the component."""
        return int(np.unique(self.occurrences.frame).size)


@dataclass(frozen=True)
class ReferenceResult:
    codes: list[tuple[int, ...]]       # canonical code of each frequent plane pattern
    frequency: list[int]               # freq(P) of each
    patterns: list[SpatioTemporalPattern]


def connected_face_sets(table: FaceTable, allowed: set[int], max_faces: int) -> Iterator[frozenset[int]]:
    """Every connected set of at most ``max_faces`` allowed faces, each exactly once (ESU order)."""
    neighbours = {f: tuple(g for g in table.neighbours[f] if g in allowed) for f in allowed}
    for root in sorted(allowed):
        yield from _grow(frozenset([root]), {g for g in neighbours[root] if g > root}, root, neighbours,
                         max_faces, {root, *neighbours[root]})


def _grow(current: frozenset[int], extension: set[int], root: int, neighbours: dict[int, tuple[int, ...]],
          max_faces: int, closed: set[int]) -> Iterator[frozenset[int]]:
    yield current
    if len(current) == max_faces:
        return
    extension = set(extension)
    while extension:
        face = extension.pop()
        fresh = {g for g in neighbours[face] if g > root and g not in closed}
        yield from _grow(current | {face}, extension | fresh, root, neighbours, max_faces,
                         closed | set(neighbours[face]))


def _occurrence_row(table: FaceTable, faces: frozenset[int]) -> tuple[tuple[int, ...], np.ndarray, np.ndarray]:
    nodes = table.nodes(faces)
    graph = table.graph
    position = graph.centroid[nodes].mean(axis=0)
    boxes = graph.bbox[nodes]
    box = np.array([boxes[:, 0].min(), boxes[:, 1].min(), boxes[:, 2].max(), boxes[:, 3].max()], dtype=float)
    return tuple(int(n) for n in nodes), position, box


def mine_reference(graphs: Sequence[PlaneGraph], params: MiningParams, first_frame: int = 0) -> ReferenceResult:
    """Mine the spatio-temporal patterns of a sequence of plane graphs (frame i = ``first_frame + i``).

    Exact: every plane pattern with ``freq >= freq_min`` is found (a pattern with an
    infrequent face cannot be frequent, so only frequent faces are grown), and every
    component of its occurrence graph with ``freq_st >= freq_st_min`` is returned.
    """
    tables = [face_table(g) for g in graphs]
    single_frames: dict[tuple[int, ...], set[int]] = defaultdict(set)
    single_code: list[dict[int, tuple[int, ...]]] = []
    for index, table in enumerate(tables):
        codes = {int(f): canonical_code(table.graph, frozenset([int(f)])) for f in table.inner}
        single_code.append(codes)
        for code in codes.values():
            single_frames[code].add(index)
    frequent_single = {c for c, frames in single_frames.items() if len(frames) >= params.frequency}
    found: dict[tuple[int, ...], list[tuple[int, frozenset[int]]]] = defaultdict(list)
    for index, table in enumerate(tables):
        allowed = {f for f, c in single_code[index].items() if c in frequent_single}
        for faces in connected_face_sets(table, allowed, params.max_faces):
            code = single_code[index][next(iter(faces))] if len(faces) == 1 else canonical_code(table.graph, faces)
            found[code].append((index, faces))
    codes, frequency, patterns = [], [], []
    for code in sorted(found):
        hits = found[code]
        freq = len({index for index, _ in hits})
        if freq < params.frequency:
            continue
        rows = [_occurrence_row(tables[index], faces) for index, faces in hits]
        occurrences = Occurrences(np.array([first_frame + index for index, _ in hits], dtype=np.int64),
                                  np.array([r[1] for r in rows]), np.array([r[2] for r in rows]),
                                  tuple(r[0] for r in rows))
        pattern_id = len(codes)
        codes.append(code)
        frequency.append(freq)
        for component in occurrence_components(occurrences, params.eps, params.tau):
            st = SpatioTemporalPattern(pattern_id, occurrences.subset(component))
            if st.freq_st >= params.freq_st_min:
                patterns.append(st)
    return ReferenceResult(codes, frequency, patterns)


def occurrence_components(occurrences: Occurrences, eps: float, tau: int) -> list[np.ndarray]:
    """Rows of each connected component of the occurrence graph (TRAP_SPEC section 3).

    Two occurrences are linked when ``0 < |t1 - t2| <= tau`` and their positions are at
    most ``eps`` apart.
    """
    count = occurrences.frame.size
    pairs = cKDTree(occurrences.position).query_pairs(eps, output_type="ndarray")
    if pairs.size:
        gap = np.abs(occurrences.frame[pairs[:, 0]] - occurrences.frame[pairs[:, 1]])
        pairs = pairs[(gap > 0) & (gap <= tau)]
    adjacency = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(count, count)) \
        if len(pairs) else coo_matrix((count, count))
    n_components, component = connected_components(adjacency, directed=False)
    order = np.argsort(component, kind="stable")
    bounds = np.searchsorted(component[order], np.arange(n_components + 1))
    return [order[bounds[i]:bounds[i + 1]] for i in range(n_components)]
