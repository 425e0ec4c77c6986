"""The whole TRAP chain on a stream of frames: parameters, graphs on threads, tracking."""

from trap_core.pipeline.bag_run import BagRun, run_bag
from trap_core.pipeline.chunks import ChunkedRun, ChunkedTracker, ChunkSummary
from trap_core.pipeline.frames_to_graphs import (SetupNote, delivered_frames, first_frame_setup, fitted_to_regions,
                                                 frame_graph, frame_regions, graphs_of, print_setup_notes,
                                                 synthetic_frames, synthetic_graphs)
from trap_core.pipeline.params import GRAPH_STAGE, IMAGE_STEP_STAGE, METHODS, SEGMENTATIONS, ParameterError, TrapParams
from trap_core.pipeline.pattern_miner import PatternMiner
from trap_core.pipeline.tracking import TrackingResult, track

__all__ = ["GRAPH_STAGE", "IMAGE_STEP_STAGE", "METHODS", "SEGMENTATIONS", "BagRun", "ChunkSummary", "ChunkedRun",
           "ChunkedTracker", "ParameterError", "PatternMiner", "SetupNote", "TrackingResult", "TrapParams",
           "delivered_frames", "first_frame_setup", "fitted_to_regions", "frame_graph", "frame_regions", "graphs_of",
           "print_setup_notes", "run_bag", "synthetic_frames", "synthetic_graphs", "track"]
