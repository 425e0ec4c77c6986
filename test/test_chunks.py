"""Long streams tracked chunk by chunk: ids continue across chunks, boxes final while reading."""
from __future__ import annotations

import numpy as np
import pytest

import trap_core.pipeline.chunks as chunks
from trap_core.clustering import Track
from trap_core.pipeline import ChunkedTracker, ParameterError, TrapParams, synthetic_graphs, track
from trap_core.synthetic import SceneConfig


class _Stub:
    """Stands in for a chunk's tracking result: tracks given per chunk (local frames)."""

    def __init__(self, tracks: list[Track]) -> None:
        self.tracks = tracks
        self.seconds = {"mining": 0.0}
        self.mining = type("Mined", (), {"n_patterns": 1, "n_st": 1})()
        self.hierarchy = type("Cut", (), {"cut_level": 1})()


def _line(track_id: int, first: int, last: int, x0: float, y: float) -> Track:
    """A 40x30 box moving 2 px a frame from ``x0`` (at global frame 0) over global frames first..last."""
    frames = np.arange(first, last + 1)
    boxes = np.column_stack([x0 + 2.0 * frames, np.full(frames.size, y), np.full(frames.size, 40.0),
                             np.full(frames.size, 30.0)])
    return Track(track_id, frames, boxes, np.ones(frames.size), track_id)


def test_ids_continue_across_chunks_and_boxes_are_final_while_reading(monkeypatch: pytest.MonkeyPatch) -> None:
    """chunk 100, tau 10: chunks [0, 140), [100, 240), [200, 260); the object on y=50 is tracked
    by every chunk, the one on y=300 by the first only, a new one appears in the last chunk."""
    per_chunk = {0: [_line(1, 0, 139, 0, 50), _line(2, 0, 139, 0, 300)],
                 100: [_line(1, 100, 239, 0, 50)],
                 200: [_line(1, 200, 259, 0, 300), _line(2, 200, 259, 0, 50)]}

    def fake_track(graphs, params, fps, miner):
        first = sorted(k for k in per_chunk if k not in seen)[0]
        seen.add(first)
        return _Stub([Track(t.track_id, t.frames - first, t.boxes, t.score, t.cluster) for t in per_chunk[first]])

    seen: set[int] = set()
    monkeypatch.setattr(chunks, "track", fake_track)
    monkeypatch.setattr(chunks, "PatternMiner", lambda params, n_frames: type("M", (), {"add": lambda s, g: None})())
    tracker = ChunkedTracker(TrapParams(chunk=100, tau=10))
    final = []
    for frame in range(260):
        tracker.add(object(), frame)
        final.append(tracker.final_frames)
    assert final[138] == 0 and final[139] == 120 and final[239] == 220  # middle of each overlap
    first_pieces = tracker.take_final()
    assert {t.track_id for t in first_pieces} == {1, 2} and all(t.frames.max() < 220 for t in first_pieces)
    run = tracker.finish()
    assert len(run.chunks) == 3
    by_id = {t.track_id: t for t in run.tracks}
    assert sorted(by_id) == [1, 2, 3]
    np.testing.assert_array_equal(by_id[1].frames, np.arange(260))  # y=50 all along, one id
    assert by_id[1].boxes[:, 1].tolist() == [50.0] * 260
    np.testing.assert_array_equal(by_id[2].frames, np.arange(120))  # y=300 until the first chunk hands over
    np.testing.assert_array_equal(by_id[3].frames, np.arange(220, 260))  # y=300 again: no shared frames, new id


def test_one_chunk_is_the_whole_video_and_chunks_keep_the_objects() -> None:
    params = TrapParams(segmentation="colour", chunk=0)
    graphs, truth = synthetic_graphs(SceneConfig(width=320, height=240, frames=300, seed=2, exits=False), params)
    whole = track(graphs, params, 25.0)
    tracker = ChunkedTracker(params, len(graphs))
    for index, graph in enumerate(graphs):
        tracker.add(graph, index * 40_000_000)
    run = tracker.finish()
    assert len(run.chunks) == 1 and len(run.tracks) == len(whole.tracks)
    for a, b in zip(run.tracks, whole.tracks):
        np.testing.assert_array_equal(a.frames, b.frames)
        np.testing.assert_allclose(a.boxes, b.boxes)
    chunked = ChunkedTracker(TrapParams(segmentation="colour", chunk=150), len(graphs))
    for index, graph in enumerate(graphs):
        chunked.add(graph, index * 40_000_000)
    run = chunked.finish()
    assert len(run.chunks) == 2
    assert len(run.tracks) == len(truth)  # every object keeps one id across the chunk border
    for t in run.tracks:
        assert np.all(np.diff(t.frames) > 0)


def test_chunk_shorter_than_the_overlap_is_refused() -> None:
    with pytest.raises(ParameterError, match="chunk"):
        TrapParams(chunk=50, tau=25)


@pytest.mark.parametrize("n_frames", [2, 99, 139, 140, 141, 221, 239, 240, 241])
def test_every_frame_is_final_once_whatever_the_length(monkeypatch: pytest.MonkeyPatch, n_frames: int) -> None:
    """One object standing in every frame of every chunk (chunk 100, overlap 40): one id, each frame once."""
    def fake_track(graphs, params, fps, miner):
        frames = np.arange(len(graphs))
        return _Stub([Track(1, frames, np.tile([10.0, 50.0, 40.0, 30.0], (frames.size, 1)), np.ones(frames.size), 1)])

    monkeypatch.setattr(chunks, "track", fake_track)
    monkeypatch.setattr(chunks, "PatternMiner", lambda params, n_frames: type("M", (), {"add": lambda s, g: None})())
    tracker = ChunkedTracker(TrapParams(chunk=100, tau=10), n_frames)
    for frame in range(n_frames):
        tracker.add(object(), frame)
    run = tracker.finish()
    assert tracker.final_frames == n_frames and len(run.tracks) == 1
    np.testing.assert_array_equal(run.tracks[0].frames, np.arange(n_frames))
