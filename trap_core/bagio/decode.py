"""Turn ``sensor_msgs/Image`` and ``sensor_msgs/CompressedImage`` payloads into RGB uint8 arrays.

Every later stage works on ``(H, W, 3)`` uint8 RGB, whatever the camera wrote; decoding
validates sizes first so that a malformed message is a :class:`BagError`, not a crash.
Wider samples (16 or 32 bits, signed, floating point: high-bit-depth, thermal and depth cameras)
are brought to 8 bits by a :class:`SampleRange`, fixed on a stream's first frame with content.
"""
from __future__ import annotations

import cv2
import numpy as np

from trap_core.bagio.compressed_depth import decode_compressed_depth, is_compressed_depth
from trap_core.bagio.errors import BagError

# OpenCV names Bayer patterns by the second row's first two pixels, ROS by the first row's;
# this table is the mapping cv_bridge uses (16-bit patterns are brought to 8 bits first).
_BAYER_TO_RGB = {
    f"bayer_{pattern}{bits}": code
    for pattern, code in (("rggb", cv2.COLOR_BayerBG2RGB), ("bggr", cv2.COLOR_BayerRG2RGB),
                          ("gbrg", cv2.COLOR_BayerGR2RGB), ("grbg", cv2.COLOR_BayerGB2RGB))
    for bits in (8, 16)
}
# OpenCV's generic types: samples of each depth, their channels taken as grey, BGR or BGRA (as
# cv_bridge does); two channels have no colour meaning and are refused.
_CV_DEPTHS = {"8u": "u1", "8s": "i1", "16u": "u2", "16s": "i2", "32s": "i4", "32f": "f4", "64f": "f8"}
_BY_CHANNELS = {1: cv2.COLOR_GRAY2RGB, 3: cv2.COLOR_BGR2RGB, 4: cv2.COLOR_BGRA2RGB}
# encoding -> (channels, sample type, conversion to RGB after wide samples are brought to 8 bits;
# None: already RGB). ROS's "yuv422" is UYVY and "yuv422_yuy2" YUYV; "nv21" is a Y plane then
# interleaved V, U at half size.
_LAYOUT = {
    "rgb8": (3, "u1", None), "bgr8": (3, "u1", cv2.COLOR_BGR2RGB), "rgba8": (4, "u1", cv2.COLOR_RGBA2RGB),
    "bgra8": (4, "u1", cv2.COLOR_BGRA2RGB),
    "rgb16": (3, "u2", None), "bgr16": (3, "u2", cv2.COLOR_BGR2RGB), "rgba16": (4, "u2", cv2.COLOR_RGBA2RGB),
    "bgra16": (4, "u2", cv2.COLOR_BGRA2RGB),
    "mono8": (1, "u1", cv2.COLOR_GRAY2RGB), "mono16": (1, "u2", cv2.COLOR_GRAY2RGB),
    **{f"{depth}c{channels}": (channels, sample, code)
       for depth, sample in _CV_DEPTHS.items() for channels, code in _BY_CHANNELS.items()},
    "yuv422": (2, "u1", cv2.COLOR_YUV2RGB_UYVY), "yuv422_yuy2": (2, "u1", cv2.COLOR_YUV2RGB_YUY2),
    "nv21": (1, "u1", cv2.COLOR_YUV2RGB_NV21),
    **{name: (1, "u2" if name.endswith("16") else "u1", code) for name, code in _BAYER_TO_RGB.items()},
}
_CHROMA_PAIRS = ("yuv422", "yuv422_yuy2", "nv21")  # chroma shared by two columns (and two rows for nv21)
# As ROS spells them (OpenCV's generic types in capitals: "32FC1"); decoding ignores case.
SUPPORTED_ENCODINGS: tuple[str, ...] = tuple(sorted(name.upper() if name[0].isdigit() else name for name in _LAYOUT))
# Share of its first frame's range a stream's sample range is widened by on each side (later
# frames may be brighter or darker), and the share of samples left out at each end when that range
# is read (a few dead or saturated pixels would otherwise set it).
RANGE_MARGIN = 0.25
RANGE_TAIL = 0.001
# Distinct sample values a frame needs to fix a stream's range: fewer, it is blank (a camera that
# starts black or saturated, a depth camera with no reading yet), and the range it would fix would
# clip every later frame.
RANGE_LEVELS = 16


class SampleRange:
    """How the wide samples of one stream (16 or 32 bits, signed, floating point) become 8-bit ones:
    fixed on its first frame with content.

    Cameras write 10, 12 or 14 significant bits in 16-bit samples, thermal cameras a narrow band
    of the range, depth cameras millimetres or metres; keeping the high byte (cv_bridge's
    conversion) leaves such frames nearly black or flat, with nothing to segment. The range the
    first frame spans (but its extreme ``RANGE_TAIL`` samples), widened by ``RANGE_MARGIN`` of
    itself on each side within the sample type's range, is mapped linearly onto 0..255;
    full-range 16-bit samples keep their high byte (rounded). It is fixed, not read again from
    each frame, so that a region keeps its colour (and its label) from frame to frame; later
    samples outside it are clipped. Blank frames (fewer than ``RANGE_LEVELS`` distinct values)
    are mapped by their own range and fix nothing. Floating-point samples that are not numbers
    (a depth camera's missing readings) become 0, infinities the ends of the range.
    """

    def __init__(self) -> None:
        self.low: float | None = None
        self.high: float | None = None

    def to_8bit(self, samples: np.ndarray) -> np.ndarray:
        """``samples`` (any numeric type, any shape) as uint8, the range set from them if it is not yet."""
        low, high = self.low, self.high
        if low is None or high is None:
            finite = samples[np.isfinite(samples)] if samples.dtype.kind == "f" else samples.ravel()
            if finite.size == 0:
                return np.zeros(samples.shape, dtype=np.uint8)
            low, high = _widened_range(finite, samples.dtype)
            if np.unique(finite).size >= RANGE_LEVELS:
                self.low, self.high = low, high
        wide = np.float32 if samples.dtype.itemsize <= 2 else np.float64  # exact for 16-bit samples
        scaled = (samples.astype(wide) - wide(low)) * wide(255.0 / (high - low))
        if samples.dtype.kind == "f":
            np.nan_to_num(scaled, copy=False, nan=0.0, posinf=255.0, neginf=0.0)
        return np.clip(np.rint(scaled), 0, 255).astype(np.uint8)


def _widened_range(samples: np.ndarray, dtype: np.dtype) -> tuple[float, float]:
    """The range of ``samples`` (finite) but their extreme tails, widened by ``RANGE_MARGIN`` each
    side within the range of ``dtype``; for integers at least 1/257 of that range wide (a flat
    first frame is not amplified; 255 for 16-bit samples, which full-range samples then map to
    their high byte exactly)."""
    low, high = (float(v) for v in np.quantile(samples, (RANGE_TAIL, 1 - RANGE_TAIL)))
    margin = RANGE_MARGIN * (high - low)
    if dtype.kind == "f":
        low, high = low - margin, high + margin
        least = 1e-6 * max(1.0, abs(low), abs(high))
        return (low, high) if high - low >= least else (low, low + least)
    info = np.iinfo(dtype)
    low, high = max(float(info.min), low - margin), min(float(info.max), high + margin)
    least = (float(info.max) - float(info.min)) / 257
    if high - low < least:
        low = max(float(info.min), min(low, float(info.max) - least))
        high = low + least
    return low, high


def _pixel_rows(data: np.ndarray | bytes, height: int, width: int, step: int, encoding: str,
                big_endian: bool) -> np.ndarray:
    """View the payload as (rows, width[, channels]) after checking its size against the header
    (rows: ``height``, or 1.5 ``height`` for nv21's chroma plane), in the encoding's sample type."""
    if height <= 0 or width <= 0:
        raise BagError(f"image of size {width}x{height}: nothing to track in an empty frame")
    if encoding in _CHROMA_PAIRS and (width % 2 or (encoding == "nv21" and height % 2)):
        raise BagError(f"{encoding} image {width}x{height}: chroma is shared by pixel pairs, the size must be even")
    channels, sample, _ = _LAYOUT[encoding]
    dtype = np.dtype(sample).newbyteorder(">" if big_endian else "<")
    rows_needed = height * 3 // 2 if encoding == "nv21" else height
    row_bytes = width * channels * dtype.itemsize
    if step < row_bytes:
        raise BagError(f"{encoding} image {width}x{height}: step {step} is shorter than a row ({row_bytes} bytes)")
    buffer = np.frombuffer(data, dtype=np.uint8)
    if buffer.size < rows_needed * step:
        raise BagError(f"{encoding} image {width}x{height}: {buffer.size} bytes of data, "
                       f"{'1.5 x ' if encoding == 'nv21' else ''}height x step needs {rows_needed * step}")
    rows = buffer[: rows_needed * step].reshape(rows_needed, step)[:, :row_bytes]
    if dtype != np.uint8:
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
        Byte order of samples wider than a byte.
    sample_range : SampleRange, optional
        The stream's: how wide samples (16 or 32 bits, signed, floating point) become 8-bit;
        None: a range read from this frame alone.

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
                       "and sensor_msgs/CompressedImage jpeg, png, compressedDepth)")
    pixels = _pixel_rows(data, height, width, step, name, bool(is_bigendian))
    if pixels.dtype != np.uint8:
        pixels = (sample_range or SampleRange()).to_8bit(pixels)
    conversion = _LAYOUT[name][2]
    if conversion is None:
        return np.ascontiguousarray(pixels)
    return cv2.cvtColor(np.ascontiguousarray(pixels), conversion)


def decode_compressed(fmt: str, data: np.ndarray | bytes, sample_range: SampleRange | None = None) -> np.ndarray:
    """Decode a ``sensor_msgs/CompressedImage`` (jpeg, png, or compressedDepth png / rvl) into an
    RGB uint8 array; 16-bit png and depth are brought to 8 bits by ``sample_range`` (see
    :func:`decode_image`)."""
    buffer = np.frombuffer(data, dtype=np.uint8)
    if buffer.size == 0:
        raise BagError(f"compressed image ({fmt!r}) with no data")
    if is_compressed_depth(fmt):
        grey = (sample_range or SampleRange()).to_8bit(decode_compressed_depth(fmt, buffer))
        return cv2.cvtColor(grey, cv2.COLOR_GRAY2RGB)
    decoded = cv2.imdecode(buffer, cv2.IMREAD_COLOR | cv2.IMREAD_ANYDEPTH)
    if decoded is None or decoded.size == 0:
        raise BagError(f"compressed image in format {fmt!r} cannot be decoded (jpeg, png and compressedDepth "
                       "are supported)")
    if decoded.dtype != np.uint8:
        decoded = (sample_range or SampleRange()).to_8bit(decoded)
    return cv2.cvtColor(decoded, cv2.COLOR_BGR2RGB)
