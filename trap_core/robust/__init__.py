"""Beyond the paper: camera-motion compensation, object/background split, fragment rejoining."""

from trap_core.robust.camera import ObservedPaths, camera_transforms, observed_paths, world_speed
from trap_core.robust.rejoin import rejoin_fragments

__all__ = ["ObservedPaths", "camera_transforms", "observed_paths", "rejoin_fragments", "world_speed"]
