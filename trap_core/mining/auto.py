"""Choose the frequencies automatically (TRAP_SPEC section 3: the paper's rule of thumb).

The paper set ``freq = freq_st`` by hand so that the number of spatio-temporal patterns lands
in 600..2000, with ``freq_st`` at most 20 % of the video. Here: mine at a starting threshold;
if that yields too many patterns, raise the threshold by filtering the result (exact, no
re-mining); if too few, halve it and mine again.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence

from trap_core.mining.miner import mine
from trap_core.mining.params import MiningParams
from trap_core.mining.result import MiningResult
from trap_core.rag import PlaneGraph

TARGET = (600, 2000)
MAX_SHARE = 0.2


def mine_auto(graphs: Sequence[PlaneGraph], params: MiningParams, target: tuple[int, int] = TARGET,
              on_frame: Callable[[int], None] | None = None) -> tuple[MiningResult, int]:
    """Mine with ``freq = freq_st = f`` chosen so the pattern count lands in ``target``.

    ``params.freq_st_min`` is the starting ``f``. Returns the result and the ``f`` used.
    """
    ceiling = max(1, int(MAX_SHARE * len(graphs)))
    frequency = min(params.freq_st_min, ceiling)
    while True:
        result = mine(graphs, dataclasses.replace(params, freq_st_min=frequency, freq_min=frequency), on_frame=on_frame)
        if result.n_st >= target[0] or frequency == 1:
            break
        frequency = max(1, frequency // 2)
    while result.n_st > target[1] and frequency < ceiling:
        step = max(1, frequency // 8)
        frequency = min(ceiling, frequency + step)
        result = result.above(frequency, frequency)
    return result, frequency
