"""Tracks' colours, and look-alikes told by them (trap_core.robust.appearance, lookalike_tracks)."""
from __future__ import annotations

import numpy as np

from trap_core.clustering import Track
from trap_core.rag import build_plane_graph
from trap_core.robust import colour_overlap, colour_shares, lookalike_tracks
from trap_core.segmentation import colour_components

RED, BLUE, GREY, WHITE = (220, 30, 30), (30, 30, 220), (128, 128, 128), (240, 240, 240)


def _frames(colours: list[tuple], n_frames: int = 10) -> tuple[list, list[np.ndarray]]:
    """Graphs of frames with one 20x20 square per colour (a white dot in its middle) moving right
    over grey, and each square's boxes."""
    graphs, boxes = [], [np.zeros((n_frames, 4)) for _ in colours]
    for frame in range(n_frames):
        rgb = np.full((120, 200, 3), GREY, dtype=np.uint8)
        for k, colour in enumerate(colours):
            x, y = 10 + 3 * frame + 50 * k, 20 + 40 * (k % 2)
            rgb[y:y + 20, x:x + 20] = colour
            rgb[y + 8:y + 12, x + 8:x + 12] = WHITE
            boxes[k][frame] = (x, y, 19, 19)
        labels, n = colour_components(rgb)
        graphs.append(build_plane_graph(labels, n, rgb))
    return graphs, boxes


def _track(track_id: int, boxes: np.ndarray) -> Track:
    frames = np.arange(len(boxes))
    return Track(track_id, frames, boxes, np.ones(len(boxes)), track_id)


def test_colour_overlap_tells_objects_of_other_colours() -> None:
    graphs, boxes = _frames([RED, BLUE, RED])
    tracks = [_track(k, b) for k, b in enumerate(boxes)]
    overlap = colour_overlap(colour_shares(tracks, graphs))
    assert overlap[0, 2] > 0.99                   # two red squares with white dots
    assert overlap[0, 1] < 0.3                    # red and blue share only the dot
    np.testing.assert_allclose(np.diag(overlap), 1.0)
    grown = [_track(0, boxes[0] + [-5, -5, 10, 10])]  # the grey around a box is not the object's
    np.testing.assert_allclose(colour_shares(grown, graphs), colour_shares(tracks[:1], graphs))


def test_tracks_of_one_size_are_lookalikes_only_in_the_same_colours() -> None:
    # Two tracks whose clusters share no structure (plane patterns 0 and 1) and whose boxes are of
    # one size: look-alikes by size, unless their colours differ.
    boxes = np.tile([0.0, 0.0, 40.0, 30.0], (10, 1))
    tracks = [_track(0, boxes), _track(1, boxes + [100, 0, 0, 0])]
    labels, st_pattern, weights = np.array([0, 1]), np.array([0, 1]), np.ones(2)
    assert lookalike_tracks(tracks, labels, st_pattern, weights)[0, 1]
    same = np.array([[1.0, 0.95], [0.95, 1.0]])
    assert lookalike_tracks(tracks, labels, st_pattern, weights, colours=same)[0, 1]
    other = np.array([[1.0, 0.2], [0.2, 1.0]])
    assert not lookalike_tracks(tracks, labels, st_pattern, weights, colours=other)[0, 1]
    shared = np.array([0, 0])                     # the same structure: look-alikes whatever the colours
    assert lookalike_tracks(tracks, labels, shared, weights, colours=other)[0, 1]
