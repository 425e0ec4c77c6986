"""Standard multi-object tracking measures: CLEAR MOT (MOTA, MOTP), IDF1 and HOTA.

Own implementations, following the definitions of Bernardin & Stiefelhagen (2008), Ristani et
al. (2016) and Luiten et al. (2021); checked against py-motmetrics on its TUD-Campus example
(``test/test_mot_metrics.py``). Boxes are ``(x, y, w, h)``; rows of both sides are
``(frame, id, x, y, w, h, ...)`` as MOTChallenge files hold them.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

from trap_core.clustering import box_iou


def iou_matrix(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """IoU of every box of ``a`` (n, 4) with every box of ``b`` (m, 4), boxes as x, y, w, h."""
    return box_iou(np.reshape(a, (-1, 1, 4)), np.reshape(b, (1, -1, 4)))


def _frames(rows: np.ndarray) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    out: dict[int, tuple[np.ndarray, np.ndarray]] = {}
    for frame in np.unique(rows[:, 0]).astype(int):
        sel = rows[:, 0] == frame
        out[frame] = (rows[sel, 1].astype(int), rows[sel, 2:6].astype(float))
    return out


@dataclass(frozen=True)
class ClearMot:
    mota: float
    motp: float       # mean 1 - IoU of matches (py-motmetrics' convention)
    recall: float
    precision: float
    false_positives: int
    misses: int
    id_switches: int
    ground_truth: int


def clear_mot(gt: np.ndarray, tracks: np.ndarray, threshold: float = 0.5) -> ClearMot:
    """CLEAR MOT: matches kept from the previous frame while IoU >= threshold, others by Hungarian."""
    gt_frames, tr_frames = _frames(gt), _frames(tracks)
    last_match: dict[int, int] = {}   # gt id -> tracker id it was last matched to
    matches = misses = false_positives = switches = total = 0
    distance = 0.0
    for frame in sorted(set(gt_frames) | set(tr_frames)):
        g_ids, g_boxes = gt_frames.get(frame, (np.empty(0, int), np.empty((0, 4))))
        t_ids, t_boxes = tr_frames.get(frame, (np.empty(0, int), np.empty((0, 4))))
        total += len(g_ids)
        iou = iou_matrix(g_boxes, t_boxes)
        valid = iou >= threshold
        pairs: list[tuple[int, int]] = []
        free_g, free_t = set(range(len(g_ids))), set(range(len(t_ids)))
        t_index = {int(t): j for j, t in enumerate(t_ids)}
        for i, g in enumerate(g_ids):
            j = t_index.get(last_match.get(int(g), -1))
            if j is not None and j in free_t and valid[i, j]:
                pairs.append((i, j))
                free_g.discard(i)
                free_t.discard(j)
        rows, cols = sorted(free_g), sorted(free_t)
        if rows and cols:
            cost = np.where(valid[np.ix_(rows, cols)], 1 - iou[np.ix_(rows, cols)], 1e6)
            for r, c in zip(*linear_sum_assignment(cost)):
                if cost[r, c] < 1e6:
                    pairs.append((rows[r], cols[c]))
        for i, j in pairs:
            g, t = int(g_ids[i]), int(t_ids[j])
            if g in last_match and last_match[g] != t:
                switches += 1
            last_match[g] = t
            distance += 1 - iou[i, j]
        matches += len(pairs)
        misses += len(g_ids) - len(pairs)
        false_positives += len(t_ids) - len(pairs)
    mota = 1 - (misses + false_positives + switches) / total if total else 0.0
    return ClearMot(mota, distance / matches if matches else 0.0, matches / total if total else 0.0,
                    matches / (matches + false_positives) if matches + false_positives else 0.0,
                    false_positives, misses, switches, total)


def idf1(gt: np.ndarray, tracks: np.ndarray, threshold: float = 0.5) -> float:
    """IDF1: 2 IDTP / (ground-truth boxes + tracker boxes), identities matched one to one globally."""
    gt_frames, tr_frames = _frames(gt), _frames(tracks)
    g_list, t_list = np.unique(gt[:, 1]).astype(int), np.unique(tracks[:, 1]).astype(int) if len(tracks) else []
    if len(g_list) == 0 or len(t_list) == 0:
        return 0.0
    g_pos = {g: i for i, g in enumerate(g_list)}
    t_pos = {t: j for j, t in enumerate(t_list)}
    together = np.zeros((len(g_list), len(t_list)))
    for frame in set(gt_frames) & set(tr_frames):
        g_ids, g_boxes = gt_frames[frame]
        t_ids, t_boxes = tr_frames[frame]
        hit = iou_matrix(g_boxes, t_boxes) >= threshold
        for i, j in zip(*np.nonzero(hit)):
            together[g_pos[int(g_ids[i])], t_pos[int(t_ids[j])]] += 1
    rows, cols = linear_sum_assignment(-together)
    idtp = together[rows, cols].sum()
    return float(2 * idtp / (len(gt) + len(tracks)))


def hota(gt: np.ndarray, tracks: np.ndarray) -> float:
    """HOTA averaged over localisation thresholds 0.05..0.95 (Luiten et al., 2021)."""
    alphas = np.arange(0.05, 0.96, 0.05)
    gt_frames, tr_frames = _frames(gt), _frames(tracks)
    g_list = np.unique(gt[:, 1]).astype(int)
    t_list = np.unique(tracks[:, 1]).astype(int) if len(tracks) else np.empty(0, int)
    if len(g_list) == 0 or len(t_list) == 0:
        return 0.0
    g_pos = {g: i for i, g in enumerate(g_list)}
    t_pos = {t: j for j, t in enumerate(t_list)}
    frames = sorted(set(gt_frames) | set(tr_frames))
    empty = (np.empty(0, int), np.empty((0, 4)))
    # Global alignment: how much each gt/tracker identity pair overlaps over the video.
    potential = np.zeros((len(g_list), len(t_list)))
    g_count = np.zeros(len(g_list))
    t_count = np.zeros(len(t_list))
    per_frame = []
    for frame in frames:
        g_ids, g_boxes = gt_frames.get(frame, empty)
        t_ids, t_boxes = tr_frames.get(frame, empty)
        gi = np.array([g_pos[int(g)] for g in g_ids], dtype=int)
        tj = np.array([t_pos[int(t)] for t in t_ids], dtype=int)
        sim = iou_matrix(g_boxes, t_boxes)
        per_frame.append((gi, tj, sim))
        g_count[gi] += 1
        t_count[tj] += 1
        if sim.size:
            denom = sim.sum(0)[None, :] + sim.sum(1)[:, None] - sim
            potential[np.ix_(gi, tj)] += np.where(denom > 0, sim / np.where(denom > 0, denom, 1), 0)
    alignment = potential / (g_count[:, None] + t_count[None, :] - potential)
    tp = np.zeros(len(alphas))
    match_counts = np.zeros((len(alphas), len(g_list), len(t_list)))
    for gi, tj, sim in per_frame:
        if sim.size == 0:
            continue
        score = alignment[np.ix_(gi, tj)] * sim
        rows, cols = linear_sum_assignment(-score)
        for a, alpha in enumerate(alphas):
            ok = sim[rows, cols] >= alpha - np.finfo(float).eps
            tp[a] += ok.sum()
            match_counts[a, gi[rows[ok]], tj[cols[ok]]] += 1
    values = []
    for a in range(len(alphas)):
        if tp[a] == 0:
            values.append(0.0)
            continue
        fn, fp = len(gt) - tp[a], len(tracks) - tp[a]
        ass = match_counts[a] / np.maximum(g_count[:, None] + t_count[None, :] - match_counts[a], 1)
        ass_a = (match_counts[a] * ass).sum() / tp[a]
        det_a = tp[a] / (tp[a] + fn + fp)
        values.append(float(np.sqrt(det_a * ass_a)))
    return float(np.mean(values))
