"""Long streams tracked chunk by chunk: ids continue across chunks, boxes final while reading."""
from __future__ import annotations

import numpy as np
import pytest

import trap_core.pipeline.chunks as chunks
from trap_core.clustering import Track
from trap_core.evaluation import boxes_by_frame, match_objects
from trap_core.pipeline import ChunkedTracker, ParameterError, TrapParams, synthetic_graphs, track
from trap_core.synthetic import SceneConfig


_FRAME = type("Graph", (), {"frame_size": (640.0, 480.0)})()  # a 640x480 frame's graph, to the tracker


class _Stub:
    """Stands in for a chunk's tracking result: tracks given per chunk (local frames); each
    track's cluster is made of ``structures[cluster]`` (plane pattern hashes, 10 occurrences each)."""

    def __init__(self, tracks: list[Track], structures: dict[int, list[int]] | None = None) -> None:
        self.tracks = tracks
        self.seconds = {"mining": 0.0}
        structures = structures or {t.cluster: [t.cluster] for t in tracks}
        pairs = [(cluster, key) for cluster, keys in structures.items() for key in keys]
        hashes = np.array(sorted({key for _, key in pairs}), dtype=np.int64)
        self.labels = np.array([cluster for cluster, _ in pairs])
        self.mining = type("Mined", (), {"n_patterns": hashes.size, "n_st": len(pairs), "pattern_hash": hashes,
                                         "st_pattern": np.searchsorted(hashes, [key for _, key in pairs]),
                                         "st_offsets": np.arange(len(pairs) + 1) * 10,
                                         "st_occurrences": np.full(len(pairs), 10)})()
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

    def fake_track(graphs, params, miner):
        first = sorted(k for k in per_chunk if k not in seen)[0]
        seen.add(first)
        return _Stub([Track(t.track_id, t.frames - first, t.boxes, t.score, t.cluster) for t in per_chunk[first]])

    seen: set[int] = set()
    monkeypatch.setattr(chunks, "track", fake_track)
    monkeypatch.setattr(chunks, "PatternMiner", lambda params, n_frames: type("M", (), {"add": lambda s, g: None})())
    tracker = ChunkedTracker(TrapParams(chunk=100, tau=10))
    final = []
    for _ in range(260):
        tracker.add(_FRAME)
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
    """Chunks of 150 frames, so the second chunk is tracked on its own from frame 150. The
    scene's objects are told apart within either chunk alone (with seed 2, two look-alikes
    travel side by side through the second chunk's first 80 frames: that chunk alone takes them
    for one object, whatever the stitching does)."""
    params = TrapParams(segmentation="colour", chunk=0)
    graphs, truth = synthetic_graphs(SceneConfig(width=320, height=240, frames=300, seed=5, exits=False), params)
    whole = track(graphs, params)
    tracker = ChunkedTracker(params, len(graphs))
    for graph in graphs:
        tracker.add(graph)
    run = tracker.finish()
    assert len(run.chunks) == 1 and len(run.tracks) == len(whole.tracks)
    for a, b in zip(run.tracks, whole.tracks):
        np.testing.assert_array_equal(a.frames, b.frames)
        np.testing.assert_allclose(a.boxes, b.boxes)
    chunked = ChunkedTracker(TrapParams(segmentation="colour", chunk=150), len(graphs))
    for graph in graphs:
        chunked.add(graph)
    run = chunked.finish()
    assert len(run.chunks) == 2
    assert len(run.tracks) == len(truth)  # every object keeps one id across the chunk border...
    boxes = [boxes_by_frame(t) for t in run.tracks]
    assert all(recall >= 0.9 for _, _, recall in match_objects(boxes, truth))  # ...and is followed in both chunks
    for t in run.tracks:
        assert np.all(np.diff(t.frames) > 0)


def test_chunk_shorter_than_the_overlap_is_refused() -> None:
    with pytest.raises(ParameterError, match="chunk"):
        TrapParams(chunk=50, tau=25)


@pytest.mark.parametrize("n_frames", [2, 99, 139, 140, 141, 221, 239, 240, 241])
def test_every_frame_is_final_once_whatever_the_length(monkeypatch: pytest.MonkeyPatch, n_frames: int) -> None:
    """One object standing in every frame of every chunk (chunk 100, overlap 40): one id, each frame once."""
    def fake_track(graphs, params, miner):
        frames = np.arange(len(graphs))
        return _Stub([Track(1, frames, np.tile([10.0, 50.0, 40.0, 30.0], (frames.size, 1)), np.ones(frames.size), 1)])

    monkeypatch.setattr(chunks, "track", fake_track)
    monkeypatch.setattr(chunks, "PatternMiner", lambda params, n_frames: type("M", (), {"add": lambda s, g: None})())
    tracker = ChunkedTracker(TrapParams(chunk=100, tau=10), n_frames)
    for _ in range(n_frames):
        tracker.add(_FRAME)
    run = tracker.finish()
    assert tracker.final_frames == n_frames and len(run.tracks) == 1
    np.testing.assert_array_equal(run.tracks[0].frames, np.arange(n_frames))


def _boxes(track_id: int, cluster: int, frames: np.ndarray, x: np.ndarray, y: float) -> Track:
    return Track(track_id, frames, np.column_stack([x, np.full(frames.size, y), np.full(frames.size, 40.0),
                                                    np.full(frames.size, 30.0)]), np.ones(frames.size), cluster)


def test_an_object_away_across_a_chunk_border_comes_back_with_its_id(monkeypatch: pytest.MonkeyPatch) -> None:
    """chunk 100, tau 10 (chunks [0, 140) and [100, 240)): A leaves at the right border at frame 90
    and B, made of A's structures, enters there at 170; D vanishes inside the view, E appears
    inside it with D's structures; C enters with other structures: a new object."""
    early, late = np.arange(0, 91), np.arange(170, 240)
    per_chunk = {
        0: ([_boxes(1, 1, early, 510.0 + early, 50), _boxes(2, 2, np.arange(61), np.full(61, 300.0), 300)],
            {1: [11, 12, 13], 2: [15, 16]}),
        100: ([_boxes(1, 7, late, 600.0 - (late - 170), 50), _boxes(2, 8, np.arange(180, 240), np.full(60, 600.0), 400),
               _boxes(3, 9, np.arange(200, 240), np.full(40, 300.0), 300)],
              {7: [11, 12, 13, 14], 8: [19], 9: [15, 16]}),
    }
    seen: list[int] = []

    def fake_track(graphs, params, miner):
        first = 0 if not seen else 100
        seen.append(first)
        tracks, structures = per_chunk[first]
        return _Stub([Track(t.track_id, t.frames - first, t.boxes, t.score, t.cluster) for t in tracks], structures)

    monkeypatch.setattr(chunks, "track", fake_track)
    monkeypatch.setattr(chunks, "PatternMiner", lambda params, n_frames: type("M", (), {"add": lambda s, g: None})())
    tracker = ChunkedTracker(TrapParams(chunk=100, tau=10))
    for _ in range(240):
        tracker.add(_FRAME)
    run = tracker.finish()
    frames = {t.track_id: t.frames.tolist() for t in run.tracks}
    assert sorted(frames) == [1, 2, 3]
    assert frames[1] == list(range(0, 91)) + list(range(170, 240))   # A, then B
    assert frames[2] == list(range(0, 61)) + list(range(200, 240))   # D, then E
    assert frames[3] == list(range(180, 240))                         # C: new


def test_timeline_bars_are_the_runs_of_frames(tmp_path) -> None:
    from trap_core.outputs import track_timeline
    from trap_core.outputs.timeline import frame_runs
    assert frame_runs(np.array([3, 4, 5, 9, 11, 12])) == [(3, 3), (9, 1), (11, 2)] and frame_runs(np.array([])) == []
    track = _line(1, 0, 99, 0, 50)
    track = Track(1, track.frames, track.boxes, track.score, 1, np.where(np.arange(100)[:, None] < 50, 1.0, np.nan)
                  * np.ones((100, 2)))
    path = track_timeline([track], 300, tmp_path / "timeline.png", chunk_starts=[0, 150])
    import cv2
    image = cv2.imread(str(path))
    assert image is not None and image.shape[1] == 1000
