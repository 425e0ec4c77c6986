"""Declare TRAP parameters on a node (with descriptions) and read them back as :class:`TrapParams`."""
from __future__ import annotations

from collections.abc import Iterable

from rcl_interfaces.msg import ParameterDescriptor
from rclpy.node import Node

from trap_core.pipeline import ParameterError, TrapParams


def declare_trap_parameters(node: Node, names: Iterable[str]) -> None:
    """Declare ``names`` (fields of TrapParams) with their defaults and descriptions."""
    defaults = TrapParams().as_dict()
    descriptions = TrapParams.descriptions()
    for name in names:
        node.declare_parameter(name, defaults[name], ParameterDescriptor(description=descriptions[name]))


def trap_parameters(node: Node, names: Iterable[str]) -> TrapParams:
    """TrapParams from the node's values of ``names`` (others at their defaults); checked."""
    values = {name: node.get_parameter(name).value for name in names}
    try:
        return TrapParams.from_mapping(values)
    except ParameterError as error:
        raise ParameterError(f"{node.get_name()}: {error}") from None
