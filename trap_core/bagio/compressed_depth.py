"""Depth images as ``sensor_msgs/CompressedImage`` (compressed_depth_image_transport's messages).

The format field is ``"<encoding>; compressedDepth"``, optionally followed by `` png`` (the
default) or `` rvl`` (:mod:`trap_core.bagio._rvl`). The data are a 12-byte header (an int32
format code, then two float32 quantisation parameters A and B) and the image: 16UC1 (mono16)
depth as its own samples; 32FC1 depth as 16-bit inverse depth ``v = A / depth + B``, 0 where
there is no reading, so that ``depth = A / (v - B)``. An RVL image starts with its uint32 width
and height.
"""
from __future__ import annotations

import cv2
import numpy as np

from trap_core.bagio._rvl import rvl_decode, rvl_encode
from trap_core.bagio.errors import BagError

HEADER_BYTES = 12
DEPTH_ENCODINGS = ("16uc1", "mono16", "32fc1")
CODECS = ("png", "rvl")
# How the publisher quantises 32FC1 depth (its parameter defaults): A = q (q + 1), B = 1 - A / max.
DEPTH_QUANTIZATION = 100.0
DEPTH_MAX = 10.0
# Largest rvl image accepted (8192 x 8192): a corrupt size field would otherwise fill memory before
# the data run out (a frame without any reading takes a few bytes, whatever its size).
MOST_PIXELS = 1 << 26


def is_compressed_depth(fmt: str) -> bool:
    """Whether a ``CompressedImage`` format names compressed_depth_image_transport's messages."""
    return "compresseddepth" in fmt.lower()


def _parts(fmt: str) -> tuple[str, str]:
    """(encoding, codec) of a compressedDepth format, both lower case; refused if unknown."""
    encoding, _, rest = fmt.partition(";")
    encoding = encoding.strip().lower()
    codec = rest.strip().lower().removeprefix("compresseddepth").strip() or "png"
    if encoding not in DEPTH_ENCODINGS or codec not in CODECS:
        raise BagError(f"compressed depth format {fmt!r} is not supported (16UC1, mono16 or 32FC1, "
                       f"compressedDepth png or rvl)")
    return encoding, codec


def decode_compressed_depth(fmt: str, buffer: np.ndarray) -> np.ndarray:
    """Depth samples of a compressedDepth message: uint16 for 16UC1 / mono16, float32 metres for
    32FC1 (NaN where there is no reading); ``buffer`` is its data as uint8."""
    encoding, codec = _parts(fmt)
    if buffer.size <= HEADER_BYTES:
        raise BagError(f"compressed depth image ({fmt!r}) of {buffer.size} bytes: no image after its header")
    quant_a, quant_b = (float(v) for v in buffer[4:HEADER_BYTES].view("<f4"))
    body = buffer[HEADER_BYTES:]
    samples = _png_samples(body, fmt) if codec == "png" else _rvl_samples(body, fmt)
    if encoding != "32fc1":
        return samples
    with np.errstate(divide="ignore", invalid="ignore"):
        depth = np.float32(quant_a) / (samples.astype(np.float32) - np.float32(quant_b))
    depth[samples == 0] = np.nan
    return depth


def _png_samples(body: np.ndarray, fmt: str) -> np.ndarray:
    samples = cv2.imdecode(body, cv2.IMREAD_UNCHANGED)
    if samples is None or samples.dtype != np.uint16 or samples.ndim != 2 or samples.size == 0:
        raise BagError(f"compressed depth image ({fmt!r}) holds no 16-bit single-channel png")
    return samples


def _rvl_samples(body: np.ndarray, fmt: str) -> np.ndarray:
    if body.size < 8:
        raise BagError(f"compressed depth image ({fmt!r}): rvl data shorter than its size fields")
    width, height = (int(v) for v in body[:8].view("<u4"))
    words = body[8: 8 + (body.size - 8) // 4 * 4].view("<u4")
    if width == 0 or height == 0 or width * height > MOST_PIXELS:
        raise BagError(f"compressed depth image ({fmt!r}): rvl size {width}x{height} does not fit its "
                       f"{body.size} bytes")
    samples, complete = rvl_decode(np.ascontiguousarray(words, dtype=np.uint32), width * height)
    if not complete:
        raise BagError(f"compressed depth image ({fmt!r}): rvl data end before its {width}x{height} pixels")
    return samples.reshape(height, width)


def compress_depth(metres: np.ndarray, fmt: str) -> np.ndarray:
    """Depth in ``metres`` as the data of a compressedDepth message in format ``fmt`` (writing
    bags: the inverse of :func:`decode_compressed_depth`): 16UC1 / mono16 in millimetres (REP
    118), 32FC1 as quantised inverse depth, where depth at or beyond ``DEPTH_MAX`` is no reading."""
    encoding, codec = _parts(fmt)
    quant_a = quant_b = 0.0
    if encoding == "32fc1":
        quant_a = DEPTH_QUANTIZATION * (DEPTH_QUANTIZATION + 1.0)
        quant_b = 1.0 - quant_a / DEPTH_MAX
        valid = np.isfinite(metres) & (metres > 0) & (metres < DEPTH_MAX)
        inverse = np.zeros(metres.shape, dtype=np.float64)
        inverse[valid] = quant_a / metres[valid] + quant_b
        samples = np.clip(inverse, 0, 65535).astype(np.uint16)
    else:
        samples = np.rint(np.clip(np.nan_to_num(metres * 1000.0), 0, 65535)).astype(np.uint16)
    header = np.zeros(HEADER_BYTES, dtype=np.uint8)
    header[4:].view("<f4")[:] = (quant_a, quant_b)
    if codec == "png":
        ok, body = cv2.imencode(".png", samples)
        if not ok:
            raise BagError(f"{fmt} encoding failed")
        body = body.reshape(-1)
    else:
        size = np.array(samples.shape[::-1], dtype="<u4").view(np.uint8)
        body = np.concatenate([size, rvl_encode(samples.reshape(-1)).astype("<u4").view(np.uint8)])
    return np.concatenate([header, body])
