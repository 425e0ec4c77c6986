"""The ROS 2 node set with the real rclpy: in one process, across processes over DDS, process_bag,
and a colcon build whose installed process_bag (what `ros2 run` executes) runs."""
from __future__ import annotations

import gc
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

rclpy = pytest.importorskip("rclpy")
from rclpy.context import Context  # noqa: E402
from rclpy.parameter import Parameter  # noqa: E402
from sensor_msgs.msg import CompressedImage  # noqa: E402
from vision_msgs.msg import Detection2DArray  # noqa: E402

from trap_core.bagio import open_image_stream  # noqa: E402
from trap_core.motformat import read_mot  # noqa: E402
from trap_core.pipeline import TrapParams, frame_graph, run_bag  # noqa: E402
from trap_core.synthetic import SceneConfig, write_synthetic  # noqa: E402
from trap_ros.bag_reader_node import BagReaderNode  # noqa: E402
from trap_ros.messages import message_graph  # noqa: E402
from trap_ros.mining_node import MiningNode  # noqa: E402
from trap_ros.qos import PIPELINE  # noqa: E402
from trap_ros.segmentation_node import SegmentationNode  # noqa: E402
from trap_ros.spinning import NodeSpinners  # noqa: E402

TOP = Path(__file__).resolve().parents[1]
SYNTHETIC = [Parameter("segmentation", value="colour")]


@pytest.fixture(scope="module")
def ros_bag(tmp_path_factory: pytest.TempPathFactory) -> Path:
    bag, _ = write_synthetic(SceneConfig(width=320, height=240, frames=60, seed=4),
                             tmp_path_factory.mktemp("rosbags") / "small")
    return bag


def _env() -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k != "_ROS_WHEELS_BOOTSTRAP_COMPLETE"}
    env.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    env["FASTRTPS_DEFAULT_PROFILES_FILE"] = str(TOP / "config" / "fastdds_profile.xml")
    return env


class SlowMiningNode(MiningNode):
    """A mining node that takes its time with every graph: the reader must wait, not drop."""

    def _on_graph(self, message: CompressedImage) -> None:
        time.sleep(0.02)
        super()._on_graph(message)


def test_nodes_in_one_process_lose_no_frame_and_keep_headers(ros_bag: Path) -> None:
    context = Context()
    rclpy.init(context=context)
    try:
        reader = BagReaderNode(context=context, parameter_overrides=[Parameter("bag", value=str(ros_bag)),
                                                                     Parameter("window", value=4)])
        segmentation = SegmentationNode(context=context, parameter_overrides=SYNTHETIC)
        mining = SlowMiningNode(context=context)
        listener = rclpy.create_node("listener", context=context)
        received: list[Detection2DArray] = []
        listener.create_subscription(Detection2DArray, "/trap/detections", received.append, PIPELINE)
        spinners = NodeSpinners((reader, segmentation, mining, listener), context)
        spinners.start()
        reader.start()
        assert mining.done.wait(timeout=120)
        deadline = time.monotonic() + 10
        while len(received) < 60 and time.monotonic() < deadline:
            time.sleep(0.05)
        spinners.stop()
        with open_image_stream(ros_bag) as stream:
            stamps = [frame.stamp_ns for frame in stream]
        assert reader.published == mining.received == len(received) == 60
        got = [m.header.stamp.sec * 1_000_000_000 + m.header.stamp.nanosec for m in received]
        assert got == stamps
        assert {m.header.frame_id for m in received} == {"camera"}
        assert mining.result is not None and mining.result.tracks
        ids = {d.id for m in received for d in m.detections}
        assert ids == {str(t.track_id) for t in mining.result.tracks}
        for node in (reader, segmentation, mining, listener):
            node.destroy_node()
    finally:
        rclpy.shutdown(context=context)


def test_stopped_spinners_leave_no_callback_to_fail_on_destroyed_nodes(capfd: pytest.CaptureFixture[str]) -> None:
    """Busy nodes (slow timers, more of them than threads could serve at once) are stopped and
    destroyed: every callback that started has finished, and none fails afterwards on a destroyed
    handle (rclpy prints "exception was never retrieved" when a failed callback is collected)."""
    context = Context()
    rclpy.init(context=context)
    started, finished = [], []

    def slow() -> None:
        started.append(1)
        time.sleep(0.05)
        finished.append(1)
    try:
        nodes = [rclpy.create_node(f"busy_{k}", context=context) for k in range(3)]
        for node in nodes:
            node.create_timer(0.005, slow)
        spinners = NodeSpinners(nodes, context)
        spinners.start()
        time.sleep(0.5)
        spinners.stop()
        assert len(started) == len(finished) > 3
        for node in nodes:
            node.destroy_node()
        time.sleep(0.3)
        del spinners
        gc.collect()
        assert len(started) == len(finished)
    finally:
        rclpy.shutdown(context=context)
    assert "never retrieved" not in capfd.readouterr().err


def test_segmentation_node_skips_frames_it_cannot_track_and_goes_on(ros_bag: Path) -> None:
    """On a live topic, a frame of an unknown encoding, a malformed one, a tiny one or one of
    another size than the first (a camera reconfigured) is skipped with an error line; the node
    keeps segmenting the frames after it."""
    from std_msgs.msg import Header

    from trap_ros.messages import image_message
    with open_image_stream(ros_bag) as stream:
        frames = [frame.rgb for frame, _ in zip(stream, range(2))]
    context = Context()
    rclpy.init(context=context)
    try:
        node = SegmentationNode(context=context, parameter_overrides=SYNTHETIC)
        listener = rclpy.create_node("graphs", context=context)  # the node publishes to a subscriber only
        listener.create_subscription(CompressedImage, "/trap/graph", lambda _: None, PIPELINE)
        good = [image_message(rgb, Header(frame_id="c")) for rgb in frames]
        unknown = image_message(frames[0], Header(frame_id="c"))
        unknown.encoding = "16UC2"
        short = image_message(frames[0], Header(frame_id="c"))
        short.data = short.data[:100]
        tiny = image_message(frames[0][:8, :8], Header(frame_id="c"))
        larger = image_message(np.zeros((480, 640, 3), np.uint8), Header(frame_id="c"))
        for message in (good[0], unknown, short, tiny, larger, good[1]):
            node._on_image(message)
        assert node.errors == 4 and len(node.pending) + node.published == 2
        node.destroy_node()
        listener.destroy_node()
    finally:
        rclpy.shutdown(context=context)


def test_node_parameter_names_do_not_collide() -> None:
    """A parameter file applies to every node (``/**``): the reader's own parameters must not
    share a name with a TRAP parameter, or one would silently set the other."""
    from trap_ros.process_bag import READER_PARAMETERS
    assert set(READER_PARAMETERS).isdisjoint(TrapParams().as_dict())


def test_graph_message_is_lossless(ros_bag: Path) -> None:
    from std_msgs.msg import Header

    from trap_ros.messages import graph_message
    with open_image_stream(ros_bag) as stream:
        first, second = (frame.rgb for frame, _ in zip(stream, range(2)))
    graph = frame_graph(second, TrapParams(segmentation="colour"), first)  # with the camera's step from the first
    assert graph.has_camera_step
    from rclpy.serialization import deserialize_message, serialize_message
    wire = deserialize_message(serialize_message(graph_message(graph, Header(frame_id="c"))), CompressedImage)
    back = message_graph(wire)
    for name in graph.__dataclass_fields__:
        assert np.array_equal(getattr(graph, name), getattr(back, name)), name


def test_reader_and_segmentation_in_two_processes(ros_bag: Path, venv_bin: Path) -> None:
    env = _env()
    common = ["--ros-args", "-p", "segmentation:=colour", "-p", f"bag:={ros_bag}", "-p", "window:=0"]
    context = Context()
    rclpy.init(context=context)
    graphs: list[CompressedImage] = []
    listener = rclpy.create_node("graph_listener", context=context)
    listener.create_subscription(CompressedImage, "/trap/graph", graphs.append, PIPELINE)
    segmentation = subprocess.Popen([str(venv_bin / "segmentation_node"), *common], env=env,
                                    stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    reader = None
    try:
        reader = subprocess.Popen([str(venv_bin / "bag_reader_node"), *common], env=env,
                                  stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        executor = rclpy.executors.SingleThreadedExecutor(context=context)
        executor.add_node(listener)
        deadline = time.monotonic() + 90
        while len(graphs) < 60 and time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.1)
        assert reader.wait(timeout=30) == 0
        assert len(graphs) == 60
        with open_image_stream(ros_bag) as stream:
            first = next(iter(stream)).rgb
        expected = frame_graph(first, TrapParams(segmentation="colour"))
        assert np.array_equal(message_graph(graphs[0]).he_next, expected.he_next)
    finally:
        for process in (reader, segmentation):
            if process and process.poll() is None:
                process.send_signal(signal.SIGINT)
                try:
                    process.wait(timeout=15)
                except subprocess.TimeoutExpired:
                    process.kill()
        listener.destroy_node()
        rclpy.shutdown(context=context)


def _process_bag(executable: Path, bag: Path, out: Path, *extra: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(executable), str(bag), "--out", str(out), *extra], env=_env(), capture_output=True,
                          text=True, timeout=300)


@pytest.mark.parametrize("overrides,chunks", [  # the bag in one window; in two, stitched; in two chunks; the paper's
    ({"mining_window": 1500}, 1), ({"mining_window": 51}, 1), ({"tau": 5, "chunk": 20}, 2), ({"method": "paper"}, 1)])
def test_process_bag_writes_every_output_and_matches_the_core_pipeline(ros_bag: Path, venv_bin: Path,
                                                                        tmp_path: Path, overrides: dict,
                                                                        chunks: int) -> None:
    assignments = [arg for name, value in overrides.items() for arg in ("-p", f"{name}:={value}")]
    done = _process_bag(venv_bin / "process_bag", ros_bag, tmp_path / "ros", "--ros-args", "--params-file",
                        str(TOP / "config" / "synthetic.yaml"), *assignments)
    assert done.returncode == 0, done.stderr[-2000:]
    out = tmp_path / "ros"
    summary = json.loads((out / "summary.json").read_text())
    assert summary["frames"] == 60 and not summary["interrupted"] and summary["counts"]["tracks"] >= 1
    assert summary["counts"]["chunks"] == chunks
    # a panning synthetic scene: every step read, but where the method never looks at it
    steps = 0 if overrides.get("method") == "paper" else 59
    assert summary["counts"]["camera_steps_from_images"] == steps
    assert summary["parameters"]["segmentation"] == "colour"  # the segmentation node's, not a default
    assert (out / "tracks.png").stat().st_size > 1000 and (out / "timeline.png").stat().st_size > 1000
    from rosbags.highlevel import AnyReader
    with AnyReader([out / "tracks.mcap"]) as reader:
        counts = {c.topic: c.msgcount for c in reader.connections}
        assert counts["/trap/detections"] == 60 and counts["/trap/tracks"] == summary["counts"]["tracks"]
        connection = next(c for c in reader.connections if c.topic == "/trap/detections")
        _, _, raw = next(reader.messages(connections=[connection]))
        message = reader.deserialize(raw, connection.msgtype)
        assert message.header.frame_id == "camera"
    core = run_bag(ros_bag, tmp_path / "core", TrapParams(segmentation="colour", **overrides))
    assert core.frames == 60 and core.camera_steps_read == steps
    np.testing.assert_allclose(read_mot(out / "tracks.txt"), read_mot(tmp_path / "core" / "tracks.txt"))


def test_process_bag_sigint_leaves_valid_partial_outputs(venv_bin: Path, tmp_path: Path) -> None:
    bag, _ = write_synthetic(SceneConfig(width=320, height=240, frames=600, seed=2), tmp_path / "long")
    process = subprocess.Popen([str(venv_bin / "process_bag"), str(bag), "--out", str(tmp_path / "out"),
                                "--ros-args", "-p", "segmentation:=felzenszwalb"], env=_env(),
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = ""
    while "process_bag: " not in line or "/600" not in line:  # wait for the first progress line
        line = process.stderr.readline()
        assert line or process.poll() is None
    time.sleep(1.0)
    process.send_signal(signal.SIGINT)
    _, err = process.communicate(timeout=120)
    assert process.returncode == 130, err[-2000:]
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["interrupted"] and 0 < summary["frames"] < 600
    from rosbags.highlevel import AnyReader
    with AnyReader([tmp_path / "out" / "tracks.mcap"]) as reader:
        assert {c.topic: c.msgcount for c in reader.connections}["/trap/detections"] == summary["frames"]


def test_process_bag_keeps_what_it_read_before_a_bad_frame_and_fails(venv_bin: Path, tmp_path: Path) -> None:
    """A 4x4 frame after 40 good ones: those 40 are tracked and written, then one error line, exit 1."""
    from trap_core.bagio import write_image_bag
    from trap_core.synthetic.scene import render
    frames = [rendered.rgb for rendered in render(SceneConfig(width=320, height=240, frames=40, seed=4))]
    write_image_bag(tmp_path / "bag", [*frames, np.zeros((4, 4, 3), np.uint8)])
    done = _process_bag(venv_bin / "process_bag", tmp_path / "bag", tmp_path / "out", "--ros-args", "-p",
                        "segmentation:=colour")
    assert done.returncode == 1
    lines = done.stderr.strip().splitlines()
    errors = [k for k, line in enumerate(lines) if line.startswith("process_bag: error:")]
    assert len(errors) == 1 and "frame 40" in lines[errors[0]] and "too small to track" in lines[errors[0]]
    assert errors[0] == len(lines) - 1, lines[errors[0]:]  # the last line: nothing printed after it
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["frames"] == 40
    from rosbags.highlevel import AnyReader
    with AnyReader([tmp_path / "out" / "tracks.mcap"]) as reader:
        assert {c.topic: c.msgcount for c in reader.connections}["/trap/detections"] == 40


def test_process_bag_refuses_exact_colour_regions_on_a_noisy_bag_at_once(venv_bin: Path, tmp_path: Path) -> None:
    """Exact-colour regions on noisy frames: one error line, last, exit 1, and no hang."""
    bag, _ = write_synthetic(SceneConfig(width=320, height=240, frames=40, seed=4, noise=2.0), tmp_path / "noisy")
    done = _process_bag(venv_bin / "process_bag", bag, tmp_path / "out", "--ros-args", "-p", "segmentation:=colour")
    assert done.returncode == 1
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith("process_bag: error: segmentation colour: the first frame has ") and \
        last.endswith("use segmentation:=felzenszwalb"), done.stderr[-2000:]


def test_process_bag_segments_a_textured_bag_with_the_k_fitted_to_its_first_frame(venv_bin: Path, tmp_path: Path,
                                                                                  textured_frames: list) -> None:
    """The segmentation node fits k on the first frame (max_regions); the summary reports it."""
    from trap_core.bagio import write_image_bag
    from trap_core.pipeline import fitted_to_regions
    frames = textured_frames
    write_image_bag(tmp_path / "bag", frames)
    done = _process_bag(venv_bin / "process_bag", tmp_path / "bag", tmp_path / "out", "--ros-args", "-p",
                        "max_regions:=60")
    assert done.returncode == 0, done.stderr[-2000:]
    used = json.loads((tmp_path / "out" / "summary.json").read_text())["parameters"]
    assert used["k"] == fitted_to_regions(frames[0], TrapParams(max_regions=60)).k > 7
    assert f"k raised from 7 to {used['k']:g}" in done.stderr + done.stdout


def test_process_bag_with_nothing_to_track_writes_every_output(venv_bin: Path, tmp_path: Path) -> None:
    """A camera panning over a scene without objects (in tiny frames): 0 tracks is a result, not an error."""
    bag, _ = write_synthetic(SceneConfig(width=96, height=72, frames=120, objects=0), tmp_path / "tiny")
    done = _process_bag(venv_bin / "process_bag", bag, tmp_path / "out")
    assert done.returncode == 0, done.stderr[-2000:]
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["frames"] == 120 and summary["counts"]["tracks"] == 0
    from rosbags.highlevel import AnyReader
    with AnyReader([tmp_path / "out" / "tracks.mcap"]) as reader:
        counts = {c.topic: c.msgcount for c in reader.connections}
    assert counts["/trap/detections"] == 120 and counts["/trap/tracks"] == 0 and counts["/trap/trajectories"] == 0


@pytest.mark.parametrize("args,pattern", [
    (["-p", "eps:=-1"], "eps must be > 0"),
    (["-p", "epsilon:=3"], "unknown parameter(s): epsilon"),
    (["-p", "max_faces:=2.5"], "must be an integer"),
    (["-p", "chunk:=50"], "chunk must be 0 (whole bag) or at least 4 x tau"),
])
def test_process_bag_refuses_bad_parameters(ros_bag: Path, venv_bin: Path, tmp_path: Path, args: list[str],
                                            pattern: str) -> None:
    done = _process_bag(venv_bin / "process_bag", ros_bag, tmp_path / "o", "--ros-args", *args)
    assert done.returncode == 1
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and pattern in lines[0], done.stderr


def test_colcon_build_installs_a_runnable_process_bag(ros_bag: Path, tmp_path: Path) -> None:
    colcon = Path(sys.executable).parent / "colcon"
    if not colcon.exists():
        pytest.skip("colcon is not installed in this environment")
    source = tmp_path / "ws" / "src" / "trap_ros"
    shutil.copytree(TOP, source, ignore=shutil.ignore_patterns(".venv", ".git", "build", "install", "log",
                                                               "example", "results", "__pycache__", "*.egg-info"))
    env = _env()
    built = subprocess.run([str(colcon), "build", "--packages-select", "trap_ros"], cwd=tmp_path / "ws", env=env,
                           capture_output=True, text=True, timeout=300)
    assert built.returncode == 0, built.stdout[-3000:] + built.stderr[-3000:]
    executable = tmp_path / "ws" / "install" / "trap_ros" / "lib" / "trap_ros" / "process_bag"
    assert executable.exists()
    site = next((tmp_path / "ws" / "install" / "trap_ros" / "lib").glob("python3*/site-packages"))
    env["PYTHONPATH"] = f"{site}{os.pathsep}{env.get('PYTHONPATH', '')}"
    env["AMENT_PREFIX_PATH"] = f"{tmp_path / 'ws' / 'install' / 'trap_ros'}{os.pathsep}{sys.prefix}"
    done = subprocess.run([str(executable), str(ros_bag), "--out", str(tmp_path / "out"), "--ros-args", "-p",
                           "segmentation:=colour"], env=env, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert (tmp_path / "out" / "tracks.txt").exists()
    share = tmp_path / "ws" / "install" / "trap_ros" / "share"
    assert (share / "ament_index" / "resource_index" / "packages" / "trap_ros").exists()
    assert (share / "trap_ros" / "config" / "trap.yaml").exists()
