"""Plane graphs over time to spatio-temporal patterns (DYPLAGRAM_ST, TRAP_SPEC section 3)."""

from trap_core.mining.errors import MiningError
from trap_core.mining.faces import FaceTable, canonical_code, face_table
from trap_core.mining.miner import (MiningParams, MiningResult, Occurrences, SpatioTemporalPattern,
                                    connected_face_sets, mine, occurrence_components)

__all__ = [
    "FaceTable",
    "MiningError",
    "MiningParams",
    "MiningResult",
    "Occurrences",
    "SpatioTemporalPattern",
    "canonical_code",
    "connected_face_sets",
    "face_table",
    "mine",
    "occurrence_components",
]
