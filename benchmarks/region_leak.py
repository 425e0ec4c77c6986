#!/usr/bin/env python3
"""Benchmark: how much of the objects the segmentation merges into the background.

TRAP sees an object only through its regions: a part of an object that Felzenszwalb's rule
merges with the ground around it belongs to no pattern of the object, and its box cannot take
it in. Compressed frames leak most (README, "Compressed frames (JPEG)"): colour edges become
ramps that a region climbs one small step at a time. For each Felzenszwalb video of the
chosen ``quality.py`` sets, frames reach the segmentation as they reach the tracker (compressed
or encoded as the set says, or as rendered with ``--rendered``), ``k`` is fitted on the first
frame as a run fits it (``max_regions``), and on ``--frames`` frames spread over the video each
region is given to what most of its pixels show: an object or the background. The object
pixels in regions given to the background have leaked. Prints, per video, the ``k`` used, the
regions a frame and the leaked share of object pixels; then over all videos. With ``--pictures
DIR``, each video's last measured frame with its regions and its leaked object pixels.
Run: ``.venv/bin/python benchmarks/region_leak.py [--sets jpeg,encoded] [--rendered] [-p mean_gap:=5.0]``
(~10 s a video: every frame up to the last measured is rendered and delivered).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import cv2
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import quality  # noqa: E402  (the benchmark sets)

from trap_core.cli import parameter_assignment  # noqa: E402
from trap_core.evaluation import leaked_pixels, leaked_regions  # noqa: E402
from trap_core.pipeline import TrapParams, delivered_frames, first_frame_setup, frame_regions  # noqa: E402


def leak_picture(rgb: np.ndarray, labels: np.ndarray, owner: np.ndarray) -> np.ndarray:
    """``rgb`` (at the size of ``labels``) with the region boundaries in black, object pixels kept
    apart from the background tinted green and leaked ones red (:func:`leaked_regions`); BGR."""
    on_object = owner >= 0
    leaked = leaked_regions(labels, int(labels.max()) + 1, owner)[labels]
    picture = rgb.astype(np.float32)
    for mask, tint in ((on_object & ~leaked, (0, 200, 0)), (on_object & leaked, (255, 0, 0))):
        picture[mask] = 0.4 * picture[mask] + 0.6 * np.array(tint, dtype=np.float32)
    boundary = np.zeros(labels.shape, dtype=bool)
    boundary[:, :-1] |= labels[:, :-1] != labels[:, 1:]
    boundary[:-1] |= labels[:-1] != labels[1:]
    picture[boundary] = 0
    return cv2.cvtColor(picture.astype(np.uint8), cv2.COLOR_RGB2BGR)


def video_leak(scene: dict, params: TrapParams, frames: int, rendered: bool, picture: Path | None = None,
               ) -> tuple[float, float, int, int]:
    """``k`` fitted on the first frame, the mean regions a frame, and the leaked and all object
    pixels over ``frames`` frames spread over the video (the first one left out: it fits ``k``);
    the last of them drawn into ``picture`` (:func:`leak_picture`) where given."""
    config, delivery = quality._scene_config(scene)
    if rendered:
        delivery = {}
    measured = set(np.linspace(0, config.frames - 1, frames + 2).round().astype(int)[1:-1].tolist())
    last = max(measured)
    leaked = total = 0
    counts = []
    for frame in delivered_frames(config, **delivery):
        if frame.index == 0:
            params = first_frame_setup(frame.rgb, params)[0]
        if frame.index not in measured:
            continue
        labels, count = frame_regions(frame.rgb, params)
        owner = cv2.resize(frame.owner, labels.shape[::-1], interpolation=cv2.INTER_NEAREST)
        frame_leaked, frame_total = leaked_pixels(labels, count, owner)
        leaked, total, counts = leaked + frame_leaked, total + frame_total, counts + [count]
        if frame.index == last:
            if picture is not None:
                small = cv2.resize(frame.rgb, labels.shape[::-1], interpolation=cv2.INTER_NEAREST)
                cv2.imwrite(str(picture), leak_picture(small, labels, owner))
            break
    return params.k, float(np.mean(counts)), leaked, total


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sets", default="jpeg", help="comma-separated: " + ", ".join(quality.SETS))
    parser.add_argument("--frames", type=int, default=3, help="frames measured a video, spread over it")
    parser.add_argument("--rendered", action="store_true",
                        help="the frames as rendered: no compression or encoding, whatever the set says")
    parser.add_argument("--pictures", type=Path, metavar="DIR",
                        help="also write each video's last measured frame here: region boundaries, object "
                             "pixels kept apart (green) and leaked (red)")
    parser.add_argument("-p", dest="overrides", action="append", default=[], type=parameter_assignment,
                        metavar="NAME:=VALUE", help="a segmentation parameter (repeatable), as after ROS's -p")
    args = parser.parse_args()
    if args.frames < 1:
        parser.error("--frames must be at least 1")
    quality.check_arguments(parser, args.sets, args.overrides)
    overrides = dict(args.overrides)
    print("| set | video | k | regions a frame | object pixels leaked % |\n|---|---|---|---|---|")
    leaked = total = 0
    if args.pictures is not None:
        args.pictures.mkdir(parents=True, exist_ok=True)
    for set_name in args.sets.split(","):
        for index, (label, scene, segmentation) in enumerate(quality.SETS[set_name]):
            if segmentation != "felzenszwalb":
                continue  # exact-colour regions are the drawn colours: nothing leaks
            params = TrapParams.from_mapping({"segmentation": segmentation, **overrides})
            picture = None if args.pictures is None else args.pictures / f"{set_name}_{index}_leak.png"
            k, regions, video_leaked, video_total = video_leak(scene, params, args.frames, args.rendered, picture)
            print(f"| {set_name} | {label} | {k:g} | {regions:.0f} | {100 * video_leaked / max(video_total, 1):.1f} |",
                  flush=True)
            leaked, total = leaked + video_leaked, total + video_total
    print(f"\nall videos: {100 * leaked / max(total, 1):.1f} % of object pixels leaked")


if __name__ == "__main__":
    main()
