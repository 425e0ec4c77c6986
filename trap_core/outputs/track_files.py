"""Tracks as MOTChallenge text (frame 1-based in image order)."""
from __future__ import annotations

from pathlib import Path

from trap_core.clustering import Track
from trap_core.motformat import write_mot


def write_tracks_mot(path: str | Path, tracks: list[Track]) -> int:
    """Write ``frame,id,x,y,w,h,conf,-1,-1,-1`` rows sorted by frame then id; return the row count."""
    rows = sorted((int(f) + 1, trk.track_id, *map(float, box), float(score))
                  for trk in tracks for f, box, score in zip(trk.frames, trk.boxes, trk.score))
    return write_mot(path, rows)
