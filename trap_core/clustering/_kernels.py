"""Compiled kernels (numba) of the pattern distance (all pairs, only over shared frames) and of a
track's core regions in each frame (its place among the occurrences, the regions most held)."""
from __future__ import annotations

import numba as nb
import numpy as np

from trap_core.mining._kernels import _root  # union-find root with path halving, shared with occurrence linking
from trap_core.rag._kernels import _grow, nodes_box, stacked_sets_nodes


@nb.njit(cache=True, nogil=True)
def pairwise_distance(start: np.ndarray, end: np.ndarray, offsets: np.ndarray, points: np.ndarray, first: int,
                      last: int, out: np.ndarray) -> None:
    """Rows ``first..last - 1`` of the condensed matrix ``out`` of d(A, B) = d_traj * (2 - d_ov)
    (TRAP_SPEC section 5), inf where two trajectories share fewer than two frames: the pairs
    (a, b > a) for a in that range, in place. Each pair's value is computed on its own, so
    bands of rows filled on several threads give the same matrix as one pass.

    Trajectory i covers frames ``start[i]..end[i]``; its points are
    ``points[offsets[i]:offsets[i + 1]]`` (one per frame, gaps already interpolated).
    """
    n = start.size
    k = first * (2 * n - first - 1) // 2  # pairs in the rows before ``first``
    for a in range(first, last):
        for b in range(a + 1, n):
            fs = max(start[a], start[b])
            fe = min(end[a], end[b])
            if fe - fs <= 0:
                out[k] = np.inf
            else:
                total = 0.0
                pa = offsets[a] + fs - start[a]
                pb = offsets[b] + fs - start[b]
                for t in range(fe - fs + 1):
                    dx = points[pa + t, 0] - points[pb + t, 0]
                    dy = points[pa + t, 1] - points[pb + t, 1]
                    total += np.sqrt(dx * dx + dy * dy)
                overlap = (fe - fs + 1) / (max(end[a], end[b]) - min(start[a], start[b]) + 1)
                out[k] = total / (fe - fs + 1) * (2.0 - overlap)
            k += 1


@nb.njit(cache=True, nogil=True)
def interpolate_samples(frames: np.ndarray, points: np.ndarray, bounds: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Offsets and points of one trajectory per sample ``frames[bounds[i]:bounds[i + 1]]``
    (sorted, distinct, at least one) with ``points`` (k, 2) there: every frame of its span,
    linearly interpolated between samples (TRAP_SPEC section 4). Written as ``np.interp``
    computes it (the sample's own value on a sample frame, else ``slope * (x - x0) + y0``), so
    both give the same bits."""
    n = bounds.size - 1
    offsets = np.zeros(n + 1, dtype=np.int64)
    for i in range(n):
        offsets[i + 1] = offsets[i] + frames[bounds[i + 1] - 1] - frames[bounds[i]] + 1
    out = np.empty((offsets[n], 2))
    for i in range(n):
        first = frames[bounds[i]]
        out[offsets[i]] = points[bounds[i]]
        for j in range(bounds[i], bounds[i + 1] - 1):
            x0, x1 = float(frames[j]), float(frames[j + 1])
            for axis in range(2):
                slope = (points[j + 1, axis] - points[j, axis]) / (x1 - x0)
                for frame in range(frames[j] + 1, frames[j + 1]):
                    out[offsets[i] + frame - first, axis] = slope * (frame - x0) + points[j, axis]
            out[offsets[i] + frames[j + 1] - first] = points[j + 1]
    return offsets, out


@nb.njit(cache=True, nogil=True)
def cluster_sums(labels: np.ndarray, start: np.ndarray, end: np.ndarray, offsets: np.ndarray, points: np.ndarray,
                 n_clusters: int, n_frames: int) -> tuple[np.ndarray, np.ndarray]:
    """Per cluster and frame: the sum of its patterns' points and how many are summed (patterns
    added in index order)."""
    sums = np.zeros((n_clusters, n_frames, 2))
    counts = np.zeros((n_clusters, n_frames), dtype=np.int64)
    for pattern in range(labels.size):
        cluster = labels[pattern]
        for frame in range(start[pattern], end[pattern] + 1):
            row = offsets[pattern] + frame - start[pattern]
            sums[cluster, frame, 0] += points[row, 0]
            sums[cluster, frame, 1] += points[row, 1]
            counts[cluster, frame] += 1
    return sums, counts


@nb.njit(cache=True, nogil=True)
def sharing_components(nodes: np.ndarray, ends: np.ndarray, n_nodes: int) -> np.ndarray:
    """Component (numbered 0.. in the order of each one's root set) of each set of nodes (set
    ``i`` is ``nodes[ends[i - 1]:ends[i]]``), sets that share a node being linked: the places
    of one frame's occurrences (:func:`trap_core.clustering.one_place`)."""
    n_sets = ends.size
    first_holder = np.full(n_nodes, -1, dtype=np.int64)
    parent = np.arange(n_sets)
    start = 0
    for item in range(n_sets):
        for j in range(start, ends[item]):
            node = nodes[j]
            if first_holder[node] < 0:
                first_holder[node] = item
            parent[_root(parent, item)] = _root(parent, first_holder[node])
        start = ends[item]
    is_root = np.zeros(n_sets, dtype=np.int64)
    roots = np.empty(n_sets, dtype=np.int64)
    for item in range(n_sets):
        roots[item] = _root(parent, item)
        is_root[roots[item]] = 1
    number = np.cumsum(is_root) - 1
    return number[roots]


@nb.njit(cache=True, nogil=True)
def most_held(nodes: np.ndarray, share: float, weights: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Nodes held by at least ``share`` times the weight of the most held node (and at least 1),
    and the most held ones; ``nodes`` are the sets' nodes one set after the other (each set's
    distinct), ``weights`` what each entry counts (its set's lifetime, or 1)."""
    seen = np.zeros(nodes.max() + 1)
    for i in range(nodes.size):
        seen[nodes[i]] += weights[i]
    top = seen.max()
    return np.flatnonzero(seen >= max(share * top, 1.0)), np.flatnonzero(seen == top)


@nb.njit(cache=True, nogil=True)
def place_kept(nodes: np.ndarray, ends: np.ndarray, lifetimes: np.ndarray, share: float, n_nodes: int,
               bbox: np.ndarray) -> np.ndarray:
    """Mask of the node sets (``nodes[ends[i - 1]:ends[i]]``) in the track's place
    (:func:`trap_core.clustering.one_place`): sets sharing a node are one place, places whose
    core boxes (``bbox`` of the nodes in ``share`` of their sets) are closer than half the
    smaller box's larger side one thing; the place of the most ``lifetimes`` is kept."""
    place = sharing_components(nodes, ends, n_nodes + 1)
    n_places = place.max() + 1
    if n_places == 1:
        return np.ones(ends.size, dtype=np.bool_)
    boxes = np.empty((n_places, 4))
    no_box, no_thickness, no_nearest = np.zeros(0), np.zeros(0, dtype=np.float32), np.zeros(0, dtype=np.int32)
    for p in range(n_places):
        held = np.empty(nodes.size, dtype=nodes.dtype)
        count = 0
        start = 0
        for item in range(ends.size):
            if place[item] == p:
                held[count:count + ends[item] - start] = nodes[start:ends[item]]
                count += ends[item] - start
            start = ends[item]
        core = most_held(held[:count], share, np.ones(count))[0]
        boxes[p] = nodes_box(bbox, no_thickness, no_nearest, core, no_box, 0.0, 0.0)
    parent = np.arange(n_places)
    for a in range(n_places):
        for b in range(a + 1, n_places):
            gap = max(boxes[a, 0] - boxes[b, 0] - boxes[b, 2], boxes[b, 0] - boxes[a, 0] - boxes[a, 2],
                      boxes[a, 1] - boxes[b, 1] - boxes[b, 3], boxes[b, 1] - boxes[a, 1] - boxes[a, 3])
            if gap < min(max(boxes[a, 2], boxes[a, 3]), max(boxes[b, 2], boxes[b, 3])) / 2:
                to = _root(parent, b)
                parent[_root(parent, a)] = to
    roots = np.empty(n_places, dtype=np.int64)
    for p in range(n_places):
        roots[p] = _root(parent, p)
    thing = np.searchsorted(np.unique(roots), roots)[place]  # numbered in the order of their roots
    if thing.max() == 0:
        return np.ones(ends.size, dtype=np.bool_)
    total = np.zeros(thing.max() + 1)
    for item in range(ends.size):
        total[thing[item]] += lifetimes[item]
    return thing == np.argmax(total)


@nb.njit(cache=True, nogil=True)
def core_regions(nodes: np.ndarray, ends: np.ndarray, lifetimes: np.ndarray, backdrop: np.ndarray,
                 bbox: np.ndarray, share: float) -> tuple[np.ndarray, np.ndarray]:
    """The core regions and the most held ones of one frame's occurrences (node sets
    ``nodes[ends[i - 1]:ends[i]]`` with their patterns' ``lifetimes``), as
    :func:`trap_core.clustering.core_regions` defines them: the ``backdrop`` left out of every
    set (unless all would go), the sets of the track's place (:func:`place_kept`), each entry
    counting its set's lifetime."""
    kept_nodes = np.empty(nodes.size, dtype=np.bool_)
    for i in range(nodes.size):
        kept_nodes[i] = not backdrop[nodes[i]]
    if not kept_nodes.all() and kept_nodes.any():  # sets left empty go
        new_ends = np.empty(ends.size, dtype=ends.dtype)
        new_lifetimes = np.empty(ends.size)
        n_sets = 0
        count = 0
        start = 0
        for item in range(ends.size):
            before = count
            for i in range(start, ends[item]):
                if kept_nodes[i]:
                    count += 1
            if count > before:
                new_ends[n_sets] = count
                new_lifetimes[n_sets] = lifetimes[item]
                n_sets += 1
            start = ends[item]
        nodes, ends, lifetimes = nodes[kept_nodes], new_ends[:n_sets], new_lifetimes[:n_sets]
    in_place = place_kept(nodes, ends, lifetimes, share, backdrop.size, bbox)
    held = np.empty(nodes.size, dtype=nodes.dtype)
    weights = np.empty(nodes.size)
    count = 0
    start = 0
    for item in range(ends.size):
        if in_place[item]:
            for i in range(start, ends[item]):
                held[count] = nodes[i]
                weights[count] = lifetimes[item]
                count += 1
        start = ends[item]
    return most_held(held[:count], share, weights[:count])


@nb.njit(cache=True, nogil=True)
def stacked_core_regions(face_sets: np.ndarray, lifetimes: np.ndarray, frames: np.ndarray, ends: np.ndarray,
                         node_offsets: np.ndarray, face_base: np.ndarray, face_offsets: np.ndarray,
                         face_half_edges: np.ndarray, he_origin: np.ndarray, backdrop: np.ndarray, bbox: np.ndarray,
                         share: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`core_regions` in each of ``frames``, whose occurrences are rows ``ends[k - 1]:ends[k]``
    of ``face_sets`` (face ids within the frame, -1 padded) and ``lifetimes``, the video's graphs
    stacked (:class:`trap_core.rag.StackedGraphs`). Returns the core regions of every frame one
    frame's after the other's, where each frame's end, and the same of the most held ones."""
    cores = np.empty(8 * max(frames.size, 1), dtype=np.int64)
    core_ends = np.empty(frames.size, dtype=np.int64)
    tops = np.empty(frames.size, dtype=np.int64)
    top_ends = np.empty(frames.size, dtype=np.int64)
    n_cores = n_tops = 0
    start = 0
    for k in range(frames.size):
        frame = frames[k]
        lo, hi = node_offsets[frame], node_offsets[frame + 1]
        nodes, node_ends = stacked_sets_nodes(face_sets[start:ends[k]], frame, node_offsets, face_base, face_offsets,
                                              face_half_edges, he_origin)
        core, top = core_regions(nodes, node_ends, lifetimes[start:ends[k]], backdrop[lo:hi], bbox[lo:hi], share)
        if n_cores + core.size > cores.size:
            cores = _grow(cores, 2 * (n_cores + core.size))
        if n_tops + top.size > tops.size:
            tops = _grow(tops, 2 * (n_tops + top.size))
        cores[n_cores:n_cores + core.size] = core
        tops[n_tops:n_tops + top.size] = top
        n_cores += core.size
        n_tops += top.size
        core_ends[k] = n_cores
        top_ends[k] = n_tops
        start = ends[k]
    return cores[:n_cores], core_ends, tops[:n_tops], top_ends


@nb.njit(cache=True, nogil=True)
def near_frames(clusters: np.ndarray, other: int, covered: np.ndarray, start: np.ndarray, offsets: np.ndarray,
                points: np.ndarray, separation: float) -> np.ndarray:
    """(len(clusters), n_frames) bool: frames where each cluster's path (``start``, ``offsets``,
    ``points``: :class:`~trap_core.clustering.Trajectories`) is within ``separation`` of cluster
    ``other``'s, both covering the frame (``covered``: (C, n_frames)). Selection asks it of every
    candidate against every kept cluster (:func:`trap_core.clustering.selection._near_frames`)."""
    near = np.zeros((clusters.size, covered.shape[1]), dtype=np.bool_)
    other_end = start[other] + offsets[other + 1] - offsets[other]
    for row in range(clusters.size):
        cluster = clusters[row]
        for frame in range(max(start[cluster], start[other]),
                           min(start[cluster] + offsets[cluster + 1] - offsets[cluster], other_end)):
            if covered[cluster, frame] and covered[other, frame]:
                here = offsets[cluster] + frame - start[cluster]
                there = offsets[other] + frame - start[other]
                dx = points[here, 0] - points[there, 0]
                dy = points[here, 1] - points[there, 1]
                near[row, frame] = np.sqrt(dx * dx + dy * dy) <= separation
    return near
