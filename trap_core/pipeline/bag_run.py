"""Run TRAP on a bag end to end and write its outputs (tracks.txt, summary.json, tracks.png,
timeline.png)."""
from __future__ import annotations

import json
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from trap_core.bagio import BagError, open_image_stream
from trap_core.outputs import Thumbnails, contact_sheet, track_timeline, write_tracks_mot
from trap_core.pipeline.chunks import ChunkedRun, ChunkedTracker
from trap_core.pipeline.frames_to_graphs import SetupNote, graphs_of, print_setup_notes
from trap_core.pipeline.params import TrapParams
from trap_core.progress import Progress

@dataclass
class BagRun:
    """What a run read and produced."""

    topic: str
    frames: int
    regions_per_frame: float
    tracking: ChunkedRun | None
    seconds: dict[str, float]
    outputs: dict[str, str]
    interrupted: bool = False
    camera_steps_read: int = 0  # frames whose camera step from the frame before was read from the images


def thumbnailed_frames(stream, thumbnails: Thumbnails, meter: Progress) -> Iterator[np.ndarray]:
    """The frames' pixels, keeping the contact sheet's thumbnails on the way."""
    for frame in stream:
        thumbnails(frame.rgb)
        meter.advance()
        yield frame.rgb


def run_bag(bag: str | Path, out: str | Path, params: TrapParams, topic: str | None = None) -> BagRun:
    """Read ``bag``, track, and write ``out/tracks.txt``, ``summary.json`` and ``tracks.png``.

    On KeyboardInterrupt the frames read so far are tracked and written, and the summary
    says the run was interrupted; the interrupt is then re-raised. A bad frame (BagError) ends
    the reading there: the frames before it are tracked and written, then the error is raised.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    regions = steps_read = 0
    interrupted = False
    bad_frame: BagError | None = None
    fitted: list[TrapParams] = []  # the segmentation's parameters, fitted to the first frame

    def tell(used: TrapParams, notes: list[SetupNote]) -> None:
        fitted.append(used)
        print_setup_notes(used, notes)
    with open_image_stream(bag, topic) as stream:
        meter = Progress(stream.count, f"segmenting {stream.topic}")
        thumbnails = Thumbnails(stream.count)
        tracker = ChunkedTracker(params, stream.count)
        start = time.perf_counter()
        try:
            for graph in graphs_of(thumbnailed_frames(stream, thumbnails, meter), params, tell):
                tracker.add(graph)
                regions += graph.n_nodes
                steps_read += graph.has_camera_step
        except KeyboardInterrupt:
            interrupted = True
        except BagError as error:
            bad_frame = error
        meter.finish()
        elapsed = time.perf_counter() - start
        chosen_topic = stream.topic
    frames = tracker.frames
    params = fitted[0] if fitted else params  # the summary reports the k used
    tracking = tracker.finish() if frames >= 2 else None
    seconds = tracking.seconds if tracking else {}
    seconds["read_segment_graph"] = elapsed - tracking.seconds_while_reading() if tracking else elapsed
    run = BagRun(chosen_topic, frames, regions / max(frames, 1), tracking, seconds, {}, interrupted, steps_read)
    write_outputs(run, bag, out, params, thumbnails.images, thumbnails.scale)
    if interrupted:
        raise KeyboardInterrupt
    if bad_frame is not None:
        raise bad_frame
    return run


def write_outputs(run: BagRun, bag: str | Path, out: Path, params: TrapParams,
                  thumbnails: dict[int, np.ndarray], scale: float) -> None:
    """tracks.txt (MOTChallenge), tracks.png (contact sheet), timeline.png (which track is seen
    when) and summary.json."""
    tracks = run.tracking.tracks if run.tracking else []
    chunks = run.tracking.chunks if run.tracking else []
    run.outputs["tracks.txt"] = str(out / "tracks.txt")
    rows = write_tracks_mot(out / "tracks.txt", tracks)
    shown = {f: t for f, t in thumbnails.items() if f < run.frames}
    if shown:
        run.outputs["tracks.png"] = str(contact_sheet(shown, tracks, scale, out / "tracks.png"))
    if run.frames:
        run.outputs["timeline.png"] = str(track_timeline(tracks, run.frames, out / "timeline.png",
                                                         [c.first_frame for c in chunks]))
    summary = {
        "bag": str(bag), "topic": run.topic, "frames": run.frames, "interrupted": run.interrupted,
        "parameters": params.as_dict(),
        "counts": {
            "regions_per_frame": run.regions_per_frame,
            "camera_steps_from_images": run.camera_steps_read,  # of frames - 1; the others' from the patterns
            "chunks": len(chunks),
            "plane_patterns": sum(c.plane_patterns for c in chunks),  # per chunk, summed
            "spatio_temporal_patterns": sum(c.spatio_temporal_patterns for c in chunks),
            "clusters_at_cut": sum(c.clusters_at_cut for c in chunks),
            "tracks": len(tracks), "track_rows": rows,
        },
        "tracks": [{"id": t.track_id, "frames": len(t), "first_frame": int(t.frames[0]) + 1,
                    "last_frame": int(t.frames[-1]) + 1} for t in tracks],
        "seconds": {k: round(v, 3) for k, v in run.seconds.items()},
        "outputs": run.outputs,
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    run.outputs["summary.json"] = str(out / "summary.json")
