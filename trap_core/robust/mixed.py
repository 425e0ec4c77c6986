"""One object per cluster: clusters of the lifetime cut that mix objects are split (ours).

The lifetime cut (TRAP_SPEC section 6) chooses one level for the whole hierarchy. Once the
background is left out, few patterns remain and the chosen level can hold a cluster whose
patterns lie on two objects at the same time: averaged, its path runs between them. Two
patterns of one object seen in the same frames are never further apart than half the sum of
their sizes (their occurrence boxes' diagonals): they overlap or touch. Such a pair is taken for
two objects when it is further apart on average over those frames, or in at least ``min_apart``
of them: where look-alikes meet, a pattern's path can go on with the other object, and its
pattern then shares that object's path for the rest of the video, which the average hides. A
cluster with such a pair is replaced by the two clusters it was merged from, and so on down the
hierarchy until every cluster passes.
"""
from __future__ import annotations

import numpy as np

from trap_core.clustering import Hierarchy, Trajectories
from trap_core.mining import MiningResult
from trap_core.robust._kernels import any_pair_apart, any_pair_far, pattern_mean_sizes


def pattern_sizes(result: MiningResult, patterns: np.ndarray, placed: MiningResult | None = None) -> np.ndarray:
    """Mean size of the occurrences of each spatio-temporal pattern in ``patterns`` (increasing):
    the diagonal of the occurrence's box.

    With ``placed``, the same occurrences placed and boxed without the backdrop
    (:func:`trap_core.robust.without_backdrop`): the backdrop's box is the frame's, which would
    make every pattern that holds it as large as the view and never apart from anything. The
    box is then the one without the backdrop, and twice the distance from the occurrence's
    position to its position without the backdrop is added: positions (the paths compared)
    keep the backdrop's pull toward the middle of the view, and two patterns of one object are
    then at most half the sum of their sizes apart.
    """
    box = (result if placed is None else placed).occ_box
    return pattern_mean_sizes(result.st_offsets, result.st_rows, np.asarray(patterns, dtype=np.int64), box,
                              result.occ_position, result.occ_position[:0] if placed is None else placed.occ_position)


def split_mixed(hierarchy: Hierarchy, distances: np.ndarray, paths: Trajectories, sizes: np.ndarray,
                min_apart: int, mean_sizes: np.ndarray | None = None) -> np.ndarray:
    """Cluster labels (0..C'-1) of the cut with every cluster that mixes objects split.

    Parameters
    ----------
    hierarchy : Hierarchy
        The dendrogram and its cut.
    distances : condensed array
        ``d(A, B) = d_traj * (2 - d_ov)`` of the clustered patterns (TRAP_SPEC section 5), from
        which the mean distance over common frames ``d_traj`` is recovered.
    paths : Trajectories
        The clustered patterns' trajectories (their spans give ``d_ov``).
    sizes : (n,) array
        Size of each pattern in every frame (:func:`pattern_sizes`).
    min_apart : int
        Frames in which two patterns further apart than half the sum of their ``sizes`` are on
        two objects whatever their mean distance (``tau``).
    mean_sizes : (n,) array, optional
        Size of each pattern on average, against which mean distances are judged
        (:func:`pattern_sizes` with the occurrences placed without the backdrop); ``sizes`` by
        default. A pattern that holds the backdrop has the frame for its box in every frame,
        yet on average lies within its box without the backdrop and the backdrop's pull; frame
        by frame its position jumps with the backdrop's barycentre (regions merging into it or
        leaving it), so only its mean distance can tell it from another object's.

    Returns
    -------
    (n,) int array
    """
    n = hierarchy.n
    if n < 2:
        return hierarchy.labels.copy()
    mean_sizes = np.asarray(sizes if mean_sizes is None else mean_sizes, dtype=np.float64)
    children = hierarchy.linkage[:, :2].astype(np.int64)
    below_cut = n + (n - hierarchy.cut_level)  # nodes formed by the merges made before the cut
    labels = np.empty(n, dtype=np.int64)
    next_label = 0
    stack = [2 * n - 2]
    while stack:
        node = stack.pop()
        leaves = _leaves(children, n, node)
        if node < n or (node < below_cut and not any_pair_far(leaves, distances, n, paths.start, paths.end, mean_sizes)
                        and not _apart_for(paths, leaves, sizes, min_apart)):
            labels[leaves] = next_label
            next_label += 1
        else:
            stack.extend(children[node - n].tolist())
    return np.unique(labels, return_inverse=True)[1]


def _apart_for(paths: Trajectories, patterns: np.ndarray, sizes: np.ndarray, min_frames: int) -> bool:
    """Whether two of ``patterns`` are further apart than half the sum of their sizes in at least
    ``min_frames`` of the frames both are seen in (compiled: every cluster of the cut is tested,
    and every node above it the split goes down through)."""
    return bool(any_pair_apart(patterns, np.asarray(sizes, dtype=np.float64), min_frames, paths.start, paths.end,
                               paths.offsets, paths.points))


def _leaves(children: np.ndarray, n: int, node: int) -> np.ndarray:
    """Patterns under ``node`` of a scipy linkage tree."""
    found, stack = [], [node]
    while stack:
        top = stack.pop()
        if top < n:
            found.append(top)
        else:
            stack.extend(children[top - n].tolist())
    return np.array(found, dtype=np.int64)
