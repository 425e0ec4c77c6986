"""The size every frame of an image stream must have: at least ``MIN_SIDE`` a side, and its first frame's."""
from __future__ import annotations

import numpy as np

from trap_core.bagio.errors import BagError

MIN_SIDE = 16  # px: below, a frame holds too few regions of a useful size to form the faces patterns are made of


class FrameSize:
    """Checks each frame of one stream (a bag's topic, a live topic) before it is tracked.

    Tracks are made in one frame's pixels (the view's borders, the camera's steps, the boxes): a
    camera that changed its resolution mid-stream would mix two scales, so a frame of another
    size than the first is refused, as is a frame too small to hold a face of regions.
    """

    def __init__(self) -> None:
        self.first: tuple[int, int] | None = None  # (height, width) of the stream's first frame

    def check(self, rgb: np.ndarray) -> None:
        """Raise :class:`BagError` if ``rgb`` may not be tracked with the frames before it."""
        height, width = rgb.shape[:2]
        if min(height, width) < MIN_SIDE:
            raise BagError(f"image of size {width}x{height} is too small to track (at least {MIN_SIDE} px a side)")
        if self.first is None:
            self.first = (height, width)
        elif (height, width) != self.first:
            raise BagError(f"image of size {width}x{height} after frames of {self.first[1]}x{self.first[0]}: "
                           "one image size per run (split the bag where the camera changed)")
