"""The one error class of :mod:`trap_core.bagio`."""


class BagError(Exception):
    """A bag or one of its images cannot be read; the message is one line meant for the user."""
