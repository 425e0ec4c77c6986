"""One frame's region adjacency graph as a plane graph (TRAP_SPEC section 2)."""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from trap_core.rag._kernels import (colour_labels, drop_short_contacts, region_stats, rotation_system, sets_nodes,
                                    trace_boundary_graph, trace_faces)
from trap_core.rag._kernels import nodes_box as _nodes_box
from trap_core.rag._kernels import outer_lines as _outer_lines
from trap_core.rag.errors import GraphError

BACKDROP_SHARE = 0.5  # a region over this share of the frame is the backdrop: only one can be
# Px of the size a frame was segmented at: a region thinner than this on average is a line of
# blended pixels along an edge. Smoothing before segmentation spreads a sharp edge over a pixel on
# either side, and Felzenszwalb's method makes each such line a region of its own (longer than
# ``min_size``); a line one pixel wide is about 1 thick, a band two pixels wide about 2.
EDGE_LINE = 1.5


def edge_line_limits(pixel: float) -> tuple[float, float]:
    """For frames segmented at ``pixel`` frame pixels per pixel (0: edge lines count like any
    region): the thickness under which a region is an edge line, and how far (frame px) such
    lines may push a box's side out and still be left out of it, a side moving by whole frame
    pixels (:meth:`PlaneGraph.nodes_box`); both 0 where they count."""
    return (EDGE_LINE * pixel, EDGE_LINE * max(pixel, 1.0)) if pixel > 0 else (0.0, 0.0)


def _box_or_none(around: np.ndarray | None) -> np.ndarray:
    """``around`` (x, y, w, h) as the compiled kernels take it: no values for no box."""
    return np.zeros(0) if around is None else np.asarray(around, dtype=np.float64)


def unknown_step() -> np.ndarray:
    """(2, 3) of NaN: the camera's step into a frame that was not read from the images (a
    video's first frame, a frame with too little texture, a graph made from labels alone)."""
    return np.full((2, 3), np.nan)


@dataclass(frozen=True)
class PlaneGraph:
    """Regions, their contacts and the planar embedding of one frame.

    Nodes ``0..n_nodes-1`` are regions; node ``n_nodes`` stands for the outside of the image
    (so contacts with the border are edges and the outer face is explicit). The embedding is
    stored as half-edges: half-edge ``h`` leaves ``he_origin[h]``; ``he_twin[h]`` is its
    reverse; ``he_next[h]`` is the next half-edge around the same node (rotation system).
    Every contact *stretch* is one edge, so two regions touching along two separate stretches
    share two edges. Faces are the orbits of ``h -> he_next[he_twin[h]]``.
    """

    n_nodes: int
    centroid: np.ndarray      # (n, 2) float32: barycentre x, y
    area: np.ndarray          # (n,) int32: pixels
    bbox: np.ndarray          # (n, 4) int32: x0, y0, x1, y1 inclusive
    colour: np.ndarray        # (n, 3) float32: mean RGB
    label: np.ndarray         # (n,) int32: discretised mean colour
    he_origin: np.ndarray     # (2m,) int32
    he_twin: np.ndarray       # (2m,) int32
    he_next: np.ndarray       # (2m,) int32
    he_length: np.ndarray     # (2m,) int32: contact length in pixel edges
    face_of: np.ndarray       # (2m,) int32: face on the left... of each half-edge's traversal
    face_half_edges: np.ndarray  # half-edges of all faces, in traversal order
    face_offsets: np.ndarray  # (F+1,) CSR offsets into face_half_edges
    camera_step: np.ndarray = field(default_factory=unknown_step)  # (2, 3) float64: the camera's motion from the
    # previous frame, a similarity taking its pixel positions to this frame's (trap_core.robust.image_steps)

    @property
    def has_camera_step(self) -> bool:
        """Whether :attr:`camera_step` was read from the images."""
        return bool(np.isfinite(self.camera_step).all())

    @property
    def outside(self) -> int:
        """Node id of the image's outside."""
        return self.n_nodes

    @property
    def frame_size(self) -> tuple[float, float]:
        """(width, height) of the frame: its regions tile it."""
        return float(self.bbox[:, 2].max() + 1), float(self.bbox[:, 3].max() + 1)

    def nodes_box(self, nodes: np.ndarray, pixel: float = 0.0, around: np.ndarray | None = None) -> np.ndarray:
        """(x, y, w, h) of the box around the pixels of regions ``nodes`` (indices or a mask; their
        ``bbox`` is inclusive) and the box ``around`` (x, y, w, h), if given.

        With ``pixel`` (frame pixels per pixel of the size the frame was segmented at), the edge
        lines outside what the box holds are left out (:meth:`outer_lines`) where they push a side
        out by at most an edge line's width: the line outside an object's edge is ground in the
        frame (smoothing blended the object's colour into it for the segmentation), and counted
        in, it widens a box by a pixel all round (a fifth of the area of a 20 px disc).
        Compiled: tracks ask for a box of every frame many times over.
        """
        nodes = np.asarray(nodes)
        nodes = np.flatnonzero(nodes) if nodes.dtype == bool else nodes.astype(np.int64, copy=False)
        return _nodes_box(self.bbox, self.thickness, self.nearest_in_colour, nodes, _box_or_none(around),
                          *edge_line_limits(pixel))

    def outer_lines(self, nodes: np.ndarray, pixel: float, around: np.ndarray | None = None) -> np.ndarray:
        """(len(nodes),) which of the regions ``nodes`` (indices) are edge lines (under
        ``EDGE_LINE`` :attr:`thickness`, in px of the segmentation's size: ``pixel`` frame pixels
        each) outside the others: a region next to them that is neither one of ``nodes`` nor
        inside the box ``around`` (x, y, w, h) has a colour nearer their own than any that is.
        Smoothing blends each side of a sharp edge with the other: the line on the object's side
        keeps most of the object's colour, the one outside most of the ground's."""
        return _outer_lines(self.bbox, self.thickness, self.nearest_in_colour, np.asarray(nodes, dtype=np.int64),
                            edge_line_limits(pixel)[0], _box_or_none(around))

    @cached_property
    def nearest_in_colour(self) -> np.ndarray:
        """(n,) each region's neighbour (the image's outside aside) of the nearest mean colour; -1
        for a region that touches nothing else. Read once per graph."""
        other = self.he_origin[self.he_twin]
        keep = (other != self.outside) & (self.he_origin != self.outside)
        origin, other = self.he_origin[keep], other[keep]
        distance = np.linalg.norm(self.colour[origin] - self.colour[other], axis=1)
        order = np.lexsort((distance, origin))
        first = np.r_[True, origin[order][1:] != origin[order][:-1]]
        nearest = np.full(self.n_nodes, -1, dtype=np.int32)  # held with the graph: kept small
        nearest[origin[order][first]] = other[order][first]
        return nearest

    @cached_property
    def thickness(self) -> np.ndarray:
        """(n,) each region's mean thickness in pixels: twice its area over its perimeter (its
        contacts' lengths, the image border's included): about 1 for a line of single pixels,
        half the side of a square, the radius of a disc. Read once per graph."""
        perimeter = np.bincount(self.he_origin, weights=self.he_length, minlength=self.n_nodes + 1)[:self.n_nodes]
        return (2.0 * self.area / np.maximum(perimeter, 1.0)).astype(np.float32)  # held with the graph: kept small

    @cached_property
    def backdrop(self) -> np.ndarray:
        """(n,) bool: the region over ``BACKDROP_SHARE`` of the frame, if there is one. Over a
        plain scene (sky, asphalt, a lawn, a smooth photograph) one region covers most of the
        view and most faces hold it, objects' faces too: it is the scene, never an object, and
        its barycentre stays near the middle of the view wherever the camera goes. Read once
        per graph: every core box of every track asks for it again."""
        return self.area > BACKDROP_SHARE * np.prod(self.frame_size)

    @property
    def n_faces(self) -> int:
        return self.face_offsets.size - 1

    @property
    def edges(self) -> np.ndarray:
        """(m, 2) node pairs, one row per contact stretch (outside node included)."""
        first = np.flatnonzero(np.arange(self.he_twin.size) < self.he_twin)
        return np.column_stack([self.he_origin[first], self.he_origin[self.he_twin[first]]])

    def face_nodes(self, face: int) -> np.ndarray:
        """Nodes around ``face`` in traversal order (a node repeats where the face touches it twice)."""
        return self.he_origin[self.face_half_edges[self.face_offsets[face]:self.face_offsets[face + 1]]]

    def faces_nodes(self, faces: np.ndarray | frozenset[int]) -> np.ndarray:
        """Nodes (sorted, distinct) around a set of faces, such as one pattern occurrence (face
        ids below 0 are padding and skipped)."""
        return self.sets_nodes(np.fromiter(faces, np.int64).reshape(1, -1))[0]

    def sets_nodes(self, face_sets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Nodes (sorted, distinct) around each row of ``face_sets`` (occurrences' faces, ids
        below 0 are padding), the rows' one after the other, and where each row's end: the
        regions of a frame's many occurrences in one compiled pass rather than one call each.
        """
        face_sets = np.asarray(face_sets, dtype=np.int64).reshape(len(face_sets), -1)
        return sets_nodes(face_sets, self.he_origin, self.face_half_edges, self.face_offsets, self.n_nodes + 1)

    def outer_faces(self) -> np.ndarray:
        """(F,) bool: the face touches the outside node (it is part of the outer face)."""
        touches = self.he_origin[self.face_half_edges] == self.outside
        return np.logical_or.reduceat(touches, self.face_offsets[:-1]) if touches.size else np.zeros(0, bool)

    def rotation(self, node: int) -> np.ndarray:
        """Neighbours of ``node`` in cyclic order around it (one entry per contact stretch)."""
        start = np.flatnonzero(self.he_origin == node)
        if start.size == 0:
            return np.empty(0, dtype=np.int64)
        order = [start[0]]
        h = self.he_next[start[0]]
        while h != start[0]:
            order.append(h)
            h = self.he_next[h]
        return self.he_origin[self.he_twin[np.array(order)]]

    def euler_characteristic(self) -> int:
        """V - E + F of the embedding, outside node included: 2 for a plane embedding."""
        return (self.n_nodes + 1) - self.he_twin.size // 2 + self.n_faces

    def degree(self) -> np.ndarray:
        """(n,) number of distinct neighbouring regions of each region (the outside not counted)."""
        pairs = self.edges
        pairs = pairs[(pairs < self.n_nodes).all(axis=1)]
        pairs = np.unique(np.sort(pairs, axis=1), axis=0)
        return np.bincount(pairs.ravel(), minlength=self.n_nodes)


def colour_label(colour: np.ndarray, bins: int) -> np.ndarray:
    """Discretise mean colours into ``bins`` levels per channel: label = r * bins^2 + g * bins + b.

    A grey mean (all channels equal: every region of a mono camera's frame) is cut into
    ``bins``^2 levels instead, labels ``bins``^3 and up: with ``bins`` levels on the grey axis
    alone, a mono video would have a handful of labels and its patterns would tell little apart.
    Levels are read in float64 (compiled: :class:`~trap_core.rag.label_memory.LabelMemory`
    labels every frame's new regions with it).
    """
    return colour_labels(np.asarray(colour, dtype=np.float64), bins)


def build_plane_graph(labels: np.ndarray, n_regions: int, rgb: np.ndarray, colour_bins: int = 4,
                      contact_tolerance: float = 0.0) -> PlaneGraph:
    """Build the plane region adjacency graph of a label image.

    Parameters
    ----------
    labels : (H, W) int32 array
        Region of each pixel, ``0..n_regions-1``, each region 4-connected (what
        :mod:`trap_core.segmentation` returns).
    n_regions : int
    rgb : (H, W, 3) uint8 array
        The frame, for mean colours.
    colour_bins : int
        Levels per channel of the node label (TRAP_SPEC section 2: label = discretised colour).
    contact_tolerance : float
        Contacts shorter than ``contact_tolerance * sqrt(area of the smaller region)`` pixels
        are dropped where that merges two faces (ours: stable faces under pixel rounding, at any
        scale); 0 keeps every contact.

    Returns
    -------
    PlaneGraph
        Nodes with barycentre, area, box, colour and label; the embedding read off the pixel
        topology (junctions of three or more regions are faces), valid by construction:
        ``euler_characteristic() == 2``.
    """
    if labels.ndim != 2 or labels.shape != rgb.shape[:2] or labels.size == 0:
        raise GraphError(f"labels {labels.shape} and image {rgb.shape} do not match")
    if not (np.isfinite(contact_tolerance) and contact_tolerance >= 0):
        raise GraphError(f"contact_tolerance must be >= 0, not {contact_tolerance}")
    if not 1 <= colour_bins <= 256:
        raise GraphError(f"colour_bins must be within 1..256, not {colour_bins}")
    labels = np.ascontiguousarray(labels, dtype=np.int32)
    area, sums, box = region_stats(labels, rgb, n_regions)
    if (area == 0).any():
        raise GraphError("label image has unused labels: regions must be numbered 0..n-1")
    centroid = sums[:, :2] / area[:, None]
    colour = sums[:, 2:] / area[:, None]
    oi, oj, sdir, twin, left, right, length, area2, dart_of = trace_boundary_graph(labels, n_regions)
    rot_next = rotation_system(oi, oj, sdir, twin, right, area2, dart_of, n_regions + 1)
    face_of, face_half_edges, face_offsets = trace_faces(rot_next, twin)
    if contact_tolerance > 0:
        right, twin, rot_next, length = drop_short_contacts(right, twin, rot_next, length, face_of, area, n_regions,
                                                            float(contact_tolerance))
        face_of, face_half_edges, face_offsets = trace_faces(rot_next, twin)
    return PlaneGraph(n_regions, *_compact(centroid, area, box, colour, colour_label(colour, colour_bins), right,
                                           twin, rot_next, length, face_of, face_half_edges, face_offsets))


def _compact(*arrays: np.ndarray) -> list[np.ndarray]:
    """32-bit copies of the graph's arrays: a video's graphs are kept until its tracks are built,
    and half the bytes is half the memory (issue #7); every count and pixel coordinate fits."""
    return [a.astype(np.float32 if a.dtype.kind == "f" else np.int32) for a in arrays]
