"""The crossing-meetings benchmark judges a meeting of two tracks by the objects the ground truth
says they hold either side of it, over the meetings the crossing rule reads (lookalike_meetings)."""
from __future__ import annotations

import numpy as np
import pytest

from trap_core.clustering import Track
from trap_core.robust import lookalike_meetings


@pytest.fixture(scope="module")
def crossing_meetings(benchmark_module):
    return benchmark_module("crossing_meetings")


def _track(track_id: int, centres: np.ndarray) -> Track:
    frames = np.arange(len(centres))
    boxes = np.hstack([centres - [20.0, 15.0], np.tile([40.0, 30.0], (len(centres), 1))])
    return Track(track_id, frames, boxes, np.ones(len(centres)), track_id)


def test_a_meeting_is_kept_traded_or_not_judged_by_the_objects_held_either_side(crossing_meetings) -> None:
    """Two 40x30 objects cross at frame 50 (P right, Q left, 10 px apart vertically). Tracks that
    stay on their objects keep the meeting, tracks that swap at frame 50 trade it, and a track
    on nothing after it (or both on one object before it) leaves it unjudged. The meeting the
    rule reads is where the centres are closer than the smaller usual size (40 px)."""
    t = np.arange(100, dtype=float)[:, None]
    p, q = [100.0, 200.0] + t * [2.0, 0.0], [300.0, 210.0] + t * [-2.0, 0.0]
    truth = [{f: tuple(np.r_[c - [20.0, 15.0], 40.0, 30.0]) for f, c in enumerate(path)} for path in (p, q)]
    own = (_track(1, p), _track(2, q))
    traded = (_track(1, np.vstack([p[:50], q[50:]])), _track(2, np.vstack([q[:50], p[50:]])))
    lost = (_track(1, np.vstack([p[:50], q[50:] + [0.0, 100.0]])), _track(2, q))
    judge = crossing_meetings.verdict
    assert [judge(pair, 45, 55, 8, truth) for pair in (own, traded, lost)] == ["kept", "traded", None]
    assert judge((_track(1, p), _track(2, p)), 45, 55, 8, truth) is None  # one object for both before it
    alike = np.ones((2, 2), dtype=bool)
    assert lookalike_meetings(list(own), 100, alike) == [(0, 1, 41, 60)]
    assert lookalike_meetings(list(own), 100, ~alike) == []  # only look-alikes trade
