"""Stage 3 on a stream: spatio-temporal patterns of a video's plane graphs as they arrive.

With ``mining_window > 0`` (the default) the graphs are mined window by window while later frames
are still being segmented, and the windows are stitched (:mod:`trap_core.mining.windows`):
memory holds one window's face sets instead of the whole video's. With ``mining_window = 0`` the
whole video is mined at once, at the end, as the paper does.
"""
from __future__ import annotations

import dataclasses
import time

from trap_core.mining import MiningParams, MiningResult, WindowedMiner, mine, mine_auto
from trap_core.pipeline.params import TrapParams
from trap_core.rag import LabelMemory, PlaneGraph


class PatternMiner:
    """Feed it every frame's graph with :meth:`add`; :meth:`finish` returns the patterns.

    ``n_frames`` (when known in advance) turns frequencies given as shares into frame counts;
    with windows they are shares of ``min(n_frames, mining_window)``, the span mined at once.
    """

    def __init__(self, params: TrapParams, n_frames: int | None = None) -> None:
        self.params = params
        self.seconds = 0.0
        self.freq_st_min = 0  # frames, once finished: fewer only where the video's ends cut a pattern
        self._graphs: list[PlaneGraph] = []
        self._windows: WindowedMiner | None = None
        self._labels = (LabelMemory(params.colour_bins) if params.method == "robust" and params.label_memory
                        else None)
        if params.mining_window > 0:
            span = min(n_frames, params.mining_window) if n_frames else params.mining_window
            self._windows = WindowedMiner(params.mining(span), params.mining_window,
                                          choose_params=self._auto_params if params.auto_frequency else None)

    def add(self, graph: PlaneGraph) -> None:
        start = time.perf_counter()
        if self._labels is not None:
            graph = self._labels(graph)
        if self._windows is None:
            self._graphs.append(graph)
        else:
            self._windows.add(graph)
        self.seconds += time.perf_counter() - start

    def finish(self) -> MiningResult:
        start = time.perf_counter()
        if self._windows is not None:
            mined = self._windows.finish()
            self.freq_st_min = self._windows.params.freq_st_min
        else:
            params = self.params.mining(len(self._graphs))
            if self.params.auto_frequency:
                mined, self.freq_st_min = mine_auto(self._graphs, params)
            else:
                mined, self.freq_st_min = mine(self._graphs, params), params.freq_st_min
            self._graphs = []
        self.seconds += time.perf_counter() - start
        return mined

    def _auto_params(self, graphs: list[PlaneGraph]) -> MiningParams:
        """The automatic frequency (the paper's rule of thumb), chosen on the first window."""
        params = self.params.mining(len(graphs))
        _, frequency = mine_auto(graphs, params)
        return dataclasses.replace(params, freq_st_min=frequency, freq_min=frequency)
