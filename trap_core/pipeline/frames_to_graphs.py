"""Segmentation and plane graphs of a stream of frames, on several threads.

The compiled kernels release the GIL, so ``threads`` frames are segmented at once while the
caller keeps decoding; results come back in frame order, and at most ``2 * threads`` frames
are in flight (memory stays flat).
"""
from __future__ import annotations

import dataclasses
from collections import deque
from collections.abc import Iterable, Iterator
from concurrent.futures import Future, ThreadPoolExecutor

import cv2
import numpy as np

from trap_core.pipeline.params import TrapParams
from trap_core.rag import PlaneGraph, build_plane_graph
from trap_core.segmentation import colour_components, felzenszwalb
from trap_core.synthetic import SceneConfig, render


def frame_graph(rgb: np.ndarray, params: TrapParams) -> PlaneGraph:
    """Regions (segmentation or exact colours) and their plane graph for one frame.

    A frame whose longer side exceeds ``params.max_side`` is segmented at that size (nearest
    pixels: averaging would blend the colours along every edge into strips of regions of their
    own, and exact-colour regions must keep exact colours), so an object is cut into as many
    regions as at the size the defaults were made for, whatever the camera's resolution; the
    graph's geometry is then given back in the frame's own pixels.
    """
    height, width = rgb.shape[:2]
    small = rgb
    if params.max_side and max(height, width) > params.max_side:
        factor = params.max_side / max(height, width)
        size = (max(1, round(width * factor)), max(1, round(height * factor)))
        small = cv2.resize(rgb, size, interpolation=cv2.INTER_NEAREST)
    if params.segmentation == "colour":
        labels, n = colour_components(small)
    else:
        labels, n = felzenszwalb(small, k=params.k, sigma=params.sigma, min_size=params.min_size,
                                 threshold=params.threshold, connectivity=params.connectivity)
    graph = build_plane_graph(labels, n, small, params.colour_bins, params.contact_tolerance)
    return graph if small is rgb else _in_frame_pixels(graph, width / small.shape[1], height / small.shape[0])


def _in_frame_pixels(graph: PlaneGraph, scale_x: float, scale_y: float) -> PlaneGraph:
    """``graph`` of a frame segmented ``scale`` times smaller, with positions, boxes, areas and
    contact lengths in the frame's pixels (boxes: every pixel a region's pixels cover)."""
    centroid = (graph.centroid + 0.5) * np.array([scale_x, scale_y], dtype=np.float32) - 0.5
    box = graph.bbox.astype(float)
    bbox = np.column_stack([np.floor(box[:, 0] * scale_x), np.floor(box[:, 1] * scale_y),
                            np.ceil((box[:, 2] + 1) * scale_x) - 1, np.ceil((box[:, 3] + 1) * scale_y) - 1])
    return dataclasses.replace(
        graph, centroid=centroid.astype(np.float32), bbox=bbox.astype(np.int32),
        area=np.rint(graph.area * scale_x * scale_y).astype(np.int32),
        he_length=np.maximum(1, np.rint(graph.he_length * np.sqrt(scale_x * scale_y))).astype(np.int32))


def graphs_of(frames: Iterable[np.ndarray], params: TrapParams) -> Iterator[PlaneGraph]:
    """Plane graph of each frame, in order. If ``frames`` fails (a bad frame in a bag), the
    graphs of the frames before it are still given, then the error is raised."""
    failure: Exception | None = None
    with ThreadPoolExecutor(params.threads, thread_name_prefix="trap-graph") as pool:
        pending: deque[Future] = deque()
        source = iter(frames)
        while True:
            try:
                rgb = next(source)
            except StopIteration:
                break
            except Exception as error:  # raised once the frames in flight are made
                failure = error
                break
            pending.append(pool.submit(frame_graph, rgb, params))
            if len(pending) >= 2 * params.threads:
                yield pending.popleft().result()
        while pending:
            yield pending.popleft().result()
    if failure is not None:
        raise failure


def synthetic_graphs(config: SceneConfig, params: TrapParams) -> tuple[list[PlaneGraph], list[dict[int, tuple]]]:
    """Plane graphs of a synthetic video and each object's ground-truth boxes (frame -> x, y, w,
    h): what tests and quality benchmarks track and score, without writing a bag."""
    truth: list[dict[int, tuple]] = [{} for _ in range(config.objects)]

    def frames() -> Iterator[np.ndarray]:
        for frame in render(config):
            for obj, box in enumerate(frame.boxes):
                if box:
                    truth[obj][frame.index] = box
            yield frame.rgb

    return list(graphs_of(frames(), params)), truth
