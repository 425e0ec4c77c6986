"""vision_msgs built into the venv is interoperable with the upstream 4.1.1 package."""
from __future__ import annotations

import json

import pytest
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

from trap_ros.recording import share_dir

# Field definitions of vision_msgs 4.1.1 (the Jazzy release), as published upstream.
UPSTREAM_4_1_1 = {
    "Point2D": "float64 x\nfloat64 y\n",
    "Pose2D": "vision_msgs/Point2D position\nfloat64 theta\n",
    "BoundingBox2D": "vision_msgs/Pose2D center\nfloat64 size_x\nfloat64 size_y\n",
    "ObjectHypothesis": "string class_id\nfloat64 score\n",
    "ObjectHypothesisWithPose": "vision_msgs/ObjectHypothesis hypothesis\ngeometry_msgs/PoseWithCovariance pose\n",
    "Detection2D": "std_msgs/Header header\nvision_msgs/ObjectHypothesisWithPose[] results\n"
                   "vision_msgs/BoundingBox2D bbox\nstring id\n",
    "Detection2DArray": "std_msgs/Header header\nvision_msgs/Detection2D[] detections\n",
}


def _upstream_hashes() -> dict[str, str]:
    store = get_typestore(Stores.ROS2_JAZZY)
    types = {}
    for name, text in UPSTREAM_4_1_1.items():
        types.update(get_types_from_msg(text, f"vision_msgs/msg/{name}"))
    store.register(types)
    return {name: store.hash_rihs01(f"vision_msgs/msg/{name}") for name in UPSTREAM_4_1_1}


@pytest.mark.parametrize("name", sorted(UPSTREAM_4_1_1))
def test_installed_type_hash_matches_upstream(name: str) -> None:
    pytest.importorskip("vision_msgs.msg")
    description = json.loads((share_dir("vision_msgs") / "msg" / f"{name}.json").read_text())
    installed = {h["type_name"]: h["hash_string"] for h in description["type_hashes"]}
    assert installed[f"vision_msgs/msg/{name}"] == _upstream_hashes()[name]


def test_method_agrees_with_a_known_installed_type() -> None:
    """The hash computation used above reproduces the sensor_msgs/Image hash of the Jazzy wheels."""
    description = json.loads((share_dir("sensor_msgs") / "msg" / "Image.json").read_text())
    installed = {h["type_name"]: h["hash_string"] for h in description["type_hashes"]}
    assert installed["sensor_msgs/msg/Image"] == get_typestore(Stores.ROS2_JAZZY).hash_rihs01("sensor_msgs/msg/Image")


def test_messages_import_and_nest() -> None:
    from vision_msgs.msg import BoundingBox2D, Detection2D, Detection2DArray
    detection = Detection2D(id="7", bbox=BoundingBox2D(size_x=3.0, size_y=4.0))
    array = Detection2DArray(detections=[detection])
    assert array.detections[0].bbox.size_y == 4.0 and array.detections[0].id == "7"
