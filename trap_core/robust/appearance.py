"""What a track's object looks like: the colours of the regions inside its boxes (ours).

Two tracks whose clusters share no structure may still hold look-alike objects (over a textured
background each object's patterns take in its own surroundings), and boxes of one size are then
the sign of it (:func:`trap_core.robust.lookalike_tracks`). Objects of one size but of different
colours are not look-alikes, though: their tracks must not trade objects where they meet, since
only motion would then decide, and two objects that meet and both turn back read as a trade. The
regions wholly inside a track's boxes are its object's parts; the share of their area in each
colour label is what it looks like.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from trap_core.clustering import Track, regions_in_box
from trap_core.rag import PlaneGraph

SAMPLES = 60  # frames a track's colours are read in, spread evenly over its frames


def colour_shares(tracks: Sequence[Track], graphs: Sequence[PlaneGraph], samples: int = SAMPLES) -> np.ndarray:
    """(T, L) per track, the share of the area of the regions wholly inside its boxes in each
    colour label (L: one past the largest label), over ``samples`` of its frames; a row of 0
    where no region is."""
    counts = []
    for track in tracks:
        rows = np.arange(len(track))
        if rows.size > samples:
            rows = np.linspace(0, rows.size - 1, samples).round().astype(np.int64)
        labels, areas = [], []
        for row in rows.tolist():
            graph = graphs[int(track.frames[row])]
            inside = regions_in_box(graph.bbox, track.boxes[row])
            labels.append(graph.label[inside])
            areas.append(graph.area[inside])
        counts.append((np.concatenate(labels or [np.zeros(0, np.int32)]).astype(np.int64),
                       np.concatenate(areas or [np.zeros(0, np.int32)]).astype(np.float64)))
    width = max((int(labels.max()) + 1 for labels, _ in counts if labels.size), default=1)
    shares = np.zeros((len(tracks), width))
    for row, (labels, areas) in enumerate(counts):
        total = areas.sum()
        if total > 0:
            shares[row] = np.bincount(labels, weights=areas, minlength=width) / total
    return shares


def colour_overlap(shares: np.ndarray) -> np.ndarray:
    """(T, T) how much of their colours two tracks share (histogram intersection of
    :func:`colour_shares`: 1 for the same colours in the same proportions, 0 for none alike)."""
    return np.minimum(shares[:, None, :], shares[None, :, :]).sum(axis=2)
