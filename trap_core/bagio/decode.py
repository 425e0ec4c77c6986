"""Turn ``sensor_msgs/Image`` and ``sensor_msgs/CompressedImage`` payloads into RGB uint8 arrays.

Every later stage works on ``(H, W, 3)`` uint8 RGB, whatever the camera wrote; decoding
validates sizes first so that a malformed message is a :class:`BagError`, not a crash.
"""
from __future__ import annotations

import cv2
import numpy as np

from trap_core.bagio.errors import BagError

# OpenCV names Bayer patterns by the second row's first two pixels, ROS by the first row's;
# this table is the mapping cv_bridge uses (the 16-bit patterns keep their 8 high bits first).
_BAYER_TO_RGB = {
    f"bayer_{pattern}{bits}": code
    for pattern, code in (("rggb", cv2.COLOR_BayerBG2RGB), ("bggr", cv2.COLOR_BayerRG2RGB),
                          ("gbrg", cv2.COLOR_BayerGR2RGB), ("grbg", cv2.COLOR_BayerGB2RGB))
    for bits in (8, 16)
}
# encoding -> (channels, bytes per channel, conversion to RGB after 16-bit samples keep their
# high byte; None: already RGB). "8uc3"/"8uc4" are taken as BGR(A), as cv_bridge does; ROS's
# "yuv422" is UYVY and "yuv422_yuy2" YUYV; "nv21" is a Y plane then interleaved V, U at half size.
_LAYOUT = {
    "rgb8": (3, 1, None), "bgr8": (3, 1, cv2.COLOR_BGR2RGB), "rgba8": (4, 1, cv2.COLOR_RGBA2RGB),
    "bgra8": (4, 1, cv2.COLOR_BGRA2RGB), "8uc3": (3, 1, cv2.COLOR_BGR2RGB), "8uc4": (4, 1, cv2.COLOR_BGRA2RGB),
    "rgb16": (3, 2, None), "bgr16": (3, 2, cv2.COLOR_BGR2RGB), "rgba16": (4, 2, cv2.COLOR_RGBA2RGB),
    "bgra16": (4, 2, cv2.COLOR_BGRA2RGB),
    "mono8": (1, 1, cv2.COLOR_GRAY2RGB), "8uc1": (1, 1, cv2.COLOR_GRAY2RGB), "mono16": (1, 2, cv2.COLOR_GRAY2RGB),
    "16uc1": (1, 2, cv2.COLOR_GRAY2RGB),
    "yuv422": (2, 1, cv2.COLOR_YUV2RGB_UYVY), "yuv422_yuy2": (2, 1, cv2.COLOR_YUV2RGB_YUY2),
    "nv21": (1, 1, cv2.COLOR_YUV2RGB_NV21),
    **{name: (1, 2 if name.endswith("16") else 1, code) for name, code in _BAYER_TO_RGB.items()},
}
_CHROMA_PAIRS = ("yuv422", "yuv422_yuy2", "nv21")  # chroma shared by two columns (and two rows for nv21)
SUPPORTED_ENCODINGS: tuple[str, ...] = tuple(sorted(_LAYOUT))


def _pixel_rows(data: np.ndarray | bytes, height: int, width: int, step: int, encoding: str,
                big_endian: bool) -> np.ndarray:
    """View the payload as (rows, width[, channels]) after checking its size against the header
    (rows: ``height``, or 1.5 ``height`` for nv21's chroma plane); 16-bit samples as uint16."""
    if height <= 0 or width <= 0:
        raise BagError(f"image of size {width}x{height}: nothing to track in an empty frame")
    if encoding in _CHROMA_PAIRS and (width % 2 or (encoding == "nv21" and height % 2)):
        raise BagError(f"{encoding} image {width}x{height}: chroma is shared by pixel pairs, the size must be even")
    channels, depth, _ = _LAYOUT[encoding]
    rows_needed = height * 3 // 2 if encoding == "nv21" else height
    row_bytes = width * channels * depth
    if step < row_bytes:
        raise BagError(f"{encoding} image {width}x{height}: step {step} is shorter than a row ({row_bytes} bytes)")
    buffer = np.frombuffer(data, dtype=np.uint8)
    if buffer.size < rows_needed * step:
        raise BagError(f"{encoding} image {width}x{height}: {buffer.size} bytes of data, "
                       f"{'1.5 x ' if encoding == 'nv21' else ''}height x step needs {rows_needed * step}")
    rows = buffer[: rows_needed * step].reshape(rows_needed, step)[:, :row_bytes]
    if depth == 2:
        dtype = np.dtype(">u2" if big_endian else "<u2")
        rows = np.ascontiguousarray(rows).view(dtype)
    shape = (rows_needed, width) if channels == 1 else (rows_needed, width, channels)
    return rows.reshape(shape)


def decode_image(encoding: str, height: int, width: int, step: int, data: np.ndarray | bytes,
                 is_bigendian: bool = False) -> np.ndarray:
    """Decode the fields of a ``sensor_msgs/Image`` into an RGB uint8 array.

    Parameters
    ----------
    encoding : str
        ROS image encoding (case-insensitive); one of :data:`SUPPORTED_ENCODINGS`.
    height, width, step : int
        Header fields; ``step`` is the row length in bytes (rows may be padded).
    data : bytes or uint8 array
        The payload.
    is_bigendian : bool
        Byte order of 16-bit encodings.

    Returns
    -------
    numpy.ndarray
        ``(height, width, 3)`` uint8, RGB; 16-bit mono keeps its 8 most significant bits.

    Raises
    ------
    BagError
        Unknown encoding, empty image, or a payload whose size disagrees with the header.
    """
    name = encoding.lower()
    if name not in _LAYOUT:
        raise BagError(f"unsupported image encoding {encoding!r} (supported: {', '.join(SUPPORTED_ENCODINGS)}, "
                       "and sensor_msgs/CompressedImage jpeg/png)")
    pixels = _pixel_rows(data, height, width, step, name, bool(is_bigendian))
    if pixels.dtype != np.uint8:
        pixels = (pixels >> 8).astype(np.uint8)
    conversion = _LAYOUT[name][2]
    if conversion is None:
        return np.ascontiguousarray(pixels)
    return cv2.cvtColor(np.ascontiguousarray(pixels), conversion)


def decode_compressed(fmt: str, data: np.ndarray | bytes) -> np.ndarray:
    """Decode a ``sensor_msgs/CompressedImage`` (jpeg or png) into an RGB uint8 array."""
    buffer = np.frombuffer(data, dtype=np.uint8)
    if buffer.size == 0:
        raise BagError(f"compressed image ({fmt!r}) with no data")
    decoded = cv2.imdecode(buffer, cv2.IMREAD_COLOR)
    if decoded is None or decoded.size == 0:
        raise BagError(f"compressed image in format {fmt!r} cannot be decoded (jpeg and png are supported)")
    return cv2.cvtColor(decoded, cv2.COLOR_BGR2RGB)
