#!/usr/bin/env python3
"""Draw docs/pipeline.png for the README: a frame, its regions and plane graph, and the tracks."""
from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

from trap_core.outputs import draw_tracks
from trap_core.pipeline import TrapParams, frame_graph, track
from trap_core.synthetic import PRESETS, SceneConfig, render


def main() -> None:
    cfg = SceneConfig(width=320, height=240, frames=240, seed=1, **PRESETS["anim2"])
    params = TrapParams(segmentation="colour", eps=20.0)
    frames, graphs = [], []
    for frame in render(cfg):
        frames.append(frame.rgb)
        graphs.append(frame_graph(frame.rgb, params))
    result = track(graphs, params)
    shown = 120
    rgb, graph = frames[shown], graphs[shown]
    overlay = (rgb * 0.35).astype(np.uint8)
    pairs = graph.edges
    for a, b in pairs[(pairs < graph.n_nodes).all(axis=1)]:
        pa, pb = graph.centroid[a].round().astype(int), graph.centroid[b].round().astype(int)
        cv2.line(overlay, tuple(pa), tuple(pb), (255, 255, 255), 1, cv2.LINE_AA)
    for (x, y), colour in zip(graph.centroid, graph.colour):
        cv2.circle(overlay, (int(round(x)), int(round(y))), 3, tuple(int(c) for c in colour), -1, cv2.LINE_AA)
    tracked = draw_tracks(rgb, shown, result.tracks)
    for trk in result.tracks:
        centres = (trk.boxes[:, :2] + trk.boxes[:, 2:] / 2)[trk.frames <= shown].round().astype(np.int32)
        cv2.polylines(tracked, [centres.reshape(-1, 1, 2)], False, (255, 255, 255), 1, cv2.LINE_AA)
    gap = np.full((rgb.shape[0], 6, 3), 255, dtype=np.uint8)
    picture = np.concatenate([rgb, gap, overlay, gap, tracked], axis=1)
    out = Path(__file__).resolve().parents[1] / "docs" / "pipeline.png"
    cv2.imwrite(str(out), cv2.cvtColor(picture, cv2.COLOR_RGB2BGR))
    print(out)


if __name__ == "__main__":
    main()
