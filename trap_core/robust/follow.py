"""Tracks followed past their ends and into their gaps by their object's regions (ours).

A track has boxes where its cluster's patterns are seen, and an object can stay in view long
before its first pattern or after its last: a structure is frequent only over ``freq_st_min``
frames, an object that goes with the camera's pan moves under ``min_speed`` in the world and its
patterns are background, and where two objects meet the patterns of both can stop. The
segmentation still holds the object there: in the frames a track misses before its first box or
after its last, the regions inside the object's box cover it as much as in the frames it holds
(README, where the objects under 90/90 lose). So the regions wholly inside a track's first box
(its object's parts) are looked for in the frame before, each where the box's motion puts it, of
about its area and colour (as the label memory finds a region again), and the box moves by the
displacement most of the parts' area agrees on; then in the frame before that, and so on; the
same forward from the last box. Parts not found keep their place in the box: one that noise
split for a frame is found again in the next. A gap longer than ``fill_gaps`` bridges (the
object hidden for a while, or its patterns lost) is followed into from both sides the same way:
forward from the box before it, then back from the box after it, up to what the first reached.

Following stops where less than half of the parts' area agrees on a displacement (the object is
hidden, or turned into other regions), where the box reaches the border (the object leaves:
:func:`~trap_core.robust.continue_to_border` boxes it while it is partly in view) and where the
box meets another track's (who is who where objects meet is for the patterns to say). A box
whose regions cover less than ``MIN_COVER`` of it (a body merged into the ground) has nothing
to follow, and one more than ``USUAL_RATIO`` off the track's usual width or height holds a part
of the object, or the object and a neighbour (two discs that met, boxed 81x100 for 51x51 and
followed into a gap, lay on neither in 45 of 48 frames).
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from trap_core.clustering import Track, box_iou, centre_path, reaches_border, regions_in_box, usual_box
from trap_core.rag import StackedGraphs
from trap_core.rag.label_memory import AREA_RATIO
from trap_core.robust.gaps import with_inferred
from trap_core.robust.motion import straight_line

MIN_COVER = 0.3  # share of the end box its parts must cover
MIN_AGREE = 0.5  # share of the parts' area that must agree on the displacement, frame after frame
COLOUR_REACH = 24.0  # RGB distance between a part's mean colour and the region that continues it
MEETING_IOU = 0.3  # a box that overlaps another track's this much is where objects meet
USUAL_RATIO = 1.25  # a box more than this off the track's usual size holds a part, or its object and more


def follow_ends(tracks: Sequence[Track], regions: StackedGraphs, width: float, height: float,
                span: int) -> list[Track]:
    """The tracks, each followed back from its first box, on from its last and into its gaps by
    its object's regions, for as long as they are found together.

    Parameters
    ----------
    tracks : sequence of Track
    regions : StackedGraphs
        The plane graphs of every frame of the video, stacked.
    width, height : float
        Frame size: a box that reaches its border is not followed further.
    span : int
        Frames at a track's end (a gap's side) whose box centres give its motion there (a
        straight line), the first prediction of where its parts go.

    Returns
    -------
    list of Track
        The boxes added are inferred (:func:`~trap_core.robust.gaps.with_inferred`). Tracks are
        followed in turn, each against the others as followed so far, so two never follow into
        one object.
    """
    out = list(tracks)
    for k in range(len(out)):
        others = out[:k] + out[k + 1:]
        track = _followed(out[k], 0, -1, -1, regions, others, width, height, span)
        track = _followed(track, len(track) - 1, 1, len(regions), regions, others, width, height, span)
        gaps = np.flatnonzero(np.diff(track.frames) > 1)
        for left, right in zip(track.frames[gaps].tolist(), track.frames[gaps + 1].tolist()):
            row = int(np.searchsorted(track.frames, left))
            track = _followed(track, row, 1, right, regions, others, width, height, span)
            row = int(np.searchsorted(track.frames, right))
            track = _followed(track, row, -1, int(track.frames[row - 1]), regions, others, width, height, span)
        out[k] = track
    return out


def _followed(track: Track, row: int, direction: int, until: int, regions: StackedGraphs, others: list[Track],
              width: float, height: float, span: int) -> Track:
    """``track`` followed from its box in ``row`` back in time (``direction`` -1) or on (1), up
    to the frame ``until`` (not included)."""
    box = track.boxes[row].astype(float)
    usual = usual_box(track)
    if reaches_border(box[None], width, height)[0] or not (np.all(box[2:] <= USUAL_RATIO * usual)
                                                            and np.all(usual <= USUAL_RATIO * box[2:])):
        return track
    seen = track.frames[row:row + span] if direction < 0 else track.frames[max(0, row + 1 - span):row + 1]
    line = straight_line(centre_path(track, int(track.frames[-1]) + 1), seen)
    parts = _parts(regions, int(track.frames[row]), box)
    if line is None or parts is None:
        return track
    offsets, areas, colours = parts
    least = MIN_AGREE * areas.sum()
    step = direction * np.asarray(line[0], dtype=float)
    tolerance = max(2.0, 0.05 * np.sqrt(box[2] * box[3]))  # px: parts of one object move as one, within
    frames, boxes = [], []
    frame = int(track.frames[row]) + direction
    while frame != until:
        predicted = box[:2] + step
        moved = _agreed_shift(regions, frame, predicted + offsets, areas, colours, 2.0 + np.hypot(*step), tolerance,
                              least)
        if moved is None:
            break
        shift, parts_found, found = moved
        new = np.r_[predicted + shift, box[2:]]
        if reaches_border(new[None], width, height)[0] or _meets(new, frame, others):
            break
        lo = regions.node_offsets[frame]
        areas[parts_found] = regions.area[lo + found]
        colours[parts_found] = regions.colour[lo + found]
        step = 0.7 * step + 0.3 * (new[:2] - box[:2])  # the motion read so far, smoothed over a few frames
        box = new
        frames.append(frame)
        boxes.append(new)
        frame += direction
    return with_inferred(track, np.array(frames), np.array(boxes).reshape(-1, 4)) if frames else track


def _parts(regions: StackedGraphs, frame: int, box: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """(offsets from the box's corner, areas, mean colours) of the regions of ``frame`` wholly
    inside ``box`` (1 px of slack) but the backdrop; None where they cover under ``MIN_COVER``."""
    lo, hi = regions.node_offsets[frame], regions.node_offsets[frame + 1]
    inside = regions_in_box(regions.bbox[lo:hi], box, slack=1.0) & ~regions.backdrop[lo:hi]
    areas = regions.area[lo:hi][inside].astype(float)
    if areas.sum() < MIN_COVER * box[2] * box[3]:
        return None
    return (regions.centroid[lo:hi][inside].astype(float) - box[:2], areas,
            regions.colour[lo:hi][inside].astype(float))


def _agreed_shift(regions: StackedGraphs, frame: int, expected: np.ndarray, areas: np.ndarray, colours: np.ndarray,
                  slack: float, tolerance: float, least: float) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """Where the parts are in ``frame``: (shift of the box from its prediction, parts found,
    their regions, numbered within the frame), or None where less than ``least`` of their area
    agrees.

    Each part's candidates are the regions of about its area and colour within ``slack`` plus
    0.3 of the square root of its area of where it is ``expected``; each candidate's offset from
    there is a vote, and the one that most of the parts' area agrees with (within
    ``tolerance``, a part counted once) wins; the shift is the area-weighted mean of the offsets
    that agree with it.
    """
    lo, hi = regions.node_offsets[frame], regions.node_offsets[frame + 1]
    centroid, area = regions.centroid[lo:hi].astype(float), regions.area[lo:hi].astype(float)
    colour = regions.colour[lo:hi].astype(float)
    reach = slack + 0.3 * np.sqrt(areas)
    near = ((np.linalg.norm(centroid[None] - expected[:, None], axis=2) <= reach[:, None])
            & (area[None] <= AREA_RATIO * areas[:, None]) & (AREA_RATIO * area[None] >= areas[:, None])
            & (np.linalg.norm(colour[None] - colours[:, None], axis=2) <= COLOUR_REACH))
    part, region = np.nonzero(near)
    if not part.size:
        return None
    offsets = centroid[region] - expected[part]
    agree = np.linalg.norm(offsets[:, None] - offsets[None], axis=2) <= tolerance
    parts_agreeing = (agree.astype(float) @ (part[:, None] == np.arange(areas.size))) > 0  # (votes, parts)
    support = parts_agreeing @ areas
    best = int(np.argmax(support))
    if support[best] < least:
        return None
    kept = agree[best]
    return np.average(offsets[kept], axis=0, weights=areas[part[kept]]), part[kept], region[kept]


def _meets(box: np.ndarray, frame: int, others: list[Track]) -> bool:
    """Whether ``box`` overlaps another track's box in ``frame`` by ``MEETING_IOU`` or more."""
    for other in others:
        row = int(np.searchsorted(other.frames, frame))
        if row < len(other) and other.frames[row] == frame and box_iou(box, other.boxes[row]) >= MEETING_IOU:
            return True
    return False
