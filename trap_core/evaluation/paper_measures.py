"""The paper's precision and recall (TRAP_SPEC section 8).

Ground truth is a dict ``{frame: (x, y, w, h)}`` for one object (frames 0-based here).
"""
from __future__ import annotations

import numpy as np

from trap_core.mining import MiningResult


def occurrences_inside(node_box: np.ndarray, gt: np.ndarray) -> np.ndarray:
    """Occurrences whose node barycentres all lie inside the ground-truth box of their frame
    (``node_box``: (N, 4) box of each occurrence's barycentres; ``gt``: (N, 4) ``(x, y, w, h)``)."""
    x, y, w, h = gt.T
    return (node_box[:, 0] >= x) & (node_box[:, 1] >= y) & (node_box[:, 2] <= x + w - 1) & (node_box[:, 3] <= y + h - 1)


def cluster_precision_recall(result: MiningResult, patterns: np.ndarray, truth: dict[int, tuple]) -> tuple[float, float]:
    """Cluster precision: share of the cluster's occurrences whose nodes all lie in the ground-truth
    box of their frame (no box: outside). Recall: share of annotated frames with at least one
    such occurrence. ``patterns``: the cluster's spatio-temporal patterns, increasing."""
    rows, _ = result.rows_of(np.asarray(patterns, dtype=np.int64))
    if rows.size == 0 or not truth:
        return 0.0, 0.0
    frames = result.occ_frame[rows]
    annotated = np.array([f in truth for f in frames.tolist()])
    gt = np.array([truth.get(f, (0, 0, 0, 0)) for f in frames.tolist()], dtype=float)
    good = annotated & occurrences_inside(result.occ_node_box[rows], gt)
    return float(good.mean()), len(set(frames[good].tolist())) / len(truth)


def box_precision_recall(track: dict[int, tuple], truth: dict[int, tuple]) -> tuple[float, float]:
    """Box tracker measures: precision = area shared with the ground truth / area of the track
    boxes; recall = share of annotated frames where the track box's centre lies in the truth box."""
    shared = total = 0.0
    hits = 0
    for frame, box in track.items():
        total += box[2] * box[3]
        if frame in truth:
            shared += shared_area(box, truth[frame])
            hits += centre_inside(box, truth[frame])
    precision = shared / total if total else 0.0
    return precision, hits / len(truth) if truth else 0.0


def centre_inside(box: tuple, truth_box: tuple) -> bool:
    """Whether the centre of ``box`` (x, y, w, h) lies in ``truth_box``: the recall test."""
    x, y, w, h = box
    gx, gy, gw, gh = truth_box
    return bool(gx <= x + w / 2 <= gx + gw and gy <= y + h / 2 <= gy + gh)


def shared_area(box: tuple, truth_box: tuple) -> float:
    """Area two boxes (x, y, w, h) share: what precision counts."""
    x, y, w, h = box
    gx, gy, gw, gh = truth_box
    return max(0.0, min(x + w, gx + gw) - max(x, gx)) * max(0.0, min(y + h, gy + gh) - max(y, gy))
