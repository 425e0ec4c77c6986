"""Benchmark: a long video tracked whole and in chunks (``chunk``): peak memory, time, quality.

Each run is a child process (its own peak RSS) that renders a synthetic video of ``--frames``
frames, segments it and streams the graphs into :class:`ChunkedTracker`, as ``process_bag``
does. Prints per run: chunks, tracks, seconds, peak RSS, MB a frame, MOTA, IDF1; then the
memory ratio whole / chunked.

Run: ``.venv/bin/python benchmarks/long_bag.py [--frames 6000] [--chunks 0,1500]``
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

from trap_core.evaluation import boxes_by_frame, mot_measures
from trap_core.pipeline import ChunkedTracker, TrapParams, graphs_of
from trap_core.synthetic import SceneConfig, render


def _worker(frames: int, chunk: int) -> None:
    params = TrapParams(segmentation="colour", chunk=chunk)
    config = SceneConfig(frames=frames, seed=3)
    truth: list[dict[int, tuple]] = [dict() for _ in range(config.objects)]

    def pixels():
        for index, frame in enumerate(render(config)):
            for obj, box in enumerate(frame.boxes):
                if box is not None:
                    truth[obj][index] = tuple(box)
            yield frame.rgb

    start = time.perf_counter()
    tracker = ChunkedTracker(params, frames)
    for graph in graphs_of(pixels(), params):
        tracker.add(graph)
    run = tracker.finish()
    seconds = time.perf_counter() - start
    boxes = [boxes_by_frame(t) for t in run.tracks]
    scores = mot_measures(boxes, truth)
    print(json.dumps({"chunk": chunk, "chunks": len(run.chunks), "tracks": len(run.tracks), "seconds": seconds,
                      "peak RSS MB": _peak_rss_mb(), "MOTA": scores["MOTA"], "IDF1": scores["IDF1"]}))


def _peak_rss_mb() -> float:
    for line in Path("/proc/self/status").read_text().splitlines():
        if line.startswith("VmHWM"):
            return int(line.split()[1]) / 1024
    return float("nan")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=6000)
    parser.add_argument("--chunks", default="0,1500", help="comma-separated chunk values (0: whole video)")
    parser.add_argument("--worker", type=int, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker is not None:
        _worker(args.frames, args.worker)
        return
    rows = []
    print(f"| chunk | chunks | tracks | s | peak RSS MB | MB / frame | MOTA | IDF1 |  ({args.frames} frames)")
    print("|---|---|---|---|---|---|---|---|")
    for chunk in (int(c) for c in args.chunks.split(",")):
        done = subprocess.run([sys.executable, __file__, "--frames", str(args.frames), "--worker", str(chunk)],
                              capture_output=True, text=True, check=True)
        row = json.loads(done.stdout.strip().splitlines()[-1])
        rows.append(row)
        print(f"| {chunk or 'whole'} | {row['chunks']} | {row['tracks']} | {row['seconds']:.0f} | "
              f"{row['peak RSS MB']:.0f} | {row['peak RSS MB'] / args.frames:.3f} | {row['MOTA']:.2f} | "
              f"{row['IDF1']:.2f} |", flush=True)
    if len(rows) >= 2:
        print(f"\npeak memory {rows[0]['chunk'] or 'whole'} / {rows[-1]['chunk'] or 'whole'}: "
              f"{rows[0]['peak RSS MB'] / rows[-1]['peak RSS MB']:.2f}x")


if __name__ == "__main__":
    main()
