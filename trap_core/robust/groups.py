"""Track boxes where objects meet: merged boxes split, occluded objects followed (ours).

Where two look-alike objects touch or overlap, their same-coloured regions become one region
and every pattern on either spans both, so both tracks get the box of the pair (a *group*);
where one object passes behind another, its patterns vanish and its track ends inside the
other's box. Blob trackers meet the same merges and splits; here they are solved with what the
tracks themselves know:

* **usual size**: a track's running median width and height over the frames where it is clear
  (its box overlaps no other track's) and its patterns are seen (a box inferred in a gap is
  drawn from the boxes beside it, and a long gap would count them over and over; if there are
  no such frames, where it is clear, else where it is in no group), the ``window``
  nearest such frames on each side within the piece of the track (no gap over ``min_gap``): a
  merge of any length, broken now and then by a few half-merged frames, does not move it, nor
  does another piece (after an exit, a zoom);
* **place**: in a group, each object's box has its usual size, inside the group box (which does
  hold both objects), centred where its own patterns are (their mean position, less its usual
  offset from the box centre when alone). An object without patterns there (hidden) takes the
  side of the group box away from its partner's, or, if neither has patterns, the side of the
  pair it was on when last seen apart (left or right, above or below), interpolated towards the
  side it is on when next seen apart;
* **occluded**: a track that ends (or pauses) inside the view while in a group continues in the
  group box: through the whole pause when it comes back out of that same box, otherwise while the
  box stays over 10 % larger than its other member was before the group formed (so it still holds
  two objects; dips shorter than ``patience`` frames do not end it), and not at all where it is
  that large in under three quarters of those frames (a box that is large one frame and not the
  next is its member's own, changing between a part of its object and the whole). Such frames get
  half the track's lowest observed confidence;
* **oversized** boxes outside groups (``factor`` times the usual size) get the usual size,
  centred where the neighbouring normal frames put the object, inside the observed box;
  **undersized** ones (``factor`` times smaller: a part of the object) likewise, around the
  observed box, unless the view may cut the object (within its usual size of the border);
* **whole**: where a piece's oversized boxes are many and of one size, they are the object's
  whole box and its usual size, and its part boxes grow to it (:func:`_whole_sizes`).
"""
from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Sequence

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from trap_core.clustering import Track, box_centres, box_containment, reaches_border, track_pieces

GROUPED = 0.5  # share of the smaller box inside the other: the two boxes hold the same regions
HOLDS_MORE = 1.1  # a box this much wider or taller than its usual size holds more than its object
HOLDS_STEADILY = 0.75  # share of a followed stretch's frames in which the group box must hold more
# A piece whose boxes are oversized in at least WHOLE_SHARE of its usual-size frames, nearly all
# (ONE_SIZE_SHARE) within ONE_SIZE of the running median of those boxes, holds its whole object there.
WHOLE_SHARE = 0.25
ONE_SIZE = 0.1
ONE_SIZE_SHARE = 0.75


def separate_groups(tracks: Sequence[Track], n_frames: int, width: float, height: float, factor: float = 1.5,
                    window: int = 100, border: float = 0.25, groups: bool = True,
                    patience: int = 25, min_gap: int = 25) -> list[Track]:
    """Tracks with merged boxes split, odd-sized boxes given the usual size and occluded objects followed.

    Parameters
    ----------
    tracks : sequence of Track
        Boxes ``(x, y, w, h)`` as built from the regions of each track's patterns.
    n_frames, width, height :
        Video length and frame size.
    factor : float
        Outside groups, a box wider or taller than ``factor`` times the usual size is oversized,
        one ``factor`` times narrower or shorter undersized; 0 = leave boxes outside groups alone.
    window : int
        Clear frames on each side of the running median of the usual size.
    border : float
        A track whose last box is within this share of its size from the image border left the
        view: it is not followed as occluded.
    groups : bool
        Split group boxes and follow occluded tracks; False: every track is taken as alone.
    patience : int
        Frames the group box may look like one object (a hidden object, the pair aligned) before
        an occluded track that did not come back ends.
    min_gap : int
        A gap of more than this many frames starts a new piece of a track, with a usual size of
        its own.

    Returns
    -------
    list of Track
    """
    if not tracks:
        return []
    boxes = np.full((len(tracks), n_frames, 4), np.nan)
    points = np.full((len(tracks), n_frames, 2), np.nan)
    for slot, t in enumerate(tracks):
        boxes[slot, t.frames] = t.boxes
        if t.points is not None:
            points[slot, t.frames] = t.points
    shared = _shares(boxes)
    partner = _partners(shared) if groups else np.full(boxes.shape[:2], -1)
    inferred = np.zeros(boxes.shape[:2], dtype=bool)
    if groups:
        inferred = _follow_occluded(boxes, partner, width, height, border, window, patience)
        if inferred.any():
            shared = _shares(boxes)
            partner = _partners(shared)
    alone = partner < 0
    clear = ~np.isnan(boxes[..., 0]) & ~np.any(shared > 0, axis=1)  # its box overlaps no other track's
    seen = ~np.isnan(points[..., 0])  # the track's patterns are there: its box was measured, not filled
    preferred = (clear & seen, clear, alone)  # the frames that show most of the object's own size
    usual = _running_median(boxes[..., 2:4], preferred, window, min_gap)
    offsets = points - box_centres(boxes)
    whole_centres = np.full(points.shape, np.nan)
    if factor > 0:
        usual, whole_centres = _whole_sizes(usual, boxes, points, offsets, preferred, factor, window, min_gap)
    offset = _running_median(offsets, preferred, window, min_gap)
    centres = points - offset
    placed = boxes.copy()
    for slot in range(len(tracks)):
        _split(placed, boxes, usual, centres, partner, shared, slot)
        if factor > 0:
            _shrink_oversized(placed[slot], usual[slot], alone[slot], factor)
            _grow_undersized(placed[slot], usual[slot], alone[slot], factor, width, height, whole_centres[slot])
    out = []
    for slot, t in enumerate(tracks):
        frames = np.flatnonzero(~np.isnan(placed[slot, :, 0]))
        score = np.full(n_frames, np.nan)
        score[t.frames] = t.score
        score[inferred[slot]] = 0.5 * float(t.score.min())
        out.append(dataclasses.replace(t, frames=frames, boxes=placed[slot, frames], score=score[frames],
                                       points=points[slot, frames]))
    return out


def _shares(boxes: np.ndarray) -> np.ndarray:
    """(T, T, F): per frame, the share of the smaller of two tracks' boxes that lies in the other
    (0 on the diagonal and where a box is absent)."""
    n_tracks = boxes.shape[0]
    shared = np.zeros((n_tracks, n_tracks, boxes.shape[1]))
    for a in range(n_tracks):
        for b in range(a + 1, n_tracks):
            shared[a, b] = shared[b, a] = box_containment(boxes[a], boxes[b])
    return shared


def _partners(shared: np.ndarray) -> np.ndarray:
    """(T, F): the track each track's box is grouped with in each frame (most overlap, the first
    of equals), -1 if none; ``shared`` as :func:`_shares` gives it."""
    best = shared.argmax(axis=1)
    grouped = np.take_along_axis(shared, best[:, None], axis=1)[:, 0] > GROUPED
    return np.where(grouped, best, -1)


def _running_median(values: np.ndarray, preferred: Sequence[np.ndarray], window: int, min_gap: int) -> np.ndarray:
    """(T, F, k): per track and piece (a run of its frames without a gap of more than
    ``min_gap``), the running median of ``values`` (T, F, k; NaN where unknown) over the
    ``window`` nearest frames on each side that the first of the (T, F) masks ``preferred``
    holding any of the piece's frames marks (all the piece's frames if none does),
    interpolated between them; NaN outside the pieces."""
    out = np.full(values.shape, np.nan)
    for slot in range(values.shape[0]):
        for piece, frames in _preferred_pieces(~np.isnan(values[slot]).any(axis=1), preferred, slot, min_gap):
            medians = _window_medians(values[slot, frames], window)
            span = np.arange(piece[0], piece[-1] + 1)
            for axis in range(values.shape[2]):
                out[slot, span, axis] = np.interp(span, frames, medians[:, axis])
    return out


def _preferred_pieces(known: np.ndarray, preferred: Sequence[np.ndarray], slot: int, min_gap: int
                      ) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """Per piece of track ``slot`` (a run of its ``known`` frames, a (F,) mask, without a gap of
    more than ``min_gap``): its frames, and those the first of the (T, F) masks ``preferred``
    that holds any of them marks (all of them if none does)."""
    present = np.flatnonzero(known)
    for rows in track_pieces(present, min_gap):
        piece = present[rows]
        if piece.size:
            yield piece, next((piece[mask[slot, piece]] for mask in preferred if mask[slot, piece].any()), piece)


def _whole_sizes(usual: np.ndarray, boxes: np.ndarray, points: np.ndarray, offsets: np.ndarray,
                 preferred: Sequence[np.ndarray], factor: float, window: int, min_gap: int
                 ) -> tuple[np.ndarray, np.ndarray]:
    """``usual`` (T, F, 2) where a piece's larger boxes are its object's size, and the centres of
    the object's whole box ((T, F, 2), NaN elsewhere); ``offsets``: the patterns' mean
    ``points`` less their box's centre, per frame.

    Where the segmentation merges an object's body with the ground around it in some frames, its
    track holds only its inner parts there, and where the body is a region of its own the box
    takes it in (:func:`trap_core.robust.grow_boxes`). The running median then follows whichever
    is more frequent, and the whole boxes, when fewer, read as oversized and are cut down to a
    part. A piece (as :func:`_running_median` reads it) whose preferred frames have boxes
    ``factor`` times their usual size in at least ``WHOLE_SHARE`` of them, those of one size
    (``ONE_SIZE_SHARE`` within ``ONE_SIZE`` of their own running median: a group of two objects,
    or a box grown over the ground, changes size as they move), takes their size as usual. Its
    part boxes then grow to it (:func:`_grow_undersized`), centred where its patterns' mean
    position less their usual offset from the whole box's centre puts the object: a part is off
    the object's centre, and the neighbouring whole boxes can be far.
    """
    out = usual.copy()
    whole_centres = np.full(points.shape, np.nan)
    for slot in range(boxes.shape[0]):
        for piece, frames in _preferred_pieces(~np.isnan(boxes[slot, :, 0]), preferred, slot, min_gap):
            sizes = boxes[slot, frames, 2:4]
            whole = frames[np.any(sizes > factor * usual[slot, frames], axis=1)]
            if whole.size < max(WHOLE_SHARE * frames.size, 3):
                continue
            medians = _window_medians(boxes[slot, whole, 2:4], window)
            if np.mean(np.all(np.abs(boxes[slot, whole, 2:4] / medians - 1) <= ONE_SIZE, axis=1)) < ONE_SIZE_SHARE:
                continue
            span = np.arange(piece[0], piece[-1] + 1)
            measured = whole[~np.isnan(offsets[slot, whole, 0])]
            offset = _window_medians(offsets[slot, measured], window) if measured.size else None
            for axis in (0, 1):
                out[slot, span, axis] = np.interp(span, whole, medians[:, axis])
                if offset is not None:
                    shift = np.interp(span, measured, offset[:, axis])
                    whole_centres[slot, span, axis] = points[slot, span, axis] - shift
    return out, whole_centres


def _window_medians(samples: np.ndarray, window: int) -> np.ndarray:
    """(n, k) per row of ``samples`` (n, k, finite), the median of the rows at most ``window``
    away, per column: all windows at once, those the ends cut short as prefixes and suffixes."""
    n = len(samples)
    medians = np.empty(samples.shape)
    if n > 2 * window:
        medians[window:n - window] = np.median(sliding_window_view(samples, 2 * window + 1, axis=0), axis=-1)
    head = np.arange(min(window, n))  # rows whose window starts at the first row
    medians[head] = _prefix_medians(samples, np.minimum(head + window + 1, n))
    tail = np.arange(max(n - window, window), n)  # rows whose window ends at the last row
    medians[tail] = _prefix_medians(samples[::-1], n - np.maximum(tail - window, 0))
    return medians


def _prefix_medians(samples: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """(len(sizes), k): per size m, the median of ``samples[:m]`` (finite) per column, as
    :func:`np.median` gives it (the mean of the two middle values where m is even)."""
    if sizes.size == 0:
        return np.empty((0, samples.shape[1]))
    rows = np.arange(sizes.max())
    padded = np.where(rows[None, :, None] < sizes[:, None, None], samples[None, :rows.size], np.inf)
    ordered = np.sort(padded, axis=1)
    pick = np.arange(sizes.size)
    return (ordered[pick, (sizes - 1) // 2] + ordered[pick, sizes // 2]) / 2


def _follow_occluded(boxes: np.ndarray, partner: np.ndarray, width: float, height: float, border: float,
                     window: int, patience: int) -> np.ndarray:
    """Give tracks that vanish inside a group box that box while it still holds them (in place);
    returns the (T, F) frames so filled. Whether the box holds more than its other member is
    judged against that member's median size when alone in the ``window`` frames before the
    group formed (the frames after may all be merged); a box that holds more in fewer than
    ``HOLDS_STEADILY`` of the frames it would fill flickers between its member's part and whole
    and is no evidence of a hidden object."""
    n_tracks, n_frames = boxes.shape[:2]
    inferred = np.zeros((n_tracks, n_frames), dtype=bool)
    observed = ~np.isnan(boxes[..., 0])
    for slot in range(n_tracks):
        present = np.flatnonzero(observed[slot])
        if present.size == 0:
            continue
        ends = present[np.flatnonzero(np.diff(np.append(present, n_frames)) > 1)]
        for last in ends:
            other = partner[slot, last]
            if other < 0 or reaches_border(boxes[slot, last][None], width, height, border)[0]:
                continue
            formed = last - _lasting(partner[slot, last::-1] == other, 1)
            before = np.arange(max(formed - window, 0), formed + 1)
            before = before[observed[other, before] & (partner[other, before] < 0)]
            if before.size == 0:
                continue
            alone_size = np.median(boxes[other, before, 2:4], axis=0)
            later = present[present > last]
            back = int(later[0]) if later.size else n_frames
            gap = np.arange(last + 1, back)
            with_other = observed[other, gap]
            if back < n_frames and partner[slot, back] == other and with_other.all():
                fill = gap  # came back out of the same box: it was there all along
            else:
                big = np.any(boxes[other, gap, 2:4] > HOLDS_MORE * alone_size, axis=1) & with_other
                held = _lasting(big, patience)
                fill = gap[:held] if held and np.mean(big[:held]) >= HOLDS_STEADILY else gap[:0]
            boxes[slot, fill] = boxes[other, fill]
            inferred[slot, fill] = True
    return inferred


def _lasting(flags: np.ndarray, patience: int) -> int:
    """Length of the leading stretch of ``flags`` that no run of ``patience`` or more False
    (or a False run reaching the end) interrupts, without its trailing False."""
    false_runs = np.flatnonzero(np.diff(np.concatenate([[1], flags.astype(np.int8), [1]])))
    for start, stop in zip(false_runs[::2], false_runs[1::2]):
        if stop - start >= patience or stop == flags.size:
            return int(start)
    return int(flags.size)


def _split(placed: np.ndarray, boxes: np.ndarray, usual: np.ndarray, centres: np.ndarray, partner: np.ndarray,
           shared: np.ndarray, slot: int) -> None:
    """In the frames where track ``slot`` is grouped, its usual-size box inside the group box:
    at the centre its patterns give, else away from its partner's, else at its side of the pair
    when seen apart (in place). ``centres``: (T, F, 2) object centres from the patterns, NaN
    where a track has none; ``shared`` as :func:`_shares` gives it."""
    for other in np.unique(partner[slot][partner[slot] >= 0]):
        grouped = np.flatnonzero(partner[slot] == other)
        box = boxes[slot, grouped]
        apart = np.flatnonzero(~np.isnan(boxes[slot, :, 0]) & ~np.isnan(boxes[other, :, 0])
                               & (shared[slot, other] <= GROUPED))
        for axis in (0, 1):
            size = np.minimum(usual[slot, grouped, axis], box[:, 2 + axis])
            room = box[:, 2 + axis] - size
            if apart.size:
                mine = boxes[slot, apart, axis] + boxes[slot, apart, 2 + axis] / 2
                theirs = boxes[other, apart, axis] + boxes[other, apart, 2 + axis] / 2
                side = np.interp(grouped, apart, (np.sign(mine - theirs) + 1) / 2)
            else:
                side = np.full(grouped.size, 0.5)
            middle = box[:, axis] + box[:, 2 + axis] / 2
            theirs = centres[other, grouped, axis]
            away = ~np.isnan(theirs)
            side[away] = (np.sign(middle[away] - theirs[away]) + 1) / 2
            start = box[:, axis] + side * room
            mine = centres[slot, grouped, axis]
            own = ~np.isnan(mine)
            start[own] = np.clip(mine[own] - size[own] / 2, box[own, axis], box[own, axis] + room[own])
            placed[slot, grouped, axis] = start
            placed[slot, grouped, 2 + axis] = size


def _shrink_oversized(placed: np.ndarray, usual: np.ndarray, alone: np.ndarray, factor: float) -> None:
    """Outside groups, boxes ``factor`` times their usual size get that size, centred on the path
    of the normal frames around them and kept inside the observed box (in place)."""
    present = ~np.isnan(placed[:, 0])
    _to_usual_size(placed, usual, present & alone & np.any(placed[:, 2:4] > factor * usual, axis=1), inside=True)


def _grow_undersized(placed: np.ndarray, usual: np.ndarray, alone: np.ndarray, factor: float, width: float,
                     height: float, centres: np.ndarray | None = None) -> None:
    """Outside groups, boxes ``factor`` times smaller than their usual size (a part of the
    object: a thin strip of region along its edge, one of its parts) get that size, centred on
    the path of the normal frames around them, or on ``centres`` where given (not NaN), and
    holding the observed box (in place). Boxes within their usual size of the image border are
    left alone: the view may cut the object."""
    x, y, w, h = placed.T
    cut = ((x < usual[:, 0]) | (y < usual[:, 1]) | (x + w > width - usual[:, 0])
           | (y + h > height - usual[:, 1]))
    present = ~np.isnan(x)
    _to_usual_size(placed, usual, present & alone & ~cut & np.any(placed[:, 2:4] * factor < usual, axis=1),
                   inside=False, centres=centres)


def _to_usual_size(placed: np.ndarray, usual: np.ndarray, odd_frames: np.ndarray, inside: bool,
                   centres: np.ndarray | None = None) -> None:
    """Boxes of ``odd_frames`` at their usual size, centred on the path of the other frames (or
    on ``centres`` where given and not NaN) and kept inside the observed box (``inside``) or
    around it (in place)."""
    present = ~np.isnan(placed[:, 0])
    normal = np.flatnonzero(present & ~odd_frames)
    odd = np.flatnonzero(odd_frames)
    if odd.size == 0 or normal.size == 0:
        return
    for axis in (0, 1):
        centre = placed[normal, axis] + placed[normal, 2 + axis] / 2
        guess = np.interp(odd, normal, centre)
        if centres is not None:
            guess = np.where(np.isnan(centres[odd, axis]), guess, centres[odd, axis])
        size = usual[odd, axis]
        start = placed[odd, axis]
        stop = start + placed[odd, 2 + axis] - size
        low, high = (start, stop) if inside else (np.minimum(stop, start), np.maximum(stop, start))
        placed[odd, axis] = np.clip(guess - size / 2, low, high)
        placed[odd, 2 + axis] = size
