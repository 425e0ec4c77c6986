"""How long a track must be without a given number of objects: a share of the video, capped in frames."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from trap_core.clustering import MAX_TRACKS, Track
from trap_core.evaluation import boxes_by_frame, match_objects
from trap_core.pipeline import ParameterError, TrapParams, synthetic_graphs, track
from trap_core.pipeline.track_rules import _long_enough
from trap_core.synthetic import SceneConfig


def test_the_share_of_the_video_is_capped_in_frames() -> None:
    params = TrapParams()
    assert params.track_length(721) == params.min_track_length  # the share asks 180 frames: under the cap
    assert params.track_length(9000) * 9000 == pytest.approx(params.min_track_frames)  # a chunk: 200, not 2250
    assert TrapParams(min_track_frames=0).track_length(9000) == params.min_track_length
    assert params.track_frames(721) == 180 and params.track_frames(1078) == params.min_track_frames
    with pytest.raises(ParameterError, match="min_track_frames"):
        TrapParams(min_track_frames=-1)


def test_a_long_video_may_hold_as_many_more_tracks_as_they_need_cover_fewer_frames() -> None:
    params = TrapParams()
    assert params.max_tracks(400) == MAX_TRACKS  # a track covers a quarter of the video: the bound as it was
    assert params.max_tracks(721) == 2 * MAX_TRACKS  # one that passes through, 100 frames instead of 180
    assert params.max_tracks(4000) == 10 * MAX_TRACKS  # 100 frames instead of 1000
    assert params.max_tracks(9000) == 22 * MAX_TRACKS
    assert TrapParams(min_pass_frames=0).max_tracks(4000) == 5 * MAX_TRACKS  # 200 frames
    assert TrapParams(min_pass_frames=0, min_track_frames=0).max_tracks(9000) == MAX_TRACKS
    assert TrapParams(min_track_length=0).max_tracks(9000) == MAX_TRACKS


def test_a_track_that_passes_through_need_cover_fewer_frames() -> None:
    params = TrapParams()
    assert params.pass_frames(721) == params.min_pass_frames < params.track_frames(721)
    assert params.pass_frames(300) == params.track_frames(300) == 75  # the share asks fewer already
    assert params.selection_length(4000) * 4000 == pytest.approx(params.min_pass_frames)
    assert TrapParams(min_pass_frames=0).pass_frames(721) == 180
    assert TrapParams(method="paper").pass_frames(721) == 180  # no track rules tell the passing tracks apart
    assert TrapParams(one_track=False).selection_length(4000) == params.track_length(4000)
    with pytest.raises(ParameterError, match="min_pass_frames"):
        TrapParams(min_pass_frames=-1)


def test_objects_passing_through_a_long_video_are_tracked() -> None:
    """Four objects pass through a 1000-frame view, each in it for 23-33 % of the video. The first
    (232 frames) is under a quarter of the video, and only the cap in frames keeps its track."""
    params = TrapParams.from_mapping({"segmentation": "colour", "max_side": 0})
    graphs, truth = synthetic_graphs(SceneConfig(width=320, height=240, frames=1000, seed=2, objects=4,
                                                 passing=True), params)
    assert len(truth[0]) < params.min_track_length * len(graphs) <= min(len(t) for t in truth[1:])

    def found(tracking: TrapParams) -> list[tuple[float, float]]:
        tracks = track(graphs, tracking).tracks
        return [(precision, recall) for _, precision, recall in match_objects([boxes_by_frame(t) for t in tracks],
                                                                              truth)]
    assert all(precision >= 0.9 and recall >= 0.9 for precision, recall in found(params))
    precision, recall = found(TrapParams.from_mapping({"segmentation": "colour", "max_side": 0,
                                                       "min_track_frames": 0, "min_pass_frames": 0}))[0]
    assert recall < 0.5  # a share of the video alone asks more of it


def test_more_objects_than_the_bound_of_a_short_video_pass_through_a_long_one() -> None:
    """28 objects pass through a 2400-frame view, up to 9 at a time: more tracks than ``MAX_TRACKS``
    are kept (the bound grows as the track length shrinks), each on its own object."""
    params = TrapParams.from_mapping({"segmentation": "colour", "max_side": 0})
    graphs, truth = synthetic_graphs(SceneConfig(width=320, height=240, frames=2400, seed=3, objects=28,
                                                 passing=True), params)
    tracks = track(graphs, params).tracks
    assert len(tracks) > MAX_TRACKS
    found = match_objects([boxes_by_frame(t) for t in tracks], truth)
    assert sum(precision >= 0.9 and recall >= 0.9 for _, precision, recall in found) > MAX_TRACKS


def test_a_track_the_rules_left_shorter_than_a_track_is_dropped() -> None:
    """The track rules take frames from the selected clusters' tracks; one left with fewer frames
    than a track must cover goes, and the ids of those kept run 1.. in their order."""
    def lasting(frames: int, cluster: int) -> Track:
        return Track(0, np.arange(frames), np.tile([10.0, 10.0, 20.0, 20.0], (frames, 1)), np.ones(frames), cluster)

    kept = _long_enough([lasting(180, 7), lasting(179, 8), lasting(400, 9)], 180, 180, 721, (320, 240),
                        np.zeros(10, dtype=bool))
    assert [(t.cluster, t.track_id) for t in kept] == [(7, 1), (9, 2)]


def test_a_short_track_is_kept_where_it_passes_through_the_view() -> None:
    """Under the frames a track must cover, a track is kept if it holds ``pass_frames`` and its
    first and last boxes are within its usual size of the border, or at the video's ends."""
    def crossing(first: int, frames: int, x0: float, x1: float, cluster: int) -> Track:
        boxes = np.column_stack([np.linspace(x0, x1, frames), np.full(frames, 100.0), np.full((frames, 2), 20.0)])
        return Track(0, np.arange(first, first + frames), boxes, np.ones(frames), cluster)

    tracks = [crossing(300, 120, 10.0, 290.0, 1),  # in at the left, out at the right
              crossing(300, 120, 60.0, 290.0, 2),  # starts 60 px in: three of its sizes
              crossing(0, 120, 150.0, 295.0, 3),  # in view when the video starts
              crossing(601, 120, 5.0, 150.0, 4),  # in view when it ends (721 frames)
              crossing(300, 99, 10.0, 290.0, 5)]  # passes, but too short
    short = np.ones(7, dtype=bool)  # every cluster selected for pass_frames
    kept = _long_enough(tracks, 180, 100, 721, (320, 240), short)
    assert [(t.cluster, t.track_id) for t in kept] == [(1, 1), (3, 2), (4, 3)]
    assert _long_enough(tracks, 180, 180, 721, (320, 240), short) == []
    inside = crossing(300, 200, 60.0, 200.0, 6)  # long enough, but from a cluster selected as a passing one
    assert [t.cluster for t in _long_enough([inside], 180, 100, 721, (320, 240), ~short)] == [6]
    assert _long_enough([inside], 180, 100, 721, (320, 240), short) == []


def test_objects_in_view_for_fewer_frames_than_a_track_are_tracked_where_they_pass_through() -> None:
    """Four objects pass through a 1000-frame view; one is in it for 177 frames, fewer than the
    200 a track of a long video must cover, and the other objects' tracks lose frames to the
    track rules too. Tracks that enter and leave through the border keep them all."""
    params = TrapParams.from_mapping({"segmentation": "colour", "max_side": 0})
    graphs, truth = synthetic_graphs(SceneConfig(width=320, height=240, frames=1000, seed=1, objects=4,
                                                 passing=True), params)
    assert min(len(t) for t in truth) < params.track_frames(len(graphs))

    def at_90(tracking: TrapParams) -> int:
        tracks = track(graphs, tracking).tracks
        return sum(precision >= 0.9 and recall >= 0.9
                   for _, precision, recall in match_objects([boxes_by_frame(t) for t in tracks], truth))
    assert at_90(params) == 4
    assert at_90(dataclasses.replace(params, min_pass_frames=0)) <= 2
