"""The paper's cluster precision/recall for every cluster of a hierarchy (TRAP_SPEC section 8):
the best cluster over every cut, and the best and longest cluster level by level (Fig. 5)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from trap_core.clustering import Hierarchy, Trajectories, labels_after_merges, select_clusters, summarise
from trap_core.evaluation.paper_measures import occurrences_inside
from trap_core.mining import MiningResult


@dataclass(frozen=True)
class LeafScores:
    """Per clustered pattern and one object: good and total occurrences, frames with a good one."""

    good: np.ndarray    # (n,)
    total: np.ndarray   # (n,)
    frames: np.ndarray  # (n, n_frames) bool
    annotated: int


def leaf_scores(result: MiningResult, patterns: np.ndarray, truth: dict[int, tuple], n_frames: int) -> LeafScores:
    """Occurrences whose nodes all lie inside the object's box of their frame, per pattern."""
    boxes = np.full((n_frames, 4), np.nan)
    for frame, box in truth.items():
        if frame < n_frames:
            boxes[frame] = box
    good = np.zeros(len(patterns))
    total = np.zeros(len(patterns))
    frames = np.zeros((len(patterns), n_frames), dtype=bool)
    for k, s in enumerate(patterns):
        rows = result.st(s)
        frame = result.occ_frame[rows]
        gt = boxes[frame]
        nb = result.occ_node_box[rows]
        inside = occurrences_inside(nb, gt)
        good[k], total[k] = inside.sum(), rows.size
        frames[k, frame[inside]] = True
    return LeafScores(good, total, frames, len(truth))


def best_cluster(hierarchy: Hierarchy, leaves: LeafScores) -> tuple[float, float]:
    """(precision, recall) of the cluster with the highest P*R among every node of the dendrogram."""
    n = hierarchy.n
    if n == 0 or leaves.annotated == 0:
        return 0.0, 0.0
    good = np.concatenate([leaves.good, np.zeros(n - 1)])
    total = np.concatenate([leaves.total, np.zeros(n - 1)])
    frames = np.concatenate([leaves.frames, np.zeros((n - 1, leaves.frames.shape[1]), dtype=bool)])
    for row, (a, b) in enumerate(hierarchy.linkage[:, :2].astype(int)):
        good[n + row] = good[a] + good[b]
        total[n + row] = total[a] + total[b]
        frames[n + row] = frames[a] | frames[b]
    precision = np.divide(good, total, out=np.zeros_like(good), where=total > 0)
    recall = frames.sum(axis=1) / leaves.annotated
    best = int(np.argmax(precision * recall))
    return float(precision[best]), float(recall[best])


def level_curves(hierarchy: Hierarchy, leaves: LeafScores, paths: Trajectories, occurrences: np.ndarray,
                 n_frames: int, levels: int = 60) -> dict[str, np.ndarray]:
    """P and R of the best and of the longest cluster at sampled levels (the paper's Fig. 5)."""
    n = hierarchy.n
    sampled = np.unique(np.geomspace(1, max(n, 1), num=min(levels, max(n, 1))).round().astype(int))
    out = {name: np.zeros(sampled.size) for name in ("best_p", "best_r", "longest_p", "longest_r")}
    for i, level in enumerate(sampled):
        labels = labels_after_merges(hierarchy.linkage, n, n - level)
        order = np.argsort(labels, kind="stable")
        bounds = np.flatnonzero(np.r_[True, np.diff(labels[order]) != 0])
        good = np.add.reduceat(leaves.good[order], bounds)
        total = np.add.reduceat(leaves.total[order], bounds)
        frames = np.logical_or.reduceat(leaves.frames[order], bounds, axis=0)
        precision = np.divide(good, total, out=np.zeros_like(good), where=total > 0)
        recall = frames.sum(axis=1) / max(leaves.annotated, 1)
        best = int(np.argmax(precision * recall))
        out["best_p"][i], out["best_r"][i] = precision[best], recall[best]
        longest = select_clusters(summarise(labels, paths, occurrences, n_frames), n_frames, n_objects=1)[0]
        out["longest_p"][i], out["longest_r"][i] = precision[longest], recall[longest]
    out["levels"] = sampled
    return out
