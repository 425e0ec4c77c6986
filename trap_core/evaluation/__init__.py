"""Measures: the paper's cluster and box precision/recall."""

from trap_core.evaluation.paper_measures import box_precision_recall, cluster_precision_recall

__all__ = ["box_precision_recall", "cluster_precision_recall"]
