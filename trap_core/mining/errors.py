"""The one error class of :mod:`trap_core.mining`."""


class MiningError(ValueError):
    """Mining parameters are unusable; the message is one line for the user."""
