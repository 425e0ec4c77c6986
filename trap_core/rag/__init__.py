"""Frames' regions to plane region adjacency graphs (nodes, contacts, rotation system, faces)."""

from trap_core.rag.errors import GraphError
from trap_core.rag.label_memory import LabelMemory
from trap_core.rag.plane_graph import PlaneGraph, build_plane_graph, colour_label, unknown_step
from trap_core.rag.serialize import graph_from_bytes, graph_to_bytes
from trap_core.rag.stacked import StackedGraphs

__all__ = ["GraphError", "LabelMemory", "PlaneGraph", "StackedGraphs", "build_plane_graph", "colour_label",
           "graph_from_bytes", "graph_to_bytes", "unknown_step"]
