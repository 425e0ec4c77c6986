"""Segmentation/RAG node: ``image`` in, each frame's plane graph out on ``graph``.

Frames are segmented on ``threads`` threads at once (the compiled kernels release the GIL)
and the graphs are published strictly in the order the images came, with the image's header.
Also publishes ``graph_markers`` (regions and contacts) for RViz / Foxglove.
"""
from __future__ import annotations

import sys
import threading
import time
from collections import deque
from concurrent.futures import Future, ThreadPoolExecutor

import numpy as np
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import CompressedImage, Image
from visualization_msgs.msg import MarkerArray

from trap_core.bagio import BagError, FrameSize, SampleRange
from trap_core.pipeline import GRAPH_STAGE, IMAGE_STEP_STAGE, first_frame_setup, frame_graph
from trap_core.segmentation import SegmentationError
from trap_ros.messages import graph_markers, graph_message, image_rgb
from trap_ros.node_main import run_node
from trap_ros.parameters import declare_trap_parameters, trap_parameters
from trap_ros.qos import PIPELINE


class SegmentationNode(Node):
    """See the module docstring."""

    def __init__(self, **kwargs) -> None:
        kwargs.setdefault("namespace", "trap")
        super().__init__("segmentation", **kwargs)
        declare_trap_parameters(self, GRAPH_STAGE + IMAGE_STEP_STAGE)
        self.declare_parameter("publish_markers", True)
        self.params = trap_parameters(self, GRAPH_STAGE + IMAGE_STEP_STAGE)
        self.markers = bool(self.get_parameter("publish_markers").value)
        self.graph_pub = self.create_publisher(CompressedImage, "graph", PIPELINE)
        self.marker_pub = self.create_publisher(MarkerArray, "graph_markers", PIPELINE)
        self.pool = ThreadPoolExecutor(self.params.threads, thread_name_prefix="trap-seg")
        self.pending: deque[tuple[Future, object]] = deque()
        self.lock = threading.Lock()
        self.published = 0
        self.errors = 0
        self.fitted = False  # whether the first frame set the segmentation up (first_frame_setup)
        # the last frame submitted, where tracking reads the camera's step from the images (read from it)
        self.previous: np.ndarray | None = None
        self.error: str | None = None  # why no frame can be segmented (first_frame_setup refused the first)
        self.sample_range = SampleRange()  # how wide samples (16-bit, depth) become 8-bit, fixed on the first frame
        self.frame_size = FrameSize()  # every frame the first one's size
        self.create_subscription(Image, "image", self._on_image, PIPELINE)
        self.create_timer(0.02, self.publish_done)

    def _on_image(self, message: Image) -> None:
        try:
            rgb = image_rgb(message, self.sample_range)
            self.frame_size.check(rgb)
        except BagError as error:
            self.errors += 1
            self.get_logger().error(f"frame skipped: {error}")
            return
        with self.lock:
            if self.error:
                return
            if not self.fitted:  # one segmentation scale for the whole video, from its first frame
                self.fitted = True
                try:
                    self.params, notes = first_frame_setup(rgb, self.params)
                except SegmentationError as error:
                    self.error = str(error)
                    self.get_logger().error(self.error)
                    return
                for note in notes:  # a fitted parameter is information; a scene that may go untracked, a warning
                    (self.get_logger().warning if note.warns else self.get_logger().info)(note)
            self.pending.append((self.pool.submit(frame_graph, rgb, self.params, self.previous), message.header))
            self.previous = rgb if self.params.reads_image_steps else None
            self._publish_ready(block=len(self.pending) > 2 * self.params.threads)

    def _downstream_ready(self, block: bool) -> bool:
        """Graphs published before a subscriber is matched would be lost: before the first one,
        wait for a subscriber (up to 60 s when the queue is full, then publish anyway)."""
        if self.published or self.graph_pub.get_subscription_count() > 0:
            return True
        if not block:
            return False
        deadline = time.monotonic() + 60.0
        while self.graph_pub.get_subscription_count() == 0 and time.monotonic() < deadline:
            time.sleep(0.05)
        if self.graph_pub.get_subscription_count() == 0:
            self.get_logger().warning("no subscriber to the graphs after 60 s; publishing anyway")
        return True

    def _publish_ready(self, block: bool) -> None:
        """Publish finished graphs from the front of the queue (in order)."""
        while self.pending and (block or self.pending[0][0].done()) and self._downstream_ready(block):
            future, header = self.pending.popleft()
            graph = future.result()
            self.graph_pub.publish(graph_message(graph, header))
            if self.markers:
                self.marker_pub.publish(graph_markers(header, graph))
            self.published += 1
            block = len(self.pending) > 2 * self.params.threads

    def publish_done(self) -> None:
        """Publish the graphs finished so far, in order (a timer calls this)."""
        with self.lock:
            self._publish_ready(block=False)

    def destroy_node(self) -> None:
        with self.lock:
            self._publish_ready(block=True)
        self.pool.shutdown(wait=True)
        super().destroy_node()


def main(args: list[str] | None = None) -> None:
    sys.setswitchinterval(0.0005)  # the executor and the segmentation threads trade the GIL per frame

    def body() -> int:
        node = SegmentationNode()
        while rclpy.ok() and not node.error:
            rclpy.spin_once(node, timeout_sec=0.1)
        return 1 if node.error else 0
    run_node("segmentation", body, args)
