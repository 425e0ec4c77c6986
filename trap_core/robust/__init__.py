"""Beyond the paper: camera-motion compensation, object/background split, fragment rejoining."""

from trap_core.robust.box_size import steady_boxes
from trap_core.robust.camera import camera_transforms, world_speed
from trap_core.robust.rejoin import border_contacts, rejoin_fragments

__all__ = ["border_contacts", "camera_transforms", "rejoin_fragments", "steady_boxes", "world_speed"]
