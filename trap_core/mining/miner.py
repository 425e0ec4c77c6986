"""DYPLAGRAM_ST: frequent plane patterns of faces and their spatio-temporal patterns.

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

from trap_core.mining.errors import MiningError
from trap_core.mining.faces import FaceTable, canonical_code, face_table
from trap_core.rag import PlaneGraph


@dataclass(frozen=True)
class MiningParams:
    """Parameters of the miner, with the paper's defaults (eps 40 px, tau 25 frames, freq = freq_st)."""

    eps: float = 40.0
    tau: int = 25
    freq_st_min: int = 20
    freq_min: int | None = None  # None: equal to freq_st_min, as in the paper
    max_faces: int = 3

    def __post_init__(self) -> None:
        if not (np.isfinite(self.eps) and self.eps > 0):
            raise MiningError(f"eps must be a positive number of pixels, not {self.eps}")
        if self.tau < 1 or self.freq_st_min < 1 or self.max_faces < 1:
            raise MiningError("tau, freq_st_min and max_faces must be at least 1")
        if self.freq_min is not None and self.freq_min < 1:
            raise MiningError(f"freq_min must be at least 1, not {self.freq_min}")

    @property
    def frequency(self) -> int:
        return self.freq_st_min if self.freq_min is None else self.freq_min


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
class MiningResult:
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


def mine(graphs: Sequence[PlaneGraph], params: MiningParams, first_frame: int = 0) -> MiningResult:
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
    return MiningResult(codes, frequency, patterns)


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
