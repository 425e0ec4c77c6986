"""Patterns that lie on another track's object are handed to that track (ours).

Average linkage (TRAP_SPEC section 6) puts a pattern with the cluster whose paths run closest
to its own over the frames they share. Where one object passes close by another for a while,
short patterns of the second (often with a background region beside it) run near the first
one's path then, and can join the first one's cluster. That cluster is then in two places at
once: its box covers both objects, or goes over to the other object for as long as those
patterns last, where the box cannot tell the track's own place
(:func:`trap_core.clustering.one_place`: the two side by side, or the other's patterns the
longer-lived).

Regions tell whose a pattern is: in one frame, patterns of one object hold the same regions.
A pattern of a selected cluster is handed to another selected cluster when, in most of its
frames, the patterns it shares regions with are mostly that cluster's, and that cluster then
also has the longer-lived ones (a track's own long patterns outweigh a few short ones that
happen to share a region). To leave alone two clusters on one object (the pieces of a track
cut by a gap, which later rules join), the move also needs frames where its own cluster is in
two places: it has there another pattern that shares no region with this one.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from trap_core.mining import MiningResult
from trap_core.rag import StackedGraphs
from trap_core.rag._kernels import video_sets_nodes
from trap_core.robust._kernels import shared_support

MOST = 0.5        # share of a pattern's frames that must point to the other cluster (more than)
TWO_PLACES = 0.25  # share of its frames pointing there while its own cluster is in two places (at least)


def hand_to_owners(result: MiningResult, labels: np.ndarray, selected: Sequence[int],
                   graphs: StackedGraphs) -> np.ndarray:
    """Cluster labels with the selected clusters' patterns that lie on another selected
    cluster's object moved to that cluster.

    Parameters
    ----------
    result : MiningResult
    labels : (S,) int array
        Cluster of each spatio-temporal pattern (-1: not clustered).
    selected : sequence of int
        The clusters kept as tracks.
    graphs : StackedGraphs
        The video's plane graphs, stacked: the regions each occurrence holds.

    Returns
    -------
    (S,) int array
        ``labels``, changed only for the moved patterns.
    """
    patterns = np.flatnonzero(np.isin(labels, selected))
    if len(selected) < 2 or patterns.size == 0:
        return labels
    slot = np.full(int(labels.max()) + 1, -1, dtype=np.int64)
    slot[np.asarray(selected)] = np.arange(len(selected))
    sighting_pattern, sighting_frame, holders, nodes = _held_regions(result, patterns, graphs)
    cluster = slot[labels[patterns[sighting_pattern]]]
    weight = result.st_occurrences[patterns[sighting_pattern]].astype(float)  # occurrences: its lifetime
    n_sightings, n_clusters = cluster.size, len(selected)
    support, own_sharers = shared_support(holders, nodes, int(graphs.node_offsets[-1]) + len(graphs), cluster,
                                          weight, n_clusters)
    rows = np.arange(n_sightings)
    own = support[rows, cluster].copy()
    support[rows, cluster] = -np.inf
    other = support.argmax(axis=1)
    goes = support[rows, other] > own
    present = np.zeros((int(sighting_frame.max()) + 1, n_clusters), dtype=np.int64)
    np.add.at(present, (sighting_frame, cluster), 1)
    two_places = present[sighting_frame, cluster] - 1 > own_sharers
    votes = np.zeros((patterns.size, n_clusters), dtype=np.int64)
    np.add.at(votes, (sighting_pattern[goes], other[goes]), 1)
    split_votes = np.zeros_like(votes)
    np.add.at(split_votes, (sighting_pattern[goes & two_places], other[goes & two_places]), 1)
    frames = np.bincount(sighting_pattern, minlength=patterns.size)
    target = votes.argmax(axis=1)
    index = np.arange(patterns.size)
    moves = (votes[index, target] > MOST * frames) & (split_votes[index, target] >= TWO_PLACES * frames)
    handed = labels.copy()
    handed[patterns[moves]] = np.asarray(selected)[target[moves]]
    return handed


def _held_regions(result: MiningResult, patterns: np.ndarray,
                  graphs: StackedGraphs) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Sightings (one pattern in one frame: index into ``patterns`` and frame) and the regions
    they hold: sighting ``holders[e]`` holds region ``nodes[e]`` (a node id over the whole video,
    :func:`trap_core.rag._kernels.video_sets_nodes`)."""
    rows, owner = result.rows_of(patterns)
    frames = result.occ_frame[rows].astype(np.int64)
    # by frame, then pattern: sightings that share regions are of one frame, so numbered close together
    keys, sighting = np.unique(frames * patterns.size + owner, return_inverse=True)
    by_frame = np.argsort(frames, kind="stable")
    known, starts = np.unique(frames[by_frame], return_index=True)
    nodes, ends = video_sets_nodes(result.occ_faces[rows[by_frame]], known, np.r_[starts[1:], by_frame.size],
                                   graphs.node_offsets, graphs.face_base, graphs.face_offsets, graphs.face_half_edges,
                                   graphs.he_origin)
    holders = np.repeat(sighting.reshape(-1)[by_frame], np.diff(ends, prepend=0))
    return keys % patterns.size, keys // patterns.size, holders, nodes
