#!/usr/bin/env python3
"""Benchmark: per-frame segmentation and plane-graph time against cv2.ximgproc and skimage.

Prints a Markdown table (and JSON with --json) of milliseconds per frame at 320x240 and
640x480 on natural images (skimage sample images), and frames per second with one and two
threads. Run: ``.venv/bin/python benchmarks/segmentation_graph.py``.
"""
from __future__ import annotations

import argparse
import json
import time
from concurrent.futures import ThreadPoolExecutor

import cv2
import numpy as np
import skimage.data
from skimage.segmentation import felzenszwalb as skimage_felzenszwalb

from trap_core.pipeline import TrapParams
from trap_core.rag import build_plane_graph
from trap_core.segmentation import colour_components, felzenszwalb
from trap_core.synthetic import SceneConfig, render

IMAGES = ("astronaut", "coffee", "chelsea", "rocket", "immunohistochemistry")


def _images(size: tuple[int, int]) -> list[np.ndarray]:
    return [cv2.resize(getattr(skimage.data, name)(), size, interpolation=cv2.INTER_AREA) for name in IMAGES]


def _ms_per_frame(function, images: list[np.ndarray], repeats: int) -> float:
    function(images[0])  # warm-up (compilation, caches)
    start = time.perf_counter()
    for _ in range(repeats):
        for image in images:
            function(image)
    return 1000 * (time.perf_counter() - start) / (repeats * len(images))


def _fps(function, images: list[np.ndarray], threads: int, repeats: int) -> float:
    work = images * repeats
    start = time.perf_counter()
    with ThreadPoolExecutor(threads) as pool:
        list(pool.map(function, work))
    return len(work) / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--json", action="store_true", help="also print the figures as JSON")
    args = parser.parse_args()
    results = {}
    k = TrapParams().k  # the default constant threshold
    constant = f"ours constant (k={k:g})"
    for size in ((320, 240), (640, 480)):
        images = _images(size)
        ximgproc = cv2.ximgproc.segmentation.createGraphSegmentation(sigma=0.8, k=300, min_size=20)
        bgr = [cv2.cvtColor(image, cv2.COLOR_RGB2BGR) for image in images]
        row = {
            constant: _ms_per_frame(lambda im: felzenszwalb(im, k=k), images, args.repeats),
            "ours size (k=300)": _ms_per_frame(lambda im: felzenszwalb(im, k=300, threshold="size"), images, args.repeats),
            "ours size 8-conn (k=300)": _ms_per_frame(
                lambda im: felzenszwalb(im, k=300, threshold="size", connectivity=8), images, args.repeats),
            "cv2.ximgproc (k=300)": _ms_per_frame(ximgproc.processImage, bgr, args.repeats),
            "skimage (scale=300)": _ms_per_frame(
                lambda im: skimage_felzenszwalb(im, scale=300, sigma=0.8, min_size=20), images, 1),
        }
        segmented = [felzenszwalb(image, k=k) for image in images]
        row["regions (ours constant)"] = float(np.mean([n for _, n in segmented]))
        row["plane graph + embedding"] = _ms_per_frame(
            lambda pair: build_plane_graph(pair[0], pair[1], pair[2]),
            [(labels, n, image) for (labels, n), image in zip(segmented, images)], args.repeats)
        both = lambda im: build_plane_graph(*felzenszwalb(im, k=k), im)  # noqa: E731
        row["fps 1 thread (seg+graph)"] = _fps(both, images, 1, args.repeats)
        row["fps 2 threads (seg+graph)"] = _fps(both, images, 2, args.repeats)
        results[f"{size[0]}x{size[1]}"] = row
    synthetic = [f.rgb for f in render(SceneConfig(frames=20, seed=1))]
    pairs = [(*colour_components(rgb), rgb) for rgb in synthetic]
    results["640x480 synthetic"] = {
        "exact-colour regions": _ms_per_frame(colour_components, synthetic, args.repeats),
        "regions (exact colour)": float(np.mean([n for _, n, _ in pairs])),
        "plane graph + embedding": _ms_per_frame(lambda p: build_plane_graph(*p), pairs, args.repeats),
    }
    columns = list(results)
    names = list(dict.fromkeys(name for row in results.values() for name in row))
    print("| ms per frame (unless named) | " + " | ".join(columns) + " |")
    print("|---" * (len(columns) + 1) + "|")
    for name in names:
        print(f"| {name} | " + " | ".join(f"{results[c][name]:.1f}" if name in results[c] else "" for c in columns) + " |")
    for column in columns[:2]:
        ratio = results[column][constant] / results[column]["cv2.ximgproc (k=300)"]
        speedup = results[column]["fps 2 threads (seg+graph)"] / results[column]["fps 1 thread (seg+graph)"]
        print(f"\n{column}: ours/ximgproc = {ratio:.2f}x time; 2 threads = {speedup:.2f}x frames per second")
    if args.json:
        print(json.dumps(results, indent=2))


if __name__ == "__main__":
    main()
