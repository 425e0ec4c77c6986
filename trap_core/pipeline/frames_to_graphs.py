"""Segmentation and plane graphs of a stream of frames, on several threads.

The compiled kernels release the GIL, so ``threads`` frames are segmented at once while the
caller keeps decoding; results come back in frame order, and at most ``2 * threads`` frames
are in flight (memory stays flat).
"""
from __future__ import annotations

import dataclasses
import sys
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ThreadPoolExecutor

import cv2
import numpy as np

from trap_core.bagio import compress_image, decode_compressed, decode_image, encode_image
from trap_core.ordered import in_order
from trap_core.pipeline.params import TrapParams
from trap_core.rag import PlaneGraph, build_plane_graph
from trap_core.robust.image_steps import image_step
from trap_core.segmentation import SegmentationError, colour_components, felzenszwalb, fitted_chroma_weight
from trap_core.synthetic import RenderedFrame, SceneConfig, render

FEW_REGIONS = 40  # a first frame with fewer Felzenszwalb regions than this gets a warning (first_frame_setup)
MAX_K = 1e4  # fitting never raises Felzenszwalb's k beyond this: every colour step of a frame merges long before
COLOUR_EXCESS = 20  # exact-colour regions are refused on a first frame with more than this times max_regions


def frame_graph(rgb: np.ndarray, params: TrapParams, previous: np.ndarray | None = None) -> PlaneGraph:
    """Regions (segmentation or exact colours) and their plane graph for one frame, with the
    camera's step from the ``previous`` frame read from the two images where it is given
    (:func:`trap_core.robust.image_steps.image_step`; the robust method's camera motion).

    A frame is segmented with its longer side scaled to ``params.max_side`` (nearest pixels:
    averaging would blend the colours along every edge into strips of regions of their own, and
    exact-colour regions must keep exact colours), so an object is cut into as many regions as
    at the size the defaults were made for, whatever the camera's resolution: a large frame at
    the paper's ``k`` would give thousands of regions, and in a small one ``min_size`` pixels
    and Gaussian smoothing swallow an object's parts. The graph's geometry is then given back in
    the frame's own pixels.
    """
    height, width = rgb.shape[:2]
    params = _chroma_weighed(rgb, params)
    small = _working_size(rgb, params)
    labels, n = _regions(small, params)
    graph = build_plane_graph(labels, n, small, params.colour_bins, params.contact_tolerance)
    if small is not rgb:
        graph = _in_frame_pixels(graph, width / small.shape[1], height / small.shape[0])
    return graph if previous is None else dataclasses.replace(graph, camera_step=image_step(previous, rgb))


def frame_regions(rgb: np.ndarray, params: TrapParams) -> tuple[np.ndarray, int]:
    """Region label of each pixel of ``rgb`` at the size it is segmented (:func:`frame_graph`:
    longer side at ``params.max_side``), and their count: what the plane graph is built on, for
    measures of the segmentation itself (``benchmarks/region_leak.py``)."""
    return _regions(_working_size(rgb, params), _chroma_weighed(rgb, params))


def fitted_to_regions(rgb: np.ndarray, params: TrapParams) -> TrapParams:
    """``params`` with Felzenszwalb's ``k`` raised, if need be, until the frame ``rgb`` has at most
    ``params.max_regions`` regions (at the working size); unchanged for exact-colour regions.

    TRAP's graphs are made for a few hundred regions a frame (the paper's videos have ~240,
    TRAP_SPEC section 9). Textured footage (grass, gravel, foliage) cut at the paper's ``k``
    gives thousands of small regions that flicker from frame to frame: every stage after
    segmentation then takes minutes instead of seconds, and flickering structures chained
    from frame to frame pass for moving ones. One ``k`` serves the whole video, chosen on its
    first frame, so that regions stay comparable from frame to frame: the smallest that meets
    the limit, within 2 % (bisection on a log scale).
    """
    k = _fitted(rgb, _chroma_weighed(rgb, params))[0].k
    return params if k == params.k else dataclasses.replace(params, k=k)


class SetupNote(str):
    """A line of :func:`first_frame_setup` for the user. ``warns``: the tracks may suffer from
    what it tells (a giant-region scene), so a node logs it as a warning; otherwise it tells of a
    parameter fitted to the video (information). A ``str``, so that it prints and compares as its
    text."""

    warns: bool

    def __new__(cls, text: str, warns: bool = False) -> SetupNote:
        note = super().__new__(cls, text)
        note.warns = warns
        return note


def print_setup_notes(used: TrapParams, notes: list[SetupNote]) -> None:
    """Write the lines of :func:`first_frame_setup` to stderr, a warning's after ``warning:``: how
    the command-line runs tell them (the ``told`` of :func:`graphs_of`); a ROS node logs each at
    its level instead. ``used``, the parameters fitted, is there for that signature."""
    print("\n".join(f"warning: {note}" if note.warns else note for note in notes), file=sys.stderr)


def first_frame_setup(rgb: np.ndarray, params: TrapParams) -> tuple[TrapParams, list[SetupNote]]:
    """The segmentation parameters of a whole video, from its first frame ``rgb``
    (:func:`fitted_chroma_weight` where ``chroma_weight`` is 0, then :func:`fitted_to_regions`),
    and the lines to tell the user about them (:class:`SetupNote`): the chroma weight, that ``k``
    was raised, and (a warning) that the first frame has fewer than ``FEW_REGIONS`` Felzenszwalb
    regions.

    Exact-colour regions (``segmentation: colour``) are made for lossless synthetic frames, where a
    drawn region is one colour (~250 regions a frame). On noisy or compressed frames (JPEG) nearly
    every pixel has a colour of its own: hundreds of thousands of regions, and mining them never
    ends. A first frame with more than ``COLOUR_EXCESS`` times ``max_regions`` of them is refused.

    A smooth scene (a face, a sky, a plain wall) cut at ``k`` 7 can give a few giant regions: every
    pattern an object shows then holds one of them, cut by the view's edge, and reads as
    background (README, Natural backgrounds). Nothing is changed for it: a finer cut of a noisy
    scene passes flickering regions for motion, so only the user can choose it.

    Raises
    ------
    SegmentationError
        Exact-colour regions on such a frame (one line, naming the way out).
    """
    if params.segmentation == "colour" and params.max_regions:
        count = frame_regions(rgb, params)[1]
        if count > COLOUR_EXCESS * params.max_regions:
            raise SegmentationError(
                f"segmentation colour: the first frame has {count} exact-colour regions (limit {COLOUR_EXCESS} x "
                f"max_regions = {COLOUR_EXCESS * params.max_regions}): its colours are noisy or compressed; "
                f"use segmentation:=felzenszwalb")
    notes: list[SetupNote] = []
    weighed = _chroma_weighed(rgb, params)
    if weighed != params:
        weight = ("as much as brightness" if weighed.chroma_weight == 1
                  else f"{weighed.chroma_weight:.2f} times brightness")
        notes.append(SetupNote(f"segmentation: chroma weighed {weight} in colour distances, fitted on the first "
                               f"frame (chroma_weight)"))
    used, count = _fitted(rgb, weighed)
    if used.k != params.k:
        notes.append(SetupNote(f"segmentation: k raised from {params.k:g} to {used.k:g}: the first frame had more "
                               f"than {params.max_regions} regions (max_regions)"))
    if count is not None and count < FEW_REGIONS:
        regions = f"{count} region" + ("s" if count != 1 else "")
        notes.append(SetupNote(f"segmentation: the first frame has only {regions} at k {used.k:g}: objects may share "
                               f"giant regions with the background and go untracked; a smaller k "
                               f"(-p k:={used.k / 2:g}) cuts finer", warns=True))
    return used, notes


def _chroma_weighed(rgb: np.ndarray, params: TrapParams) -> TrapParams:
    """``params`` with a ``chroma_weight`` of 0 (fit it) replaced by the one fitted on ``rgb``
    (:func:`fitted_chroma_weight`). A video's is fitted on its first frame (:func:`first_frame_setup`);
    a frame given on its own gets its own. At the frame's own size: scaled up by nearest pixels,
    most neighbours would repeat one pixel and nothing would seem to vary."""
    if params.segmentation != "felzenszwalb" or params.chroma_weight != 0:
        return params
    return dataclasses.replace(params, chroma_weight=fitted_chroma_weight(rgb, params.colour_space))


def _fitted(rgb: np.ndarray, params: TrapParams) -> tuple[TrapParams, int | None]:
    """:func:`fitted_to_regions`, and the frame's count of Felzenszwalb regions with the
    parameters it gives (None for exact-colour regions); each ``k`` is tried once."""
    if params.segmentation != "felzenszwalb":
        return params, None
    small = _working_size(rgb, params)
    counts: dict[float, int] = {}

    def count(k: float) -> int:
        if k not in counts:
            counts[k] = _regions(small, dataclasses.replace(params, k=k))[1]
        return counts[k]

    def fits(k: float) -> bool:
        return count(k) <= params.max_regions
    if not params.max_regions or fits(params.k):
        return params, count(params.k)
    low, high = max(params.k, 1e-3), max(2 * params.k, 1.0)
    while not fits(high) and high < MAX_K:
        low, high = high, 2 * high
    while high > 1.02 * low:
        middle = float(np.sqrt(low * high))
        low, high = (low, middle) if fits(middle) else (middle, high)
    k = round(high, 3)
    return dataclasses.replace(params, k=k), count(k)


def _working_size(rgb: np.ndarray, params: TrapParams) -> np.ndarray:
    """The frame at the size it is segmented: its longer side scaled (nearest pixels) to ``params.max_side``."""
    height, width = rgb.shape[:2]
    working = params.working_side(width, height)
    if working is None:
        return rgb
    factor = working / max(height, width)
    size = (max(1, round(width * factor)), max(1, round(height * factor)))
    return cv2.resize(rgb, size, interpolation=cv2.INTER_NEAREST)


def _regions(small: np.ndarray, params: TrapParams) -> tuple[np.ndarray, int]:
    """Region label of each pixel of ``small`` (the frame at its working size), and their count."""
    if params.segmentation == "colour":
        return colour_components(small)
    return felzenszwalb(small, k=params.k, sigma=params.sigma, min_size=params.min_size,
                        threshold=params.threshold, connectivity=params.connectivity, mean_gap=params.mean_gap,
                        colour_space=params.colour_space, chroma_weight=params.chroma_weight)


def _in_frame_pixels(graph: PlaneGraph, scale_x: float, scale_y: float) -> PlaneGraph:
    """``graph`` of a frame segmented at 1/``scale`` of its size (a scale below 1: scaled up), with
    positions, boxes, areas and contact lengths in the frame's pixels. Boxes hold every frame pixel a
    region's pixels cover: scaled down, a working pixel covers a block of them; scaled up, it
    shows the frame pixel its position rounds down to (``cv2.INTER_NEAREST``), and the block's
    end would add a pixel to every box."""
    centroid = (graph.centroid + 0.5) * np.array([scale_x, scale_y], dtype=np.float32) - 0.5
    box = graph.bbox.astype(float)
    bbox = np.column_stack([np.floor(box[:, 0] * scale_x), np.floor(box[:, 1] * scale_y),
                            _last_pixel(box[:, 2], scale_x), _last_pixel(box[:, 3], scale_y)])
    return dataclasses.replace(
        graph, centroid=centroid.astype(np.float32), bbox=bbox.astype(np.int32),
        area=np.rint(graph.area * scale_x * scale_y).astype(np.int32),
        he_length=np.maximum(1, np.rint(graph.he_length * np.sqrt(scale_x * scale_y))).astype(np.int32))


def _last_pixel(last: np.ndarray, scale: float) -> np.ndarray:
    """The last frame pixel of a box whose last working pixel is ``last`` (:func:`_in_frame_pixels`)."""
    return np.floor(last * scale) if scale < 1 else np.ceil((last + 1) * scale) - 1


def graphs_of(frames: Iterable[np.ndarray], params: TrapParams,
              told: Callable[[TrapParams, list[SetupNote]], None] | None = None,
              image_steps: bool | None = None) -> Iterator[PlaneGraph]:
    """Plane graph of each frame, in order, with the parameters :func:`first_frame_setup` gives
    on the first frame and the camera's step from the frame before (:func:`frame_graph`) where
    ``image_steps`` (by default where tracking with ``params`` reads them,
    :attr:`TrapParams.reads_image_steps`); where :func:`first_frame_setup` has lines for the
    user, they and those parameters are passed to ``told`` (the run prints them and reports the
    ``k`` it used). If ``frames`` fails (a bad frame in a bag), the graphs of the frames before
    it are still given, then the error is raised."""
    if image_steps is None:
        image_steps = params.reads_image_steps
    failure: list[Exception] = []  # raised once the frames in flight are made

    def calls() -> Iterator[tuple]:
        """``frame_graph``'s arguments for each frame, the first frame's setup made on it."""
        nonlocal params
        previous = None
        source = iter(frames)
        first = True
        while True:
            try:
                rgb = next(source)
            except StopIteration:
                return
            except Exception as error:
                failure.append(error)
                return
            if first:
                first, (params, notes) = False, first_frame_setup(rgb, params)
                if told is not None and notes:
                    told(params, notes)
            yield rgb, params, previous
            previous = rgb if image_steps else None

    with ThreadPoolExecutor(params.threads, thread_name_prefix="trap-graph") as pool:
        yield from in_order(pool, frame_graph, calls(), params.threads)
    if failure:
        raise failure[0]


def synthetic_graphs(config: SceneConfig, params: TrapParams, compressed: str | None = None, encoding: str = "rgb8",
                     ) -> tuple[list[PlaneGraph], list[dict[int, tuple]]]:
    """Plane graphs of a synthetic video and each object's ground-truth boxes (frame -> x, y, w,
    h): what tests and quality benchmarks track and score, without writing a bag. ``compressed``
    (``jpeg`` or ``png``): each frame is compressed and decoded first, as a bag of
    ``sensor_msgs/CompressedImage`` would bring it; else ``encoding``: each frame is encoded so and
    decoded, as a ``sensor_msgs/Image`` of that encoding would bring it (``yuv422`` halves the
    colour's resolution across, a Bayer pattern keeps one colour a pixel)."""
    truth: list[dict[int, tuple]] = [{} for _ in range(config.objects)]
    return list(graphs_of(synthetic_frames(config, compressed, truth, encoding), params)), truth


def synthetic_frames(config: SceneConfig, compressed: str | None = None,
                     truth: list[dict[int, tuple]] | None = None, encoding: str = "rgb8") -> Iterator[np.ndarray]:
    """The RGB frames of a synthetic video, each compressed (or encoded) and decoded first as
    :func:`synthetic_graphs` takes them; each object's box in each frame is written into
    ``truth`` (one dict per object) when given."""
    for frame in delivered_frames(config, compressed, encoding):
        if truth is not None:
            for obj, box in enumerate(frame.boxes):
                if box:
                    truth[obj][frame.index] = box
        yield frame.rgb


def delivered_frames(config: SceneConfig, compressed: str | None = None, encoding: str = "rgb8",
                     ) -> Iterator[RenderedFrame]:
    """The frames of a synthetic video with their ground truth (boxes and each pixel's object),
    their pixels compressed (or encoded) and decoded first as :func:`synthetic_frames` gives them."""
    for frame in render(config):
        yield dataclasses.replace(frame, rgb=_as_delivered(frame.rgb, compressed, encoding))


def _as_delivered(rgb: np.ndarray, compressed: str | None, encoding: str) -> np.ndarray:
    """``rgb`` as a subscriber decodes it from a message: compressed as ``compressed``, or in the
    raw ``encoding``."""
    if compressed is not None:
        return decode_compressed(compressed, compress_image(rgb, compressed))
    if encoding.lower() == "rgb8":
        return rgb
    payload, step = encode_image(rgb, encoding)
    return decode_image(encoding, rgb.shape[0], rgb.shape[1], step, payload)
