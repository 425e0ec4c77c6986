"""Tracks: per-frame boxes of the selected clusters (TRAP_SPEC section 7)."""
from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from trap_core.clustering._kernels import core_regions as _core_regions
from trap_core.clustering._kernels import place_kept
from trap_core.clustering._kernels import stacked_core_regions as _stacked_core_regions
from trap_core.mining import MiningResult
from trap_core.rag import PlaneGraph, StackedGraphs


@dataclass(frozen=True)
class Track:
    """One object: ``boxes[i] = (x, y, w, h)`` in frame ``frames[i]``, with a confidence in (0, 1].

    ``points[i]``: mean position of the track's pattern occurrences in that frame (NaN where none,
    as in frames where the object is only inferred); None when not known.
    """

    track_id: int
    frames: np.ndarray
    boxes: np.ndarray
    score: np.ndarray
    cluster: int
    points: np.ndarray | None = None

    def __len__(self) -> int:
        return int(self.frames.size)


def with_frames(track: Track, frames: np.ndarray, boxes: np.ndarray, score: np.ndarray,
                points: np.ndarray | None) -> Track:
    """``track`` with boxes (confidences, points) added in ``frames``, which it does not cover,
    kept in frame order; no points at all unless both sides have them."""
    every = np.concatenate([track.frames, frames])
    order = np.argsort(every, kind="stable")
    merged_points = None
    if track.points is not None and points is not None:
        merged_points = np.vstack([track.points, points])[order]
    return dataclasses.replace(track, frames=every[order], boxes=np.vstack([track.boxes, boxes])[order],
                               score=np.concatenate([track.score, score])[order], points=merged_points)


def in_rows(track: Track, rows: np.ndarray) -> Track:
    """``track`` in the rows ``rows`` (a mask or indices of its frames) only."""
    return dataclasses.replace(track, frames=track.frames[rows], boxes=track.boxes[rows], score=track.score[rows],
                               points=None if track.points is None else track.points[rows])


def track_pieces(frames: np.ndarray, min_gap: int, boxes: np.ndarray | None = None) -> list[np.ndarray]:
    """Rows of each piece of a track with the (increasing) ``frames``: a run of its frames
    without a gap of more than ``min_gap`` frames (where its object was occluded or out of
    view) and, given its ``boxes``, without a jump of the box centre by more than the larger
    box's extent from one box to the next (where the track went over to another object)."""
    cuts = np.diff(frames) > min_gap
    if boxes is not None and len(boxes) > 1:
        cuts |= centre_steps(boxes) > np.maximum(boxes[:-1, 2:4].max(axis=1), boxes[1:, 2:4].max(axis=1))
    return np.split(np.arange(len(frames)), np.flatnonzero(cuts) + 1)


def box_centres(boxes: np.ndarray) -> np.ndarray:
    """Centres of boxes ``(x, y, w, h)`` (last axis), broadcast over the others."""
    return boxes[..., :2] + boxes[..., 2:4] / 2


def centre_steps(boxes: np.ndarray) -> np.ndarray:
    """(N-1,) distance between the centres of each two consecutive boxes (N, 4) of a track."""
    return np.linalg.norm(np.diff(box_centres(boxes), axis=0), axis=1)


def box_path(track: Track, length: int) -> np.ndarray:
    """(length, 4) the track's box in each frame, NaN where it has none."""
    boxes = np.full((length, 4), np.nan)
    boxes[track.frames] = track.boxes
    return boxes


def centre_path(track: Track, length: int) -> np.ndarray:
    """(length, 2) the track's box centre in each frame, NaN where it has no box."""
    centres = np.full((length, 2), np.nan)
    centres[track.frames] = box_centres(track.boxes)
    return centres


def usual_size(track: Track) -> float:
    """The size of the track's object: the median of its boxes' larger side."""
    return float(np.median(np.max(track.boxes[:, 2:4], axis=1)))


def usual_box(track: Track) -> np.ndarray:
    """(2,) the track's usual (width, height): the median of each over its boxes, (0, 0) for an
    empty track. Beside :func:`usual_size` where a box's shape matters, not only its size."""
    return np.median(track.boxes[:, 2:4], axis=0) if len(track) else np.zeros(2)


def box_iou(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Intersection over union of boxes ``(x, y, w, h)`` (last axis), broadcast over the others."""
    a, b, inter = _intersection(a, b)
    union = a[..., 2] * a[..., 3] + b[..., 2] * b[..., 3] - inter
    return np.where(union > 0, inter / np.where(union > 0, union, 1), 0.0)


def box_containment(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Share of the smaller of boxes ``a``, ``b`` ``(x, y, w, h)`` (last axis) that lies in the
    other, broadcast over the others (0 where a box is absent: NaN)."""
    a, b, inter = _intersection(a, b)
    smaller = np.minimum(a[..., 2] * a[..., 3], b[..., 2] * b[..., 3])
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.nan_to_num(inter / smaller, posinf=0.0)


def centre_inside(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Whether the centre of the smaller of boxes ``a``, ``b`` ``(x, y, w, h)`` (last axis) lies in
    the other, broadcast over the others (False where a box is absent: NaN)."""
    a, b = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(b, dtype=float))
    a_smaller = (a[..., 2] * a[..., 3] <= b[..., 2] * b[..., 3])[..., None]
    small, large = np.where(a_smaller, a, b), np.where(a_smaller, b, a)
    return points_in_boxes(box_centres(small), large)


def seen_rows(track: Track) -> np.ndarray:
    """Per row of the track: whether its patterns are seen there (its box measured, not inferred
    through a gap)."""
    return np.ones(len(track), dtype=bool) if track.points is None else ~np.isnan(track.points[:, 0])


def points_in_boxes(points: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """Whether each point lies in its box (``(x, y, w, h)``, broadcast); False where the box or
    the point is NaN."""
    return np.all((points >= boxes[..., :2]) & (points <= boxes[..., :2] + boxes[..., 2:4]), axis=-1)


def regions_in_box(bbox: np.ndarray, box: np.ndarray, slack: float = 0.0) -> np.ndarray:
    """Which regions (``bbox``: (N, 4) first and last pixel, x0, y0, x1, y1, as plane graphs keep
    them) lie wholly inside ``box`` ``(x, y, w, h)``: a region's last pixel may be the one just
    past the box's (its right and bottom edges lie on pixel boundaries), and with ``slack`` its
    first may lie that many pixels before the box's left and top edges."""
    x, y, w, h = box
    return (bbox[:, 0] >= x - slack) & (bbox[:, 1] >= y - slack) & (bbox[:, 2] <= x + w) & (bbox[:, 3] <= y + h)


def reaches_border(boxes: np.ndarray, width: float, height: float, margin: float = 0.25,
                   size: np.ndarray | None = None) -> np.ndarray:
    """Whether boxes ``(x, y, w, h)`` (N, 4) come within ``margin`` times their size (their own,
    or at least ``size``: width, height) of the image border: the object is entering or leaving
    the view."""
    boxes = np.asarray(boxes, dtype=float)
    w, h = boxes[:, 2], boxes[:, 3]
    reach_x, reach_y = (margin * w, margin * h) if size is None else (margin * np.maximum(w, size[0]),
                                                                       margin * np.maximum(h, size[1]))
    return border_sides(boxes, width, height, reach_x, reach_y).any(axis=1)


def border_sides(boxes: np.ndarray, width: float, height: float, reach_x: np.ndarray | float,
                 reach_y: np.ndarray | float) -> np.ndarray:
    """(N, 4) bool: per box ``(x, y, w, h)``, whether it lies within ``reach_x`` (``reach_y``) px
    of the left, top, right and bottom border of a ``width`` x ``height`` image (which borders
    :func:`reaches_border` is about)."""
    x, y, w, h = boxes.T
    return np.column_stack([x <= reach_x, y <= reach_y, x + w >= width - reach_x, y + h >= height - reach_y])


def region_boxes_reach_border(boxes: np.ndarray, width: float, height: float, margin: float = 0.25,
                              shift: np.ndarray | None = None) -> np.ndarray:
    """:func:`reaches_border` of region boxes ``(x0, y0, x1, y1)`` inclusive (N, 4; whole pixels,
    as an occurrence's ``occ_box``), moved by ``shift`` (N, 2) px where given."""
    box = np.asarray(boxes, dtype=float)
    corner = box[:, :2] if shift is None else box[:, :2] + shift
    return reaches_border(np.column_stack([corner, box[:, 2:] - box[:, :2] + 1]), width, height, margin)


def _intersection(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``a`` and ``b`` as float arrays, and the area their boxes share (broadcast)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    ix = np.minimum(a[..., 0] + a[..., 2], b[..., 0] + b[..., 2]) - np.maximum(a[..., 0], b[..., 0])
    iy = np.minimum(a[..., 1] + a[..., 3], b[..., 1] + b[..., 3]) - np.maximum(a[..., 1], b[..., 1])
    return a, b, np.clip(ix, 0, None) * np.clip(iy, 0, None)


def build_track(result: MiningResult, pattern_labels: np.ndarray, cluster: int, track_id: int,
                graphs: StackedGraphs | None = None, core_share: float = 0.0, pixel: float = 0.0,
                cores: FrameCores | None = None) -> Track:
    """Box of the cluster in each frame: around the regions of its patterns' occurrences there.

    With ``graphs`` (every frame's, stacked) and ``core_share > 0`` (ours), only the regions found
    in at least that share of the frame's occurrences in the track's place count (as many as the
    most shared region, :func:`core_regions`): a pattern that mixes the object with a background
    region it passes over then does not stretch the box to that whole background region. With ``pixel``
    too (frame pixels per pixel of the segmentation's size), edge lines alone do not widen the
    box (:meth:`PlaneGraph.nodes_box`). ``cores``: the cluster's :func:`frame_cores` at
    ``core_share``, where the caller has them already.

    Confidence: the number of the cluster's patterns seen in the frame over the most seen in
    any frame (1 where the object shows all its structure).
    """
    patterns = np.flatnonzero(pattern_labels == cluster)
    rows, owner = result.rows_of(patterns)
    frames = result.occ_frame[rows]
    known, inverse = np.unique(frames, return_inverse=True)
    boxes = result.occ_box[rows]
    x0 = np.full(known.size, np.inf)
    y0 = np.full(known.size, np.inf)
    x1 = np.full(known.size, -np.inf)
    y1 = np.full(known.size, -np.inf)
    np.minimum.at(x0, inverse, boxes[:, 0])
    np.minimum.at(y0, inverse, boxes[:, 1])
    np.maximum.at(x1, inverse, boxes[:, 2])
    np.maximum.at(y1, inverse, boxes[:, 3])
    around = np.column_stack([x0, y0, x1 - x0 + 1, y1 - y0 + 1])
    if graphs is not None and core_share > 0:
        cores = frame_cores(result, patterns, graphs, core_share) if cores is None else cores
        around = graphs.nodes_boxes(cores.frames, cores.core, cores.core_ends, pixel)
    seen = np.unique(np.column_stack([inverse, owner]), axis=0)[:, 0]
    per_frame = np.bincount(seen, minlength=known.size).astype(float)
    score = per_frame / per_frame.max() if per_frame.size else per_frame
    occurrences = np.bincount(inverse, minlength=known.size)[:, None]
    points = np.column_stack([np.bincount(inverse, weights=result.occ_position[rows, axis], minlength=known.size)
                              for axis in (0, 1)]) / np.maximum(occurrences, 1)
    return Track(track_id, known, around, score, cluster, points)


def _by_frame(result: MiningResult, patterns: np.ndarray, end_frames: int = 0
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The occurrences of ``patterns`` in frame order (stable): the frames they are in, where
    each frame's end among them, their face sets (rows of ``occ_faces``) and the lifetime of
    each one's pattern (its occurrences in the whole video). With ``end_frames``, only those in
    the first and the last ``end_frames`` frames they are in."""
    rows, owner = result.rows_of(patterns)
    frames = result.occ_frame[rows]
    if end_frames and frames.size:
        seen = np.unique(frames)
        ends = (frames <= seen[min(end_frames, seen.size) - 1]) | (frames >= seen[-min(end_frames, seen.size)])
        rows, owner, frames = rows[ends], owner[ends], frames[ends]
    order = np.argsort(frames, kind="stable")
    known, counts = np.unique(frames[order], return_counts=True)
    return known, np.cumsum(counts), result.occ_faces[rows[order]], result.st_occurrences[patterns][owner][order]


@dataclass(frozen=True)
class FrameCores:
    """Per frame where a cluster's patterns occur (``frames``, increasing), its :func:`core_regions`:
    frame ``frames[k]``'s are ``core[core_ends[k - 1]:core_ends[k]]`` (numbered within the frame),
    and the most held of them ``top[top_ends[k - 1]:top_ends[k]]``."""

    frames: np.ndarray
    core: np.ndarray
    core_ends: np.ndarray
    top: np.ndarray
    top_ends: np.ndarray

    def __iter__(self) -> Iterator[tuple[int, np.ndarray, np.ndarray]]:
        """Each frame, its core regions and the most held ones."""
        core_starts, top_starts = np.r_[0, self.core_ends[:-1]], np.r_[0, self.top_ends[:-1]]
        for k, frame in enumerate(self.frames.tolist()):
            yield (frame, self.core[core_starts[k]:self.core_ends[k]], self.top[top_starts[k]:self.top_ends[k]])


def frame_cores(result: MiningResult, patterns: np.ndarray, graphs: StackedGraphs, share: float,
                end_frames: int = 0) -> FrameCores:
    """Per frame where any of ``patterns`` occurs: the :func:`core_regions` of their occurrences
    there, all frames in one compiled pass (``graphs``: every frame's, stacked). Read once per
    cluster: its track's boxes and the still-region rule
    (:func:`trap_core.robust.drop_still_regions`) both start from them. With ``end_frames``,
    only the first and the last ``end_frames`` of those frames (what a fragment looks like at
    its ends, :class:`trap_core.robust.EndColours`)."""
    known, ends, face_sets, lifetimes = _by_frame(result, patterns, end_frames)
    return FrameCores(known, *_stacked_core_regions(face_sets.astype(np.int64).reshape(len(face_sets), -1),
                                                    lifetimes.astype(np.float64), known.astype(np.int64), ends,
                                                    graphs.node_offsets, graphs.face_base, graphs.face_offsets,
                                                    graphs.face_half_edges, graphs.he_origin, graphs.backdrop,
                                                    graphs.bbox, share))


def core_regions(graph: PlaneGraph, face_sets: np.ndarray, share: float,
                 lifetimes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Regions (graph nodes) that at least ``share`` of one frame's occurrences (face sets)
    contain, as many as the most shared region, and those most shared ones: the track's box
    surrounds the first (:func:`build_track`); the second are the object itself, whatever else
    its patterns hold.

    Each occurrence counts as many times as its pattern occurs in the whole video
    (``lifetimes``): where a short-lived pattern of the cluster holds other regions than the
    object's long-lived one (a background region beside the object, whose barycentre moves
    while the object covers it bit by bit), those regions are held by few occurrence-lifetimes
    and stay out, however few patterns the frame has. Only the occurrences in the track's
    place count (:func:`one_place`): where the cluster is in two places at once, the one of its
    longest-lived patterns. The backdrop (:attr:`PlaneGraph.backdrop`) is never a core region:
    over a plain scene every face of an object holds it, and the box would be the whole view.
    """
    nodes, ends = graph.sets_nodes(face_sets)
    return _core_regions(nodes, ends, np.asarray(lifetimes, dtype=np.float64), graph.backdrop, graph.bbox, share)


def one_place(graph: PlaneGraph, node_sets: list[np.ndarray], lifetimes: np.ndarray,
              share: float) -> list[np.ndarray]:
    """The node sets (occurrences of one frame) of the place where the track's object is.

    Occurrences that share a region are in one place. Places whose core boxes (regions in
    ``share`` of their occurrences) are closer than half the smaller box's larger side are parts
    of one thing: a person's two legs share no region but stand side by side. Further apart, the
    cluster is in two places (its patterns went on with a look-alike or a structure they passed,
    often a few short ones); the place whose patterns have the longest ``lifetimes`` in all is
    the track's, since a track's own long patterns outweigh a few short ones elsewhere, however
    many those are in the frame.
    """
    kept = place_kept(np.concatenate(node_sets).astype(np.int64), np.cumsum([n.size for n in node_sets]),
                      np.asarray(lifetimes, dtype=np.float64), share, graph.n_nodes, graph.bbox)
    return [nodes for nodes, keep in zip(node_sets, kept) if keep]
