"""One track per object: tracks that hold the same object at the same time are merged (ours).

The lifetime cut can leave one object's patterns in two clusters that overlap in time (with
noisy regions each holds a different subset of its structures, and each may have been
rejoined to another fragment of the object). Both are then selected and the object gets two
tracks with the same box, one of them a false positive in every frame they share. Two tracks
are taken for one object when, over at least ``min_common`` frames both cover, their boxes
match in at least ``min_share`` of those frames: IoU at least ``min_iou``, or the smaller box
at least ``min_inside`` inside the other (a fragment on part of the object, rejoined to a later
fragment of it, makes a track that holds part of the object where it overlaps the object's other
track). Over *all* the frames they share, not only some: look-alikes that travel overlapped for
a while and then part keep their own tracks.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from trap_core.clustering import Track, box_containment, box_iou, with_frames


def merge_duplicates(tracks: Sequence[Track], min_common: int, min_iou: float = 0.5, min_inside: float = 0.9,
                     min_share: float = 0.8) -> list[Track]:
    """Tracks with duplicates merged: each group keeps its longest track's boxes and id order,
    and takes the others' frames where it has none. Ids are renumbered 1.. in order."""
    merged: list[Track] = []
    for candidate in sorted(tracks, key=len, reverse=True):
        for k, kept in enumerate(merged):
            if _same_object(kept, candidate, min_common, min_iou, min_inside, min_share):
                merged[k] = _union(kept, candidate)
                break
        else:
            merged.append(candidate)
    merged.sort(key=lambda t: t.track_id)
    return [dataclasses.replace(t, track_id=i) for i, t in enumerate(merged, start=1)]


def _same_object(a: Track, b: Track, min_common: int, min_iou: float, min_inside: float, min_share: float) -> bool:
    common, in_a, in_b = np.intersect1d(a.frames, b.frames, assume_unique=True, return_indices=True)
    if common.size < min_common:
        return False
    boxes_a, boxes_b = a.boxes[in_a], b.boxes[in_b]
    same = (box_iou(boxes_a, boxes_b) >= min_iou) | (box_containment(boxes_a, boxes_b) >= min_inside)
    return float(np.mean(same)) >= min_share


def _union(kept: Track, other: Track) -> Track:
    """``kept`` with ``other``'s frames that it does not cover."""
    extra = ~np.isin(other.frames, kept.frames)
    return with_frames(kept, other.frames[extra], other.boxes[extra], other.score[extra],
                       None if other.points is None else other.points[extra])
