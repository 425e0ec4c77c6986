"""Write the published results to ``tracks.mcap`` (readable by rosbags, ros2 bag and Foxglove)."""
from __future__ import annotations

import os
import sys
from pathlib import Path

from rclpy.serialization import serialize_message
from rosbags.rosbag2 import CompressionFormat, CompressionMode, StoragePlugin, Writer
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

from trap_core.bagio import BagError, stamp_ns

VISION_TYPES = ("Point2D", "Pose2D", "BoundingBox2D", "ObjectHypothesis", "ObjectHypothesisWithPose",
                "Detection2D", "Detection2DArray")
TOPICS = {"detections": "vision_msgs/msg/Detection2DArray", "tracks": "vision_msgs/msg/Detection2DArray",
          "trajectories": "visualization_msgs/msg/MarkerArray"}


def share_dir(package: str) -> Path:
    """``share/<package>`` of the ament prefixes in use, or of this Python's prefix (the venv)."""
    prefixes = [p for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p] + [sys.prefix]
    for prefix in prefixes:
        if (Path(prefix) / "share" / package).is_dir():
            return Path(prefix) / "share" / package
    raise BagError(f"package {package} not found under {', '.join(prefixes)}")


def _typestore():
    store = get_typestore(Stores.ROS2_JAZZY)
    msg_dir = share_dir("vision_msgs") / "msg"
    types = {}
    for name in VISION_TYPES:
        types.update(get_types_from_msg((msg_dir / f"{name}.msg").read_text(), f"vision_msgs/msg/{name}"))
    store.register(types)
    return store


def write_results_bag(path: str | Path, published: dict[str, list], namespace: str = "/trap") -> Path:
    """Write every published message (``{'detections': [...], 'tracks': [...], ...}``) to an mcap bag.

    Log times are the messages' header stamps, so the bag lines up with the input bag.
    """
    path = Path(path)
    if path.exists():
        raise BagError(f"{path} exists already; remove it or choose another --out")
    store = _typestore()
    writer = Writer(path, version=9, storage_plugin=StoragePlugin.MCAP)
    writer.set_compression(CompressionMode.STORAGE, CompressionFormat.ZSTD)
    with writer:
        for name, msgtype in TOPICS.items():
            connection = writer.add_connection(f"{namespace}/{name}", msgtype, typestore=store)
            for message in published.get(name, []):
                header = message.header if hasattr(message, "header") else message.markers[0].header
                writer.write(connection, stamp_ns(header), serialize_message(message))
    return path
