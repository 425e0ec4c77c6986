"""Beyond the paper: camera-motion compensation, object/background split, fragment rejoining."""

from trap_core.robust.camera import ObservedPaths, camera_transforms, observed_paths, world_speed
from trap_core.robust.box_size import steady_boxes
from trap_core.robust.rejoin import border_contacts, rejoin_fragments

__all__ = ["ObservedPaths", "border_contacts", "camera_transforms", "observed_paths", "rejoin_fragments",
           "steady_boxes", "world_speed"]
