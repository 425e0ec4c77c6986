"""Shared fixtures: small synthetic videos and bags, written once per test session."""
from __future__ import annotations

import os
import sys
from pathlib import Path

import pytest

from trap_core.synthetic import SceneConfig, write_synthetic

os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")


@pytest.fixture(scope="session")
def small_scene() -> SceneConfig:
    """A short Anim2-like video: 120 frames at 320x240 (objects cross; one leaves the view)."""
    return SceneConfig(width=320, height=240, frames=120, seed=3)


@pytest.fixture(scope="session")
def small_bag(tmp_path_factory: pytest.TempPathFactory, small_scene: SceneConfig) -> Path:
    bag, _ = write_synthetic(small_scene, tmp_path_factory.mktemp("bags") / "small")
    return bag


@pytest.fixture(scope="session")
def benchmark_module():
    """Loader of a benchmark script (``benchmarks/NAME.py``) as a module, for tests of its parts:
    the scripts are not a package."""
    import importlib.util

    def load(name: str):
        path = Path(__file__).resolve().parents[1] / "benchmarks" / f"{name}.py"
        spec = importlib.util.spec_from_file_location(f"{name}_benchmark", path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    return load


@pytest.fixture(scope="session")
def venv_bin() -> Path:
    """Folder of the console scripts installed beside the running interpreter."""
    return Path(sys.executable).parent


@pytest.fixture(scope="session")
def textured_frames() -> list:
    """Six frames of a camera panning down over grass (160x120): at the paper's k, about 170
    regions each (a textured scene)."""
    import cv2
    import numpy as np
    import skimage.data
    grass = np.repeat(skimage.data.grass()[..., None], 3, axis=2)
    return [cv2.resize(grass[4 * t:4 * t + 240, :320], (160, 120), interpolation=cv2.INTER_AREA) for t in range(6)]
