"""The one error class of :mod:`trap_core.clustering`."""


class ClusteringError(ValueError):
    """Clustering or selection parameters are unusable; one line for the user."""
