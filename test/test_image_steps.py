"""The camera's motion read from the images (trap_core.robust.image_steps) and its use by the tracker."""
from __future__ import annotations

import cv2
import numpy as np
import skimage.data

from trap_core.clustering import ObservedPaths
from trap_core.rag import graph_from_bytes, graph_to_bytes
from trap_core.robust import camera_transforms
from trap_core.robust.image_steps import image_step


def _similarity(angle_deg: float, scale: float, shift: tuple[float, float], centre: tuple[float, float]) -> np.ndarray:
    """(2, 3) turn by ``angle_deg`` and zoom by ``scale`` about ``centre``, then ``shift``."""
    matrix = cv2.getRotationMatrix2D(centre, angle_deg, scale)
    matrix[:, 2] += shift
    return matrix


def _grid_error(read: np.ndarray, truth: np.ndarray, width: int, height: int) -> float:
    """Largest distance (px) between where ``read`` and ``truth`` put points spread over the frame."""
    ys, xs = np.mgrid[0:height:20, 0:width:20]
    points = np.column_stack([xs.ravel(), ys.ravel(), np.ones(xs.size)])
    return float(np.linalg.norm(points @ read.T - points @ truth.T, axis=1).max())


def test_a_turn_a_zoom_and_a_shift_are_read_to_a_tenth_of_a_pixel() -> None:
    scene = skimage.data.astronaut()
    previous = scene[:360, :480].copy()
    height, width = previous.shape[:2]
    truth = _similarity(1.5, 1.02, (3.3, -2.2), (width / 2, height / 2))
    current = cv2.warpAffine(previous, truth, (width, height), flags=cv2.INTER_LINEAR,
                             borderMode=cv2.BORDER_REFLECT)
    read = image_step(previous, current)
    assert _grid_error(read, truth, width, height) < 0.1


def test_over_a_smooth_background_the_step_is_the_backgrounds_not_the_objects() -> None:
    """A colour wheel pans 2 px right and 1 down while three sharp-edged objects, which hold every
    corner of the frame, move 5 px left: the step read is the wheel's."""
    wheel = skimage.data.colorwheel()
    world = cv2.resize(wheel, (800, 600), interpolation=cv2.INTER_LINEAR)
    frames = []
    for t in range(2):
        view = world[100 + t:100 + t + 240, 150 + 2 * t:150 + 2 * t + 320].copy()
        for k, (x, y) in enumerate([(60, 50), (180, 120), (100, 170)]):
            x0 = x - 5 * t
            view[y:y + 40, x0:x0 + 24] = (30 + 60 * k, 200, 90)
            view[y + 10:y + 25, x0 + 6:x0 + 18] = (220, 40, 160)
        frames.append(view)
    truth = np.array([[1.0, 0.0, -2.0], [0.0, 1.0, -1.0]])  # a scene point moves opposite to the camera
    assert _grid_error(image_step(*frames), truth, 320, 240) < 0.1


def test_a_step_is_unknown_where_the_images_show_nothing_to_read() -> None:
    flat = np.full((120, 160, 3), 128, dtype=np.uint8)
    assert np.isnan(image_step(flat, flat)).all()
    textured = skimage.data.astronaut()[:120, :160].copy()
    assert np.isnan(image_step(textured, textured[:100])).all()  # frames of two sizes
    assert np.isnan(image_step(textured[:10, :10], textured[:10, :10])).all()  # under a window


def test_camera_transforms_take_the_image_steps_where_read_and_fit_the_paths_elsewhere() -> None:
    """The paths say the camera pans 3 px a frame; the images say 1 px in frames 1-3 and nothing
    (NaN) in frames 4-5."""
    n_frames = 6
    rng = np.random.default_rng(4)
    world = rng.uniform(0, 300, size=(30, 2))
    rows = [(s, t, world[s] + [3.0 * t, 0.0]) for s in range(len(world)) for t in range(n_frames)]
    paths = ObservedPaths(np.array([r[0] for r in rows]), np.array([r[1] for r in rows]),
                          np.array([r[2] for r in rows]))
    steps = np.full((n_frames, 2, 3), np.nan)
    steps[1:4] = [[1.0, 0.0, 1.0], [0.0, 1.0, 0.0]]
    transforms = camera_transforms(paths, n_frames, steps)
    np.testing.assert_allclose(transforms[:, 0, 2], [0, 1, 2, 3, 6, 9], atol=1e-3)
    np.testing.assert_allclose(camera_transforms(paths, n_frames)[:, 0, 2], 3.0 * np.arange(n_frames), atol=1e-3)


def test_the_camera_step_travels_with_the_graph() -> None:
    from trap_core.pipeline import TrapParams, frame_graph
    scene = skimage.data.astronaut()
    previous, current = scene[:120, :160].copy(), scene[2:122, 3:163].copy()
    params = TrapParams(segmentation="felzenszwalb")
    graph = frame_graph(current, params, previous)
    np.testing.assert_allclose(graph.camera_step, [[1, 0, -3], [0, 1, -2]], atol=0.1)
    np.testing.assert_array_equal(graph_from_bytes(graph_to_bytes(graph)).camera_step, graph.camera_step)
    first = frame_graph(previous, params)
    assert not first.has_camera_step and not graph_from_bytes(graph_to_bytes(first)).has_camera_step


def test_the_graph_stage_reads_the_steps_only_where_tracking_does() -> None:
    """The paper's method, and the robust one told not to (``image_motion`` false), never look at
    the camera's steps: their graphs are made without reading them (2.5 ms a frame), unless
    asked for (the evaluation's ablation takes both methods from one set of graphs)."""
    from trap_core.pipeline import TrapParams, graphs_of
    scene = skimage.data.astronaut()
    frames = [scene[2 * t:120 + 2 * t, 3 * t:160 + 3 * t].copy() for t in range(4)]

    def read(params: TrapParams, **asked: bool) -> list[bool]:
        return [graph.has_camera_step for graph in graphs_of(frames, params, **asked)]
    assert read(TrapParams()) == [False, True, True, True]
    assert read(TrapParams(method="paper")) == read(TrapParams(image_motion=False)) == [False] * 4
    assert read(TrapParams(method="paper"), image_steps=True) == [False, True, True, True]


def test_objects_over_a_smooth_background_are_tracked_with_the_camera_read_from_the_images() -> None:
    """Two people over a colour wheel (320x240, 150 frames): the wheel gives no frequent pattern and
    few regions, so the camera's motion read from patterns and regions follows the people (over a
    px a frame off the true pan, median over 8 frames) and one of them stands still in the world
    and is lost. Read from the images it is the pan, and both are tracked."""
    from trap_core.clustering import observed_paths
    from trap_core.evaluation import boxes_by_frame, match_objects
    from trap_core.pipeline import PatternMiner, TrapParams, synthetic_graphs, track
    from trap_core.rag import StackedGraphs
    from trap_core.robust import camera_paths, without_backdrop
    from trap_core.synthetic import SceneConfig
    from trap_core.synthetic.scene import build_world
    config = SceneConfig(width=320, height=240, frames=150, seed=3, background="colorwheel", objects=2, shape="person")
    params = TrapParams()
    graphs, truth = synthetic_graphs(config, params)
    assert all(graph.has_camera_step for graph in graphs[1:])
    miner = PatternMiner(params, len(graphs))
    for graph in graphs:
        miner.add(graph)
    mined = miner.finish()
    stacked = StackedGraphs.of(graphs)
    paths = camera_paths(stacked, observed_paths(without_backdrop(mined, stacked)), params.eps)
    pan = build_world(config).camera.astype(float)

    def errors(transforms: np.ndarray) -> np.ndarray:
        shift = -transforms[:, :2, 2]
        return np.abs((shift[8:] - shift[:-8]) - (pan[8:] - pan[:-8])).max(axis=1) / 8
    assert np.median(errors(camera_transforms(paths, len(graphs)))) > 1.0
    assert errors(camera_transforms(paths, len(graphs), np.stack([g.camera_step for g in graphs]))).max() < 0.05
    objects = match_objects([boxes_by_frame(t) for t in track(graphs, params).tracks], truth)
    assert [(p >= 0.9, r >= 0.9) for _, p, r in objects] == [(True, True)] * 2


def test_cached_graphs_are_keyed_by_the_code_that_reads_the_steps(monkeypatch) -> None:
    """The quality benchmark caches graphs with their camera steps: a constant of the step reader,
    or of the fit it calls, changes the key; one it does not use leaves it."""
    import importlib.util
    from pathlib import Path

    import trap_core.robust.camera as camera
    import trap_core.robust.image_steps as image_steps
    path = Path(__file__).resolve().parents[1] / "benchmarks" / "quality.py"
    spec = importlib.util.spec_from_file_location("quality_benchmark", path)
    quality = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(quality)
    before = quality._code_digest(image_step)
    assert before == quality.IMAGE_STEP_CODE
    monkeypatch.setattr(camera, "HOP_SHARE", 0.9)  # the tracker's, named by nothing the reader calls
    assert quality._code_digest(image_step) == before
    monkeypatch.setattr(image_steps, "FLOW_WINDOW", image_steps.FLOW_WINDOW + 2)
    assert quality._code_digest(image_step) != before
    monkeypatch.undo()
    monkeypatch.setattr(camera, "AGREE_PX", camera.AGREE_PX * 2)  # the fit's, which the reader calls
    assert quality._code_digest(image_step) != before
