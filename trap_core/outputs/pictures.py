"""Pictures people look at: frames with the track boxes drawn, as a contact sheet."""
from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

from trap_core.clustering import Track


def track_colour(track_id: int) -> tuple[int, int, int]:
    """A distinct, stable RGB colour per track id (golden-angle hues)."""
    hue = int((track_id * 137.508) % 180)
    bgr = cv2.cvtColor(np.uint8([[[hue, 230, 255]]]), cv2.COLOR_HSV2BGR)[0, 0]
    return int(bgr[2]), int(bgr[1]), int(bgr[0])


def draw_tracks(rgb: np.ndarray, frame: int, tracks: list[Track], scale: float = 1.0) -> np.ndarray:
    """Copy of ``rgb`` with each track's box in ``frame`` and its id drawn."""
    out = rgb.copy()
    for trk in tracks:
        where = np.searchsorted(trk.frames, frame)
        if where < len(trk) and trk.frames[where] == frame:
            x, y, w, h = (trk.boxes[where] * scale).round().astype(int)
            colour = track_colour(trk.track_id)
            cv2.rectangle(out, (x, y), (x + w - 1, y + h - 1), colour, 2)
            cv2.putText(out, str(trk.track_id), (x, max(y - 4, 10)), cv2.FONT_HERSHEY_SIMPLEX, 0.5, colour, 1,
                        cv2.LINE_AA)
    return out


def sheet_frames(n_frames: int, count: int = 12) -> np.ndarray:
    """Indices of the frames a contact sheet shows: ``count`` evenly spaced frames."""
    return np.unique(np.linspace(0, max(n_frames - 1, 0), min(count, max(n_frames, 1))).round().astype(int))


class Thumbnails:
    """Small copies of the frames a contact sheet of a ``total``-frame video will show, kept
    while the frames stream past (call with every frame, in order)."""

    def __init__(self, total: int, width: int = 320) -> None:
        self.wanted = set(sheet_frames(total).tolist())
        self.width = width
        self.images: dict[int, np.ndarray] = {}
        self.scale = 1.0
        self.next_index = 0

    def __call__(self, rgb: np.ndarray) -> None:
        if self.next_index in self.wanted:
            self.scale = min(1.0, self.width / rgb.shape[1])
            self.images[self.next_index] = cv2.resize(rgb, None, fx=self.scale, fy=self.scale,
                                                      interpolation=cv2.INTER_AREA)
        self.next_index += 1


def contact_sheet(thumbnails: dict[int, np.ndarray], tracks: list[Track], scale: float, path: str | Path,
                  columns: int = 4) -> Path:
    """Write a grid of thumbnails (frame index -> RGB, already scaled by ``scale``) with the tracks drawn."""
    tiles = []
    for frame in sorted(thumbnails):
        tile = draw_tracks(thumbnails[frame], frame, tracks, scale)
        cv2.putText(tile, f"frame {frame + 1}", (4, tile.shape[0] - 6), cv2.FONT_HERSHEY_SIMPLEX, 0.45,
                    (255, 255, 255), 1, cv2.LINE_AA)
        tiles.append(tile)
    if not tiles:
        raise ValueError("no frames for a contact sheet")
    height, width = tiles[0].shape[:2]
    rows = -(-len(tiles) // columns)
    sheet = np.zeros((rows * height, columns * width, 3), dtype=np.uint8)
    for i, tile in enumerate(tiles):
        r, c = divmod(i, columns)
        sheet[r * height:(r + 1) * height, c * width:(c + 1) * width] = tile[:height, :width]
    path = Path(path)
    cv2.imwrite(str(path), cv2.cvtColor(sheet, cv2.COLOR_RGB2BGR))
    return path
