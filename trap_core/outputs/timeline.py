"""A bag's tracks on one picture: which track is seen in which frames (a row per track id).

The contact sheet shows a dozen frames; over a long bag it cannot show when each object was
tracked, where ids change or where a track is only inferred. Here every track is a row of bars
over the frames it covers, strong where its patterns were seen and pale where its box is
inferred (gaps filled, followed behind another object, continued across the border), with the
chunk borders marked.
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from trap_core.clustering import Track, seen_rows
from trap_core.outputs.pictures import track_colour


def track_timeline(tracks: Sequence[Track], n_frames: int, path: str | Path,
                   chunk_starts: Sequence[int] = ()) -> Path:
    """Write the timeline picture of ``tracks`` over frames 1..``n_frames`` to ``path``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(10, 1.2 + 0.35 * max(len(tracks), 1)), dpi=100)
    for row, trk in enumerate(tracks):
        inferred = ~seen_rows(trk)
        colour = np.array(track_colour(trk.track_id)) / 255
        for seen in (True, False):
            runs = frame_runs(trk.frames[inferred != seen])
            axes.broken_barh([(first + 1, length) for first, length in runs], (row - 0.35, 0.7),
                             facecolors=colour, alpha=1.0 if seen else 0.35, linewidth=0)
    for start in chunk_starts[1:]:
        axes.axvline(start + 1, color="0.5", linestyle="--", linewidth=0.8)
    axes.set_yticks(range(len(tracks)), [str(t.track_id) for t in tracks])
    axes.set_ylim(-0.7, max(len(tracks), 1) - 0.3)
    axes.invert_yaxis()
    axes.set_xlim(1, max(n_frames, 2))
    axes.set_xlabel("frame (pale: inferred, not seen; dashed: chunk borders)" if chunk_starts[1:] else
                    "frame (pale: inferred, not seen)")
    axes.set_ylabel("track")
    axes.set_title(f"{len(tracks)} tracks over {n_frames} frames")
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path)
    plt.close(figure)
    return path


def frame_runs(frames: np.ndarray) -> list[tuple[int, int]]:
    """(first frame, length) of each run of consecutive ``frames`` (sorted): the bars of a row."""
    if frames.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(frames) > 1)
    firsts = np.r_[frames[0], frames[breaks + 1]]
    lasts = np.r_[frames[breaks], frames[-1]]
    return [(int(a), int(b - a + 1)) for a, b in zip(firsts, lasts)]
