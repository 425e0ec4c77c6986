"""Mining node: accumulates plane graphs, mines them window by window and tracks them chunk by
chunk as they come (:mod:`trap_core.pipeline.chunks`); publishes ``detections`` (one
``vision_msgs/Detection2DArray`` per frame, header = that frame's image header) as soon as a
chunk makes them final, and at the end of the bag the rest of them, ``tracks`` (one
Detection2DArray per track, latched) and ``trajectories`` (``visualization_msgs/MarkerArray``).
Acknowledges every graph on ``progress`` (the bag reader's flow control).
"""
from __future__ import annotations

import threading
from collections.abc import Callable

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import CompressedImage
from std_msgs.msg import Header, UInt64
from vision_msgs.msg import Detection2DArray
from visualization_msgs.msg import MarkerArray

from trap_core.pipeline import GRAPH_STAGE, ChunkedRun, ChunkedTracker, TrapParams
from trap_ros.messages import frame_detections, message_graph, track_arrays, trajectory_markers
from trap_ros.node_main import run_node
from trap_ros.parameters import declare_trap_parameters, trap_parameters
from trap_ros.qos import LATCHED, PIPELINE

MINING_STAGE = tuple(name for name in TrapParams().as_dict() if name not in GRAPH_STAGE)


class MiningNode(Node):
    """See the module docstring. ``on_done(result, published)`` is called after publishing."""

    def __init__(self, on_done: Callable[[ChunkedRun | None, dict], None] | None = None, **kwargs) -> None:
        kwargs.setdefault("namespace", "trap")
        super().__init__("mining", **kwargs)
        declare_trap_parameters(self, MINING_STAGE)
        self.params = trap_parameters(self, MINING_STAGE)
        self.tracker = ChunkedTracker(self.params)
        self.regions = 0  # summed over the frames received
        self.camera_steps_read = 0  # frames received whose camera step was read from the images
        self.headers: list[Header] = []
        self.expected: int | None = None
        self.on_done = on_done
        self.done = threading.Event()
        self.result: ChunkedRun | None = None
        self.error: str | None = None
        self.published: dict[str, list] = {"detections": [], "tracks": [], "trajectories": []}
        self._started = False
        self._lock = threading.Lock()
        self.progress_pub = self.create_publisher(UInt64, "progress", PIPELINE)
        self.detections_pub = self.create_publisher(Detection2DArray, "detections", PIPELINE)
        self.tracks_pub = self.create_publisher(Detection2DArray, "tracks", LATCHED)
        self.trajectories_pub = self.create_publisher(MarkerArray, "trajectories", LATCHED)
        self.create_subscription(CompressedImage, "graph", self._on_graph, PIPELINE)
        self.create_subscription(UInt64, "end_of_bag", self._on_end, LATCHED)

    @property
    def received(self) -> int:
        """Graphs received (one header kept per graph)."""
        return len(self.headers)

    def _on_graph(self, message: CompressedImage) -> None:
        graph = message_graph(message)
        with self._lock:  # windows are mined here, while later frames are being segmented
            if self._started:
                return
            self.headers.append(message.header)
            self.regions += graph.n_nodes
            self.camera_steps_read += graph.has_camera_step
            try:
                self.tracker.add(graph)
                self._publish_final()
            except Exception as error:  # a chunk failed: reported, the run ends with an error
                self._fail(error)
            count = self.received
        self.progress_pub.publish(UInt64(data=count))
        self._maybe_finish()

    def _on_end(self, message: UInt64) -> None:
        self.expected = int(message.data)
        self.get_logger().info(f"end of bag announced: {self.expected} frames")
        self._maybe_finish()

    def _maybe_finish(self) -> None:
        with self._lock:
            ready = self.expected is not None and self.received >= self.expected and not self._started
            self._started = self._started or ready
        if ready:
            threading.Thread(target=self._track_and_publish, name="trap-tracking", daemon=True).start()

    def finish(self) -> None:
        """Track over the graphs received so far and publish (after an interrupt); if tracking
        has started already, wait for it instead of tracking twice."""
        with self._lock:
            running = self._started
            self._started = True
        if running:
            self.done.wait()
        else:
            self._track_and_publish()

    def _publish_final(self) -> None:
        """Publish the detections of the frames the tracker has made final since the last call."""
        first = len(self.published["detections"])
        stop = self.tracker.final_frames
        if stop > first:
            pieces = self.tracker.take_final()
            if stop < self.received:  # a chunk was tracked while the bag plays
                self.get_logger().info(f"chunk {len(self.tracker.run.chunks)} tracked: detections of frames "
                                       f"{first + 1}-{stop} final ({len({p.track_id for p in pieces})} tracks there)")
            messages = frame_detections(self.headers, pieces, first, stop)
            for message in messages:
                self.detections_pub.publish(message)
            self.published["detections"] += messages

    def _fail(self, error: Exception) -> None:
        self.error = f"tracking failed: {error}"
        self.get_logger().error(self.error)

    def _track_and_publish(self) -> None:
        try:
            with self._lock:  # no graph is added from here on (_started is set)
                if self.received >= 2:
                    self.get_logger().info(f"tracking over {self.received} frames")
                    self.result = self.tracker.finish()
                    self._publish_final()
                else:
                    self.get_logger().warning(f"{self.received} frame(s): too few to track")
            if self.result is not None:
                self.published["tracks"] = track_arrays(self.headers, self.result.tracks)
                for message in self.published["tracks"]:
                    self.tracks_pub.publish(message)
                markers = trajectory_markers(self.headers[0], self.result.tracks)
                self.trajectories_pub.publish(markers)  # empty when nothing was tracked: latched all the same
                self.published["trajectories"] = [markers] if markers.markers else []  # recorded at its stamp
                self.get_logger().info(f"{len(self.result.tracks)} tracks published")
        except Exception as error:  # reported, never swallowed: the run ends with an error
            self._fail(error)
        if self.on_done:
            self.on_done(self.result, self.published)
        self.done.set()


def main(args: list[str] | None = None) -> None:
    def body() -> int:
        node = MiningNode()
        while rclpy.ok() and not node.done.is_set():
            rclpy.spin_once(node, timeout_sec=0.1)
        for _ in range(20):  # let late subscribers fetch the latched results
            rclpy.spin_once(node, timeout_sec=0.05)
        return 1 if node.error else 0
    run_node("mining", body, args)
