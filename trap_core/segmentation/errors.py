"""The one error class of :mod:`trap_core.segmentation`."""


class SegmentationError(ValueError):
    """Segmentation parameters or input are unusable; the message is one line for the user."""
