"""A track cut short is continued by the cluster that goes on where it ended (ours).

Where an object passes behind a look-alike, its patterns' paths can go on with the other
object; :func:`trap_core.robust.drop_shared_stretches` then ends its track there. The object's
own patterns after the meeting often make a cluster of their own that starts where the track
ended but is too short to be selected, and overlaps the track's cluster in time too much to be
rejoined to it. :func:`continue_tracks` appends it.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from trap_core.clustering import ClusterSummary, Track, centre_path, in_rows, with_frames
from trap_core.robust.duplicates import repeats_others
from trap_core.robust.motion import straight_line


def continue_tracks(tracks: Sequence[Track], summary: ClusterSummary, candidates: np.ndarray, n_frames: int,
                    window: int, reach: float, build: Callable[[int], Track], min_iou: float = 0.5) -> list[Track]:
    """Tracks that end more than ``window`` frames before the video, each continued by at most
    one of the clusters ``candidates``.

    A candidate continues a track if it covers at least ``window`` frames after the track's last
    one, the first of them at most ``window`` frames after it, and there its mean position is
    at most ``reach`` px from where the track's motion (a straight line through its last
    ``window`` box centres) puts it; the closest one is taken, and its boxes (``build(cluster)``)
    after the track's end are appended, except where they repeat another track's box (IoU at
    least ``min_iou``). A candidate continues one track only.
    """
    out = list(tracks)
    taken: set[int] = set()
    for slot, current in enumerate(out):
        end = int(current.frames[-1])
        if end >= n_frames - window:
            continue
        line = straight_line(centre_path(current, end + 1), np.arange(max(end + 1 - window, 0), end + 1))
        if line is None:
            continue
        velocity, origin = line
        best, best_error = None, reach
        for cluster in candidates.tolist():
            after = np.flatnonzero(summary.covered[cluster, end + 1:]) + end + 1
            if cluster in taken or after.size < window or after[0] > end + window:
                continue
            position = summary.paths.at(cluster, after[0])
            error = float(np.linalg.norm(position - (origin + velocity * after[0])))
            if error <= best_error:
                best, best_error = cluster, error
        if best is None:
            continue
        follow = build(best)
        follow = in_rows(follow, follow.frames > end)
        follow = in_rows(follow, ~repeats_others(follow, [t for k, t in enumerate(out) if k != slot], min_iou))
        out[slot] = with_frames(current, follow.frames, follow.boxes, follow.score, follow.points)
        taken.add(best)
    return out
