"""``ros2 run trap_ros process_bag BAG``: the bag reader, segmentation and mining nodes in one
process, each spun in its own thread; results written to ``--out``:

- ``tracks.mcap``: every output topic (detections, tracks, trajectories);
- ``tracks.txt``: MOTChallenge rows ``frame,id,x,y,w,h,conf,-1,-1,-1`` (frame 1-based);
- ``summary.json``: parameters, counts, per-stage times, whether the run was interrupted;
- ``tracks.png``: a contact sheet of frames with the tracks drawn;
- ``timeline.png``: which track is seen (or inferred) in which frames, chunk borders marked.
"""
from __future__ import annotations

import argparse
import dataclasses
import shutil
import signal
import sys
import threading
import time
from pathlib import Path

import rclpy
import yaml
from rclpy.parameter import Parameter
from rclpy.signals import SignalHandlerOptions

from trap_core.cli import UsageError, parameter_assignment, results_folder, run_main
from trap_core.outputs import Thumbnails
from trap_core.pipeline import GRAPH_STAGE, BagRun, ParameterError, TrapParams
from trap_core.pipeline.bag_run import write_outputs
from trap_core.progress import Progress
from trap_ros.bag_reader_node import BagReaderNode
from trap_ros.memory import limit_malloc_arenas
from trap_ros.mining_node import MiningNode
from trap_ros.recording import write_results_bag
from trap_ros.segmentation_node import SegmentationNode
from trap_ros.spinning import NodeSpinners

READER_PARAMETERS = ("bag", "topic", "rate", "window", "stall_timeout", "publish_markers")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="process_bag", description="Track objects in a camera bag with TRAP.",
                                     epilog="ROS arguments: --ros-args --params-file FILE -p name:=value")
    parser.add_argument("bag", type=Path, help="ROS 2 bag folder, .mcap, .db3 or ROS 1 .bag")
    parser.add_argument("--topic", help="image topic (default: the only image topic of the bag)")
    parser.add_argument("--out", type=Path, default=Path("results"), help="output folder (default: results)")
    parser.add_argument("--objects", type=int, help="number of objects (default: found without supervision)")
    return parser


def checked_parameters(ros_args: list[str], objects: int | None) -> TrapParams:
    """Validate the parameters given on the command line before any node starts."""
    values: dict[str, object] = {}
    i = 0
    while i < len(ros_args):
        if ros_args[i] in ("--params-file", "-p") and i + 1 >= len(ros_args):
            raise UsageError(f"{ros_args[i]} needs a value")
        if ros_args[i] == "--params-file":
            try:
                content = yaml.safe_load(Path(ros_args[i + 1]).read_text()) or {}
            except (OSError, yaml.YAMLError) as error:
                raise UsageError(f"cannot read parameter file {ros_args[i + 1]}: {' '.join(str(error).split())}") \
                    from None
            for body in content.values():
                if isinstance(body, dict) and isinstance(body.get("ros__parameters"), dict):
                    values.update(body["ros__parameters"])
        elif ros_args[i] == "-p":
            name, value = parameter_assignment(ros_args[i + 1])
            values[name] = value
        i += 2 if ros_args[i] in ("--params-file", "-p") else 1
    values = {k: v for k, v in values.items() if k not in READER_PARAMETERS}
    if objects is not None:
        values["n_objects"] = objects
    try:
        return TrapParams.from_mapping(values)
    except ParameterError as error:
        raise UsageError(str(error)) from None


def _await_tracking(mining: MiningNode, interrupt: threading.Event, seconds: float = 60.0) -> None:
    """Wait for the mining node to track the frames announced; after ``seconds``, or at once on a
    (further) Ctrl-C, it tracks over what has arrived."""
    deadline = time.monotonic() + seconds
    while not mining.done.wait(timeout=0.2):
        if interrupt.is_set() or time.monotonic() > deadline:
            mining.finish()
            break


def _main() -> int:
    argv = sys.argv[1:]
    split = argv.index("--ros-args") if "--ros-args" in argv else len(argv)
    args = build_parser().parse_args(argv[:split])
    ros_args = argv[split + 1:]
    checked_parameters(ros_args, args.objects)  # refuse bad parameters before any node starts
    results_folder(args.out)
    if (args.out / "tracks.mcap").exists():
        shutil.rmtree(args.out / "tracks.mcap")
    # SIGINT is ours: the nodes must stay usable to finish on the frames read so far. The handler
    # only sets a flag the main loop polls: a KeyboardInterrupt raised wherever the main thread is
    # (a finaliser run by the garbage collector swallows it) could be lost, and Ctrl-C with it.
    interrupt = threading.Event()
    previous_handler = signal.signal(signal.SIGINT, lambda signum, frame: interrupt.set())
    rclpy.init(args=["process_bag", "--ros-args", *ros_args], signal_handler_options=SignalHandlerOptions.NO)
    nodes = []
    try:
        reader = BagReaderNode(parameter_overrides=[Parameter("bag", value=str(args.bag)),
                                                    Parameter("topic", value=args.topic or "")])
        nodes.append(reader)
        keeper = Thumbnails(reader.total or 0)
        reader.frame_hook = keeper
        markers = any(a.startswith("publish_markers:=") for a in ros_args)
        segmentation = SegmentationNode(parameter_overrides=[] if markers else [Parameter("publish_markers", value=False)])
        nodes.append(segmentation)
        overrides = [Parameter("n_objects", value=args.objects)] if args.objects is not None else []
        mining = MiningNode(parameter_overrides=overrides)
        nodes.append(mining)
        spinners = NodeSpinners(nodes)
        meter = Progress(reader.total, "process_bag")
        start = time.perf_counter()
        interrupted = False
        spinners.start()
        reader.start()
        while not mining.done.wait(timeout=0.2) and not interrupt.is_set():
            if segmentation.error:  # the first frame was refused: nothing to track
                reader.stop()
                reader.finished.wait(timeout=5.0)
                spinners.stop()
                raise UsageError(segmentation.error)
            if reader.error and reader.finished.is_set():
                # The reader stopped on a bad frame and announced what it published before it:
                # those frames are tracked and written as at a normal end, then the error is raised.
                _await_tracking(mining, interrupt)
                break
            if mining.received > meter.done:
                meter.advance(mining.received - meter.done)
        if interrupt.is_set() and not mining.done.is_set():
            # Stop reading; the reader announces what it published, the frames in flight are
            # segmented and mined, and the mining node tracks over all of them as at a normal end.
            interrupted = True
            interrupt.clear()
            reader.stop()
            _await_tracking(mining, interrupt)
        meter.advance(mining.received - meter.done)
        meter.finish()
        spinners.stop()  # the nodes are destroyed below: not while a callback may still run
        seconds = {"total": time.perf_counter() - start, **(mining.result.seconds if mining.result else {})}
        run = BagRun(reader.stream.topic, mining.received, mining.regions / max(mining.received, 1), mining.result,
                     seconds, {}, interrupted, mining.camera_steps_read)
        # Each node holds the parameters of its own stages; the summary reports the run's.
        graph_stage = {name: getattr(segmentation.params, name) for name in GRAPH_STAGE}
        params = dataclasses.replace(mining.params, **graph_stage)
        write_outputs(run, args.bag, args.out, params, keeper.images, keeper.scale)
        run.outputs["tracks.mcap"] = str(write_results_bag(args.out / "tracks.mcap", mining.published))
        tracks = len(mining.result.tracks) if mining.result else 0
        print(f"{tracks} tracks over {run.frames} frames{' (interrupted)' if interrupted else ''}; "
              f"results in {args.out}: tracks.mcap, tracks.txt, summary.json, tracks.png, timeline.png")
        if mining.error:
            raise UsageError(mining.error)
        if reader.error:  # the frames read before it are tracked and written above
            raise UsageError(reader.error)
        return 130 if interrupted else 0
    finally:
        for node in nodes:
            node.destroy_node()
        if rclpy.ok():
            rclpy.shutdown()
        signal.signal(signal.SIGINT, previous_handler)


def main() -> None:
    # Several threads (reader, node spinners, segmentation pool) hand the GIL to each other per frame;
    # with the default 5 ms switch interval they queue behind each other (measured: 7 vs 45 fps).
    sys.setswitchinterval(0.0005)
    limit_malloc_arenas()
    sys.exit(run_main(_main, "process_bag"))
