"""Tracks followed past their ends by their object's regions (trap_core.robust.follow)."""
from __future__ import annotations

import dataclasses
from collections.abc import Container

import numpy as np

from trap_core.clustering import Track
from trap_core.pipeline import TrapParams, frame_graph
from trap_core.rag import StackedGraphs
from trap_core.robust import follow_ends

SIZE = (200, 120)  # frame width, height


def _frames(objects: list[tuple[tuple[int, int, int], list[tuple[int, int] | None]]], n: int) -> StackedGraphs:
    """The stacked graphs of ``n`` frames over a grey ground with a white mark, each object
    (colour, its corner per frame or None where it is not drawn) a 24x16 block whose right third
    is red."""
    params = TrapParams(segmentation="colour")
    graphs = []
    for t in range(n):
        rgb = np.full((SIZE[1], SIZE[0], 3), 40, np.uint8)
        rgb[95:105, 150:160] = 255
        for colour, corners in objects:
            if corners[t] is not None:
                x, y = corners[t]
                rgb[y:y + 16, x:x + 16] = colour
                rgb[y:y + 16, x + 16:x + 24] = (200, 0, 0)
        graphs.append(frame_graph(rgb, params))
    return StackedGraphs.of(graphs)


def _track(track_id: int, corners: list[tuple[int, int] | None], frames: range) -> Track:
    """A track whose boxes lie on the object drawn at ``corners``, in ``frames`` only."""
    boxes = np.array([[*corners[t], 24, 16] for t in frames], dtype=float)
    return Track(track_id, np.array(frames), boxes, np.ones(len(frames)), track_id)


def _moving(n: int, x0: int, y: int, step: int, seen: Container[int] | None = None) -> list[tuple[int, int] | None]:
    """An object's corner in each of ``n`` frames, moving right ``step`` px a frame along row
    ``y`` (None outside the frames it is ``seen`` in)."""
    return [(x0 + step * t, y) if seen is None or t in seen else None for t in range(n)]


def test_a_track_is_followed_over_the_frames_its_object_is_seen_before_and_after_it() -> None:
    path = _moving(30, 30, 50, 3)
    regions = _frames([((0, 200, 0), path)], 30)
    followed = follow_ends([_track(1, path, range(10, 20))], regions, *SIZE, span=6)[0]
    np.testing.assert_array_equal(followed.frames, np.arange(30))
    np.testing.assert_allclose(followed.boxes, _track(1, path, range(30)).boxes, atol=0.5)
    np.testing.assert_array_equal(followed.score[:10], 0.5)  # inferred, not seen


def test_following_stops_where_the_object_is_not_seen() -> None:
    path = _moving(30, 30, 50, 3, seen=range(5, 25))
    regions = _frames([((0, 200, 0), path)], 30)
    followed = follow_ends([_track(1, path, range(10, 20))], regions, *SIZE, span=6)[0]
    np.testing.assert_array_equal(followed.frames, np.arange(5, 25))


def test_following_stops_before_the_border_and_where_another_track_is() -> None:
    leaving = _moving(30, 110, 20, 3)  # its box within a quarter of its width (6 px) of the right border from frame 21
    twice = _moving(30, 40, 70, 3)  # held by two tracks: frames 0-7 and 15-24
    regions = _frames([((0, 200, 0), leaving), ((0, 0, 200), twice)], 30)
    tracks = [_track(1, leaving, range(5, 15)), _track(2, twice, range(15, 25)), _track(3, twice, range(0, 8))]
    out = follow_ends(tracks, regions, *SIZE, span=6)
    np.testing.assert_array_equal(out[0].frames, np.arange(21))
    np.testing.assert_array_equal(out[1].frames, np.arange(8, 30))  # up to the other track's first box
    np.testing.assert_array_equal(out[2].frames, np.arange(8))  # the first one took the object on from there


def test_a_box_that_holds_no_regions_of_its_own_is_not_followed() -> None:
    path = _moving(30, 30, 50, 3)
    regions = _frames([((0, 200, 0), path)], 30)
    # a box on the ground around the white mark: a tenth of it is regions of its own
    on_ground = Track(1, np.arange(10, 20), np.tile([[138.0, 80.0, 32.0, 30.0]], (10, 1)), np.ones(10), 1)
    assert follow_ends([on_ground], regions, *SIZE, span=6)[0] is on_ground


def test_a_gap_is_followed_into_from_both_sides_where_the_object_is_seen() -> None:
    path = _moving(40, 20, 50, 3, seen=set(range(40)) - set(range(18, 22)))  # hidden over frames 18-21
    regions = _frames([((0, 200, 0), path)], 40)
    held = [*range(0, 10), *range(30, 40)]
    gappy = Track(1, np.array(held), np.array([[*path[t], 24, 16] for t in held], float), np.ones(20), 1)
    followed = follow_ends([gappy], regions, *SIZE, span=6)[0]
    np.testing.assert_array_equal(followed.frames, [t for t in range(40) if not 18 <= t <= 21])
    seen = [t for t in range(40) if path[t] is not None]
    np.testing.assert_allclose(followed.boxes, [[*path[t], 24, 16] for t in seen], atol=0.5)


def test_a_box_off_the_track_s_usual_size_is_not_followed() -> None:
    """A first box 1.5 times the usual size holds the object and something else: only the last,
    of the usual size, is followed."""
    path = _moving(30, 30, 50, 3)
    regions = _frames([((0, 200, 0), path)], 30)
    held = _track(1, path, range(10, 20))
    boxes = held.boxes.copy()
    boxes[0] = [path[10][0] - 6, 46, 36, 24]
    followed = follow_ends([dataclasses.replace(held, boxes=boxes)], regions, *SIZE, span=6)[0]
    np.testing.assert_array_equal(followed.frames, np.arange(10, 30))
