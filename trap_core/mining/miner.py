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

from collections.abc import Callable, Sequence

import numpy as np

from trap_core.mining._kernels import (assign_occurrences, enumerate_face_sets, face_adjacency, inner_faces,
                                       link_occurrences, occurrence_geometry, single_face_hashes)
from trap_core.mining.params import MiningParams
from trap_core.mining.result import MiningResult
from trap_core.rag import PlaneGraph


def _frame_singles(graph: PlaneGraph) -> tuple[np.ndarray, np.ndarray]:
    inner = inner_faces(graph.he_origin, graph.face_half_edges, graph.face_offsets, graph.outside)
    hashes = single_face_hashes(graph.he_origin, graph.he_twin, graph.he_next, graph.face_of,
                                graph.face_half_edges, graph.face_offsets, graph.label, inner)
    return inner, hashes


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
        ``eps``, ``tau``, ``freq_min``, ``freq_st_min``, ``max_faces``.
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
    singles = [_frame_singles(graph) for graph in graphs]
    frequent_faces, _ = _frequent([np.unique(h[inner]) for inner, h in singles], params.frequency)
    chunks = []
    for index, (graph, (inner, hashes)) in enumerate(zip(graphs, singles)):
        allowed = inner & np.isin(hashes, frequent_faces)
        adj_offsets, adj_targets = face_adjacency(graph.he_twin, graph.face_of, graph.face_half_edges,
                                                  graph.face_offsets, allowed)
        set_hashes, sets = enumerate_face_sets(params.max_faces, allowed, adj_offsets, adj_targets,
                                               graph.he_origin, graph.he_twin, graph.he_next, graph.face_of,
                                               graph.face_half_edges, graph.face_offsets, graph.label, hashes)
        chunks.append((set_hashes, sets.astype(np.int32)))
        if on_frame:
            on_frame(index + 1)
    pattern_hash, pattern_frequency = _frequent([np.unique(h) for h, _ in chunks], params.frequency)
    frames_list, hashes_list, faces_list, position_list, box_list, node_box_list = [], [], [], [], [], []
    for index, (set_hashes, sets) in enumerate(chunks):
        kept = np.isin(set_hashes, pattern_hash)
        sets = sets[kept]
        position, box, node_box = occurrence_geometry(sets, graphs[index].he_origin, graphs[index].face_half_edges,
                                                      graphs[index].face_offsets, graphs[index].centroid,
                                                      graphs[index].bbox, np.zeros(0, dtype=np.bool_))
        frames_list.append(np.full(sets.shape[0], index, dtype=np.int64))
        hashes_list.append(set_hashes[kept])
        faces_list.append(sets)
        position_list.append(position)
        box_list.append(box.astype(np.float32))
        node_box_list.append(node_box.astype(np.float32))
        chunks[index] = None  # the unfiltered face sets are the largest temporary: free them as we go
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
