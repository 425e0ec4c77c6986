"""Conversions between ROS messages and trap_core data.

Plane graphs travel as ``sensor_msgs/CompressedImage`` whose ``format`` is
``trap_ros/plane_graph;v3`` and whose ``data`` is :func:`trap_core.rag.graph_to_bytes` (a
standard type with a header and a byte payload; lossless). Tracks travel as
``vision_msgs/Detection2DArray``: on ``detections`` one message per frame (every box of that
frame, ``Detection2D.id`` = track id), on ``tracks`` one message per track (its box in every
frame, each detection with that frame's header).
"""
from __future__ import annotations

import numpy as np
from geometry_msgs.msg import Point
from sensor_msgs.msg import CompressedImage, Image
from std_msgs.msg import ColorRGBA, Header
from vision_msgs.msg import BoundingBox2D, Detection2D, Detection2DArray, ObjectHypothesis, ObjectHypothesisWithPose
from visualization_msgs.msg import Marker, MarkerArray

from trap_core.bagio import SampleRange, decode_image
from trap_core.clustering import Track
from trap_core.outputs import track_colour
from trap_core.rag import PlaneGraph, graph_from_bytes, graph_to_bytes

GRAPH_FORMAT = "trap_ros/plane_graph;v3"
CLASS_ID = "object"


def image_message(rgb: np.ndarray, header: Header) -> Image:
    """An rgb8 ``sensor_msgs/Image`` of ``rgb`` with ``header``."""
    message = Image(header=header, height=rgb.shape[0], width=rgb.shape[1], encoding="rgb8", is_bigendian=0,
                    step=rgb.shape[1] * 3)
    message.data = np.ascontiguousarray(rgb).reshape(-1).tobytes()
    return message


def image_rgb(message: Image, sample_range: SampleRange | None = None) -> np.ndarray:
    """RGB of an image message; ``sample_range``: the topic's, for wide samples (16-bit, depth)."""
    return decode_image(message.encoding, message.height, message.width, message.step,
                        np.asarray(message.data, dtype=np.uint8), bool(message.is_bigendian), sample_range)


def graph_message(graph: PlaneGraph, header: Header) -> CompressedImage:
    message = CompressedImage(header=header, format=GRAPH_FORMAT)
    message.data = graph_to_bytes(graph)
    return message


def message_graph(message: CompressedImage) -> PlaneGraph:
    if message.format != GRAPH_FORMAT:
        raise ValueError(f"graph message of format {message.format!r}, expected {GRAPH_FORMAT!r}")
    return graph_from_bytes(np.asarray(message.data, dtype=np.uint8).tobytes())


def _detection(header: Header, track_id: int, box: np.ndarray, score: float) -> Detection2D:
    x, y, w, h = (float(v) for v in box)
    bbox = BoundingBox2D(size_x=w, size_y=h)
    bbox.center.position.x = x + w / 2
    bbox.center.position.y = y + h / 2
    hypothesis = ObjectHypothesisWithPose(hypothesis=ObjectHypothesis(class_id=CLASS_ID, score=float(score)))
    return Detection2D(header=header, results=[hypothesis], bbox=bbox, id=str(track_id))


def frame_detections(headers: list[Header], tracks: list[Track], first: int = 0, stop: int | None = None,
                     ) -> list[Detection2DArray]:
    """One Detection2DArray per frame of ``first..stop-1`` (default: every frame of ``headers``),
    empty where no track is seen; header = the frame's image header."""
    stop = len(headers) if stop is None else stop
    per_frame: list[list[Detection2D]] = [[] for _ in range(first, stop)]
    for trk in tracks:
        for frame, box, score in zip(trk.frames.tolist(), trk.boxes, trk.score):
            if first <= frame < stop:
                per_frame[frame - first].append(_detection(headers[frame], trk.track_id, box, score))
    return [Detection2DArray(header=headers[first + i], detections=found) for i, found in enumerate(per_frame)]


def track_arrays(headers: list[Header], tracks: list[Track]) -> list[Detection2DArray]:
    """One Detection2DArray per track: its box in every frame it is seen (header: its first frame)."""
    return [Detection2DArray(header=headers[int(trk.frames[0])],
                             detections=[_detection(headers[f], trk.track_id, box, score)
                                         for f, box, score in zip(trk.frames, trk.boxes, trk.score)])
            for trk in tracks]


def _colour(rgb: tuple[int, int, int], alpha: float = 1.0) -> ColorRGBA:
    return ColorRGBA(r=rgb[0] / 255, g=rgb[1] / 255, b=rgb[2] / 255, a=alpha)


def trajectory_markers(header: Header, tracks: list[Track]) -> MarkerArray:
    """A LINE_STRIP per track through its box centres, in pixel coordinates of the camera frame."""
    markers = MarkerArray()
    for trk in tracks:
        marker = Marker(header=header, ns="trap_trajectories", id=trk.track_id, type=Marker.LINE_STRIP,
                        action=Marker.ADD, color=_colour(track_colour(trk.track_id)))
        marker.scale.x = 2.0
        marker.pose.orientation.w = 1.0
        centres = trk.boxes[:, :2] + trk.boxes[:, 2:] / 2
        marker.points = [Point(x=float(x), y=float(y), z=0.0) for x, y in centres]
        markers.markers.append(marker)
    return markers


def graph_markers(header: Header, graph: PlaneGraph) -> MarkerArray:
    """Regions as points (their mean colour) and contacts as lines, in pixel coordinates."""
    nodes = Marker(header=header, ns="trap_graph_nodes", id=0, type=Marker.SPHERE_LIST, action=Marker.ADD)
    nodes.scale.x = nodes.scale.y = nodes.scale.z = 4.0
    nodes.pose.orientation.w = 1.0
    nodes.points = [Point(x=float(x), y=float(y), z=0.0) for x, y in graph.centroid]
    nodes.colors = [_colour(tuple(int(c) for c in colour)) for colour in graph.colour]
    edges = Marker(header=header, ns="trap_graph_edges", id=1, type=Marker.LINE_LIST, action=Marker.ADD,
                   color=ColorRGBA(r=1.0, g=1.0, b=1.0, a=0.6))
    edges.scale.x = 1.0
    edges.pose.orientation.w = 1.0
    pairs = graph.edges
    pairs = pairs[(pairs < graph.n_nodes).all(axis=1)]
    edges.points = [Point(x=float(graph.centroid[n, 0]), y=float(graph.centroid[n, 1]), z=0.0) for n in pairs.ravel()]
    return MarkerArray(markers=[nodes, edges])
