"""Felzenszwalb-Huttenlocher segmentation and exact-colour regions."""
from __future__ import annotations

import threading

import cv2
import numpy as np
import pytest
import skimage.data
from scipy import ndimage as ndi
from skimage.segmentation import felzenszwalb as skimage_felzenszwalb

from trap_core.segmentation import SegmentationError, colour_components, felzenszwalb, fitted_chroma_weight
from trap_core.segmentation._kernels import felzenszwalb_kernel, relabel_4connected
from trap_core.segmentation.felzenszwalb import MAX_CHROMA_WEIGHT
from trap_core.synthetic import SceneConfig, build_world, render

NATURAL = ("astronaut", "coffee", "chelsea", "rocket")


def _natural(name: str, size: tuple[int, int] = (320, 240)) -> np.ndarray:
    return cv2.resize(getattr(skimage.data, name)(), size, interpolation=cv2.INTER_AREA)


def _same_partition(a: np.ndarray, b: np.ndarray) -> bool:
    """Two label images describe the same regions (labels may be numbered differently)."""
    pairs = np.unique(np.column_stack([a.ravel(), b.ravel()]), axis=0)
    return len(pairs) == len(np.unique(a)) == len(np.unique(b))


def test_flat_colour_frames_give_exactly_the_colour_regions_like_skimage() -> None:
    """Where the algorithms coincide (flat colours, no smoothing), labels are identical."""
    frame = next(iter(render(SceneConfig(width=320, height=240, frames=1, seed=8))))
    truth, _ = colour_components(frame.rgb)
    for threshold, k in (("size", 1.0), ("constant", 1.0)):
        mine, _ = felzenszwalb(frame.rgb, k=k, sigma=0, min_size=0, threshold=threshold)
        assert _same_partition(mine, truth)
    reference = skimage_felzenszwalb(frame.rgb, scale=1, sigma=0, min_size=0).astype(np.int32)
    assert _same_partition(relabel_4connected(reference)[0], truth)


def test_size_mode_region_counts_match_skimage_on_natural_images() -> None:
    ours = theirs = 0
    for name in NATURAL:
        image = _natural(name)
        smoothed = ndi.gaussian_filter(image.astype(np.float32), sigma=[0.8, 0.8, 0], mode="reflect")
        for k in (100, 300, 1000):
            ours += len(np.unique(felzenszwalb_kernel(smoothed, float(k), 20, True, 8, 0.0)))
            theirs += skimage_felzenszwalb(image, scale=k, sigma=0.8, min_size=20).max() + 1
    assert abs(ours / theirs - 1) < 0.06, (ours, theirs)


def test_constant_threshold_is_independent_of_region_size() -> None:
    """tau = k treats a 2-pixel image and two 6000-pixel halves alike; tau = k/|C| does not."""
    contrast = 12  # 12 * sqrt(3) ~ 20.8 colour units between the two sides
    tiny = np.zeros((1, 2, 3), dtype=np.uint8)
    tiny[:, 1:] = contrast
    big = np.zeros((60, 200, 3), dtype=np.uint8)
    big[:, 100:] = contrast
    for image in (tiny, big):
        assert felzenszwalb(image, k=25, sigma=0, min_size=0)[1] == 1
        assert felzenszwalb(image, k=15, sigma=0, min_size=0)[1] == 2
    assert felzenszwalb(tiny, k=200, sigma=0, min_size=0, threshold="size")[1] == 1
    assert felzenszwalb(big, k=200, sigma=0, min_size=0, threshold="size")[1] == 2


def test_mean_gap_stops_a_region_climbing_a_colour_ramp() -> None:
    """Grey and magenta joined by a ramp of steps under k: the paper's rule merges them one step at a
    time; with mean_gap, the two sides' mean colours are too far apart, whatever the steps."""
    grey, magenta = np.array([100.0, 100.0, 100.0]), np.array([160.0, 100.0, 160.0])  # 85 units apart
    ramp = np.linspace(0, 1, 16)[:, None] * (magenta - grey) + grey  # steps of 5.7 units
    row = np.vstack([np.repeat(grey[None], 40, axis=0), ramp, np.repeat(magenta[None], 40, axis=0)])
    image = np.repeat(row[None], 30, axis=0).round().astype(np.uint8)
    assert felzenszwalb(image, k=7, sigma=0, min_size=20)[1] == 1
    labels, n = felzenszwalb(image, k=7, sigma=0, min_size=20, mean_gap=5)
    assert n == 2 and labels[0, 0] != labels[0, -1]
    assert felzenszwalb(image, k=7, sigma=0, min_size=20, mean_gap=5, threshold="size")[1] == felzenszwalb(
        image, k=7, sigma=0, min_size=20, threshold="size")[1]  # size threshold: k is not in colour units


def test_lab_distances_weigh_a_grey_step_as_rgb_and_a_hue_change_more() -> None:
    """Two greys 20 apart in each channel (34.6 RGB units) and a reddish patch at about the
    brightness of the lighter grey, 33.2 RGB units from it: in RGB the patch is as near as the
    grey step and k 40 merges all three; in scaled CIELAB the grey step keeps its weight (35.2)
    while the hue change weighs 75.8, and the patch stays a region of its own."""
    image = np.full((40, 80, 3), 100, dtype=np.uint8)
    image[:, 40:] = 120
    image[10:30, 50:70] = (150, 110, 110)
    assert felzenszwalb(image, k=40, sigma=0, min_size=0)[1] == 1
    labels, n = felzenszwalb(image, k=40, sigma=0, min_size=0, colour_space="lab")
    assert n == 2 and labels[0, 0] == labels[0, -1] != labels[20, 60]
    assert felzenszwalb(image, k=30, sigma=0, min_size=0, colour_space="lab")[1] == 3  # the grey step: 35.2 > 30


def test_a_chroma_weight_keeps_a_hue_patch_apart_from_a_grey_ground_of_its_brightness() -> None:
    """The reddish patch of the test above, 33.2 RGB units from the lighter grey, lies 32.8 units
    along chroma and 5.8 along brightness: at weight 2 it is 66.0 away, and k 40 keeps it apart
    while the grey step (all brightness, 34.6) still merges. Weight 1 is RGB exactly."""
    image = np.full((40, 80, 3), 100, dtype=np.uint8)
    image[:, 40:] = 120
    image[10:30, 50:70] = (150, 110, 110)
    rgb = felzenszwalb(image, k=40, sigma=0.8, min_size=0)
    assert rgb[1] == 1
    assert all(np.array_equal(a, b) for a, b in zip(rgb, felzenszwalb(image, k=40, sigma=0.8, min_size=0,
                                                                       chroma_weight=1.0)))
    labels, n = felzenszwalb(image, k=40, sigma=0, min_size=0, chroma_weight=2.0)
    assert n == 2 and labels[0, 0] == labels[0, -1] != labels[20, 60]


def test_fitted_chroma_weight_follows_how_much_less_chroma_varies_than_brightness() -> None:
    """Noise drawn in each channel apart varies chroma as much as brightness: weight 1. Grey
    texture (the same noise in every channel) does not vary chroma at all: the cap. Between
    them, the weight is the ratio of the spreads."""
    rng = np.random.default_rng(3)
    base = np.full((120, 160, 3), 128.0)
    per_channel = base + rng.normal(0, 6, base.shape)
    grey_texture = base + rng.normal(0, 6, base.shape[:2])[..., None]
    assert fitted_chroma_weight(np.clip(per_channel, 0, 255).astype(np.uint8)) == pytest.approx(1.0, abs=0.1)
    assert fitted_chroma_weight(np.clip(grey_texture, 0, 255).astype(np.uint8)) == MAX_CHROMA_WEIGHT
    # grey noise of 4 in each channel spreads brightness by 6.9: ratios 1.15, 1.32 and 1.53
    weights = [fitted_chroma_weight(np.clip(base + rng.normal(0, 4, base.shape[:2])[..., None]
                                            + rng.normal(0, spread, base.shape), 0, 255).astype(np.uint8))
               for spread in (12, 8, 6)]
    assert weights == pytest.approx([1.15, 1.32, 1.53], abs=0.08)
    assert fitted_chroma_weight(np.full((10, 10, 3), 50, dtype=np.uint8)) == 1.0  # nothing varies: RGB
    with pytest.raises(SegmentationError, match="colour_space must be one of"):
        fitted_chroma_weight(np.full((10, 10, 3), 50, dtype=np.uint8), "hsv")  # not weighed on RGB's axes unasked


def test_regions_are_four_connected_and_compact() -> None:
    image = _natural("astronaut")
    for connectivity in (4, 8):
        labels, n = felzenszwalb(image, k=10, connectivity=connectivity)
        assert labels.dtype == np.int32 and labels.min() == 0 and labels.max() == n - 1
        assert relabel_4connected(labels)[1] == n
    labels, n = felzenszwalb(image, k=10, min_size=50)
    assert np.bincount(labels.ravel()).min() >= 50 or n == 1


def _reference_segmentation(image: np.ndarray, k: float, min_size: int, connectivity: int) -> np.ndarray:
    """The constant-threshold merge rule written plainly: edges in raster order (pixel, then
    right, down, and for 8-connectivity the two diagonals), stably sorted by weight in 1/16
    units; the larger component (the first on a tie) keeps its root."""
    height, width, _ = image.shape
    offsets = [(0, 1), (1, 0), (1, 1), (1, -1)][:2 if connectivity == 4 else 4]
    edges = []
    for y in range(height):
        for x in range(width):
            for dy, dx in offsets:
                if y + dy < height and 0 <= x + dx < width:
                    weight = np.float32(np.sqrt(np.sum((image[y, x] - image[y + dy, x + dx]) ** 2, dtype=np.float64)))
                    edges.append((int(weight * 16), y * width + x, (y + dy) * width + x + dx, weight))
    edges.sort(key=lambda edge: edge[0])  # stable: raster order within a bin
    parent, size, internal = list(range(height * width)), [1] * (height * width), [np.float32(0)] * (height * width)

    def root(node: int) -> int:
        while parent[node] != node:
            node = parent[node]
        return node

    def join(a: int, b: int) -> int:
        if size[a] < size[b]:
            a, b = b, a
        parent[b] = a
        size[a] += size[b]
        return a
    for _, p, q, weight in edges:
        a, b = root(p), root(q)
        if a != b and weight <= min(internal[a] + np.float32(k), internal[b] + np.float32(k)):
            kept = join(a, b)
            internal[kept] = max(weight, internal[a], internal[b])
    for _, p, q, _ in edges:
        a, b = root(p), root(q)
        if a != b and (size[a] < min_size or size[b] < min_size):
            join(a, b)
    return np.array([root(p) for p in range(height * width)]).reshape(height, width)


@pytest.mark.parametrize("connectivity", [4, 8])
def test_the_compiled_kernel_is_the_merge_rule_written_plainly(connectivity: int) -> None:
    """Same roots, not just the same regions: edge order and tie-breaking are pinned down."""
    rng = np.random.default_rng(connectivity)
    for _ in range(3):
        image = cv2.GaussianBlur(rng.integers(0, 256, (18, 23, 3)).astype(np.float32), (0, 0), 1.5)
        image[:, :8] += 40  # a coloured block, so that some edges are far above k
        expected = _reference_segmentation(image, 7.0, 5, connectivity)
        assert np.array_equal(felzenszwalb_kernel(image, 7.0, 5, False, connectivity, 0.0), expected)


def test_min_size_merges_small_regions() -> None:
    image = _natural("coffee")
    _, many = felzenszwalb(image, k=5, min_size=0)
    _, few = felzenszwalb(image, k=5, min_size=100)
    assert few < many


def test_two_threads_give_the_same_labels() -> None:
    images = [_natural(name) for name in NATURAL]
    expected = [felzenszwalb(image)[0] for image in images]
    results: dict[int, np.ndarray] = {}

    def work(index: int) -> None:
        results[index] = felzenszwalb(images[index])[0]

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(images))]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert all(np.array_equal(results[i], expected[i]) for i in range(len(images)))


@pytest.mark.parametrize("kwargs,pattern", [
    (dict(threshold="median"), "threshold must be"), (dict(k=-1), "k >= 0"),
    (dict(sigma=float("nan")), "sigma >= 0"), (dict(connectivity=6), "connectivity"),
    (dict(mean_gap=-1.0), "mean_gap >= 0"), (dict(colour_space="hsv"), "colour_space must be"),
    (dict(chroma_weight=0.0), "chroma_weight must be > 0"),
])
def test_bad_parameters(kwargs: dict, pattern: str) -> None:
    with pytest.raises(SegmentationError, match=pattern):
        felzenszwalb(np.zeros((4, 4, 3), dtype=np.uint8), **kwargs)


def test_empty_image_is_refused() -> None:
    with pytest.raises(SegmentationError, match="expected an"):
        felzenszwalb(np.zeros((0, 5, 3), dtype=np.uint8))
    with pytest.raises(SegmentationError, match="expected an"):
        colour_components(np.zeros((5, 0, 3), dtype=np.uint8))


def test_colour_components_split_same_colour_islands() -> None:
    image = np.zeros((5, 5, 3), dtype=np.uint8)
    image[0, 0] = image[4, 4] = 200
    image[1, 1] = 200  # diagonal to (0, 0): a separate region under 4-adjacency
    labels, n = colour_components(image)
    assert n == 4
    assert labels[0, 0] != labels[1, 1] != labels[4, 4]


def _body_outside_box(k: float | None) -> list[float]:
    """Per checked frame of a noisy video of round objects: how much of the region holding most of
    object 1's body lies outside the object's box, as a share of the body."""
    cfg = SceneConfig(width=320, height=240, frames=41, seed=65, noise=2.0, shape="disc", exits=False)
    body = build_world(cfg).object_colours[0, 0].astype(float)
    shares = []
    for frame in render(cfg):
        if frame.index % 10 or frame.boxes[0] is None:
            continue
        x, y, w, h = frame.boxes[0]
        inside = np.zeros(frame.rgb.shape[:2], dtype=bool)
        inside[y:y + h, x:x + w] = True
        pixels = inside & (np.linalg.norm(frame.rgb - body, axis=2) < 15)
        labels, _ = felzenszwalb(frame.rgb) if k is None else felzenszwalb(frame.rgb, k=k)
        ids, counts = np.unique(labels[pixels], return_counts=True)
        region = labels == ids[np.argmax(counts)]
        shares.append(float((region & ~inside).sum() / pixels.sum()))
    return shares


def test_a_round_body_stays_its_own_region_under_noise() -> None:
    # With the paper's constant threshold a region climbs the colour ramp that smoothing leaves
    # along a curved edge; the default k is small enough that it does not (README, shapes).
    assert max(_body_outside_box(None)) < 0.2
    assert max(_body_outside_box(10.0)) > 1.0  # the former default: the body leaks into the background
