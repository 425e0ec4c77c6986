"""MOTA, IDF1 and HOTA: against py-motmetrics' published TUD-Campus figures and hand-made cases."""
from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from trap_core.evaluation.mot_metrics import clear_mot, hota, idf1, iou_matrix
from trap_core.motformat import read_mot


def _tud_campus() -> tuple[np.ndarray, np.ndarray]:
    spec = importlib.util.find_spec("motmetrics")
    if spec is None or not spec.submodule_search_locations:
        pytest.skip("py-motmetrics (reference data) is not installed")
    folder = Path(spec.submodule_search_locations[0]) / "data" / "TUD-Campus"
    return read_mot(folder / "gt.txt"), read_mot(folder / "test.txt")


def test_clear_mot_and_idf1_match_py_motmetrics_on_tud_campus() -> None:
    gt, test = _tud_campus()
    clear = clear_mot(gt, test)
    # Figures py-motmetrics 1.4.0 asserts for this sequence (its test_motchallenge_files).
    assert (clear.false_positives, clear.misses, clear.id_switches) == (13, 150, 7)
    assert clear.mota == pytest.approx(0.526462, abs=1e-6)
    assert clear.motp == pytest.approx(0.277201, abs=1e-6)
    assert clear.recall == pytest.approx(0.582173, abs=1e-6)
    assert clear.precision == pytest.approx(0.941441, abs=1e-6)
    assert idf1(gt, test) == pytest.approx(0.557659, abs=1e-6)


def _rows(boxes: dict[tuple[int, int], tuple[float, float, float, float]]) -> np.ndarray:
    return np.array([(f, i, *b) for (f, i), b in sorted(boxes.items())], dtype=float)


def test_perfect_tracking_scores_one() -> None:
    truth = _rows({(f, i): (10.0 * i + f, 5.0, 8.0, 8.0) for f in range(1, 11) for i in (1, 2)})
    assert clear_mot(truth, truth).mota == 1.0 and idf1(truth, truth) == 1.0
    assert hota(truth, truth) == pytest.approx(1.0)
    renamed = truth.copy()
    renamed[:, 1] += 100
    assert hota(truth, renamed) == pytest.approx(1.0) and idf1(truth, renamed) == 1.0


def test_identity_swap_halfway() -> None:
    truth = _rows({(f, i): (30.0 * i, 0.0, 10.0, 10.0) for f in range(1, 11) for i in (1, 2)})
    swapped = truth.copy()
    later = swapped[:, 0] > 5
    swapped[later, 1] = 3 - swapped[later, 1]
    clear = clear_mot(truth, swapped)
    assert clear.id_switches == 2 and clear.mota == pytest.approx(1 - 2 / 20)
    assert idf1(truth, swapped) == pytest.approx(0.5)
    # Detection is perfect (DetA = 1); association halves: AssA = 0.5 * 1/3 + ... (HOTA = sqrt(AssA)).
    assert hota(truth, swapped) == pytest.approx(np.sqrt(1 / 3), abs=1e-9)


def test_missing_half_the_boxes() -> None:
    truth = _rows({(f, 1): (0.0, 0.0, 10.0, 10.0) for f in range(1, 11)})
    half = truth[truth[:, 0] <= 5]
    assert clear_mot(truth, half).mota == pytest.approx(0.5)
    assert idf1(truth, half) == pytest.approx(2 * 5 / 15)
    # DetA = 5 / 10, AssA = 5 / 10 at every threshold.
    assert hota(truth, half) == pytest.approx(0.5)


def test_iou() -> None:
    a = np.array([[0.0, 0.0, 10.0, 10.0]])
    b = np.array([[5.0, 0.0, 10.0, 10.0], [20.0, 20.0, 1.0, 1.0]])
    np.testing.assert_allclose(iou_matrix(a, b), [[50 / 150, 0.0]])
