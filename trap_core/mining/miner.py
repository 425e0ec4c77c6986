"""DYPLAGRAM_ST, compiled: frequent plane patterns of faces and their spatio-temporal patterns.

TRAP_SPEC section 3. A pattern P (a connected set of at most ``max_faces`` inner faces) is
frequent when ``freq(P)``, the number of frames holding an occurrence, reaches ``freq_min``.
Occurrences are linked when they lie in different frames at most ``tau`` apart and within
``eps`` pixels; each connected component of that occurrence graph is a spatio-temporal
pattern, kept when it spans at least ``freq_st_min`` distinct frames (``freq_st_cut`` within
``tau`` of the first or last frame, ours: the video cut it). With
``linking="assignment"`` (ours) occurrences are chained one to one instead, so the
occurrences of look-alike objects that pass close to each other stay apart.

Exact: a pattern with an infrequent face cannot be frequent (freq is anti-monotone), so only
frequent faces are grown, and every frequent pattern is found. Patterns are identified by a
64-bit hash of their canonical code (a collision between two of the ~10^4 patterns of a video
has probability ~1e-11).
"""
from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from trap_core.mining._kernels import (assign_occurrences, enumerate_face_sets, face_adjacency, inner_faces,
                                       link_occurrences, occurrence_geometry, single_face_hashes)
from trap_core.mining.params import MiningParams
from trap_core.mining.result import MiningResult
from trap_core.ordered import in_order
from trap_core.rag import PlaneGraph


def _frame_singles(graph: PlaneGraph) -> tuple[np.ndarray, np.ndarray]:
    inner = inner_faces(graph.he_origin, graph.face_half_edges, graph.face_offsets, graph.outside)
    hashes = single_face_hashes(graph.he_origin, graph.he_twin, graph.he_next, graph.face_of,
                                graph.face_half_edges, graph.face_offsets, graph.label, inner)
    return inner, hashes


def _face_sets(graph: PlaneGraph, inner: np.ndarray, hashes: np.ndarray, frequent_faces: np.ndarray,
               max_faces: int) -> tuple[np.ndarray, np.ndarray]:
    """Code hashes and faces (-1 padded) of every connected set of at most ``max_faces`` of
    ``graph``'s inner faces that are frequent alone (``hashes``: each face's alone)."""
    allowed = inner & np.isin(hashes, frequent_faces)
    adj_offsets, adj_targets = face_adjacency(graph.he_twin, graph.face_of, graph.face_half_edges, graph.face_offsets,
                                              allowed)
    set_hashes, sets = enumerate_face_sets(max_faces, allowed, adj_offsets, adj_targets, graph.he_origin,
                                           graph.he_twin, graph.he_next, graph.face_of, graph.face_half_edges,
                                           graph.face_offsets, graph.label, hashes)
    return set_hashes, sets.astype(np.int32)


def _frequent_occurrences(graph: PlaneGraph, set_hashes: np.ndarray, sets: np.ndarray, pattern_hash: np.ndarray
                          ) -> tuple[np.ndarray, ...]:
    """The face sets of one frame that are occurrences of frequent patterns (``pattern_hash``):
    their hashes, faces, positions, region boxes and node boxes."""
    kept = np.isin(set_hashes, pattern_hash)
    sets = sets[kept]
    position, box, node_box = occurrence_geometry(sets, graph.he_origin, graph.face_half_edges, graph.face_offsets,
                                                  graph.centroid, graph.bbox, np.zeros(0, dtype=np.bool_))
    return set_hashes[kept], sets, position, box.astype(np.float32), node_box.astype(np.float32)


def _frequent(per_frame_hashes: list[np.ndarray], minimum: int) -> tuple[np.ndarray, np.ndarray]:
    """Hashes occurring in at least ``minimum`` distinct frames, and their frame counts
    (``per_frame_hashes[i]``: the hashes seen in frame i, each once)."""
    values, counts = np.unique(np.concatenate(per_frame_hashes) if per_frame_hashes else np.empty(0, np.int64),
                               return_counts=True)
    keep = counts >= minimum
    return values[keep], counts[keep]


def mine(graphs: Sequence[PlaneGraph], params: MiningParams, first_frame: int = 0,
         on_frame: Callable[[int], None] | None = None, open_ends: tuple[int, int] = (0, 0)) -> MiningResult:
    """Mine the spatio-temporal patterns of consecutive frames' plane graphs.

    Parameters
    ----------
    graphs : sequence of PlaneGraph
        Frame ``first_frame + i`` is ``graphs[i]``.
    params : MiningParams
        ``eps``, ``tau``, ``freq_min``, ``freq_st_min``, ``max_faces``; ``threads`` frames are
        enumerated at once (the result is the same for any number).
    on_frame : callable, optional
        Called with the number of frames enumerated so far (progress).
    open_ends : (int, int)
        Components with an occurrence in the first ``open_ends[0]`` or the last
        ``open_ends[1]`` frames are kept whatever their ``freq_st``: they may continue in a
        neighbouring window (:mod:`trap_core.mining.windows`).

    Returns
    -------
    MiningResult
    """
    with ThreadPoolExecutor(params.threads, thread_name_prefix="trap-mine") as pool:
        singles = list(in_order(pool, _frame_singles, ((graph,) for graph in graphs), params.threads))
        frequent_faces, _ = _frequent([np.unique(h[inner]) for inner, h in singles], params.frequency)
        chunks = []
        for chunk in in_order(pool, _face_sets, ((graph, *single, frequent_faces, params.max_faces)
                                                  for graph, single in zip(graphs, singles)), params.threads):
            chunks.append(chunk)
            if on_frame:
                on_frame(len(chunks))
        pattern_hash, pattern_frequency = _frequent([np.unique(h) for h, _ in chunks], params.frequency)

        def frame_sets() -> Iterator[tuple]:
            """Each frame's face sets, let go as they are handed out: the unfiltered face sets
            are the largest temporary."""
            for index, graph in enumerate(graphs):
                yield graph, *chunks[index], pattern_hash
                chunks[index] = None

        kept = list(in_order(pool, _frequent_occurrences, frame_sets(), params.threads))
    hashes_list, faces_list, position_list, box_list, node_box_list = ([row[k] for row in kept] for k in range(5))
    frames_list = [np.full(sets.shape[0], index, dtype=np.int64) for index, sets in enumerate(faces_list)]
    del kept
    frames = np.concatenate(frames_list) if frames_list else np.empty(0, np.int64)
    hashes = np.concatenate(hashes_list) if hashes_list else np.empty(0, np.int64)
    occ_faces = np.concatenate(faces_list) if faces_list else np.empty((0, params.max_faces), np.int32)
    position = np.concatenate(position_list) if position_list else np.empty((0, 2))
    box = np.concatenate(box_list) if box_list else np.empty((0, 4), np.float32)
    node_box = np.concatenate(node_box_list) if node_box_list else np.empty((0, 4), np.float32)
    del frames_list, hashes_list, faces_list, position_list, box_list, node_box_list
    pattern = np.searchsorted(pattern_hash, hashes)
    order = np.lexsort((frames, pattern))
    starts = np.searchsorted(pattern[order], np.arange(pattern_hash.size + 1))
    if params.linking == "assignment":
        extent = (np.maximum(box[:, 2] - box[:, 0], box[:, 3] - box[:, 1]) + 1).astype(np.float64)
        component = assign_occurrences(starts, frames[order], position[order], extent[order], float(params.eps),
                                       int(params.tau), float(params.reach))
    else:
        component = link_occurrences(starts, frames[order], position[order], float(params.eps), int(params.tau))
    open_after = len(graphs) - open_ends[1] if open_ends[1] > 0 else len(graphs)
    st_pattern, st_offsets, st_rows = _components(component, pattern[order], frames[order], order, params,
                                                  len(graphs), (open_ends[0], open_after))
    pattern_faces = np.zeros(pattern_hash.size, dtype=np.int64)
    pattern_faces[pattern] = (occ_faces >= 0).sum(axis=1)
    # Keep only the occurrences of kept spatio-temporal patterns.
    used = np.unique(st_rows)
    return MiningResult(pattern_hash, pattern_frequency, pattern_faces, (frames[used] + first_frame).astype(np.int32),
                        pattern[used].astype(np.int32), position[used].astype(np.float32), box[used],
                        node_box[used], occ_faces[used], st_pattern, st_offsets,
                        np.searchsorted(used, st_rows).astype(np.int32))


def _components(component: np.ndarray, pattern: np.ndarray, frames: np.ndarray, rows: np.ndarray,
                params: MiningParams, n_frames: int,
                open_frames: tuple[int, int]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Group sorted occurrences by component root; keep components spanning enough frames
    (:meth:`MiningParams.frequent_enough` over ``n_frames``), or reaching before
    ``open_frames[0]`` or from ``open_frames[1]`` on."""
    if component.size == 0:
        return np.empty(0, np.int64), np.zeros(1, np.int64), np.empty(0, np.int64)
    order = np.lexsort((frames, component))
    root = component[order]
    bounds = np.flatnonzero(np.r_[True, root[1:] != root[:-1], True])
    sorted_frames = frames[order]
    distinct = np.r_[True, (root[1:] != root[:-1]) | (sorted_frames[1:] != sorted_frames[:-1])]
    frames_per = np.add.reduceat(distinct.astype(np.int64), bounds[:-1])
    first, last = sorted_frames[bounds[:-1]], sorted_frames[bounds[1:] - 1]
    kept = params.frequent_enough(frames_per, first, last, n_frames) | (first < open_frames[0]) | (last >= open_frames[1])
    keep = np.flatnonzero(kept)
    offsets = np.r_[0, np.cumsum(bounds[keep + 1] - bounds[keep])].astype(np.int64)
    picked = order[np.repeat(kept, np.diff(bounds))]
    return pattern[order[bounds[keep]]], offsets, rows[picked]
