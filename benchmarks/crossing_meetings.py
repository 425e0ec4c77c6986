#!/usr/bin/env python3
"""Benchmark: what the exchanges at crossings do to the look-alike meetings of real tracks.

``crowd_trades.py`` measures :func:`trap_core.robust.swap_at_crossings` on drawn boxes with no
noise. Here it is measured where its tracks come from: each video of ``quality.py``'s sets is
tracked with the defaults, and the tracks the rule is given and those it gives back are kept
(the rule is wrapped in the tracking run, which it does not otherwise change). Two alike tracks
meet while their box centres are closer than the smaller of their usual sizes, as the rule reads
it. Before a meeting and after it, over ``tau``/3 frames (the rule's window), each track holds
the object that the ground truth gives at least 60 % of its box centres
(:func:`trap_core.evaluation.held_objects`); a meeting is judged where both tracks hold one
object each, different before it, and, after it, each holds its own (kept) or the other's
(traded); other meetings (a track on nothing, on a third object, or absent) are not. Prints per
set the meetings judged on the tracks given, how many the tracks leave traded, and what the rule
made of them: traded ones put right or left, kept ones left or put wrong (session 79 labelled
987 meetings so to find the crossings that no test took back; README, one track per object).
Run: ``.venv/bin/python benchmarks/crossing_meetings.py [--sets later,jpeg] [-p name:=value]``
(graphs from ``quality.py``'s cache; about 10 min over every set once they are made).
"""
from __future__ import annotations

import argparse
import sys
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from unittest import mock

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import quality  # noqa: E402  (the benchmark sets and their graph cache)

from trap_core.cli import parameter_assignment  # noqa: E402
from trap_core.clustering import Track  # noqa: E402
from trap_core.evaluation.held_objects import NONE, held_objects  # noqa: E402
from trap_core.pipeline import TrapParams, track  # noqa: E402
from trap_core.pipeline import track_rules  # noqa: E402
from trap_core.robust import lookalike_meetings  # noqa: E402

HELD_SHARE = 0.6  # of a side's boxes on one object, for the track to hold it there


def held_over(track_: Track, frames: range, truth: Sequence[dict]) -> int:
    """The object ``track_`` holds over ``frames`` (:data:`HELD_SHARE` of its boxes there), else NONE."""
    inside = np.isin(track_.frames, np.arange(frames.start, frames.stop))
    boxes = {int(f): tuple(box) for f, box in zip(track_.frames[inside], track_.boxes[inside])}
    counts = Counter(held_objects(boxes, truth).values())
    if not counts:
        return NONE
    obj, count = counts.most_common(1)[0]
    return obj if count >= HELD_SHARE * len(boxes) else NONE


def verdict(pair: tuple[Track, Track], start: int, stop: int, window: int, truth: Sequence[dict]) -> str | None:
    """'kept' or 'traded' for two tracks' meeting over frames ``start``-``stop`` (see the module), or None."""
    before = [held_over(t, range(start - window, start), truth) for t in pair]
    after = [held_over(t, range(stop, stop + window), truth) for t in pair]
    if NONE in before or NONE in after or before[0] == before[1]:
        return None
    return "kept" if after == before else "traded" if after == before[::-1] else None


def video_counts(scene: dict, segmentation: str, cache: Path, overrides: dict) -> Counter:
    """For one video: meetings judged before the rule, by what they were and what the rule left."""
    graphs, truth = quality._graphs(scene, segmentation, cache, overrides)
    seen: list[tuple] = []
    rule = track_rules.swap_at_crossings

    def recording(tracks, n_frames, window, alike, *rest, **options):
        out = rule(tracks, n_frames, window, alike, *rest, **options)
        seen.append((list(tracks), out, n_frames, window, alike))
        return out

    with mock.patch.object(track_rules, "swap_at_crossings", recording):
        track(graphs, TrapParams.from_mapping({"segmentation": segmentation, **overrides}))
    counts: Counter = Counter()
    for given, returned, n_frames, window, alike in seen:
        for a, b, start, stop in lookalike_meetings(given, n_frames, alike):
            was = verdict((given[a], given[b]), start, stop, window, truth)
            if was is not None:
                counts[was, verdict((returned[a], returned[b]), start, stop, window, truth) or "neither"] += 1
    return counts


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sets", default=",".join(quality.SETS), help="comma-separated: " + ", ".join(quality.SETS))
    parser.add_argument("--cache", type=Path, default=Path.home() / ".cache" / "trap_ros" / "quality")
    parser.add_argument("-p", dest="overrides", action="append", default=[], type=parameter_assignment,
                        metavar="NAME:=VALUE", help="parameter for every run (as process_bag's -p)")
    args = parser.parse_args()
    quality.check_arguments(parser, args.sets, args.overrides)
    overrides = dict(args.overrides)
    print("| set | meetings judged | traded as given | traded put right | traded left | kept left | kept put wrong "
          "| other after |\n|---|---|---|---|---|---|---|---|")
    total: Counter = Counter()
    for name in args.sets.split(","):
        counts: Counter = Counter()
        for _, scene, segmentation in quality.SETS[name]:
            counts += video_counts(scene, segmentation, args.cache, overrides)
        total += counts
        print(_row(name, counts), flush=True)
    print(_row("all", total))


def _row(name: str, counts: Counter) -> str:
    traded = sum(n for (was, _), n in counts.items() if was == "traded")
    other = sum(n for (_, now), n in counts.items() if now == "neither")
    return (f"| {name} | {sum(counts.values())} | {traded} | {counts['traded', 'kept']} | "
            f"{counts['traded', 'traded']} | {counts['kept', 'kept']} | {counts['kept', 'traded']} | {other} |")


if __name__ == "__main__":
    main()
