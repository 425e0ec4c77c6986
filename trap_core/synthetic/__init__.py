"""Synthetic benchmark videos with exact ground truth (analogues of the paper's Anim1/Anim2)."""

from trap_core.synthetic.scene import PRESETS, RenderedFrame, SceneConfig, build_world, light_gain, render
from trap_core.synthetic.video import write_synthetic

__all__ = ["PRESETS", "RenderedFrame", "SceneConfig", "build_world", "light_gain", "render", "write_synthetic"]
