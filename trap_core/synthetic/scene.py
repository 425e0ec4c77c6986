"""Synthetic benchmark videos with exact ground truth: analogues of the paper's Anim1 / Anim2.

A camera pans over a wide world of coloured Voronoi cells sprinkled with small islands (about
240 regions a frame, mean adjacency degree near 3.9, as in the paper's Anim videos). Objects
made of several coloured parts (car-like boxes by default; tall "persons", round "discs", or a
mix: ``SHAPES``) move in image space along piecewise-linear paths with abrupt
turns, cross and occlude each other (fixed depth order); the last object leaves the field of
view for 3-4 s several times. With ``passing``, objects instead pass through: each enters once
through a border at its own time, crosses the view and leaves for good, as traffic under a
drone does. Everything is drawn with exact colours (no anti-aliasing), so the
ground-truth box of an object is the box of its visible pixels, computed while drawing.
"""
from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import cv2
import numpy as np
from scipy.spatial import Delaunay, cKDTree

# Object shapes: parts drawn in order, each a colour slot (0 = body) and a rectangle or the
# ellipse inscribed in it, in unit box coordinates (x0, y0, x1, y1); pixels no part covers show
# the background. Every shape has junctions of parts inside the object and with the background.
RECT, ELLIPSE = "rect", "ellipse"
SHAPES = {
    # two upper panels meeting in the middle, two "wheels" on the lower edge
    "car": ((0, RECT, (0.0, 0.0, 1.0, 1.0)), (1, RECT, (0.10, 0.15, 0.50, 0.58)),
            (2, RECT, (0.50, 0.15, 0.90, 0.58)), (3, RECT, (0.14, 0.74, 0.36, 1.0)),
            (3, RECT, (0.64, 0.74, 0.86, 1.0))),
    # tall and thin, not convex: head, torso, arms down the sides over the top of the legs, legs apart
    "person": ((1, ELLIPSE, (0.3, 0.0, 0.7, 0.2)), (0, RECT, (0.14, 0.18, 0.86, 0.6)),
               (2, RECT, (0.16, 0.58, 0.46, 1.0)), (2, RECT, (0.54, 0.58, 0.84, 1.0)),
               (3, RECT, (0.0, 0.22, 0.2, 0.68)), (3, RECT, (0.8, 0.22, 1.0, 0.68))),
    # round: two half-panels meeting in the middle, a spot on the lower edge
    "disc": ((0, ELLIPSE, (0.0, 0.0, 1.0, 1.0)), (1, RECT, (0.2, 0.3, 0.5, 0.62)),
             (2, RECT, (0.5, 0.3, 0.8, 0.62)), (3, ELLIPSE, (0.38, 0.8, 0.62, 1.0))),
}
SHAPE_SIZES = {"car": (0.1, 0.09), "person": (0.065, 0.2), "disc": (0.08, 0.107)}  # share of width, height
COLOUR_SLOTS = 4
MIXED = "mixed"  # object i has shape i of SHAPES, cycling
CELLS = "cells"  # the background: coloured Voronoi cells with islands, as the paper's Anim videos
ROAD = "road"  # or grey asphalt with dashed lane markings between two verges, seen from above
# Or a photograph bundled with scikit-image (skimage.data, no download), stretched over the world
# the camera pans: other scenes, smooth (chelsea, colorwheel, retina) to textured (grass, gravel).
PHOTOS = ("astronaut", "brick", "camera", "chelsea", "coffee", "colorwheel", "grass", "gravel", "hubble_deep_field",
          "immunohistochemistry", "retina", "rocket")


@dataclass(frozen=True)
class SceneConfig:
    """Everything that defines a synthetic video; the same config and seed give the same pixels."""

    width: int = 640
    height: int = 480
    frames: int = 721
    fps: float = 25.0
    objects: int = 3
    identical: bool = False
    regions: int = 240
    island_ratio: float = 0.8
    seed: int = 0
    noise: float = 0.0
    illumination: float = 0.0
    exits: bool = True
    passing: bool = False  # objects pass through the view once each, at their own times (no object stays)
    object_scale: float = 1.0
    rotation: float = 0.0  # degrees: the camera also turns (yaw), up to this either way
    zoom: float = 0.0      # the camera also zooms, up to this share in and out
    shape: str = "car"     # one of SHAPES, or "mixed"
    background: str = CELLS  # "cells", "road", or one of PHOTOS


    def __post_init__(self) -> None:
        if self.width < 64 or self.height < 48:
            raise ValueError(f"frame {self.width}x{self.height} is too small (at least 64x48)")
        if self.frames < 1 or self.objects < 0 or self.regions < 8:
            raise ValueError("frames >= 1, objects >= 0 and regions >= 8 are required")
        if self.noise < 0 or not 0 <= self.illumination < 1:
            raise ValueError("noise >= 0 and 0 <= illumination < 1 are required")
        if not 0 <= self.rotation <= 45 or not 0 <= self.zoom < 0.5:
            raise ValueError("0 <= rotation <= 45 degrees and 0 <= zoom < 0.5 are required")
        if self.background not in (CELLS, ROAD, *PHOTOS):
            raise ValueError(f"background {self.background!r} is not one of {', '.join([CELLS, ROAD, *PHOTOS])}")
        if self.shape != MIXED and self.shape not in SHAPES:
            raise ValueError(f"shape {self.shape!r} is not one of {', '.join([*SHAPES, MIXED])}")

    def shape_of(self, obj: int) -> str:
        """Shape of object ``obj``."""
        return list(SHAPES)[obj % len(SHAPES)] if self.shape == MIXED else self.shape

    def size_of(self, obj: int) -> tuple[int, int]:
        """Width and height in pixels of object ``obj``."""
        share_w, share_h = SHAPE_SIZES[self.shape_of(obj)]
        return (max(8, int(round(share_w * self.width * self.object_scale))),
                max(6, int(round(share_h * self.height * self.object_scale))))


PRESETS = {
    "anim1": dict(identical=True),
    "anim2": dict(identical=False),
}


@dataclass
class _World:
    rgb: np.ndarray                  # the background the camera pans over
    camera: np.ndarray               # (frames, 2) integer top-left of the view in the world
    object_colours: np.ndarray       # (objects, COLOUR_SLOTS, 3)
    stamps: list[np.ndarray]         # per object, (h, w) colour slot of each pixel, -1 where none
    paths: np.ndarray                # (objects, frames, 2) float top-left in the image


def _distinct_colours(rng: np.random.Generator, count: int, avoid: np.ndarray, min_dist: float) -> np.ndarray:
    """Draw ``count`` colours at least ``min_dist`` (RGB distance) from each other and from ``avoid``."""
    chosen: list[np.ndarray] = []
    pool = list(avoid)
    tries = 0
    while len(chosen) < count:
        candidate = rng.integers(20, 236, size=3)
        tries += 1
        if all(np.linalg.norm(candidate - other) >= min_dist for other in pool) or tries > 20000:
            chosen.append(candidate)
            pool.append(candidate)
    return np.array(chosen, dtype=np.int64).reshape(count, 3)


def _camera_path(rng: np.random.Generator, cfg: SceneConfig, margin: tuple[int, int]) -> np.ndarray:
    """Smooth pan (two sinusoids per axis) that stays inside the world."""
    t = np.arange(cfg.frames, dtype=np.float64)
    path = np.empty((cfg.frames, 2))
    for axis, span in enumerate(margin):
        periods = rng.uniform(250, 600, size=2)
        phases = rng.uniform(0, 2 * np.pi, size=2)
        wave = 0.65 * np.sin(2 * np.pi * t / periods[0] + phases[0]) + 0.35 * np.sin(2 * np.pi * t / periods[1] + phases[1])
        path[:, axis] = span + 0.9 * span * wave
    return np.rint(path).astype(np.int64)


def _background(rng: np.random.Generator, cfg: SceneConfig, world_w: int, world_h: int,
                palette: np.ndarray) -> np.ndarray:
    """Voronoi cells coloured so that neighbours differ, plus islands inside some cells."""
    area_ratio = world_w * world_h / (cfg.width * cfg.height)
    # 0.82: cells cut by the frame edges count as extra regions (calibrated at 640x480).
    cells_per_view = 0.82 * cfg.regions / (1 + cfg.island_ratio)
    n_cells = max(4, int(round(cells_per_view * area_ratio)))
    seeds = rng.uniform((0, 0), (world_w, world_h), size=(n_cells, 2))
    ys, xs = np.mgrid[0:world_h, 0:world_w]
    _, owner = cKDTree(seeds).query(np.column_stack([xs.ravel(), ys.ravel()]), workers=-1)
    owner = owner.reshape(world_h, world_w)
    neighbours: list[set[int]] = [set() for _ in range(n_cells)]
    for simplex in Delaunay(seeds).simplices:
        for a in simplex:
            neighbours[a].update(int(b) for b in simplex if b != a)
    colour_of = np.full(n_cells, -1)
    for cell in rng.permutation(n_cells):
        taken = {colour_of[n] for n in neighbours[cell]}
        free = [c for c in range(len(palette)) if c not in taken] or list(range(len(palette)))
        colour_of[cell] = rng.choice(free)
    rgb = palette[colour_of[owner]].astype(np.uint8)
    # Islands: discs around cell seeds, small enough to stay inside their cell.
    spacing, _ = cKDTree(seeds).query(seeds, k=2)
    n_islands = int(round(n_cells * cfg.island_ratio))
    for cell in rng.choice(n_cells, size=min(n_islands, n_cells), replace=False):
        radius = min(0.4 * spacing[cell, 1], rng.uniform(0.008, 0.018) * cfg.width)
        if radius < 2.5:
            continue
        cx, cy = seeds[cell]
        x0, x1 = int(max(cx - radius, 0)), int(min(cx + radius + 1, world_w))
        y0, y1 = int(max(cy - radius, 0)), int(min(cy + radius + 1, world_h))
        yy, xx = np.mgrid[y0:y1, x0:x1]
        disc = (xx - cx) ** 2 + ((yy - cy) / rng.uniform(0.6, 1.0)) ** 2 <= radius ** 2
        colours = [c for c in range(len(palette)) if c != colour_of[cell]]
        rgb[y0:y1, x0:x1][disc] = palette[rng.choice(colours)]
    return rgb


def _road(rng: np.random.Generator, cfg: SceneConfig, world_w: int, world_h: int) -> np.ndarray:
    """Grey asphalt with a faint grain, dashed white lane markings every quarter of the world's
    height and green verges along its top and bottom: one region as large as the view under
    every object, as for cars seen from a drone. Its own generator: the camera and the objects
    move as over the photographs for the same seed."""
    scale = cfg.width / 640
    rgb = np.full((world_h, world_w, 3), (96, 96, 100), dtype=np.float32)
    rgb = np.clip(np.rint(rgb + rng.normal(0, 2, rgb.shape)), 0, 255).astype(np.uint8)
    dash, line = max(4, round(40 * scale)), max(2, round(4 * scale))
    for y in range(world_h // 8, world_h, world_h // 4):
        for x in range(0, world_w, 2 * dash):
            rgb[y:y + line, x:x + dash] = 235
    verge = world_h // 20
    rgb[:verge], rgb[world_h - verge:] = (70, 140, 60), (70, 140, 60)
    return cv2.GaussianBlur(rgb, (3, 3), 0)


def _photo(name: str, world_w: int, world_h: int) -> np.ndarray:
    """The scikit-image photograph ``name`` (grey ones as RGB) stretched to the world's size."""
    from skimage import data  # only for these backgrounds
    rgb = getattr(data, name)()
    rgb = np.repeat(rgb[..., None], 3, axis=2) if rgb.ndim == 2 else rgb[..., :3]
    return cv2.resize(np.ascontiguousarray(rgb, dtype=np.uint8), (world_w, world_h), interpolation=cv2.INTER_CUBIC)


def _object_paths(rng: np.random.Generator, cfg: SceneConfig) -> np.ndarray:
    """Piecewise-linear image-space paths (top-left corners) with abrupt turns; every third leg
    heads for the centre (so paths cross); the last object leaves the view for 3-4 s every ~6-9 s.
    With ``cfg.passing``, :func:`_passing_paths` instead."""
    if cfg.passing:
        return _passing_paths(rng, cfg)
    paths = np.empty((cfg.objects, cfg.frames, 2))
    scale = cfg.width / 640
    for obj in range(cfg.objects):
        w, h = cfg.size_of(obj)
        low, high = _corner_range(cfg, obj)
        centre = (low + high) / 2
        leaves = cfg.exits and obj == cfg.objects - 1 and cfg.objects > 0
        pos = rng.uniform(low, high)
        frame, leg = 0, 0
        next_exit = int(rng.uniform(60, 120))
        while frame < cfg.frames:
            if leaves and frame >= next_exit:
                # Leave through the nearest vertical border, stay out 75-100 frames, come back elsewhere.
                side = -1 if pos[0] < centre[0] else 1
                outside = np.array([-1.6 * w if side < 0 else cfg.width + 0.6 * w, pos[1]])
                frame, pos = _walk(paths[obj], frame, pos, outside, 5.0 * scale)
                hidden = int(rng.uniform(75, 100))
                paths[obj, frame:frame + hidden] = pos
                frame += hidden
                entry_side = rng.choice([-1, 1])
                pos = np.array([-1.6 * w if entry_side < 0 else cfg.width + 0.6 * w, rng.uniform(low[1], high[1])])
                next_exit = frame + int(rng.uniform(90, 150))
                continue
            target = centre + rng.uniform(-0.12, 0.12, 2) * (high - low) if leg % 3 == 2 else rng.uniform(low, high)
            frame, pos = _walk(paths[obj], frame, pos, target, rng.uniform(1.5, 4.0) * scale)
            leg += 1
    return paths


def _passing_paths(rng: np.random.Generator, cfg: SceneConfig) -> np.ndarray:
    """Paths of objects that each pass through the view once: out of view until a time drawn over
    the video, in through a random border, one to three legs to points in view, out through a
    random border, and out of view for the rest of the video. An object is in view for a few
    hundred frames however long the video, so a long video holds short tracks: what footage of
    traffic or passers-by gives, and the paper's videos (every object in view throughout) do not."""
    paths = np.empty((cfg.objects, cfg.frames, 2))
    scale = cfg.width / 640
    for obj in range(cfg.objects):
        w, h = cfg.size_of(obj)
        low, high = _corner_range(cfg, obj)
        pos = _outside(rng, cfg, w, h, low, high)
        enters = int(rng.uniform(0, 0.85 * cfg.frames))
        paths[obj, :enters] = pos
        frame = enters
        for _ in range(int(rng.integers(1, 4))):
            frame, pos = _walk(paths[obj], frame, pos, rng.uniform(low, high), rng.uniform(1.5, 4.0) * scale)
        frame, pos = _walk(paths[obj], frame, pos, _outside(rng, cfg, w, h, low, high),
                           rng.uniform(1.5, 4.0) * scale)
        paths[obj, frame:] = pos
    return paths


def _corner_range(cfg: SceneConfig, obj: int) -> tuple[np.ndarray, np.ndarray]:
    """Least and greatest top-left corner of object ``obj`` inside the view, 2 % of it from its edges."""
    w, h = cfg.size_of(obj)
    margin = np.array([0.02 * cfg.width, 0.02 * cfg.height])
    return margin, np.array([cfg.width - w, cfg.height - h]) - margin


def _outside(rng: np.random.Generator, cfg: SceneConfig, w: int, h: int, low: np.ndarray,
             high: np.ndarray) -> np.ndarray:
    """A top-left corner that puts a ``w`` x ``h`` object just out of view beyond a random border."""
    x, y = rng.uniform(low, high)
    side = int(rng.integers(4))
    return np.array([(-1.6 * w, y), (cfg.width + 0.6 * w, y), (x, -1.6 * h), (x, cfg.height + 0.6 * h)][side])


def _walk(path: np.ndarray, frame: int, start: np.ndarray, target: np.ndarray, speed: float) -> tuple[int, np.ndarray]:
    """Fill ``path`` from ``frame`` on with a straight walk to ``target``; return where it ended."""
    steps = max(1, int(np.ceil(np.linalg.norm(target - start) / speed)))
    end = min(frame + steps, len(path))
    fractions = (np.arange(frame, end) - frame + 1) / steps
    path[frame:end] = start + fractions[:, None] * (target - start)
    return end, (path[end - 1].copy() if end > frame else start)


def build_world(cfg: SceneConfig) -> _World:
    """Lay out background, camera path, object colours and paths for ``cfg``."""
    rng = np.random.default_rng(cfg.seed)
    palette_bg = _distinct_colours(rng, 12, np.empty((0, 3)), 45)
    n_object_colours = COLOUR_SLOTS * (1 if cfg.identical else max(cfg.objects, 1))
    object_palette = _distinct_colours(rng, n_object_colours, palette_bg, 40)
    if cfg.identical:
        colours = np.repeat(object_palette[None], cfg.objects, axis=0)
    else:
        colours = object_palette.reshape(max(cfg.objects, 1), COLOUR_SLOTS, 3)[: cfg.objects]
    margin = (int(0.3 * cfg.width), int(0.3 * cfg.height))
    world_w, world_h = cfg.width + 2 * margin[0], cfg.height + 2 * margin[1]
    if cfg.background == CELLS:
        background = _background(rng, cfg, world_w, world_h, palette_bg)
    elif cfg.background == ROAD:
        background = _road(np.random.default_rng(cfg.seed + 2), cfg, world_w, world_h)
    else:
        background = _photo(cfg.background, world_w, world_h)
    camera = _camera_path(rng, cfg, margin)
    paths = _object_paths(rng, cfg)
    stamps = [_stamp(SHAPES[cfg.shape_of(obj)], cfg.size_of(obj)) for obj in range(cfg.objects)]
    return _World(background, camera, colours, stamps, paths)


@dataclass(frozen=True)
class RenderedFrame:
    """A frame and its ground truth: ``boxes[obj] = (x, y, w, h)`` of visible pixels, or None, and
    ``owner``, the object each pixel shows (H, W; -1: the background), for measures of how a
    segmentation cuts the objects apart from the background (``benchmarks/region_leak.py``)."""

    index: int
    rgb: np.ndarray
    boxes: tuple[tuple[int, int, int, int] | None, ...]
    owner: np.ndarray


def _stamp(parts: tuple, size: tuple[int, int]) -> np.ndarray:
    """(h, w) colour slot of each pixel of an object of ``size`` made of ``parts``, -1 where none."""
    w, h = size
    stamp = np.full((h, w), -1, dtype=np.int8)
    ys, xs = np.mgrid[0:h, 0:w] + 0.5
    for slot, kind, (bx0, by0, bx1, by1) in parts:
        x0, y0, x1, y1 = (int(round(bx0 * w)), int(round(by0 * h)), int(round(bx1 * w)), int(round(by1 * h)))
        if kind == RECT:
            stamp[y0:y1, x0:x1] = slot
        else:
            inside = (((xs - (x0 + x1) / 2) / max((x1 - x0) / 2, 0.5)) ** 2
                      + ((ys - (y0 + y1) / 2) / max((y1 - y0) / 2, 0.5)) ** 2) <= 1
            stamp[inside] = slot
    return stamp


def _draw(frame: np.ndarray, owner: np.ndarray, stamp: np.ndarray, colours: np.ndarray, corner: np.ndarray,
          obj: int) -> None:
    """Paint ``stamp`` with ``colours`` at top-left ``corner`` (rounded), clipped to the frame, in place."""
    x0, y0 = int(round(corner[0])), int(round(corner[1]))
    h, w = stamp.shape
    height, width = owner.shape
    xa, ya, xb, yb = max(x0, 0), max(y0, 0), min(x0 + w, width), min(y0 + h, height)
    if xa >= xb or ya >= yb:
        return
    slots = stamp[ya - y0:yb - y0, xa - x0:xb - x0]
    drawn = slots >= 0
    frame[ya:yb, xa:xb][drawn] = colours[slots[drawn]]
    owner[ya:yb, xa:xb][drawn] = obj


def render(cfg: SceneConfig) -> Iterator[RenderedFrame]:
    """Yield the frames of the video described by ``cfg``, one at a time, with ground truth."""
    world = build_world(cfg)
    noise_rng = np.random.default_rng(cfg.seed + 1)
    W, H = cfg.width, cfg.height
    for t in range(cfg.frames):
        cx, cy = world.camera[t]
        if cfg.rotation or cfg.zoom:
            frame = _turned_view(world.rgb, cx, cy, W, H, cfg, t)
        else:
            frame = world.rgb[cy:cy + H, cx:cx + W].copy()
        owner = np.full((H, W), -1, dtype=np.int16)
        for obj in range(cfg.objects):
            _draw(frame, owner, world.stamps[obj], world.object_colours[obj], world.paths[obj, t], obj)
        boxes = tuple(_visible_box(owner, obj) for obj in range(cfg.objects))
        if cfg.illumination or cfg.noise:
            gain = light_gain(cfg, t)
            shaded = frame.astype(np.float32) * gain
            if cfg.noise:
                shaded += noise_rng.normal(0, cfg.noise, size=frame.shape).astype(np.float32)
            frame = np.clip(np.rint(shaded), 0, 255).astype(np.uint8)
        yield RenderedFrame(t, frame, boxes, owner)


def light_gain(cfg: SceneConfig, t: int) -> float:
    """The gain of the light on frame ``t`` of ``cfg``'s video (1 where it has no
    ``illumination`` swing): two slow swings over the video."""
    return 1.0 + cfg.illumination * np.sin(2 * np.pi * t / max(cfg.frames, 2) * 2)


def _turned_view(world: np.ndarray, cx: int, cy: int, width: int, height: int, cfg: SceneConfig,
                 t: int) -> np.ndarray:
    """The view at ``(cx, cy)`` with the camera also turned and zoomed about the view's centre
    (slow sinusoids over the video; nearest pixels, so colours stay exact). Objects are drawn in
    image space afterwards: only the background turns, as for a drone that yaws and climbs."""
    phase = 2 * np.pi * t / max(cfg.frames, 2)
    angle = np.radians(cfg.rotation * np.sin(phase * 1.5))
    scale = 1.0 + cfg.zoom * np.sin(phase * 2.5 + 1.0)
    c, s = np.cos(angle) / scale, np.sin(angle) / scale
    centre_x, centre_y = cx + width / 2, cy + height / 2
    to_world = np.array([[c, -s, centre_x - c * width / 2 + s * height / 2],
                         [s, c, centre_y - s * width / 2 - c * height / 2]])
    return cv2.warpAffine(world, to_world, (width, height), flags=cv2.INTER_NEAREST | cv2.WARP_INVERSE_MAP,
                          borderMode=cv2.BORDER_REFLECT)


def _visible_box(owner: np.ndarray, obj: int) -> tuple[int, int, int, int] | None:
    mask = owner == obj
    rows = np.flatnonzero(mask.any(axis=1))
    if rows.size == 0:
        return None
    cols = np.flatnonzero(mask[rows[0]:rows[-1] + 1].any(axis=0))
    return int(cols[0]), int(rows[0]), int(cols[-1] - cols[0] + 1), int(rows[-1] - rows[0] + 1)
