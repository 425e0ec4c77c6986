"""Image topics of ROS 1 / ROS 2 bags: stream them out as RGB frames, or write RGB frames into them."""

from trap_core.bagio.decode import SUPPORTED_ENCODINGS, SampleRange, decode_compressed, decode_image
from trap_core.bagio.encode import COMPRESSED_FORMATS, compress_image, encode_image
from trap_core.bagio.errors import BagError
from trap_core.bagio.frame_size import FrameSize
from trap_core.bagio.reader import ImageFrame, ImageStream, image_topics, open_image_stream, stamp_ns
from trap_core.bagio.writer import STORAGES, write_image_bag

__all__ = [
    "COMPRESSED_FORMATS",
    "STORAGES",
    "SUPPORTED_ENCODINGS",
    "BagError",
    "FrameSize",
    "compress_image",
    "ImageFrame",
    "ImageStream",
    "SampleRange",
    "decode_compressed",
    "decode_image",
    "encode_image",
    "image_topics",
    "open_image_stream",
    "stamp_ns",
    "write_image_bag",
]
