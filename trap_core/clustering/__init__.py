"""Spatio-temporal patterns to tracks: trajectories, distance, hierarchy, lifetime cut, selection."""

from trap_core.clustering.distance import pattern_distances
from trap_core.clustering.errors import ClusteringError
from trap_core.clustering.hierarchy import LINKAGES, Hierarchy, cluster_patterns, labels_after_merges, lifetime_cut
from trap_core.clustering.selection import (MAX_TRACKS, ClusterSummary, seen_frames, select_clusters, summarise,
                                           twin_clusters)
from trap_core.clustering.tracks import (FrameCores, Track, border_sides, box_centres, box_containment, box_iou,
                                        box_path, build_track, centre_inside, centre_path, centre_steps, core_regions,
                                        frame_cores, in_rows, one_place, points_in_boxes, reaches_border,
                                        region_boxes_reach_border, regions_in_box, seen_rows, track_pieces, usual_box,
                                        usual_size, with_frames)
from trap_core.clustering.trajectory import ObservedPaths, Trajectories, observed_paths, trajectories

__all__ = [
    "LINKAGES",
    "MAX_TRACKS",
    "ClusterSummary",
    "ClusteringError",
    "FrameCores",
    "Hierarchy",
    "ObservedPaths",
    "Track",
    "Trajectories",
    "border_sides",
    "box_centres",
    "box_containment",
    "box_iou",
    "box_path",
    "build_track",
    "centre_inside",
    "centre_path",
    "centre_steps",
    "cluster_patterns",
    "core_regions",
    "frame_cores",
    "in_rows",
    "labels_after_merges",
    "lifetime_cut",
    "observed_paths",
    "one_place",
    "points_in_boxes",
    "reaches_border",
    "region_boxes_reach_border",
    "regions_in_box",
    "pattern_distances",
    "seen_frames",
    "seen_rows",
    "select_clusters",
    "summarise",
    "track_pieces",
    "trajectories",
    "twin_clusters",
    "usual_box",
    "usual_size",
    "with_frames",
]
