"""Run TRAP on a bag end to end and write its outputs (tracks.txt, summary.json, tracks.png)."""
from __future__ import annotations

import json
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from trap_core.bagio import open_image_stream
from trap_core.outputs import Thumbnails, contact_sheet, write_tracks_mot
from trap_core.pipeline.frames_to_graphs import graphs_of
from trap_core.pipeline.params import TrapParams
from trap_core.pipeline.pattern_miner import PatternMiner
from trap_core.pipeline.tracking import TrackingResult, frame_rate, track
from trap_core.progress import Progress
from trap_core.rag import PlaneGraph

@dataclass
class BagRun:
    """What a run read and produced."""

    topic: str
    frames: int
    graphs: list[PlaneGraph]
    result: TrackingResult | None
    seconds: dict[str, float]
    outputs: dict[str, str]
    interrupted: bool = False


def stamped_frames(stream, thumbnails: Thumbnails, meter: Progress, stamps: list[int]) -> Iterator[np.ndarray]:
    """The frames' pixels, keeping their stamps and the contact sheet's thumbnails on the way."""
    for frame in stream:
        stamps.append(frame.stamp_ns)
        thumbnails(frame.rgb)
        meter.advance()
        yield frame.rgb


def run_bag(bag: str | Path, out: str | Path, params: TrapParams, topic: str | None = None) -> BagRun:
    """Read ``bag``, track, and write ``out/tracks.txt``, ``summary.json`` and ``tracks.png``.

    On KeyboardInterrupt the frames read so far are tracked and written, and the summary
    says the run was interrupted; the interrupt is then re-raised.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    seconds: dict[str, float] = {}
    graphs: list[PlaneGraph] = []
    stamps: list[int] = []
    interrupted = False
    with open_image_stream(bag, topic) as stream:
        meter = Progress(stream.count, f"segmenting {stream.topic}")
        thumbnails = Thumbnails(stream.count)
        miner = PatternMiner(params, stream.count)
        start = time.perf_counter()
        try:
            for graph in graphs_of(stamped_frames(stream, thumbnails, meter, stamps), params):
                graphs.append(graph)
                miner.add(graph)
        except KeyboardInterrupt:
            interrupted = True
        meter.finish()
        seconds["read_segment_graph"] = time.perf_counter() - start - miner.seconds  # windows mined meanwhile: "mining"
        chosen_topic = stream.topic
    result = track(graphs, params, frame_rate(stamps[:len(graphs)]), miner) if len(graphs) >= 2 else None
    if result is not None:
        seconds.update(result.seconds)
    run = BagRun(chosen_topic, len(graphs), graphs, result, seconds, {}, interrupted)
    write_outputs(run, bag, out, params, thumbnails.images, thumbnails.scale)
    if interrupted:
        raise KeyboardInterrupt
    return run


def write_outputs(run: BagRun, bag: str | Path, out: Path, params: TrapParams,
                  thumbnails: dict[int, np.ndarray], scale: float) -> None:
    """tracks.txt (MOTChallenge), tracks.png (contact sheet) and summary.json."""
    tracks = run.result.tracks if run.result else []
    run.outputs["tracks.txt"] = str(out / "tracks.txt")
    rows = write_tracks_mot(out / "tracks.txt", tracks)
    shown = {f: t for f, t in thumbnails.items() if f < run.frames}
    if shown:
        run.outputs["tracks.png"] = str(contact_sheet(shown, tracks, scale, out / "tracks.png"))
    mined = run.result.mining if run.result else None
    summary = {
        "bag": str(bag), "topic": run.topic, "frames": run.frames, "interrupted": run.interrupted,
        "parameters": params.as_dict(),
        "counts": {
            "regions_per_frame": float(np.mean([g.n_nodes for g in run.graphs])) if run.graphs else 0.0,
            "plane_patterns": mined.n_patterns if mined else 0,
            "spatio_temporal_patterns": mined.n_st if mined else 0,
            "clusters_at_cut": run.result.hierarchy.cut_level if run.result else 0,
            "tracks": len(tracks), "track_rows": rows,
        },
        "tracks": [{"id": t.track_id, "frames": len(t), "first_frame": int(t.frames[0]) + 1,
                    "last_frame": int(t.frames[-1]) + 1} for t in tracks],
        "seconds": {k: round(v, 3) for k, v in run.seconds.items()},
        "outputs": run.outputs,
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    run.outputs["summary.json"] = str(out / "summary.json")
