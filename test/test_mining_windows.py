"""Windowed mining: stitched windows give the whole video's spatio-temporal patterns."""
from __future__ import annotations

import numpy as np
import pytest

from trap_core.mining import MiningError, MiningParams, WindowedMiner, mine
from trap_core.rag import build_plane_graph
from trap_core.segmentation import colour_components
from trap_core.synthetic import SceneConfig, render


@pytest.fixture(scope="module")
def graphs():
    frames = [f.rgb for f in render(SceneConfig(width=320, height=240, frames=150, seed=2))]
    return [build_plane_graph(*colour_components(rgb), rgb) for rgb in frames]


def _patterns(result) -> set[frozenset]:
    """Each spatio-temporal pattern as the set of its occurrences' identities."""
    return {frozenset((int(result.occ_frame[r]), int(result.pattern_hash[result.occ_pattern[r]]),
                       tuple(result.occ_faces[r].tolist())) for r in result.st(s)) for s in range(result.n_st)}


def _windowed(graphs, params: MiningParams, window: int, overlap: int):
    miner = WindowedMiner(params, window, overlap)
    for graph in graphs:
        miner.add(graph)
    return miner.finish(), miner.windows_mined


def test_windows_give_the_whole_videos_components_when_every_pattern_is_frequent(graphs) -> None:
    params = MiningParams(tau=10, freq_st_min=15, freq_min=1, max_faces=2)
    whole = mine(graphs, params)
    stitched, windows = _windowed(graphs, params, window=60, overlap=10)
    assert windows == 3
    assert _patterns(stitched) == _patterns(whole)
    np.testing.assert_array_equal(np.sort(stitched.freq_st()), np.sort(whole.freq_st()))
    first, last = (np.array([f(stitched.occ_frame[stitched.st(s)]) for s in range(stitched.n_st)]) for f in (np.min,
                                                                                                             np.max))
    assert np.sum((first < 50) & (last >= 110)) > 100  # patterns that continue through two window borders
    frames = stitched.occ_frame[stitched.st_rows]
    owner = np.repeat(np.arange(stitched.n_st), stitched.st_occurrences)
    assert np.all((np.diff(frames) >= 0) | (np.diff(owner) != 0))  # sorted by frame in each pattern


def test_windows_keep_the_patterns_the_videos_ends_cut_as_the_whole_video_does(graphs) -> None:
    params = MiningParams(tau=10, freq_st_min=40, freq_min=1, max_faces=2, freq_st_cut=12)
    whole = mine(graphs, params)
    stitched, windows = _windowed(graphs, params, window=60, overlap=10)
    assert windows == 3
    assert _patterns(stitched) == _patterns(whole)
    assert (whole.freq_st() < 40).any()  # patterns kept only as the video's ends cut them


def test_one_window_is_the_plain_miner(graphs) -> None:
    params = MiningParams(tau=10, freq_st_min=15, max_faces=2, linking="assignment")
    stitched, windows = _windowed(graphs, params, window=500, overlap=10)
    assert windows == 1
    assert _patterns(stitched) == _patterns(mine(graphs, params))


def test_stitched_assignment_paths_stay_one_occurrence_per_frame(graphs) -> None:
    params = MiningParams(tau=10, freq_st_min=15, freq_min=1, max_faces=2, linking="assignment")
    whole = _patterns(mine(graphs, params))
    stitched, _ = _windowed(graphs, params, window=60, overlap=10)
    for s in range(stitched.n_st):
        frames = stitched.occ_frame[stitched.st(s)]
        assert frames.size == np.unique(frames).size
    assert len(_patterns(stitched) & whole) >= 0.98 * len(whole)


def test_window_frequencies_prune_only_patterns_rare_in_a_window(graphs) -> None:
    params = MiningParams(tau=10, freq_st_min=15, max_faces=2)
    whole = mine(graphs, params)
    stitched, _ = _windowed(graphs, params, window=60, overlap=10)
    assert set(stitched.pattern_hash.tolist()) <= set(whole.pattern_hash.tolist())
    assert len(_patterns(stitched) & _patterns(whole)) >= 0.85 * whole.n_st
    assert stitched.freq_st().min() >= 15


def test_short_and_empty_streams(graphs) -> None:
    params = MiningParams(tau=10, freq_st_min=3, freq_min=1, max_faces=2)
    empty = WindowedMiner(params, 60, 10).finish()
    assert empty.n_st == 0 and empty.occ_frame.size == 0
    for frames in (60, 65):  # a last window with nothing new, and one with 5 new frames
        stitched, windows = _windowed(graphs[:frames], params, window=60, overlap=10)
        assert windows == (1 if frames == 60 else 2)
        assert _patterns(stitched) == _patterns(mine(graphs[:frames], params))


@pytest.mark.parametrize("window, overlap", [(60, 5), (20, 10), (0, 10)])
def test_bad_windows(window: int, overlap: int) -> None:
    with pytest.raises(MiningError):
        WindowedMiner(MiningParams(tau=10), window, overlap)


def test_automatic_frequency_is_chosen_on_the_first_window(graphs) -> None:
    from trap_core.mining import mine_auto
    from trap_core.pipeline import PatternMiner, TrapParams
    params = TrapParams(segmentation="colour", tau=10, freq_st_min=30, max_faces=2, auto_frequency=True,
                        mining_window=60, freq_st_cut=0)
    miner = PatternMiner(params, len(graphs))
    for graph in graphs:
        miner.add(graph)
    stitched = miner.finish()
    _, frequency = mine_auto(graphs[:60], params.mining(60))
    assert miner._windows.params.freq_st_min == miner._windows.params.freq_min == miner.freq_st_min == frequency < 30
    assert stitched.n_st > 0 and stitched.freq_st().min() >= frequency
