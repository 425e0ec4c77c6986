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

A cluster with no steady pattern at all is judged on its patterns' hops pooled: each of them
may be just short of moving in hops (over the cameraman with noise 2, chains of two unsteady
patterns with 40-43 % and 81-85 % of their paths in hops made 5 extra tracks), but the
cluster's occurrences, on average, are on paths made half or more in hops.

Steady steps alone do not make a pattern steady evidence (:func:`steady_patterns`): linking with
motion prediction can chain noise-born structures along a straight line, one hop after another,
each step about the chain's own speed. Such a pattern (over the cameraman, 51-70 % of its path in
hops of ``eps``/4 at 3-4.6 px a frame) neither vouches for hoppers nor counts as steady for the
pooled test, unless it moves so fast (``eps``/8 a frame or more) that its steps, up to two
frames apart, are hop-sized anyway.

A cluster with no steady pattern that passes all of this (chains whose uneven steps are shorter
than a hop) is still no evidence of an object: :func:`steady_clusters` tells the track rules,
which leave such a cluster's track out of the unsupervised count unless the track's own boxes
step steadily (:func:`track_steps_steadily`; README, tracks with no steady pattern).
"""
from __future__ import annotations

import numpy as np

from trap_core.clustering import ObservedPaths, Track, box_centres
from trap_core.mining import MiningResult
from trap_core.robust.camera import HOP_SHARE, world_speed, world_steps

VOUCHED_SHARE = 0.5  # a hopping pattern with this share of its occurrences where a steady one of its cluster is seen


def unsteady_steps(median: np.ndarray, mean: np.ndarray, speed: np.ndarray, share: float) -> np.ndarray:
    """Which paths do not step as an object does, from their ``median`` and ``mean`` world step
    per frame and their ``speed`` over many frames (:func:`~trap_core.robust.camera.world_steps`,
    :func:`~trap_core.robust.camera.world_speed`): the median under ``share`` of the speed (still
    between hops) or the mean over its inverse times it (back and forth; README, steady steps).
    A NaN median (never seen in frames close enough) compares False."""
    return (median < share * speed) | (mean > speed / share)


def track_steps_steadily(track: Track, transforms: np.ndarray, lag: int, share: float) -> bool:
    """Whether ``track``'s box centres step steadily in the world (:func:`unsteady_steps`, speed
    over ``lag`` frames). A slow object whose cluster holds few patterns (a person over a JPEG
    road: two, at about 1 px a frame) can have none steady, each pattern's barycentre jittering
    by twice its speed as limbs and compression change its regions, while the track's boxes,
    built from all the object's regions, follow it. A chain of noise-born structures has no
    object under it, and its boxes jitter as its patterns do (README, tracks with no steady
    pattern)."""
    if not len(track):
        return False
    path = ObservedPaths(np.zeros(len(track), dtype=np.int64), track.frames.astype(np.int64),
                         box_centres(track.boxes).astype(np.float64))
    speed = world_speed(path, transforms, 1, lag)
    median, mean, _ = world_steps(path, transforms, 1, hop=np.inf)  # the share in hops is not read
    return not bool(unsteady_steps(median, mean, speed, share)[0])


def steady_patterns(unsteady: np.ndarray, in_hops: np.ndarray, speed: np.ndarray, hop: float) -> np.ndarray:
    """Patterns whose motion is evidence of an object: steady steps (not ``unsteady``), and under
    ``HOP_SHARE`` of the path ``in_hops`` of ``hop`` px unless their ``speed`` (px a frame) is
    at least half a hop, where steps two frames apart are hops by themselves."""
    return ~unsteady & ((in_hops < HOP_SHARE) | (speed >= hop / 2))


def steady_clusters(labels: np.ndarray, steady: np.ndarray, n_clusters: int) -> np.ndarray:
    """(``n_clusters``,) which clusters have at least one ``steady`` pattern (:func:`steady_patterns`;
    ``labels``: each pattern's cluster, -1 in none). A cluster with none has no evidence of an
    object's motion, whatever its speed: noise-born chains over a smooth ground step unevenly
    without a hop (README, tracks with no steady pattern)."""
    held = labels >= 0
    return np.bincount(labels[held], weights=steady[held], minlength=n_clusters) > 0


def moves_in_hops(result: MiningResult, patterns: np.ndarray, labels: np.ndarray, hopping: np.ndarray,
                  steady: np.ndarray, in_hops: np.ndarray) -> np.ndarray:
    """Which clusters move in hops: background chains between look-alikes.

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
    in_hops : (K,) float array
        Share of each pattern's world path made in hops
        (:func:`~trap_core.robust.camera.world_steps`).

    Returns
    -------
    (C,) bool array
        Clusters with more than ``HOP_SHARE`` of their occurrences on hopping patterns that no
        steady pattern vouches for (under ``VOUCHED_SHARE`` of their occurrences within the span
        of one of the cluster's steady patterns), and clusters with no steady pattern whose
        occurrences' patterns have on average ``HOP_SHARE`` of their paths in hops or more.
    """
    n_clusters = int(labels.max()) + 1 if labels.size else 0
    occurrences = result.st_occurrences[patterns]
    counted = hopping & (_vouched_share(result, patterns, labels, steady, occurrences) < VOUCHED_SHARE)
    total = np.maximum(np.bincount(labels, weights=occurrences, minlength=n_clusters), 1)
    unvouched = np.bincount(labels, weights=occurrences * counted, minlength=n_clusters) / total
    pooled = np.bincount(labels, weights=occurrences * in_hops, minlength=n_clusters) / total
    none_steady = np.bincount(labels, weights=steady, minlength=n_clusters) == 0
    return (unvouched > HOP_SHARE) | (none_steady & (pooled >= HOP_SHARE))


def _vouched_share(result: MiningResult, patterns: np.ndarray, labels: np.ndarray, steady: np.ndarray,
                   occurrences: np.ndarray) -> np.ndarray:
    """(K,) share of each of ``patterns``' ``occurrences`` (how many each has) within the frame
    span of a ``steady`` pattern of its cluster (``labels``)."""
    if not steady.any():
        return np.zeros(patterns.size)
    rows, owner = result.rows_of(patterns)
    frame = result.occ_frame[rows].astype(np.int64)
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
    return np.bincount(owner, weights=inside, minlength=patterns.size) / np.maximum(occurrences, 1)
