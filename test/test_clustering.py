"""Trajectories, the pattern distance, the lifetime cut, selection and tracks."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.cluster.hierarchy import linkage

from trap_core.clustering import (ClusteringError, Trajectories, build_track, cluster_patterns, labels_after_merges,
                                  lifetime_cut, observed_paths, pattern_distances, seen_frames, select_clusters,
                                  summarise, trajectories, twin_clusters)
from trap_core.mining import MiningResult


def _paths(segments: list[tuple[int, np.ndarray]]) -> Trajectories:
    starts = np.array([s for s, _ in segments])
    points = [np.asarray(p, dtype=float) for _, p in segments]
    ends = starts + np.array([len(p) for p in points]) - 1
    return Trajectories(starts, ends, np.r_[0, np.cumsum([len(p) for p in points])], np.concatenate(points))


def _naive_distance(a: tuple[int, np.ndarray], b: tuple[int, np.ndarray]) -> float:
    (sa, pa), (sb, pb) = a, b
    ea, eb = sa + len(pa) - 1, sb + len(pb) - 1
    fs, fe = max(sa, sb), min(ea, eb)
    if fe - fs <= 0:
        return np.inf
    d_traj = np.mean([np.linalg.norm(pa[t - sa] - pb[t - sb]) for t in range(fs, fe + 1)])
    d_ov = (fe - fs + 1) / (max(ea, eb) - min(sa, sb) + 1)
    return d_traj * (2 - d_ov)


def test_dense_gives_each_trajectory_point_in_its_span_and_nan_outside() -> None:
    """Many trajectories read at once in any frames (repeated rows too): each point where the
    trajectory has one, NaN before its first frame and after its last."""
    rng = np.random.default_rng(4)
    segments = [(int(rng.integers(0, 40)), rng.uniform(0, 100, size=(int(rng.integers(1, 30)), 2))) for _ in range(20)]
    paths = _paths(segments)
    rows, frames = np.array([3, 0, 3, 19, 7]), np.array([50, 2, 0, 31, 12, 69])
    points = paths.dense(rows, frames)
    assert points.shape == (5, 6, 2)
    for i, row in enumerate(rows):
        start, pts = segments[row]
        for j, frame in enumerate(frames):
            if start <= frame < start + len(pts):
                np.testing.assert_array_equal(points[i, j], pts[frame - start])
            else:
                assert np.isnan(points[i, j]).all()
    assert np.isnan(points).any() and not np.isnan(points).all()
    assert paths.dense(np.zeros(0, dtype=np.int64), frames).shape == (0, 6, 2)


def test_distance_matches_the_formula_and_the_papers_example() -> None:
    rng = np.random.default_rng(0)
    segments = [(int(rng.integers(0, 30)), rng.uniform(0, 100, size=(int(rng.integers(1, 25)), 2))) for _ in range(40)]
    condensed = pattern_distances(_paths(segments))
    expected = [_naive_distance(segments[i], segments[j]) for i in range(40) for j in range(i + 1, 40)]
    np.testing.assert_allclose(condensed, expected)
    # Fig. 2: A on frames 1..6, B on 4..8, distances a, b, c on the shared frames 4..6.
    a = (1, np.array([[0, 0]] * 6, dtype=float))
    b = (4, np.array([[3, 0], [4, 0], [5, 0], [9, 9], [9, 9]], dtype=float))
    assert pattern_distances(_paths([a, b]))[0] == pytest.approx((3 + 4 + 5) / 3 * (2 - 3 / 8))


def test_distance_bands_filled_on_threads_give_the_matrix_of_one_pass() -> None:
    from trap_core.clustering.distance import row_bands
    rng = np.random.default_rng(1)
    segments = [(int(rng.integers(0, 30)), rng.uniform(0, 100, size=(int(rng.integers(1, 25)), 2))) for _ in range(57)]
    paths = _paths(segments)
    one = pattern_distances(paths)
    for threads in (2, 3, 7, 100):
        np.testing.assert_array_equal(pattern_distances(paths, threads), one)
    for n in (0, 1, 2, 5, 57, 1000):
        for bands in (1, 2, 3, 8):
            bounds = row_bands(n, bands)
            assert bounds[0] == 0 and bounds[-1] == n and (n == 0 or np.all(np.diff(bounds) > 0))
            assert bounds.size - 1 <= bands
    pairs = [sum(999 - a for a in range(lo, hi)) for lo, hi in zip(*[row_bands(1000, 4)[i:] for i in (0, 1)])]
    assert max(pairs) - min(pairs) < 1000  # within one row's pairs of each other


def test_trajectories_average_and_interpolate() -> None:
    frames = np.array([2, 2, 5])
    positions = np.array([[0.0, 0.0], [2.0, 2.0], [4.0, 7.0]])
    result = MiningResult(np.array([1]), np.array([2]), np.array([1]), frames, np.zeros(3, np.int64), positions,
                          np.zeros((3, 4)), np.zeros((3, 4)), np.zeros((3, 1), np.int64), np.array([0]),
                          np.array([0, 3]), np.arange(3))
    paths = trajectories(observed_paths(result), np.arange(result.n_st))
    assert paths.start.tolist() == [2] and paths.end.tolist() == [5]
    np.testing.assert_allclose(paths.of(0), [[1, 1], [2, 3], [3, 5], [4, 7]])


def test_lifetime_cut_picks_the_most_stable_level() -> None:
    # Three tight groups of 5 points, far apart: the 3-cluster level lives longest.
    rng = np.random.default_rng(1)
    points = np.concatenate([rng.normal(centre, 0.1, size=(5, 2)) for centre in ((0, 0), (10, 0), (0, 30))])
    matrix = linkage(points, "average")
    assert lifetime_cut(matrix, 15, ignore_top=0.1) == 3
    labels = labels_after_merges(matrix, 15, 12)
    assert sorted(np.bincount(labels).tolist()) == [5, 5, 5]
    assert labels[0] == 0  # clusters numbered by their first member


def test_lifetime_cut_ignores_outliers_merging_at_the_top() -> None:
    rng = np.random.default_rng(2)
    points = np.concatenate([rng.normal(0, 0.1, size=(10, 2)), rng.normal(5, 0.1, size=(10, 2)), [[1000.0, 1000.0]]])
    matrix = linkage(points, "average")
    # Without the rule, the outlier level (2 clusters) wins; ignoring levels 1..0.1n (1, 2), the groups do.
    assert lifetime_cut(matrix, 21, ignore_top=0.0) == 2
    level = lifetime_cut(matrix, 21, ignore_top=0.1)
    # The longest-lived cluster is the group completed first; the cut is where it was created,
    # so the other group may still be in two pieces, but groups never mix.
    assert level in (3, 4)
    labels = labels_after_merges(matrix, 21, 21 - level)
    assert not set(labels[:10]) & set(labels[10:20]) and labels[20] not in set(labels[:20])


def test_infinite_distances_get_a_finite_stand_in() -> None:
    condensed = np.array([1.0, np.inf, np.inf])  # 0-1 close, 2 shares no frames with them
    hierarchy = cluster_patterns(condensed, 3)
    assert np.isfinite(hierarchy.linkage[:, 2]).all() and hierarchy.linkage[-1, 2] == 3.0
    with pytest.raises(ClusteringError, match="linkage"):
        cluster_patterns(condensed, 3, method="ward")


def test_selection_longest_then_most_patterns_then_occurrences() -> None:
    # Cluster 0: frames 0-99 (1 pattern); cluster 1: 0-95 (3 patterns); cluster 2: 0-49.
    paths = _paths([(0, np.zeros((100, 2))), (0, np.full((96, 2), 200.0)), (0, np.full((96, 2), 200.0)),
                    (0, np.full((96, 2), 200.0)), (0, np.full((50, 2), 400.0))])
    labels = np.array([0, 1, 1, 1, 2])
    summary = summarise(labels, paths, np.array([10, 5, 5, 5, 50]), 100)
    assert summary.length.tolist() == [100, 96, 50]
    # Within 10 % of the longest, the one with most patterns wins.
    assert select_clusters(summary, 100, n_objects=1) == [1]
    assert select_clusters(summary, 100, n_objects=2) == [1, 0]
    assert select_clusters(summary, 100, n_objects=1, tolerance=0.0) == [0]
    # Unsupervised: all three are long enough (>= 25 %) and far apart.
    assert select_clusters(summary, 100) == [1, 0, 2]
    assert select_clusters(summary, 100, min_length=0.6) == [1, 0]
    # A cluster whose path runs within `separation` of a kept one is the same object.
    near = _paths([(0, np.zeros((100, 2))), (0, np.full((90, 2), 10.0))])
    summary = summarise(np.array([0, 1]), near, np.array([1, 1]), 100)
    assert select_clusters(summary, 100, separation=40.0) == [0]
    assert select_clusters(summary, 100, separation=5.0) == [0, 1]


def test_selection_rejects_a_chain_of_fragments_on_kept_objects() -> None:
    """Cluster 2 follows object 0 for 40 frames, then object 1 for 40 frames: its mean distance to
    each is large (it is far from each half the time), but in every frame it is on a kept one."""
    a, b = np.zeros((100, 2)), np.full((100, 2), 300.0)
    chain = np.r_[np.zeros((40, 2)), np.full((20, 2), 150.0), np.full((40, 2), 300.0)]
    paths = _paths([(0, a), (0, b), (0, chain[:40]), (60, chain[60:])])
    summary = summarise(np.array([0, 1, 2, 2]), paths, np.ones(4), 100)
    assert select_clusters(summary, 100, min_length=0.3) == [0, 1]
    alone = _paths([(0, a), (0, np.full((80, 2), 150.0))])  # far from the kept one all along
    summary = summarise(np.array([0, 1]), alone, np.ones(2), 100)
    assert select_clusters(summary, 100, min_length=0.3) == [0, 1]


def test_selection_by_own_frames_prefers_a_cluster_of_its_own_to_a_chain() -> None:
    """Cluster 1 follows kept cluster 0 for 40 frames, then object 1 for 60; cluster 2 is object
    1 for 90 frames, 50 of them beside the chain. By all frames the chain comes first (and then
    cluster 2 is mostly near it); by own frames cluster 2 does (and then the chain has 10 left)."""
    a = np.zeros((100, 2))
    chain = np.r_[np.zeros((40, 2)), np.full((60, 2), 300.0)]
    paths = _paths([(0, a), (0, a), (0, a), (0, chain), (0, np.full((90, 2), 300.0))])
    summary = summarise(np.array([0, 0, 0, 1, 2]), paths, np.ones(5), 100)
    assert select_clusters(summary, 100) == [0, 1]
    assert select_clusters(summary, 100, own_frames=True) == [0, 2]
    assert select_clusters(summary, 100, n_objects=2, own_frames=True) == [0, 1]  # the paper's rule: longest


def test_unsupervised_selection_asks_a_cluster_to_be_seen_not_only_to_span() -> None:
    """Cluster 1 spans 57 frames but has occurrences in 8 of them (one pattern seen now and
    then): with the frames it is seen in, it is no track; the paper's count by ``n_objects``
    still takes it."""
    frames = np.r_[np.arange(100), np.arange(20, 80, 8)]
    result = MiningResult(np.array([1, 2]), np.array([100, 8]), np.array([1, 1]), frames,
                          np.r_[np.zeros(100, int), np.ones(8, int)], np.r_[np.zeros((100, 2)), np.full((8, 2), 300.0)],
                          np.zeros((108, 4)), np.zeros((108, 4)), np.zeros((108, 1), np.int64), np.array([0, 1]),
                          np.array([0, 100, 108]), np.arange(108))
    seen = seen_frames(result, np.array([0, 1]), np.array([0, 1]))
    assert seen.tolist() == [100, 8]
    summary = summarise(np.array([0, 1]), trajectories(observed_paths(result), np.arange(2)), np.array([100, 8]), 100)
    assert summary.length.tolist() == [100, 57]
    assert select_clusters(summary, 100, separation=5.0) == [0, 1]
    assert select_clusters(summary, 100, separation=5.0, seen=seen) == [0]
    assert select_clusters(summary, 100, n_objects=2, seen=seen) == [0, 1]


def _seen_every(step: int, place: np.ndarray) -> MiningResult:
    """Pattern 0 seen in all of 100 frames at (0, 0); pattern 1 every ``step`` frames at ``place``
    (one position per frame, (100, 2))."""
    rare = np.arange(0, 100, step)
    frames = np.r_[np.arange(100), rare]
    n = frames.size
    return MiningResult(np.array([1, 2]), np.array([100, rare.size]), np.array([1, 1]), frames,
                        np.r_[np.zeros(100, int), np.ones(rare.size, int)], np.r_[np.zeros((100, 2)), place[rare]],
                        np.zeros((n, 4)), np.zeros((n, 4)), np.zeros((n, 1), np.int64), np.array([0, 1]),
                        np.array([0, 100, n]), np.arange(n))


def test_a_cluster_seen_in_half_the_frames_asked_is_a_track_only_apart_from_the_others() -> None:
    """With own frames, cluster 1 (seen in 15 frames, 0.15 of the video, under ``min_length``
    0.25 but over half of it) is taken after cluster 0 while it keeps its distance in three
    quarters of its frames (passing cluster 0 in a fifth of them, as where a track trades onto
    its object for a while); passing it in half of them it is not (more likely a fragment of
    cluster 0's object), and seen in 9 frames it never is."""
    apart = np.full((100, 2), 300.0)
    passing_a_fifth, passing_a_half = apart.copy(), apart.copy()
    passing_a_fifth[40:60] = 5.0
    passing_a_half[20:70] = 5.0
    for place, step, expected in ((apart, 7, [0, 1]), (passing_a_fifth, 7, [0, 1]), (passing_a_half, 7, [0]),
                                  (apart, 12, [0])):
        result = _seen_every(step, place)
        seen = seen_frames(result, np.array([0, 1]), np.array([0, 1]))
        summary = summarise(np.array([0, 1]), trajectories(observed_paths(result), np.arange(2)),
                            np.bincount(result.occ_pattern), 100)
        assert summary.length[1] >= 25
        assert select_clusters(summary, 100, separation=40.0, own_frames=True, seen=seen) == expected
        assert select_clusters(summary, 100, separation=40.0, seen=seen) == [0]  # without own frames: as asked


def test_occurrences_cut_by_the_view_do_not_count_as_seen() -> None:
    """Pattern 0 (cluster 0): 60 occurrences inside a 640x480 view, then 40 with the frame's box
    (the backdrop); pattern 1 (cluster 1): 20 at the left edge. With the view, cluster 0 is seen
    in 60 frames and cluster 1 in none; with pattern 1's boxes placed otherwise (``boxes``:
    without the backdrop, inside the view), in its 20."""
    inside, frame_box, at_edge = [100, 100, 150, 150], [0, 0, 639, 479], [0, 200, 50, 250]
    box = np.array([inside] * 60 + [frame_box] * 40 + [at_edge] * 20, dtype=np.float32)
    frames = np.r_[np.arange(100), np.arange(20)]
    result = MiningResult(np.array([1, 2]), np.array([100, 20]), np.array([1, 1]), frames,
                          np.r_[np.zeros(100, int), np.ones(20, int)], np.zeros((120, 2)), box, box,
                          np.zeros((120, 1), np.int64), np.array([0, 1]), np.array([0, 100, 120]), np.arange(120))
    patterns, labels = np.array([0, 1]), np.array([0, 1])
    assert seen_frames(result, patterns, labels).tolist() == [100, 20]
    assert seen_frames(result, patterns, labels, (640, 480)).tolist() == [60, 0]
    placed = box.copy()
    placed[100:] = [10, 200, 60, 250]
    assert seen_frames(result, patterns, labels, (640, 480), placed).tolist() == [60, 20]


def test_twin_clusters_are_beside_a_kept_one_with_frames_it_lacks() -> None:
    """Cluster 1 holds kept cluster 0's object and goes on 40 frames after it ends; cluster 2 is
    near it for 20 frames only; cluster 3 is kept. In a video of 120 frames, 40 new frames are
    under ``min_new`` = 41; where the video ends with them (100 frames), half as many do, as the
    video cut the object's time short."""
    paths = _paths([(0, np.zeros((60, 2))), (0, np.full((100, 2), 5.0)), (0, np.r_[np.zeros((20, 2)),
                    np.full((80, 2), 200.0)]), (0, np.full((100, 2), 400.0))])
    summary = summarise(np.arange(4), paths, np.ones(4), 120)
    assert twin_clusters(summary, [3, 0], 120, 0.25, 40.0, min_new=25) == [1]
    assert twin_clusters(summary, [3, 0], 120, 0.25, 40.0, min_new=41) == []
    assert twin_clusters(summary, [3, 0], 120, 0.25, 40.0, 25, eligible=np.array([1, 0, 1, 1], bool)) == []
    at_end = summarise(np.arange(4), paths, np.ones(4), 100)
    assert twin_clusters(at_end, [3, 0], 100, 0.25, 40.0, min_new=41) == [1]
    assert twin_clusters(at_end, [3, 0], 100, 0.25, 40.0, min_new=81) == []


def test_track_boxes_and_scores() -> None:
    frames = np.array([0, 0, 1])
    boxes = np.array([[10, 10, 19, 19], [15, 5, 30, 12], [0, 0, 4, 4]], dtype=float)
    result = MiningResult(np.array([1, 2]), np.array([2, 1]), np.array([1, 1]), frames, np.array([0, 1, 0]),
                          np.zeros((3, 2)), boxes, boxes, np.zeros((3, 1), np.int64), np.array([0, 1]),
                          np.array([0, 2, 3]), np.array([0, 2, 1]))
    track = build_track(result, np.array([0, 0]), 0, track_id=7)
    assert track.track_id == 7 and track.frames.tolist() == [0, 1]
    np.testing.assert_array_equal(track.boxes, [[10, 5, 21, 15], [0, 0, 5, 5]])
    np.testing.assert_array_equal(track.score, [1.0, 0.5])


def test_centre_inside_takes_the_smaller_boxs_centre_in_the_larger() -> None:
    """A box half as large 8 px off a 40x30 box's centre holds its object (IoU 0.25); one whose
    centre is 25 px off does not; either order, and never with an absent (NaN) box."""
    from trap_core.clustering import box_iou, centre_inside
    large = np.array([100.0, 200.0, 40.0, 30.0])
    near = np.array([118.0, 207.5, 20.0, 15.0])
    far = near + [25.0, 0.0, 0.0, 0.0]
    assert box_iou(near, large) < 0.5
    assert centre_inside(near, large) and centre_inside(large, near)
    assert not centre_inside(far, large) and not centre_inside(large, far)
    assert centre_inside(np.array([near, far]), large).tolist() == [True, False]
    assert not centre_inside(np.full(4, np.nan), large)


def test_sets_sharing_a_node_are_one_component() -> None:
    """The compiled union of node sets groups them as a graph's connected components do."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import connected_components

    from trap_core.clustering._kernels import sharing_components
    rng = np.random.default_rng(2)
    for _ in range(50):
        sets = [np.unique(rng.integers(0, 30, size=rng.integers(1, 4))) for _ in range(rng.integers(1, 12))]
        nodes, ends = np.concatenate(sets), np.cumsum([s.size for s in sets])
        holder = np.repeat(np.arange(len(sets)), [s.size for s in sets])
        incidence = csr_matrix((np.ones(nodes.size), (holder, nodes)), shape=(len(sets), 30))
        _, expected = connected_components(incidence @ incidence.T, directed=False)
        found = sharing_components(nodes, ends, 30)
        assert found.max() == expected.max()
        assert np.array_equal(found[:, None] == found, expected[:, None] == expected)
