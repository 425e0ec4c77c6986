"""The fresh-draw benchmark draws what it says it draws: valid scenes over the whole space, the
same ones for one generator seed and others for another."""
from __future__ import annotations

import pytest

from trap_core.synthetic.scene import CELLS, MIXED, PHOTOS, ROAD, SHAPES


@pytest.fixture(scope="module")
def fresh_draws(benchmark_module):
    return benchmark_module("fresh_draws")


def test_a_generator_seed_gives_the_same_videos_and_another_seed_others(fresh_draws) -> None:
    first = fresh_draws.drawn_scenes(7, 6)
    assert first == fresh_draws.drawn_scenes(7, 6)
    assert fresh_draws.drawn_scenes(7, 3) == first[:3]
    others = fresh_draws.drawn_scenes(8, 6)
    assert not {label for label, _ in first} & {label for label, _ in others}


def test_the_draws_are_valid_scenes_spread_over_every_size_shape_ground_and_delivery(fresh_draws) -> None:
    scenes = [scene for _, scene in fresh_draws.drawn_scenes(1, 300)]
    for scene in scenes:
        fresh_draws.quality._scene_config(scene)  # raises on a scene the generator cannot make
        assert 2 <= scene["objects"] <= 5 and 300 <= scene["frames"] <= 500
    assert {(scene["width"], scene["height"]) for scene in scenes} == set(fresh_draws.SIZES)
    assert {scene["shape"] for scene in scenes} == {*SHAPES, MIXED}
    assert {scene["background"] for scene in scenes} == {CELLS, ROAD, *PHOTOS}
    assert {scene.get("encoding", scene.get("compressed", "raw")) for scene in scenes} == {
        "raw", "bgra8", "yuv422", "jpeg"}
    assert {scene["identical"] for scene in scenes} == {True, False}


def test_a_label_names_what_was_drawn(fresh_draws) -> None:
    scene = dict(seed=1, identical=False, shape=MIXED, objects=4, object_scale=0.8, width=960, height=540,
                 frames=400, zoom=0.1, rotation=0.0, illumination=0.05, noise=1.5, background="gravel",
                 compressed="jpeg")
    assert fresh_draws.scene_label(scene) == ("distinct, mixed shapes, 4 objects 0.8x, 960x540, 400 frames, zoom 10 %, "
                                              "illumination 5 %, noise 1.5, gravel, JPEG")


def test_enlarged_objects_are_the_same_draw_with_larger_objects(fresh_draws) -> None:
    drawn = [scene for _, scene in fresh_draws.drawn_scenes(7, 6)]
    enlarged = [scene for _, scene in fresh_draws.drawn_scenes(7, 6, enlarged=2.5)]
    for usual, large in zip(drawn, enlarged):
        assert large["object_scale"] == pytest.approx(2.5 * usual["object_scale"])
        assert {**large, "object_scale": usual["object_scale"]} == usual
        fresh_draws.quality._scene_config(large)
