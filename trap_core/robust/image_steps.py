"""The camera's motion between two frames, read from the images themselves.

Beyond the paper (TRAP_SPEC section 10, "object versus background": "a homography between
frames"). :mod:`trap_core.robust.camera` reads the camera's motion from the patterns and the
regions; over a smooth scene (a colour wheel, a sky, a retina at 320x240) nearly all of them lie
on the objects, and the motion read from them follows an object, which then stands still in the
world and goes untracked (README, "A smooth background with few regions": 2-3 px a frame off
the true pan over the colour wheel). The image's grey levels vary over such a background even
where no region boundary lies, and optical flow reads the pan from them: pyramidal Lucas-Kanade
at the points of a regular grid (not at corners, which a smooth background has none of), fitted
by the same grid vote as the patterns (:func:`~trap_core.robust.camera.similarity_step`): each
cell of the frame votes once, so the objects' points, however many, are outliers. Over the
benchmark scenes that only pan, the error is 0.00-0.03 px a frame, the colour wheel included
(``benchmarks/camera_motion.py``).
"""
from __future__ import annotations

import cv2
import numpy as np

from trap_core.rag import unknown_step
from trap_core.robust.camera import similarity_step

FLOW_SIDE = 320  # px: frames are read for the camera's motion with their longer side at most this
FLOW_SPACING = 16  # px at that size between the grid points the flow is read at (300 points in 320x240)
FLOW_WINDOW = 15  # px at that size: side of the Lucas-Kanade window
FLOW_LEVELS = 3  # pyramid levels below the frame: steps up to about 2^3 windows are read
FLOW_MIN_EIG = 1e-5  # Lucas-Kanade's own texture test (smallest eigenvalue of a window's gradients, per pixel),
# a tenth of OpenCV's default: a smooth background's gradients are weak, yet its flow reads true (the grid vote
# rejects what it reads wrong)
MIN_POINTS = 12  # fewer points tracked: the step is not read (the patterns' fit stands)


def image_step(previous: np.ndarray, current: np.ndarray) -> np.ndarray:
    """(2, 3) similarity taking pixel positions of frame ``previous`` to where the scene shows in
    frame ``current`` (both (H, W, 3) uint8 RGB, as every stage takes them), or :func:`unknown_step`.

    Both frames are read at their longer side scaled down to ``FLOW_SIDE`` (averaging: a cheap
    low-pass that also steadies the flow under sensor noise) and the step is given back in the
    frames' pixels. Points Lucas-Kanade cannot follow (flat areas) are left out; of the others,
    the grid vote keeps the motion most of the frame agrees on: objects, occlusions and the
    aperture problem along straight edges are outliers to it. (Tracking each point back and
    keeping those that land within half a pixel of their start was tried: the same error on the
    hardest scenes, at 1.7 times the time.)
    """
    if previous.shape != current.shape:
        return unknown_step()
    a, b = _flow_image(previous), _flow_image(current)
    height, width = a.shape
    if min(height, width) < FLOW_WINDOW:
        return unknown_step()
    scale = np.array([previous.shape[1] / width, previous.shape[0] / height])  # frame pixels per flow pixel
    ys, xs = np.mgrid[FLOW_SPACING // 2:height:FLOW_SPACING, FLOW_SPACING // 2:width:FLOW_SPACING]
    start = np.column_stack([xs.ravel(), ys.ravel()]).astype(np.float32).reshape(-1, 1, 2)
    there, found, _ = cv2.calcOpticalFlowPyrLK(a, b, start, None, winSize=(FLOW_WINDOW, FLOW_WINDOW),
                                               maxLevel=FLOW_LEVELS, minEigThreshold=FLOW_MIN_EIG)
    kept = found.ravel() == 1
    if kept.sum() < MIN_POINTS:
        return unknown_step()
    src = ((start.reshape(-1, 2)[kept] + 0.5) * scale - 0.5).astype(np.float32)  # pixel centres, frame pixels
    dst = ((there.reshape(-1, 2)[kept] + 0.5) * scale - 0.5).astype(np.float32)
    fitted = similarity_step(src, dst, np.array(previous.shape[1::-1], dtype=np.float32))
    return unknown_step() if fitted is None else fitted.astype(np.float64)


def _flow_image(rgb: np.ndarray) -> np.ndarray:
    """``rgb`` in grey at its flow size (longer side at most ``FLOW_SIDE``)."""
    grey = cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)
    factor = FLOW_SIDE / max(grey.shape)
    if factor >= 1:
        return grey
    size = (max(1, round(grey.shape[1] * factor)), max(1, round(grey.shape[0] * factor)))
    return cv2.resize(grey, size, interpolation=cv2.INTER_AREA)
