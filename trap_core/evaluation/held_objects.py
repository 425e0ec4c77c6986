"""Which object each track holds, frame by frame, against ground truth, and its picture.

Precision, recall, MOTA and IDF1 say how much a set of tracks misses; they do not say where a
track went over to another object, followed the background for a while or came back after an
exit. Here each track is a row of bars over its frames, coloured by the object whose
ground-truth box holds its box centre (the recall test of :func:`box_precision_recall`), grey
where none does: a trade between look-alikes is a change of colour, a track on the background
a grey run.
"""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from trap_core.outputs.timeline import frame_runs

Boxes = dict[int, tuple]  # frame (0-based) -> (x, y, w, h), as the scores take them
NONE = -1  # the track's box centre lies in no object's box
NONE_GREY = "0.6"  # its bars' colour
# Objects' colours: matplotlib's tab20 without its two greys (which a track on no object is drawn
# in), the ten strong shades first (tab10's but its grey), then their pale twins: a video of more
# objects than that (traffic passing through the view) repeats them, but never shows an object
# as grey.
OBJECT_SHADES = (0, 2, 4, 6, 8, 10, 12, 16, 18, 1, 3, 5, 7, 9, 11, 13, 17, 19)


def held_objects(track: Boxes, truth: Sequence[Boxes]) -> dict[int, int]:
    """Per frame of ``track``: the object whose ground-truth box holds the track box's centre
    (the smallest such box where several do: the nearer object hides the other), else
    :data:`NONE`."""
    held = {}
    for frame, (x, y, w, h) in track.items():
        cx, cy = x + w / 2, y + h / 2
        best, best_area = NONE, np.inf
        for obj, boxes in enumerate(truth):
            if frame not in boxes:
                continue
            gx, gy, gw, gh = boxes[frame]
            if gx <= cx <= gx + gw and gy <= cy <= gy + gh and gw * gh < best_area:
                best, best_area = obj, gw * gh
        held[int(frame)] = best
    return held


def object_timeline(boxes_per_track: Sequence[Boxes], truth: Sequence[Boxes], n_frames: int, path: str | Path,
                    title: str = "") -> Path:
    """Write the picture of which object each track holds (:func:`held_objects`) over frames
    1..``n_frames`` to ``path``, a row per track, then a row of each object's own frames (objects
    numbered from 1, as in ground-truth files)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tab20 = plt.get_cmap("tab20")

    def colour(obj: int) -> str | tuple:
        return NONE_GREY if obj == NONE else tab20(OBJECT_SHADES[obj % len(OBJECT_SHADES)])
    rows = len(boxes_per_track) + len(truth)
    figure, axes = plt.subplots(figsize=(10, 1.4 + 0.3 * max(rows, 1)), dpi=100)
    for row, track in enumerate(boxes_per_track):
        held = held_objects(track, truth)
        frames = np.array(sorted(held), dtype=np.int64)
        objects = np.array([held[f] for f in frames.tolist()], dtype=np.int64)
        for obj in np.unique(objects).tolist():  # frames are whole: a run of one object's frames holds no other
            axes.broken_barh([(first + 1, length) for first, length in frame_runs(frames[objects == obj])],
                             (row - 0.35, 0.7), linewidth=0, facecolors=colour(obj))
    for obj, boxes in enumerate(truth):
        axes.broken_barh([(first + 1, length) for first, length in frame_runs(np.array(sorted(boxes), dtype=np.int64))],
                         (len(boxes_per_track) + obj - 0.2, 0.4), linewidth=0, facecolors=colour(obj))
    labels = [f"track {k + 1}" for k in range(len(boxes_per_track))]
    labels += [f"object {k + 1}" for k in range(len(truth))]
    axes.set_yticks(range(rows), labels)
    axes.set_ylim(-0.7, max(rows, 1) - 0.3)
    axes.invert_yaxis()
    axes.set_xlim(1, max(n_frames, 2))
    axes.set_xlabel("frame (colour: the object a track's box centre lies on; grey: none)")
    axes.set_title(title or f"{len(boxes_per_track)} tracks, {len(truth)} objects")
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path)
    plt.close(figure)
    return path

