"""Encode RGB uint8 frames as ``sensor_msgs/Image`` payloads or compressed images.

The inverse of :mod:`trap_core.bagio.decode`: the synthetic video writer uses it to produce
bags in any supported encoding, and the tests use it to check every decoder.
"""
from __future__ import annotations

import cv2
import numpy as np

from trap_core.bagio.errors import BagError

# Position of R, G, B samples in a 2x2 Bayer tile, as (row, col) per channel index.
_BAYER_TILES = {
    "bayer_rggb8": {0: (0, 0), 1: ((0, 1), (1, 0)), 2: (1, 1)},
    "bayer_bggr8": {0: (1, 1), 1: ((0, 1), (1, 0)), 2: (0, 0)},
    "bayer_gbrg8": {0: (1, 0), 1: ((0, 0), (1, 1)), 2: (0, 1)},
    "bayer_grbg8": {0: (0, 1), 1: ((0, 0), (1, 1)), 2: (1, 0)},
}


def mosaic(rgb: np.ndarray, encoding: str) -> np.ndarray:
    """Sample an RGB frame through a Bayer colour filter (what a raw sensor would record)."""
    tile = _BAYER_TILES[encoding]
    raw = np.empty(rgb.shape[:2], dtype=np.uint8)
    r_row, r_col = tile[0]
    b_row, b_col = tile[2]
    raw[r_row::2, r_col::2] = rgb[r_row::2, r_col::2, 0]
    raw[b_row::2, b_col::2] = rgb[b_row::2, b_col::2, 2]
    for g_row, g_col in tile[1]:
        raw[g_row::2, g_col::2] = rgb[g_row::2, g_col::2, 1]
    return raw


def encode_image(rgb: np.ndarray, encoding: str) -> tuple[np.ndarray, int]:
    """Return ``(payload bytes as uint8 array, step)`` of ``rgb`` in a ROS raw encoding."""
    gray = None
    if encoding in ("mono8", "mono16"):
        gray = cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)
    if encoding == "rgb8":
        pixels = rgb
    elif encoding == "bgr8":
        pixels = cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR)
    elif encoding == "rgba8":
        pixels = cv2.cvtColor(rgb, cv2.COLOR_RGB2RGBA)
    elif encoding == "bgra8":
        pixels = cv2.cvtColor(rgb, cv2.COLOR_RGB2BGRA)
    elif encoding == "mono8":
        pixels = gray
    elif encoding == "mono16":
        pixels = (gray.astype("<u2") * 257).view(np.uint8).reshape(gray.shape[0], -1)
    elif encoding in _BAYER_TILES:
        pixels = mosaic(rgb, encoding)
    else:
        raise BagError(f"cannot encode frames as {encoding!r}")
    payload = np.ascontiguousarray(pixels).reshape(rgb.shape[0], -1)
    return payload.reshape(-1), payload.shape[1]


def compress_image(rgb: np.ndarray, fmt: str, jpeg_quality: int = 90) -> np.ndarray:
    """Compress ``rgb`` as ``jpeg`` or ``png`` (payload of a ``sensor_msgs/CompressedImage``)."""
    if fmt not in ("jpeg", "png"):
        raise BagError(f"cannot compress frames as {fmt!r} (jpeg or png)")
    params = [cv2.IMWRITE_JPEG_QUALITY, jpeg_quality] if fmt == "jpeg" else []
    ok, buffer = cv2.imencode("." + ("jpg" if fmt == "jpeg" else "png"), cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR), params)
    if not ok:
        raise BagError(f"{fmt} encoding failed")
    return buffer.reshape(-1)
