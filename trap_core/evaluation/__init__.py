"""Measures: the paper's cluster and box precision/recall, scores of a set of tracks, which object
each track holds (and its picture), why an object falls short (the frames and box area its track
loses, by cause), and how much of the objects a segmentation leaks into the background."""

from trap_core.evaluation.held_objects import held_objects, object_timeline
from trap_core.evaluation.losses import ObjectLosses, object_losses
from trap_core.evaluation.paper_measures import box_precision_recall, cluster_precision_recall
from trap_core.evaluation.region_leak import leaked_pixels, leaked_regions
from trap_core.evaluation.scoring import boxes_by_frame, match_objects, mot_measures

__all__ = ["ObjectLosses", "box_precision_recall", "boxes_by_frame", "cluster_precision_recall", "held_objects",
           "leaked_pixels", "leaked_regions", "match_objects", "mot_measures", "object_losses", "object_timeline"]
