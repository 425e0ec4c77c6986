"""Which clusters are tracks (TRAP_SPEC section 7)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from trap_core.clustering._kernels import cluster_sums, near_frames
from trap_core.clustering.tracks import region_boxes_reach_border
from trap_core.clustering.trajectory import Trajectories
from trap_core.mining import MiningResult

MAX_TRACKS = 20  # no more tracks than this in a video where a track covers a share of it (min_length)
APART_SHARE = 0.75  # share of its frames a cluster seen in under min_length of the video must lie apart from tracks


@dataclass(frozen=True)
class ClusterSummary:
    """Per cluster: frames covered by its patterns, pattern and occurrence counts, mean path."""

    covered: np.ndarray       # (C, n_frames) bool
    n_patterns: np.ndarray    # (C,)
    n_occurrences: np.ndarray  # (C,)
    paths: Trajectories       # mean trajectory of each cluster's patterns, per covered frame

    @property
    def length(self) -> np.ndarray:
        return self.covered.sum(axis=1)


def summarise(labels: np.ndarray, tracks: Trajectories, occurrences_per_pattern: np.ndarray,
              n_frames: int) -> ClusterSummary:
    """Length, counts and mean path of each cluster (labels 0..C-1 over the patterns)."""
    n_clusters = int(labels.max()) + 1 if labels.size else 0
    sums, counts = cluster_sums(np.asarray(labels, dtype=np.int64), tracks.start, tracks.end, tracks.offsets,
                                np.asarray(tracks.points, dtype=np.float64), n_clusters, n_frames)
    covered = counts > 0
    cluster_of, frames = np.nonzero(covered)  # cluster by cluster, frames increasing
    paths = Trajectories.interpolated(frames.astype(np.int64), sums[cluster_of, frames] / counts[cluster_of, frames, None],
                                      np.r_[0, np.cumsum(covered.sum(axis=1))])
    return ClusterSummary(covered, np.bincount(labels, minlength=n_clusters),
                          np.bincount(labels, weights=occurrences_per_pattern, minlength=n_clusters).astype(np.int64),
                          paths)


def _longest(summary: ClusterSummary, candidates: np.ndarray, lengths: np.ndarray, tolerance_frames: float) -> int:
    """The paper's "longest": within ``tolerance_frames`` of the longest of ``lengths`` (one per
    candidate), most patterns, then most occurrences."""
    near = candidates[lengths >= lengths.max() - tolerance_frames]
    order = np.lexsort((-summary.n_occurrences[near], -summary.n_patterns[near]))
    return int(near[order[0]])


def seen_frames(result: MiningResult, patterns: np.ndarray, labels: np.ndarray,
                view: tuple[float, float] | None = None, boxes: np.ndarray | None = None) -> np.ndarray:
    """(C,) frames in which each cluster (``labels``: cluster of each of ``patterns``) has an
    occurrence. A cluster's length counts every frame its patterns span, and a pattern's path
    bridges gaps of up to ``tau`` frames: one pattern seen now and then spans many frames it is
    not seen in (a background structure that noise makes and unmakes).

    With the ``view``'s width and height, only occurrences whose regions do not reach its edge
    count (``boxes``: each occurrence's region box, x0, y0, x1, y1 inclusive; by default
    ``result.occ_box``). One that does can hold the backdrop, which is in every frame with the
    frame's box whatever the objects do: a cluster that has it over some frames, and an
    object's patterns over others, is seen on an object only in the others.
    """
    rows, owner = result.rows_of(patterns)
    if view is not None:
        whole = ~region_boxes_reach_border((result.occ_box if boxes is None else boxes)[rows], *view, margin=0.0)
        rows, owner = rows[whole], owner[whole]
    frames = result.occ_frame[rows].astype(np.int64)
    n_frames = int(result.occ_frame.max()) + 1 if result.occ_frame.size else 1
    sightings = np.unique(labels[owner].astype(np.int64) * n_frames + frames)
    return np.bincount(sightings // n_frames, minlength=int(labels.max()) + 1 if labels.size else 0)


def select_clusters(summary: ClusterSummary, n_frames: int, n_objects: int | None = None,
                    tolerance: float = 0.1, min_length: float = 0.25, separation: float = 40.0,
                    max_objects: int = MAX_TRACKS, eligible: np.ndarray | None = None, own_frames: bool = False,
                    seen: np.ndarray | None = None) -> list[int]:
    """Clusters that are tracks, in order of selection.

    ``eligible``: per cluster, whether it may be a track at all (ours: clusters that move
    relative to the camera); by default every cluster.

    With ``n_objects``: the ``n_objects`` longest clusters, one after another (the paper).
    Without (ours, unsupervised): keep taking the next longest cluster while it covers at
    least ``min_length`` of the video, skipping any cluster that is, in most of the frames it
    covers, within ``separation`` pixels of a cluster already kept: "the longest clusters that
    are far enough from each other". Counting frames against every kept cluster (not a mean
    distance to each) also rejects a chain of fragments that follows one object, then
    another. With ``own_frames`` (ours) "longest" counts only a cluster's own frames, those
    where no kept cluster is near: a chain that follows a kept object for a third of its frames
    no longer beats a shorter cluster that is all its own. Given ``seen`` (ours: per cluster,
    the frames where it has occurrences, :func:`seen_frames`), the unsupervised count also asks
    that a cluster be seen in ``min_length`` of the video, not only span it. With both, a
    cluster seen in at least half that is taken after the others, when it is apart from every
    track in ``APART_SHARE`` of its frames: an object whose regions keep changing shape (a
    glyph that merges with its body in every other frame) gives frequent patterns in a third of
    its frames; clusters seen as rarely beside a track are mostly its fragments, or a second
    cluster on its object.
    """
    remaining = np.arange(summary.length.size)
    if eligible is not None:
        remaining = remaining[eligible]
    if n_objects is None and own_frames:
        long_enough = remaining[summary.length[remaining] >= min_length * n_frames]
        if seen is None:
            return _most_own_frames(summary, long_enough, n_frames, tolerance, separation, max_objects)
        often = seen[long_enough] >= min_length * n_frames
        rarely = ~often & (seen[long_enough] >= min_length * n_frames / 2)
        chosen = _most_own_frames(summary, long_enough[often], n_frames, tolerance, separation, max_objects)
        return chosen + _most_own_frames(summary, long_enough[rarely], n_frames, tolerance, separation,
                                         max_objects - len(chosen), chosen, APART_SHARE)
    if n_objects is None and seen is not None:
        remaining = remaining[seen[remaining] >= min_length * n_frames]
    chosen: list[int] = []
    limit = n_objects if n_objects is not None else max_objects
    while remaining.size and len(chosen) < limit:
        best = _longest(summary, remaining, summary.length[remaining], tolerance * n_frames)
        remaining = remaining[remaining != best]
        if n_objects is None:
            if summary.length[best] < min_length * n_frames:
                break
            if chosen and _near_kept(summary, np.array([best]), chosen, separation).sum() > summary.length[best] / 2:
                continue
        chosen.append(best)
    return chosen


def _most_own_frames(summary: ClusterSummary, candidates: np.ndarray, n_frames: int, tolerance: float,
                     separation: float, max_objects: int, kept: list[int] | None = None,
                     own_share: float = 0.5) -> list[int]:
    """Unsupervised selection among long enough ``candidates`` by own frames (no cluster of
    ``kept`` or chosen here near), each chosen only while at least ``own_share`` of its frames
    are its own."""
    chosen: list[int] = []
    near = (_near_kept(summary, candidates, kept, separation) if kept and candidates.size
            else np.zeros((candidates.size, n_frames), dtype=bool))
    while candidates.size and len(chosen) < max_objects:
        own = (summary.covered[candidates] & ~near).sum(axis=1)
        free = own >= own_share * summary.length[candidates]
        if not free.any():
            break
        chosen.append(_longest(summary, candidates[free], own[free], tolerance * n_frames))
        keep = candidates != chosen[-1]
        candidates, near = candidates[keep], near[keep] | _near_kept(summary, candidates[keep], chosen[-1:], separation)
    return chosen


def _near_kept(summary: ClusterSummary, clusters: np.ndarray, kept: list[int], separation: float) -> np.ndarray:
    """(len(clusters), n_frames) bool: frames where a cluster's mean position is within
    ``separation`` pixels of the mean position of one of ``kept`` covering that frame."""
    return np.any([_near_frames(summary, clusters, other, separation) for other in kept], axis=0)


def _near_frames(summary: ClusterSummary, clusters: np.ndarray, other: int, separation: float) -> np.ndarray:
    """(len(clusters), n_frames) bool: frames where each cluster's mean position is within
    ``separation`` pixels of the mean position of cluster ``other`` (both covering the frame)."""
    paths = summary.paths
    return near_frames(np.asarray(clusters, dtype=np.int64), int(other), summary.covered, paths.start, paths.offsets,
                       paths.points, float(separation))


def twin_clusters(summary: ClusterSummary, chosen: list[int], n_frames: int, min_length: float, separation: float,
                  min_new: int, eligible: np.ndarray | None = None) -> list[int]:
    """Clusters left out beside a kept one that can lend it frames (ours), longest first.

    A cluster of at least ``min_length`` of the video, left out because in most of its frames
    it is near one kept cluster, often holds the same object with other structures (noisy
    regions split an object's patterns among clusters that overlap in time) and may cover
    frames the kept one lacks (the object's return, which rejoined only one of them). Those
    covering at least ``min_new`` such frames are returned, or half as many where they reach
    the video's first or last frame (the video cut the object's time there short, as
    :func:`trap_core.robust.drop_stray_pieces` reads a piece there); the tracks decide which
    frames are taken (:func:`trap_core.robust.extend_from_twins`).
    """
    spare = np.arange(summary.length.size)
    if eligible is not None:
        spare = spare[eligible]
    spare = spare[(summary.length[spare] >= min_length * n_frames) & ~np.isin(spare, chosen)]
    spare = spare[np.argsort(-summary.length[spare], kind="stable")]
    if not chosen or not spare.size:
        return []
    near = np.array([_near_frames(summary, spare, kept, separation).sum(axis=1) for kept in chosen])  # (kept, spare)
    twins = []
    for column, cluster in enumerate(spare.tolist()):
        beside = int(np.argmax(near[:, column]))
        new = summary.covered[cluster] & ~summary.covered[chosen[beside]]
        needed = min_new / 2 if new[0] or new[-1] else min_new
        if near[beside, column] >= summary.length[cluster] / 2 and np.count_nonzero(new) >= needed:
            twins.append(cluster)
    return twins
