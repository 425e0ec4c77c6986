"""Turn ``sensor_msgs/Image`` and ``sensor_msgs/CompressedImage`` payloads into RGB uint8 arrays.

Every later stage works on ``(H, W, 3)`` uint8 RGB, whatever the camera wrote; decoding
validates sizes first so that a malformed message is a :class:`BagError`, not a crash.
16-bit samples are brought to 8 bits by a :class:`SampleRange`, fixed on a stream's first frame
with content.
"""
from __future__ import annotations

import cv2
import numpy as np

from trap_core.bagio.errors import BagError

# OpenCV names Bayer patterns by the second row's first two pixels, ROS by the first row's;
# this table is the mapping cv_bridge uses (16-bit patterns are brought to 8 bits first).
_BAYER_TO_RGB = {
    f"bayer_{pattern}{bits}": code
    for pattern, code in (("rggb", cv2.COLOR_BayerBG2RGB), ("bggr", cv2.COLOR_BayerRG2RGB),
                          ("gbrg", cv2.COLOR_BayerGR2RGB), ("grbg", cv2.COLOR_BayerGB2RGB))
    for bits in (8, 16)
}
# encoding -> (channels, bytes per channel, conversion to RGB after 16-bit samples are brought to
# 8 bits; None: already RGB). "8uc3"/"8uc4" are taken as BGR(A), as cv_bridge does; ROS's
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
# Share of its first frame's range a stream's 16-bit range is widened by on each side (later
# frames may be brighter or darker), and the share of samples left out at each end when that range
# is read (a few dead or saturated pixels would otherwise set it).
RANGE_MARGIN = 0.25
RANGE_TAIL = 0.001
# Distinct sample values a frame needs to fix a stream's range: fewer, it is blank (a camera that
# starts black or saturated), and the range it would fix would clip every later frame.
RANGE_LEVELS = 16


class SampleRange:
    """How the 16-bit samples of one stream become 8-bit ones: fixed on its first frame with content.

    Cameras write 10, 12 or 14 significant bits in 16-bit samples, and thermal cameras a narrow
    band of the range; keeping the high byte (cv_bridge's conversion) leaves such frames nearly
    black or flat, with nothing to segment. The range the first frame spans (but its extreme
    ``RANGE_TAIL`` samples), widened by ``RANGE_MARGIN`` of itself on each side within 0..65535,
    is mapped linearly onto 0..255; full-range samples keep their high byte (rounded). It is
    fixed, not read again from each frame, so that a region keeps its colour (and its label)
    from frame to frame; later samples outside it are clipped. Blank frames (fewer than
    ``RANGE_LEVELS`` distinct values) are mapped by their own range and fix nothing.
    """

    def __init__(self) -> None:
        self.low: float | None = None
        self.high: float | None = None

    def to_8bit(self, samples: np.ndarray) -> np.ndarray:
        """``samples`` (uint16, any shape) as uint8, the range set from them if it is not yet."""
        low, high = self.low, self.high
        if low is None or high is None:
            low, high = _widened_range(samples)
            if np.count_nonzero(np.bincount(samples.ravel(), minlength=1)) >= RANGE_LEVELS:
                self.low, self.high = low, high
        scaled = (samples.astype(np.float32) - low) * np.float32(255.0 / (high - low))
        return np.clip(np.rint(scaled), 0, 255).astype(np.uint8)


def _widened_range(samples: np.ndarray) -> tuple[float, float]:
    """The range of ``samples`` but their extreme tails, widened by ``RANGE_MARGIN`` each side,
    within 0..65535 and at least 255 wide (a flat first frame is not amplified)."""
    low, high = (float(v) for v in np.quantile(samples, (RANGE_TAIL, 1 - RANGE_TAIL)))
    margin = RANGE_MARGIN * (high - low)
    low, high = max(0.0, low - margin), min(65535.0, high + margin)
    if high - low < 255:
        low = max(0.0, min(low, 65535.0 - 255))
        high = low + 255
    return low, high


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
                 is_bigendian: bool = False, sample_range: SampleRange | None = None) -> np.ndarray:
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
    sample_range : SampleRange, optional
        The stream's: how 16-bit samples become 8-bit; None: a range read from this frame alone.

    Returns
    -------
    numpy.ndarray
        ``(height, width, 3)`` uint8, RGB.

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
        pixels = (sample_range or SampleRange()).to_8bit(pixels)
    conversion = _LAYOUT[name][2]
    if conversion is None:
        return np.ascontiguousarray(pixels)
    return cv2.cvtColor(np.ascontiguousarray(pixels), conversion)


def decode_compressed(fmt: str, data: np.ndarray | bytes, sample_range: SampleRange | None = None) -> np.ndarray:
    """Decode a ``sensor_msgs/CompressedImage`` (jpeg or png) into an RGB uint8 array; a 16-bit
    png is brought to 8 bits by ``sample_range`` (see :func:`decode_image`)."""
    buffer = np.frombuffer(data, dtype=np.uint8)
    if buffer.size == 0:
        raise BagError(f"compressed image ({fmt!r}) with no data")
    decoded = cv2.imdecode(buffer, cv2.IMREAD_COLOR | cv2.IMREAD_ANYDEPTH)
    if decoded is None or decoded.size == 0:
        raise BagError(f"compressed image in format {fmt!r} cannot be decoded (jpeg and png are supported)")
    if decoded.dtype != np.uint8:
        decoded = (sample_range or SampleRange()).to_8bit(decoded)
    return cv2.cvtColor(decoded, cv2.COLOR_BGR2RGB)
