"""Boxes that leave a track's path for a few frames (ours).

Where look-alikes meet, a cluster's patterns can hold blends of both objects for a few frames,
and its box is then the pair's; :func:`trap_core.robust.separate_groups` gives such a box the
track's usual size, but where the patterns sit mostly on the other object, so the track's box
slides onto that object and back. A box can also come from a pattern path linked, for a frame
or two, to the same structure on something else. Either way the track seems to turn twice where
the object went straight on, and the rules that compare tracks' motions (the trade of
continuations at crossings, who loses a shared stretch) read the wrong track as the one that
turns. :func:`drop_strays` removes such boxes; :func:`trap_core.robust.fill_gaps` then puts
the track's path through those frames.

Where a rule cuts a stretch on another object out of a track, it can leave a few frames on their
own: where the track was still parting from the other object's path, or a box a twin cluster
lent far from the rest. :func:`drop_stray_pieces` removes such pieces; kept, they make the track
seem to end (or start) there, and the rules that join a track to its continuation look for it
at the wrong frame.
"""
from __future__ import annotations

import numpy as np

from trap_core.clustering import Track, centre_path, in_rows, track_pieces, usual_size
from trap_core.robust._kernels import stray_rows


def drop_strays(track: Track, window: int, reach: float = 0.5) -> Track:
    """The track without the boxes that stray from its path.

    Parameters
    ----------
    track : Track
    window : int
        Frames on either side of a box through which the track's path there is drawn: the
        Theil-Sen line (:func:`trap_core.robust.motion.straight_line`) through the other box
        centres of those frames, so that a few stray boxes among them do not pull it (one
        compiled pass over the track, :func:`trap_core.robust._kernels.stray_rows`).
    reach : float
        A box whose centre lies farther from that line than this share of the track's usual
        size (median of the larger box side) strays: at half the size, the box covers less
        than about half of the object it should hold.

    Returns
    -------
    Track
    """
    if len(track) < 3:
        return track
    frames = track.frames
    centres = centre_path(track, int(frames[-1]) + 1)
    stray = stray_rows(np.ascontiguousarray(centres, dtype=np.float64), frames.astype(np.int64), window,
                       reach * usual_size(track))
    return in_rows(track, ~stray)


def drop_stray_pieces(track: Track, n_frames: int, min_gap: int, min_frames: int) -> Track:
    """The track without its short pieces apart from the rest.

    Parameters
    ----------
    track : Track
    n_frames : int
        Frames of the video.
    min_gap : int
        A piece is a run of the track's frames without a gap of more than this many frames
        (:func:`trap_core.clustering.track_pieces`). At the video's first or last frame, a
        piece that spans fewer frames goes: too few to read a motion from, where the video may
        have cut short the object's time in view.
    min_frames : int
        Elsewhere, a piece that spans fewer frames goes: the rules take an object's stretch on
        another's path, and a track's own stretch, to last at least this long (tau).

    Returns
    -------
    Track
        Unchanged where it has one piece: a short track is for the rules on whole tracks.
    """
    pieces = track_pieces(track.frames, min_gap)
    if len(pieces) < 2:
        return track
    keep = np.ones(len(track), dtype=bool)
    for rows in pieces:
        first, last = int(track.frames[rows[0]]), int(track.frames[rows[-1]])
        at_edge = first == 0 or last == n_frames - 1
        keep[rows] = last - first + 1 >= (min_gap if at_edge else min_frames)
    return in_rows(track, keep)
