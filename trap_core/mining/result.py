"""What the miner returns: occurrences as parallel arrays, spatio-temporal patterns as row groups."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class MiningResult:
    """Frequent plane patterns, their kept occurrences, and the spatio-temporal patterns.

    The per-occurrence arrays are 32-bit: a long video has millions of occurrences.

    Occurrence ``r`` is the face set ``occ_faces[r]`` (graph face ids, -1 padded) of frame
    ``occ_frame[r]``, an occurrence of plane pattern ``occ_pattern[r]``. Spatio-temporal
    pattern ``s`` is the rows ``st_rows[st_offsets[s]:st_offsets[s + 1]]`` (sorted by frame).
    """

    pattern_hash: np.ndarray       # (P,) int64 hash of each plane pattern's canonical code
    pattern_frequency: np.ndarray  # (P,) freq(P): frames with an occurrence
    pattern_faces: np.ndarray      # (P,) faces per pattern
    occ_frame: np.ndarray          # (N,) int32
    occ_pattern: np.ndarray        # (N,) int32
    occ_position: np.ndarray       # (N, 2) float32 mean barycentre of the occurrence's nodes
    occ_box: np.ndarray            # (N, 4) float32 x0, y0, x1, y1 of its regions' pixels (inclusive)
    occ_node_box: np.ndarray       # (N, 4) float32 extent of its nodes' barycentres
    occ_faces: np.ndarray          # (N, max_faces) int32 face ids in the frame's graph, -1 padded
    st_pattern: np.ndarray         # (S,) plane pattern of each spatio-temporal pattern
    st_offsets: np.ndarray         # (S+1,)
    st_rows: np.ndarray            # int32 occurrence rows of all spatio-temporal patterns

    @property
    def n_patterns(self) -> int:
        return int(self.pattern_hash.size)

    @property
    def n_st(self) -> int:
        return int(self.st_pattern.size)

    @property
    def st_occurrences(self) -> np.ndarray:
        """(S,) occurrences of each spatio-temporal pattern (its rows in ``st_rows``)."""
        return np.diff(self.st_offsets)

    def st(self, index: int) -> np.ndarray:
        """Occurrence rows of spatio-temporal pattern ``index``."""
        return self.st_rows[self.st_offsets[index]:self.st_offsets[index + 1]]

    def rows_of(self, patterns: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Occurrence rows of the spatio-temporal patterns ``patterns`` (increasing), pattern after
        pattern, and for each row the index in ``patterns`` of the pattern it belongs to."""
        # each pattern's slice of st_rows, read directly: a cluster's rows cost what it holds, not
        # what the video holds (rules read them for hundreds of clusters of a long video)
        lengths = self.st_occurrences[patterns]
        before = np.cumsum(lengths) - lengths
        slots = np.repeat(self.st_offsets[patterns] - before, lengths) + np.arange(int(lengths.sum()))
        return self.st_rows[slots], np.repeat(np.arange(len(patterns)), lengths)

    def freq_st(self) -> np.ndarray:
        """(S,) distinct frames of each spatio-temporal pattern."""
        frames = self.occ_frame[self.st_rows]
        owner = np.repeat(np.arange(self.n_st), self.st_occurrences)
        distinct = np.ones(frames.size, dtype=bool)
        distinct[1:] = (frames[1:] != frames[:-1]) | (owner[1:] != owner[:-1])
        return np.bincount(owner[distinct], minlength=self.n_st)

    def above(self, min_freq: int, min_freq_st: int) -> MiningResult:
        """The spatio-temporal patterns that higher thresholds would have kept: ``freq(P) >= min_freq``
        and ``freq_st >= min_freq_st`` (mining is exact, so this equals mining again with them)."""
        keep = (self.pattern_frequency[self.st_pattern] >= min_freq) & (self.freq_st() >= min_freq_st)
        sizes = self.st_occurrences[keep]
        rows, _ = self.rows_of(np.flatnonzero(keep))
        return MiningResult(self.pattern_hash, self.pattern_frequency, self.pattern_faces, self.occ_frame,
                            self.occ_pattern, self.occ_position, self.occ_box, self.occ_node_box, self.occ_faces,
                            self.st_pattern[keep], np.r_[0, np.cumsum(sizes)].astype(np.int64), rows)
