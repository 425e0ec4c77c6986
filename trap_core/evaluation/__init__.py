"""Measures: the paper's cluster and box precision/recall, scores of a set of tracks, and how much of
the objects a segmentation leaks into the background."""

from trap_core.evaluation.paper_measures import box_precision_recall, cluster_precision_recall
from trap_core.evaluation.region_leak import leaked_pixels, leaked_regions
from trap_core.evaluation.scoring import boxes_by_frame, match_objects, mot_measures

__all__ = ["box_precision_recall", "boxes_by_frame", "cluster_precision_recall", "leaked_pixels", "leaked_regions",
           "match_objects", "mot_measures"]
