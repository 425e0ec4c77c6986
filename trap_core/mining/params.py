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

    def __post_init__(self) -> None:
        if not (np.isfinite(self.eps) and self.eps > 0):
            raise MiningError(f"eps must be a positive number of pixels, not {self.eps}")
        if self.tau < 1 or self.freq_st_min < 1 or self.max_faces < 1:
            raise MiningError("tau, freq_st_min and max_faces must be at least 1")
        if self.linking not in LINKINGS:
            raise MiningError(f"linking must be one of {LINKINGS}, not {self.linking!r}")
        if not (np.isfinite(self.reach) and self.reach >= 0):
            raise MiningError(f"reach must be a number >= 0, not {self.reach}")
        if self.freq_min is not None and self.freq_min < 1:
            raise MiningError(f"freq_min must be at least 1, not {self.freq_min}")

    @property
    def frequency(self) -> int:
        return self.freq_st_min if self.freq_min is None else self.freq_min
