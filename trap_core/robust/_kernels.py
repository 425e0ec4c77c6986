"""Compiled kernels (numba, ``nogil``) of the robust method's rules: the grown track boxes (which
regions move with a track), the camera's motion (which regions of two consecutive frames are
one), and the passes that read every frame's regions or many patterns' paths in one call. Each
kernel's docstring names the rule it serves."""
from __future__ import annotations

import numba as nb
import numpy as np

from trap_core.mining._kernels import occurrence_geometry
from trap_core.rag._kernels import nodes_box, stacked_face_ids

# An object's part keeps its area from frame to frame; a background region the object passes
# over loses or regains the part it hides, and its barycentre drifts with the object.
AREA_RATIO = 1.25


@nb.njit(cache=True, nogil=True, inline="always")
def _mapped(camera: np.ndarray, x: float, y: float) -> tuple[float, float]:
    """The point (x, y) mapped by the homography ``camera`` (3x3)."""
    scale = camera[2, 0] * x + camera[2, 1] * y + camera[2, 2]
    return (camera[0, 0] * x + camera[0, 1] * y + camera[0, 2]) / scale, \
        (camera[1, 0] * x + camera[1, 1] * y + camera[1, 2]) / scale


@nb.njit(cache=True, nogil=True, inline="always")
def _alike_in_area(area: float, other_area: float, factor: float) -> bool:
    """Whether a region of ``other_area`` is within ``factor`` of ``area`` either way (look-alikes)."""
    return factor * other_area > area and other_area < factor * area


@nb.njit(cache=True, nogil=True)
def moving_regions(near: np.ndarray, centroid: np.ndarray, area: np.ndarray, label: np.ndarray,
                   other_centroid: np.ndarray, other_area: np.ndarray, other_label: np.ndarray,
                   other_by_place: np.ndarray, box: np.ndarray, other_box: np.ndarray, line: np.ndarray,
                   other_line: np.ndarray, camera: np.ndarray, tolerance: float, known: np.ndarray) -> np.ndarray:
    """Mask of the regions ``near`` (rows, :func:`near_box`) that the track's displacement to the
    other frame (``box`` to ``other_box``, or ``line`` to ``other_line``: the boxes centred on
    the line through the track's centres) puts on a look-alike region (same label, area within
    ``AREA_RATIO``, within ``tolerance`` sqrt(area) + 1 px) at least twice as close as the camera's
    motion ``camera`` (3x3) does. ``other_by_place``: the other frame's rows ordered by label, then
    x, so that only the look-alikes within reach of each motion's point are read (over a road or
    gravel of few labels a region has hundreds of look-alikes in the frame). ``known``: per
    region, whether it was found so before for the same frames, motions and camera (-1: not
    looked for yet), filled in here: a box that grows again searches mostly the same regions."""
    shifts = np.empty((2, 2))  # centre to centre, by each reading
    shifts[0] = (other_box[:2] + other_box[2:] / 2) - (box[:2] + box[2:] / 2)
    shifts[1] = (other_line[:2] + other_line[2:] / 2) - (line[:2] + line[2:] / 2)
    found = np.zeros(centroid.shape[0], dtype=np.bool_)
    for i in near:
        if known[i] >= 0:
            found[i] = known[i] == 1
            continue
        cx, cy = centroid[i, 0], centroid[i, 1]
        limit = tolerance * np.sqrt(area[i]) + 1
        # the nearest look-alike to where the track's motion puts the region counts only within
        # ``limit``, and is then within ``limit`` in x: only those are read
        with_track = np.inf
        for s in range(2):
            mx, my = cx + shifts[s, 0], cy + shifts[s, 1]
            for k in range(_first_at(other_label, other_centroid, other_by_place, label[i], mx - limit - 1),
                           other_by_place.size):
                j = other_by_place[k]
                if other_label[j] != label[i] or other_centroid[j, 0] > mx + limit + 1:
                    break
                if _alike_in_area(area[i], other_area[j], AREA_RATIO):
                    with_track = min(with_track, np.hypot(other_centroid[j, 0] - mx, other_centroid[j, 1] - my))
        found[i] = with_track <= limit
        if found[i]:  # unless a look-alike lies within twice that of where the camera's motion puts it
            kx, ky = _mapped(camera, cx, cy)
            for k in range(_first_at(other_label, other_centroid, other_by_place, label[i], kx - 2 * with_track - 1),
                           other_by_place.size):
                j = other_by_place[k]
                if other_label[j] != label[i] or other_centroid[j, 0] > kx + 2 * with_track + 1:
                    break
                if (_alike_in_area(area[i], other_area[j], AREA_RATIO)
                        and np.hypot(other_centroid[j, 0] - kx, other_centroid[j, 1] - ky) / 2 <= with_track):
                    found[i] = False
                    break
        known[i] = 1 if found[i] else 0
    return found


@nb.njit(cache=True, nogil=True)
def near_box(bbox: np.ndarray, area: np.ndarray, around: np.ndarray, reach: float, max_area: float) -> np.ndarray:
    """Rows of the regions whose box meets ``around`` (x, y, w, h) grown by ``reach`` times its
    size on each side, but for those over ``max_area`` times ``around`` whose box does not
    enclose it. Read once per round of a grown box, for both frames its motions are read to."""
    x, y, w, h = around[0], around[1], around[2], around[3]
    rows = np.empty(bbox.shape[0], dtype=np.int64)
    n = 0
    for i in range(bbox.shape[0]):
        if (bbox[i, 2] < x - reach * w or bbox[i, 3] < y - reach * h or bbox[i, 0] > x + w + reach * w
                or bbox[i, 1] > y + h + reach * h):
            continue
        encloses = bbox[i, 0] <= x and bbox[i, 1] <= y and bbox[i, 2] >= x + w - 1 and bbox[i, 3] >= y + h - 1
        if area[i] > max_area * w * h and not encloses:
            continue
        rows[n] = i
        n += 1
    return rows[:n]


@nb.njit(cache=True, nogil=True)
def _first_at(label: np.ndarray, centroid: np.ndarray, by_place: np.ndarray, want_label: int, min_x: float) -> int:
    """First position in ``by_place`` (rows ordered by label, then x) of a region of label
    ``want_label`` at x ``min_x`` or beyond (binary search)."""
    lo, hi = 0, by_place.size
    while lo < hi:
        middle = (lo + hi) // 2
        row = by_place[middle]
        if label[row] < want_label or (label[row] == want_label and centroid[row, 0] < min_x):
            lo = middle + 1
        else:
            hi = middle
    return lo


@nb.njit(cache=True, nogil=True)
def grow_boxes(offsets: np.ndarray, bbox: np.ndarray, centroid: np.ndarray, area: np.ndarray, label: np.ndarray,
               backdrop: np.ndarray, thickness: np.ndarray, nearest: np.ndarray, by_place: np.ndarray,
               frames: np.ndarray, slot: np.ndarray, core: np.ndarray, line: np.ndarray, searched: np.ndarray,
               boxes: np.ndarray, cameras: np.ndarray, lag: int, reach: float, tolerance: float, max_area: float,
               rounds: int, thin_below: float, line_reach: float) -> None:
    """Grow ``searched`` and ``boxes`` (T, 4) of a track's ``frames`` in place over the regions
    that move with it (:func:`trap_core.robust.grow_boxes`). The video's regions are stacked:
    frame ``t``'s are rows ``offsets[t]:offsets[t + 1]`` of ``bbox`` ... ``by_place`` (the last two
    numbered within the frame). ``slot``: row of ``core`` (the boxes motions are read between) of
    each video frame, -1 where none, and of ``line`` (those boxes centred on the line through
    their centres: the second reading of the motion); ``cameras`` (T, 2, 3, 3): the camera's
    motion from each frame to ``lag`` frames before and after. ``thin_below`` > 0: edge lines
    left out of ``boxes`` within ``line_reach`` (:func:`trap_core.rag._kernels.nodes_box`)."""
    n_frames = offsets.size - 1
    for i in range(frames.size):
        frame = frames[i]
        lo, hi = offsets[frame], offsets[frame + 1]
        others = np.empty(2, dtype=np.int64)
        sides = np.empty(2, dtype=np.int64)
        n_sides = 0
        for side, other in enumerate((frame - lag, frame + lag)):
            if 0 <= other < n_frames and slot[other] >= 0:
                others[n_sides] = other
                sides[n_sides] = side
                n_sides += 1
        if n_sides == 0:
            continue
        known = np.full((2, hi - lo), -1, dtype=np.int8)  # each region's verdict per side, for every round
        for round_ in range(rounds if n_sides == 2 else 1):
            moving = np.zeros(hi - lo, dtype=np.bool_) if round_ == 0 else np.ones(hi - lo, dtype=np.bool_)
            near = near_box(bbox[lo:hi], area[lo:hi], searched[i], reach, max_area)
            for k in range(n_sides):
                olo, ohi = offsets[others[k]], offsets[others[k] + 1]
                found = moving_regions(near, centroid[lo:hi], area[lo:hi], label[lo:hi], centroid[olo:ohi],
                                       area[olo:ohi], label[olo:ohi], by_place[olo:ohi], core[slot[frame]],
                                       core[slot[others[k]]], line[slot[frame]], line[slot[others[k]]],
                                       cameras[i, sides[k]], tolerance, known[k])
                moving = (moving | found) if round_ == 0 else (moving & found)
            moving &= ~backdrop[lo:hi]
            held = np.flatnonzero(moving)
            if held.size == 0:
                break
            grown = nodes_box(bbox[lo:hi], thickness[lo:hi], nearest[lo:hi], held, searched[i], 0.0, 0.0)
            if np.all(grown == searched[i]):
                break
            searched[i] = grown
            boxes[i] = nodes_box(bbox[lo:hi], thickness[lo:hi], nearest[lo:hi], held, boxes[i], thin_below,
                                 line_reach) if thin_below > 0 else grown


@nb.njit(cache=True, nogil=True)
def found_again(centroid: np.ndarray, area: np.ndarray, label: np.ndarray, other_centroid: np.ndarray,
                other_area: np.ndarray, other_label: np.ndarray, regions: np.ndarray, shift: np.ndarray,
                camera: np.ndarray, area_factor: float) -> tuple[np.ndarray, np.ndarray]:
    """Per region of ``regions``: the distance from where ``shift`` (a track's motion to the other
    frame) puts it, and from where the camera's motion ``camera`` (3x3) puts it, to the nearest
    region of the other frame of its label and an area within ``area_factor`` of its own; inf
    for both where there is none (:func:`still_core_boxes`, :func:`anchors_found_again`)."""
    with_track = np.full(regions.size, np.inf)
    with_camera = np.full(regions.size, np.inf)
    for k in range(regions.size):
        i = regions[k]
        cx, cy = np.float64(centroid[i, 0]), np.float64(centroid[i, 1])
        mx, my = cx + shift[0], cy + shift[1]
        kx, ky = _mapped(camera, cx, cy)
        for j in range(other_area.size):
            if other_label[j] != label[i] or not _alike_in_area(area[i], other_area[j], area_factor):
                continue
            with_track[k] = min(with_track[k], np.hypot(other_centroid[j, 0] - mx, other_centroid[j, 1] - my))
            with_camera[k] = min(with_camera[k], np.hypot(other_centroid[j, 0] - kx, other_centroid[j, 1] - ky))
    return with_track, with_camera


@nb.njit(cache=True, nogil=True)
def still_core_boxes(node_offsets: np.ndarray, bbox: np.ndarray, centroid: np.ndarray, area: np.ndarray,
                     label: np.ndarray, thickness: np.ndarray, nearest: np.ndarray, frames: np.ndarray,
                     core: np.ndarray, core_ends: np.ndarray, top: np.ndarray, top_ends: np.ndarray,
                     slot: np.ndarray, points: np.ndarray, cameras: np.ndarray, boxes: np.ndarray, lag: int,
                     area_factor: float, thin_below: float, line_reach: float) -> None:
    """Rebuild ``boxes`` (a track's, rows ``slot[frame]``) in place without the core regions
    that stand still (:func:`trap_core.robust.drop_still_regions`): per frame ``frames[k]``, its
    core regions ``core[core_ends[k - 1]:core_ends[k]]`` other than the most held ones (``top``,
    alike) found again, in every frame ``lag`` away the track covers, at most half as far from
    where the camera's motion (``cameras[k, side]``, before and after) puts them as from where
    the track's ``points`` move. The video's regions are stacked as for :func:`grow_boxes`."""
    n_frames = node_offsets.size - 1
    no_box = np.zeros(0)
    core_start = top_start = 0
    for k in range(frames.size):
        frame = frames[k]
        here_core, anchor = core[core_start:core_ends[k]], top[top_start:top_ends[k]]
        core_start, top_start = core_ends[k], top_ends[k]
        i = slot[frame]
        if i < 0:
            continue
        keep = np.ones(here_core.size, dtype=np.bool_)
        for c in range(here_core.size):
            for a in range(anchor.size):
                if here_core[c] == anchor[a]:
                    keep[c] = False
        others = here_core[keep]
        if others.size == 0:
            continue
        still = np.ones(others.size, dtype=np.bool_)
        tested = False
        lo, hi = node_offsets[frame], node_offsets[frame + 1]
        for side, other in enumerate((frame - lag, frame + lag)):
            j = slot[other] if 0 <= other < n_frames else -1
            if j < 0:
                continue
            shift = points[j] - points[i]
            if np.isnan(shift).any():
                continue
            tested = True
            olo, ohi = node_offsets[other], node_offsets[other + 1]
            with_track, with_camera = found_again(centroid[lo:hi], area[lo:hi], label[lo:hi], centroid[olo:ohi],
                                                  area[olo:ohi], label[olo:ohi], others, shift, cameras[k, side],
                                                  area_factor)
            still &= 2 * with_camera < with_track
        if not tested or not still.any():
            continue
        held = np.concatenate((anchor, others[~still]))
        boxes[i] = nodes_box(bbox[lo:hi], thickness[lo:hi], nearest[lo:hi], held, no_box, thin_below, line_reach)


@nb.njit(cache=True, nogil=True, inline="always")
def _reaches_edge(x0: float, y0: float, x1: float, y1: float, width: float, height: float) -> bool:
    """Whether a box (x0, y0, x1, y1 inclusive, whole pixels) touches the edge of a ``width`` x
    ``height`` image (:func:`trap_core.clustering.reaches_border` with margin 0)."""
    return x0 <= 0 or y0 <= 0 or x1 + 1 >= width or y1 + 1 >= height


@nb.njit(cache=True, nogil=True)
def region_steps(node_offsets: np.ndarray, bbox: np.ndarray, centroid: np.ndarray, area: np.ndarray,
                 label: np.ndarray, backdrop: np.ndarray, by_place: np.ndarray, reach: float,
                 max_ratio: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Regions matched between consecutive frames (:func:`trap_core.robust.camera_paths`): of the
    regions that are not the ``backdrop`` and do not reach the frame's edge, pairs of one label,
    areas within ``max_ratio`` of each other, each the other's nearest such within ``reach`` px
    (the lower row on a tie). The video's regions are stacked as for :func:`grow_boxes`; each
    region searches the next frame's of its label by place (``by_place``), within ``reach`` in x.
    Returns the pairs' rows in the stacked arrays, and the first one's frame, by frame then row."""
    n_frames = node_offsets.size - 1
    inner = np.zeros(area.size, dtype=np.bool_)
    for t in range(n_frames):
        lo, hi = node_offsets[t], node_offsets[t + 1]
        if hi == lo:
            continue
        width, height = bbox[lo:hi, 2].max() + 1, bbox[lo:hi, 3].max() + 1
        for r in range(lo, hi):
            inner[r] = not backdrop[r] and not _reaches_edge(bbox[r, 0], bbox[r, 1], bbox[r, 2], bbox[r, 3], width,
                                                             height)
    first, second, frames = [], [], []
    placed = np.empty(area.size, dtype=np.int64)  # the next frame's inner regions, by label then x
    best_next = np.empty(area.size, dtype=np.int64)
    best_next_distance = np.empty(area.size)
    best_here = np.empty(area.size, dtype=np.int64)
    best_here_distance = np.empty(area.size)
    for t in range(n_frames - 1):
        lo, hi, nlo, nhi = node_offsets[t], node_offsets[t + 1], node_offsets[t + 1], node_offsets[t + 2]
        n_placed = 0
        for k in range(nhi - nlo):
            r = nlo + by_place[nlo + k]
            if inner[r]:
                placed[n_placed] = r
                n_placed += 1
        best_next[lo:hi] = -1
        best_next_distance[lo:hi] = np.inf
        best_here[nlo:nhi] = -1
        best_here_distance[nlo:nhi] = np.inf
        for i in range(lo, hi):
            if not inner[i]:
                continue
            x, y = np.float64(centroid[i, 0]), np.float64(centroid[i, 1])
            low, high = 0, n_placed  # the first placed region of this label and x - reach or more
            while low < high:
                mid = (low + high) // 2
                other = placed[mid]
                if label[other] < label[i] or (label[other] == label[i] and centroid[other, 0] < x - reach):
                    low = mid + 1
                else:
                    high = mid
            for k in range(low, n_placed):
                j = placed[k]
                if label[j] != label[i] or centroid[j, 0] > x + reach:
                    break
                if area[i] > max_ratio * area[j] or area[j] > max_ratio * area[i]:
                    continue
                dx, dy = x - np.float64(centroid[j, 0]), y - np.float64(centroid[j, 1])
                distance = np.sqrt(dx * dx + dy * dy)
                if distance > reach:
                    continue
                if distance < best_next_distance[i] or (distance == best_next_distance[i] and j < best_next[i]):
                    best_next_distance[i] = distance
                    best_next[i] = j
                if distance < best_here_distance[j]:  # rows come in order: the lower one is kept on a tie
                    best_here_distance[j] = distance
                    best_here[j] = i
        for i in range(lo, hi):
            if best_next[i] >= 0 and best_here[best_next[i]] == i:
                first.append(i)
                second.append(best_next[i])
                frames.append(t)
    return np.array(first, dtype=np.int64), np.array(second, dtype=np.int64), np.array(frames, dtype=np.int64)


@nb.njit(cache=True, nogil=True)
def rejoin_candidates(share: np.ndarray, overlap: np.ndarray, start: np.ndarray, end: np.ndarray, max_overlap: int,
                      min_similarity: float, near_gap: int, near_counts: bool, to_border: np.ndarray,
                      from_border: np.ndarray, leaves: np.ndarray, enters: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The pairs (earlier, later) of fragments that may be one object's, in row order
    (:func:`trap_core.robust.rejoin_fragments`): ``later`` starts after ``earlier``, they share at
    most ``max_overlap`` frames (``overlap``: (C, C)), and either one's ``share`` of structures in
    the other is at least ``min_similarity`` or, with ``near_counts``, ``later`` starts at most
    ``near_gap`` frames after ``earlier`` ends. With the four border flags (per fragment; empty:
    not read), ``earlier`` may go to the border and ``later`` come from it, or neither left nor
    entered. One pass over the pairs, as a textured scene has thousands of fragments."""
    first, second = [], []
    bordered = to_border.size > 0
    for i in range(start.size):
        for j in range(start.size):
            if start[i] >= start[j] or overlap[i, j] > max_overlap:
                continue
            if not (share[i, j] >= min_similarity or share[j, i] >= min_similarity
                    or (near_counts and start[j] - end[i] <= near_gap)):
                continue
            if bordered and not ((to_border[i] and from_border[j]) or (not leaves[i] and not enters[j])):
                continue
            first.append(i)
            second.append(j)
    return np.array(first, dtype=np.int64), np.array(second, dtype=np.int64)


@nb.njit(cache=True, nogil=True)
def long_overlaps(overlap: np.ndarray, length: np.ndarray, min_frames: int, min_share: float
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The pairs i < j, in row order, that share (``overlap``: (C, C) frames) at least
    ``min_frames`` frames and ``min_share`` of the shorter one's ``length``: candidates for
    going along one object (:func:`trap_core.robust.rejoin._going_along`)."""
    first, second = [], []
    for i in range(length.size):
        for j in range(i + 1, length.size):
            if overlap[i, j] >= min_frames and overlap[i, j] >= min_share * min(length[i], length[j]):
                first.append(i)
                second.append(j)
    return np.array(first, dtype=np.int64), np.array(second, dtype=np.int64)


@nb.njit(cache=True, nogil=True)
def away_from_boxes(clusters: np.ndarray, first: int, last: int, covered: np.ndarray, start: np.ndarray,
                    offsets: np.ndarray, points: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """Per cluster of ``clusters``: whether, of frames ``first``..``last``, it covers at least half
    (``covered``: (C, n_frames)) and, in at least half, its path (``start``, ``offsets``,
    ``points``: :class:`~trap_core.clustering.Trajectories`) lies in none of the ``boxes``
    ((T, n_frames, 4) x, y, w, h; NaN where none, edges inside): a cluster that may hold a
    track's object where that track's boxes repeat another's
    (:func:`trap_core.robust.continuation.mend_shared_stretches`)."""
    half = (last - first + 1) / 2
    out = np.zeros(clusters.size, dtype=np.bool_)
    for k in range(clusters.size):
        cluster = clusters[k]
        seen = 0
        away = 0
        for frame in range(first, last + 1):
            if not covered[cluster, frame]:
                continue
            seen += 1
            row = offsets[cluster] + frame - start[cluster]
            x, y = points[row, 0], points[row, 1]
            held = False
            for t in range(boxes.shape[0]):
                box = boxes[t, frame]
                if x >= box[0] and y >= box[1] and x <= box[0] + box[2] and y <= box[1] + box[3]:
                    held = True
                    break
            away += not held
        out[k] = seen >= half and away >= half
    return out


@nb.njit(cache=True, nogil=True)
def pairs_within(first: np.ndarray, second: np.ndarray, both: np.ndarray, reach: float, covered: np.ndarray,
                 start: np.ndarray, offsets: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Per pair (``first[i]``, ``second[i]``) of clusters: whether their paths (``start``,
    ``offsets``, ``points``: :class:`~trap_core.clustering.Trajectories`) are on average at most
    ``reach`` apart over the ``both[i]`` (> 0) frames both cover (``covered``: (C, n_frames)).
    Only the frames of the two spans are read, and a pair's reading stops once its distances
    sum beyond ``reach`` times ``both[i]``: most pairs lie far apart, and that shows in a few
    frames."""
    out = np.zeros(first.size, dtype=np.bool_)
    for i in range(first.size):
        a, b = first[i], second[i]
        lo = max(start[a], start[b])
        hi = min(start[a] + offsets[a + 1] - offsets[a], start[b] + offsets[b + 1] - offsets[b])
        beyond = reach * both[i] * (1.0 + 1e-9)  # a sum past this is a mean past reach, whatever rounding
        total = 0.0
        count = 0
        for frame in range(lo, hi):
            if covered[a, frame] and covered[b, frame]:
                pa = offsets[a] + frame - start[a]
                pb = offsets[b] + frame - start[b]
                dx = points[pa, 0] - points[pb, 0]
                dy = points[pa, 1] - points[pb, 1]
                total += np.sqrt(dx * dx + dy * dy)
                count += 1
                if total > beyond:
                    break
        out[i] = count > 0 and total / count <= reach
    return out


@nb.njit(cache=True, nogil=True)
def group_distances(first: np.ndarray, second: np.ndarray, frames: np.ndarray, covered: np.ndarray,
                    start: np.ndarray, offsets: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Per frame of ``frames``: the distance between the mean positions of the clusters in the
    masks ``first`` and ``second`` that cover it (``covered``: (C, n_frames); each frame covered
    by both; paths as in :func:`pairs_within`), each mean summed in cluster order."""
    first_sums, first_counts = _group_sums(first, covered, start, offsets, points)
    second_sums, second_counts = _group_sums(second, covered, start, offsets, points)
    out = np.empty(frames.size)
    for k in range(frames.size):
        frame = frames[k]
        dx = first_sums[frame, 0] / first_counts[frame] - second_sums[frame, 0] / second_counts[frame]
        dy = first_sums[frame, 1] / first_counts[frame] - second_sums[frame, 1] / second_counts[frame]
        out[k] = np.sqrt(dx * dx + dy * dy)
    return out


@nb.njit(cache=True, nogil=True)
def _group_sums(members: np.ndarray, covered: np.ndarray, start: np.ndarray, offsets: np.ndarray,
                points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per frame of the video: the sum of the positions of the clusters in the mask ``members``
    that cover it, added in cluster order, and how many they are."""
    sums = np.zeros((covered.shape[1], 2))
    counts = np.zeros(covered.shape[1])
    for cluster in range(members.size):
        if members[cluster]:
            for frame in range(start[cluster], start[cluster] + offsets[cluster + 1] - offsets[cluster]):
                if covered[cluster, frame]:
                    row = offsets[cluster] + frame - start[cluster]
                    sums[frame, 0] += points[row, 0]
                    sums[frame, 1] += points[row, 1]
                    counts[frame] += 1
    return sums, counts


@nb.njit(cache=True, nogil=True)
def _numpy_sum(values: np.ndarray, lo: int, n: int) -> float:
    """Sum of ``values[lo:lo + n]`` added as numpy adds a float64 array, so that a mean taken here
    has the bits of ``np.mean``: halves (cut at multiples of 8) summed apart and added, down to
    blocks of at most 128 (:func:`_block_sum`). Walked with a stack of its own: numba's cache
    does not load recursive functions safely."""
    first = np.empty(64, dtype=np.int64)
    size = np.empty(64, dtype=np.int64)
    step = np.zeros(64, dtype=np.int8)  # 0: left half next, 1: right half next, 2: add the halves
    left = np.empty(64)
    top, total = 0, 0.0
    first[0], size[0] = lo, n
    while top >= 0:
        if size[top] <= 128:
            total = _block_sum(values, first[top], size[top])
            top -= 1
            continue
        half = size[top] // 2
        half -= half % 8
        if step[top] == 0:
            step[top] = 1
            top += 1
            first[top], size[top], step[top] = first[top - 1], half, 0
        elif step[top] == 1:
            left[top], step[top] = total, 2
            top += 1
            first[top], size[top], step[top] = first[top - 1] + half, size[top - 1] - half, 0
        else:
            total = left[top] + total
            top -= 1
    return total


@nb.njit(cache=True, nogil=True)
def _block_sum(values: np.ndarray, lo: int, n: int) -> float:
    """numpy's sum of at most 128 float64 values: in order under 8, else eight running sums
    added pairwise, then the rest in order."""
    if n < 8:
        total = 0.0
        for i in range(n):
            total += values[lo + i]
        return total
    r0, r1, r2, r3 = values[lo], values[lo + 1], values[lo + 2], values[lo + 3]
    r4, r5, r6, r7 = values[lo + 4], values[lo + 5], values[lo + 6], values[lo + 7]
    i = 8
    while i < n - n % 8:
        r0 += values[lo + i]
        r1 += values[lo + i + 1]
        r2 += values[lo + i + 2]
        r3 += values[lo + i + 3]
        r4 += values[lo + i + 4]
        r5 += values[lo + i + 5]
        r6 += values[lo + i + 6]
        r7 += values[lo + i + 7]
        i += 8
    total = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < n:
        total += values[lo + i]
        i += 1
    return total


@nb.njit(cache=True, nogil=True)
def companions_apart(group: np.ndarray, group_covered: np.ndarray, companions: np.ndarray, covered: np.ndarray,
                     start: np.ndarray, offsets: np.ndarray, points: np.ndarray,
                     max_apart: float) -> tuple[int, int]:
    """Of the ``companions`` (clusters) seen in frames the clusters in the mask ``group`` cover
    (``group_covered``): how many are, and how many of those are on average more than
    ``max_apart`` px from the group over those frames (each frame's distance as
    :func:`group_distances`, their mean as ``np.mean``)."""
    sums, counts = _group_sums(group, covered, start, offsets, points)
    distances = np.empty(covered.shape[1])
    seen, apart = 0, 0
    for companion in companions:
        n = 0
        for frame in range(start[companion], start[companion] + offsets[companion + 1] - offsets[companion]):
            if group_covered[frame] and covered[companion, frame]:
                row = offsets[companion] + frame - start[companion]
                dx = sums[frame, 0] / counts[frame] - points[row, 0]
                dy = sums[frame, 1] / counts[frame] - points[row, 1]
                distances[n] = np.sqrt(dx * dx + dy * dy)
                n += 1
        if n:
            seen += 1
            apart += _numpy_sum(distances, 0, n) / n > max_apart
    return seen, apart


@nb.njit(cache=True, nogil=True)
def any_pair_apart(patterns: np.ndarray, sizes: np.ndarray, min_frames: int, start: np.ndarray, end: np.ndarray,
                   offsets: np.ndarray, points: np.ndarray) -> bool:
    """Whether two of ``patterns`` are further apart than half the sum of their ``sizes`` in at
    least ``min_frames`` of the frames both cover (paths as in :func:`pairs_within`; a
    pair stops being read once it has that many)."""
    if min_frames <= 0:
        return patterns.size > 1
    for i in range(patterns.size - 1):
        a = patterns[i]
        for j in range(i + 1, patterns.size):
            b = patterns[j]
            limit = (sizes[b] + sizes[a]) / 2
            count = 0
            for frame in range(max(start[a], start[b]), min(end[a], end[b]) + 1):
                dx = points[offsets[b] + frame - start[b], 0] - points[offsets[a] + frame - start[a], 0]
                dy = points[offsets[b] + frame - start[b], 1] - points[offsets[a] + frame - start[a], 1]
                if np.sqrt(dx * dx + dy * dy) > limit:
                    count += 1
                    if count >= min_frames:
                        return True
    return False


@nb.njit(cache=True, nogil=True)
def any_pair_far(patterns: np.ndarray, distances: np.ndarray, n: int, start: np.ndarray, end: np.ndarray,
                 sizes: np.ndarray) -> bool:
    """Whether two of ``patterns`` (of ``n`` clustered) that share at least two frames are further
    apart on average over them than half the sum of their ``sizes``: the mean distance is
    recovered from the condensed ``distances`` ``d_traj * (2 - d_ov)`` (TRAP_SPEC section 5),
    pair by pair, so that no (n, n) matrix is built and the first such pair ends the search."""
    for i in range(patterns.size - 1):
        for j in range(i + 1, patterns.size):
            a, b = min(patterns[i], patterns[j]), max(patterns[i], patterns[j])
            common = min(end[a], end[b]) - max(start[a], start[b]) + 1
            if common < 2:
                continue
            shared = common / ((end[a] - start[a] + 1) + (end[b] - start[b] + 1) - common)
            mean_distance = distances[n * a - a * (a + 1) // 2 + b - a - 1] / (2 - shared)
            if mean_distance > (sizes[a] + sizes[b]) / 2:
                return True
    return False


@nb.njit(cache=True, nogil=True)
def near_paths(mine: np.ndarray, theirs: np.ndarray, reach: np.float32) -> np.ndarray:
    """(len(mine), n_frames) whether path ``mine[i]`` has one of ``theirs`` within ``reach`` in
    each frame (paths (k, n_frames, 2), float32, NaN where not seen). Distances are taken in
    float32, as numpy takes them of float32 points."""
    near = np.zeros(mine.shape[:2], dtype=np.bool_)
    for frame in range(mine.shape[1]):
        for i in range(mine.shape[0]):
            if np.isnan(mine[i, frame, 0]):
                continue
            for j in range(theirs.shape[0]):
                if np.isnan(theirs[j, frame, 0]):
                    continue
                dx = mine[i, frame, 0] - theirs[j, frame, 0]
                dy = mine[i, frame, 1] - theirs[j, frame, 1]
                if np.sqrt(dx * dx + dy * dy) <= reach:
                    near[i, frame] = True
                    break
    return near


@nb.njit(cache=True, nogil=True)
def goes_along(short_rows: np.ndarray, long_rows: np.ndarray, sizes: np.ndarray, start: np.ndarray, end: np.ndarray,
               offsets: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Per pattern of ``short_rows``: whether one of ``long_rows`` lies within half the smaller
    of their ``sizes`` of it in at least half of its frames (paths as in
    :func:`pairs_within`; points and reach in float32, to ``(reach / 2) ** 2``)."""
    along = np.zeros(short_rows.size, dtype=np.bool_)
    for i in range(short_rows.size):
        a = short_rows[i]
        length = end[a] - start[a] + 1
        for b in long_rows:
            first, last = max(start[a], start[b]), min(end[a], end[b])
            if first > last:
                continue
            reach = np.float32(min(sizes[b], sizes[a])) / np.float32(2)
            limit = reach * reach
            count = 0
            for frame in range(first, last + 1):
                dx = np.float32(points[offsets[b] + frame - start[b], 0]) - np.float32(points[offsets[a] + frame - start[a], 0])
                dy = np.float32(points[offsets[b] + frame - start[b], 1]) - np.float32(points[offsets[a] + frame - start[a], 1])
                if dx * dx + dy * dy <= limit:
                    count += 1
            if 2 * count >= length:
                along[i] = True
                break
    return along


@nb.njit(cache=True, nogil=True, inline="always")
def _world_point(frame: np.ndarray, position: np.ndarray, inverse: np.ndarray, i: int) -> tuple[float, float]:
    """Observation ``i``'s ``position`` mapped to the world by its frame's ``inverse`` transform."""
    x, y, f = np.float64(position[i, 0]), np.float64(position[i, 1]), frame[i]
    return (inverse[f, 0, 2] + inverse[f, 0, 0] * x + inverse[f, 0, 1] * y,
            inverse[f, 1, 2] + inverse[f, 1, 0] * x + inverse[f, 1, 1] * y)


@nb.njit(cache=True, nogil=True, inline="always")
def _apart(frame: np.ndarray, position: np.ndarray, inverse: np.ndarray, i: int, j: int) -> float:
    """World distance from observation ``i`` to ``j`` (:func:`_world_point`)."""
    xi, yi = _world_point(frame, position, inverse, i)
    xj, yj = _world_point(frame, position, inverse, j)
    dx, dy = xj - xi, yj - yi
    return np.sqrt(dx * dx + dy * dy)


@nb.njit(cache=True, nogil=True, inline="always")
def _median(values: np.ndarray) -> float:
    """The median of ``values``: for an even count, half the sum of the two middle ones."""
    ordered = np.sort(values)
    return 0.5 * (ordered[(ordered.size - 1) // 2] + ordered[ordered.size // 2])


@nb.njit(cache=True, nogil=True, inline="always")
def _run_end(pattern: np.ndarray, lo: int) -> int:
    """Where the run of observations of ``pattern[lo]`` that starts at ``lo`` ends (sorted by pattern)."""
    hi = lo + 1
    while hi < pattern.size and pattern[hi] == pattern[lo]:
        hi += 1
    return hi


@nb.njit(cache=True, nogil=True)
def _longest_run(pattern: np.ndarray) -> int:
    """The most observations of one pattern (sorted by pattern): the buffers' size."""
    longest, lo = 0, 0
    while lo < pattern.size:
        hi = _run_end(pattern, lo)
        longest, lo = max(longest, hi - lo), hi
    return longest


@nb.njit(cache=True, nogil=True)
def world_speeds(pattern: np.ndarray, frame: np.ndarray, position: np.ndarray, inverse: np.ndarray, lag: int,
                 n_patterns: int) -> np.ndarray:
    """:func:`trap_core.robust.world_speed` of observations sorted by ``pattern``, then ``frame``:
    per pattern, the median over its observations of the world displacement to its first
    observation at least ``lag`` frames later, per frame (first to last for a pattern seen for
    less than ``lag`` frames; 0 for one seen once)."""
    speed = np.zeros(n_patterns)
    rates = np.empty(_longest_run(pattern))
    lo = 0
    while lo < frame.size:
        hi = _run_end(pattern, lo)
        k = 0
        later = lo
        for i in range(lo, hi):
            while later < hi and frame[later] < frame[i] + lag:
                later += 1
            if later == hi:
                break
            rates[k] = _apart(frame, position, inverse, i, later) / (frame[later] - frame[i])
            k += 1
        if k == 0 and hi - 1 > lo:
            rates[0] = _apart(frame, position, inverse, lo, hi - 1) / (frame[hi - 1] - frame[lo])
            k = 1
        if k:
            speed[pattern[lo]] = _median(rates[:k])
        lo = hi
    return speed


@nb.njit(cache=True, nogil=True)
def world_step_sums(pattern: np.ndarray, frame: np.ndarray, position: np.ndarray, inverse: np.ndarray, hop: float,
                    max_gap: int, n_patterns: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """For :func:`trap_core.robust.world_steps`, from the world displacements between consecutive
    observations (sorted by ``pattern``, then ``frame``) at most ``max_gap`` frames apart, per
    pattern: their median per frame (NaN without any), their summed length, the frames they
    span, and the length of those of at least ``hop`` px."""
    median = np.full(n_patterns, np.nan)
    path, frames, hopped = np.zeros(n_patterns), np.zeros(n_patterns), np.zeros(n_patterns)
    steps = np.empty(_longest_run(pattern))
    lo = 0
    while lo < frame.size:
        hi = _run_end(pattern, lo)
        p, k = pattern[lo], 0
        for i in range(lo, hi - 1):
            gap = frame[i + 1] - frame[i]
            if 0 < gap <= max_gap:
                length = _apart(frame, position, inverse, i, i + 1)
                steps[k] = length / gap
                k += 1
                path[p] += length
                frames[p] += gap
                if length >= hop:
                    hopped[p] += length
        if k:
            median[p] = _median(steps[:k])
        lo = hi
    return median, path, frames, hopped


@nb.njit(cache=True, nogil=True)
def window_lines(centres: np.ndarray, starts: np.ndarray, window: int) -> tuple[np.ndarray, np.ndarray]:
    """Per start: the Theil-Sen line (velocity, position at frame 0) through the ``centres``
    (n_frames, 2; NaN where not seen) seen in frames ``start..start + window - 1`` (clipped to the
    video), and whether it could be drawn (three centres at least; NaN lines where not): what
    :func:`trap_core.robust.motion.straight_line` gives for each window, in one call."""
    lines = np.full((starts.size, 2, 2), np.nan)
    drawn = np.zeros(starts.size, dtype=np.bool_)
    for s in range(starts.size):
        lo, hi = max(starts[s], 0), min(starts[s] + window, centres.shape[0])
        count = 0
        for frame in range(lo, hi):
            if not np.isnan(centres[frame, 0]):
                count += 1
        if count < 3:
            continue
        points = np.empty((count, 2))
        frames = np.empty(count)
        count = 0
        for frame in range(lo, hi):
            if not np.isnan(centres[frame, 0]):
                points[count, 0], points[count, 1] = centres[frame, 0], centres[frame, 1]
                frames[count] = frame
                count += 1
        lines[s, 0], lines[s, 1] = theil_sen(points, frames)
        drawn[s] = True
    return lines, drawn


@nb.njit(cache=True, nogil=True)
def theil_sen(points: np.ndarray, frames: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Velocity and position at frame 0 of the Theil-Sen line through ``points`` (k, 2) seen in
    ``frames`` (k,, distinct, k >= 2): per axis, the median of the pairwise slopes, then the
    median of the offsets (:func:`trap_core.robust.motion.straight_line`)."""
    k = frames.size
    slopes = np.empty(k * (k - 1) // 2)
    offsets = np.empty(k)
    velocity = np.empty(2)
    origin = np.empty(2)
    for axis in range(2):
        n = 0
        for i in range(k):
            for j in range(i + 1, k):
                slopes[n] = (points[j, axis] - points[i, axis]) / (frames[j] - frames[i])
                n += 1
        velocity[axis] = np.median(slopes)
        for i in range(k):
            offsets[i] = points[i, axis] - velocity[axis] * frames[i]
        origin[axis] = np.median(offsets)
    return velocity, origin


@nb.njit(cache=True, nogil=True)
def stray_rows(centres: np.ndarray, frames: np.ndarray, window: int, limit: float) -> np.ndarray:
    """Per frame of ``frames`` (a track's, increasing): whether its centre (``centres``: the
    track's, one per frame from 0, NaN where it has none) lies farther than ``limit`` from the
    :func:`theil_sen` line through the other centres within ``window`` frames (not with fewer
    than three of them) (:func:`trap_core.robust.drop_strays`)."""
    n = centres.shape[0]
    stray = np.zeros(frames.size, dtype=np.bool_)
    seen = np.empty(2 * window, dtype=np.float64)
    points = np.empty((2 * window, 2), dtype=np.float64)
    for row in range(frames.size):
        frame = frames[row]
        k = 0
        for other in range(max(frame - window, 0), min(frame + window, n - 1) + 1):
            if other != frame and not np.isnan(centres[other, 0]):
                seen[k] = other
                points[k, 0] = centres[other, 0]
                points[k, 1] = centres[other, 1]
                k += 1
        if k < 3:
            continue
        velocity, origin = theil_sen(points[:k], seen[:k])
        dx = centres[frame, 0] - (origin[0] + velocity[0] * frame)
        dy = centres[frame, 1] - (origin[1] + velocity[1] * frame)
        stray[row] = np.sqrt(dx * dx + dy * dy) > limit
    return stray


@nb.njit(cache=True, nogil=True)
def anchors_found_again(node_offsets: np.ndarray, centroid: np.ndarray, area: np.ndarray, label: np.ndarray,
                        frames: np.ndarray, top: np.ndarray, top_ends: np.ndarray, positions: np.ndarray,
                        cameras: np.ndarray, lag: int, area_factor: float) -> tuple[int, int]:
    """How many of a cluster's anchors go with it and how many stay with the scene
    (:func:`trap_core.robust.stays_with_scene`): in each of ``frames`` that is a multiple of
    ``lag`` and where its mean path ``positions`` (n_frames, 2; NaN where it has none) is known,
    its anchors (``top[top_ends[k - 1]:top_ends[k]]``, :class:`~trap_core.clustering.FrameCores`)
    are looked for again ``lag`` frames before and after (where the path is known too): found
    at most half as far from where the cluster's motion puts them as from where the camera's
    (``cameras[k, side]``) does, they go with it; the other way round, they stay. The video's
    regions are stacked as for :func:`grow_boxes`."""
    n_frames = node_offsets.size - 1
    with_cluster = with_scene = 0
    top_start = 0
    for k in range(frames.size):
        frame = frames[k]
        anchor = top[top_start:top_ends[k]]
        top_start = top_ends[k]
        if frame % lag != 0 or np.isnan(positions[frame, 0]) or np.isnan(positions[frame, 1]):
            continue
        lo, hi = node_offsets[frame], node_offsets[frame + 1]
        for side, other in enumerate((frame - lag, frame + lag)):
            if not 0 <= other < n_frames or np.isnan(positions[other, 0]) or np.isnan(positions[other, 1]):
                continue
            olo, ohi = node_offsets[other], node_offsets[other + 1]
            near_cluster, near_scene = found_again(centroid[lo:hi], area[lo:hi], label[lo:hi], centroid[olo:ohi],
                                                   area[olo:ohi], label[olo:ohi], anchor,
                                                   positions[other] - positions[frame], cameras[k, side], area_factor)
            for a in range(anchor.size):
                if 2 * near_cluster[a] < near_scene[a]:
                    with_cluster += 1
                if 2 * near_scene[a] < near_cluster[a]:
                    with_scene += 1
    return with_cluster, with_scene


@nb.njit(cache=True, nogil=True)
def _grouped(keys: np.ndarray, n_keys: int) -> tuple[np.ndarray, np.ndarray]:
    """The entries of ``keys`` (each in ``0..n_keys-1``) grouped by key, in order within a key,
    and where each key's group starts (CSR offsets, ``n_keys + 1`` of them)."""
    offsets = np.zeros(n_keys + 1, dtype=np.int64)
    for key in keys:
        offsets[key + 1] += 1
    for key in range(n_keys):
        offsets[key + 1] += offsets[key]
    cursor = offsets[:-1].copy()
    entries = np.empty(keys.size, dtype=np.int64)
    for e in range(keys.size):
        entries[cursor[keys[e]]] = e
        cursor[keys[e]] += 1
    return entries, offsets


@nb.njit(cache=True, nogil=True)
def shared_support(holders: np.ndarray, nodes: np.ndarray, n_nodes: int, cluster: np.ndarray, weight: np.ndarray,
                   n_clusters: int) -> tuple[np.ndarray, np.ndarray]:
    """For each sighting (a pattern in one frame, of cluster ``cluster``), the ``weight`` of the
    other sightings that hold a region with it, summed by their cluster (sightings, clusters),
    and how many of those are of its own cluster (:func:`trap_core.robust.hand_to_owners`).
    ``holders[e]`` holds region ``nodes[e]`` (ids below ``n_nodes``), a pair may repeat."""
    n = cluster.size
    by_holder, holder_offsets = _grouped(holders, n)
    by_node, node_offsets = _grouped(nodes, n_nodes)
    support = np.zeros((n, n_clusters))
    own_sharers = np.zeros(n, dtype=np.int64)
    counted_for = np.full(n, -1, dtype=np.int64)  # the sighting each other one was last counted for
    for s in range(n):
        counted_for[s] = s
        for e in by_holder[holder_offsets[s]:holder_offsets[s + 1]]:
            node = nodes[e]
            for f in by_node[node_offsets[node]:node_offsets[node + 1]]:
                other = holders[f]
                if counted_for[other] != s:
                    counted_for[other] = s
                    support[s, cluster[other]] += weight[other]
                    if cluster[other] == cluster[s]:
                        own_sharers[s] += 1
    return support, own_sharers


@nb.njit(cache=True, nogil=True)
def backdrop_free_geometry(occ_frame: np.ndarray, occ_faces: np.ndarray, node_offsets: np.ndarray,
                           face_base: np.ndarray, face_offsets: np.ndarray, face_half_edges: np.ndarray,
                           he_origin: np.ndarray, centroid: np.ndarray, bbox: np.ndarray, backdrop: np.ndarray,
                           position: np.ndarray, box: np.ndarray) -> None:
    """:func:`trap_core.robust.without_backdrop` in one pass: each occurrence (its frame and face
    set, faces numbered within the frame) of a frame with a backdrop that holds other regions
    too gets, in ``position`` and ``box``, the :func:`~trap_core.mining._kernels.occurrence_geometry`
    of those others. The video's regions are stacked as for :func:`grow_boxes`."""
    n_frames = node_offsets.size - 1
    by_frame, frame_offsets = _grouped(occ_frame, n_frames)
    for t in range(n_frames):
        lo, hi = node_offsets[t], node_offsets[t + 1]
        rows = by_frame[frame_offsets[t]:frame_offsets[t + 1]]
        if rows.size == 0 or not backdrop[lo:hi].any():
            continue
        placed, boxed, _ = occurrence_geometry(stacked_face_ids(occ_faces[rows], face_base[t]), he_origin,
                                               face_half_edges, face_offsets, centroid[lo:hi], bbox[lo:hi],
                                               backdrop[lo:hi])
        for k in range(rows.size):
            if not np.isnan(placed[k, 0]):
                for c in range(2):
                    position[rows[k], c] = placed[k, c]
                for c in range(4):
                    box[rows[k], c] = boxed[k, c]


@nb.njit(cache=True, nogil=True)
def cut_counts(st_offsets: np.ndarray, st_rows: np.ndarray, patterns: np.ndarray, occ_box: np.ndarray,
               width: float, height: float) -> np.ndarray:
    """Per spatio-temporal pattern of ``patterns``: how many of its occurrences have regions that
    reach the image's edge (their box x0, y0, x1, y1 inclusive; :func:`trap_core.robust.border_share`)."""
    counts = np.zeros(patterns.size, dtype=np.int64)
    for k in range(patterns.size):
        for a in range(st_offsets[patterns[k]], st_offsets[patterns[k] + 1]):
            box = occ_box[st_rows[a]]
            if _reaches_edge(np.float64(box[0]), np.float64(box[1]), np.float64(box[2]), np.float64(box[3]),
                             width, height):
                counts[k] += 1
    return counts


@nb.njit(cache=True, nogil=True)
def pattern_mean_sizes(st_offsets: np.ndarray, st_rows: np.ndarray, patterns: np.ndarray, box: np.ndarray,
                       position: np.ndarray, placed_position: np.ndarray) -> np.ndarray:
    """:func:`trap_core.robust.pattern_sizes` of ``patterns``: per pattern, the mean over its
    occurrences of the diagonal of ``box`` (x0, y0, x1, y1 inclusive) plus, where
    ``placed_position`` has rows, twice the distance from ``position`` to it (in float32, as the
    positions are)."""
    sizes = np.zeros(patterns.size)
    pulled = placed_position.shape[0] > 0
    for k in range(patterns.size):
        lo, hi = st_offsets[patterns[k]], st_offsets[patterns[k] + 1]
        for a in range(lo, hi):
            r = st_rows[a]
            size = np.hypot(np.float64(box[r, 2]) - np.float64(box[r, 0]) + 1,
                            np.float64(box[r, 3]) - np.float64(box[r, 1]) + 1)
            if pulled:
                dx, dy = position[r, 0] - placed_position[r, 0], position[r, 1] - placed_position[r, 1]
                size += 2 * np.sqrt(dx * dx + dy * dy)
            sizes[k] += size
        sizes[k] /= max(hi - lo, 1)
    return sizes


@nb.njit(cache=True, nogil=True)
def side_lines(frames: np.ndarray, edges: np.ndarray, half: int, step: int, min_side: int) -> np.ndarray:
    """Steady box edges (:func:`trap_core.robust.box_edges.steady_edges`): (n, k) where the
    Theil-Sen line of each column of ``edges`` (n, k) over the rows on one side of each row
    (``step`` -1: before it, 1: after it; the ``half`` nearest rows, those within ``half``
    frames) puts it in that row's frame (``frames``, increasing); NaN where fewer than
    ``min_side`` rows are on that side."""
    n, k = edges.shape
    out = np.full((n, k), np.nan)
    lags = np.empty(half)
    values = np.empty(half)
    slopes = np.empty(half * (half - 1) // 2)
    for row in range(n):
        count = 0
        other = row + step
        while 0 <= other < n and count < half and abs(frames[other] - frames[row]) <= half:
            lags[count] = frames[other] - frames[row]
            count += 1
            other += step
        if count < min_side:
            continue
        for column in range(k):
            for i in range(count):
                values[i] = edges[row + step * (i + 1), column]
            pairs = 0
            for i in range(count):
                for j in range(i + 1, count):
                    slopes[pairs] = (values[j] - values[i]) / (lags[j] - lags[i])
                    pairs += 1
            slope = np.median(slopes[:pairs])
            for i in range(count):
                values[i] -= slope * lags[i]
            out[row, column] = np.median(values[:count])
    return out
