"""From plane graphs to tracks: mining, trajectories, clustering, lifetime cut, selection."""
from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from trap_core.clustering import (ClusterSummary, Hierarchy, Track, Trajectories, build_track, cluster_patterns,
                                  pattern_distances, select_clusters, summarise, trajectories)
from trap_core.mining import MiningResult, mine
from trap_core.pipeline.params import TrapParams
from trap_core.rag import PlaneGraph


@dataclass
class TrackingResult:
    """Everything a run produced, for outputs, evaluation and pictures."""

    mining: MiningResult
    trajectories: Trajectories
    hierarchy: Hierarchy
    summary: ClusterSummary
    selected: list[int]
    tracks: list[Track]
    seconds: dict[str, float] = field(default_factory=dict)


def track(graphs: Sequence[PlaneGraph], params: TrapParams) -> TrackingResult:
    """Run TRAP's stages 3-7 on the plane graphs of a whole video (frame i = graphs[i])."""
    seconds: dict[str, float] = {}
    start = time.perf_counter()
    mined = mine(graphs, params.mining(len(graphs)))
    seconds["mining"] = time.perf_counter() - start
    start = time.perf_counter()
    paths = trajectories(mined)
    distances = pattern_distances(paths)
    seconds["distances"] = time.perf_counter() - start
    start = time.perf_counter()
    hierarchy = cluster_patterns(distances, len(paths), params.linkage, params.ignore_top)
    summary = summarise(hierarchy.labels, paths, np.diff(mined.st_offsets), len(graphs))
    selected = select_clusters(summary, len(graphs), params.n_objects or None, params.length_tolerance,
                               params.min_track_length, params.separation)
    tracks = [build_track(mined, hierarchy.labels, cluster, track_id)
              for track_id, cluster in enumerate(selected, start=1)]
    seconds["clustering"] = time.perf_counter() - start
    return TrackingResult(mined, paths, hierarchy, summary, selected, tracks, seconds)
