"""Results as files and pictures: MOTChallenge tracks, contact sheets with boxes drawn, a timeline
of the tracks."""

from trap_core.outputs.pictures import Thumbnails, contact_sheet, draw_tracks, sheet_frames, track_colour
from trap_core.outputs.timeline import track_timeline
from trap_core.outputs.track_files import write_tracks_mot

__all__ = ["Thumbnails", "contact_sheet", "draw_tracks", "sheet_frames", "track_colour", "track_timeline",
           "write_tracks_mot"]
