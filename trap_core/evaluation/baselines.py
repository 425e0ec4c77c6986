"""Supervised box trackers from OpenCV, started from the first ground-truth box of each object.

The paper compared TRAP with TLD and CT; CT is not in OpenCV, so TLD, MedianFlow, KCF, CSRT and
MIL stand in (opencv-contrib). They see the same frames as TRAP.
"""
from __future__ import annotations

from collections.abc import Callable, Iterable

import cv2
import numpy as np

TRACKERS: dict[str, Callable[[], object]] = {
    "TLD": lambda: cv2.legacy.TrackerTLD_create(),
    "MedianFlow": lambda: cv2.legacy.TrackerMedianFlow_create(),
    "KCF": lambda: cv2.TrackerKCF_create(),
    "CSRT": lambda: cv2.TrackerCSRT_create(),
    "MIL": lambda: cv2.TrackerMIL_create(),
}


def run_baselines(frames: Iterable[np.ndarray], truth: list[dict[int, tuple]], names: Iterable[str] = TRACKERS,
                  ) -> dict[str, list[dict[int, tuple]]]:
    """Boxes ``{frame: (x, y, w, h)}`` of every tracker for every object (one pass over ``frames``).

    Each tracker starts on an object at the first frame where the object has a ground-truth
    box, and reports a box wherever it claims to see it.
    """
    names = list(names)
    starts = [min(t) if t else None for t in truth]
    boxes: dict[str, list[dict[int, tuple]]] = {n: [{} for _ in truth] for n in names}
    live: dict[tuple[str, int], object] = {}
    for index, rgb in enumerate(frames):
        bgr = cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR)
        for obj, start in enumerate(starts):
            for name in names:
                if index == start:
                    tracker = TRACKERS[name]()
                    x, y, w, h = (int(v) for v in truth[obj][start])
                    tracker.init(bgr, (x, y, max(w, 1), max(h, 1)))
                    live[(name, obj)] = tracker
                    boxes[name][obj][index] = (x, y, w, h)
                elif (name, obj) in live:
                    ok, box = live[(name, obj)].update(bgr)
                    if ok:
                        boxes[name][obj][index] = tuple(float(v) for v in box)
    return boxes
