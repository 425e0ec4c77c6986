"""The one error class of :mod:`trap_core.rag`."""


class GraphError(ValueError):
    """A label image or graph parameter cannot make a plane graph; one line for the user."""
