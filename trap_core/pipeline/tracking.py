"""From plane graphs to tracks: mining, trajectories, clustering, lifetime cut, selection; the
selected clusters become tracks in :mod:`trap_core.pipeline.track_rules`."""
from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from trap_core.clustering import (ClusterSummary, Hierarchy, ObservedPaths, Track, Trajectories, cluster_patterns,
                                  observed_paths, pattern_distances, seen_frames, select_clusters, summarise,
                                  trajectories, usual_size)
from trap_core.mining import MiningResult
from trap_core.pipeline.params import TrapParams
from trap_core.pipeline.pattern_miner import PatternMiner
from trap_core.pipeline.track_rules import Clusters, ClusterTracks, tracks_of_clusters
from trap_core.rag import PlaneGraph, StackedGraphs
from trap_core.robust import (CUT_SHARE, HELD_SHARE, HOP_SHARE, SHADOWED_SHARE, EndColours, alone_at_ends,
                              border_contacts, border_share, camera_paths, camera_transforms, cluster_world_speed,
                              hand_to_owners, held_share, moves_in_hops, pattern_sizes, rejoin_fragments,
                              scene_patterns, shadowed, split_mixed, stays_with_scene, steady_clusters, steady_patterns,
                              unsteady_steps, whole_patterns_apart, without_backdrop, world_speed, world_steps)


@dataclass
class TrackingResult:
    """Everything a run produced, for outputs, evaluation and pictures."""

    mining: MiningResult
    trajectories: Trajectories  # of the clustered patterns, in the order of ``clustered`` (but those clustered
    # again without the backdrop: their trajectories are placed without it)
    clustered: np.ndarray       # spatio-temporal patterns that were clustered (increasing)
    hierarchy: Hierarchy        # of ``clustered`` but those the video's ends cut short (hierarchy leaves)
    summary: ClusterSummary
    selected: list[int]
    tracks: list[Track]
    labels: np.ndarray  # cluster of each spatio-temporal pattern (-1: not clustered)
    seconds: dict[str, float] = field(default_factory=dict)


def track(graphs: Sequence[PlaneGraph], params: TrapParams, miner: PatternMiner | None = None) -> TrackingResult:
    """Run TRAP's stages 3-7 on the plane graphs of a whole video (frame i = graphs[i]).

    ``miner``: a :class:`PatternMiner` that was given every graph as it was made (mining
    then overlaps segmentation); by default the graphs are mined here.

    ``method="paper"``: every spatio-temporal pattern is clustered. ``"robust"`` (ours): one path
    per object when linking occurrences, only patterns that move relative to the camera's
    motion are clustered, and fragments of one object are rejoined across gaps; over a plain
    scene, clusters that move only once the backdrop is left out of their occurrences are
    clustered again without it (:mod:`trap_core.robust.backdrop`); without ``n_objects``, where half
    the largest track's size (``size_separation``) is more than ``separation``, clusters are selected
    again with that separation.
    """
    seconds: dict[str, float] = {}
    n_frames = len(graphs)
    width, height = graphs[0].frame_size
    robust = params.method == "robust"
    if miner is None:
        miner = PatternMiner(params, n_frames)
        for graph in graphs:
            miner.add(graph)
    mined = miner.finish()
    params = params.in_frame_pixels(width, height)
    seconds["mining"] = miner.seconds
    start = time.perf_counter()
    observed = observed_paths(mined)  # each pattern's mean position per frame: speeds and trajectories
    clustered = np.arange(mined.n_st)
    cut_short = mined.freq_st() < miner.freq_st_min  # kept only as the video's ends cut them (robust)
    transforms = None
    free, free_observed = mined, observed
    stacked = StackedGraphs.of(graphs) if robust else None  # every frame's regions, for the rules that read them
    if params.reads_camera:
        free = without_backdrop(mined, stacked)  # where the backdrop is, occurrences placed and boxed without it
        free_observed = observed if free is mined else observed_paths(free)
        image_steps = np.stack([graph.camera_step for graph in graphs]) if params.reads_image_steps else None
        transforms = camera_transforms(camera_paths(stacked, free_observed, params.eps), n_frames, image_steps)
    still_below = params.min_speed * width  # px per frame
    if robust and params.min_speed > 0:
        hop = params.eps / 4  # a world step this long (a texture's spacing) is a hop
        speed, unsteady, in_hops = _pattern_motion(observed, transforms, mined.n_st, params, hop)
        hopping = unsteady & (in_hops >= HOP_SHARE)  # between look-alikes of the background
        steady = steady_patterns(unsteady, in_hops, speed, hop)  # vouch for their clusters
        # a pattern cut short has its speed read over few frames, where jitter passes for motion:
        # clustered only if it is steady evidence (a fast one's steps are hops by themselves)
        clustered = np.flatnonzero((speed >= still_below) & ~(cut_short & ~steady))
    sub_paths = trajectories(observed, clustered)
    if cut_short[clustered].any():  # those on objects that longer patterns follow add nothing
        kept = np.flatnonzero(~cut_short[clustered] | alone_at_ends(sub_paths, cut_short[clustered],
                                                                     pattern_sizes(mined, clustered)))
        clustered, sub_paths = clustered[kept], sub_paths.subset(kept)
    seconds["camera"] = time.perf_counter() - start
    seconds["distances"] = 0.0  # clustering: everything after the camera but the pattern distances
    after_camera = time.perf_counter()

    def lifetime_clusters(patterns: np.ndarray, result: MiningResult,
                          paths: Trajectories) -> tuple[Hierarchy, np.ndarray]:
        """The lifetime cut of ``patterns`` (``paths``: their trajectories), then with the robust
        method clusters that mix objects split (their sizes from ``result``)."""
        start = time.perf_counter()
        distances = pattern_distances(paths, params.threads)
        seconds["distances"] += time.perf_counter() - start
        hierarchy = cluster_patterns(distances, len(paths), params.linkage, params.ignore_top)
        labels = hierarchy.labels
        if robust and params.one_object:
            labels = split_mixed(hierarchy, distances, paths, pattern_sizes(result, patterns), params.tau,
                                 pattern_sizes(result, patterns, free if result is mined else None))
        return hierarchy, labels

    def cluster(patterns: np.ndarray, result: MiningResult, paths: Trajectories) -> tuple[Hierarchy, np.ndarray]:
        """Clusters of ``patterns`` (``paths``: their trajectories; their sizes and border contacts
        from ``result``): :func:`lifetime_clusters`, then with the robust method fragments of one
        object rejoined. Patterns the video's ends cut short (fewer than ``freq_st_min`` frames)
        are cut apart, those of its start and of its end each on their own: their short paths
        would shift the others' lifetime cut; they join the others only by rejoining. The
        hierarchy is the others'."""
        short = cut_short[patterns]
        if not short.any():
            hierarchy, labels = lifetime_clusters(patterns, result, paths)
        else:
            labels = np.full(patterns.size, -1, dtype=np.int64)
            rows = np.flatnonzero(~short)
            hierarchy, labels[rows] = lifetime_clusters(patterns[rows], result, paths.subset(rows))
            at_start = paths.start < n_frames / 2
            for rows in (np.flatnonzero(short & at_start), np.flatnonzero(short & ~at_start)):
                if rows.size:
                    labels[rows] = labels.max() + 1 + lifetime_clusters(patterns[rows], result, paths.subset(rows))[1]
        if robust and params.rejoin:
            fragments = np.unique(labels, return_inverse=True)[1]  # 0..C-1: the colours' and the rejoining's ids
            colours = (EndColours(result, patterns, fragments, stacked, params.core_share, params.rejoin_colour_reach)
                       if params.rejoin_colour_reach > 0 else None)
            labels = rejoin_fragments(fragments, paths, mined.st_pattern[patterns], n_frames,
                                      params.rejoin_similarity, params.tau,
                                      border_contacts(result, patterns, width, height, lag=max(1, params.tau // 2),
                                                      reach=params.tau),
                                      mined.st_occurrences[patterns], transforms,
                                      adjacent_gap=max(1, params.tau // 10), adjacent_reach=params.eps / 4,
                                      lone_gap=params.tau, max_apart=params.eps, colours=colours,
                                      view=(width, height))
        return hierarchy, labels

    hierarchy, labels = cluster(clustered, mined, sub_paths)
    occurrences = mined.st_occurrences[clustered]
    if robust and params.min_speed > 0:  # an object's patterns out of a cluster mostly cut by the view
        labels = whole_patterns_apart(mined, clustered, labels, width, height)
    summary = summarise(labels, sub_paths, occurrences, n_frames)
    moving = None
    region_boxes = mined.occ_box  # each occurrence's, as its cluster places it (with the backdrop or without)
    if robust and params.min_speed > 0:
        def moving_clusters(result: MiningResult, paths_summary: ClusterSummary, against: np.ndarray,
                            steady: np.ndarray, in_hops: np.ndarray) -> np.ndarray:
            """Clusters that move relative to the camera as a whole (averaged, noise no longer passes
            for motion), are mostly seen whole (a large region cut by the view "moves" as the camera
            pans), and do not move in hops: patterns ``against`` them that none of their ``steady``
            patterns vouches for, or with none steady, their patterns' share of paths ``in_hops``
            (:mod:`trap_core.robust.hops`)."""
            return ((cluster_world_speed(paths_summary, transforms, params.tau) >= still_below)
                    & (border_share(result, clustered, labels, width, height) <= CUT_SHARE)
                    & ~moves_in_hops(result, clustered, labels, against[clustered], steady[clustered],
                                     in_hops[clustered]))

        def seen_without_backdrop(moving: np.ndarray) -> np.ndarray:
            """Clusters not ``moving`` that mostly hold the backdrop and, placed without it, move
            steadily, where no moving cluster goes (:mod:`trap_core.robust.backdrop`)."""
            free_summary = summarise(labels, free_paths, occurrences, n_frames)
            again = (~moving & (held_share(mined, free, clustered, labels) > HELD_SHARE)
                     & moving_clusters(free, free_summary, wandering, ~wandering, free_in_hops))
            again[again] = shadowed(free_summary, np.flatnonzero(again), np.flatnonzero(moving),
                                    params.eps) <= SHADOWED_SHARE
            return again

        moving = moving_clusters(mined, summary, hopping, steady, in_hops)
        if free is not mined and moving.size:  # a plain scene: objects may have no face without the backdrop
            # placed without it, the specks of a textured backdrop jitter: a pattern that does not
            # move steadily (slow, in hops or unsteady steps) counts against its cluster
            free_speed, free_unsteady, free_in_hops = _pattern_motion(free_observed, transforms, mined.n_st,
                                                                        params, hop)
            wandering = (free_speed < still_below) | free_unsteady | (free_in_hops >= HOP_SHARE)
            free_paths = trajectories(free_observed, clustered)
            again = seen_without_backdrop(moving)
            if again.any():  # clustered again on their own, placed without the backdrop
                apart = np.flatnonzero(again[labels])
                labels = labels.copy()
                labels[apart] = labels.max() + 1 + cluster(clustered[apart], free, free_paths.subset(apart))[1]
                labels = np.unique(labels, return_inverse=True)[1]
                moving = moving_clusters(mined, summarise(labels, sub_paths, occurrences, n_frames), hopping,
                                         steady, in_hops)
                moving |= seen_without_backdrop(moving)
                sub_paths = _with_paths(sub_paths, apart, free_paths)
                summary = summarise(labels, sub_paths, occurrences, n_frames)
                region_boxes = _with_boxes(mined, free, clustered[apart])
    own_frames = robust and params.own_frames
    seen = seen_frames(mined, clustered, labels, (width, height), region_boxes) if own_frames else None
    built: dict[tuple[int, bytes], Track] = {}  # each cluster's track by its patterns, for either selection

    def selected_tracks(separation: float) -> tuple[list[int], np.ndarray, list[Track]]:
        """The clusters selected with ``separation`` (frame px), the labels of every spatio-temporal
        pattern once selection has taken the scene's patterns out of them, and their tracks."""
        chosen = replace(params, separation=separation)
        eligible_now = moving

        def selection(eligible: np.ndarray | None) -> list[int]:
            return select_clusters(summary, n_frames, params.n_objects or None, params.length_tolerance,
                                   params.selection_length(n_frames), separation, params.max_tracks(n_frames),
                                   eligible=eligible, own_frames=own_frames, seen=seen)
        selected = selection(eligible_now)
        if robust and params.min_speed > 0 and params.own_region:  # until every selected cluster's own region moves
            tested: set[int] = set()
            while fresh := [c for c in selected if c not in tested]:
                tested.update(fresh)
                paths = summary.paths.dense(np.array(fresh), np.arange(n_frames))
                still = [c for c, path in zip(fresh, paths)
                         if stays_with_scene(mined, clustered[labels == c], path, stacked, transforms,
                                             params.core_share, max(1, params.tau // 5))]
                if not still:
                    break
                eligible_now = eligible_now.copy()
                eligible_now[still] = False
                selected = selection(eligible_now)
        all_labels = np.full(mined.n_st, -1, dtype=np.int64)
        all_labels[clustered] = labels
        if robust and params.min_speed > 0 and params.own_region and selected:  # each selected cluster's pattern too
            rows = np.flatnonzero(np.isin(labels, selected))
            scene = scene_patterns(mined, clustered[rows], sub_paths.subset(rows), n_frames, stacked, transforms,
                                   params.core_share, max(1, params.tau // 5))
            all_labels[clustered[rows[scene]]] = -1
            selected = [c for c in selected if (all_labels == c).any()]  # none left: all of it was the scene
        if robust and params.one_object:
            all_labels = hand_to_owners(mined, all_labels, selected, stacked)
            selected = [c for c in selected if (all_labels == c).any()]  # none left: all of it lay on others' objects
        steady_evidence = (steady_clusters(all_labels, steady, summary.length.size)  # of the patterns of their tracks
                           if robust and params.min_speed > 0 else None)
        clusters = Clusters(summary, selected, eligible_now, labels, mined.st_pattern[clustered], occurrences,
                            steady_evidence)
        tracks_of = ClusterTracks(mined, all_labels, graphs, stacked, transforms, chosen, built)
        tracks = tracks_of_clusters(clusters, tracks_of, n_frames, (width, height), own_frames)
        return selected, all_labels, tracks

    selected, all_labels, tracks = selected_tracks(params.separation)
    if robust and not params.n_objects and params.size_separation > 0 and tracks:
        wanted = params.size_separation * max(usual_size(t) for t in tracks)
        # objects large in the view: parts of one (a person's head and legs, a car's two ends)
        # stand further apart than separation, and each can be a track; the largest track's size
        # says how far apart one object's parts can lie (README, "Objects large in the view")
        if wanted > params.separation:
            selected, all_labels, tracks = selected_tracks(wanted)
    seconds["clustering"] = time.perf_counter() - after_camera - seconds["distances"]
    return TrackingResult(mined, sub_paths, clustered, hierarchy, summary, selected, tracks, all_labels, seconds)



def _pattern_motion(observed: ObservedPaths, transforms: np.ndarray, n_patterns: int,
                    params: TrapParams, hop: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per pattern, from its ``observed`` path: its world speed over tau/2 frames (px a frame),
    whether its frame-to-frame steps are unsteady for that speed, and the share of its path made
    in hops of ``hop`` px (:func:`trap_core.robust.world_steps`; neither with ``steady_steps`` 0).
    NaN steps (never seen in frames close enough) compare False: steady."""
    speed = world_speed(observed, transforms, n_patterns, max(1, params.tau // 2))
    if params.steady_steps <= 0:
        return speed, np.zeros(n_patterns, dtype=bool), np.zeros(n_patterns)
    median, mean, in_hops = world_steps(observed, transforms, n_patterns, hop=hop)
    return speed, unsteady_steps(median, mean, speed, params.steady_steps), in_hops


def _with_boxes(result: MiningResult, placed: MiningResult, patterns: np.ndarray) -> np.ndarray:
    """``result``'s occurrence boxes, with those of ``patterns`` from ``placed`` (the same
    occurrences placed and boxed otherwise: without the backdrop)."""
    boxes = result.occ_box.copy()
    rows = placed.rows_of(patterns)[0]
    boxes[rows] = placed.occ_box[rows]
    return boxes


def _with_paths(paths: Trajectories, rows: np.ndarray, others: Trajectories) -> Trajectories:
    """``paths`` with its trajectories ``rows`` taken from ``others`` (trajectories of the same patterns)."""
    source = [paths] * len(paths)
    for row in rows:
        source[row] = others
    return Trajectories.pack([int(s.start[k]) for k, s in enumerate(source)], [s.of(k) for k, s in enumerate(source)])
