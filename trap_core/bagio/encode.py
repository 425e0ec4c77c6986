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


_FROM_RGB = {"bgr8": cv2.COLOR_RGB2BGR, "8uc3": cv2.COLOR_RGB2BGR, "rgba8": cv2.COLOR_RGB2RGBA,
             "bgra8": cv2.COLOR_RGB2BGRA, "8uc4": cv2.COLOR_RGB2BGRA, "mono8": cv2.COLOR_RGB2GRAY,
             "8uc1": cv2.COLOR_RGB2GRAY, "yuv422": cv2.COLOR_RGB2YUV_UYVY, "yuv422_yuy2": cv2.COLOR_RGB2YUV_YUY2}
# 16-bit encoding -> the 8-bit one whose samples it spreads over 16 bits
_WIDE = {"rgb16": "rgb8", "bgr16": "bgr8", "rgba16": "rgba8", "bgra16": "bgra8", "mono16": "mono8",
         "16uc1": "8uc1", **{name[:-1] + "16": name for name in _BAYER_TILES}}


def encode_image(rgb: np.ndarray, encoding: str, sample_bits: int = 16) -> tuple[np.ndarray, int]:
    """Return ``(payload bytes as uint8 array, step)`` of ``rgb`` in a ROS raw encoding.

    16-bit encodings spread the 8-bit samples over ``sample_bits`` significant bits (16: the full
    range; 10, 12 or 14: what many cameras write in 16-bit samples).
    """
    if encoding in _WIDE:
        if not 8 <= sample_bits <= 16:
            raise BagError(f"sample_bits must be within 8..16, not {sample_bits}")
        narrow, _ = encode_image(rgb, _WIDE[encoding])
        top = (1 << sample_bits) - 1
        wide = np.rint(narrow.astype(np.float64) * (top / 255)).astype("<u2")
        payload = wide.view(np.uint8).reshape(rgb.shape[0], -1)
        return payload.reshape(-1), payload.shape[1]
    if encoding == "rgb8":
        pixels = rgb
    elif encoding in _FROM_RGB:
        pixels = cv2.cvtColor(rgb, _FROM_RGB[encoding])
    elif encoding in _BAYER_TILES:
        pixels = mosaic(rgb, encoding)
    elif encoding == "nv21":
        pixels = _nv21(rgb)
    else:
        raise BagError(f"cannot encode frames as {encoding!r}")
    payload = np.ascontiguousarray(pixels).reshape(pixels.shape[0], -1)
    return payload.reshape(-1), payload.shape[1]


def _nv21(rgb: np.ndarray) -> np.ndarray:
    """Y plane, then V and U interleaved at half width and height (1.5 x height rows)."""
    height, width = rgb.shape[:2]
    planar = cv2.cvtColor(rgb, cv2.COLOR_RGB2YUV_I420).reshape(-1)  # Y, then U, then V planes
    luma, quarter = height * width, height * width // 4
    chroma = np.empty(2 * quarter, dtype=np.uint8)
    chroma[0::2] = planar[luma + quarter:]
    chroma[1::2] = planar[luma:luma + quarter]
    return np.concatenate([planar[:luma], chroma]).reshape(height * 3 // 2, width)


def compress_image(rgb: np.ndarray, fmt: str, jpeg_quality: int = 90) -> np.ndarray:
    """Compress ``rgb`` as ``jpeg`` or ``png`` (payload of a ``sensor_msgs/CompressedImage``)."""
    if fmt not in ("jpeg", "png"):
        raise BagError(f"cannot compress frames as {fmt!r} (jpeg or png)")
    params = [cv2.IMWRITE_JPEG_QUALITY, jpeg_quality] if fmt == "jpeg" else []
    ok, buffer = cv2.imencode("." + ("jpg" if fmt == "jpeg" else "png"), cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR), params)
    if not ok:
        raise BagError(f"{fmt} encoding failed")
    return buffer.reshape(-1)
