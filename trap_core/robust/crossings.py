"""Where look-alikes meet, two tracks can trade objects (ours).

When two look-alike objects overlap, their patterns' occurrences are blends of both, and the
paths of :func:`trap_core.mining` can leave the meeting each on the other object. Both tracks
then hold one object before and the other after: no stretch is repeated (that is
:func:`trap_core.robust.drop_shared_stretches`' case), each track just turns and jumps where
the objects meet. :func:`swap_at_crossings` gives each track the other's continuation where
that makes both motions go on as they were going (and, where three crowd and leave it as a
cycle, turns their continuations a step around). Only look-alikes trade
(:func:`lookalike_tracks`: the same structures, or boxes of one size): where the objects differ,
their patterns already told them apart, and two objects that meet and both turn back keep their
tracks.
"""
from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np

from trap_core.clustering import Track, box_centres, box_iou, box_path, in_rows, usual_box, usual_size, with_frames
from trap_core.robust._kernels import window_lines
from trap_core.robust.duplicates import TURN, flag_runs
from trap_core.robust.motion import straight_line
from trap_core.robust.rejoin import structure_similarity


# Two tracks' clusters share at least this share of structures where their objects look alike.
# Different objects share next to none (at most 0.07 over every quality.py video); look-alikes
# share less than the rejoin test asks for where their clusters also hold structures of the
# different backgrounds around them (photographs: 0.13-0.27).
LOOKALIKE_SIMILARITY = 0.1
# Boxes whose median width and height differ by at most this share are of one size.
SAME_SIZE = 0.1
# Tracks of one size hold look-alikes only if their colours overlap by this much
# (:func:`trap_core.robust.appearance.colour_overlap`). Over every quality.py video, tracks of
# one size whose clusters share no structure overlapped by 0.94-0.99 on look-alikes, and by at
# most 0.53 (mostly under 0.05) on objects of different colours.
SAME_COLOURS = 0.7
# Two tracks' boxes that overlap by at least this much somewhere in a meeting may hold a blend of
# both objects: a track's box can glide from one onto the other there. At 0.5 (the same object
# by the usual IoU test), look-alike people that crossed over brick with boxes overlapping by
# 0.43 at most kept their trade (quality.py photos); with no bound, people on a road whose boxes
# passed each other at 0.20 and who both turned there were exchanged (quality.py random).
BLEND_IOU = 0.3
# Boxes that overlap by at least this much hold one object (the test the track rules use throughout).
SAME_OBJECT_IOU = 0.5
# Two straight lines join where, at a meeting's middle frame, they are at most this share of the
# smaller usual size apart. Over 987 meetings of look-alike tracks in quality.py (read before any
# exchange, labelled by the ground truth), lines on either side of a meeting joined for the
# exchanged pairing and not for the tracks' own in four meetings: three where the tracks had traded
# objects (two of them exchanged at a cut already) and one that overlaps a trade's meeting (taken,
# it put that trade right); the same at any share from 0.15 to 0.25. At 0.5, one that the tracks
# had left each on its own object passed too.
JOINED = 0.25


def lookalike_tracks(tracks: Sequence[Track], labels: np.ndarray, st_pattern: np.ndarray, weights: np.ndarray,
                     min_similarity: float = LOOKALIKE_SIMILARITY, colours: np.ndarray | None = None) -> np.ndarray:
    """(T, T) whether two tracks may hold look-alike objects: their clusters are made of the
    same structures (the :func:`trap_core.robust.rejoin.structure_similarity` of the patterns
    with cluster ``labels`` (-1: none), plane pattern ``st_pattern`` and ``weights``
    (occurrences) is at least ``min_similarity``), or their boxes are of one size (median width
    and height within ``SAME_SIZE``) and, given their ``colours`` (T, T) overlap
    (:func:`trap_core.robust.appearance.colour_overlap`), they are of the same colours (at least
    ``SAME_COLOURS``). Over a textured background the segmentation can merge each look-alike
    with its own surroundings, so that their clusters share no structure at all; their boxes
    and colours still match. Objects of one size and different colours are not look-alikes (a
    6000-frame video of three such objects: two that met and both turned back traded tracks,
    IDF1 0.69)."""
    clusters = np.unique([t.cluster for t in tracks])
    member = np.flatnonzero(np.isin(labels, clusters))
    similarity = structure_similarity(np.searchsorted(clusters, labels[member]), st_pattern[member], weights[member])
    slot = np.searchsorted(clusters, [t.cluster for t in tracks])
    sizes = np.array([usual_box(t) for t in tracks]).reshape(-1, 2)
    larger = np.maximum(sizes[:, None], sizes[None])
    one_size = np.all(np.abs(sizes[:, None] - sizes[None]) <= SAME_SIZE * larger, axis=2)
    if colours is not None:
        one_size &= colours >= SAME_COLOURS
    return (similarity[np.ix_(slot, slot)] >= min_similarity) | one_size


def swap_at_crossings(tracks: Sequence[Track], n_frames: int, window: int, alike: np.ndarray,
                      min_iou: float = BLEND_IOU) -> list[Track]:
    """Tracks with their continuations exchanged where two of them meet and trade objects.

    Two tracks meet while their box centres are closer than the smaller of their usual sizes
    (the larger side's median). At each frame ``k`` of a meeting, a pairing of what comes before
    ``k`` with what comes after is scored by how much it breaks each track's motion: the change
    of velocity between straight lines fitted (robustly) to the centres over ``window`` frames
    before and after, plus the gap between the two lines at the cut divided by ``window`` (a
    jump spread over the window), summed over both tracks. The continuations are exchanged at
    the frame where that helps most, if there the tracks' own pairing breaks their motion by
    more than ``TURN`` times the smaller size per frame (a turn, not jitter) and the exchanged
    pairing does not, by at most half as much (both go on as they were going). Where no frame
    passes and somewhere in the meeting the boxes overlap by at least ``min_iou``, the lines
    after may start up to ``window`` frames later, past a blend of both objects
    (:func:`_best_cut`); where still none passes, the same test on the lines before and after
    the whole meeting exchanges them at its middle frame (:func:`_across_meeting`), if there each
    track's line before and the other's line after are at most the smaller size apart: the trade
    needs no jump, each track's box glided from one object onto the other while they overlapped
    (look-alikes that pass each other and both turn there are a jump apart). Where the
    lines at the cut lie inside the meeting, they may be on boxes of two objects that travel
    together: the cut is not taken where the lines before and after the whole meeting break
    less with the tracks' own pairing. Where both tracks hold one object on either side of the
    cut (:func:`_one_object_either_side`), its lines tell nothing (both pairings read that
    object's motion, and which breaks it less is the jitter of two boxes on it: a track that went
    onto another's object as its own left the view traded the rest of both tracks there), and
    the lines either side of the whole meeting decide as where no frame passes. Only tracks
    ``alike[a, b]`` (:func:`lookalike_tracks`) trade. The lines either side of the whole meeting
    exchange the tracks only if somewhere in it their boxes overlap by at least ``min_iou`` (may
    hold the same object): boxes that stay apart each kept their own object, and a trade between
    them would be a jump that the test at each frame looks for. Two equal boxes overlap by
    ``BLEND_IOU`` when their centres are about half a box apart. Or else only if the objects
    passed through each other while each track stalled on its own side of their blend (its boxes
    apart from the other's throughout): at the meeting's middle frame each track's line before
    joins the other's line after and not its own (within ``JOINED`` times the smaller size), and
    the exchanged pairing breaks the motions less. Where the lines join either way (head on, or
    one turning just where they meet), the motions cannot tell a crossing from two objects that
    turned back, and nothing is exchanged. The pairs are looked at again until a pass over them
    exchanges nothing: an exchange changes what both tracks hold after its cut, and so their
    meetings with the others (where three look-alikes crowd, one pair's trade may show only once
    another pair's is put right). A pair is not cut again within ``window`` frames of a cut it
    was exchanged at: the lines there read that seam (an exchange made halfway across a blend
    leaves its frames to either track), and two cuts a few frames apart would exchange the
    tracks back and forth from pass to pass. Where three look-alikes leave a crowd each on the
    next one's object, no exchange of two tracks puts any of them right (:func:`_exchange_cycles`).
    """
    out = list(tracks)
    seams: dict[tuple[int, int], list[int]] = {}
    for _ in range(2 * len(out) ** 2):  # a bound; the passes end at one that exchanges nothing
        if not _swap_pass(out, n_frames, window, alike, min_iou, seams):
            break
    _exchange_cycles(out, n_frames, window, alike, min_iou)
    return out


def _swap_pass(out: list[Track], n_frames: int, window: int, alike: np.ndarray, min_iou: float,
               seams: dict[tuple[int, int], list[int]]) -> bool:
    """One pass of :func:`swap_at_crossings` over every pair of ``out`` (changed in place), away
    from the ``seams`` (per pair of slots, the cuts exchanged so far; added to); whether it
    exchanged any continuations."""
    exchanged_any = False
    boxes, centres, sizes = _paths(out, n_frames)
    for a in range(len(out)):
        for b in range(a + 1, len(out)):
            if not alike[a, b]:
                continue
            size = min(sizes[a], sizes[b])
            for start, stop in _meeting_runs(centres, sizes, a, b):
                blended = np.nan_to_num(box_iou(boxes[a, start:stop], boxes[b, start:stop])).max() >= min_iou
                found = _best_cut(centres[a], centres[b], range(start, stop + 1), window, TURN * size,
                                  window if blended else 0)
                if found is not None and any(abs(found[0] - seam) <= window for seam in seams.get((a, b), ())):
                    found = None  # the cut's lines read an earlier exchange's seam: the whole meeting tells
                if found is not None and _one_object_either_side(boxes[a], boxes[b], found[0], *found[1]):
                    found = None  # the cut's lines read one object: the whole meeting tells
                kept, exchanged, apart, own_apart = _across_meeting(centres[a], centres[b], start, stop, window)
                if found is None:
                    glided = blended and bool(np.all(apart <= size))  # NaN: a line is missing
                    passed = bool(np.all(apart <= JOINED * size) and np.all(own_apart > JOINED * size))
                    taken = (glided and _gain(kept, exchanged, TURN * size) > 0) or (passed and exchanged < kept)
                    cut = (start + stop) // 2 if taken else None
                else:
                    cut, (first_line, last_line) = found
                    if start <= first_line and last_line <= stop and kept < exchanged:
                        cut = None
                if cut is None:
                    continue
                _exchange_at(out, (boxes, centres), a, b, cut)
                exchanged_any = True
                seams.setdefault((a, b), []).append(cut)
    return exchanged_any


def _exchange_cycles(out: list[Track], n_frames: int, window: int, alike: np.ndarray, min_iou: float) -> None:
    """Where three look-alikes crowd, their tracks' continuations turned a step around (changed in
    place in ``out``) if they left the crowd as a cycle, each on the next one's object.

    Three tracks crowd while at least two of their three pairs meet (closer than the smaller usual
    size of the two, as in :func:`swap_at_crossings`). Each track's straight line over ``window``
    frames before the crowd and after it gives, for every track and every continuation, how much
    taking it breaks the motion (:func:`_break`, the jump spread over the window and the crowd). The
    cycle that breaks them least is taken, at the crowd's middle frame, where it breaks the three
    motions by at most 1.5 ``TURN`` times the smallest size per frame (what two tracks may break by
    in :func:`_gain`, for three), the tracks' own continuations by more and by at least twice as
    much, each track's line before lies within the size of its new continuation's line after (no
    jump), and each track's boxes overlap by ``min_iou`` somewhere in the crowd with those of the
    track whose continuation it takes (a trade needs a blend). Only tracks ``alike`` to each other
    are turned.
    """
    boxes, centres, sizes = _paths(out, n_frames)
    meet = {(i, j): _meet(centres, sizes, i, j) for i, j in itertools.combinations(range(len(out)), 2) if alike[i, j]}
    for trio in itertools.combinations(range(len(out)), 3):
        pairs = [pair for pair in itertools.combinations(trio, 2) if pair in meet]
        if len(pairs) < 3:
            continue
        crowded = np.sum([meet[pair] for pair in pairs], axis=0) >= 2
        size = float(sizes[list(trio)].min())
        for start, stop in zip(*(bounds.tolist() for bounds in flag_runs(crowded))):
            cycle = _best_cycle(boxes[list(trio)], centres[list(trio)], start, stop, window, size, min_iou)
            if cycle is None:
                continue
            for x, y in ((0, cycle[0]), (cycle[0], cycle[cycle[0]])):  # two exchanges make the turn
                _exchange_at(out, (boxes, centres), trio[x], trio[y], (start + stop) // 2)


def _best_cycle(boxes: np.ndarray, centres: np.ndarray, start: int, stop: int, window: int, size: float,
                min_iou: float) -> tuple[int, int, int] | None:
    """For three tracks' box and centre paths (3, n_frames, ...) that crowd over frames
    ``start``-``stop``: the cycle (``cycle[i]``: whose continuation track ``i`` takes) that
    :func:`_exchange_cycles` takes, or None."""
    n_frames = centres.shape[1]
    lines = [[straight_line(path, frames) for path in centres]
             for frames in (np.arange(max(start - window, 0), start), np.arange(stop, min(stop + window, n_frames)))]
    if any(line is None for side in lines for line in side):
        return None
    before, after = (np.array(side, dtype=float) for side in lines)
    middle = (start + stop) // 2
    breaks = _break(before[:, None], after[None, :], middle, window + stop - start)  # before i, after j
    kept, least = float(np.trace(breaks)), 1.5 * TURN * size
    best, best_turned = None, np.inf
    for cycle in ((1, 2, 0), (2, 0, 1)):
        turned = float(sum(breaks[i, cycle[i]] for i in range(3)))
        if not (turned <= least < kept and 2 * turned <= kept and turned < best_turned):
            continue
        if max(float(_jump(before[i], after[cycle[i]], middle)) for i in range(3)) > size:
            continue
        if all(np.nan_to_num(box_iou(boxes[i, start:stop], boxes[cycle[i], start:stop])).max() >= min_iou
               for i in range(3)):
            best, best_turned = cycle, turned
    return best


def _one_object_either_side(first: np.ndarray, second: np.ndarray, cut: int, first_line: int, last_line: int
                            ) -> bool:
    """Whether two box paths (n_frames, 4) hold one object both before ``cut`` (from
    ``first_line``) and from it on (to ``last_line``): their boxes overlap by at least
    ``SAME_OBJECT_IOU`` in most frames of each side (median; NaN where either is absent counts 0)."""
    first_line = max(first_line, 0)  # a line drawn from the video's start
    overlap = np.nan_to_num(box_iou(first[first_line:last_line + 1], second[first_line:last_line + 1]))
    before, after = overlap[:cut - first_line], overlap[cut - first_line:]
    return bool(before.size and after.size and np.median(before) >= SAME_OBJECT_IOU
                and np.median(after) >= SAME_OBJECT_IOU)


def _best_cut(first: np.ndarray, second: np.ndarray, cuts: range, window: int, least: float, most_skipped: int
              ) -> tuple[int, tuple[int, int]] | None:
    """Frame of ``cuts`` where exchanging the centre paths' continuations helps most, and the
    first and last frame of the lines that tell it; None where no frame does.

    Where no frame parts them, the lines after a cut may start up to ``most_skipped`` frames
    later (the cut and skip that help most): where the objects overlap, one track can hold a
    blend of both for a few frames after the other has already left on its new object, and a
    line through the blend fits neither pairing. The frames skipped are counted in the spread
    of the jump, and the exchange is made halfway across them."""
    def lines(starts: range) -> np.ndarray:
        """(len(starts), 2, 2, 2): :func:`_lines` over ``window`` frames from each start on
        (compiled over all the starts: every frame of every meeting is a cut to try)."""
        at = np.arange(starts.start, starts.stop, dtype=np.int64)
        (own, own_drawn), (other, other_drawn) = (window_lines(np.asarray(path, dtype=np.float64), at, window)
                                                  for path in (first, second))
        both = np.stack([own, other], axis=1)
        both[~(own_drawn & other_drawn)] = np.nan
        return both

    before = lines(range(cuts.start - window, cuts.stop - window))
    after = lines(range(cuts.start, cuts.stop + window))
    best, best_gain = None, 0.0
    for skipped in range(most_skipped + 1):
        if skipped == 1 and best is not None:
            break
        middle = np.arange(cuts.start, cuts.stop) + skipped // 2
        gain = _gain(*_breaks(before, after[skipped:skipped + len(cuts)], middle, window + skipped), least)
        if gain.size and gain.max() > best_gain:
            cut = cuts.start + int(gain.argmax())
            best, best_gain = (cut + skipped // 2, (cut - window, cut + skipped + window - 1)), float(gain.max())
    return best


def _across_meeting(first: np.ndarray, second: np.ndarray, start: int, stop: int, window: int
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`_breaks` of a cut at the meeting's middle frame, judged from the lines over
    ``window`` frames before the meeting and after it (the tracks may hold one object together
    in it, so that no single frame of it parts them, or travel together for long), and how far
    each track's line before is at that frame from the other's line after (exchanged pairing)
    and from its own (2, each); NaN where a line is missing."""
    before = _lines(first, second, np.arange(max(start - window, 0), start))
    after = _lines(first, second, np.arange(stop, min(stop + window, len(first))))
    middle = (start + stop) // 2
    kept, exchanged = _breaks(before, after, middle, window + stop - start)
    return kept, exchanged, _jump(before, after[::-1], middle), _jump(before, after, middle)


def _lines(first: np.ndarray, second: np.ndarray, frames: np.ndarray) -> np.ndarray:
    """(2 paths, velocity and position, 2): both centre paths' straight lines over ``frames``;
    NaN where either cannot be drawn."""
    lines = straight_line(first, frames), straight_line(second, frames)
    return np.full((2, 2, 2), np.nan) if lines[0] is None or lines[1] is None else np.array(lines, dtype=float)


def _breaks(before: np.ndarray, after: np.ndarray, cut: np.ndarray | int, spread: int
            ) -> tuple[np.ndarray, np.ndarray]:
    """How much two tracks' own pairing and the exchanged one (continuations traded at ``cut``)
    break their motions (:func:`_break`, jumps spread over ``spread`` frames), from their
    :func:`_lines` ``before`` and ``after`` (..., 2, 2, 2; cuts (...) broadcast); NaN where a
    line is missing."""
    kept = _break(before[..., 0, :, :], after[..., 0, :, :], cut, spread) + _break(
        before[..., 1, :, :], after[..., 1, :, :], cut, spread)
    exchanged = _break(before[..., 0, :, :], after[..., 1, :, :], cut, spread) + _break(
        before[..., 1, :, :], after[..., 0, :, :], cut, spread)
    return kept, exchanged


def _gain(kept: np.ndarray, exchanged: np.ndarray, least: float) -> np.ndarray:
    """How much exchanging lessens the break of the motions (``kept``: own pairing's,
    ``exchanged``); 0 unless the own pairing breaks by more than ``least`` and the exchanged one
    by at most that, and by at most half as much (NaN: no)."""
    return np.where((exchanged <= least) & (least < kept) & (2 * exchanged <= kept), kept - exchanged, 0.0)


def _break(before: np.ndarray, after: np.ndarray, cut: np.ndarray | int, window: int) -> np.ndarray:
    """How much going from the line ``before`` (velocity, position at frame 0) to the line
    ``after`` at ``cut`` breaks a straight motion: the change of velocity, and the jump between
    the lines spread over ``window`` frames. Lines (..., 2, 2) and cuts (...) broadcast."""
    velocity_change = np.linalg.norm(after[..., 0, :] - before[..., 0, :], axis=-1)
    return velocity_change + _jump(before, after, cut) / window


def _jump(before: np.ndarray, after: np.ndarray, cut: np.ndarray | int) -> np.ndarray:
    """Distance between the lines ``before`` and ``after`` (velocity, position at frame 0) where
    the one gives way to the other, halfway between frames ``cut - 1`` and ``cut``. Lines
    (..., 2, 2) and cuts (...) broadcast."""
    (v0, p0), (v1, p1) = np.moveaxis(before, -2, 0), np.moveaxis(after, -2, 0)
    at = np.asarray(cut, dtype=float)[..., None] - 0.5
    return np.linalg.norm((p1 + v1 * at) - (p0 + v0 * at), axis=-1)


def lookalike_meetings(tracks: Sequence[Track], n_frames: int, alike: np.ndarray) -> list[tuple[int, int, int, int]]:
    """(a, b, first frame, frame past the last) of each meeting of two tracks ``alike[a, b]`` of
    ``tracks``, as :func:`swap_at_crossings` reads them: for measures of what it does to them
    (``benchmarks/crossing_meetings.py``)."""
    _, centres, sizes = _paths(tracks, n_frames)
    return [(a, b, start, stop) for a, b in itertools.combinations(range(len(tracks)), 2) if alike[a, b]
            for start, stop in _meeting_runs(centres, sizes, a, b)]


def _meet(centres: np.ndarray, sizes: np.ndarray, a: int, b: int) -> np.ndarray:
    """Per frame: whether tracks ``a`` and ``b`` (of :func:`_paths`' ``centres`` and ``sizes``)
    meet, their box centres closer than the smaller of their usual sizes (False where either
    is absent)."""
    return np.linalg.norm(centres[a] - centres[b], axis=1) < min(sizes[a], sizes[b])


def _meeting_runs(centres: np.ndarray, sizes: np.ndarray, a: int, b: int) -> list[tuple[int, int]]:
    """(first frame, frame past the last) of each meeting of tracks ``a`` and ``b`` (:func:`_meet`)."""
    return list(zip(*(bounds.tolist() for bounds in flag_runs(_meet(centres, sizes, a, b)))))


def _paths(out: Sequence[Track], n_frames: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The tracks' box paths (T, n_frames, 4; NaN where a track has no box), their centres and
    the tracks' usual sizes (0 for an empty track): what the meetings are read from."""
    boxes = np.array([box_path(t, n_frames) for t in out]).reshape(len(out), n_frames, 4)
    return boxes, box_centres(boxes), np.array([usual_size(t) if len(t) else 0.0 for t in out])


def _exchange_at(out: list[Track], paths: tuple[np.ndarray, ...], a: int, b: int, cut: int) -> None:
    """Tracks ``a`` and ``b`` of ``out`` with their continuations from ``cut`` on exchanged, and
    so their ``paths`` (per track, along frames), all in place."""
    out[a], out[b] = _exchanged(out[a], out[b], cut)
    for path in paths:
        path[[a, b], cut:] = path[[b, a], cut:]


def _exchanged(a: Track, b: Track, cut: int) -> tuple[Track, Track]:
    """``a`` before ``cut`` with ``b`` from ``cut`` on, and the other way round; ids stay."""
    b_after, a_after = in_rows(b, b.frames >= cut), in_rows(a, a.frames >= cut)
    return (with_frames(in_rows(a, a.frames < cut), b_after.frames, b_after.boxes, b_after.score, b_after.points),
            with_frames(in_rows(b, b.frames < cut), a_after.frames, a_after.boxes, a_after.score, a_after.points))
