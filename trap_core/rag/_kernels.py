"""Compiled kernels of the plane-graph stage (numba, ``nogil``).

The region adjacency graph is built as the dual of the *boundary graph*: its vertices are
pixel corners where three or more regions meet (junctions), its edges the maximal crack
paths between them (one per contact stretch), and its faces the regions. The image outside
is one more region, so the border is a boundary like any other. Reading the embedding off the
crack grid makes it valid by construction (TRAP_SPEC section 2, section 10 "Graph").
"""
from __future__ import annotations

import numba as nb
import numpy as np

# Crack directions from a corner, clockwise on screen (y down): up, right, down, left.
_DY = np.array([-1, 0, 1, 0], dtype=np.int64)
_DX = np.array([0, 1, 0, -1], dtype=np.int64)


@nb.njit(cache=True, nogil=True, inline="always")
def _label(labels: np.ndarray, y: int, x: int, outside: int) -> int:
    if y < 0 or x < 0 or y >= labels.shape[0] or x >= labels.shape[1]:
        return outside
    return labels[y, x]


@nb.njit(cache=True, nogil=True)
def _corner_cracks(labels: np.ndarray, outside: int) -> np.ndarray:
    """Bit d of ``mask[i, j]`` is set when a crack leaves corner (i, j) in direction d."""
    height, width = labels.shape
    mask = np.zeros((height + 1, width + 1), dtype=np.uint8)
    for i in range(height + 1):
        for j in range(width + 1):
            tl = _label(labels, i - 1, j - 1, outside)
            tr = _label(labels, i - 1, j, outside)
            bl = _label(labels, i, j - 1, outside)
            br = _label(labels, i, j, outside)
            bits = 0
            if tl != tr:
                bits |= 1
            if tr != br:
                bits |= 2
            if bl != br:
                bits |= 4
            if tl != bl:
                bits |= 8
            mask[i, j] = bits
    return mask


@nb.njit(cache=True, nogil=True, inline="always")
def _sides(labels: np.ndarray, i: int, j: int, d: int, outside: int) -> tuple[int, int]:
    """(left, right) region of the crack leaving corner (i, j) in direction d."""
    tl = _label(labels, i - 1, j - 1, outside)
    tr = _label(labels, i - 1, j, outside)
    bl = _label(labels, i, j - 1, outside)
    br = _label(labels, i, j, outside)
    if d == 0:
        return tl, tr
    if d == 1:
        return tr, br
    if d == 2:
        return br, bl
    return bl, tl


@nb.njit(cache=True, nogil=True)
def trace_boundary_graph(labels: np.ndarray, n_regions: int):
    """Trace every contact stretch between junctions.

    Returns per dart (directed stretch): origin corner (i, j), start direction, twin dart,
    left and right region, crack length, and twice the signed shoelace area of its path.
    Closed boundaries without any junction (a region enclosed by one other region, or one
    region filling the image) get a virtual junction on the loop.
    """
    outside = n_regions
    mask = _corner_cracks(labels, outside)
    height, width = mask.shape
    dart_of = np.full((height, width, 4), -1, dtype=np.int64)
    seen = np.zeros((height, width), dtype=np.bool_)
    cap = 64
    origin_i = np.empty(cap, dtype=np.int64)
    origin_j = np.empty(cap, dtype=np.int64)
    start_dir = np.empty(cap, dtype=np.int64)
    twin = np.empty(cap, dtype=np.int64)
    left = np.empty(cap, dtype=np.int64)
    right = np.empty(cap, dtype=np.int64)
    length = np.empty(cap, dtype=np.int64)
    area2 = np.empty(cap, dtype=np.int64)
    n_darts = 0
    # Pass 0 starts at real junctions; pass 1 at loop corners never reached (virtual junctions).
    for pass_no in range(2):
        for i0 in range(height):
            for j0 in range(width):
                bits = mask[i0, j0]
                degree = (bits & 1) + ((bits >> 1) & 1) + ((bits >> 2) & 1) + ((bits >> 3) & 1)
                if pass_no == 0 and degree < 3:
                    continue
                if pass_no == 1 and (degree != 2 or seen[i0, j0]):
                    continue
                seen[i0, j0] = True
                for d0 in range(4):
                    if not (bits >> d0) & 1 or dart_of[i0, j0, d0] >= 0:
                        continue
                    if n_darts + 2 > cap:
                        cap *= 2
                        origin_i = _grow(origin_i, cap)
                        origin_j = _grow(origin_j, cap)
                        start_dir = _grow(start_dir, cap)
                        twin = _grow(twin, cap)
                        left = _grow(left, cap)
                        right = _grow(right, cap)
                        length = _grow(length, cap)
                        area2 = _grow(area2, cap)
                    i, j, d = i0, j0, d0
                    steps = 0
                    area = 0
                    while True:
                        ni, nj = i + _DY[d], j + _DX[d]
                        area += j * ni - nj * i
                        steps += 1
                        i, j = ni, nj
                        nbits = mask[i, j]
                        ndeg = (nbits & 1) + ((nbits >> 1) & 1) + ((nbits >> 2) & 1) + ((nbits >> 3) & 1)
                        if ndeg >= 3 or (i == i0 and j == j0):
                            break
                        seen[i, j] = True
                        back = (d + 2) % 4
                        for nd in range(4):
                            if (nbits >> nd) & 1 and nd != back:
                                d = nd
                                break
                    back = (d + 2) % 4
                    fwd, rev = n_darts, n_darts + 1
                    lf, rf = _sides(labels, i0, j0, d0, outside)
                    origin_i[fwd], origin_j[fwd], start_dir[fwd] = i0, j0, d0
                    origin_i[rev], origin_j[rev], start_dir[rev] = i, j, back
                    twin[fwd], twin[rev] = rev, fwd
                    left[fwd], right[fwd], left[rev], right[rev] = lf, rf, rf, lf
                    length[fwd] = length[rev] = steps
                    area2[fwd], area2[rev] = area, -area
                    dart_of[i0, j0, d0] = fwd
                    dart_of[i, j, back] = rev
                    n_darts += 2
    return (origin_i[:n_darts], origin_j[:n_darts], start_dir[:n_darts], twin[:n_darts],
            left[:n_darts], right[:n_darts], length[:n_darts], area2[:n_darts], dart_of)


@nb.njit(cache=True, nogil=True)
def _grow(array: np.ndarray, cap: int) -> np.ndarray:
    out = np.empty(cap, dtype=array.dtype)
    out[: array.size] = array
    return out


@nb.njit(cache=True, nogil=True)
def rotation_system(origin_i: np.ndarray, origin_j: np.ndarray, start_dir: np.ndarray, twin: np.ndarray,
                    right: np.ndarray, area2: np.ndarray, dart_of: np.ndarray, n_nodes: int) -> np.ndarray:
    """``rot_next[d]``: the next half-edge around node ``right[d]`` in the region graph.

    Half-edge d of the region graph leaves node ``right[d]`` across stretch d. Around a node
    the half-edges follow its boundary (phi(d) = the dart before twin(d) clockwise at the
    junction). A region with holes has one boundary cycle per hole besides its outer one;
    each hole's cycle is spliced in after the outer cycle, which keeps the embedding plane
    (the hole's contents hang on this region alone).
    """
    n = twin.size
    phi = np.empty(n, dtype=np.int64)
    for d in range(n):
        t = twin[d]
        i, j, dd = origin_i[t], origin_j[t], start_dir[t]
        for step in range(1, 5):
            cand = dart_of[i, j, (dd - step) % 4]
            if cand >= 0:
                phi[d] = cand
                break
    rot_next = phi.copy()
    # Group the phi-cycles by node; the cycle of largest |area| is the outer boundary.
    cycle_of = np.full(n, -1, dtype=np.int64)
    cycle_first = np.empty(n, dtype=np.int64)
    cycle_last = np.empty(n, dtype=np.int64)
    cycle_area = np.empty(n, dtype=np.int64)
    cycle_node = np.empty(n, dtype=np.int64)
    n_cycles = 0
    for d in range(n):
        if cycle_of[d] >= 0:
            continue
        area = 0
        e = d
        last = d
        while cycle_of[e] < 0:
            cycle_of[e] = n_cycles
            area += area2[e]
            last = e
            e = phi[e]
        cycle_first[n_cycles] = d
        cycle_last[n_cycles] = last
        cycle_area[n_cycles] = abs(area)
        cycle_node[n_cycles] = right[d]
        n_cycles += 1
    outer = np.full(n_nodes, -1, dtype=np.int64)
    for c in range(n_cycles):
        node = cycle_node[c]
        if outer[node] < 0 or cycle_area[c] > cycle_area[outer[node]]:
            outer[node] = c
    tail = np.full(n_nodes, -1, dtype=np.int64)  # current last half-edge of the spliced rotation
    for node in range(n_nodes):
        if outer[node] >= 0:
            tail[node] = cycle_last[outer[node]]
    for c in range(n_cycles):
        node = cycle_node[c]
        if c == outer[node]:
            continue
        head = rot_next[tail[node]]
        rot_next[tail[node]] = cycle_first[c]
        rot_next[cycle_last[c]] = head
        tail[node] = cycle_last[c]
    return rot_next


@nb.njit(cache=True, nogil=True)
def trace_faces(rot_next: np.ndarray, twin: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Faces of the embedding: orbits of ``h -> rot_next[twin[h]]``.

    Returns ``face_of`` (face of each half-edge), and the half-edges of all faces in
    traversal order with CSR ``offsets``.
    """
    n = twin.size
    face_of = np.full(n, -1, dtype=np.int64)
    order = np.empty(n, dtype=np.int64)
    offsets = np.empty(n + 1, dtype=np.int64)
    offsets[0] = 0
    n_faces = 0
    pos = 0
    for h in range(n):
        if face_of[h] >= 0:
            continue
        e = h
        while face_of[e] < 0:
            face_of[e] = n_faces
            order[pos] = e
            pos += 1
            e = rot_next[twin[e]]
        n_faces += 1
        offsets[n_faces] = pos
    return face_of, order, offsets[: n_faces + 1]


@nb.njit(cache=True, nogil=True)
def region_stats(labels: np.ndarray, rgb: np.ndarray, n: int):
    """Area, pixel sums of x, y and colour, and bounding box (x0, y0, x1, y1 inclusive) per region."""
    area = np.zeros(n, dtype=np.int64)
    sums = np.zeros((n, 5), dtype=np.float64)
    box = np.empty((n, 4), dtype=np.int64)
    box[:, 0] = labels.shape[1]
    box[:, 1] = labels.shape[0]
    box[:, 2] = -1
    box[:, 3] = -1
    for y in range(labels.shape[0]):
        for x in range(labels.shape[1]):
            r = labels[y, x]
            area[r] += 1
            sums[r, 0] += x
            sums[r, 1] += y
            sums[r, 2] += rgb[y, x, 0]
            sums[r, 3] += rgb[y, x, 1]
            sums[r, 4] += rgb[y, x, 2]
            box[r, 0] = min(box[r, 0], x)
            box[r, 1] = min(box[r, 1], y)
            box[r, 2] = max(box[r, 2], x)
            box[r, 3] = max(box[r, 3], y)
    return area, sums, box


@nb.njit(cache=True, nogil=True)
def drop_short_contacts(right, twin, rot_next, length, face_of, area, outside, tolerance):
    """Remove contacts shorter than ``tolerance * sqrt(smaller region area)`` between two regions
    (ours, TRAP_SPEC section 10 "face flicker"): a point where four regions meet then reads as one
    face whatever the pixel rounding, at any scale. A contact is kept when removing it would not
    merge two different faces (it is then a bridge) and when it touches the outside.
    Returns the kept half-edges' (right, twin, rot_next, length), renumbered.
    """
    n = twin.size
    prev = np.empty(n, dtype=np.int64)
    for h in range(n):
        prev[rot_next[h]] = h
    parent = np.arange(face_of.max() + 1 if n else 1)
    removed = np.zeros(n, dtype=np.bool_)
    for h in np.argsort(length):  # shortest first
        t = twin[h]
        if h > t or removed[h]:
            continue
        u, v = right[h], right[t]
        if u == outside or v == outside:
            continue
        if length[h] >= tolerance * np.sqrt(min(area[u], area[v])):
            continue
        fa, fb = face_of[h], face_of[t]
        while parent[fa] != fa:
            fa = parent[fa]
        while parent[fb] != fb:
            fb = parent[fb]
        if fa == fb or rot_next[h] == h or rot_next[t] == t:
            continue
        parent[fb] = fa
        for e in (h, t):
            p, q = prev[e], rot_next[e]
            rot_next[p] = q
            prev[q] = p
            removed[e] = True
    index = np.full(n, -1, dtype=np.int64)
    kept = 0
    for h in range(n):
        if not removed[h]:
            index[h] = kept
            kept += 1
    new_right = np.empty(kept, dtype=right.dtype)
    new_twin = np.empty(kept, dtype=np.int64)
    new_next = np.empty(kept, dtype=np.int64)
    new_length = np.empty(kept, dtype=length.dtype)
    for h in range(n):
        if not removed[h]:
            k = index[h]
            new_right[k] = right[h]
            new_twin[k] = index[twin[h]]
            new_next[k] = index[rot_next[h]]
            new_length[k] = length[h]
    return new_right, new_twin, new_next, new_length


@nb.njit(cache=True, nogil=True)
def sets_nodes(face_sets: np.ndarray, he_origin: np.ndarray, face_half_edges: np.ndarray, face_offsets: np.ndarray,
               n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """The distinct nodes (ascending) around each row of ``face_sets`` (face ids, -1 padded), all
    rows' one after the other, and where each row's end (``n_nodes`` counts the outside node)."""
    seen_in = np.full(n_nodes, -1, dtype=np.int64)  # the last row that took each node
    nodes = np.empty(16 * max(face_sets.shape[0], 1), dtype=np.int64)
    ends = np.empty(face_sets.shape[0], dtype=np.int64)
    n = 0
    for row in range(face_sets.shape[0]):
        start = n
        for i in range(face_sets.shape[1]):
            f = face_sets[row, i]
            if f < 0:
                continue
            for a in range(face_offsets[f], face_offsets[f + 1]):
                node = he_origin[face_half_edges[a]]
                if seen_in[node] == row:
                    continue
                seen_in[node] = row
                if n == nodes.size:
                    nodes = _grow(nodes, 2 * n)
                nodes[n] = node
                n += 1
        nodes[start:n] = np.sort(nodes[start:n])
        ends[row] = n
    return nodes[:n], ends


@nb.njit(cache=True, nogil=True)
def stacked_face_ids(face_sets: np.ndarray, base: int) -> np.ndarray:
    """``face_sets`` (face ids within one frame, -1 padded) as ids of the stacked graphs' faces
    (:class:`trap_core.rag.StackedGraphs`: that frame's ``face_base`` is ``base``), a copy."""
    rows = face_sets.astype(np.int64)
    for i in range(rows.shape[0]):
        for j in range(rows.shape[1]):
            if rows[i, j] >= 0:
                rows[i, j] += base
    return rows


@nb.njit(cache=True, nogil=True)
def stacked_sets_nodes(face_sets: np.ndarray, frame: int, node_offsets: np.ndarray, face_base: np.ndarray,
                       face_offsets: np.ndarray, face_half_edges: np.ndarray,
                       he_origin: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`sets_nodes` of occurrences ``face_sets`` (face ids within frame ``frame``, -1
    padded) in the video's graphs stacked (:class:`trap_core.rag.StackedGraphs`); nodes are
    numbered within the frame."""
    return sets_nodes(stacked_face_ids(face_sets, face_base[frame]), he_origin, face_half_edges, face_offsets,
                      node_offsets[frame + 1] - node_offsets[frame] + 1)


@nb.njit(cache=True, nogil=True)
def video_sets_nodes(face_sets: np.ndarray, frames: np.ndarray, ends: np.ndarray, node_offsets: np.ndarray,
                     face_base: np.ndarray, face_offsets: np.ndarray, face_half_edges: np.ndarray,
                     he_origin: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`stacked_sets_nodes` of the occurrences of each of ``frames``, rows
    ``ends[k - 1]:ends[k]`` of ``face_sets``, as node ids over the whole video (frame ``t``'s
    node ``n`` is ``node_offsets[t] + t + n``: each frame has its outside node too), every row's
    one after the other, and where each row ends."""
    nodes = np.empty(16 * max(face_sets.shape[0], 1), dtype=np.int64)
    row_ends = np.empty(face_sets.shape[0], dtype=np.int64)
    n = 0
    start = 0
    for k in range(frames.size):
        frame = frames[k]
        frame_nodes, frame_ends = stacked_sets_nodes(face_sets[start:ends[k]], frame, node_offsets, face_base,
                                                     face_offsets, face_half_edges, he_origin)
        if n + frame_nodes.size > nodes.size:
            nodes = _grow(nodes, 2 * (n + frame_nodes.size))
        nodes[n:n + frame_nodes.size] = frame_nodes + node_offsets[frame] + frame
        row_ends[start:ends[k]] = frame_ends + n
        n += frame_nodes.size
        start = ends[k]
    return nodes[:n], row_ends


@nb.njit(cache=True, nogil=True)
def outer_lines(bbox: np.ndarray, thickness: np.ndarray, nearest: np.ndarray, nodes: np.ndarray,
                thin_below: float, around: np.ndarray) -> np.ndarray:
    """Which of ``nodes`` are edge lines outside the others (:meth:`PlaneGraph.outer_lines`):
    thinner than ``thin_below``, their nearest neighbour in colour (``nearest``, -1: none)
    neither one of ``nodes`` nor, where ``around`` (x, y, w, h) has 4 values, inside it."""
    held = np.zeros(thickness.size, dtype=np.bool_)
    for node in nodes:
        held[node] = True
    outer = np.zeros(nodes.size, dtype=np.bool_)
    for i in range(nodes.size):
        if thickness[nodes[i]] >= thin_below:
            continue
        other = nearest[nodes[i]]
        if other < 0 or held[other]:
            continue
        if around.size == 4 and (bbox[other, 0] >= around[0] and bbox[other, 1] >= around[1]
                                 and bbox[other, 2] < around[0] + around[2]
                                 and bbox[other, 3] < around[1] + around[3]):
            continue
        outer[i] = True
    return outer


@nb.njit(cache=True, nogil=True, inline="always")
def _nodes_sides(bbox: np.ndarray, nodes: np.ndarray, keep: np.ndarray, around: np.ndarray) -> np.ndarray:
    """(x0, y0, x1, y1), x1 and y1 exclusive, around the ``nodes`` that ``keep`` and the box
    ``around`` (x, y, w, h: 4 values, or none)."""
    sides = np.array([np.inf, np.inf, -np.inf, -np.inf])
    for i in range(nodes.size):
        if keep[i]:
            node = nodes[i]
            sides[0] = min(sides[0], bbox[node, 0])
            sides[1] = min(sides[1], bbox[node, 1])
            sides[2] = max(sides[2], bbox[node, 2] + 1)
            sides[3] = max(sides[3], bbox[node, 3] + 1)
    if around.size == 4:
        sides[0] = min(sides[0], around[0])
        sides[1] = min(sides[1], around[1])
        sides[2] = max(sides[2], around[0] + around[2])
        sides[3] = max(sides[3], around[1] + around[3])
    return sides


@nb.njit(cache=True, nogil=True)
def nodes_box(bbox: np.ndarray, thickness: np.ndarray, nearest: np.ndarray, nodes: np.ndarray,
              around: np.ndarray, thin_below: float, reach: float) -> np.ndarray:
    """(x, y, w, h) around ``nodes`` and ``around`` (:meth:`PlaneGraph.nodes_box`): where
    ``thin_below`` > 0, each side pulled in past the edge lines outside the others
    (:func:`outer_lines`) when they push it out by at most ``reach``. No nodes: ``around``."""
    if nodes.size == 0:
        return around.copy()
    whole = _nodes_sides(bbox, nodes, np.ones(nodes.size, dtype=np.bool_), around)
    if thin_below > 0:
        outer = outer_lines(bbox, thickness, nearest, nodes, thin_below, around)
        if outer.any() and (around.size == 4 or not outer.all()):
            inner = _nodes_sides(bbox, nodes, ~outer, around)
            for side in range(2):
                if inner[side] - whole[side] <= reach:
                    whole[side] = inner[side]
                if whole[side + 2] - inner[side + 2] <= reach:
                    whole[side + 2] = inner[side + 2]
    return np.array([whole[0], whole[1], whole[2] - whole[0], whole[3] - whole[1]])


@nb.njit(cache=True, nogil=True)
def stacked_nodes_boxes(node_offsets: np.ndarray, bbox: np.ndarray, thickness: np.ndarray, nearest: np.ndarray,
                        frames: np.ndarray, nodes: np.ndarray, ends: np.ndarray, thin_below: float,
                        reach: float) -> np.ndarray:
    """(K, 4) :func:`nodes_box` of each of ``frames`` around its ``nodes[ends[k - 1]:ends[k]]``
    (numbered within the frame), the frames' regions stacked (rows ``node_offsets[t]:
    node_offsets[t + 1]``: :class:`trap_core.rag.StackedGraphs`)."""
    out = np.empty((frames.size, 4))
    no_box = np.zeros(0)
    start = 0
    for k in range(frames.size):
        lo, hi = node_offsets[frames[k]], node_offsets[frames[k] + 1]
        out[k] = nodes_box(bbox[lo:hi], thickness[lo:hi], nearest[lo:hi], nodes[start:ends[k]], no_box, thin_below,
                           reach)
        start = ends[k]
    return out


@nb.njit(cache=True, nogil=True)
def colour_labels(colour: np.ndarray, bins: int) -> np.ndarray:
    """:func:`trap_core.rag.plane_graph.colour_label` of float64 mean colours (n, 3)."""
    label = np.empty(colour.shape[0], dtype=np.int64)
    for i in range(colour.shape[0]):
        r, g, b = colour[i, 0], colour[i, 1], colour[i, 2]
        if r == g and g == b:
            label[i] = bins ** 3 + min(max(np.int64(r * bins ** 2 / 256.0), 0), bins ** 2 - 1)
        else:
            label[i] = ((min(max(np.int64(r * bins / 256.0), 0), bins - 1) * bins
                         + min(max(np.int64(g * bins / 256.0), 0), bins - 1)) * bins
                        + min(max(np.int64(b * bins / 256.0), 0), bins - 1))
    return label


@nb.njit(cache=True, nogil=True)
def median_gain(colour: np.ndarray, carried: np.ndarray, fallback: np.ndarray, dark: float) -> np.ndarray:
    """Per channel: the median of ``colour / carried`` over the rows bright enough (at least
    ``dark``) in both, ``fallback``'s where none is (:mod:`trap_core.rag.label_memory`)."""
    gain = fallback.copy()
    ratios = np.empty(colour.shape[0])
    for channel in range(3):
        n = 0
        for i in range(colour.shape[0]):
            if colour[i, channel] >= dark and carried[i, channel] >= dark:
                ratios[n] = colour[i, channel] / carried[i, channel]
                n += 1
        if n:
            gain[channel] = np.median(ratios[:n])
    return gain


@nb.njit(cache=True, nogil=True)
def remembered_labels(colour: np.ndarray, area: np.ndarray, distance: np.ndarray, nearest: np.ndarray,
                      their_colour: np.ndarray, their_area: np.ndarray, their_carried: np.ndarray,
                      their_label: np.ndarray, gain: np.ndarray, bins: int, reach: float, area_ratio: float,
                      colour_step: float, steady: float, dark: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One frame of :class:`trap_core.rag.label_memory.LabelMemory`: each region's label, its
    colour under the first light and the light's gain, given its ``nearest`` region of the
    previous frame (``their_``: that frame's regions; ``nearest`` empty where there is none)
    and the ``distance`` to it."""
    n = colour.shape[0]
    same = np.zeros(n, dtype=np.bool_)
    for i in range(nearest.size):
        j = nearest[i]
        a, b = area[i], their_area[j]
        if distance[i] <= 0.5 * np.sqrt(a) + reach and b < area_ratio * a and b * area_ratio > a:
            step = 0.0
            for c in range(3):
                step = max(step, abs(colour[i, c] - their_colour[j, c]))
            same[i] = step <= colour_step
    kept = np.flatnonzero(same)
    if kept.size:
        measured = median_gain(colour[kept], their_carried[nearest[kept]], gain, dark)
        change = 0.0
        for c in range(3):
            change = max(change, abs(measured[c] / gain[c] - 1))
        if change > steady:
            gain = measured
    carried = np.empty((n, 3))
    for i in range(n):
        for c in range(3):
            carried[i, c] = colour[i, c] / gain[c]
    for i in kept:
        carried[i] = their_carried[nearest[i]]
    label = colour_labels(carried, bins)
    for i in kept:
        label[i] = their_label[nearest[i]]
    return label, carried, gain
