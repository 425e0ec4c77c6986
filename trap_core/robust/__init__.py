"""Beyond the paper: camera-motion compensation, object/background split, fragment rejoining,
track boxes without the background and where objects meet."""

from trap_core.clustering import reaches_border
from trap_core.robust.anchors import scene_patterns, stays_with_scene
from trap_core.robust.appearance import colour_overlap, colour_shares
from trap_core.robust.backdrop import (HELD_SHARE, SHADOWED_SHARE, held_share, shadowed,
                                       without_backdrop)
from trap_core.robust.borders import continue_to_border, end_at_exits
from trap_core.robust.box_edges import steady_edges
from trap_core.robust.camera import (HOP_SHARE, camera_paths, camera_transforms, cluster_world_speed, world_reach,
                                     world_speed, world_steps)
from trap_core.robust.continuation import continue_tracks, join_handovers, mend_shared_stretches
from trap_core.robust.crossings import lookalike_meetings, lookalike_tracks, swap_at_crossings
from trap_core.robust.end_colours import EndColours, colours_match
from trap_core.robust.ends import alone_at_ends
from trap_core.robust.duplicates import (drop_repeated_pieces, drop_shared_stretches, extend_from_twins,
                                         merge_duplicates, merge_parts, repeats_others)
from trap_core.robust.extent import grow_boxes
from trap_core.robust.follow import follow_ends
from trap_core.robust.gaps import fill_gaps
from trap_core.robust.groups import separate_groups
from trap_core.robust.hops import moves_in_hops, steady_clusters, steady_patterns, track_steps_steadily, unsteady_steps
from trap_core.robust.mixed import pattern_sizes, split_mixed
from trap_core.robust.owners import hand_to_owners
from trap_core.robust.rejoin import (CUT_SHARE, BorderContacts, border_contacts, border_share, rejoin_fragments,
                                    whole_patterns_apart)
from trap_core.robust.returns import entering_part, join_returns, join_spare_returns, spare_entries
from trap_core.robust.sizes import keep_one_size
from trap_core.robust.still import drop_still_regions
from trap_core.robust.strays import drop_stray_pieces, drop_strays
from trap_core.robust.through_groups import GroupBoxes, through_groups

__all__ = ["CUT_SHARE", "HELD_SHARE", "HOP_SHARE", "SHADOWED_SHARE", "BorderContacts", "EndColours", "GroupBoxes",
           "alone_at_ends", "border_contacts", "border_share", "camera_paths", "camera_transforms",
           "cluster_world_speed", "colour_overlap", "colour_shares", "colours_match", "continue_to_border",
           "continue_tracks", "drop_repeated_pieces", "drop_shared_stretches", "drop_still_regions",
           "drop_stray_pieces", "drop_strays", "end_at_exits", "entering_part", "extend_from_twins", "fill_gaps",
           "follow_ends", "grow_boxes", "hand_to_owners", "held_share", "join_handovers", "join_returns",
           "join_spare_returns", "keep_one_size", "lookalike_meetings", "lookalike_tracks", "mend_shared_stretches",
           "merge_duplicates", "merge_parts", "moves_in_hops", "pattern_sizes", "reaches_border", "rejoin_fragments",
           "repeats_others", "scene_patterns", "separate_groups", "shadowed", "spare_entries", "split_mixed",
           "stays_with_scene", "steady_clusters", "steady_edges", "steady_patterns", "swap_at_crossings",
           "through_groups", "track_steps_steadily", "unsteady_steps", "whole_patterns_apart", "without_backdrop",
           "world_reach", "world_speed", "world_steps"]
