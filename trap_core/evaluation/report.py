"""``evaluate``: TRAP (paper and robust, step by step) and supervised baselines on bags with
ground truth; a Markdown report in the shape of the paper's Fig. 4/6 tables, with pictures."""
from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from trap_core.bagio import open_image_stream  # noqa: E402
from trap_core.cli import UsageError, parameter_assignment, results_folder, run_main  # noqa: E402
from trap_core.evaluation.baselines import TRACKERS, run_baselines  # noqa: E402
from trap_core.evaluation.cluster_scores import best_cluster, leaf_scores, level_curves  # noqa: E402
from trap_core.evaluation.held_objects import object_timeline  # noqa: E402
from trap_core.evaluation.losses import causes_line, object_losses  # noqa: E402
from trap_core.evaluation.paper_measures import cluster_precision_recall  # noqa: E402
from trap_core.evaluation.scoring import boxes_by_frame, match_objects, mot_measures  # noqa: E402
from trap_core.motformat import ground_truth_path, read_mot  # noqa: E402
from trap_core.outputs import Thumbnails, contact_sheet  # noqa: E402
from trap_core.pipeline import TrapParams, graphs_of, print_setup_notes, track  # noqa: E402
from trap_core.pipeline.bag_run import thumbnailed_frames  # noqa: E402
from trap_core.progress import Progress  # noqa: E402

# The ablation: the paper's method, then each step of the robust one added in turn (its parameter
# back at its default), from one-to-one linking alone.
_ROBUST_OFF = dict(link_reach=0.0, label_memory=False, min_speed=0.0, image_motion=False, steady_steps=0.0,
                   own_region=False, one_object=False, rejoin=False, rejoin_colour_reach=0.0, core_share=0.0,
                   still_regions=False, grow=False, edge_lines=False, fill_gaps=False, one_track=False,
                   own_frames=False, size_jump=0.0, groups=False, to_border=False,
                   follow_ends=False, steady_edges=False)
_ROBUST_STEPS = (("+ steps within reach", "link_reach"), ("+ label memory", "label_memory"),
                 ("+ camera motion", "min_speed"), ("+ camera motion from the images", "image_motion"),
                 ("+ steady steps", "steady_steps"), ("+ own region moves", "own_region"),
                 ("+ one object per cluster", "one_object"),
                 ("+ rejoin fragments", "rejoin"), ("+ colours across exits", "rejoin_colour_reach"),
                 ("+ core boxes", "core_share"),
                 ("+ background out of boxes", "still_regions"), ("+ grown boxes", "grow"),
                 ("+ edge lines out of boxes", "edge_lines"), ("+ filled gaps", "fill_gaps"),
                 ("+ one track per object", "one_track"),
                 ("+ own frames, twin clusters", "own_frames"),
                 ("+ steady box size", "size_jump"),
                 ("+ where objects meet", "groups"), ("+ across the border", "to_border"),
                 ("+ followed past their ends", "follow_ends"),
                 ("robust (+ steady box edges)", "steady_edges"))


def _ablation() -> tuple[tuple[str, dict], ...]:
    """(label, parameter overrides) of every step, so each robust rule's share shows in the report."""
    steps = [("paper", dict(method="paper")), ("+ one path per object", dict(method="robust", **_ROBUST_OFF))]
    off = dict(_ROBUST_OFF)
    for label, key in _ROBUST_STEPS:
        del off[key]
        steps.append((label, dict(method="robust", **off)))
    return tuple(steps)


STEPS = _ablation()


def _truth(path: Path) -> list[dict[int, tuple]]:
    rows = read_mot(path)
    ids = np.unique(rows[:, 1]).astype(int)
    return [{int(r[0]) - 1: tuple(r[2:6]) for r in rows[rows[:, 1] == i]} for i in ids]


def evaluate_bag(bag: Path, gt_path: Path, base: TrapParams, baselines: list[str], out: Path, topic: str | None,
                 ) -> dict:
    truth = _truth(gt_path)
    name = bag.name.removesuffix(bag.suffix) if bag.suffix else bag.name
    with open_image_stream(bag, topic) as stream:
        meter = Progress(stream.count, f"evaluate {name}: graphs")
        thumbnails = Thumbnails(stream.count)
        start = time.perf_counter()
        # with the camera's steps whatever the base method: the ablation adds them in its own step
        graphs = list(graphs_of(thumbnailed_frames(stream, thumbnails, meter), base, print_setup_notes,
                                image_steps=True))
        graph_seconds = time.perf_counter() - start
        meter.finish()
    n_frames = len(graphs)
    result: dict = {"bag": str(bag), "frames": n_frames, "objects": len(truth), "graph_seconds": graph_seconds,
                    "methods": {}, "baselines": {}}
    for label, overrides in STEPS:
        params = dataclasses.replace(base, **overrides)
        if overrides["method"] == "paper":  # the paper takes the number of objects as given
            params = dataclasses.replace(params, n_objects=len(truth))
        start = time.perf_counter()
        run = track(graphs, params)
        seconds = time.perf_counter() - start
        boxes = [boxes_by_frame(t) for t in run.tracks]
        matched = match_objects(boxes, truth)
        objects = []
        for obj, ((k, p, r), gt) in enumerate(zip(matched, truth)):
            cp, cr = (cluster_precision_recall(run.mining, np.flatnonzero(run.labels == run.tracks[k].cluster), gt)
                      if k is not None else (0.0, 0.0))
            lost = object_losses(None if k is None else boxes[k], truth, obj)
            objects.append({"box_p": p, "box_r": r, "cluster_p": cp, "cluster_r": cr,
                            "loses_most": "" if lost.good else lost.cause})
        entry = {"seconds": seconds, "tracks": len(run.tracks), "objects": objects, **mot_measures(boxes, truth),
                 "patterns": run.mining.n_st}
        if overrides["method"] == "paper":
            clustered = np.arange(run.mining.n_st)
            leaves = [leaf_scores(run.mining, clustered, gt, n_frames) for gt in truth]
            entry["best_cluster"] = [best_cluster(run.hierarchy, lv) for lv in leaves]
            occurrences = run.mining.st_occurrences
            for o, lv in enumerate(leaves):
                curves = level_curves(run.hierarchy, lv, run.trajectories, occurrences, n_frames)
                entry.setdefault("figures", []).append(_plot_levels(curves, run.hierarchy.cut_level,
                                                                    out / f"levels_{name}_object{o + 1}.png",
                                                                    f"{name}, object {o + 1}"))
        if label.startswith("robust"):
            result["sheet"] = str(contact_sheet(thumbnails.images, run.tracks, thumbnails.scale,
                                                out / f"tracks_{name}.png"))
            result["held_objects"] = str(object_timeline(boxes, truth, n_frames, out / f"objects_{name}.png",
                                                         f"{name}: the object each robust track holds"))
        result["methods"][label] = entry
    if baselines:
        with open_image_stream(bag, topic) as stream:
            meter = Progress(stream.count, f"evaluate {name}: baselines {', '.join(baselines)}")

            def plain():
                for frame in stream:
                    meter.advance()
                    yield frame.rgb
            start = time.perf_counter()
            tracked = run_baselines(plain(), truth, baselines)
            meter.finish()
        per_tracker = (time.perf_counter() - start) / len(baselines)
        for tracker, boxes in tracked.items():
            losses = [object_losses(b, truth, obj) for obj, b in enumerate(boxes)]
            result["baselines"][tracker] = {"objects": [{"box_p": lost.precision, "box_r": lost.recall,
                                                         "loses_most": "" if lost.good else lost.cause}
                                                        for lost in losses],
                                            "seconds": per_tracker, **mot_measures(boxes, truth)}
    return result


def _plot_levels(curves: dict[str, np.ndarray], cut: int, path: Path, title: str) -> str:
    figure, axis = plt.subplots(figsize=(6, 3.2))
    for key, style, text in (("best_p", "-", "best P"), ("best_r", "--", "best R"),
                             ("longest_p", "-", "longest P"), ("longest_r", "--", "longest R")):
        axis.plot(curves["levels"], curves[key], style, label=text,
                  color="tab:blue" if key.startswith("best") else "tab:orange")
    axis.axvline(cut, color="k", linestyle=":", label=f"lifetime cut ({cut})")
    axis.set_xscale("log")
    axis.set_xlabel("level (number of clusters)")
    axis.set_ylim(0, 1.02)
    axis.set_title(title)
    axis.legend(fontsize=7, loc="lower left")
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return str(path)


def _pct(value: float) -> str:
    return f"{100 * value:.0f}"


def _causes(entry: dict) -> str:
    """How many of a method's objects under 90/90 each cause loses the most, as one line."""
    return causes_line(o["loses_most"] for o in entry["objects"] if o["loses_most"])


def markdown(results: list[dict]) -> str:
    lines = ["# TRAP evaluation", "",
             "Precision / recall (%) per object. Box measures (TRAP_SPEC section 8) for every method: "
             "precision = area shared with the ground truth / area of the track boxes, recall = frames whose "
             "box centre lies in the ground-truth box. TRAP columns also give the paper's cluster measures "
             "(occurrences whose nodes all lie in the box). The paper's method is given the number of objects; "
             "the robust one finds it. Baselines start from the first ground-truth box. For an object under 90/90: "
             "what loses its track the most frames (no track, before or after the track, in its gaps, on another "
             "object, on nothing), or where only precision falls short, the most box area off the object "
             "(trap_core.evaluation.losses).", ""]
    for res in results:
        methods, baselines = res["methods"], res["baselines"]
        lines += [f"## {Path(res['bag']).name} ({res['frames']} frames, {res['objects']} objects)", ""]
        header = ["object", *baselines, "TRAP paper L (box)", "TRAP paper L (cluster)", "TRAP paper B (cluster)",
                  "TRAP robust (box)", "TRAP robust (cluster)", "robust: loses most"]
        lines += ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
        paper, robust = methods["paper"], methods[STEPS[-1][0]]
        for o in range(res["objects"]):
            cells = [str(o + 1)]
            cells += [f"{_pct(b['objects'][o]['box_p'])}/{_pct(b['objects'][o]['box_r'])}" for b in baselines.values()]
            po, ro = paper["objects"][o], robust["objects"][o]
            bp, br = paper["best_cluster"][o]
            cells += [f"{_pct(po['box_p'])}/{_pct(po['box_r'])}", f"{_pct(po['cluster_p'])}/{_pct(po['cluster_r'])}",
                      f"{_pct(bp)}/{_pct(br)}", f"{_pct(ro['box_p'])}/{_pct(ro['box_r'])}",
                      f"{_pct(ro['cluster_p'])}/{_pct(ro['cluster_r'])}", ro["loses_most"] or "-"]
            lines.append("| " + " | ".join(cells) + " |")
        lines += ["", "| method | tracks | MOTA | IDF1 | HOTA | seconds (after graphs) | under 90/90, by what loses "
                      "most |", "|---|---|---|---|---|---|---|"]
        for label, entry in methods.items():
            lines.append(f"| TRAP {label} | {entry['tracks']} | {entry['MOTA']:.2f} | {entry['IDF1']:.2f} | "
                         f"{entry['HOTA']:.2f} | {entry['seconds']:.1f} | {_causes(entry)} |")
        for label, entry in baselines.items():
            lines.append(f"| {label} (supervised) | {res['objects']} | {entry['MOTA']:.2f} | {entry['IDF1']:.2f} | "
                         f"{entry['HOTA']:.2f} | {entry['seconds']:.1f} | {_causes(entry)} |")
        lines += ["", f"Segmentation and graphs: {res['graph_seconds']:.1f} s "
                      f"({res['frames'] / max(res['graph_seconds'], 1e-9):.0f} frames/s).", ""]
        lines += [f"![tracks]({Path(res['sheet']).name})", "", f"![objects held]({Path(res['held_objects']).name})", ""]
        for figure in paper.get("figures", []):
            lines.append(f"![levels]({Path(figure).name})")
        lines.append("")
    return "\n".join(lines)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="evaluate", description=__doc__.splitlines()[0])
    parser.add_argument("bags", nargs="+", type=Path, help="bags; ground truth in NAME.gt.txt beside each")
    parser.add_argument("--out", type=Path, default=Path("results/evaluation"))
    parser.add_argument("--topic")
    parser.add_argument("--baselines", default=",".join(TRACKERS),
                        help=f"comma-separated, from {', '.join(TRACKERS)}; 'none' to skip")
    parser.add_argument("-p", dest="overrides", action="append", default=[], metavar="NAME:=VALUE",
                        help="TRAP parameter, as for process_bag (e.g. -p segmentation:=colour)")
    return parser


def _main() -> int:
    args = build_parser().parse_args()
    baselines = [] if args.baselines == "none" else [b for b in args.baselines.split(",") if b]
    unknown = [b for b in baselines if b not in TRACKERS]
    if unknown:
        raise UsageError(f"unknown baseline(s) {', '.join(unknown)} (known: {', '.join(TRACKERS)})")
    base = TrapParams.from_mapping(dict(parameter_assignment(item) for item in args.overrides))
    results_folder(args.out)
    results = []
    for bag in args.bags:
        gt = ground_truth_path(bag)
        if not gt.exists():
            raise UsageError(f"no ground truth for {bag}: expected {gt}")
        results.append(evaluate_bag(bag, gt, base, baselines, args.out, args.topic))
    (args.out / "report.json").write_text(json.dumps(results, indent=2, default=float))
    (args.out / "report.md").write_text(markdown(results))
    print(f"report: {args.out / 'report.md'}")
    return 0


def main() -> None:
    sys.exit(run_main(_main, "evaluate"))
