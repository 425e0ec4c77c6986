"""Why an object falls short of the paper's measures: the frames and box area its track loses, by cause.

Precision and recall (:func:`~trap_core.evaluation.paper_measures.box_precision_recall`) say how
much of an object its matched track misses, not why; the rules that could win it back differ by
cause. An annotated frame the recall test misses is lost because no track was matched to the
object, because the track has no box there (before its first box or after its last one, or in a
gap between two), or because the track's box there is on another object or on nothing (the
centre test of :func:`~trap_core.evaluation.held_objects.held_objects`). The area that precision
loses, a track box's area outside the object's box, is lost in frames where the box is on its
object (a box larger than the object or shifted off it), on another object, on nothing, or where
the object is not annotated (it has left the view).
"""
from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from trap_core.evaluation.held_objects import NONE, Boxes, held_objects
from trap_core.evaluation.paper_measures import box_precision_recall, centre_inside, shared_area

MISSED = ("no track", "before or after the track", "in the track's gaps", "on another object", "on nothing")
OFF = ("on its object", "on another object", "on nothing", "while its object is out of view")
GOOD = 0.895  # precision and recall at least this are 90 % as printed


@dataclass(frozen=True)
class ObjectLosses:
    """One object's losses: its annotated ``frames``, the frames the recall test misses per cause
    of :data:`MISSED`, and the box area precision loses per cause of :data:`OFF` (with the
    ``area`` of all the track's boxes), besides the object's ``precision`` and ``recall``."""

    frames: int
    missed: dict[str, int]
    area: float
    off: dict[str, float]
    precision: float
    recall: float

    @property
    def good(self) -> bool:
        """At 90/90 or better, as printed."""
        return self.precision >= GOOD and self.recall >= GOOD

    @property
    def cause(self) -> str:
        """What loses the most: the cause of most missed frames where recall falls short, else
        ``box <cause>`` of most area off the object (precision alone falls short)."""
        if self.recall < GOOD:
            return max(MISSED, key=self.missed.__getitem__)
        return "box " + max(OFF, key=self.off.__getitem__)


def object_losses(track: Boxes | None, truth: Sequence[Boxes], obj: int) -> ObjectLosses:
    """The losses of object ``obj`` of ``truth`` (one ``{frame: (x, y, w, h)}`` per object) to the
    ``track`` matched to it (None: none was; :func:`~trap_core.evaluation.scoring.match_objects`)."""
    own = truth[obj]
    missed = dict.fromkeys(MISSED, 0)
    off = dict.fromkeys(OFF, 0.0)
    if track is None:
        missed["no track"] = len(own)
        return ObjectLosses(len(own), missed, 0.0, off, 0.0, 0.0)
    held = held_objects(track, truth)
    first, last = min(track, default=0), max(track, default=-1)
    for frame, box in own.items():
        if frame not in track:
            missed["in the track's gaps" if first < frame < last else "before or after the track"] += 1
        elif not centre_inside(track[frame], box):
            missed["on nothing" if held[frame] == NONE else "on another object"] += 1
    area = 0.0
    for frame, box in track.items():
        size = box[2] * box[3]
        area += size
        if frame not in own:
            off["while its object is out of view"] += size
            continue
        outside = size - shared_area(box, own[frame])
        on = "on its object" if centre_inside(box, own[frame]) else (
            "on nothing" if held[frame] == NONE else "on another object")
        off[on] += outside
    return ObjectLosses(len(own), missed, area, off, *box_precision_recall(track, own))


def causes_line(causes: Iterable[str]) -> str:
    """What loses the most, one entry per object under 90/90 (:attr:`ObjectLosses.cause`), as
    one line of counts, most first (``cause count, ...``; ``none`` where there are none)."""
    return ", ".join(f"{cause} {count}" for cause, count in Counter(causes).most_common()) or "none"


def losses_chart(causes_by_set: dict[str, dict[str, int]], path: str | Path) -> Path:
    """Write a picture of what loses the most (:attr:`ObjectLosses.cause`) for the objects under
    90/90 of each set of videos: a bar per set (``causes_by_set``: set name -> cause -> objects),
    its parts coloured by cause, to ``path``."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    causes = [*MISSED, *(f"box {cause}" for cause in OFF)]
    names = list(causes_by_set)
    figure, axes = plt.subplots(figsize=(10, 1.6 + 0.32 * max(len(names), 1)), dpi=100)
    left = np.zeros(len(names))
    palette = plt.get_cmap("tab10")
    for index, cause in enumerate(causes):
        counts = np.array([causes_by_set[name].get(cause, 0) for name in names], dtype=float)
        if counts.any():
            axes.barh(range(len(names)), counts, left=left, color=palette(index % 10), label=cause)
            left += counts
    axes.set_yticks(range(len(names)), names)
    axes.invert_yaxis()
    axes.set_xlabel("objects under 90/90, by what loses the most")
    axes.xaxis.get_major_locator().set_params(integer=True)
    if left.any():
        axes.legend(loc="best", fontsize="small")
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path)
    plt.close(figure)
    return path
