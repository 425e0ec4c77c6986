"""How much of the objects a segmentation merges into the background (ours).

TRAP sees an object only through its regions: a part of it that the segmentation merges with
the ground around it belongs to none of the object's patterns, and no box built from regions
takes it in (README, "Compressed frames (JPEG)"). ``benchmarks/region_leak.py`` measures it over
the benchmark videos.
"""
from __future__ import annotations

import numpy as np


def leaked_regions(labels: np.ndarray, count: int, owner: np.ndarray) -> np.ndarray:
    """(``count``,) whether each region of a frame segmented into ``labels`` is given to the
    background: more of its pixels show the background than an object (a tie goes to the
    objects). ``owner``: the object each pixel shows, -1 for the background."""
    on_background, on_objects = _pixel_counts(labels, count, owner)
    return on_background > on_objects


def leaked_pixels(labels: np.ndarray, count: int, owner: np.ndarray) -> tuple[int, int]:
    """Object pixels of a frame segmented into ``labels`` (``count`` regions) that lie in regions
    given to the background (:func:`leaked_regions`), and all its object pixels.

    Parameters
    ----------
    labels : (H, W) int
        Region of each pixel, 0 .. ``count`` - 1.
    count : int
        Number of regions.
    owner : (H, W) int
        The object each pixel shows, -1 for the background (``RenderedFrame.owner`` at the size
        of ``labels``).

    Returns
    -------
    leaked, total : int
        Object pixels in regions given to the background, and all object pixels.
    """
    on_background, on_objects = _pixel_counts(labels, count, owner)
    return int(on_objects[on_background > on_objects].sum()), int(on_objects.sum())


def _pixel_counts(labels: np.ndarray, count: int, owner: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Background and object pixels of each region."""
    return (np.bincount(labels[owner < 0], minlength=count), np.bincount(labels[owner >= 0], minlength=count))
