"""Felzenszwalb-Huttenlocher graph segmentation with the paper's constant threshold."""
from __future__ import annotations

import cv2
import numpy as np

from trap_core.segmentation._kernels import compact_labels, felzenszwalb_kernel, relabel_4connected
from trap_core.segmentation.errors import SegmentationError

THRESHOLD_MODES = ("constant", "size")
COLOUR_SPACES = ("rgb", "lab")
# CIELAB distances (CIE76 delta E) times this weigh a step between two greys about as RGB
# distances do (a grey's L* changes by ~0.39 per unit of each channel, its RGB distance by
# sqrt(3)), so that ``k`` keeps its scale in either colour space.
LAB_SCALE = 4.4
# Brightness and two chroma axes of RGB, orthonormal: distances between pixels are RGB's until
# the chroma axes are weighed (``chroma_weight``).
OPPONENT_AXES = np.array([[1, 1, 1] / np.sqrt(3), [1, -1, 0] / np.sqrt(2), [1, 1, -2] / np.sqrt(6)], dtype=np.float32)
# A fitted chroma weight is at most this: independent noise in each channel, two thirds of it
# chroma, then weighs sqrt(3) times as much as in RGB, where CIELAB weighs it 2-3 times as much.
MAX_CHROMA_WEIGHT = 2.0


def felzenszwalb(rgb: np.ndarray, k: float = 7.0, sigma: float = 0.8, min_size: int = 20,
                 threshold: str = "constant", connectivity: int = 4, mean_gap: float = 0.0,
                 colour_space: str = "rgb", chroma_weight: float = 1.0) -> tuple[np.ndarray, int]:
    """Segment an RGB frame into regions (TRAP_SPEC section 1).

    Parameters
    ----------
    rgb : (H, W, 3) uint8 array
        The frame.
    k : float
        Threshold constant. ``threshold='constant'``: ``tau(C) = k``, in colour-distance units
        (the paper's size-independent variant; small values, ~5-30). ``'size'``: the original
        ``tau(C) = k / |C|`` (k in units x pixels, ~100-1000).
    sigma : float
        Gaussian smoothing before segmentation (0 disables it).
    min_size : int
        Regions smaller than this are merged into a neighbour afterwards.
    threshold : {'constant', 'size'}
        Threshold mode, see ``k``.
    connectivity : {4, 8}
        Pixel graph of the segmentation. 4 (default) is the plane graph's adjacency and the
        faster; 8 is what skimage and cv2.ximgproc use (regions that then touch only
        diagonally are split, as the plane graph needs 4-connected regions).
    mean_gap : float
        ``threshold='constant'`` only (ours): two regions of at least ``min_size`` pixels merge
        only if their mean colours are at most ``mean_gap * k`` apart; 0 disables it (the
        paper's rule alone). Smoothing, and the halved colour resolution of JPEG and video
        codecs, leave colour ramps along edges: each step is small, and a region merges along
        one step at a time, its largest step ``Int`` growing as it goes, until it is merged
        with a differently coloured neighbour (a coloured object with a grey textured ground).
    colour_space : {'rgb', 'lab'}
        Where colour distances are measured: RGB (the paper's) or CIELAB (ours), scaled by
        ``LAB_SCALE`` so that steps between greys weigh as in RGB. In RGB a change of hue at
        one brightness (a coloured object on a ground of its brightness, the blurred chroma
        edges of JPEG) is short next to the brightness steps of texture; in CIELAB distances
        follow what the eye tells apart.
    chroma_weight : float
        Weight of the two chroma axes against brightness (ours): the opponent axes of RGB
        (``OPPONENT_AXES``) or CIELAB's a* and b*. 1 keeps the colour space's distances;
        :func:`fitted_chroma_weight` chooses one for a video.

    Returns
    -------
    labels : (H, W) int32 array
        Region of each pixel, 0..n-1, every region 4-connected.
    n : int
        Number of regions.

    Notes
    -----
    Compiled (numba, GIL released): two threads segment two frames at once. Edges are ordered
    by a counting sort on weights quantised to 1/16 colour unit, O(pixels).

    References
    ----------
    P. F. Felzenszwalb, D. P. Huttenlocher, "Efficient graph-based image segmentation",
    IJCV 59(2), 2004.
    """
    if threshold not in THRESHOLD_MODES:
        raise SegmentationError(f"threshold must be one of {THRESHOLD_MODES}, not {threshold!r}")
    if connectivity not in (4, 8):
        raise SegmentationError(f"connectivity must be 4 or 8, not {connectivity}")
    if not (np.isfinite(k) and k >= 0 and np.isfinite(sigma) and sigma >= 0 and min_size >= 0
            and np.isfinite(mean_gap) and mean_gap >= 0):
        raise SegmentationError(f"need k >= 0, sigma >= 0, min_size >= 0, mean_gap >= 0 (got k={k}, "
                                f"sigma={sigma}, min_size={min_size}, mean_gap={mean_gap})")
    _check_colour_space(colour_space)
    if not (np.isfinite(chroma_weight) and chroma_weight > 0):
        raise SegmentationError(f"chroma_weight must be > 0, not {chroma_weight}")
    _check_frame(rgb)
    if colour_space == "rgb" and chroma_weight == 1:
        image = rgb.astype(np.float32)  # the paper's distances, as they always were computed
    else:
        image = _colour_axes(rgb, colour_space)
        image[..., 1:] *= chroma_weight
    if sigma > 0:
        image = cv2.GaussianBlur(image, (0, 0), sigmaX=sigma, sigmaY=sigma, borderType=cv2.BORDER_REFLECT)
    max_mean_distance = float(mean_gap * k) if threshold == "constant" else 0.0
    raw = felzenszwalb_kernel(image, float(k), int(min_size), threshold == "size", int(connectivity),
                              max_mean_distance)
    # 4-connected merging yields 4-connected regions; 8-connected ones may touch only diagonally.
    return compact_labels(raw) if connectivity == 4 else relabel_4connected(raw)


def _check_frame(rgb: np.ndarray) -> None:
    if rgb.ndim != 3 or rgb.shape[0] == 0 or rgb.shape[1] == 0 or rgb.shape[2] != 3:
        raise SegmentationError(f"expected an (H, W, 3) image, got shape {rgb.shape}")


def _check_colour_space(colour_space: str) -> None:
    if colour_space not in COLOUR_SPACES:
        raise SegmentationError(f"colour_space must be one of {COLOUR_SPACES}, not {colour_space!r}")


def _colour_axes(rgb: np.ndarray, colour_space: str) -> np.ndarray:
    """``rgb`` as float32 in axes whose Euclidean distances are the colour space's, brightness first
    and chroma after: RGB's opponent axes (``OPPONENT_AXES``) or scaled CIELAB (``LAB_SCALE``)."""
    image = rgb.astype(np.float32)
    if colour_space == "lab":
        return LAB_SCALE * cv2.cvtColor(image / 255.0, cv2.COLOR_RGB2Lab)
    return image @ OPPONENT_AXES.T


def fitted_chroma_weight(rgb: np.ndarray, colour_space: str = "rgb") -> float:
    """The chroma weight (``felzenszwalb``) that gives a frame's chroma axes the spread its
    brightness has between neighbouring pixels, within 1..``MAX_CHROMA_WEIGHT`` (ours).

    What separates neighbouring pixels of one surface is noise, texture and compression. Noise
    drawn independently in each channel spreads as much along chroma as along brightness, and
    RGB distances (weight 1) are right for it. Camera and codec pipelines keep chroma at half
    resolution and smooth it (JPEG, 4:2:0 video), and textured grounds (grass, gravel, roads)
    vary mostly in brightness: chroma then spreads less, and the hue edge between an object and
    a ground of its brightness is blurred into steps small next to the ground's brightness
    steps, which Felzenszwalb's rule merges across. Weighing chroma by the ratio of the spreads
    (median absolute deviation of neighbour differences, which edges barely move) measures
    every axis in units of what varies within a surface. The cap keeps a frame with no chroma
    variation at all (grey texture) from weighing the least chroma change without bound.
    """
    _check_colour_space(colour_space)
    _check_frame(rgb)
    image = _colour_axes(rgb, colour_space)
    steps = np.concatenate([(image[:, 1:] - image[:, :-1]).reshape(-1, 3),
                            (image[1:] - image[:-1]).reshape(-1, 3)])
    spread = np.median(np.abs(steps - np.median(steps, axis=0)), axis=0)
    brightness, chroma = float(spread[0]), float(np.sqrt((spread[1] ** 2 + spread[2] ** 2) / 2))
    if brightness <= chroma:
        return 1.0
    return MAX_CHROMA_WEIGHT if chroma == 0 else float(min(brightness / chroma, MAX_CHROMA_WEIGHT))
