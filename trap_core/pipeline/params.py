"""All parameters of a TRAP run, flat names as used in ROS parameter files (config/trap.yaml)."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from trap_core.clustering import LINKAGES
from trap_core.mining import MiningParams
from trap_core.segmentation import THRESHOLD_MODES

SEGMENTATIONS = ("felzenszwalb", "colour")
METHODS = ("paper", "robust")


class ParameterError(ValueError):
    """A parameter is unknown or out of range; the message is one line for the user."""


@dataclass(frozen=True)
class TrapParams:
    """Defaults are the paper's (TRAP_SPEC), marked (ours) where the paper is silent."""

    # Segmentation (section 1)
    segmentation: str = "felzenszwalb"   # or "colour": exact-colour regions (synthetic videos)
    k: float = 10.0                      # threshold constant (constant mode: colour units)
    sigma: float = 0.8
    min_size: int = 20
    threshold: str = "constant"          # "constant" (paper) or "size" (original)
    connectivity: int = 4
    # Graph (section 2)
    colour_bins: int = 4                 # levels per channel of node labels (ours)
    # Mining (section 3)
    eps: float = 40.0
    tau: int = 25
    freq_st_min: float = 0.05            # < 1: share of the frames; >= 1: frames (ours: 5 %)
    freq_min: float = 0.0                # 0: equal to freq_st_min (paper)
    max_faces: int = 3
    # Clustering and selection (sections 6-7)
    method: str = "robust"               # "paper": TRAP as published; "robust" (ours): see README
    min_speed: float = 0.5               # px/frame relative to the camera: slower patterns are background (robust)
    rejoin_similarity: float = 0.3       # Jaccard of plane patterns to rejoin fragments (robust)
    core_share: float = 0.5              # track box: regions in this share of the occurrences (robust)
    linkage: str = "average"             # (ours)
    ignore_top: float = 0.1
    n_objects: int = 0                   # 0: found without supervision (ours)
    length_tolerance: float = 0.1
    min_track_length: float = 0.25       # share of the video a track must cover (ours)
    separation: float = 40.0             # px between kept tracks' paths (ours)
    threads: int = 2

    def __post_init__(self) -> None:
        checks = [
            (self.segmentation in SEGMENTATIONS, f"segmentation must be one of {SEGMENTATIONS}"),
            (self.threshold in THRESHOLD_MODES, f"threshold must be one of {THRESHOLD_MODES}"),
            (self.method in METHODS, f"method must be one of {METHODS}"),
            (self.linkage in LINKAGES, f"linkage must be one of {LINKAGES}"),
            (self.k >= 0 and self.sigma >= 0 and self.min_size >= 0, "k, sigma and min_size must be >= 0"),
            (self.connectivity in (4, 8), "connectivity must be 4 or 8"),
            (1 <= self.colour_bins <= 256, "colour_bins must be within 1..256"),
            (self.eps > 0 and self.tau >= 1, "eps must be > 0 and tau >= 1"),
            (self.freq_st_min > 0 and self.freq_min >= 0, "freq_st_min must be > 0 and freq_min >= 0"),
            (1 <= self.max_faces <= 8, "max_faces must be within 1..8"),
            (0 <= self.ignore_top < 1 and 0 <= self.length_tolerance <= 1, "ignore_top and length_tolerance within [0, 1)"),
            (self.n_objects >= 0 and 0 <= self.min_track_length <= 1, "n_objects >= 0, min_track_length within [0, 1]"),
            (self.separation >= 0 and 1 <= self.threads <= 64, "separation >= 0 and threads within 1..64"),
            (self.min_speed >= 0 and 0 <= self.rejoin_similarity <= 1 and 0 <= self.core_share <= 1,
             "min_speed >= 0, rejoin_similarity and core_share within [0, 1]"),
        ]
        for ok, message in checks:
            if not ok:
                raise ParameterError(f"{message} (got {self.as_dict()})")

    def as_dict(self) -> dict[str, Any]:
        return dataclasses.asdict(self)

    def mining(self, n_frames: int) -> MiningParams:
        """Mining parameters for a video of ``n_frames`` (shares of the video become frame counts)."""
        def frames(value: float) -> int:
            return max(1, round(value * n_frames)) if value < 1 else int(value)
        return MiningParams(eps=self.eps, tau=self.tau, freq_st_min=frames(self.freq_st_min),
                            freq_min=frames(self.freq_min) if self.freq_min else None, max_faces=self.max_faces,
                            linking="assignment" if self.method == "robust" else "graph")

    @classmethod
    def from_mapping(cls, values: dict[str, Any]) -> TrapParams:
        """Build from a flat mapping (ROS parameters); unknown names are an error."""
        fields = {f.name: f for f in dataclasses.fields(cls)}
        unknown = sorted(set(values) - set(fields))
        if unknown:
            raise ParameterError(f"unknown parameter(s): {', '.join(unknown)} (known: {', '.join(fields)})")
        typed = {}
        for name, value in values.items():
            kind = type(fields[name].default)
            try:
                typed[name] = kind(value) if kind is not bool else bool(value)
            except (TypeError, ValueError):
                raise ParameterError(f"parameter {name} must be a {kind.__name__}, not {value!r}") from None
        return cls(**typed)
