"""Results as files and pictures: MOTChallenge tracks, contact sheets with boxes drawn."""

from trap_core.outputs.pictures import Thumbnails, contact_sheet, draw_tracks, sheet_frames, track_colour
from trap_core.outputs.track_files import write_tracks_mot

__all__ = ["Thumbnails", "contact_sheet", "draw_tracks", "sheet_frames", "track_colour", "write_tracks_mot"]
