"""Synthetic benchmark videos: ground truth matches the pixels, the scene has the promised events."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from trap_core.bagio import open_image_stream
from trap_core.motformat import read_mot
from trap_core.pipeline import synthetic_frames
from trap_core.synthetic import SceneConfig, build_world, render, write_synthetic
from trap_core.synthetic.cli import build_parser


def _colour_mask(rgb: np.ndarray, colours: np.ndarray) -> np.ndarray:
    mask = np.zeros(rgb.shape[:2], dtype=bool)
    for colour in colours:
        mask |= np.all(rgb == colour, axis=-1)
    return mask


def _colour_box(rgb: np.ndarray, colours: np.ndarray) -> tuple[int, int, int, int] | None:
    mask = _colour_mask(rgb, colours)
    if not mask.any():
        return None
    rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
    return int(cols[0]), int(rows[0]), int(cols[-1] - cols[0] + 1), int(rows[-1] - rows[0] + 1)


def test_ground_truth_is_the_box_and_the_mask_of_visible_pixels() -> None:
    cfg = SceneConfig(width=320, height=240, frames=300, seed=5)
    colours = build_world(cfg).object_colours
    checked = 0
    for frame in render(cfg):
        assert frame.owner.shape == frame.rgb.shape[:2]
        for obj, box in enumerate(frame.boxes):
            assert box == _colour_box(frame.rgb, colours[obj]), f"frame {frame.index} object {obj}"
            assert np.array_equal(frame.owner == obj, _colour_mask(frame.rgb, colours[obj])), f"frame {frame.index}"
            checked += box is not None
    assert checked > 600


@pytest.mark.parametrize("shape", ["person", "disc", "mixed"])
def test_shapes_ground_truth_and_proportions(shape: str) -> None:
    cfg = SceneConfig(width=320, height=240, frames=60, seed=5, shape=shape, objects=3, exits=False)
    colours = build_world(cfg).object_colours
    sizes = {obj: [] for obj in range(cfg.objects)}
    for frame in render(cfg):
        for obj, box in enumerate(frame.boxes):
            assert box == _colour_box(frame.rgb, colours[obj]), f"frame {frame.index} object {obj}"
            sizes[obj].append(box[2:])
    aspect = {obj: float(np.median([h / w for w, h in boxes])) for obj, boxes in sizes.items()}
    expected = {"person": 2.3, "disc": 1.0, "car": 0.67}  # height over width of the visible pixels
    for obj in range(cfg.objects):
        assert aspect[obj] == pytest.approx(expected[cfg.shape_of(obj)], rel=0.25), (obj, aspect)
    if shape == "mixed":
        assert [cfg.shape_of(obj) for obj in range(3)] == ["car", "person", "disc"]


def test_unknown_shape_is_refused() -> None:
    with pytest.raises(ValueError, match="shape"):
        SceneConfig(shape="triangle")
    with pytest.raises(SystemExit):
        build_parser().parse_args(["clip", "--shape", "triangle"])
    assert build_parser().parse_args(["clip", "--shape", "mixed"]).shape == "mixed"


def test_same_seed_same_video_other_seed_other_video() -> None:
    cfg = SceneConfig(width=160, height=120, frames=5, seed=11)
    first = [f.rgb for f in render(cfg)]
    again = [f.rgb for f in render(cfg)]
    other = [f.rgb for f in render(SceneConfig(width=160, height=120, frames=5, seed=12))]
    assert all(np.array_equal(a, b) for a, b in zip(first, again))
    assert not np.array_equal(first[0], other[0])


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_anim_events_exits_crossings_camera_motion(seed: int) -> None:
    cfg = SceneConfig(width=320, height=240, frames=721, seed=seed)
    frames = list(render(cfg))
    last = np.array([f.boxes[-1] is None for f in frames])
    # Runs of absence of the last object: several, each 3-4 s (75-100 frames at 25 Hz) or more.
    edges = np.flatnonzero(np.diff(np.r_[0, last.astype(int), 0]))
    starts, ends = edges[::2], edges[1::2]
    complete = (ends - starts)[ends < len(frames)]
    assert len(complete) >= 2 and all(75 <= run <= 130 for run in complete), complete
    # The others stay in view and at some point overlap another object (crossing / occlusion).
    assert all(f.boxes[0] is not None and f.boxes[1] is not None for f in frames)
    def overlap(a, b):
        return a and b and a[0] < b[0] + b[2] and b[0] < a[0] + a[2] and a[1] < b[1] + b[3] and b[1] < a[1] + a[3]
    crossings = sum(any(overlap(f.boxes[i], f.boxes[j]) for i in range(3) for j in range(i + 1, 3)) for f in frames)
    assert crossings > 0
    camera = build_world(cfg).camera
    assert np.ptp(camera[:, 0]) > 20 and np.ptp(camera[:, 1]) > 20


def test_background_statistics_match_the_papers_anim_videos() -> None:
    from scipy import ndimage
    frame = next(iter(render(SceneConfig(seed=2, frames=1))))
    code = frame.rgb.astype(np.int64) @ np.array([65536, 256, 1])
    labels = np.zeros(code.shape, dtype=np.int64)
    count = 0
    for value in np.unique(code):
        components, k = ndimage.label(code == value)
        labels[components > 0] = components[components > 0] + count
        count += k
    pairs = np.concatenate([np.stack([labels[:, 1:].ravel(), labels[:, :-1].ravel()], 1),
                            np.stack([labels[1:].ravel(), labels[:-1].ravel()], 1)])
    pairs = np.unique(np.sort(pairs[pairs[:, 0] != pairs[:, 1]], axis=1), axis=0)
    assert 200 <= count <= 290
    assert 3.5 <= 2 * len(pairs) / count <= 4.4


def test_anim1_objects_are_identical_anim2_differ() -> None:
    anim1 = build_world(SceneConfig(width=160, height=120, frames=2, identical=True)).object_colours
    anim2 = build_world(SceneConfig(width=160, height=120, frames=2, identical=False)).object_colours
    assert (anim1 == anim1[0]).all()
    assert len({tuple(c) for obj in anim2 for c in obj}) == anim2.shape[0] * anim2.shape[1]


def test_written_bag_and_ground_truth_agree(tmp_path: Path) -> None:
    cfg = SceneConfig(width=160, height=120, frames=30, seed=4, noise=3.0, illumination=0.2)
    bag, gt = write_synthetic(cfg, tmp_path / "noisy", compressed="jpeg")
    rows = read_mot(gt)
    assert gt.name == "noisy.gt.txt"
    expected = [(f.index + 1, obj + 1, *box) for f in render(cfg) for obj, box in enumerate(f.boxes) if box]
    np.testing.assert_array_equal(rows[:, :6], np.array(expected, dtype=float))
    clean = next(iter(render(SceneConfig(width=160, height=120, frames=1, seed=4))))
    with open_image_stream(bag) as stream:
        assert stream.count == 30
        first = next(iter(stream)).rgb
    assert first.shape == (120, 160, 3)
    assert 1.0 < np.abs(first.astype(int) - clean.rgb).mean() < 30  # noise and jpeg, same scene


@pytest.mark.parametrize("delivery", [{"encoding": "yuv422"}, {"encoding": "bayer_rggb8"}, {"encoding": "bgra8"},
                                      {"compressed": "jpeg"}])
def test_frames_made_in_memory_are_those_a_bag_of_the_encoding_brings(tmp_path: Path, delivery: dict) -> None:
    """The quality benchmark tracks frames encoded and decoded in memory, not read from a bag:
    they must be the very pixels a bag written in that encoding gives back (a Bayer pattern's
    demosaicing, yuv422's shared colour of two columns, JPEG's losses)."""
    cfg = SceneConfig(width=160, height=120, frames=5, seed=8, noise=1.0, shape="person")
    bag, _ = write_synthetic(cfg, tmp_path / "bag", **delivery)
    with open_image_stream(bag) as stream:
        from_bag = [frame.rgb for frame in stream]
    in_memory = list(synthetic_frames(cfg, **delivery))
    assert len(in_memory) == len(from_bag) == 5
    for mine, theirs in zip(in_memory, from_bag):
        np.testing.assert_array_equal(mine, theirs)
    rendered = next(iter(render(cfg))).rgb
    lossless = delivery.get("encoding") == "bgra8"
    assert np.array_equal(in_memory[0], rendered) == lossless


def test_bad_configs_are_refused() -> None:
    with pytest.raises(ValueError, match="too small"):
        SceneConfig(width=10, height=10)
    with pytest.raises(ValueError):
        SceneConfig(frames=0)
    with pytest.raises(ValueError, match="rotation"):
        SceneConfig(rotation=90.0)


def test_a_turning_zooming_camera_moves_the_background_only() -> None:
    """Objects are drawn in image space: same boxes; the background is another view of the same
    world, in its exact colours (nearest pixels)."""
    still = list(render(SceneConfig(width=160, height=120, frames=40, seed=4)))
    turned = list(render(SceneConfig(width=160, height=120, frames=40, seed=4, rotation=15.0, zoom=0.2)))
    assert [f.boxes for f in still] == [f.boxes for f in turned]
    assert np.abs(still[20].rgb.astype(int) - turned[20].rgb).mean() > 5
    world_colours = {tuple(c) for f in still for c in f.rgb.reshape(-1, 3)}
    assert {tuple(c) for c in turned[20].rgb.reshape(-1, 3)} <= world_colours | _object_colours(turned[20])


def _object_colours(frame) -> set[tuple]:
    colours = set()
    for box in frame.boxes:
        if box is not None:
            x, y, w, h = box
            colours |= {tuple(c) for c in frame.rgb[y:y + h, x:x + w].reshape(-1, 3)}
    return colours


def test_a_photograph_background_is_panned_over_with_the_objects_drawn_on_it() -> None:
    """Other scenes: the camera pans over a scikit-image photograph; outside the objects' boxes
    the frame is the photograph's view, inside them the objects are drawn."""
    photo = SceneConfig(width=160, height=120, frames=12, seed=4, background="chelsea")
    world = build_world(photo)
    assert world.rgb.shape[:2] == (120 + 2 * 36, 160 + 2 * 48)  # the view and a margin of 0.3 of it
    assert len(np.unique(world.rgb.reshape(-1, 3), axis=0)) > 1000  # a photograph, not a dozen colours
    for frame in render(photo):
        x, y = world.camera[frame.index]
        view = world.rgb[y:y + 120, x:x + 160]
        outside = np.ones((120, 160), dtype=bool)
        for box in frame.boxes:
            if box:
                inside = (slice(box[1], box[1] + box[3]), slice(box[0], box[0] + box[2]))
                assert not np.array_equal(frame.rgb[inside], view[inside])
                outside[inside] = False
        assert np.array_equal(frame.rgb[outside], view[outside])
    assert frame.boxes.count(None) < len(frame.boxes)
    with pytest.raises(ValueError, match="background"):
        SceneConfig(background="nowhere")
    assert build_parser().parse_args(["bag", "--background", "grass"]).background == "grass"


def test_a_road_background_is_asphalt_with_lane_markings_and_verges() -> None:
    """One region as large as the view under every object (cars seen from a drone); the same
    camera and objects as over a photograph for the same seed."""
    road = SceneConfig(width=160, height=120, frames=6, seed=4, background="road")
    world = build_world(road)
    height = world.rgb.shape[0]
    asphalt = world.rgb[height // 2 - 3, 10]
    assert abs(int(asphalt[0]) - 96) <= 8 and tuple(world.rgb[1, 5]) == (70, 140, 60)  # asphalt, verge
    assert (world.rgb[height // 8 + 1, :, 0] >= 200).mean() > 0.3  # a dashed marking
    photo = build_world(SceneConfig(width=160, height=120, frames=6, seed=4, background="chelsea"))
    assert np.array_equal(world.camera, photo.camera) and np.array_equal(world.paths, photo.paths)
    assert build_parser().parse_args(["bag", "--background", "road"]).background == "road"


def test_passing_objects_enter_once_and_leave_for_good() -> None:
    """With ``passing`` each object is in view for one stretch of the video, entering and leaving
    across the border, so a long video holds short tracks (benchmarks/passing_objects.py)."""
    cfg = SceneConfig(width=320, height=240, frames=1500, seed=7, objects=6, passing=True)
    seen = np.zeros((cfg.objects, cfg.frames), dtype=bool)
    border = np.zeros((cfg.objects, cfg.frames), dtype=bool)
    for frame in render(cfg):
        for obj, box in enumerate(frame.boxes):
            seen[obj, frame.index] = box is not None
            if box is not None:
                x, y, w, h = box
                border[obj, frame.index] = x == 0 or y == 0 or x + w == cfg.width or y + h == cfg.height
    for obj in range(cfg.objects):
        frames = np.flatnonzero(seen[obj])
        assert frames.size, obj
        assert frames[-1] - frames[0] + 1 == frames.size, f"object {obj} is in view more than once"
        assert frames.size < 0.6 * cfg.frames, obj
        if frames[0] > 0:
            assert border[obj, frames[0]], f"object {obj} appears inside the view"
        if frames[-1] < cfg.frames - 1:
            assert border[obj, frames[-1]], f"object {obj} vanishes inside the view"
    assert len({int(np.flatnonzero(s)[0]) for s in seen}) == cfg.objects  # each enters at its own time
    assert build_parser().parse_args(["clip", "--passing"]).passing
