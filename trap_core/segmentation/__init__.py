"""Frames to regions: Felzenszwalb-Huttenlocher (constant or size threshold) or exact colours."""

from trap_core.segmentation.components import colour_components
from trap_core.segmentation.errors import SegmentationError
from trap_core.segmentation.felzenszwalb import COLOUR_SPACES, THRESHOLD_MODES, felzenszwalb, fitted_chroma_weight

__all__ = ["COLOUR_SPACES", "THRESHOLD_MODES", "SegmentationError", "colour_components", "felzenszwalb",
           "fitted_chroma_weight"]
