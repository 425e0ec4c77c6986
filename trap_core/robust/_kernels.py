"""Compiled kernel of the grown track boxes (numba, ``nogil``): which regions move with a track."""
from __future__ import annotations

import numba as nb
import numpy as np

# An object's part keeps its area from frame to frame; a background region the object passes
# over loses or regains the part it hides, and its barycentre drifts with the object.
AREA_RATIO = 1.25


@nb.njit(cache=True, nogil=True)
def moving_regions(bbox: np.ndarray, centroid: np.ndarray, area: np.ndarray, label: np.ndarray,
                   other_centroid: np.ndarray, other_area: np.ndarray, other_label: np.ndarray,
                   box: np.ndarray, other_box: np.ndarray, camera: np.ndarray, reach: float, tolerance: float,
                   max_area: float) -> np.ndarray:
    """Mask of the regions near ``box`` that the track's displacement to the other frame puts on
    a look-alike region (same label, area within ``AREA_RATIO``, within ``tolerance`` sqrt(area) + 1
    px) at least twice as close as the camera's motion ``camera`` (3x3) does. Regions over
    ``max_area`` times the box are left out unless their box encloses it."""
    x, y, w, h = box[0], box[1], box[2], box[3]
    shift_x = other_box[0] + other_box[2] / 2 - (x + w / 2)
    shift_y = other_box[1] + other_box[3] / 2 - (y + h / 2)
    found = np.zeros(bbox.shape[0], dtype=np.bool_)
    for i in range(bbox.shape[0]):
        if (bbox[i, 2] < x - reach * w or bbox[i, 3] < y - reach * h or bbox[i, 0] > x + w + reach * w
                or bbox[i, 1] > y + h + reach * h):
            continue
        encloses = bbox[i, 0] <= x and bbox[i, 1] <= y and bbox[i, 2] >= x + w - 1 and bbox[i, 3] >= y + h - 1
        if area[i] > max_area * w * h and not encloses:
            continue
        cx, cy = centroid[i, 0], centroid[i, 1]
        mx, my = cx + shift_x, cy + shift_y
        scale = camera[2, 0] * cx + camera[2, 1] * cy + camera[2, 2]
        kx = (camera[0, 0] * cx + camera[0, 1] * cy + camera[0, 2]) / scale
        ky = (camera[1, 0] * cx + camera[1, 1] * cy + camera[1, 2]) / scale
        with_track = np.inf
        with_camera = np.inf
        for j in range(other_centroid.shape[0]):
            if (other_label[j] != label[i] or other_area[j] >= AREA_RATIO * area[i]
                    or AREA_RATIO * other_area[j] <= area[i]):
                continue
            with_track = min(with_track, np.hypot(other_centroid[j, 0] - mx, other_centroid[j, 1] - my))
            with_camera = min(with_camera, np.hypot(other_centroid[j, 0] - kx, other_centroid[j, 1] - ky))
        found[i] = with_track <= tolerance * np.sqrt(area[i]) + 1 and with_track < with_camera / 2
    return found
