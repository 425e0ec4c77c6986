"""Tracks: per-frame boxes of the selected clusters (TRAP_SPEC section 7)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from trap_core.mining import MiningResult


@dataclass(frozen=True)
class Track:
    """One object: ``boxes[i] = (x, y, w, h)`` in frame ``frames[i]``, with a confidence in (0, 1]."""

    track_id: int
    frames: np.ndarray
    boxes: np.ndarray
    score: np.ndarray
    cluster: int

    def __len__(self) -> int:
        return int(self.frames.size)


def build_track(result: MiningResult, pattern_labels: np.ndarray, cluster: int, track_id: int) -> Track:
    """Box of the cluster in each frame: around the regions of its patterns' occurrences there.

    Confidence: the number of the cluster's patterns seen in the frame over the most seen in
    any frame (1 where the object shows all its structure).
    """
    patterns = np.flatnonzero(pattern_labels == cluster)
    rows = np.concatenate([result.st(s) for s in patterns]) if patterns.size else np.empty(0, np.int64)
    owner = np.repeat(patterns, [result.st(s).size for s in patterns])
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
    seen = np.unique(np.column_stack([inverse, owner]), axis=0)[:, 0]
    per_frame = np.bincount(seen, minlength=known.size).astype(float)
    score = per_frame / per_frame.max() if per_frame.size else per_frame
    return Track(track_id, known, np.column_stack([x0, y0, x1 - x0 + 1, y1 - y0 + 1]), score, cluster)
