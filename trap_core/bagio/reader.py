"""Stream one image topic of a bag, frame by frame, with the count known up front.

rosbags reads ROS 1 bags, ROS 2 bag folders (sqlite3 or mcap) and bare ``.db3`` / ``.mcap``
files without a ROS installation. Frames are decoded one at a time, so memory does not grow
with the length of the bag, and the number of frames comes from the bag's index so progress
can be shown from the first frame.
"""
from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from tempfile import TemporaryDirectory
from types import TracebackType

import numpy as np
from rosbags.highlevel import AnyReader

from trap_core.bagio.decode import SampleRange, decode_compressed, decode_image
from trap_core.bagio.errors import BagError
from trap_core.bagio.frame_size import FrameSize

IMAGE_TYPES = ("sensor_msgs/msg/Image", "sensor_msgs/msg/CompressedImage")
ROS1_MAGIC = b"#ROSBAG V2.0\n"  # first line of every ROS 1 bag


@dataclass(frozen=True)
class ImageFrame:
    """One decoded frame: ``index`` counts from 0 in bag order; stamp and frame_id are the header's."""

    index: int
    stamp_ns: int
    frame_id: str
    rgb: np.ndarray


def _reason(error: BaseException) -> str:
    """Squeeze an exception from rosbags, sqlite or a decoder into one line."""
    text = " ".join(str(error).split()) or type(error).__name__
    return text if len(text) < 300 else text[:297] + "..."


class _OpenBag:
    """An open rosbags reader with, for a ROS 1 bag named without ``.bag``, the temporary alias
    it reads through: closing one removes the other, so no link outlives the reading."""

    def __init__(self, path: Path) -> None:
        if not path.exists():
            raise BagError(f"bag not found: {path}")
        self._alias = _ros1_alias(path)
        try:
            self.reader = AnyReader([path if self._alias is None else Path(self._alias.name) / f"{path.name}.bag"])
            self.reader.open()
        except Exception as error:  # rosbags, sqlite3 and mcap raise many unrelated types
            self._remove_alias()
            raise BagError(f"{path} is not a readable ROS 1 or ROS 2 bag: {_reason(error)}") from None

    def close(self) -> None:
        """Close the reader and remove the alias (idempotent)."""
        if self.reader.stack is not None:
            self.reader.close()
        self._remove_alias()

    def _remove_alias(self) -> None:
        if self._alias is not None:
            self._alias.cleanup()
            self._alias = None


def _ros1_alias(path: Path) -> TemporaryDirectory | None:
    """For a ROS 1 bag file named without ``.bag`` (rosbags tells ROS 1 from ROS 2 by that
    suffix), a temporary folder holding a link to it under that suffix; None otherwise."""
    if not path.is_file() or path.suffix == ".bag":
        return None
    with path.open("rb") as head:
        if head.read(len(ROS1_MAGIC)) != ROS1_MAGIC:
            return None
    alias = TemporaryDirectory(prefix="trap_bag_")
    (Path(alias.name) / f"{path.name}.bag").symlink_to(path.resolve())
    return alias


def image_topics(path: str | Path) -> dict[str, tuple[str, int]]:
    """Return ``{topic: (message type, message count)}`` for every image topic of the bag."""
    bag = _OpenBag(Path(path))
    try:
        return _image_topics(bag.reader)
    finally:
        bag.close()


def _image_topics(reader: AnyReader) -> dict[str, tuple[str, int]]:
    topics: dict[str, tuple[str, int]] = {}
    for connection in reader.connections:
        if connection.msgtype in IMAGE_TYPES:
            _, count = topics.get(connection.topic, (connection.msgtype, 0))
            topics[connection.topic] = (connection.msgtype, count + connection.msgcount)
    return topics


class ImageStream:
    """Frames of one image topic; use as a context manager and iterate.

    ``count`` (frames in the topic) and ``topic`` are known as soon as the stream is open.
    """

    def __init__(self, path: str | Path, topic: str | None = None) -> None:
        self.path = Path(path)
        self._bag = _OpenBag(self.path)
        self._sample_range = SampleRange()  # wide samples (16-bit, depth): one mapping for the whole topic
        self._frame_size = FrameSize()  # every frame the first one's size
        try:
            self.topic, self.msgtype, self.count = self._choose_topic(topic)
        except BagError:
            self._bag.close()
            raise

    def _choose_topic(self, topic: str | None) -> tuple[str, str, int]:
        topics = _image_topics(self._bag.reader)
        if topic is not None:
            if topic not in topics:
                known = ", ".join(sorted(topics)) or "none"
                raise BagError(f"no image topic {topic!r} in {self.path} (image topics: {known})")
            return topic, *topics[topic]
        if not topics:
            others = ", ".join(sorted({c.topic for c in self._bag.reader.connections})) or "none"
            raise BagError(f"{self.path} holds no sensor_msgs/Image or CompressedImage topic (topics: {others})")
        if len(topics) > 1:
            raise BagError(f"{self.path} holds several image topics, choose one with --topic: "
                           f"{', '.join(sorted(topics))}")
        only = next(iter(topics))
        return only, *topics[only]

    def __iter__(self) -> Iterator[ImageFrame]:
        connections = [c for c in self._bag.reader.connections if c.topic == self.topic]
        messages = self._bag.reader.messages(connections=connections)
        index = 0
        while True:
            try:
                connection, _, raw = next(messages)
                message = self._bag.reader.deserialize(raw, connection.msgtype)
            except StopIteration:
                return
            except Exception as error:  # a truncated or corrupt chunk surfaces here
                raise BagError(f"{self.path}: cannot read frame {index} of {self.topic}: {_reason(error)}") from None
            yield ImageFrame(index, stamp_ns(message.header), message.header.frame_id, self._decode(message, index))
            index += 1

    def _decode(self, message: object, index: int) -> np.ndarray:
        try:
            if self.msgtype.endswith("CompressedImage"):
                rgb = decode_compressed(message.format, message.data, self._sample_range)
            else:
                rgb = decode_image(message.encoding, message.height, message.width, message.step,
                                   message.data, bool(message.is_bigendian), self._sample_range)
            self._frame_size.check(rgb)
            return rgb
        except BagError as error:
            raise BagError(f"{self.path}: frame {index} of {self.topic}: {error}") from None

    def close(self) -> None:
        """Release the bag files (idempotent)."""
        self._bag.close()

    def __enter__(self) -> ImageStream:
        return self

    def __exit__(self, kind: type[BaseException] | None, error: BaseException | None,
                 trace: TracebackType | None) -> None:
        self.close()


def stamp_ns(header: object) -> int:
    """Nanoseconds of a ``std_msgs/Header``'s stamp (rosbags' or rclpy's message)."""
    return int(header.stamp.sec) * 1_000_000_000 + int(header.stamp.nanosec)


def open_image_stream(path: str | Path, topic: str | None = None) -> ImageStream:
    """Open ``path`` (a ROS 2 bag folder, ``.mcap``, ``.db3`` or a ROS 1 bag, ``.bag`` or not) for streaming.

    Parameters
    ----------
    path : str or Path
        The bag.
    topic : str, optional
        Image topic; chosen automatically when the bag has exactly one.

    Returns
    -------
    ImageStream
        Open stream; ``count`` frames of ``topic``.

    Raises
    ------
    BagError
        Missing or unreadable bag, missing topic, no or several image topics.
    """
    return ImageStream(path, topic)
