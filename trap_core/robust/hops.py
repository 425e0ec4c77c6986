"""Clusters that move in hops: background, unless steady patterns of theirs vouch for them (ours).

A spatio-temporal pattern that the linking took from one look-alike to the next (bricks, gravel,
a row of identical objects) moves in hops (:func:`~trap_core.robust.camera.world_steps`), and a
cluster with more than ``HOP_SHARE`` of its occurrences on such patterns is background
(TRAP_SPEC section 10, "object versus background").

But look-alike objects make hopping patterns too: a pattern small enough to be found on several
discs of one colour hops between them, and its average trajectory lies beside the steady
patterns of the disc it is on most. The lifetime cut puts them in one cluster, and over gravel
at 320x240, 7 such patterns (280 occurrences) outweighed the 2 steady whole-disc patterns
(261 occurrences) of the object they were clustered with: the object had no track at all. So
a hopping pattern counts against its cluster only where nothing steady of the cluster is seen:
one with at least ``VOUCHED_SHARE`` of its occurrences within the frame span of a steady pattern
of its cluster is vouched for. A background chain has no steady pattern to vouch for it; one
that happens to have one for a few frames (a pattern whose jitter stayed small while it was
seen) keeps its hoppers seen outside them against it.
"""
from __future__ import annotations

import numpy as np

from trap_core.mining import MiningResult

VOUCHED_SHARE = 0.5  # a hopping pattern with this share of its occurrences where a steady one of its cluster is seen


def unvouched_hop_share(result: MiningResult, patterns: np.ndarray, labels: np.ndarray, hopping: np.ndarray,
                        steady: np.ndarray) -> np.ndarray:
    """Per cluster, the share of its occurrences on hopping patterns that no steady pattern vouches for.

    Parameters
    ----------
    result : MiningResult
        The mining result ``patterns`` index into.
    patterns : (K,) int array
        Clustered spatio-temporal patterns, increasing.
    labels : (K,) int array
        Cluster of each of ``patterns`` (0 .. C-1).
    hopping, steady : (K,) bool arrays
        Which of ``patterns`` move in hops (they count against their cluster) and which move
        steadily (they vouch for their cluster's hoppers within their frame span).

    Returns
    -------
    (C,) float array
        Occurrences of the cluster's hopping patterns with under ``VOUCHED_SHARE`` of their
        occurrences within the span of one of the cluster's steady patterns, over all its
        occurrences.
    """
    n_clusters = int(labels.max()) + 1 if labels.size else 0
    occurrences = result.st_occurrences[patterns]
    rows, owner = result.rows_of(patterns)
    frame = result.occ_frame[rows].astype(np.int64)
    vouched_share = np.zeros(patterns.size)
    if steady.any() and hopping.any():
        ends = np.cumsum(occurrences)
        first, last = frame[ends - occurrences], frame[ends - 1]  # rows are by frame within a pattern
        stride = int(frame.max()) + 2  # (cluster, frame) as one key, clusters apart
        vouchers = np.flatnonzero(steady)
        vouchers = vouchers[np.lexsort((first[vouchers], labels[vouchers]))]
        span_start = labels[vouchers] * stride + first[vouchers]
        reach = np.maximum.accumulate(labels[vouchers] * stride + last[vouchers])  # never past its own cluster
        key = labels[owner] * stride + frame
        before = np.searchsorted(span_start, key, side="right") - 1
        inside = (before >= 0) & (reach[np.maximum(before, 0)] >= key)
        vouched_share = np.bincount(owner, weights=inside, minlength=patterns.size) / np.maximum(occurrences, 1)
    counted = hopping & (vouched_share < VOUCHED_SHARE)
    return (np.bincount(labels, weights=occurrences * counted, minlength=n_clusters)
            / np.maximum(np.bincount(labels, weights=occurrences, minlength=n_clusters), 1))
