"""Rejoin the fragments of one object separated by an occlusion or an exit (ours, TRAP_SPEC
section 10 "fragments never rejoin").

The pattern distance is infinite between patterns that share no frames, so an object that
disappears for a while comes back as another cluster. Two clusters are joined when they do
not overlap in time (at most ``max_overlap`` shared frames), are made of the same structures
(for one of them, the share of its occurrences whose plane patterns the other also has is at
least ``min_similarity``: a short fragment may show only some of the object's structures, and
the ones an object shows all along count more than those seen for a moment), and,
among all such pairs, the later one starts closest to where the earlier one's motion predicts
(steady in the view or, with the camera's motion, in the world); pairs are joined greedily,
closest first, and a joined cluster can no longer take a fragment that overlaps it, which
keeps look-alike objects apart. A fragment that starts right where and when another ends
is a candidate even without shared structures (noise can change them all at once), and so is
one that starts a little later where the other's motion puts it when no third fragment comes
nearly as close to continuing either: look-alikes that cross break their patterns where they
meet and come back showing others (a disc's small regions blend with its neighbour's). With the
fragments' border contacts, a fragment that left the view (its last box at the image border,
going out) continues only one that enters it (first box at the border, coming in), and one
that vanished inside the view (occluded) only one that appears inside it: an object comes back
the way it went. A fragment whose patterns broke up shortly before its object reached the
border (or formed shortly after it came in) may have gone either way; pairs that surely came
back the way they went are joined first. Where one surely left the view and the other surely
enters it, the object's motion out of view says little of where it comes back: such pairs go
by how much of both fragments is made of structures the other has (the smaller share, to a
tenth: a fragment of a few patterns can be all on structures of a larger one), and the
prediction decides only between equals (two identical cars: one that left was continued by a
3-pattern fragment of the other car's patterns and the ground, starting at the border 40
frames later, instead of its own return). A fragment that was going to the border and is
continued inside the view more than ``lone_gap`` frames later, by one that does not come from
the border, turned back rather than went out: that continuation must start where the earlier
fragment's motion puts it (within ``max_apart``). Identical objects share every structure:
without this, one that went out was continued by a look-alike anywhere in the view.
Two groups seen at once in different places (further apart than the linking distance over the
frames both cover) are two objects and are never joined, not even through a later fragment.
Nor is a fragment joined to a group when it goes along with other clusters (in the same place,
for most of its frames) that are mostly seen with that group elsewhere: it is on their object.
Where an object's motion says nothing of where it comes back (it left the view, or was away for
longer than ``lone_gap``), structures made of discretised colours are not enough: the two
fragments' regions must also have the same colours (:mod:`trap_core.robust.end_colours`).
Nor is a group joined where one of its fragments would follow one of the other's that it could
not have become in the frames between (:mod:`trap_core.robust.reach`): pairs are joined one at
a time, and two look-alikes that each rejoin a third fragment would otherwise be one object.
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy import sparse

from trap_core.clustering import ClusterSummary, Trajectories, region_boxes_reach_border, summarise
from trap_core.mining import MiningResult
from trap_core.robust._kernels import (companions_apart, cut_counts, group_distances, long_overlaps, pairs_within,
                                      rejoin_candidates)
from trap_core.robust.camera import map_points, to_world
from trap_core.robust.end_colours import MIN_MATCH, EndColours
from trap_core.robust.reach import TAIL, FragmentReach


class BorderContacts(NamedTuple):
    """Per spatio-temporal pattern (:func:`border_contacts`): whether it enters the view,
    whether it leaves it, whether it may have come from the border and whether it may be going
    to it (these two include entering and leaving)."""

    enters: np.ndarray
    leaves: np.ndarray
    from_border: np.ndarray
    to_border: np.ndarray


# Clusters go along (are on one object) when they share at least ALONG_FRAMES times the overlap
# two fragments of one object may have and ALONG_SHARE of the shorter one's frames, within a
# quarter of the distance that makes two groups apart: evidence strong enough to overrule
# similar structures and a good prediction (a cluster along a fragment for a few frames may be
# a look-alike passing by).
ALONG_FRAMES = 4
ALONG_SHARE = 0.8
RIVAL_RATIO = 2.0  # a fragment continues another whatever its structures only where no rival comes this close
CUT_SHARE = 0.5  # a cluster (pattern) with more of its occurrences cut by the view is no evidence of motion


def structure_similarity(labels: np.ndarray, st_pattern: np.ndarray, weights: np.ndarray | float = 1.0
                         ) -> np.ndarray:
    """How much two clusters (labels 0..C-1) are made of the same structures: for the one that
    has less in the other, the share of its weight (per pattern ``weights``: its occurrences, say)
    on plane patterns the other also has. (C, C), symmetric, 1 on the diagonal."""
    share = _structure_shares(labels, st_pattern, weights)
    return np.maximum(share, share.T)


def _structure_shares(labels: np.ndarray, st_pattern: np.ndarray, weights: np.ndarray | float = 1.0
                      ) -> np.ndarray:
    """(C, C): row ``a``, column ``b``: the share of cluster ``a``'s weight on plane patterns that
    cluster ``b`` also has (:func:`structure_similarity` is the larger of the two ways)."""
    shape = (int(labels.max()) + 1 if labels.size else 0, int(st_pattern.max()) + 1 if st_pattern.size else 0)
    per_pattern = np.broadcast_to(np.asarray(weights, dtype=float), labels.shape)
    weighted = sparse.csr_matrix((per_pattern, (labels, st_pattern)), shape=shape)  # repeated cells add up
    present = weighted.copy()
    present.data = (present.data > 0).astype(float)
    totals = np.asarray(weighted.sum(axis=1)).ravel()
    return (weighted @ present.T).toarray() / np.maximum(totals, 1e-12)[:, None]


def rejoin_fragments(labels: np.ndarray, paths: Trajectories, st_pattern: np.ndarray, n_frames: int,
                     min_similarity: float = 0.3, max_overlap: int = 25,
                     at_border: BorderContacts | None = None,
                     weights: np.ndarray | None = None, transforms: np.ndarray | None = None,
                     adjacent_gap: int = 0, adjacent_reach: float = 0.0, lone_gap: int = 0,
                     max_apart: float = np.inf, colours: EndColours | None = None,
                     view: tuple[float, float] | None = None) -> np.ndarray:
    """Cluster labels (0..C'-1) after joining fragments of the same object.

    Candidate pairs and their costs are computed once on the fragments; they are then taken
    cheapest first, and a pair is joined only if the two groups it would unite (including
    earlier joins) still share at most ``max_overlap`` frames. ``at_border``: the patterns'
    contacts with the view's border (:func:`border_contacts`); pairs where the earlier fragment
    may be going to the border and the later may come from it are candidates too, taken after
    those that surely came back the way they went.
    ``weights``: per pattern, how much of its fragment it is (its occurrences); by default
    every pattern counts one. ``transforms``: the camera's motion (``transforms[t]`` maps
    frame-0 coordinates to frame ``t``); with it, a fragment may also continue where the
    earlier one's motion in the world puts it (:func:`_prediction_errors`). A fragment that
    starts at most ``adjacent_gap`` frames after another ends, at most ``adjacent_reach`` px
    from where its motion puts it, is a candidate whatever its structures: an object does not
    jump, but a noisy one can change every structure it shows from one frame to the next. So is
    one that starts up to ``lone_gap`` frames later within that reach, when no other pair of
    either fragment has a prediction error under ``RIVAL_RATIO`` times its own.
    Groups seen in the same frames more than ``max_apart`` px apart (on average over those
    frames) are two objects, whatever else they share: they are not joined. A fragment that
    may be going to the border but does not surely leave the view is continued by one that
    appears inside it (not from the border) more than ``lone_gap`` frames later only within
    ``max_apart`` of where its motion puts it. Neither are two
    fragments when one goes along with clusters (:func:`_going_along`) that are mostly seen
    with the other's group and apart from it (:func:`_on_another_object`). With ``colours``
    (each fragment's at its ends, :class:`EndColours`), two fragments across a sure exit and
    entry, or more than ``lone_gap`` frames apart, are joined only where their colours match
    (``MIN_MATCH``). Where one group's fragment follows the other's after a gap, it must begin
    within reach of where that one ended (:class:`FragmentReach`, ``max_apart`` of slack).
    With the ``view``'s width and height, a pair is a sure exit and entry (taken before the
    others) only where the earlier fragment itself ends, and the later begins, within
    ``max_apart`` of its border: a pattern's flag says only that its first (last) box reached
    the border, and a box that holds a large ground region reaches it from far inside.
    """
    labels = np.unique(labels, return_inverse=True)[1]
    summary = summarise(labels, paths, np.ones(labels.size), n_frames)
    n_clusters = summary.length.size
    if n_clusters < 2:
        return labels
    share = _structure_shares(labels, st_pattern, 1.0 if weights is None else weights)
    covered = summary.covered.astype(np.float32)
    overlap = covered @ covered.T
    start, end = summary.paths.start, summary.paths.end
    enters = leaves = from_border = to_border = np.zeros(0, dtype=bool)  # not read without ``at_border``
    if at_border is not None:
        enters, from_border = (_flag_near(labels, paths.start, summary.paths.start, flags, max_overlap)
                               for flags in (at_border.enters, at_border.from_border))
        leaves, to_border = (_flag_near(labels, paths.end, summary.paths.end, flags, max_overlap)
                             for flags in (at_border.leaves, at_border.to_border))
    earlier, later = rejoin_candidates(share, overlap, start, end, max_overlap, min_similarity,
                                       max(adjacent_gap, lone_gap), adjacent_reach > 0, to_border, from_border,
                                       leaves, enters)
    gap = start[later] - end[earlier]
    forth, back = share[earlier, later], share[later, earlier]  # each pair's shares of the other's structures
    costs = _prediction_errors(summary.paths, earlier, later, transforms)
    keep = (np.maximum(forth, back) >= min_similarity) | (
        (costs <= adjacent_reach) & ((gap <= adjacent_gap) | _unrivalled(earlier, later, costs, n_clusters)))
    if at_border is not None:  # going out, back inside the view only where its motion puts it
        turned = to_border[earlier] & ~leaves[earlier] & ~from_border[later] & (gap > lone_gap)
        keep &= ~turned | (costs <= max_apart)
    earlier, later, costs, gap, forth, back = (each[keep] for each in (earlier, later, costs, gap, forth, back))
    unsure = np.zeros(costs.size, dtype=bool)
    if at_border is not None:  # surely out and in only where the fragments themselves end and begin at the border
        surely_out, surely_in = leaves, enters
        if view is not None:  # each fragment's mean path: its last and first points
            ends = summary.paths.points[summary.paths.offsets[1:] - 1]
            starts = summary.paths.points[summary.paths.offsets[:-1]]
            surely_out = leaves & (_distance_to_border(ends, *view) <= max_apart)
            surely_in = enters & (_distance_to_border(starts, *view) <= max_apart)
        unsure = surely_out[earlier] != surely_in[later]
    # out of the view an object's motion says little: what both fragments show goes first (to a tenth)
    shown = (np.zeros(costs.size) if at_border is None
             else np.where(leaves[earlier] & enters[later], -np.round(np.minimum(forth, back), 1), 0.0))
    # out of the view, or away for long, only colours tell an object's return from a newcomer
    by_colours = np.zeros(costs.size, dtype=bool) if colours is None else gap > lone_gap
    if colours is not None and at_border is not None:
        by_colours |= leaves[earlier] & enters[later]
    group = np.arange(n_clusters)
    group_covered = summary.covered.copy()
    reach = FragmentReach(summary.paths, transforms, max_apart)
    along = _going_along(summary, overlap, ALONG_FRAMES * max_overlap, max_apart / 4)
    for pair in np.lexsort((costs, shown, unsure)):
        a, b = group[earlier[pair]], group[later[pair]]
        if a == b:
            continue
        both = np.flatnonzero(group_covered[a] & group_covered[b])
        if both.size > max_overlap:
            continue
        if both.size and _apart(summary, group == a, group == b, both) > max_apart:
            continue
        if _on_another_object(summary, group, group_covered, earlier[pair], later[pair], along, max_apart):
            continue
        if by_colours[pair] and colours.match(earlier[pair], later[pair]) < MIN_MATCH:
            continue
        if not reach.seams_within_reach(np.flatnonzero(group == a), np.flatnonzero(group == b)):
            continue
        group[group == b] = a
        group_covered[a] |= group_covered[b]
    return np.unique(group[labels], return_inverse=True)[1]


def _going_along(summary: ClusterSummary, overlap: np.ndarray, min_frames: int, reach: float) -> np.ndarray:
    """(C, C) whether two clusters are on one object: they share at least ``min_frames`` frames
    and ``ALONG_SHARE`` of the shorter one's, and are on average at most ``reach`` px apart in
    those frames (patterns on different parts of an object are a part's size apart)."""
    along = np.zeros(overlap.shape, dtype=bool)
    first, second = long_overlaps(overlap, summary.length, min_frames, ALONG_SHARE)
    if first.size == 0:
        return along
    paths = summary.paths
    within = pairs_within(first, second, overlap[first, second].astype(np.int64), reach, summary.covered,
                          paths.start, paths.offsets, paths.points)
    along[first, second] = along[second, first] = within
    return along


def _on_another_object(summary: ClusterSummary, group: np.ndarray, group_covered: np.ndarray, first: int,
                       second: int, along: np.ndarray, max_apart: float) -> bool:
    """Whether fragment ``first`` or ``second`` is on another object than the other's group:
    most of the clusters it goes along with (``along``, outside both groups) that are seen at
    once with that group are more than ``max_apart`` px from it. Most, not any: a cluster
    that mixes two look-alikes goes along with one for a while and is seen with the other."""
    outside = (group != group[first]) & (group != group[second])
    paths = summary.paths
    for mine, theirs in ((first, group[second]), (second, group[first])):
        seen, apart = companions_apart(group == theirs, group_covered[theirs], np.flatnonzero(along[mine] & outside),
                                       summary.covered, paths.start, paths.offsets, paths.points, max_apart)
        if 2 * apart > seen:
            return True
    return False


def _apart(summary: ClusterSummary, first: np.ndarray, second: np.ndarray, frames: np.ndarray) -> float:
    """Mean distance, over ``frames``, between the mean positions of the clusters in the masks
    ``first`` and ``second`` that cover each frame (every frame is covered by both)."""
    paths = summary.paths
    return float(np.mean(group_distances(first, second, frames, summary.covered, paths.start, paths.offsets,
                                         paths.points)))


def _prediction_errors(paths: Trajectories, earlier: np.ndarray, later: np.ndarray,
                       transforms: np.ndarray | None = None) -> np.ndarray:
    """Per pair (``earlier[i]``, ``later[i]``): distance between where ``later`` starts and where
    ``earlier``'s last motion would put it.

    Two motions are extrapolated across the gap: steady in the view, and, with the camera's
    ``transforms``, steady in the world (mapped back into the view with the camera's motion).
    Under a panning camera the two part by the camera's motion times the gap. Which one holds
    depends on the shot: a camera that follows the object keeps it steady in the view, a
    camera that sweeps past it leaves it steady in the world; the error is the smaller one.
    Each earlier cluster's motions are read once, however many pairs it is in (a textured
    scene has millions of pairs).
    """
    if earlier.size == 0:
        return np.zeros(0)
    ends, slot = np.unique(earlier, return_inverse=True)
    # a path's last motion runs from the first to the last of its last (up to) TAIL points
    last_frame = paths.end[ends]
    tail = np.minimum(last_frame - paths.start[ends] + 1, TAIL)
    last_row = paths.offsets[ends + 1] - 1
    last_in_view, velocity_in_view = _steady(paths.points[last_row - tail + 1], paths.points[last_row], tail)
    gap = (paths.start[later] - paths.end[earlier])[:, None]
    arrival = paths.points[paths.offsets[later]]
    error = np.linalg.norm(arrival - (last_in_view[slot] + velocity_in_view[slot] * gap), axis=1)
    if transforms is None:
        return error
    tail_start = to_world(transforms, last_frame - tail + 1, paths.points[last_row - tail + 1])
    tail_end = to_world(transforms, last_frame, paths.points[last_row])
    last_in_world, velocity_in_world = _steady(tail_start, tail_end, tail)
    seen = map_points(transforms[paths.start[later]], last_in_world[slot] + velocity_in_world[slot] * gap)
    return np.minimum(error, np.linalg.norm(arrival - seen, axis=1))


def _unrivalled(earlier: np.ndarray, later: np.ndarray, costs: np.ndarray, n_clusters: int) -> np.ndarray:
    """Per pair: no other pair of its earlier or of its later fragment costs less than
    ``RIVAL_RATIO`` times it. Look-alikes that cross break their patterns where they meet, and
    each fragment that ends there then has as many continuations as there are look-alikes."""
    rival = np.full(costs.size, np.inf)
    for ends in (earlier, later):
        lowest, next_lowest = _two_lowest(ends, costs, n_clusters)
        other = np.where(costs <= lowest[ends], next_lowest[ends], lowest[ends])
        rival = np.minimum(rival, other)
    return rival > RIVAL_RATIO * costs


def _two_lowest(keys: np.ndarray, costs: np.ndarray, n_keys: int) -> tuple[np.ndarray, np.ndarray]:
    """Per key 0..n_keys-1: the lowest and the second lowest of its ``costs`` (inf where none)."""
    lowest, second = np.full(n_keys, np.inf), np.full(n_keys, np.inf)
    if keys.size == 0:
        return lowest, second
    order = np.lexsort((costs, keys))
    keys, costs = keys[order], costs[order]
    first = np.r_[True, keys[1:] != keys[:-1]]
    lowest[keys[first]] = costs[first]
    runner_up = np.flatnonzero(first[:-1] & ~first[1:]) + 1
    second[keys[runner_up]] = costs[runner_up]
    return lowest, second


def _steady(first: np.ndarray, last: np.ndarray, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Last position and mean velocity (per frame) of paths (N, 2) whose last ``points`` (N,)
    positions run from ``first`` to ``last`` (one per frame): each is ``last + velocity * gap``
    ``gap`` frames later, moving steadily."""
    return last, (last - first) / np.maximum(points - 1, 1)[:, None]


def _flag_near(labels: np.ndarray, pattern_edge: np.ndarray, cluster_edge: np.ndarray, flags: np.ndarray,
               slack: int) -> np.ndarray:
    """Per cluster: ``flags`` of any of its patterns whose first (last) frame is within ``slack``
    frames of the cluster's first (last) frame (an object's patterns do not all vanish at once)."""
    out = np.zeros(cluster_edge.size, dtype=bool)
    near = np.abs(pattern_edge - cluster_edge[labels]) <= slack
    np.logical_or.at(out, labels[near], flags[near])
    return out


def border_contacts(result: MiningResult, patterns: np.ndarray, width: int, height: int,
                    margin: float = 0.25, lag: int = 1, reach: int = 0) -> BorderContacts:
    """Per spatio-temporal pattern of ``patterns``: whether it enters the view (its first
    occurrence box reaches the image border, :func:`trap_core.clustering.region_boxes_reach_border`,
    and its ``lag``-th is further from the border) and whether it leaves it (its last reaches the border and its
    ``lag``-th from the end was further). A pattern that starts at the border as its object
    goes out (the border cuts new structures out of it) does not enter. Then whether it may
    have come from the border and whether it may be going to it: as entering and leaving, or,
    starting (ending) clear of the border, its first box moved back (last box moved on) at the
    pattern's speed over its first (last) ``lag`` occurrences for ``reach`` frames reaches it
    (a pattern can form after its object came in, or break up before it goes out)."""
    begin, stop = result.st_offsets[patterns], result.st_offsets[patterns + 1] - 1
    later = np.minimum(begin + lag, stop)
    earlier = np.maximum(stop - lag, begin)
    rows = [result.st_rows[k] for k in (begin, later, stop, earlier)]
    first, after, last, before = (_border_distance(result, r, width, height) for r in rows)
    starts_at, ends_at = (region_boxes_reach_border(result.occ_box[rows[k]], width, height, margin) for k in (0, 2))
    enters = starts_at & (after > first)
    leaves = ends_at & (before > last)
    from_border = enters | (~starts_at & region_boxes_reach_border(
        result.occ_box[rows[0]], width, height, margin, shift=_drift(result, rows[1], rows[0]) * reach))
    to_border = leaves | (~ends_at & region_boxes_reach_border(
        result.occ_box[rows[2]], width, height, margin, shift=_drift(result, rows[3], rows[2]) * reach))
    return BorderContacts(enters, leaves, from_border, to_border)


def _drift(result: MiningResult, start: np.ndarray, end: np.ndarray) -> np.ndarray:
    """(N, 2) px per frame from occurrences ``start`` to ``end``, whichever comes first in time
    (zero between occurrences of one frame): from a later one to an earlier, the way back."""
    frames = np.abs(result.occ_frame[end] - result.occ_frame[start]).astype(float)
    step = result.occ_position[end].astype(float) - result.occ_position[start]
    return np.divide(step, frames[:, None], out=np.zeros_like(step), where=frames[:, None] != 0)


def _border_distance(result: MiningResult, rows: np.ndarray, width: float, height: float) -> np.ndarray:
    """Distance of occurrences' box centres (``rows``) to the nearest image border."""
    box = result.occ_box[rows].astype(float)
    return _distance_to_border(np.column_stack([box[:, 0] + box[:, 2], box[:, 1] + box[:, 3]]) / 2, width, height)


def _distance_to_border(points: np.ndarray, width: float, height: float) -> np.ndarray:
    """(N,) distance of ``points`` (N, 2) to the nearest border of a ``width`` x ``height`` view."""
    x, y = points[:, 0], points[:, 1]
    return np.minimum.reduce([x, y, width - x, height - y])


def border_share(result: MiningResult, patterns: np.ndarray, labels: np.ndarray, width: int,
                 height: int) -> np.ndarray:
    """(C,) share of each cluster's occurrences (``labels``: cluster of each of ``patterns``) whose
    regions reach the image's edge. Regions cut by the view have barycentres that move with
    the crop, not with what they show: a cluster seen mostly so is no evidence of motion."""
    return _cut_share(labels, _cut_counts(result, patterns, width, height), result.st_occurrences[patterns])


def whole_patterns_apart(result: MiningResult, patterns: np.ndarray, labels: np.ndarray, width: int, height: int,
                         max_cut: float = CUT_SHARE) -> np.ndarray:
    """``labels`` (cluster of each of ``patterns``) where each cluster seen mostly cut by the view
    (:func:`border_share` over ``max_cut``) has its patterns that are mostly seen whole moved to a
    cluster of their own (numbered after the others).

    Such a cluster is no evidence of motion as a whole, yet it can hold an object's patterns that
    trajectory clustering put with background patterns cut by the edge (identical discs on a
    road, one disc's few patterns with those of the road's markings): apart, they are judged on
    their own motion (the same labels are returned where no cluster has any).
    """
    cut, occurrences = _cut_counts(result, patterns, width, height), result.st_occurrences[patterns]
    apart = (_cut_share(labels, cut, occurrences)[labels] > max_cut) & (cut / np.maximum(occurrences, 1) <= max_cut)
    if not apart.any():
        return labels
    out = labels.copy()
    out[apart] = labels.max() + 1 + np.unique(labels[apart], return_inverse=True)[1].reshape(-1)
    return out


def _cut_counts(result: MiningResult, patterns: np.ndarray, width: float, height: float) -> np.ndarray:
    """Per pattern of ``patterns``: its occurrences whose regions reach the image's edge (margin 0)."""
    return cut_counts(result.st_offsets, result.st_rows, np.asarray(patterns, dtype=np.int64), result.occ_box,
                      float(width), float(height))


def _cut_share(labels: np.ndarray, cut: np.ndarray, occurrences: np.ndarray) -> np.ndarray:
    """Per cluster 0..max of ``labels`` (one per pattern): the share of its patterns' ``occurrences``
    that are ``cut`` (0 for a cluster with none)."""
    return np.bincount(labels, weights=cut) / np.maximum(np.bincount(labels, weights=occurrences), 1)
