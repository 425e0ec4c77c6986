"""Whether the fragments rejoined into one group could be one object gone on (ours, TRAP_SPEC
section 10 "fragments never rejoin").

:func:`trap_core.robust.rejoin_fragments` joins fragments a pair at a time, and a group is the
union of every pair joined. Two fragments that were never compared can so end up next to each
other in one group: a car that left through the right of the view and a look-alike that entered
through the bottom the next frame each rejoin a third fragment, seen hundreds of frames later,
and the group then holds the first car, then the second, as if it had crossed the view in a
frame. An object does not jump: where one fragment of a group ends and the next begins, the
next begins within reach of the first's end, at ``PACE`` times the faster of the two motions
there (as :func:`trap_core.robust.fill_gaps` bridges a gap), plus a slack for the distance
between two parts of one object (its patterns' barycentres). The motion is read in the view and,
with the camera's motion, in the world; a seam is within reach when it is in either (a camera
that follows its object keeps it steady in the view, one that sweeps past leaves it steady in
the world).
"""
from __future__ import annotations

import numpy as np

from trap_core.clustering import Trajectories
from trap_core.robust.camera import to_world

PACE = 3.0  # an object out of sight goes at most this many times as fast as it went in sight
TAIL = 10  # frames at a fragment's end (start) over which its motion there is read (here and in its predictions)


class FragmentReach:
    """Each fragment's first and last place and its speed there, in the view and, with the
    camera's ``transforms`` (frame-0 coordinates to frame ``t``), in the world; ``paths``: one
    mean path per fragment (0..C-1). ``slack``: px a seam may span whatever the motion."""

    def __init__(self, paths: Trajectories, transforms: np.ndarray | None, slack: float) -> None:
        self._start, self._end, self._slack = paths.start, paths.end, slack
        tail = np.minimum(paths.end - paths.start + 1, TAIL)
        first_row, last_row = paths.offsets[:-1], paths.offsets[1:] - 1
        rows = (first_row, first_row + tail - 1, last_row - tail + 1, last_row)
        frames = (paths.start, paths.start + tail - 1, paths.end - tail + 1, paths.end)
        in_view = [paths.points[r] for r in rows]
        self._ends = [_ends(*in_view, tail)]
        if transforms is not None:
            in_world = [to_world(transforms, f, p) for f, p in zip(frames, in_view)]
            self._ends.append(_ends(*in_world, tail))

    def seams_within_reach(self, group: np.ndarray, other: np.ndarray) -> bool:
        """Whether, in the union of fragments ``group`` and ``other`` ordered by their starts,
        every fragment of one that follows one of the other after a gap begins within reach of
        where that one ended (fragments that overlap in time are left to the rejoining's own
        tests)."""
        members = np.concatenate([group, other])
        sides = np.r_[np.zeros(group.size, dtype=bool), np.ones(other.size, dtype=bool)]
        order = np.argsort(self._start[members], kind="stable")
        members, sides = members[order], sides[order]
        seams = np.flatnonzero(sides[1:] != sides[:-1])
        before, after = members[seams], members[seams + 1]
        gap = self._start[after] - self._end[before]
        before, after, gap = before[gap > 0], after[gap > 0], gap[gap > 0]
        reached = np.zeros(gap.size, dtype=bool)
        for first, last, start_speed, end_speed in self._ends:
            speed = np.maximum(end_speed[before], start_speed[after])
            reached |= np.linalg.norm(first[after] - last[before], axis=1) <= PACE * speed * gap + self._slack
        return bool(reached.all())


def _ends(first: np.ndarray, after_first: np.ndarray, before_last: np.ndarray, last: np.ndarray,
          tail: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """First and last places of paths and their mean speeds (px per frame) over their first and
    last ``tail`` points (``after_first``, ``before_last``: the other ends of those stretches)."""
    steps = np.maximum(tail - 1, 1)
    return (first, last, np.linalg.norm(after_first - first, axis=1) / steps,
            np.linalg.norm(last - before_last, axis=1) / steps)
