"""Bag reader node: streams one image topic of a bag as ``sensor_msgs/Image`` (rgb8).

Headers are the bag's own. Flow control: with ``window > 0`` at most ``window`` frames are
published beyond the count acknowledged on ``progress`` (published by the mining node), so a
slow consumer slows the reader instead of losing images. ``end_of_bag`` (latched) carries
the number of frames published once the bag is exhausted.
"""
from __future__ import annotations

import threading
import time

import rclpy
from rcl_interfaces.msg import ParameterDescriptor
from rclpy.duration import Duration
from rclpy.node import Node
from sensor_msgs.msg import Image
from std_msgs.msg import Header, UInt64

from trap_core.bagio import BagError, open_image_stream
from trap_core.progress import Progress
from trap_ros.messages import image_message
from trap_ros.node_main import run_node
from trap_ros.qos import LATCHED, PIPELINE


class BagReaderNode(Node):
    """Publishes the frames of ``bag`` on ``image``; see the module docstring."""

    def __init__(self, **kwargs) -> None:
        kwargs.setdefault("namespace", "trap")
        super().__init__("bag_reader", **kwargs)
        declare = lambda name, value, text: self.declare_parameter(  # noqa: E731
            name, value, ParameterDescriptor(description=text))
        declare("bag", "", "bag to read: ROS 2 folder, .mcap, .db3 or ROS 1 .bag")
        declare("topic", "", "image topic in the bag (empty: the only image topic)")
        declare("rate", 0.0, "frames per second to publish; 0 = as fast as the consumers accept")
        declare("window", 16, "frames in flight beyond the acknowledged count; 0 = no flow control")
        declare("stall_timeout", 60.0, "seconds without acknowledgement before giving up (window > 0)")
        self.image_pub = self.create_publisher(Image, "image", PIPELINE)
        self.end_pub = self.create_publisher(UInt64, "end_of_bag", LATCHED)
        self._progress_topic = self.create_subscription(UInt64, "progress", self._on_progress, PIPELINE).topic_name
        self._acknowledged = 0
        self._changed = threading.Condition()
        self._stop = threading.Event()
        self.published = 0
        self.total: int | None = None
        self.error: str | None = None
        self.finished = threading.Event()
        self.frame_hook = None  # called with each frame's RGB before it is published (process_bag: thumbnails)
        bag = self.get_parameter("bag").value
        if not bag:
            raise BagError("parameter 'bag' is empty: give the bag to read")
        self.stream = open_image_stream(bag, self.get_parameter("topic").value or None)
        self.total = self.stream.count
        self.get_logger().info(f"reading {self.stream.count} frames of {self.stream.topic} from {bag}")
        self._thread = threading.Thread(target=self._publish_all, name="bag-reader", daemon=True)

    def start(self) -> None:
        """Start publishing (on a thread of its own, so callbacks keep running)."""
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        with self._changed:
            self._changed.notify_all()

    def _on_progress(self, message: UInt64) -> None:
        with self._changed:
            self._acknowledged = max(self._acknowledged, int(message.data))
            self._changed.notify_all()

    def _wait_for_credit(self, window: int, stall_timeout: float) -> bool:
        deadline = time.monotonic() + stall_timeout
        with self._changed:
            while self.published - self._acknowledged >= window and not self._stop.is_set():
                if not self._changed.wait(timeout=min(0.5, max(deadline - time.monotonic(), 0.01))):
                    if time.monotonic() >= deadline:
                        self.error = (f"no consumer acknowledged a frame for {stall_timeout:.0f} s "
                                      f"({self._acknowledged}/{self.published}); is the mining node running?")
                        return False
                else:
                    deadline = time.monotonic() + stall_timeout
        return not self._stop.is_set()

    def _wait_for_consumers(self, need_acknowledgement: bool, timeout: float) -> bool:
        """Frames published before a subscriber is matched would be lost: wait for one (and for
        the node that acknowledges, under flow control)."""
        deadline = time.monotonic() + timeout
        while not self._stop.is_set():
            ready = self.image_pub.get_subscription_count() > 0
            if need_acknowledgement:
                ready = ready and self.count_publishers(self._progress_topic) > 0
            if ready:
                return True
            if time.monotonic() >= deadline:
                self.error = (f"no subscriber to {self.image_pub.topic_name} after {timeout:.0f} s "
                              "(start the segmentation and mining nodes, or set window:=0)")
                return False
            time.sleep(0.05)
        return False

    def _publish_all(self) -> None:
        window = int(self.get_parameter("window").value)
        rate = float(self.get_parameter("rate").value)
        stall_timeout = float(self.get_parameter("stall_timeout").value)
        if not self._wait_for_consumers(window > 0, stall_timeout):
            self.get_logger().error(self.error)
            self.end_pub.publish(UInt64(data=0))
            self.finished.set()
            return
        meter = Progress(self.stream.count, "bag_reader")
        start = time.monotonic()
        try:
            with self.stream:
                for frame in self.stream:
                    if window > 0 and not self._wait_for_credit(window, stall_timeout):
                        break
                    if self._stop.is_set():
                        break
                    if rate > 0:
                        time.sleep(max(0.0, start + self.published / rate - time.monotonic()))
                    if self.frame_hook:
                        self.frame_hook(frame.rgb)
                    seconds, nanoseconds = divmod(frame.stamp_ns, 1_000_000_000)
                    header = Header(frame_id=frame.frame_id)
                    header.stamp.sec, header.stamp.nanosec = int(seconds), int(nanoseconds)
                    self.image_pub.publish(image_message(frame.rgb, header))
                    self.published += 1
                    meter.advance()
        except BagError as error:
            self.error = str(error)
        if self.error:
            self.get_logger().error(self.error)
        self.end_pub.publish(UInt64(data=self.published))
        # Reliable delivery needs the writer alive until the subscribers have acknowledged.
        if not self.image_pub.wait_for_all_acked(Duration(seconds=stall_timeout)):
            self.get_logger().warning("not every image was acknowledged before the end of the bag")
        self.get_logger().info(f"end of bag: {self.published} frames published")
        self.finished.set()


def main(args: list[str] | None = None) -> None:
    def body() -> int:
        node = BagReaderNode()
        node.start()
        while rclpy.ok() and not node.finished.is_set():
            rclpy.spin_once(node, timeout_sec=0.1)
        node.destroy_node()
        return 1 if node.error else 0
    run_node("bag_reader", body, args)
