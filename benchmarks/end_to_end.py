#!/usr/bin/env python3
"""Benchmark: TRAP end to end on the synthetic Anim1/Anim2 analogues (640x480, ~240 regions).

Prints a Markdown table and JSON: frames per second of each stage (decode, segmentation and
graph, mining, clustering), of ``process_bag`` end to end, peak RSS, the OpenCV trackers on the
same frames, and how time and memory grow with 721 / 2000 / 5600 frames (slope in ms/frame).
Run: ``.venv/bin/python benchmarks/end_to_end.py`` (about 10 minutes; ``--quick`` for less).
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import psutil

from trap_core.bagio import open_image_stream
from trap_core.pipeline import TrapParams, frame_graph, graphs_of, track
from trap_core.synthetic import PRESETS, SceneConfig, render, write_synthetic

TOP = Path(__file__).resolve().parents[1]


def _stage_rates(bag: Path, segmentation: str) -> dict[str, float]:
    params = TrapParams(segmentation=segmentation)
    start = time.perf_counter()
    with open_image_stream(bag) as stream:
        frames = [f.rgb for f in stream]
    decode = time.perf_counter() - start
    frame_graph(frames[0], params)  # compiled kernels loaded
    start = time.perf_counter()
    for previous, rgb in zip(frames[:100], frames[1:101]):  # with the camera's step, as graphs_of makes them
        frame_graph(rgb, params, previous)
    one_thread = (time.perf_counter() - start) / 100
    start = time.perf_counter()
    graphs = list(graphs_of(frames, params))
    graph_time = time.perf_counter() - start
    run = track(graphs, params)
    n = len(frames)
    return {"frames": n, "regions": float(np.mean([g.n_nodes for g in graphs])),
            "decode fps": n / decode, "segmentation+graph fps (1 thread)": 1 / one_thread,
            "segmentation+graph fps (2 threads)": n / graph_time,
            "mining fps": n / run.seconds["mining"],
            "clustering fps": n / (run.seconds["camera"] + run.seconds["distances"] + run.seconds["clustering"]),
            "patterns": run.mining.n_st, "tracks": len(run.tracks)}


def _process_bag(bag: Path, out: Path, segmentation: str) -> dict[str, float]:
    env = {k: v for k, v in os.environ.items() if k != "_ROS_WHEELS_BOOTSTRAP_COMPLETE"}
    env.update(ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST", FASTRTPS_DEFAULT_PROFILES_FILE=str(TOP / "config" /
                                                                                             "fastdds_profile.xml"))
    env.setdefault("ROS_DOMAIN_ID", str(40 + os.getpid() % 40))
    command = [str(Path(sys.executable).parent / "process_bag"), str(bag), "--out", str(out), "--ros-args", "-p",
               f"segmentation:={segmentation}"]
    start = time.perf_counter()
    process = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    watched = psutil.Process(process.pid)
    peak = 0
    while process.poll() is None:
        try:
            peak = max(peak, watched.memory_info().rss)
        except psutil.Error:
            pass
        time.sleep(0.1)
    seconds = time.perf_counter() - start
    frames = json.loads((out / "summary.json").read_text())["frames"] if process.returncode == 0 else 0
    return {"process_bag fps": frames / seconds, "process_bag seconds": seconds, "process_bag peak RSS MB": peak / 2**20,
            "exit": process.returncode}


def _trackers(bag: Path, frames: int = 150) -> dict[str, float]:
    import cv2
    from trap_core.evaluation.baselines import TRACKERS
    with open_image_stream(bag) as stream:
        images = [cv2.cvtColor(f.rgb, cv2.COLOR_RGB2BGR) for f, _ in zip(stream, range(frames))]
    rates = {}
    for name in ("TLD", "KCF", "CSRT", "MedianFlow"):
        tracker = TRACKERS[name]()
        tracker.init(images[0], (300, 200, 60, 40))
        start = time.perf_counter()
        for image in images[1:]:
            tracker.update(image)
        rates[f"{name} fps (one object)"] = (len(images) - 1) / (time.perf_counter() - start)
    return rates


def _scaling_worker(frames: int) -> None:
    """Child process: graphs and tracking for ``frames`` frames; prints times and peak RSS."""
    params = TrapParams(segmentation="colour")
    cfg = SceneConfig(frames=frames, seed=3)
    start = time.perf_counter()
    graphs = list(graphs_of((f.rgb for f in render(cfg)), params))
    graph_seconds = time.perf_counter() - start
    run = track(graphs, params)
    print(json.dumps({"frames": frames, "graphs s": graph_seconds, "mining s": run.seconds["mining"],
                      "clustering s": run.seconds["camera"] + run.seconds["distances"] + run.seconds["clustering"],
                      "patterns": run.mining.n_st,
                      "peak RSS MB": _peak_rss_mb()}))


def _peak_rss_mb() -> float:
    """This process's own high-water mark (VmHWM; ru_maxrss would include the parent's at fork)."""
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1024
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the 5600-frame run and the felzenszwalb e2e run")
    parser.add_argument("--scaling-worker", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.scaling_worker:
        _scaling_worker(args.scaling_worker)
        return
    results: dict[str, dict] = {}
    with tempfile.TemporaryDirectory(prefix="trap-bench-") as tmp:
        for preset in ("anim1", "anim2"):
            bag, _ = write_synthetic(SceneConfig(**PRESETS[preset]), Path(tmp) / preset)
            for segmentation in ("colour", "felzenszwalb"):
                if args.quick and segmentation == "felzenszwalb":
                    continue
                key = f"{preset} ({segmentation})"
                results[key] = _stage_rates(bag, segmentation)
                results[key].update(_process_bag(bag, Path(tmp) / f"out-{key}", segmentation))
            results[f"{preset} trackers"] = _trackers(bag)
    scaling = []
    for frames in ((100, 721, 2000) if args.quick else (100, 721, 2000, 5600)):
        done = subprocess.run([sys.executable, __file__, "--scaling-worker", str(frames)], capture_output=True,
                              text=True)
        if done.returncode:
            sys.exit(f"end_to_end: the {frames}-frame scaling run failed: {done.stderr.strip()[-2000:]}")
        scaling.append(json.loads(done.stdout.strip().splitlines()[-1]))
    columns = [k for k in results if not k.endswith("trackers")]
    names = list(dict.fromkeys(n for k in columns for n in results[k]))
    print("| figure | " + " | ".join(columns) + " |")
    print("|---" * (len(columns) + 1) + "|")
    for name in names:
        print(f"| {name} | " + " | ".join(f"{results[c].get(name, float('nan')):.1f}" for c in columns) + " |")
    print("\n| OpenCV tracker (one object) | " + " | ".join(k for k in results if k.endswith("trackers")) + " |")
    print("|---|---|---|")
    for name in results["anim1 trackers"]:
        print(f"| {name} | " + " | ".join(f"{results[k][name]:.1f}" for k in results if k.endswith("trackers")) + " |")
    print("\n| frames | graphs s | mining s | clustering s | patterns | peak RSS MB |")
    print("|---|---|---|---|---|---|")
    for row in scaling:
        print(f"| {row['frames']} | {row['graphs s']:.1f} | {row['mining s']:.1f} | {row['clustering s']:.1f} | "
              f"{row['patterns']} | {row['peak RSS MB']:.0f} |")
    frames = np.array([r["frames"] for r in scaling], dtype=float)
    for key in ("mining s", "peak RSS MB"):
        slope = np.polyfit(frames, [r[key] for r in scaling], 1)[0]
        print(f"{key}: slope {1000 * slope if key == 'mining s' else slope:.2f} "
              f"{'ms' if key == 'mining s' else 'MB'} per frame")
    print(json.dumps({"stages": results, "scaling": scaling}, indent=2))


if __name__ == "__main__":
    main()
