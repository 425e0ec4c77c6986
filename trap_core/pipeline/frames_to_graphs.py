"""Segmentation and plane graphs of a stream of frames, on several threads.

The compiled kernels release the GIL, so ``threads`` frames are segmented at once while the
caller keeps decoding; results come back in frame order, and at most ``2 * threads`` frames
are in flight (memory stays flat).
"""
from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Iterator
from concurrent.futures import Future, ThreadPoolExecutor

import numpy as np

from trap_core.pipeline.params import TrapParams
from trap_core.rag import PlaneGraph, build_plane_graph
from trap_core.segmentation import colour_components, felzenszwalb
from trap_core.synthetic import SceneConfig, render


def frame_graph(rgb: np.ndarray, params: TrapParams) -> PlaneGraph:
    """Regions (segmentation or exact colours) and their plane graph for one frame."""
    if params.segmentation == "colour":
        labels, n = colour_components(rgb)
    else:
        labels, n = felzenszwalb(rgb, k=params.k, sigma=params.sigma, min_size=params.min_size,
                                 threshold=params.threshold, connectivity=params.connectivity)
    return build_plane_graph(labels, n, rgb, params.colour_bins, params.contact_tolerance)


def graphs_of(frames: Iterable[np.ndarray], params: TrapParams) -> Iterator[PlaneGraph]:
    """Plane graph of each frame, in order."""
    with ThreadPoolExecutor(params.threads, thread_name_prefix="trap-graph") as pool:
        pending: deque[Future] = deque()
        for rgb in frames:
            pending.append(pool.submit(frame_graph, rgb, params))
            if len(pending) >= 2 * params.threads:
                yield pending.popleft().result()
        while pending:
            yield pending.popleft().result()


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
