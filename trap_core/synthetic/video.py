"""Write a synthetic video as a bag plus its MOTChallenge ground truth."""
from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np

from trap_core.bagio import write_image_bag
from trap_core.motformat import ground_truth_path, write_mot
from trap_core.progress import Progress
from trap_core.synthetic.scene import SceneConfig, render


def write_synthetic(cfg: SceneConfig, bag: str | Path, *, encoding: str = "rgb8", compressed: str | None = None,
                    storage: str = "mcap", topic: str = "/camera/image_raw", progress: bool = False,
                    sample_bits: int | None = None) -> tuple[Path, Path]:
    """Render ``cfg`` into ``bag`` and its ground truth into ``NAME.gt.txt`` beside it.

    ``progress`` prints frames done / total, rate and ETA to stderr; ``sample_bits``: significant
    bits of wide integer encodings' samples (:func:`trap_core.bagio.encode_image`).

    Returns
    -------
    (Path, Path)
        The bag and the ground-truth file. Object ids in the ground truth are 1-based.
    """
    bag = Path(bag)
    meter = Progress(cfg.frames, f"rendering {bag.name}") if progress else None
    gt_rows: list[tuple[int, int, float, float, float, float, float]] = []

    def frames() -> Iterator[np.ndarray]:
        for rendered in render(cfg):
            for obj, box in enumerate(rendered.boxes):
                if box is not None:
                    gt_rows.append((rendered.index + 1, obj + 1, *box, 1))
            if meter:
                meter.advance()
            yield rendered.rgb

    write_image_bag(bag, frames(), topic=topic, encoding=encoding, compressed=compressed,
                    storage=storage, fps=cfg.fps, sample_bits=sample_bits)
    if meter:
        meter.finish()
    gt = ground_truth_path(bag)
    write_mot(gt, gt_rows)
    return bag, gt
