"""The miner against a brute-force oracle: face sets, plane isomorphism, frequencies, components."""
from __future__ import annotations

import dataclasses
import itertools
from collections import defaultdict

import networkx as nx
import numpy as np
import pytest
from networkx.algorithms.isomorphism import DiGraphMatcher

from trap_core.mining import MiningError, MiningParams, mine
from trap_core.mining.reference import (Occurrences, canonical_code, connected_face_sets, face_table, mine_reference,
                                        occurrence_components)
from trap_core.rag import build_plane_graph
from trap_core.segmentation._kernels import relabel_4connected


def _random_graph(rng: np.random.Generator, size: int = 9, labels: int = 5):
    """A random plane graph: blocky random regions, node labels from 2 colours (so patterns repeat)."""
    coarse = rng.integers(0, labels, size=(size // 3 + 1, size // 3 + 1))
    fine = np.kron(coarse, np.ones((3, 3), dtype=np.int64))[:size, :size]
    fine = np.where(rng.random(fine.shape) < 0.15, rng.integers(0, labels, fine.shape), fine)
    region, n = relabel_4connected(fine.astype(np.int32))
    palette = np.array([[30, 30, 30], [220, 220, 220]], dtype=np.uint8)
    colour_of_region = rng.integers(0, 2, size=n)
    rgb = palette[colour_of_region[region]]
    return build_plane_graph(region, n, rgb, colour_bins=2)


def _adjacent(graph, f: int, g: int) -> bool:
    ring = graph.face_half_edges[graph.face_offsets[f]:graph.face_offsets[f + 1]]
    return any(graph.face_of[graph.he_twin[h]] == g for h in ring)


def _brute_force_sets(graph, faces: list[int], max_faces: int) -> set[frozenset[int]]:
    found = set()
    for size in range(1, max_faces + 1):
        for subset in itertools.combinations(faces, size):
            component = {subset[0]}
            grew = True
            while grew:
                grew = False
                for f in subset:
                    if f not in component and any(_adjacent(graph, f, g) for g in component):
                        component.add(f)
                        grew = True
            if len(component) == size:
                found.add(frozenset(subset))
    return found


def _plane_digraph(graph, faces: frozenset[int]) -> nx.DiGraph:
    """Half-edges of the face set, with face successor, twin and same-origin relations."""
    ring = [int(h) for f in faces for h in graph.face_half_edges[graph.face_offsets[f]:graph.face_offsets[f + 1]]]
    digraph = nx.DiGraph()
    for h in ring:
        twin = int(graph.he_twin[h])
        digraph.add_node(h, label=int(graph.label[graph.he_origin[h]]), open=graph.face_of[twin] not in faces)
    kinds: dict[tuple[int, int], set[str]] = defaultdict(set)
    for h in ring:
        twin = int(graph.he_twin[h])
        kinds[(h, int(graph.he_next[twin]))].add("next")
        if graph.face_of[twin] in faces:
            kinds[(h, twin)].add("twin")
        for other in ring:
            if other != h and graph.he_origin[other] == graph.he_origin[h]:
                kinds[(h, other)].add("same")
    for (a, b), names in kinds.items():
        digraph.add_edge(a, b, kinds=tuple(sorted(names)))
    return digraph


def _isomorphic(a: nx.DiGraph, b: nx.DiGraph) -> bool:
    if a.number_of_nodes() != b.number_of_nodes() or a.number_of_edges() != b.number_of_edges():
        return False
    return DiGraphMatcher(a, b, node_match=lambda x, y: x == y, edge_match=lambda x, y: x == y).is_isomorphic()


@pytest.mark.parametrize("seed", range(6))
def test_connected_face_sets_are_all_and_only_the_connected_ones(seed: int) -> None:
    graph = _random_graph(np.random.default_rng(seed))
    table = face_table(graph)
    allowed = {int(f) for f in table.inner}
    enumerated = list(connected_face_sets(table, allowed, 3))
    assert len(enumerated) == len(set(enumerated))
    assert set(enumerated) == _brute_force_sets(graph, sorted(allowed), 3)


def test_canonical_codes_decide_plane_isomorphism_like_the_oracle() -> None:
    rng = np.random.default_rng(42)
    occurrences = []
    for _ in range(6):
        graph = _random_graph(rng)
        table = face_table(graph)
        for faces in connected_face_sets(table, {int(f) for f in table.inner}, 2):
            occurrences.append((canonical_code(graph, faces), _plane_digraph(graph, faces)))
    assert len(occurrences) > 80
    by_code = defaultdict(list)
    for code, digraph in occurrences:
        by_code[code].append(digraph)
    representatives = [group[0] for group in by_code.values()]
    for group in by_code.values():  # same code => isomorphic
        assert all(_isomorphic(group[0], other) for other in group[1:])
    for a, b in itertools.combinations(range(len(representatives)), 2):  # different codes => not
        assert not _isomorphic(representatives[a], representatives[b])


def test_rotating_the_image_keeps_codes_mirroring_changes_chiral_ones() -> None:
    """Rotation renumbers every region and every start; codes stay. A mirror flips orientation."""
    labels = np.array([[0, 0, 1, 1, 1],
                       [0, 0, 1, 1, 1],
                       [2, 2, 2, 3, 3],
                       [2, 2, 2, 3, 3],
                       [4, 4, 4, 4, 4]])
    palette = np.array([[250, 0, 0], [0, 250, 0], [0, 0, 250], [250, 250, 0], [0, 250, 250]], dtype=np.uint8)

    def codes(image: np.ndarray) -> set[tuple[int, ...]]:
        region, n = relabel_4connected(np.ascontiguousarray(image, dtype=np.int32))
        first_pixel = {int(region.ravel()[i]): int(image.ravel()[i]) for i in range(image.size)}
        rgb = palette[np.vectorize(first_pixel.get)(region)]
        graph = build_plane_graph(region, n, rgb, colour_bins=2)
        table = face_table(graph)
        return {canonical_code(graph, s) for s in connected_face_sets(table, {int(f) for f in table.inner}, 3)}

    original = codes(labels)
    assert original and codes(np.rot90(labels, 2)) == original
    assert codes(np.rot90(labels, 1)) == original
    assert codes(labels[:, ::-1]) != original  # a triangle of three colours is chiral


def _naive_components(frames: np.ndarray, positions: np.ndarray, eps: float, tau: int) -> set[frozenset[int]]:
    parent = list(range(len(frames)))

    def find(i: int) -> int:
        while parent[i] != i:
            i = parent[i]
        return i
    for i, j in itertools.combinations(range(len(frames)), 2):
        if 0 < abs(frames[i] - frames[j]) <= tau and np.hypot(*(positions[i] - positions[j])) <= eps:
            parent[find(i)] = find(j)
    groups = defaultdict(set)
    for i in range(len(frames)):
        groups[find(i)].add(i)
    return {frozenset(g) for g in groups.values()}


def test_occurrence_components_match_naive_linking() -> None:
    rng = np.random.default_rng(5)
    frames = rng.integers(0, 60, size=150)
    positions = rng.uniform(0, 200, size=(150, 2))
    occurrences = Occurrences(frames, positions, np.zeros((150, 4)), tuple(() for _ in range(150)))
    mine_components = {frozenset(int(i) for i in c) for c in occurrence_components(occurrences, 30.0, 5)}
    assert mine_components == _naive_components(frames, positions, 30.0, 5)


def test_same_frame_occurrences_are_not_linked() -> None:
    occurrences = Occurrences(np.array([0, 0]), np.array([[0.0, 0.0], [1.0, 0.0]]), np.zeros((2, 4)), ((), ()))
    assert len(occurrence_components(occurrences, 10.0, 3)) == 2


def test_mine_matches_brute_force_frequencies_and_components() -> None:
    rng = np.random.default_rng(11)
    graphs = [_random_graph(rng) for _ in range(8)]
    params = MiningParams(eps=6.0, tau=2, freq_st_min=2, freq_min=3, max_faces=2)
    result = mine_reference(graphs, params)
    # Oracle: every connected face set of every frame, grouped by plane isomorphism.
    classes: list[tuple[nx.DiGraph, list[tuple[int, frozenset[int]]]]] = []
    for t, graph in enumerate(graphs):
        table = face_table(graph)
        for faces in _brute_force_sets(graph, [int(f) for f in table.inner], 2):
            digraph = _plane_digraph(graph, faces)
            for representative, members in classes:
                if _isomorphic(representative, digraph):
                    members.append((t, faces))
                    break
            else:
                classes.append((digraph, [(t, faces)]))
    frequent = [members for _, members in classes if len({t for t, _ in members}) >= 3]
    assert sorted(len({t for t, _ in m}) for m in frequent) == sorted(result.frequency)
    expected = set()
    for members in frequent:
        frames = np.array([t for t, _ in members])
        positions = np.array([graphs[t].centroid[face_table(graphs[t]).nodes(f)].mean(axis=0) for t, f in members])
        for component in _naive_components(frames, positions, 6.0, 2):
            if len({int(frames[i]) for i in component}) >= 2:
                expected.add(frozenset((int(frames[i]), tuple(int(n) for n in face_table(graphs[int(frames[i])])
                                                              .nodes(members[i][1]))) for i in component))
    got = {frozenset(zip(p.occurrences.frame.tolist(), p.occurrences.nodes)) for p in result.patterns}
    assert frequent and expected
    assert got == expected


def test_bad_parameters() -> None:
    with pytest.raises(MiningError, match="eps"):
        MiningParams(eps=0)
    with pytest.raises(MiningError, match="at least 1"):
        MiningParams(tau=0)
    with pytest.raises(MiningError, match="freq_min"):
        MiningParams(freq_min=0)
    with pytest.raises(MiningError, match="freq_st_cut"):
        MiningParams(freq_st_cut=0)
    with pytest.raises(MiningError, match="threads"):
        MiningParams(threads=0)


def _node_sets(graphs, result) -> set[frozenset]:
    def nodes(graph, faces):
        return tuple(int(n) for n in np.unique(np.concatenate([graph.face_nodes(f) for f in faces if f >= 0])))
    return {frozenset((int(result.occ_frame[r]), nodes(graphs[result.occ_frame[r]], result.occ_faces[r]))
                      for r in result.st(s)) for s in range(result.n_st)}


@pytest.mark.parametrize("max_faces", [1, 2, 3])
def test_compiled_miner_equals_reference_on_random_graphs(max_faces: int) -> None:
    rng = np.random.default_rng(20 + max_faces)
    graphs = [_random_graph(rng, size=12) for _ in range(10)]
    params = MiningParams(eps=8.0, tau=3, freq_st_min=2, freq_min=3, max_faces=max_faces)
    reference = mine_reference(graphs, params)
    compiled = mine(graphs, params)
    assert sorted(compiled.pattern_frequency.tolist()) == sorted(reference.frequency)
    assert compiled.n_st == len(reference.patterns) > 0
    expected = {frozenset(zip(p.occurrences.frame.tolist(), p.occurrences.nodes)) for p in reference.patterns}
    assert _node_sets(graphs, compiled) == expected
    assert sorted(compiled.freq_st().tolist()) == sorted(p.freq_st for p in reference.patterns)


def test_compiled_miner_equals_reference_on_a_synthetic_video() -> None:
    from trap_core.segmentation import colour_components
    from trap_core.synthetic import SceneConfig, render
    frames = [f.rgb for f in render(SceneConfig(width=320, height=240, frames=30, seed=2))]
    graphs = [build_plane_graph(*colour_components(rgb), rgb) for rgb in frames]
    params = MiningParams(freq_st_min=8, max_faces=2)
    reference = mine_reference(graphs, params)
    compiled = mine(graphs, params, first_frame=100)
    assert compiled.n_patterns == len(reference.codes) and compiled.n_st == len(reference.patterns) > 50
    assert compiled.occ_frame.min() >= 100
    shifted = type(compiled)(**{**compiled.__dict__, "occ_frame": compiled.occ_frame - 100})
    expected = {frozenset(zip(p.occurrences.frame.tolist(), p.occurrences.nodes)) for p in reference.patterns}
    assert _node_sets(graphs, shifted) == expected
    # Geometry: the position is the mean barycentre of the occurrence's nodes, the box bounds its regions.
    row = compiled.st(0)[0]
    graph = graphs[compiled.occ_frame[row] - 100]
    nodes = np.unique(np.concatenate([graph.face_nodes(f) for f in compiled.occ_faces[row] if f >= 0]))
    np.testing.assert_allclose(compiled.occ_position[row], graph.centroid[nodes].mean(axis=0))
    np.testing.assert_array_equal(compiled.occ_box[row], [graph.bbox[nodes, 0].min(), graph.bbox[nodes, 1].min(),
                                                          graph.bbox[nodes, 2].max(), graph.bbox[nodes, 3].max()])


def test_threads_enumerate_frames_in_order_to_the_same_result() -> None:
    rng = np.random.default_rng(40)
    graphs = [_random_graph(rng, size=12) for _ in range(25)]
    params = MiningParams(eps=8.0, tau=3, freq_st_min=2, freq_min=3, max_faces=3)
    done: list[int] = []
    one = mine(graphs, params)
    several = mine(graphs, dataclasses.replace(params, threads=3), on_frame=done.append)
    assert done == list(range(1, 26))  # progress in frame order, every frame once
    assert one.n_st > 0
    for name in one.__dataclass_fields__:
        np.testing.assert_array_equal(getattr(several, name), getattr(one, name), err_msg=name)


def test_filtering_a_result_equals_mining_with_higher_thresholds() -> None:
    rng = np.random.default_rng(31)
    graphs = [_random_graph(rng, size=12) for _ in range(12)]
    low = mine(graphs, MiningParams(eps=8.0, tau=3, freq_st_min=2, freq_min=2, max_faces=2))
    high = mine(graphs, MiningParams(eps=8.0, tau=3, freq_st_min=4, freq_min=5, max_faces=2))
    assert high.n_st < low.n_st
    assert _node_sets(graphs, low.above(5, 4)) == _node_sets(graphs, high)


def test_patterns_the_videos_ends_cut_need_only_freq_st_cut_frames() -> None:
    rng = np.random.default_rng(31)
    graphs = [_random_graph(rng, size=12) for _ in range(16)]
    base = MiningParams(eps=8.0, tau=3, freq_st_min=6, freq_min=2, max_faces=2)
    every = mine(graphs, dataclasses.replace(base, freq_st_min=1))
    seen = every.freq_st()
    first = np.array([every.occ_frame[every.st(s)].min() for s in range(every.n_st)])
    last = np.array([every.occ_frame[every.st(s)].max() for s in range(every.n_st)])
    at_ends = (first < 3) | (last >= 13)
    cut_short = (seen < 6) & (seen >= 2) & at_ends
    inside_short = (seen < 6) & (seen >= 2) & ~at_ends
    assert cut_short.any() and inside_short.any()
    keep = (seen >= 6) | cut_short
    kept = type(every)(**{**every.__dict__, "st_pattern": every.st_pattern[keep],
                          "st_offsets": np.r_[0, np.cumsum(every.st_occurrences[keep])],
                          "st_rows": every.rows_of(np.flatnonzero(keep))[0]})
    assert _node_sets(graphs, mine(graphs, dataclasses.replace(base, freq_st_cut=2))) == _node_sets(graphs, kept)
    assert _node_sets(graphs, mine(graphs, base)) == _node_sets(graphs, every.above(2, 6))


def test_auto_frequency_lands_in_the_target_or_at_a_bound() -> None:
    from trap_core.mining import mine_auto
    from trap_core.segmentation import colour_components
    from trap_core.synthetic import SceneConfig, render
    frames = [f.rgb for f in render(SceneConfig(width=320, height=240, frames=60, seed=2))]
    graphs = [build_plane_graph(*colour_components(rgb), rgb) for rgb in frames]
    result, frequency = mine_auto(graphs, MiningParams(freq_st_min=30), target=(150, 400))
    assert 150 <= result.n_st <= 400 or frequency in (1, 12)
    assert frequency <= 12  # at most 20 % of the frames
    assert result.freq_st().min() >= frequency
