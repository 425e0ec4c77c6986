"""Lossless byte encoding of a :class:`PlaneGraph`, for passing graphs between ROS nodes.

Layout (little-endian): the 8-byte magic ``TRAPPG03``, then the node count and the sizes of
the half-edge and face arrays as three uint64, the camera's step into the frame as six float64
(NaN where it was not read), then the arrays in field order, each as raw float32 or int32 (the
graph's own types). ``graph_from_bytes(graph_to_bytes(g))`` equals ``g`` field for field.
"""
from __future__ import annotations

import numpy as np

from trap_core.rag.errors import GraphError
from trap_core.rag.plane_graph import PlaneGraph

MAGIC = b"TRAPPG03"
HEADER = 8 + 3 * 8 + 6 * 8  # magic, sizes, camera step
# (field, dtype, shape given n nodes / h half-edges / f faces)
_FIELDS = (
    ("centroid", "<f4", lambda n, h, f: (n, 2)), ("area", "<i4", lambda n, h, f: (n,)),
    ("bbox", "<i4", lambda n, h, f: (n, 4)), ("colour", "<f4", lambda n, h, f: (n, 3)),
    ("label", "<i4", lambda n, h, f: (n,)), ("he_origin", "<i4", lambda n, h, f: (h,)),
    ("he_twin", "<i4", lambda n, h, f: (h,)), ("he_next", "<i4", lambda n, h, f: (h,)),
    ("he_length", "<i4", lambda n, h, f: (h,)), ("face_of", "<i4", lambda n, h, f: (h,)),
    ("face_half_edges", "<i4", lambda n, h, f: (h,)), ("face_offsets", "<i4", lambda n, h, f: (f + 1,)),
)


def graph_to_bytes(graph: PlaneGraph) -> bytes:
    """Encode ``graph`` (see the module docstring for the layout)."""
    sizes = np.array([graph.n_nodes, graph.he_twin.size, graph.n_faces], dtype="<u8")
    parts = [MAGIC, sizes.tobytes(), np.ascontiguousarray(graph.camera_step, dtype="<f8").tobytes()]
    parts += [np.ascontiguousarray(getattr(graph, name), dtype=dtype).tobytes() for name, dtype, _ in _FIELDS]
    return b"".join(parts)


def graph_from_bytes(data: bytes | bytearray | memoryview | np.ndarray) -> PlaneGraph:
    """Decode what :func:`graph_to_bytes` wrote; a malformed buffer is a :class:`GraphError`."""
    buffer = memoryview(np.frombuffer(data, dtype=np.uint8)).cast("B") if isinstance(data, np.ndarray) \
        else memoryview(data).cast("B")
    if bytes(buffer[:8]) != MAGIC or len(buffer) < HEADER:
        raise GraphError("not a trap_ros plane graph (bad magic or too short)")
    n, h, f = (int(v) for v in np.frombuffer(buffer[8:32], dtype="<u8"))
    camera_step = np.frombuffer(buffer[32:HEADER], dtype="<f8").reshape(2, 3).astype(np.float64)
    offset = HEADER
    arrays = {}
    for name, dtype, shape_of in _FIELDS:
        shape = shape_of(n, h, f)
        size = int(np.prod(shape)) * np.dtype(dtype).itemsize
        if offset + size > len(buffer):
            raise GraphError(f"plane graph buffer truncated in {name}")
        arrays[name] = np.frombuffer(buffer[offset:offset + size], dtype=dtype).reshape(shape).astype(dtype[1:])
        offset += size
    if offset != len(buffer):
        raise GraphError(f"plane graph buffer has {len(buffer) - offset} trailing bytes")
    return PlaneGraph(n_nodes=n, **arrays, camera_step=camera_step)
