"""Compiled kernels of the miner (numba, ``nogil``): inner faces, face-set enumeration, canonical
codes, occurrence geometry (and positions without some regions, for the camera's motion),
occurrence linking. :mod:`trap_core.mining.miner` drives them;
:mod:`trap_core.mining.reference` is the readable version they are tested against.
"""
from __future__ import annotations

import numba as nb
import numpy as np

# Token kinds of a traversal code (same as the reference implementation).
_NEW_NODE, _SEEN_NODE, _FACE, _OPEN, _END = 0, 1, 2, 3, 4
_MASK64 = np.uint64(0xFFFFFFFFFFFFFFFF)


@nb.njit(cache=True, nogil=True)
def inner_faces(he_origin, face_half_edges, face_offsets, outside):
    """(F,) bool: face avoids the outside node and has at least three distinct nodes."""
    n_faces = face_offsets.size - 1
    inner = np.zeros(n_faces, dtype=np.bool_)
    for f in range(n_faces):
        start, stop = face_offsets[f], face_offsets[f + 1]
        ok = True
        distinct = 0
        for a in range(start, stop):
            node = he_origin[face_half_edges[a]]
            if node == outside:
                ok = False
                break
            repeated = False
            for b in range(start, a):
                if he_origin[face_half_edges[b]] == node:
                    repeated = True
                    break
            if not repeated:
                distinct += 1
        inner[f] = ok and distinct >= 3
    return inner


@nb.njit(cache=True, nogil=True)
def face_adjacency(he_twin, face_of, face_half_edges, face_offsets, usable):
    """CSR adjacency between usable faces sharing an edge (each neighbour once)."""
    n_faces = face_offsets.size - 1
    offsets = np.zeros(n_faces + 1, dtype=np.int64)
    targets = np.empty(face_half_edges.size, dtype=np.int64)
    count = 0
    for f in range(n_faces):
        if usable[f]:
            for a in range(face_offsets[f], face_offsets[f + 1]):
                g = face_of[he_twin[face_half_edges[a]]]
                if g == f or not usable[g]:
                    continue
                seen = False
                for b in range(offsets[f], count):
                    if targets[b] == g:
                        seen = True
                        break
                if not seen:
                    targets[count] = g
                    count += 1
        offsets[f + 1] = count
    return offsets, targets[:count]


@nb.njit(cache=True, nogil=True, inline="always")
def _in(values, length, x):
    for i in range(length):
        if values[i] == x:
            return i
    return -1


@nb.njit(cache=True, nogil=True, inline="always")
def _order_from(tokens, best, best_len, start, stop):
    """Compare ``tokens[start:stop]`` with the same slice of ``best``: -1 larger (or longer than
    best), 1 smaller, 0 equal so far."""
    for i in range(start, stop):
        if i >= best_len or tokens[i] > best[i]:
            return -1
        if tokens[i] < best[i]:
            return 1
    return 0


@nb.njit(cache=True, nogil=True)
def _traverse(start, faces, n_faces, he_origin, he_twin, he_next, face_of, face_offsets, label,
              tokens, best, best_len, queue, face_ids, node_ids):
    """Write the traversal code from half-edge ``start`` into ``tokens``; stop early (return -1)
    as soon as it is larger than ``best[:best_len]`` (best_len < 0: no best yet)."""
    n_face_ids = 1
    face_ids[0] = face_of[start]
    queue[0] = start
    n_queue = 1
    n_nodes = 0
    pos = 0
    smaller = best_len < 0
    q = 0
    while q < n_queue:
        entry = queue[q]
        q += 1
        h = entry
        while True:
            node = he_origin[h]
            k = _in(node_ids, n_nodes, node)
            if k >= 0:
                tokens[pos] = _SEEN_NODE
                tokens[pos + 1] = k
            else:
                node_ids[n_nodes] = node
                n_nodes += 1
                tokens[pos] = _NEW_NODE
                tokens[pos + 1] = label[node]
            twin = he_twin[h]
            across = face_of[twin]
            if _in(faces, n_faces, across) >= 0:
                k = _in(face_ids, n_face_ids, across)
                if k < 0:
                    k = n_face_ids
                    face_ids[n_face_ids] = across
                    n_face_ids += 1
                    queue[n_queue] = twin
                    n_queue += 1
                tokens[pos + 2] = _FACE
                tokens[pos + 3] = k
            else:
                tokens[pos + 2] = _OPEN
                tokens[pos + 3] = 0
            if not smaller:
                order = _order_from(tokens, best, best_len, pos, pos + 4)
                if order < 0:
                    return -1
                smaller = order > 0
            pos += 4
            h = he_next[twin]
            if h == entry:
                break
        tokens[pos] = _END
        tokens[pos + 1] = 0
        if not smaller:
            order = _order_from(tokens, best, best_len, pos, pos + 2)
            if order < 0:
                return -1
            smaller = order > 0
        pos += 2
    if not smaller:  # equal to the best so far
        return -1
    return pos


@nb.njit(cache=True, nogil=True)
def code_hash(faces, n_faces, he_origin, he_twin, he_next, face_of, face_half_edges, face_offsets, label,
              tokens, best, queue, face_ids, node_ids):
    """64-bit hash of the canonical code (smallest traversal code over all starts) of a face set."""
    best_len = -1
    for i in range(n_faces):
        f = faces[i]
        for a in range(face_offsets[f], face_offsets[f + 1]):
            length = _traverse(face_half_edges[a], faces, n_faces, he_origin, he_twin, he_next, face_of,
                               face_offsets, label, tokens, best, best_len, queue, face_ids, node_ids)
            if length >= 0:
                best[:length] = tokens[:length]
                best_len = length
    value = np.uint64(0x9E3779B97F4A7C15) ^ np.uint64(best_len)
    for i in range(best_len):  # splitmix64-style mixing of each token
        value = (value ^ np.uint64(best[i] + 0x632BE59BD9B4E019)) * np.uint64(0xBF58476D1CE4E5B9)
        value ^= value >> np.uint64(31)
    return np.int64(value & np.uint64(0x7FFFFFFFFFFFFFFF))


@nb.njit(cache=True, nogil=True)
def single_face_hashes(he_origin, he_twin, he_next, face_of, face_half_edges, face_offsets, label, inner):
    """Code hash of every inner face alone (-1 for other faces)."""
    n_faces = face_offsets.size - 1
    longest = 1
    for f in range(n_faces):
        longest = max(longest, face_offsets[f + 1] - face_offsets[f])
    tokens = np.empty(6 * longest + 8, dtype=np.int64)
    best = np.empty_like(tokens)
    queue = np.empty(2, dtype=np.int64)
    face_ids = np.empty(2, dtype=np.int64)
    node_ids = np.empty(longest + 1, dtype=np.int64)
    faces = np.empty(1, dtype=np.int64)
    hashes = np.full(n_faces, -1, dtype=np.int64)
    for f in range(n_faces):
        if inner[f]:
            faces[0] = f
            hashes[f] = code_hash(faces, 1, he_origin, he_twin, he_next, face_of, face_half_edges, face_offsets,
                                  label, tokens, best, queue, face_ids, node_ids)
    return hashes


@nb.njit(cache=True, nogil=True)
def enumerate_face_sets(max_faces, allowed, adj_offsets, adj_targets, he_origin, he_twin, he_next, face_of,
                        face_half_edges, face_offsets, label, single_hash):
    """Every connected set of at most ``max_faces`` allowed faces (ESU: each set once, rooted at
    its smallest face), with its code hash. Returns (hashes, sets padded with -1)."""
    n_faces = face_offsets.size - 1
    longest = 1
    max_degree = 1
    for f in range(n_faces):
        longest = max(longest, face_offsets[f + 1] - face_offsets[f])
        max_degree = max(max_degree, adj_offsets[f + 1] - adj_offsets[f])
    cap_tokens = max_faces * (6 * longest + 2) + 8
    tokens = np.empty(cap_tokens, dtype=np.int64)
    best = np.empty_like(tokens)
    queue = np.empty(max_faces + 1, dtype=np.int64)
    face_ids = np.empty(max_faces + 1, dtype=np.int64)
    node_ids = np.empty(max_faces * longest + 1, dtype=np.int64)
    sub = np.empty(max_faces, dtype=np.int64)
    max_ext = max_faces * max_degree + 1
    ext = np.empty((max_faces, max_ext), dtype=np.int64)
    ext_len = np.zeros(max_faces, dtype=np.int64)
    cap = 1024
    out_hash = np.empty(cap, dtype=np.int64)
    out_sets = np.full((cap, max_faces), -1, dtype=np.int64)
    count = 0
    for root in range(n_faces):
        if not allowed[root]:
            continue
        sub[0] = root
        if count == cap:
            cap *= 2
            out_hash, out_sets = _grow_sets(out_hash, out_sets, cap)
        out_hash[count] = single_hash[root]
        out_sets[count, 0] = root
        count += 1
        ext_len[0] = 0
        for a in range(adj_offsets[root], adj_offsets[root + 1]):
            u = adj_targets[a]
            if allowed[u] and u > root:
                ext[0, ext_len[0]] = u
                ext_len[0] += 1
        depth = 0  # sub[:depth + 1] is the current set, ext[depth] its extension
        while depth >= 0:
            if depth + 1 == max_faces or ext_len[depth] == 0:
                depth -= 1
                continue
            ext_len[depth] -= 1
            w = ext[depth, ext_len[depth]]
            n = ext_len[depth]
            ext[depth + 1, :n] = ext[depth, :n]
            for a in range(adj_offsets[w], adj_offsets[w + 1]):
                u = adj_targets[a]
                if not allowed[u] or u <= root or _in(sub, depth + 1, u) >= 0:
                    continue
                closed = False
                for i in range(depth + 1):
                    s = sub[i]
                    for b in range(adj_offsets[s], adj_offsets[s + 1]):
                        if adj_targets[b] == u:
                            closed = True
                            break
                    if closed:
                        break
                if not closed:
                    ext[depth + 1, n] = u
                    n += 1
            ext_len[depth + 1] = n
            sub[depth + 1] = w
            depth += 1
            if count == cap:
                cap *= 2
                out_hash, out_sets = _grow_sets(out_hash, out_sets, cap)
            out_hash[count] = code_hash(sub, depth + 1, he_origin, he_twin, he_next, face_of, face_half_edges,
                                        face_offsets, label, tokens, best, queue, face_ids, node_ids)
            out_sets[count, :depth + 1] = sub[:depth + 1]
            count += 1
    return out_hash[:count], out_sets[:count]


@nb.njit(cache=True, nogil=True)
def _grow_sets(hashes, sets, cap):
    new_hashes = np.empty(cap, dtype=np.int64)
    new_sets = np.full((cap, sets.shape[1]), -1, dtype=np.int64)
    new_hashes[: hashes.size] = hashes
    new_sets[: sets.shape[0]] = sets
    return new_hashes, new_sets


@nb.njit(cache=True, nogil=True)
def _set_nodes(face_set, he_origin, face_half_edges, face_offsets, left_out, nodes):
    """The distinct nodes around one face set (face ids, -1 padded) but those ``left_out``
    (nodes past its end are kept), written into ``nodes`` (a larger array is returned where it
    is too small), and their count."""
    n = 0
    for i in range(face_set.size):
        f = face_set[i]
        if f < 0:
            break
        for a in range(face_offsets[f], face_offsets[f + 1]):
            node = he_origin[face_half_edges[a]]
            if (node < left_out.size and left_out[node]) or _in(nodes, n, node) >= 0:
                continue
            if n == nodes.size:
                bigger = np.empty(2 * n, dtype=np.int64)
                bigger[:n] = nodes
                nodes = bigger
            nodes[n] = node
            n += 1
    return nodes, n


@nb.njit(cache=True, nogil=True)
def occurrence_geometry(sets, he_origin, face_half_edges, face_offsets, centroid, bbox, left_out):
    """Per face set, of its distinct nodes but those ``left_out`` (an empty mask leaves none
    out): their mean barycentre, the box of their regions and the box of their barycentres
    (x0, y0, x1, y1); NaN where no node is left."""
    count = sets.shape[0]
    position = np.full((count, 2), np.nan)
    box = np.full((count, 4), np.nan)
    node_box = np.full((count, 4), np.nan)
    nodes = np.empty(64, dtype=np.int64)
    for r in range(count):
        nodes, n = _set_nodes(sets[r], he_origin, face_half_edges, face_offsets, left_out, nodes)
        if n == 0:
            continue
        sx = sy = 0.0
        box[r, 0] = box[r, 1] = node_box[r, 0] = node_box[r, 1] = 1e18
        box[r, 2] = box[r, 3] = node_box[r, 2] = node_box[r, 3] = -1e18
        for i in range(n):
            node = nodes[i]
            x, y = centroid[node, 0], centroid[node, 1]
            sx += x
            sy += y
            node_box[r, 0] = min(node_box[r, 0], x)
            node_box[r, 1] = min(node_box[r, 1], y)
            node_box[r, 2] = max(node_box[r, 2], x)
            node_box[r, 3] = max(node_box[r, 3], y)
            box[r, 0] = min(box[r, 0], bbox[node, 0])
            box[r, 1] = min(box[r, 1], bbox[node, 1])
            box[r, 2] = max(box[r, 2], bbox[node, 2])
            box[r, 3] = max(box[r, 3], bbox[node, 3])
        position[r, 0] = sx / n
        position[r, 1] = sy / n
    return position, box, node_box


@nb.njit(cache=True, nogil=True)
def _root(parent, i):
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


@nb.njit(cache=True, nogil=True)
def link_occurrences(group_start, frame, position, eps, tau):
    """Union-find component of each occurrence. Occurrences are sorted by (pattern, frame);
    ``group_start`` bounds each pattern. Linked: same pattern, 0 < frame gap <= tau, distance <= eps."""
    count = frame.size
    parent = np.arange(count)
    eps2 = eps * eps
    for g in range(group_start.size - 1):
        lo, hi = group_start[g], group_start[g + 1]
        for i in range(lo, hi):
            for j in range(i + 1, hi):
                gap = frame[j] - frame[i]
                if gap > tau:
                    break
                if gap == 0:
                    continue
                dx = position[i, 0] - position[j, 0]
                dy = position[i, 1] - position[j, 1]
                if dx * dx + dy * dy <= eps2:
                    ri, rj = _root(parent, i), _root(parent, j)
                    if ri != rj:
                        parent[max(ri, rj)] = min(ri, rj)
    for i in range(count):
        parent[i] = _root(parent, i)
    return parent


@nb.njit(cache=True, nogil=True)
def assign_occurrences(group_start, frame, position, extent, eps, tau, reach):
    """One object, one path (ours, TRAP_SPEC section 10): chain each pattern's occurrences frame by
    frame, each occurrence continuing at most one chain and each chain taking at most one
    occurrence per frame. A chain predicts its next position from its last velocity; pairs are
    taken in order of distance to the prediction, within ``eps`` and, if ``reach > 0``, within
    ``reach`` times the ``extent`` of the chain's last occurrence times the square root of the
    frames since (a step the size of the pattern is to another object, not along this one); a
    chain waits up to ``tau`` frames for its next occurrence. Returns the chain of each
    occurrence (sorted input order).
    """
    count = frame.size
    chain = np.full(count, -1, dtype=np.int64)
    last_frame = np.empty(count, dtype=np.int64)
    last_x = np.empty(count)
    last_y = np.empty(count)
    vel_x = np.zeros(count)
    vel_y = np.zeros(count)
    last_extent = np.empty(count)
    n_chains = 0
    eps2 = eps * eps
    taken_at = np.full(count, -1, dtype=np.int64)  # the step in which each chain last took an occurrence
    step = 0
    longest = 0
    for g in range(group_start.size - 1):
        longest = max(longest, group_start[g + 1] - group_start[g])
    active = np.empty(longest, dtype=np.int64)  # chains of the current pattern still waiting
    costs = np.empty(64)  # candidate pairs of one frame: squared distance, occurrence, chain
    occ = np.empty(64, dtype=np.int64)
    chn = np.empty(64, dtype=np.int64)
    first = np.zeros(1, dtype=np.int64)  # the order of a single pair
    for g in range(group_start.size - 1):
        lo, hi = group_start[g], group_start[g + 1]
        n_active = 0
        i = lo
        while i < hi:
            j = i
            while j < hi and frame[j] == frame[i]:
                j += 1
            t = frame[i]
            keep = 0
            for a in range(n_active):  # drop chains that waited too long
                if t - last_frame[active[a]] <= tau:
                    active[keep] = active[a]
                    keep += 1
            n_active = keep
            n_pairs = 0
            if (j - i) * n_active > costs.size:
                costs = np.empty(2 * (j - i) * n_active)
                occ = np.empty(costs.size, dtype=np.int64)
                chn = np.empty(costs.size, dtype=np.int64)
            for k in range(i, j):
                for a in range(n_active):
                    c = active[a]
                    dt = t - last_frame[c]
                    dx = position[k, 0] - (last_x[c] + vel_x[c] * dt)
                    dy = position[k, 1] - (last_y[c] + vel_y[c] * dt)
                    d2 = dx * dx + dy * dy
                    within = reach * last_extent[c]
                    if d2 <= eps2 and (reach <= 0 or d2 <= within * within * dt):
                        costs[n_pairs] = d2
                        occ[n_pairs] = k
                        chn[n_pairs] = c
                        n_pairs += 1
            order = np.argsort(costs[:n_pairs]) if n_pairs > 1 else first[:n_pairs]
            for p in order:
                k, c = occ[p], chn[p]
                if chain[k] >= 0 or taken_at[c] == step:
                    continue
                chain[k] = c
                taken_at[c] = step
                dt = t - last_frame[c]
                vel_x[c] = 0.5 * vel_x[c] + 0.5 * (position[k, 0] - last_x[c]) / dt
                vel_y[c] = 0.5 * vel_y[c] + 0.5 * (position[k, 1] - last_y[c]) / dt
                last_frame[c] = t
                last_x[c] = position[k, 0]
                last_y[c] = position[k, 1]
                last_extent[c] = extent[k]
            for k in range(i, j):
                if chain[k] < 0:
                    c = n_chains
                    n_chains += 1
                    chain[k] = c
                    last_frame[c] = t
                    last_x[c] = position[k, 0]
                    last_y[c] = position[k, 1]
                    last_extent[c] = extent[k]
                    active[n_active] = c
                    n_active += 1
            i = j
            step += 1
    return chain
