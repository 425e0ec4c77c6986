"""MOTChallenge text files: ``frame,id,x,y,w,h,conf,-1,-1,-1``, frame 1-based in image order.

Used for the synthetic ground truth and for the tracks that ``process_bag`` writes, so both
sides of an evaluation go through the same reader.
"""
from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

import numpy as np

# One row per box: frame (1-based), id, x, y, w, h, confidence.
MOT_COLUMNS = ("frame", "id", "x", "y", "w", "h", "conf")


def write_mot(path: str | Path, rows: Iterable[tuple[int, int, float, float, float, float, float]]) -> int:
    """Write rows ``(frame, id, x, y, w, h, conf)``; return how many were written."""
    count = 0
    with open(path, "w", encoding="ascii") as out:
        for frame, ident, x, y, w, h, conf in rows:
            out.write(f"{int(frame)},{int(ident)},{_num(x)},{_num(y)},{_num(w)},{_num(h)},{_num(conf)},-1,-1,-1\n")
            count += 1
    return count


def _num(value: float) -> str:
    return str(int(value)) if float(value).is_integer() else f"{float(value):.2f}"


def read_mot(path: str | Path) -> np.ndarray:
    """Read a MOTChallenge file into a ``(n, 7)`` float array of ``MOT_COLUMNS``."""
    text = Path(path).read_text(encoding="ascii")
    rows = [line.split(",")[:7] for line in text.splitlines() if line.strip()]
    if not rows:
        return np.empty((0, 7))
    return np.array(rows, dtype=np.float64)


def ground_truth_path(bag: str | Path) -> Path:
    """Where the synthetic writer puts a bag's ground truth: ``NAME.gt.txt`` beside the bag."""
    bag = Path(bag)
    return bag.with_name(bag.name.removesuffix(bag.suffix) + ".gt.txt") if bag.suffix else bag.with_name(bag.name + ".gt.txt")
