"""Plane region adjacency graphs: valid embeddings (Euler), faces, rotations, attributes."""
from __future__ import annotations

import cv2
import numpy as np
import pytest
import skimage.data

from trap_core.rag import GraphError, build_plane_graph
from trap_core.segmentation import colour_components, felzenszwalb
from trap_core.segmentation._kernels import relabel_4connected
from trap_core.synthetic import SceneConfig, render


def _graph(labels: np.ndarray, rgb: np.ndarray | None = None):
    labels, n = relabel_4connected(np.ascontiguousarray(labels, dtype=np.int32))
    rgb = np.zeros(labels.shape + (3,), dtype=np.uint8) if rgb is None else rgb
    return build_plane_graph(labels, n, rgb)


def _assert_valid_embedding(graph) -> None:
    assert graph.euler_characteristic() == 2
    half_edges = graph.he_twin.size
    assert np.array_equal(graph.he_twin[graph.he_twin], np.arange(half_edges))
    assert np.array_equal(np.sort(graph.he_next), np.arange(half_edges))  # a permutation
    assert np.array_equal(graph.he_origin[graph.he_next], graph.he_origin)  # rotation stays at its node
    assert np.array_equal(np.sort(graph.face_half_edges), np.arange(half_edges))  # each in one face
    # Consecutive half-edges of a face chain head to tail.
    for face in range(graph.n_faces):
        ring = graph.face_half_edges[graph.face_offsets[face]:graph.face_offsets[face + 1]]
        heads = graph.he_origin[graph.he_twin[ring]]
        assert np.array_equal(heads, graph.he_origin[np.roll(ring, -1)])
    # Without the outside node: one component, inner faces + 1 outer face.
    inner = (~graph.outer_faces()).sum()
    edges = graph.edges
    inner_edges = (edges < graph.n_nodes).all(axis=1).sum()
    assert graph.n_nodes - inner_edges + inner + 1 == 2


@pytest.mark.parametrize("seed", range(4))
def test_euler_on_synthetic_video_frames(seed: int) -> None:
    degrees = []
    for frame in render(SceneConfig(width=320, height=240, frames=60, seed=seed)):
        if frame.index % 10:
            continue
        labels, n = colour_components(frame.rgb)
        graph = build_plane_graph(labels, n, frame.rgb)
        _assert_valid_embedding(graph)
        degrees.append(graph.degree().mean())
    assert 3.4 < np.mean(degrees) < 4.5


def test_euler_on_random_label_images() -> None:
    rng = np.random.default_rng(1)
    for _ in range(300):
        height, width = rng.integers(1, 14, size=2)
        labels = rng.integers(0, rng.integers(1, 6), size=(height, width))
        _assert_valid_embedding(_graph(labels))


@pytest.mark.parametrize("name", ["astronaut", "coffee", "chelsea", "camera"])
def test_euler_on_natural_images(name: str) -> None:
    image = getattr(skimage.data, name)()
    image = cv2.cvtColor(image, cv2.COLOR_GRAY2RGB) if image.ndim == 2 else image
    image = cv2.resize(image, (320, 240), interpolation=cv2.INTER_AREA)
    for k in (5, 20):
        labels, n = felzenszwalb(image, k=k)
        _assert_valid_embedding(build_plane_graph(labels, n, image))


def test_region_enclosed_by_one_region() -> None:
    labels = np.zeros((7, 7), dtype=np.int32)
    labels[2:5, 2:5] = 1
    graph = _graph(labels)
    _assert_valid_embedding(graph)
    assert graph.degree().tolist() == [1, 1]
    assert graph.rotation(1).tolist() == [0]
    assert sorted(graph.rotation(0).tolist()) == [1, 2]  # the island and the outside


def test_single_region_image() -> None:
    graph = _graph(np.zeros((3, 4), dtype=np.int32))
    _assert_valid_embedding(graph)
    assert graph.n_nodes == 1 and graph.edges.tolist() == [[0, 1]]


def test_three_regions_meeting_make_an_inner_face_and_mirror_reverses_it() -> None:
    labels = np.zeros((8, 8), dtype=np.int32)
    labels[:, 4:] = 1
    labels[4:, :] = 2  # a T: 0 top-left, 1 top-right, 2 bottom
    graph = _graph(labels)
    inner = [graph.face_nodes(f).tolist() for f in range(graph.n_faces) if not graph.outer_faces()[f]]
    assert len(inner) == 1 and sorted(inner[0]) == [0, 1, 2]
    inner_face = int(np.flatnonzero(~graph.outer_faces())[0])
    np.testing.assert_array_equal(graph.faces_nodes(np.array([inner_face, -1])), [0, 1, 2])  # -1: padding
    mirrored = _graph(labels[:, ::-1])  # relabelled: 0 is now the top-left region (was 1)
    mirror_inner = [mirrored.face_nodes(f).tolist() for f in range(mirrored.n_faces) if not mirrored.outer_faces()[f]]

    def cyclic(seq: list[int]) -> list[int]:
        start = seq.index(min(seq))
        return seq[start:] + seq[:start]
    # Mapping old -> new ids (0<->1) and reading the face the other way round gives the same cycle.
    swapped = [{0: 1, 1: 0, 2: 2}[v] for v in inner[0]]
    assert cyclic(mirror_inner[0]) == cyclic(swapped[::-1])
    assert cyclic(mirror_inner[0]) != cyclic(swapped)


def test_rotation_follows_the_geometry() -> None:
    """Around the centre of a 3x3 block layout, neighbours come in circular order."""
    labels = np.repeat(np.repeat(np.arange(9).reshape(3, 3), 4, axis=0), 4, axis=1)
    graph = _graph(labels)
    ring = graph.rotation(4).tolist()
    assert sorted(ring) == [1, 3, 5, 7]
    start = ring.index(1)
    assert ring[start:] + ring[:start] in ([1, 5, 7, 3], [1, 3, 7, 5])


def test_two_separate_contacts_are_two_edges() -> None:
    labels = np.zeros((5, 9), dtype=np.int32)
    labels[1:4, 1:8] = 1
    labels[2, 1:8] = 2   # region 2 splits 1? no: 1 stays a ring-less pair of bars joined at the ends
    labels[1:4, 1] = 1
    labels[1:4, 7] = 1
    graph = _graph(labels)
    _assert_valid_embedding(graph)
    pairs = [tuple(sorted(e)) for e in graph.edges.tolist()]
    assert pairs.count((0, 1)) == 1  # the ring 1 meets 0 along one closed stretch
    assert pairs.count((1, 2)) == 1


def test_pinched_checkerboard() -> None:
    labels = np.array([[0, 1], [1, 0]])
    graph = _graph(np.kron(labels, np.ones((3, 3), dtype=int)))
    _assert_valid_embedding(graph)
    assert graph.n_nodes == 4


def test_node_attributes() -> None:
    rgb = np.zeros((10, 20, 3), dtype=np.uint8)
    rgb[:, 10:] = (250, 10, 10)
    labels, n = colour_components(rgb)
    graph = build_plane_graph(labels, n, rgb, colour_bins=4)
    right = labels[0, 15]
    assert graph.area[right] == 100
    assert graph.centroid[right].tolist() == [14.5, 4.5]
    assert graph.bbox[right].tolist() == [10, 0, 19, 9]
    assert graph.colour[right].tolist() == [250, 10, 10]
    assert graph.label[right] == 3 * 16


def test_grey_regions_get_finer_labels_than_colours() -> None:
    """A mono camera's regions are all grey: 100 and 120 share a level of four, not of sixteen."""
    from trap_core.rag import colour_label
    grey = colour_label(np.array([[100.0, 100.0, 100.0], [120.0, 120.0, 120.0]]), 4)
    assert grey.tolist() == [64 + 6, 64 + 7]
    assert colour_label(np.array([[100.0, 100.0, 101.0], [250.0, 10.0, 10.0]]), 4).tolist() == [21, 48]


def test_colour_levels_are_clipped_and_read_alike_from_float32() -> None:
    """Colours past either end of the range fall in the first or last level (a brightened mean can
    pass 256), and a graph's float32 colours get the labels of the same colours in float64."""
    from trap_core.rag import colour_label
    colours = np.array([[-3.0, 256.0, 300.0], [255.9, 255.9, 255.9], [-1.0, -1.0, -1.0], [63.99, 64.0, 127.5]])
    assert colour_label(colours, 4).tolist() == [3 + 3 * 4, 64 + 15, 64, 1 * 4 + 1]
    grid = np.random.default_rng(0).uniform(0, 256, (500, 3)).astype(np.float32)
    grid[::3] = grid[::3, :1]
    for bins in (2, 4, 8):
        assert np.array_equal(colour_label(grid, bins), colour_label(grid.astype(np.float64), bins))


def test_bad_input() -> None:
    with pytest.raises(GraphError, match="do not match"):
        build_plane_graph(np.zeros((3, 3), dtype=np.int32), 1, np.zeros((4, 3, 3), dtype=np.uint8))
    with pytest.raises(GraphError, match="unused labels"):
        build_plane_graph(np.zeros((3, 3), dtype=np.int32), 2, np.zeros((3, 3, 3), dtype=np.uint8))
    with pytest.raises(GraphError, match="colour_bins"):
        build_plane_graph(np.zeros((3, 3), dtype=np.int32), 1, np.zeros((3, 3, 3), dtype=np.uint8), colour_bins=0)


def test_contact_tolerance_makes_a_four_region_point_one_face_at_any_scale() -> None:
    """A 1-pixel notch turns the 4-face of four blocks into two triangles; the tolerance,
    relative to region size, restores the single face at two scales."""
    for size in (20, 48):
        labels = np.zeros((2 * size, 2 * size), dtype=np.int32)
        labels[:size, size:] = 1
        labels[size:, :size] = 2
        labels[size:, size:] = 3
        labels[size, size - 1] = 0  # pixel rounding: region 0 reaches down one pixel
        labels[size - 1, size] = 3 if size == 48 else 1  # a second, different rounding at the larger scale

        def inner_faces(tolerance: float) -> list[list[int]]:
            graph = build_plane_graph(*relabel_4connected(labels), np.zeros(labels.shape + (3,), np.uint8),
                                      contact_tolerance=tolerance)
            _assert_valid_embedding(graph)
            return [sorted(graph.face_nodes(f).tolist()) for f in range(graph.n_faces) if not graph.outer_faces()[f]]
        assert len(inner_faces(0.0)) == 2
        assert inner_faces(0.1) == [[0, 1, 2, 3]]


def test_contact_tolerance_keeps_embeddings_valid() -> None:
    rng = np.random.default_rng(9)
    for _ in range(200):
        height, width = rng.integers(2, 14, size=2)
        labels, n = relabel_4connected(rng.integers(0, 5, size=(height, width)).astype(np.int32))
        graph = build_plane_graph(labels, n, np.zeros((height, width, 3), np.uint8), contact_tolerance=0.7)
        _assert_valid_embedding(graph)
    with pytest.raises(GraphError, match="contact_tolerance"):
        build_plane_graph(labels, n, np.zeros((height, width, 3), np.uint8), contact_tolerance=-1)


def test_label_memory_keeps_labels_through_a_slow_drift_but_not_a_jump() -> None:
    from trap_core.pipeline import TrapParams, frame_graph
    from trap_core.rag import LabelMemory
    params = TrapParams(segmentation="colour")
    memory = LabelMemory()
    plain, kept = [], []
    for t in range(12):
        rgb = np.full((60, 80, 3), 30, np.uint8)
        red = 116 + 2 * t if t < 10 else 40  # drifts across the level boundary at 128, then jumps
        rgb[20:40, 20:50] = (red, 200, 30)
        graph = frame_graph(rgb, params)
        block = int(np.argmin(np.abs(graph.area - 600)))
        plain.append(int(graph.label[block]))
        kept.append(int(memory(graph).label[block]))
    assert len(set(plain[:10])) == 2 and len(set(kept[:10])) == 1  # quantised labels flip at 128; kept do not
    assert kept[10] == plain[10] != kept[9]  # a colour jump is a new label


def test_label_memory_labels_a_region_that_appears_under_the_first_frame_light() -> None:
    from trap_core.pipeline import TrapParams, frame_graph
    from trap_core.rag import LabelMemory, colour_label
    params = TrapParams(segmentation="colour")
    memory = LabelMemory(params.colour_bins)
    base = np.array([100.0, 150.0, 50.0])  # the object's colour under the first frame's light
    for t in range(31):
        gain = 1.0 + 0.01 * t  # the exposure rises 30 % (within 16 levels a frame)
        rgb = np.zeros((60, 80, 3), np.uint8)
        rgb[:, :40], rgb[:, 40:] = np.rint(np.multiply((60, 120, 180), gain)), np.rint(np.multiply((200, 100, 40), gain))
        if t == 30:  # the object comes into view late, under brighter light
            rgb[20:40, 30:50] = np.rint(base * gain)
        graph = memory(frame_graph(rgb, params))
    block = int(np.argmin(np.abs(graph.area - 400)))
    assert memory.gain == pytest.approx(1.3, abs=0.01)
    plain = colour_label(base[None] * 1.3, params.colour_bins)[0]
    assert graph.label[block] == colour_label(base[None], params.colour_bins)[0] != plain


def test_a_large_frame_is_segmented_at_the_working_size_with_geometry_in_its_own_pixels() -> None:
    from trap_core.pipeline import TrapParams, frame_graph
    big = np.full((960, 1280, 3), 40, np.uint8)
    big[100:300, 200:500] = (200, 30, 30)
    big[500:900, 700:1280] = (30, 200, 30)  # touches the right border
    graph = frame_graph(big, TrapParams(segmentation="colour", max_side=640))
    full = frame_graph(big, TrapParams(segmentation="colour", max_side=0))
    assert graph.n_nodes == full.n_nodes == 3 and graph.n_faces == full.n_faces
    order, full_order = np.argsort(graph.area), np.argsort(full.area)
    np.testing.assert_array_equal(graph.bbox[order], full.bbox[full_order])  # same pixels covered
    np.testing.assert_array_equal(graph.area[order], full.area[full_order])
    np.testing.assert_allclose(graph.centroid[order], full.centroid[full_order], atol=1e-3)
    assert graph.bbox[:, 2].max() == 1279 and graph.bbox[:, 3].max() == 959
    with pytest.raises(ValueError, match="max_side"):
        TrapParams(max_side=8)


def test_pixel_distances_are_pixels_of_the_working_size() -> None:
    from trap_core.pipeline import TrapParams
    params = TrapParams(eps=40.0, separation=30.0, max_side=640)
    assert params.in_frame_pixels(640, 480) is params and params.in_frame_pixels(480, 640) is params
    big = params.in_frame_pixels(1920, 1080)  # segmented 3x smaller: objects 3x larger in its pixels
    assert (big.eps, big.separation) == (40.0, 90.0)
    small = params.in_frame_pixels(320, 240)  # segmented 2x larger: objects 2x smaller in its pixels
    assert (small.eps, small.separation) == (40.0, 15.0)
    assert TrapParams(max_side=0).in_frame_pixels(1920, 1080).separation == 40.0
    assert (params.working_pixel(1920, 1080), params.working_pixel(320, 240), params.working_pixel(480, 640)) == (
        3.0, 0.5, 1.0)


def test_a_small_frame_is_segmented_scaled_up_and_its_geometry_given_back_in_its_pixels() -> None:
    """Exact-colour regions of a 400x300 frame are the same scaled up to 640x480 (nearest pixels):
    their boxes in the frame's pixels are the boxes at its own size, to the pixel."""
    from trap_core.pipeline import TrapParams, frame_graph
    frame = next(iter(render(SceneConfig(width=400, height=300, frames=1, seed=24, identical=True))))
    scaled = frame_graph(frame.rgb, TrapParams(segmentation="colour"))
    native = frame_graph(frame.rgb, TrapParams(segmentation="colour", max_side=0))
    assert (scaled.n_nodes, scaled.n_faces) == (native.n_nodes, native.n_faces)
    np.testing.assert_array_equal(scaled.bbox, native.bbox)
    np.testing.assert_allclose(scaled.centroid, native.centroid, atol=1.0)  # uneven duplication: within a pixel


def test_objects_in_small_frames_are_tracked_at_the_working_size() -> None:
    """240x180 frames over a photograph: at their own size, min_size pixels and the smoothing
    merge a small object's parts into the background and one object of three goes untracked
    (measured); segmented at 640x320 every object is."""
    from trap_core.evaluation import boxes_by_frame, match_objects
    from trap_core.pipeline import TrapParams, synthetic_graphs, track
    params = TrapParams()
    graphs, truth = synthetic_graphs(SceneConfig(width=240, height=180, frames=240, seed=1, background="retina",
                                                 noise=0.5), params)
    tracks = track(graphs, params).tracks
    boxes = [boxes_by_frame(t) for t in tracks]
    assert len(tracks) == 3
    assert all(precision >= 0.85 and recall >= 0.9 for _, precision, recall in match_objects(boxes, truth))


def test_a_textured_frame_gets_the_least_k_that_cuts_it_into_at_most_max_regions(textured_frames: list) -> None:
    import dataclasses

    from trap_core.pipeline import TrapParams, fitted_to_regions, frame_graph
    rgb = textured_frames[0]
    params = TrapParams(max_regions=50)  # the chroma weight fitted where fitting k needs it, not returned
    assert frame_graph(rgb, params).n_nodes > 3 * params.max_regions
    fitted = fitted_to_regions(rgb, params)
    assert fitted.k > params.k and dataclasses.replace(fitted, k=params.k) == params  # only k changes
    assert frame_graph(rgb, fitted).n_nodes <= params.max_regions
    assert frame_graph(rgb, dataclasses.replace(fitted, k=0.9 * fitted.k)).n_nodes > params.max_regions  # least
    assert fitted_to_regions(rgb, fitted) == fitted  # fitting twice changes nothing
    for kept in (TrapParams(max_regions=0), TrapParams(max_regions=100_000), TrapParams(segmentation="colour")):
        assert fitted_to_regions(rgb, kept) is kept
    with pytest.raises(ValueError, match="max_regions"):
        TrapParams(max_regions=3)


def test_every_frame_of_a_stream_is_cut_with_the_k_fitted_to_its_first(textured_frames: list) -> None:
    from trap_core.pipeline import TrapParams, fitted_to_regions, frame_graph, graphs_of
    textured, plain = textured_frames[0], np.full((120, 160, 3), 90, np.uint8)
    params = TrapParams(max_regions=50, threads=2, chroma_weight=1.0)  # k alone is fitted
    reported: list[tuple[TrapParams, list[str]]] = []
    frames = [textured, plain, textured, textured]
    graphs = list(graphs_of(frames, params, lambda used, notes: reported.append((used, notes))))
    fitted = fitted_to_regions(textured, params)
    assert reported == [(fitted, [f"segmentation: k raised from 7 to {fitted.k:g}: the first frame had more than 50 "
                                  "regions (max_regions)"])]
    assert not reported[0][1][0].warns
    assert [g.n_nodes for g in graphs] == [frame_graph(f, fitted).n_nodes for f in frames]
    reported.clear()
    list(graphs_of([plain, textured], params, lambda used, notes: reported.append((used, notes))))
    assert len(reported) == 1 and reported[0][0] == params  # fitted on a plain first frame: k as given
    assert reported[0][1][0].startswith("segmentation: the first frame has only 1 region")  # and the user is told
    reported.clear()
    list(graphs_of([textured, plain], TrapParams(threads=2, chroma_weight=1.0),
                   lambda used, notes: reported.append((used, notes))))
    assert reported == []  # within max_regions and not too few: nothing to tell


def test_a_stream_that_fails_gives_the_graphs_before_the_failure_then_raises(textured_frames: list) -> None:
    from trap_core.pipeline import TrapParams, frame_graph, graphs_of
    textured = textured_frames[0]
    params = TrapParams(threads=2)

    def frames():
        for _ in range(7):  # more than the 2 x threads frames in flight
            yield textured
        raise OSError("corrupt message")

    graphs = []
    with pytest.raises(OSError, match="corrupt message"):
        for graph in graphs_of(frames(), params, image_steps=False):
            graphs.append(graph)
    assert [g.n_nodes for g in graphs] == [frame_graph(textured, params).n_nodes] * 7


def test_a_first_frame_of_few_felzenszwalb_regions_gets_a_warning(textured_frames: list) -> None:
    from trap_core.pipeline import TrapParams, first_frame_setup, frame_graph
    smooth = np.zeros((120, 160, 3), np.uint8)
    smooth[:, :, 0] = np.linspace(0, 255, 160, dtype=np.uint8)  # a ramp cut into a few bands
    smooth[40:80, 60:100] = (20, 200, 20)
    params = TrapParams(chroma_weight=1.0)
    graph = frame_graph(smooth, params)
    assert graph.n_nodes < 40
    assert first_frame_setup(smooth, params) == (params, [
        f"segmentation: the first frame has only {graph.n_nodes} regions at k 7: objects may share giant regions "
        "with the background and go untracked; a smaller k (-p k:=3.5) cuts finer"])
    assert first_frame_setup(smooth, TrapParams(segmentation="colour")) == (TrapParams(segmentation="colour"), [])
    assert first_frame_setup(textured_frames[0], params) == (params, [])
    plain = np.full((120, 160, 3), 90, np.uint8)
    note = first_frame_setup(plain, params)[1][0]
    assert "the first frame has only 1 region at k 7:" in note and note.warns  # the tracks may suffer: a warning


def test_command_line_runs_print_a_warning_note_as_a_warning(capsys: pytest.CaptureFixture) -> None:
    """``run_bag`` and the evaluation print the first-frame notes to stderr; without the level a
    ROS node logs, a warning must say it is one."""
    from trap_core.pipeline import SetupNote, TrapParams, print_setup_notes
    print_setup_notes(TrapParams(), [SetupNote("segmentation: k raised"), SetupNote("segmentation: few", warns=True)])
    assert capsys.readouterr().err == "segmentation: k raised\nwarning: segmentation: few\n"


def test_a_chroma_weight_of_zero_is_fitted_on_the_first_frame_for_the_whole_video() -> None:
    """``chroma_weight`` 0 asks for the weight to be fitted; the video's parameters then hold it, the
    user is told, and the graphs are those of that weight. It is fitted on the frame at its own
    size: scaled up to the working size by nearest pixels, most neighbours repeat one pixel and
    nothing seems to vary."""
    from trap_core.pipeline import TrapParams, first_frame_setup, frame_graph
    from trap_core.segmentation import fitted_chroma_weight
    rng = np.random.default_rng(5)
    grey_texture = np.clip(110 + rng.normal(0, 6, (120, 160))[..., None].repeat(3, axis=2), 0, 255)
    grey_texture[40:80, 60:100] += (25, -8, -8)  # a reddish patch about as bright as the ground
    frame = np.clip(grey_texture, 0, 255).astype(np.uint8)
    used, notes = first_frame_setup(frame, TrapParams())
    assert fitted_chroma_weight(cv2.resize(frame, (640, 480), interpolation=cv2.INTER_NEAREST)) == 1.0
    assert used.chroma_weight == fitted_chroma_weight(frame) == 2.0 and used.k == 7.0
    assert notes[0] == ("segmentation: chroma weighed 2.00 times brightness in colour distances, fitted on the first "
                        "frame (chroma_weight)")
    assert not notes[0].warns  # a parameter fitted: information, not a warning
    assert frame_graph(frame, used).n_nodes != frame_graph(frame, TrapParams(chroma_weight=1.0)).n_nodes
    assert frame_graph(frame, TrapParams()).n_nodes == frame_graph(frame, used).n_nodes  # a frame alone: its own
    assert first_frame_setup(frame, TrapParams(chroma_weight=1.0))[0].chroma_weight == 1.0  # the colour space's
    noise = np.random.default_rng(6).integers(0, 256, (120, 160, 3), dtype=np.uint8)  # as much in chroma
    assert first_frame_setup(noise, TrapParams(max_regions=0))[1] == [
        "segmentation: chroma weighed as much as brightness in colour distances, fitted on the first frame "
        "(chroma_weight)"]
    assert first_frame_setup(frame, TrapParams(segmentation="colour", chroma_weight=0.0, max_regions=0))[0] == \
        TrapParams(segmentation="colour", chroma_weight=0.0, max_regions=0)  # exact colours weigh no distances


def test_exact_colour_regions_are_refused_on_a_noisy_first_frame() -> None:
    """Noise (or JPEG) gives nearly every pixel a colour of its own: exact-colour regions would be
    tens of thousands a frame and mining them would never end, so the first frame is refused."""
    from trap_core.pipeline import TrapParams, first_frame_setup, graphs_of
    from trap_core.segmentation import SegmentationError
    clean, noisy = (next(iter(render(SceneConfig(width=320, height=240, frames=1, seed=3, noise=noise))))
                    for noise in (0.0, 2.0))
    colour = TrapParams(segmentation="colour")
    assert first_frame_setup(clean.rgb, colour) == (colour, [])
    with pytest.raises(SegmentationError, match=r"^segmentation colour: the first frame has \d+ exact-colour regions "
                                                r"\(limit 20 x max_regions = 9600\).*use segmentation:=felzenszwalb$"):
        list(graphs_of([noisy.rgb, clean.rgb], colour))
    assert first_frame_setup(noisy.rgb, TrapParams(segmentation="colour", max_regions=0))[0].max_regions == 0  # off
    assert first_frame_setup(noisy.rgb, TrapParams(chroma_weight=1.0))[1] == []  # Felzenszwalb regions: no complaint


def test_occurrences_nodes_in_one_pass_are_the_faces_nodes_one_by_one() -> None:
    """The compiled pass over many face sets gives each set the distinct nodes around its
    faces (padding skipped), as the faces' own traversals do."""
    frame = next(iter(render(SceneConfig(width=160, height=120, frames=1, seed=3))))
    graph = build_plane_graph(*colour_components(frame.rgb), frame.rgb)
    rng = np.random.default_rng(0)
    face_sets = np.full((40, 5), -1, dtype=np.int64)
    for row in face_sets:
        n = rng.integers(1, 6)
        row[:n] = rng.choice(graph.n_faces, size=n, replace=False)
    nodes, ends = graph.sets_nodes(face_sets)
    for row, (start, end) in zip(face_sets, zip(np.r_[0, ends[:-1]], ends)):
        expected = np.unique(np.concatenate([graph.face_nodes(f) for f in row if f >= 0]))
        assert np.array_equal(nodes[start:end], expected)
    assert np.array_equal(graph.faces_nodes(frozenset(face_sets[0][face_sets[0] >= 0].tolist())), nodes[:ends[0]])


def test_thickness_tells_a_line_from_a_body() -> None:
    """Twice the area over the perimeter: about 1 for a line of single pixels, half the side of
    a square."""
    labels = np.zeros((40, 40), dtype=np.int32)
    labels[10:30, 10:30] = 1
    labels[5, 2:38] = 2
    labels, n = relabel_4connected(labels)
    graph = build_plane_graph(labels, n, np.zeros((40, 40, 3), dtype=np.uint8))
    assert graph.thickness[labels[20, 20]] == pytest.approx(10.0, rel=0.05)
    assert graph.thickness[labels[5, 20]] < 1.1


def test_the_line_outside_a_sharp_edge_does_not_widen_the_box() -> None:
    """A sharp rectangle over a plain ground, segmented after smoothing: the pixels either side
    of its edge become lines of their own. The outer one is ground in the frame, yet widens the
    rectangle's box by a pixel all round; given the working pixel, the box is the rectangle's.
    The inner lines, of the rectangle's colour, stay; a box that only outer lines touch does
    not grow."""
    rng = np.random.default_rng(0)
    rgb = np.full((80, 100, 3), (40, 90, 40), dtype=np.uint8)
    rgb[30:50, 20:60] = (220, 60, 60)
    noisy = np.clip(rgb + rng.normal(0, 1, rgb.shape), 0, 255).astype(np.uint8)
    labels, n = felzenszwalb(noisy, k=7.0, sigma=0.8, min_size=20)
    graph = build_plane_graph(labels, n, noisy)
    held = np.flatnonzero(np.arange(graph.n_nodes) != labels[0, 0])
    rectangle = [20.0, 30.0, 40.0, 20.0]
    assert graph.nodes_box(held).tolist() == [19.0, 29.0, 42.0, 22.0]
    assert graph.nodes_box(held, pixel=1.0).tolist() == rectangle
    outer = graph.outer_lines(held, 1.0)
    assert outer.any() and (graph.thickness[held[outer]] < 1.5).all()
    assert not outer[np.isin(held, labels[[30, 40, 49], [40, 20, 40]])].any()  # the inner lines and the body
    assert graph.nodes_box(held[outer], pixel=1.0, around=np.array(rectangle)).tolist() == rectangle
    assert graph.nodes_box(held[outer], around=np.array(rectangle)).tolist() == [19.0, 29.0, 42.0, 22.0]
    mask = np.isin(np.arange(graph.n_nodes), held)  # regions given as a mask: the same boxes
    assert graph.nodes_box(mask, pixel=1.0).tolist() == rectangle
    around = np.array([20.5, 30.25, 0.1, 0.2])  # no regions: the box around, as it is
    assert graph.nodes_box(np.zeros(0, dtype=np.int64), pixel=1.0, around=around).tolist() == around.tolist()


def test_a_coloured_object_in_a_jpeg_frame_keeps_out_of_a_textured_ground() -> None:
    """JPEG halves the colour resolution: a person's coloured torso over grey grass meets it along
    a colour ramp. Climbing it one small step at a time, the torso's region takes in a large part
    of the ground; with mean_gap 5, no torso region reaches 100 px beyond its person."""
    from trap_core.bagio import compress_image, decode_compressed
    from trap_core.pipeline import TrapParams, first_frame_setup
    frame = next(iter(render(SceneConfig(seed=35, shape="person", background="grass", noise=1.0, frames=1))))
    rgb = decode_compressed("jpeg", compress_image(frame.rgb, "jpeg"))

    def torso_overreach(mean_gap: float) -> list[int]:
        params = first_frame_setup(rgb, TrapParams(mean_gap=mean_gap))[0]
        labels = felzenszwalb(rgb, k=params.k, sigma=params.sigma, min_size=params.min_size, mean_gap=mean_gap)[0]
        reach = []
        for x, y, w, h in frame.boxes:
            ys, xs = np.nonzero(labels == labels[y + h // 3, x + w // 2])
            reach.append(max(x - xs.min(), y - ys.min(), xs.max() + 1 - x - w, ys.max() + 1 - y - h))
        return reach

    assert max(torso_overreach(0.0)) > 100
    assert max(torso_overreach(5.0)) < 100
