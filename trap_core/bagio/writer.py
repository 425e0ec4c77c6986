"""Write a stream of RGB frames as an image topic of a ROS 2 (mcap / sqlite3) or ROS 1 bag."""
from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

import numpy as np
from rosbags.rosbag1 import Writer as Ros1Writer
from rosbags.rosbag2 import CompressionFormat, CompressionMode, StoragePlugin
from rosbags.rosbag2 import Writer as Ros2Writer
from rosbags.typesys import Stores, get_typestore

from trap_core.bagio.encode import compress_image, encode_image
from trap_core.bagio.errors import BagError

STORAGES = ("mcap", "sqlite3", "ros1")


def write_image_bag(path: str | Path, frames: Iterable[np.ndarray], *, topic: str = "/camera/image_raw",
                    encoding: str = "rgb8", compressed: str | None = None, storage: str = "mcap",
                    fps: float = 25.0, frame_id: str = "camera", start_ns: int = 1_700_000_000_000_000_000,
                    sample_bits: int | None = None) -> int:
    """Write ``frames`` (RGB uint8) to a new bag and return the number written.

    Parameters
    ----------
    path : str or Path
        ROS 2: the bag folder to create; ROS 1: the ``.bag`` file.
    frames : iterable of ndarray
        RGB frames, consumed lazily (the video is never held in memory).
    topic, frame_id : str
        Topic name and header frame id.
    encoding : str
        Raw encoding (``rgb8``, ``bgr8``, ``mono8``, ``bayer_rggb8``, ...), ignored if ``compressed``.
    compressed : str, optional
        Write ``sensor_msgs/CompressedImage`` in this format (one of ``COMPRESSED_FORMATS``: jpeg,
        png, or a compressedDepth one) instead of raw images.
    storage : {'mcap', 'sqlite3', 'ros1'}
        Container; mcap chunks are zstd-compressed (readable by Foxglove and ros2 bag).
    fps : float
        Frame rate that sets the header stamps and the log times.
    sample_bits : int, optional
        Integer encodings wider than 8 bits: significant bits of each sample (:func:`encode_image`).
    """
    if storage not in STORAGES:
        raise BagError(f"unknown storage {storage!r} (one of {', '.join(STORAGES)})")
    path = Path(path)
    if path.exists():
        raise BagError(f"{path} exists already; bags are never overwritten")
    store = get_typestore(Stores.ROS1_NOETIC if storage == "ros1" else Stores.ROS2_JAZZY)
    image_type = "sensor_msgs/msg/CompressedImage" if compressed else "sensor_msgs/msg/Image"
    if storage == "ros1":
        writer = Ros1Writer(path)
    else:
        plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
        writer = Ros2Writer(path, version=9, storage_plugin=plugin)
        if storage == "mcap":
            writer.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
    serialize = store.serialize_ros1 if storage == "ros1" else store.serialize_cdr
    types = store.types
    written = 0
    with writer:
        connection = writer.add_connection(topic, image_type, typestore=store)
        for index, rgb in enumerate(frames):
            stamp_ns = start_ns + round(index * 1e9 / fps)
            header = types["std_msgs/msg/Header"](
                **({"seq": index} if storage == "ros1" else {}),
                stamp=types["builtin_interfaces/msg/Time"](sec=stamp_ns // 1_000_000_000,
                                                           nanosec=stamp_ns % 1_000_000_000),
                frame_id=frame_id)
            if compressed:
                message = types[image_type](header=header, format=compressed, data=compress_image(rgb, compressed))
            else:
                data, step = encode_image(rgb, encoding, sample_bits)
                message = types[image_type](header=header, height=rgb.shape[0], width=rgb.shape[1],
                                            encoding=encoding, is_bigendian=0, step=step, data=data)
            writer.write(connection, stamp_ns, serialize(message, image_type))
            written += 1
    return written
