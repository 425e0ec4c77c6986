"""Exact-colour regions: what the paper uses on synthetic videos instead of a segmentation."""
from __future__ import annotations

import numpy as np

from trap_core.segmentation._kernels import relabel_4connected
from trap_core.segmentation.errors import SegmentationError


def colour_components(rgb: np.ndarray) -> tuple[np.ndarray, int]:
    """Label the 4-connected components of identical colour ("true coloured regions").

    Returns
    -------
    labels : (H, W) int32 array, 0..n-1
    n : int
    """
    if rgb.ndim != 3 or rgb.shape[0] == 0 or rgb.shape[1] == 0:
        raise SegmentationError(f"expected an (H, W, 3) image, got shape {rgb.shape}")
    packed = (rgb[..., 0].astype(np.int32) << 16) | (rgb[..., 1].astype(np.int32) << 8) | rgb[..., 2]
    return relabel_4connected(packed)
