"""Reading image topics: every encoding, every storage, and every kind of bad input."""
from __future__ import annotations

import shutil
import warnings
from pathlib import Path

import cv2
import numpy as np
import pytest

from trap_core.bagio import (SUPPORTED_ENCODINGS, BagError, SampleRange, decode_compressed, decode_image,
                             encode_image, image_topics, open_image_stream, write_image_bag)


def _frames(count: int = 4, height: int = 24, width: int = 32) -> list[np.ndarray]:
    """Frames of flat 8x8 colour blocks (Bayer and JPEG round trips are exact inside blocks)."""
    rng = np.random.default_rng(7)
    frames = []
    for _ in range(count):
        blocks = rng.integers(0, 256, size=(height // 8, width // 8, 3), dtype=np.uint8)
        frames.append(np.kron(blocks, np.ones((8, 8, 1), dtype=np.uint8)))
    return frames


def _block_centres(rgb: np.ndarray) -> np.ndarray:
    return rgb[3::8, 3::8].astype(int)


@pytest.mark.parametrize("encoding", ["rgb8", "bgr8", "rgba8", "bgra8", "8uc3", "8uc4", "rgb16", "bgr16", "rgba16",
                                      "bgra16"])
def test_colour_encodings_are_exact(tmp_path: Path, encoding: str) -> None:
    frames = _frames()
    write_image_bag(tmp_path / "bag", frames, encoding=encoding)
    with open_image_stream(tmp_path / "bag") as stream:
        assert stream.count == len(frames)
        read = list(stream)
    assert [f.index for f in read] == list(range(len(frames)))
    for frame, original in zip(read, frames):
        assert frame.rgb.dtype == np.uint8 and frame.rgb.shape == original.shape
        np.testing.assert_array_equal(frame.rgb, original)


@pytest.mark.parametrize("encoding", ["mono8", "mono16", "8uc1", "16uc1"])
def test_mono_encodings_give_grey_rgb(tmp_path: Path, encoding: str) -> None:
    frames = _frames()
    write_image_bag(tmp_path / "bag", frames, encoding=encoding)
    with open_image_stream(tmp_path / "bag") as stream:
        for frame, original in zip(stream, frames):
            grey = cv2.cvtColor(original, cv2.COLOR_RGB2GRAY)
            for channel in range(3):
                np.testing.assert_array_equal(frame.rgb[..., channel], frame.rgb[..., 0])
            if "16" in encoding:  # the first frame's greys, widened a little, span the 8 bits
                gain, residual = _linear_fit(frame.rgb[..., 0], grey)
                assert gain >= 1 and residual <= 1, (gain, residual)
            else:
                np.testing.assert_array_equal(frame.rgb[..., 0], grey)


@pytest.mark.parametrize("encoding", [f"bayer_{p}{bits}" for p in ("rggb", "bggr", "gbrg", "grbg") for bits in (8, 16)])
def test_bayer_encodings_demosaic_to_the_right_colours(tmp_path: Path, encoding: str) -> None:
    frames = _frames()
    write_image_bag(tmp_path / "bag", frames, encoding=encoding)
    with open_image_stream(tmp_path / "bag") as stream:
        for frame, original in zip(stream, frames):
            # Inside flat blocks demosaicing is exact; a swapped R/B pattern would not be.
            np.testing.assert_allclose(_block_centres(frame.rgb), _block_centres(original), atol=2)


@pytest.mark.parametrize("encoding", ["yuv422", "yuv422_yuy2", "nv21"])
def test_chroma_subsampled_encodings_keep_the_colours(tmp_path: Path, encoding: str) -> None:
    frames = _frames()  # 8x8 blocks: no pixel pair (2x2 square for nv21) straddles two colours
    write_image_bag(tmp_path / "bag", frames, encoding=encoding)
    with open_image_stream(tmp_path / "bag") as stream:
        for frame, original in zip(stream, frames):
            np.testing.assert_allclose(frame.rgb.astype(int), original.astype(int), atol=3)


def test_chroma_subsampled_byte_orders() -> None:
    """ROS's yuv422 is U Y V Y, yuv422_yuy2 is Y U Y V, nv21 has V before U: a bright and a dark
    grey pixel, and a reddish square (V high, U low)."""
    grey = {"yuv422": [128, 200, 128, 50], "yuv422_yuy2": [200, 128, 50, 128]}
    for encoding, payload in grey.items():
        rgb = decode_image(encoding, 1, 2, 4, np.array(payload, dtype=np.uint8))
        assert rgb[0, 0, 0] > 180 and rgb[0, 1, 0] < 60 and np.ptp(rgb[0, 0]) <= 2, encoding
    red = decode_image("nv21", 2, 2, 2, np.array([120] * 4 + [200, 60], dtype=np.uint8))[0, 0]
    assert red[0] > 200 and red[2] < 60
    with pytest.raises(BagError, match="size must be even"):
        decode_image("yuv422", 1, 3, 6, np.zeros(6, dtype=np.uint8))


@pytest.mark.parametrize("fmt,tolerance", [("png", 0), ("jpeg", 12)])
def test_compressed_images(tmp_path: Path, fmt: str, tolerance: int) -> None:
    frames = _frames()
    write_image_bag(tmp_path / "bag", frames, compressed=fmt, topic="/cam/compressed")
    with open_image_stream(tmp_path / "bag") as stream:
        assert stream.msgtype == "sensor_msgs/msg/CompressedImage"
        for frame, original in zip(stream, frames):
            np.testing.assert_allclose(_block_centres(frame.rgb), _block_centres(original), atol=tolerance)


@pytest.mark.parametrize("storage,name", [("mcap", "bag"), ("sqlite3", "bag"), ("ros1", "bag.bag"),
                                          ("ros1", "recording")])  # a ROS 1 bag named without .bag
def test_storages_keep_stamps_and_frame_ids(tmp_path: Path, storage: str, name: str) -> None:
    frames = _frames(count=5)
    write_image_bag(tmp_path / name, frames, storage=storage, fps=10, frame_id="cam_optical")
    with open_image_stream(tmp_path / name) as stream:
        read = list(stream)
    assert len(read) == 5
    stamps = np.array([f.stamp_ns for f in read])
    np.testing.assert_array_equal(np.diff(stamps), 100_000_000)
    assert {f.frame_id for f in read} == {"cam_optical"}
    np.testing.assert_array_equal(read[-1].rgb, frames[-1])


def test_ros1_alias_is_removed_when_the_stream_closes(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A ROS 1 bag named without .bag is read through a temporary link; closing removes it."""
    import tempfile
    temporary = tmp_path / "tmp"
    temporary.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(temporary))
    write_image_bag(tmp_path / "recording", _frames(count=3), storage="ros1")
    with open_image_stream(tmp_path / "recording") as stream:
        assert len(list(temporary.iterdir())) == 1
        assert len(list(stream)) == 3
    assert not list(temporary.iterdir())


def test_bare_storage_file_is_readable(tmp_path: Path) -> None:
    write_image_bag(tmp_path / "bag", _frames(count=3))
    (storage_file,) = (tmp_path / "bag").glob("*.mcap")
    with open_image_stream(storage_file) as stream:
        assert len(list(stream)) == 3


def test_topic_choice(tmp_path: Path) -> None:
    from rosbags.rosbag2 import Writer
    from rosbags.typesys import Stores, get_typestore
    store = get_typestore(Stores.ROS2_JAZZY)
    Image, Header, Time = (store.types[n] for n in ("sensor_msgs/msg/Image", "std_msgs/msg/Header",
                                                     "builtin_interfaces/msg/Time"))
    with Writer(tmp_path / "two", version=9) as writer:
        for topic in ("/left", "/right"):
            connection = writer.add_connection(topic, Image.__msgtype__, typestore=store)
            message = Image(header=Header(stamp=Time(sec=1, nanosec=0), frame_id=topic), height=16, width=16,
                            encoding="mono8", is_bigendian=0, step=16, data=np.arange(256, dtype=np.uint8))
            writer.write(connection, 1, store.serialize_cdr(message, Image.__msgtype__))
    assert set(image_topics(tmp_path / "two")) == {"/left", "/right"}
    with pytest.raises(BagError, match="several image topics.*/left, /right"):
        open_image_stream(tmp_path / "two")
    with open_image_stream(tmp_path / "two", "/right") as stream:
        assert [f.frame_id for f in stream] == ["/right"]
    with pytest.raises(BagError, match="no image topic '/middle'"):
        open_image_stream(tmp_path / "two", "/middle")


def test_bag_without_images(tmp_path: Path) -> None:
    from rosbags.rosbag2 import Writer
    from rosbags.typesys import Stores, get_typestore
    store = get_typestore(Stores.ROS2_JAZZY)
    with Writer(tmp_path / "strings", version=9) as writer:
        connection = writer.add_connection("/chatter", "std_msgs/msg/String", typestore=store)
        writer.write(connection, 1, store.serialize_cdr(store.types["std_msgs/msg/String"](data="hi"),
                                                        "std_msgs/msg/String"))
    with pytest.raises(BagError, match="no sensor_msgs/Image.*/chatter"):
        open_image_stream(tmp_path / "strings")


def test_missing_and_non_bag_paths(tmp_path: Path) -> None:
    with pytest.raises(BagError, match="bag not found"):
        open_image_stream(tmp_path / "nothing")
    text = tmp_path / "notes.mcap"
    text.write_text("this is not a bag\n")
    with pytest.raises(BagError, match="not a readable"):
        open_image_stream(text)
    empty_dir = tmp_path / "emptydir"
    empty_dir.mkdir()
    with pytest.raises(BagError, match="not a readable"):
        open_image_stream(empty_dir)


@pytest.mark.parametrize("storage", ["mcap", "sqlite3"])
def test_truncated_bag(tmp_path: Path, storage: str) -> None:
    write_image_bag(tmp_path / "bag", _frames(count=30, height=64, width=64), storage=storage)
    (storage_file,) = [p for p in (tmp_path / "bag").iterdir() if p.suffix in (".mcap", ".db3")]
    data = storage_file.read_bytes()
    storage_file.write_bytes(data[: len(data) // 2])
    with pytest.raises(BagError):
        with open_image_stream(tmp_path / "bag") as stream:
            for _ in stream:
                pass


def test_tiny_frames_are_refused(tmp_path: Path) -> None:
    write_image_bag(tmp_path / "bag", _frames(count=3, height=64, width=8))
    with pytest.raises(BagError, match=r"frame 0 of /camera/image_raw: image of size 8x64 is too small to track"):
        with open_image_stream(tmp_path / "bag") as stream:
            for _ in stream:
                pass


@pytest.mark.parametrize("bad_size,message", [
    ((4, 4), "image of size 4x4 is too small"),
    ((480, 640), "image of size 640x480 after frames of 320x240: one image size per run"),  # a camera reconfigured
])
def test_run_bag_tracks_and_writes_the_frames_before_a_bad_one(tmp_path: Path, bad_size: tuple[int, int],
                                                               message: str) -> None:
    import json

    from trap_core.pipeline import TrapParams, run_bag
    from trap_core.synthetic import SceneConfig
    from trap_core.synthetic.scene import render
    frames = [rendered.rgb for rendered in render(SceneConfig(width=320, height=240, frames=40, seed=4))]
    write_image_bag(tmp_path / "bag", [*frames, np.zeros((*bad_size, 3), np.uint8)])
    with pytest.raises(BagError, match=f"frame 40 of /camera/image_raw: {message}"):
        run_bag(tmp_path / "bag", tmp_path / "out", TrapParams(segmentation="colour"))
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["frames"] == 40 and summary["counts"]["tracks"] >= 1  # every frame in flight was kept



def test_the_frame_rate_in_the_stamps_changes_no_track(tmp_path: Path) -> None:
    """The speed that tells objects from background is per frame (min_speed per tau frames):
    the same frames stamped at 10 Hz and at 25 Hz give the same tracks. Per second, the slowest
    object of this video falls under it at 10 Hz."""
    from trap_core.pipeline import TrapParams, run_bag
    from trap_core.synthetic import SceneConfig
    from trap_core.synthetic.scene import render
    frames = [rendered.rgb for rendered in render(SceneConfig(width=320, height=240, frames=200, seed=5))]
    tracks = []
    for fps in (10, 25):
        write_image_bag(tmp_path / f"bag{fps}", frames, fps=fps)
        run_bag(tmp_path / f"bag{fps}", tmp_path / f"out{fps}", TrapParams(segmentation="colour"))
        tracks.append((tmp_path / f"out{fps}" / "tracks.txt").read_text())
    assert tracks[0] == tracks[1] and tracks[0].count("\n") > 100

def test_corrupt_ros1_header(tmp_path: Path) -> None:
    write_image_bag(tmp_path / "bag.bag", _frames(count=10, height=64, width=64), storage="ros1")
    path = tmp_path / "bag.bag"
    data = bytearray(path.read_bytes())
    data[13:213] = b"\xff" * 200  # just after the "#ROSBAG V2.0" magic line
    path.write_bytes(bytes(data))
    with pytest.raises(BagError):
        with open_image_stream(path) as stream:
            for _ in stream:
                pass


def test_decode_rejects_bad_headers() -> None:
    payload = np.zeros(12, dtype=np.uint8)
    with pytest.raises(BagError, match="unsupported image encoding '16uc2'"):  # two channels: no colours
        decode_image("16uc2", 2, 2, 4, payload)
    with pytest.raises(BagError, match="height x step needs 24"):
        decode_image("rgb8", 2, 4, 12, payload)
    with pytest.raises(BagError, match="step 4 is shorter than a row"):
        decode_image("rgb8", 2, 2, 4, payload)
    with pytest.raises(BagError, match="size 0x0"):
        decode_image("rgb8", 0, 0, 0, b"")


def test_decode_handles_padded_rows_and_big_endian() -> None:
    rgb = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3)
    padded = np.zeros((2, 12), dtype=np.uint8)
    padded[:, :9] = rgb.reshape(2, 9)
    np.testing.assert_array_equal(decode_image("rgb8", 2, 3, 12, padded.ravel()), rgb)
    samples = np.array([[0x0100, 0x1234, 0xFF00]])
    big, little = (samples.astype(order).view(np.uint8).ravel() for order in (">u2", "<u2"))
    np.testing.assert_array_equal(decode_image("mono16", 1, 3, 6, big, is_bigendian=True),
                                  decode_image("mono16", 1, 3, 6, little))
    assert decode_image("mono16", 1, 3, 6, big, is_bigendian=True)[0, :, 0].tolist() == [1, 18, 254]


def test_encoding_list_is_covered() -> None:
    frame = _frames(count=1)[0]
    for encoding in SUPPORTED_ENCODINGS:
        data, step = encode_image(frame, encoding)
        assert decode_image(encoding, frame.shape[0], frame.shape[1], step, data).shape == frame.shape


def test_unsupported_encoding_in_bag(tmp_path: Path) -> None:
    from rosbags.rosbag2 import Writer
    from rosbags.typesys import Stores, get_typestore
    store = get_typestore(Stores.ROS2_JAZZY)
    Image, Header, Time = (store.types[n] for n in ("sensor_msgs/msg/Image", "std_msgs/msg/Header",
                                                     "builtin_interfaces/msg/Time"))
    with Writer(tmp_path / "depth", version=9) as writer:
        connection = writer.add_connection("/cam", Image.__msgtype__, typestore=store)
        message = Image(header=Header(stamp=Time(sec=1, nanosec=0), frame_id="c"), height=2, width=2,
                        encoding="16UC2", is_bigendian=0, step=8, data=np.zeros(16, dtype=np.uint8))
        writer.write(connection, 1, store.serialize_cdr(message, Image.__msgtype__))
    with pytest.raises(BagError, match="frame 0 of /cam: unsupported image encoding '16UC2'"):
        with open_image_stream(tmp_path / "depth") as stream:
            list(stream)


def test_streaming_does_not_hold_the_bag(small_bag: Path) -> None:
    """Frames arrive one at a time: dropping them keeps at most a couple alive."""
    import gc
    import weakref
    alive = []
    with open_image_stream(small_bag) as stream:
        for frame in stream:
            alive.append(weakref.ref(frame.rgb.base if frame.rgb.base is not None else frame.rgb))
            del frame
            gc.collect()
            assert sum(ref() is not None for ref in alive) <= 2


def test_bags_are_never_overwritten(tmp_path: Path) -> None:
    write_image_bag(tmp_path / "bag", _frames(count=1))
    with pytest.raises(BagError, match="exists already"):
        write_image_bag(tmp_path / "bag", _frames(count=1))
    shutil.rmtree(tmp_path / "bag")


def test_run_bag_reports_the_k_fitted_to_a_textured_first_frame(tmp_path: Path, capsys, textured_frames: list) -> None:
    import json

    from trap_core.pipeline import TrapParams, fitted_to_regions, run_bag
    frames = textured_frames
    write_image_bag(tmp_path / "bag", frames)
    params = TrapParams(max_regions=60)
    run_bag(tmp_path / "bag", tmp_path / "out", params)
    used = json.loads((tmp_path / "out" / "summary.json").read_text())["parameters"]
    assert used["k"] == fitted_to_regions(frames[0], params).k > params.k and used["max_regions"] == 60
    assert f"k raised from 7 to {used['k']:g}" in capsys.readouterr().err


def _linear_fit(decoded: np.ndarray, original: np.ndarray) -> tuple[float, float]:
    """Gain of the least-squares line from ``original`` to ``decoded`` samples, and its largest residual."""
    x, y = original.astype(float).ravel(), decoded.astype(float).ravel()
    gain, offset = np.polyfit(x, y, 1)
    return gain, float(np.abs(y - (gain * x + offset)).max())


@pytest.mark.parametrize("encoding", ["mono16", "rgb16", "bayer_rggb16"])
@pytest.mark.parametrize("bits", [10, 12, 14])
def test_cameras_writing_fewer_bits_in_16_bit_samples_keep_their_contrast(tmp_path: Path, encoding: str,
                                                                           bits: int) -> None:
    # Keeping the high byte made a 12-bit camera's 0..4095 a frame of greys 0..15: nothing to segment.
    frames = _frames()
    write_image_bag(tmp_path / "bag", frames, encoding=encoding, sample_bits=bits)
    with open_image_stream(tmp_path / "bag") as stream:
        for frame, original in zip(stream, frames):
            if encoding == "mono16":
                original = cv2.cvtColor(original, cv2.COLOR_RGB2GRAY)[..., None].repeat(3, axis=2)
            decoded, original = _block_centres(frame.rgb), _block_centres(original)
            gain, residual = _linear_fit(decoded, original)
            assert gain >= 0.75 and residual <= 3, (gain, residual)


def test_a_narrow_band_of_16_bit_samples_is_spread_over_the_greys() -> None:
    # what a thermal camera writes: a scene within 7000..8000 of 0..65535
    band = (7000 + _frames(count=1)[0][..., 0].astype(np.uint16) * 4).astype("<u2")
    height, width = band.shape
    grey = decode_image("16uc1", height, width, width * 2, band.view(np.uint8).ravel())[..., 0]
    assert int(grey.max()) - int(grey.min()) >= 150


def test_a_stream_maps_16_bit_samples_alike_in_every_frame(tmp_path: Path) -> None:
    # A region keeps its colour (and its label) from frame to frame: the mapping is the first frame's,
    # later samples outside its range are clipped.
    first = np.repeat(np.linspace(100, 150, 32).round().astype(np.uint8)[None, :, None], 24, axis=0).repeat(3, axis=2)
    later = first.copy()
    later[:8] = 0
    later[16:] = 255
    write_image_bag(tmp_path / "bag", [first, later], encoding="rgb16", sample_bits=12)
    with open_image_stream(tmp_path / "bag") as stream:
        decoded_first, decoded_later = (frame.rgb for frame in stream)
    np.testing.assert_array_equal(decoded_later[8:16], decoded_first[8:16])
    assert decoded_first[0, -1, 0] - decoded_first[0, 0, 0] > 100  # 100 vs 150 of 0..255 (in 12 bits), stretched
    assert decoded_later[0].max() == 0 and decoded_later[-1].min() == 255


def test_a_stream_that_starts_black_takes_its_range_from_the_first_frame_with_content(tmp_path: Path) -> None:
    frames = _frames(count=2)
    write_image_bag(tmp_path / "bag", [np.zeros_like(frames[0]), *frames], encoding="rgb16", sample_bits=12)
    with open_image_stream(tmp_path / "bag") as stream:
        black, *decoded = (frame.rgb for frame in stream)
    assert black.max() == 0
    for frame, original in zip(decoded, frames):
        gain, residual = _linear_fit(_block_centres(frame), _block_centres(original))
        assert gain >= 0.75 and residual <= 3, (gain, residual)


def test_16_bit_png_keeps_its_contrast() -> None:
    original = _frames(count=1)[0]
    sample_range = SampleRange()
    twelve_bit = np.rint(cv2.cvtColor(original, cv2.COLOR_RGB2BGR) * (4095 / 255)).astype(np.uint16)
    ok, png = cv2.imencode(".png", twelve_bit)
    assert ok
    decoded = decode_compressed("png", png.ravel(), sample_range)
    gain, residual = _linear_fit(decoded, original)
    assert gain >= 0.75 and residual <= 1, (gain, residual)
    assert sample_range.high is not None and sample_range.high < 65535 / 8


def test_sample_bits_out_of_range_are_refused() -> None:
    with pytest.raises(BagError, match="sample_bits"):
        encode_image(_frames(count=1)[0], "mono16", sample_bits=17)


def _grey(rgb: np.ndarray) -> np.ndarray:
    return cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)


@pytest.mark.parametrize("encoding", ["8sc1", "16sc1", "32sc1", "32fc1", "64fc1", "16uc3", "16sc4", "32fc3",
                                      "64fc4"])
def test_signed_and_floating_point_samples_keep_their_contrast(tmp_path: Path, encoding: str) -> None:
    # Depth, thermal and scientific cameras write these; they were refused as unknown encodings.
    frames = _frames()
    write_image_bag(tmp_path / "bag", frames, encoding=encoding.upper())
    with open_image_stream(tmp_path / "bag") as stream:
        for frame, original in zip(stream, frames):
            if encoding.endswith("c1"):
                original = _grey(original)[..., None].repeat(3, axis=2)
            gain, residual = _linear_fit(frame.rgb, original)
            assert gain >= 0.65 and residual <= 1, (gain, residual)  # at least 1 / (1 + 2 RANGE_MARGIN)


def test_floating_point_depth_without_readings() -> None:
    # REP 117: NaN is no reading, +Inf too far, -Inf too near; an all-NaN first frame fixes nothing.
    # Decoding must not leave NaN to the cast to uint8 (undefined: a RuntimeWarning, made an error here).
    warnings.simplefilter("error", RuntimeWarning)
    metres = 0.5 + _grey(_frames(count=1)[0]).astype(np.float32) / 50
    metres[:8, :8], metres[8:16, :8], metres[16:, :8] = np.nan, np.inf, -np.inf
    height, width = metres.shape
    sample_range = SampleRange()
    blank = decode_image("32FC1", height, width, width * 4, np.full_like(metres, np.nan).view(np.uint8).ravel(),
                         sample_range=sample_range)
    assert blank.max() == 0 and sample_range.low is None
    grey = decode_image("32FC1", height, width, width * 4, metres.view(np.uint8).ravel(),
                        sample_range=sample_range)[..., 0]
    assert grey[:8, :8].max() == 0 and grey[8:16, :8].min() == 255 and grey[16:, :8].max() == 0
    gain, residual = _linear_fit(grey[:, 8:], metres[:, 8:])
    assert gain >= 0.75 * 50 and residual <= 1, (gain, residual)


@pytest.mark.parametrize("codec", ["png", "rvl"])
@pytest.mark.parametrize("encoding", ["16UC1", "32FC1"])
def test_compressed_depth_images(tmp_path: Path, encoding: str, codec: str) -> None:
    # compressed_depth_image_transport's messages: a 12-byte header, then png or rvl (32FC1: quantised inverse depth)
    frames = _frames()
    write_image_bag(tmp_path / "bag", frames, compressed=f"{encoding}; compressedDepth {codec}")
    with open_image_stream(tmp_path / "bag") as stream:
        for frame, original in zip(stream, frames):
            gain, residual = _linear_fit(frame.rgb[..., 0], _grey(original))
            assert gain >= 0.75 and residual <= 1, (gain, residual)


def test_rvl_bit_layout() -> None:
    # [0, 0, 5, 0]: 2 zeros (nibble 2), 1 non-zero (1), 5 as zigzag 10 = 3-bit groups 010, 001 lowest
    # first (nibbles A, 1), 1 zero (1), no non-zero (0); nibbles fill a word from its top.
    from trap_core.bagio._rvl import rvl_decode, rvl_encode
    samples, complete = rvl_decode(np.array([0x21A11000], dtype=np.uint32), 4)
    assert complete and samples.tolist() == [0, 0, 5, 0]
    assert rvl_encode(samples).tolist() == [0x21A11000]
    rng = np.random.default_rng(3)
    depth = rng.integers(0, 65536, 5000).astype(np.uint16) * (rng.random(5000) < 0.6)
    decoded, complete = rvl_decode(rvl_encode(depth), depth.size)
    assert complete
    np.testing.assert_array_equal(decoded, depth)


def test_corrupt_compressed_depth_is_refused() -> None:
    from trap_core.bagio import compress_image
    rvl = compress_image(_frames(count=1)[0], "16UC1; compressedDepth rvl")
    huge = rvl.copy()
    huge[12:20] = 255
    cases = [(rvl[:12], "no image after its header"), (rvl[:-8], "end before its 32x24 pixels"),
             (huge, "rvl size 4294967295x4294967295"), (rvl[:12].copy(), "no image")]
    for data, message in cases:
        with pytest.raises(BagError, match=message):
            decode_compressed("16UC1; compressedDepth rvl", data)
    with pytest.raises(BagError, match="no 16-bit single-channel png"):
        decode_compressed("16UC1; compressedDepth png", rvl)
    with pytest.raises(BagError, match="'16UC1; compressedDepth zstd' is not supported"):
        decode_compressed("16UC1; compressedDepth zstd", rvl)
