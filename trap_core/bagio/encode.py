"""Encode RGB uint8 frames as ``sensor_msgs/Image`` payloads or compressed images.

The inverse of :mod:`trap_core.bagio.decode`: the synthetic video writer uses it to produce
bags in any supported encoding, and the tests use it to check every decoder.
"""
from __future__ import annotations

import cv2
import numpy as np

from trap_core.bagio.compressed_depth import compress_depth, is_compressed_depth
from trap_core.bagio.decode import _CV_DEPTHS
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
# encoding of wide samples -> (the 8-bit one whose samples it spreads, its sample type)
_WIDE = {"rgb16": ("rgb8", "u2"), "bgr16": ("bgr8", "u2"), "rgba16": ("rgba8", "u2"), "bgra16": ("bgra8", "u2"),
         "mono16": ("mono8", "u2"), **{name[:-1] + "16": (name, "u2") for name in _BAYER_TILES},
         **{f"{depth}c{channels}": (f"8uc{channels}", sample)
            for depth, sample in _CV_DEPTHS.items() if depth != "8u" for channels in (1, 3, 4)}}
COMPRESSED_FORMATS = ("jpeg", "png", "16UC1; compressedDepth png", "16UC1; compressedDepth rvl",
                      "32FC1; compressedDepth png", "32FC1; compressedDepth rvl")


def encode_image(rgb: np.ndarray, encoding: str, sample_bits: int | None = None) -> tuple[np.ndarray, int]:
    """Return ``(payload bytes as uint8 array, step)`` of ``rgb`` in a ROS raw encoding.

    Integer encodings wider than 8 bits spread the 8-bit samples over ``sample_bits`` significant
    bits (None: the full width; 10, 12 or 14: what many cameras write in 16-bit samples), from 0
    (unsigned) or centred on 0 (signed); floating-point ones hold them as 0..1. Encoding names are
    case-insensitive, as in :func:`trap_core.bagio.decode_image`.
    """
    encoding = encoding.lower()
    if encoding in _WIDE:
        narrow_encoding, sample = _WIDE[encoding]
        narrow, _ = encode_image(rgb, narrow_encoding)
        wide = _spread(narrow, np.dtype(sample), sample_bits)
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


def _spread(narrow: np.ndarray, dtype: np.dtype, sample_bits: int | None) -> np.ndarray:
    """8-bit samples as little-endian ``dtype`` ones (see :func:`encode_image`)."""
    if dtype.kind == "f":
        if sample_bits is not None:
            raise BagError("sample_bits is for integer samples; floating-point ones hold 0..1")
        return (narrow / 255.0).astype(dtype.newbyteorder("<"))
    bits = 8 * dtype.itemsize if sample_bits is None else sample_bits
    if not 8 <= bits <= 8 * dtype.itemsize:
        raise BagError(f"sample_bits must be within 8..{8 * dtype.itemsize} for {dtype.itemsize}-byte samples, "
                       f"not {sample_bits}")
    low = -(1 << (bits - 1)) if dtype.kind == "i" else 0
    return np.rint(low + narrow.astype(np.float64) * (((1 << bits) - 1) / 255)).astype(dtype.newbyteorder("<"))


def compress_image(rgb: np.ndarray, fmt: str, jpeg_quality: int = 90) -> np.ndarray:
    """Compress ``rgb`` in one of :data:`COMPRESSED_FORMATS` (payload of a
    ``sensor_msgs/CompressedImage``); as depth, its grey is 0.5 m (black) to 5.6 m (white)."""
    if is_compressed_depth(fmt):
        return compress_depth(0.5 + cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY).astype(np.float32) * np.float32(0.02), fmt)
    if fmt not in ("jpeg", "png"):
        raise BagError(f"cannot compress frames as {fmt!r} ({', '.join(COMPRESSED_FORMATS)})")
    params = [cv2.IMWRITE_JPEG_QUALITY, jpeg_quality] if fmt == "jpeg" else []
    ok, buffer = cv2.imencode("." + ("jpg" if fmt == "jpeg" else "png"), cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR), params)
    if not ok:
        raise BagError(f"{fmt} encoding failed")
    return buffer.reshape(-1)
