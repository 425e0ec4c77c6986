"""Parameters of the miner, with the paper's defaults (TRAP_SPEC section 3)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from trap_core.mining.errors import MiningError

LINKINGS = ("graph", "assignment")


@dataclass(frozen=True)
class MiningParams:
    """Parameters of the miner, with the paper's defaults (eps 40 px, tau 25 frames, freq = freq_st)."""

    eps: float = 40.0
    tau: int = 25
    freq_st_min: int = 20
    freq_min: int | None = None  # None: equal to freq_st_min, as in the paper
    max_faces: int = 3
    linking: str = "graph"  # "graph": components of the occurrence graph (paper); "assignment": one path per object (ours)
    reach: float = 0.0  # assignment: steps of a chain at most this times its last occurrence's size (x sqrt(gap)); 0 = eps only
    freq_st_cut: int | None = None  # frames enough for a pattern seen within tau of the first or last frame (ours); None = freq_st_min
    threads: int = 1  # frames whose face sets are enumerated at once (the compiled kernels release the GIL)

    def __post_init__(self) -> None:
        if not (np.isfinite(self.eps) and self.eps > 0):
            raise MiningError(f"eps must be a positive number of pixels, not {self.eps}")
        if self.tau < 1 or self.freq_st_min < 1 or self.max_faces < 1:
            raise MiningError("tau, freq_st_min and max_faces must be at least 1")
        if self.linking not in LINKINGS:
            raise MiningError(f"linking must be one of {LINKINGS}, not {self.linking!r}")
        if not (np.isfinite(self.reach) and self.reach >= 0):
            raise MiningError(f"reach must be a number >= 0, not {self.reach}")
        if self.freq_st_cut is not None and self.freq_st_cut < 1:
            raise MiningError(f"freq_st_cut must be at least 1, not {self.freq_st_cut}")
        if self.threads < 1:
            raise MiningError(f"threads must be at least 1, not {self.threads}")
        if self.freq_min is not None and self.freq_min < 1:
            raise MiningError(f"freq_min must be at least 1, not {self.freq_min}")

    def frequent_enough(self, frames_seen: np.ndarray, first: np.ndarray, last: np.ndarray,
                        n_frames: int) -> np.ndarray:
        """Whether spatio-temporal patterns seen in ``frames_seen`` distinct frames, from frame
        ``first`` to ``last`` of frames 0..``n_frames``-1, are kept: ``freq_st >= freq_st_min``
        (TRAP_SPEC section 3), or, for one seen within ``tau`` frames of the first or last frame,
        ``freq_st >= freq_st_cut``: the video's start or end cut it, and an object that enters
        (leaves) the view in its last (first) ``freq_st_min`` frames could not be seen longer."""
        kept = frames_seen >= self.freq_st_min
        if self.freq_st_cut is not None:
            kept |= (frames_seen >= self.freq_st_cut) & ((first < self.tau) | (last >= n_frames - self.tau))
        return kept

    @property
    def frequency(self) -> int:
        return self.freq_st_min if self.freq_min is None else self.freq_min
