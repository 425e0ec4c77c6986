"""Scores of a set of tracks against per-object ground truth: the paper's box measures per
object (each object matched to one track) and the multi-object measures of the whole set."""
from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment

from trap_core.clustering import Track
from trap_core.evaluation.mot_metrics import clear_mot, hota, idf1
from trap_core.evaluation.paper_measures import box_precision_recall

Boxes = dict[int, tuple]  # frame (0-based) -> (x, y, w, h)


def boxes_by_frame(track: Track) -> Boxes:
    """The track's boxes as the scores take them (and the ground truth comes): frame -> (x, y, w, h)."""
    return {int(frame): tuple(box) for frame, box in zip(track.frames, track.boxes)}


def match_objects(boxes_per_track: list[Boxes], truth: list[Boxes]) -> list[tuple[int | None, float, float]]:
    """For each object: (track index, box precision, box recall) of the track matched to it,
    one to one, maximising the sum of precision x recall; (None, 0, 0) for an object no
    track is matched to."""
    scores = np.array([[box_precision_recall(t, gt) for gt in truth] for t in boxes_per_track]).reshape(
        len(boxes_per_track), len(truth), 2)
    out: list[tuple[int | None, float, float]] = [(None, 0.0, 0.0)] * len(truth)
    if len(boxes_per_track):
        rows, cols = linear_sum_assignment(-(scores[..., 0] * scores[..., 1]))
        for r, c in zip(rows, cols):
            out[c] = (int(r), float(scores[r, c, 0]), float(scores[r, c, 1]))
    return out


def mot_measures(boxes_per_track: list[Boxes], truth: list[Boxes]) -> dict[str, float]:
    """MOTA, IDF1 and HOTA of the whole set of tracks."""
    gt, tr = _rows(truth), _rows(boxes_per_track)
    return {"MOTA": clear_mot(gt, tr).mota, "IDF1": idf1(gt, tr), "HOTA": hota(gt, tr)}


def _rows(boxes_per_track: list[Boxes]) -> np.ndarray:
    """MOTChallenge rows (1-based frame, id, x, y, w, h)."""
    rows = [(f + 1, k + 1, *box) for k, boxes in enumerate(boxes_per_track) for f, box in boxes.items()]
    return np.array(rows, dtype=float).reshape(-1, 6)
