"""From the selected clusters to tracks: each cluster's boxes, then the rules that compare tracks.

The paper's method makes one track of each selected cluster (TRAP_SPEC section 7). The robust
method (ours) then compares the tracks: duplicates merged, look-alikes that traded objects
exchanged back, stretches that repeat another track dropped or mended, tracks continued by the
clusters left over. Those rules ask for the same clusters' tracks again and again, so each
cluster's track is built once (:class:`ClusterTracks`).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from trap_core.clustering import (ClusterSummary, Track, build_track, frame_cores, reaches_border,
                                  twin_clusters, usual_size)
from trap_core.mining import MiningResult
from trap_core.ordered import each_on_threads
from trap_core.pipeline.params import TrapParams
from trap_core.rag import PlaneGraph, StackedGraphs
from trap_core.robust import (GroupBoxes, colour_overlap, colour_shares, continue_to_border, continue_tracks,
                              drop_repeated_pieces, drop_shared_stretches, drop_still_regions, drop_stray_pieces,
                              drop_strays, end_at_exits, entering_part, extend_from_twins, fill_gaps, follow_ends,
                              grow_boxes, join_handovers, join_returns, join_spare_returns, keep_one_size,
                              lookalike_tracks, mend_shared_stretches, merge_duplicates, merge_parts, separate_groups,
                              spare_entries, steady_edges, swap_at_crossings, through_groups, track_steps_steadily,
                              world_reach)


@dataclass
class ClusterTracks:
    """Each cluster's track, built once with the rules in effect that look at one track alone:
    its regions' boxes (core share), still regions left out, boxes grown to their regions, gaps
    filled. ``labels``: cluster of each spatio-temporal pattern of ``mined`` (-1: none);
    ``stacked``: every frame's plane graph, stacked once for every cluster's core regions and
    boxes (None where no rule reads them: the paper's method); ``transforms``: the camera's, or
    None where no rule needs them. ``by_patterns``: the tracks built, by cluster and its patterns,
    shared with other instances over the same ``mined`` and parameters but for ``separation``,
    which no build reads: a cluster whose patterns are those it had there has that track (the
    second selection of objects large in the view keeps most clusters as they were)."""

    mined: MiningResult
    labels: np.ndarray
    graphs: Sequence[PlaneGraph]
    stacked: StackedGraphs | None
    transforms: np.ndarray | None
    params: TrapParams
    by_patterns: dict[tuple[int, bytes], Track] = field(default_factory=dict)
    _built: dict[int, Track] = field(default_factory=dict)

    def __call__(self, cluster: int, track_id: int = 0) -> Track:
        """The cluster's track with id ``track_id``."""
        return replace(self.many([cluster])[0], track_id=track_id)

    def many(self, clusters: Sequence[int]) -> list[Track]:
        """The tracks of ``clusters`` (id 0), those not built yet taken from ``by_patterns`` or
        built ``params.threads`` at once: a build is mostly compiled kernels that release the
        GIL, and the rules that ask for several tracks (the selected clusters, the candidates
        that may mend or bring back a track) know them all before reading any."""
        wanted = [cluster for cluster in dict.fromkeys(clusters) if cluster not in self._built]
        keys = {cluster: (cluster, np.flatnonzero(self.labels == cluster).tobytes()) for cluster in wanted}
        fresh = [cluster for cluster in wanted if keys[cluster] not in self.by_patterns]
        for cluster, built in zip(fresh, each_on_threads(self._build, fresh, self.params.threads)):
            self.by_patterns[keys[cluster]] = built
        for cluster in wanted:
            self._built[cluster] = self.by_patterns[keys[cluster]]
        return [self._built[cluster] for cluster in clusters]

    @cached_property
    def _edge_pixel(self) -> float:
        """Frame pixels per pixel of the segmentation's size, for edge lines (0: they count like
        any region); the same for every cluster's track."""
        robust_lines = self.params.method == "robust" and self.params.edge_lines
        return self.params.working_pixel(*self.graphs[0].frame_size) if robust_lines else 0.0

    def _build(self, cluster: int) -> Track:
        params = self.params
        robust = params.method == "robust"
        lag = max(1, params.tau // 5)  # frames either side where a region is looked for again
        pixel = self._edge_pixel
        share = params.core_share if robust else 0.0
        stacked = self.stacked if share else None
        cores = frame_cores(self.mined, np.flatnonzero(self.labels == cluster), stacked, share) if share else None
        built = build_track(self.mined, self.labels, cluster, 0, stacked, share, pixel, cores)
        if robust and params.still_regions and share > 0:
            built = drop_still_regions(built, cores, stacked, self.transforms, lag, pixel)
        if robust and params.grow:
            built = grow_boxes(built, self.stacked, self.transforms, lag=lag, max_gap=2 * lag, pixel=pixel)
        if robust and params.fill_gaps:
            built = fill_gaps(built, params.tau, view=self.graphs[0].frame_size)
        return built


@dataclass
class Clusters:
    """What the track rules read of the clustering: the ``summary`` of every cluster, the
    ``selected`` ones, which are ``moving`` (None: all may be), and the ``labels``, plane
    ``structures`` and ``occurrences`` of the clustered patterns (look-alikes share structures);
    ``steady``: which clusters have a pattern that moves steadily in the world
    (:func:`trap_core.robust.steady_patterns`; None: not read)."""

    summary: ClusterSummary
    selected: list[int]
    moving: np.ndarray | None
    labels: np.ndarray
    structures: np.ndarray
    occurrences: np.ndarray
    steady: np.ndarray | None = None


def tracks_of_clusters(clusters: Clusters, tracks_of: ClusterTracks, n_frames: int, view: tuple[int, int],
                       own_frames: bool) -> list[Track]:
    """The selected clusters' tracks (ids from 1), with the rules of ``tracks_of.params`` that
    compare tracks (``own_frames``: clusters were selected by the frames they hold alone, and
    their twins may extend them)."""
    params = tracks_of.params
    robust = params.method == "robust"
    width, height = view
    summary, selected, moving = clusters.summary, clusters.selected, clusters.moving
    tracks = [replace(t, track_id=i) for i, t in enumerate(tracks_of.many(selected), start=1)]
    counted = robust and params.one_track and not params.n_objects  # the unsupervised count's tracks
    need = params.track_frames(n_frames)
    short = summary.length < need  # per cluster: selected (if at all) for pass_frames alone
    if counted:  # such a cluster is a track only if it passes through the view, before any rule reads it
        tracks = _long_enough(tracks, 0, 0, n_frames, view, short)
    if robust and params.one_track:
        tracks = merge_duplicates(tracks, params.tau)
    if own_frames and not params.n_objects:
        twins = twin_clusters(summary, selected, n_frames, params.track_length(n_frames), params.separation,
                              params.tau, moving)
        tracks = extend_from_twins(tracks, tracks_of.many(twins), params.tau, params.size_jump, view=view)
    placed = GroupBoxes({})
    if robust and (params.size_jump or params.groups):
        seen = tracks
        tracks = separate_groups(tracks, n_frames, width, height, params.size_jump, 4 * params.tau,
                                 groups=params.groups, patience=params.tau, min_gap=params.tau)
        placed = GroupBoxes.placed(seen, tracks)
    motion_window = max(3, params.tau // 2)  # frames over which a track's motion at a point is read
    if robust and params.one_track:
        tracks = _one_track_per_object(tracks, clusters, tracks_of, n_frames, view, motion_window)
    if robust and params.to_border:
        tracks = [continue_to_border(t, n_frames, width, height, motion_window, 2 * params.tau,
                                      max(1, params.tau // 5)) for t in tracks]
    if robust and params.one_track and params.rejoin and len(tracks) > 1:
        tracks = join_returns(tracks, width, height, _lookalikes(tracks, clusters, tracks_of.graphs))
    if robust and params.one_track and params.rejoin and tracks:
        tracks = _returns_of_spares(tracks, clusters, tracks_of, n_frames, view, motion_window)
    if robust and params.groups:  # who is who is settled: placed boxes back on their track's path
        tracks = [through_groups(t, placed, 2 * params.tau) for t in tracks]
    if robust and params.one_track:
        tracks = merge_parts(tracks, params.tau)
    if counted:
        transforms = tracks_of.transforms
        tracks = [t for t in tracks
                  if _goes_somewhere(t, transforms) and _steadily_seen(t, clusters.steady, transforms, params)]
        tracks = _long_enough(tracks, need, params.pass_frames(n_frames), n_frames, view, short)
    if robust and params.follow_ends:
        tracks = follow_ends(tracks, tracks_of.stacked, width, height, motion_window)
    if robust and params.steady_edges:
        tracks = [steady_edges(t, motion_window, width, height) for t in tracks]
    return tracks


def _long_enough(tracks: list[Track], min_frames: int, pass_frames: int, n_frames: int,
                 view: tuple[int, int], short: np.ndarray) -> list[Track]:
    """The tracks that still hold at least ``min_frames`` frames, and those of clusters that span
    fewer (``short``, per cluster: selected for ``pass_frames``) that hold ``pass_frames`` and
    pass through the view (:func:`_passes_through`); ids renumbered 1.. in order.

    A cluster is selected for covering a track's length, but the rules that compare tracks take
    frames away (stretches that repeat another track's, boxes past an exit, pieces of another
    size), and a track left shorter than a track must be is what was left of background or of
    another object once those were taken (README, tracks left short). A short cluster's track
    must still pass through however many frames the rules gave it: other clusters lend frames
    to any track."""
    def kept_one(track: Track) -> bool:
        if short[track.cluster]:
            return len(track) >= pass_frames and _passes_through(track, n_frames, view)
        return len(track) >= min_frames

    kept = [t for t in tracks if kept_one(t)]
    return [replace(t, track_id=i) for i, t in enumerate(kept, start=1)]


def _goes_somewhere(track: Track, transforms: np.ndarray | None) -> bool:
    """Whether ``track``'s box goes farther in the world than its own usual size (the median of
    its larger side; :func:`trap_core.robust.world_reach`). A chain of background patterns that
    hop between neighbouring look-alikes can pass every speed test and still never leave the
    place where it started (README, tracks that go nowhere); an object moves on."""
    return len(track) > 0 and world_reach(track, transforms) >= usual_size(track)


def _steadily_seen(track: Track, steady: np.ndarray | None, transforms: np.ndarray | None, params: TrapParams) -> bool:
    """Whether one of the patterns of ``track``'s cluster moves steadily in the world (``steady``,
    per cluster; None: not read), or, with none, the track's own boxes do. Noise makes and
    unmakes structures over a smooth or grainy ground, and a chain of them can pass every test of
    a cluster's motion with not one pattern whose steps follow each other as an object's do, nor
    boxes that do; every object's track has one or the other (README, tracks with no steady
    pattern)."""
    if steady is None or steady[track.cluster]:
        return True
    return transforms is not None and track_steps_steadily(track, transforms, max(1, params.tau // 2),
                                                           params.steady_steps)


def _passes_through(track: Track, n_frames: int, view: tuple[int, int]) -> bool:
    """Whether ``track`` enters the view through its border (or is in it when the video starts)
    and leaves through it (or is in it when the video ends): an object that crosses the view in
    fewer frames than a track must hold is seen whole so, where a piece of an object or of the
    background starts or stops inside the view (README, tracks that pass through). An end box
    within the track's usual size (its median) of the border counts: the patterns of an object
    half out of view may hold only a sliver of it, or none."""
    if not len(track):
        return False
    ends = reaches_border(track.boxes[[0, -1]], *view, margin=1.0, size=np.median(track.boxes[:, 2:], axis=0))
    return bool((track.frames[0] == 0 or ends[0]) and (track.frames[-1] == n_frames - 1 or ends[1]))


def _one_track_per_object(tracks: list[Track], clusters: Clusters, tracks_of: ClusterTracks, n_frames: int,
                          view: tuple[int, int], motion_window: int) -> list[Track]:
    """The ``one_track`` rules (README, one track per object): strays dropped, trades at
    crossings exchanged back, shared stretches mended or dropped, tracks ended at exits and
    continued by spare clusters, handovers joined, one size kept."""
    params = tracks_of.params
    width, height = view
    summary = clusters.summary
    tracks = _gaps_filled([drop_strays(t, max(3, params.tau // 3)) for t in tracks], params, view)
    alike = _lookalikes(tracks, clusters, tracks_of.graphs)
    tracks = swap_at_crossings(tracks, n_frames, max(3, params.tau // 3), alike)
    spare = _spare_clusters(clusters, params.tau)
    tracks = mend_shared_stretches(tracks, summary, spare, n_frames, params.tau, tracks_of.many, window=motion_window)
    tracks = drop_shared_stretches(tracks, n_frames, params.tau, motion_window)
    tracks = drop_repeated_pieces(tracks, motion_window, min_frames=params.tau)
    tracks = [t for t in (drop_stray_pieces(t, n_frames, motion_window, params.tau) for t in tracks) if len(t)]
    tracks = [end_at_exits(t, width, height, motion_window) for t in tracks]
    tracks = continue_tracks(tracks, summary, spare, n_frames, width, height, motion_window, params.eps, tracks_of)
    tracks = [end_at_exits(t, width, height, motion_window) for t in tracks]  # and the continuations'
    tracks = join_handovers(tracks, n_frames, motion_window, params.eps, max_gap=2 * params.tau)
    tracks = _gaps_filled(tracks, params, view)
    if params.size_jump:  # the continuations' boxes were not sized against their tracks yet
        tracks = separate_groups(tracks, n_frames, width, height, params.size_jump, 4 * params.tau,
                                 groups=False, min_gap=params.tau)
    if not params.n_objects:
        tracks = keep_one_size(tracks, params.tau, params.track_frames(n_frames))
    return tracks


def _spare_clusters(clusters: Clusters, min_frames: int) -> np.ndarray:
    """Clusters not selected that move and span at least ``min_frames`` frames: they may hold an
    object's frames that the selected clusters miss."""
    summary = clusters.summary
    spare = np.flatnonzero((summary.length >= min_frames) & (True if clusters.moving is None else clusters.moving))
    return spare[~np.isin(spare, clusters.selected)]


def _returns_of_spares(tracks: list[Track], clusters: Clusters, tracks_of: ClusterTracks, n_frames: int,
                       view: tuple[int, int], motion_window: int) -> list[Track]:
    """Tracks whose object left the view continued by the spare cluster that brings it back
    (:func:`join_spare_returns`, out of view within 2 tau frames). A spare is read from its first
    frame after the exit off the tracks' boxes near the border (:func:`spare_entries`), its
    frames where its box repeats a track's are left out (it holds that track's object there),
    and it starts at its first box at the border (:func:`entering_part`); one left with fewer
    than tau frames brings nothing back."""
    params = tracks_of.params
    width, height = view

    def spares_after(frame: int, size: np.ndarray) -> list[Track]:
        first = spare_entries(clusters.summary, _spare_clusters(clusters, params.tau), tracks, frame, size, width,
                              height, params.tau)
        parts = [entering_part(built, first[built.cluster], tracks, width, height)
                 for built in tracks_of.many(list(first))]
        return [part for part in parts if len(part) >= params.tau]

    return join_spare_returns(tracks, spares_after, lambda every: _lookalikes(every, clusters, tracks_of.graphs),
                              *view, n_frames, motion_window, 2 * params.tau)


def _lookalikes(tracks: list[Track], clusters: Clusters, graphs: Sequence[PlaneGraph]) -> np.ndarray:
    """(T, T) whether two tracks may hold look-alike objects (:func:`lookalike_tracks`, colours too)."""
    return lookalike_tracks(tracks, clusters.labels, clusters.structures, clusters.occurrences,
                            colours=colour_overlap(colour_shares(tracks, graphs)))


def _gaps_filled(tracks: list[Track], params: TrapParams, view: tuple[int, int]) -> list[Track]:
    """The tracks with their gaps filled again after a rule removed or appended boxes."""
    return [fill_gaps(t, params.tau, view=view) for t in tracks] if params.fill_gaps else tracks
