"""Turn ``sensor_msgs/Image`` and ``sensor_msgs/CompressedImage`` payloads into RGB uint8 arrays.

Every later stage works on ``(H, W, 3)`` uint8 RGB, whatever the camera wrote; decoding
validates sizes first so that a malformed message is a :class:`BagError`, not a crash.
"""
from __future__ import annotations

import cv2
import numpy as np

from trap_core.bagio.errors import BagError

# OpenCV names Bayer patterns by the second row's first two pixels, ROS by the first row's;
# this table is the mapping cv_bridge uses.
_BAYER_TO_RGB = {
    "bayer_rggb8": cv2.COLOR_BayerBG2RGB,
    "bayer_bggr8": cv2.COLOR_BayerRG2RGB,
    "bayer_gbrg8": cv2.COLOR_BayerGR2RGB,
    "bayer_grbg8": cv2.COLOR_BayerGB2RGB,
}
# encoding -> (channels, bytes per channel)
_LAYOUT = {
    "rgb8": (3, 1), "bgr8": (3, 1), "rgba8": (4, 1), "bgra8": (4, 1),
    "mono8": (1, 1), "8uc1": (1, 1), "mono16": (1, 2), "16uc1": (1, 2),
    **{name: (1, 1) for name in _BAYER_TO_RGB},
}
SUPPORTED_ENCODINGS: tuple[str, ...] = tuple(sorted(_LAYOUT))


def _pixel_rows(data: np.ndarray | bytes, height: int, width: int, step: int, encoding: str,
                big_endian: bool) -> np.ndarray:
    """View the payload as (height, width[, channels]) after checking its size against the header."""
    if height <= 0 or width <= 0:
        raise BagError(f"image of size {width}x{height}: nothing to track in an empty frame")
    channels, depth = _LAYOUT[encoding]
    row_bytes = width * channels * depth
    if step < row_bytes:
        raise BagError(f"{encoding} image {width}x{height}: step {step} is shorter than a row ({row_bytes} bytes)")
    buffer = np.frombuffer(data, dtype=np.uint8)
    if buffer.size < height * step:
        raise BagError(f"{encoding} image {width}x{height}: {buffer.size} bytes of data, "
                       f"height x step needs {height * step}")
    rows = buffer[: height * step].reshape(height, step)[:, :row_bytes]
    if depth == 2:
        dtype = np.dtype(">u2" if big_endian else "<u2")
        rows = np.ascontiguousarray(rows).view(dtype)
    shape = (height, width) if channels == 1 else (height, width, channels)
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
    if name == "rgb8":
        return np.ascontiguousarray(pixels)
    if name == "bgr8":
        return cv2.cvtColor(pixels, cv2.COLOR_BGR2RGB)
    if name == "rgba8":
        return cv2.cvtColor(pixels, cv2.COLOR_RGBA2RGB)
    if name == "bgra8":
        return cv2.cvtColor(pixels, cv2.COLOR_BGRA2RGB)
    if name in ("mono16", "16uc1"):
        pixels = (pixels >> 8).astype(np.uint8)
    if name in _BAYER_TO_RGB:
        return cv2.cvtColor(np.ascontiguousarray(pixels), _BAYER_TO_RGB[name])
    return cv2.cvtColor(np.ascontiguousarray(pixels), cv2.COLOR_GRAY2RGB)


def decode_compressed(fmt: str, data: np.ndarray | bytes) -> np.ndarray:
    """Decode a ``sensor_msgs/CompressedImage`` (jpeg or png) into an RGB uint8 array."""
    buffer = np.frombuffer(data, dtype=np.uint8)
    if buffer.size == 0:
        raise BagError(f"compressed image ({fmt!r}) with no data")
    decoded = cv2.imdecode(buffer, cv2.IMREAD_COLOR)
    if decoded is None or decoded.size == 0:
        raise BagError(f"compressed image in format {fmt!r} cannot be decoded (jpeg and png are supported)")
    return cv2.cvtColor(decoded, cv2.COLOR_BGR2RGB)
