"""How long a track must be without a given number of objects: a share of the video, capped in frames."""
from __future__ import annotations

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
    assert params.max_tracks(721) == MAX_TRACKS  # a track covers a quarter of the video: the bound as it was
    assert params.max_tracks(4000) == 5 * MAX_TRACKS  # 200 frames instead of 1000
    assert params.max_tracks(9000) == 11 * MAX_TRACKS
    assert TrapParams(min_track_frames=0).max_tracks(9000) == MAX_TRACKS
    assert TrapParams(min_track_length=0).max_tracks(9000) == MAX_TRACKS


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
                                                       "min_track_frames": 0}))[0]
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

    kept = _long_enough([lasting(180, 7), lasting(179, 8), lasting(400, 9)], 180)
    assert [(t.cluster, t.track_id) for t in kept] == [(7, 1), (9, 2)]
