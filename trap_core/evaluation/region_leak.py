"""How much of the objects a segmentation merges into the background (ours).

TRAP sees an object only through its regions: a part of it that the segmentation merges with
the ground around it belongs to none of the object's patterns, and no box built from regions
takes it in (README, "Compressed frames (JPEG)"). ``benchmarks/region_leak.py`` measures it over
the benchmark videos.
"""
from __future__ import annotations

import numpy as np


def leaked_pixels(labels: np.ndarray, count: int, owner: np.ndarray) -> tuple[int, int]:
    """Object pixels of a frame segmented into ``labels`` (``count`` regions) that lie in regions
    most of whose pixels show the background, and all its object pixels.

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
        Object pixels in regions given to the background (more of their pixels are background
        than object; a tie goes to the objects), and all object pixels.
    """
    on_background = np.bincount(labels[owner < 0], minlength=count)
    on_objects = np.bincount(labels[owner >= 0], minlength=count)
    return int(on_objects[on_background > on_objects].sum()), int(on_objects.sum())
