"""meshgap.RobotScene.from_moveit: the test arm (boxes) in a MoveIt planning scene of one box, distances against the
gaps of axis-aligned boxes worked out by hand, the allowed collision matrix honoured, the request's start and goal,
and one clear error for a bad scene."""
import os

import numpy as np
import pytest

import meshgap

HERE = os.path.dirname(os.path.abspath(__file__))
ARM = os.path.join(HERE, "..", "resources", "robot", "problems", "arm2.urdf")

# arm2 at yaw = elbow = 0: the forearm box spans x in [0.5, 0.9], y in [-0.02, 0.02], z in [0.18, 0.22]; the base
# box x, y in [-0.1, 0.1], z in [0, 0.1]. The block spans x in [1.1, 1.3], y in [-0.1, 0.1], z in [0.1, 0.3]: the
# forearm's end is 0.2 from it. With the forearm allowed to touch the block, the least gap is the base against the
# forearm (self pair): hypot(0.5 - 0.1, 0.18 - 0.1).
SCENE = """world:
  collision_objects:
    - id: block
      pose: {position: [1.0, 0, 0], orientation: [0, 0, 0, 1]}
      primitives:
        - type: box
          dimensions: [0.2, 0.2, 0.2]
      primitive_poses:
        - position: [0.2, 0, 0.2]
          orientation: [0, 0, 0, 1]
robot_state:
  joint_state: {name: [yaw, elbow], position: [0, 0]}
%s"""
ACM = """allowed_collision_matrix:
  entry_names: [fore, block]
  entry_values:
    - enabled: [false, true]
    - enabled: [true, false]
"""
REQUEST = """start_state:
  joint_state: {name: [yaw, elbow], position: [0.5, 0.25]}
goal_constraints:
  - joint_constraints:
      - {joint_name: yaw, position: -1.0}
      - {joint_name: elbow, position: -0.5}
"""


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_distances_match_the_boxes_and_the_matrix_is_honoured(tmp_path):
    s = meshgap.RobotScene.from_moveit(ARM, scene=write(tmp_path, "scene.yaml", SCENE % ""))
    r = s.distance(np.zeros((1, 2)))
    assert r["distance"][0] == pytest.approx(0.2, abs=1e-9)
    assert s.link_names[r["link"][0]] == "fore"
    allowed = meshgap.RobotScene.from_moveit(ARM, scene=write(tmp_path, "acm.yaml", SCENE % ACM))
    r = allowed.distance(np.zeros((1, 2)))
    assert r["distance"][0] == pytest.approx(np.hypot(0.4, 0.08), abs=1e-9)
    assert r["self_pair"][0]


def test_request_gives_start_and_goal(tmp_path):
    s = meshgap.RobotScene.from_moveit(ARM, scene=write(tmp_path, "scene.yaml", SCENE % ""),
                                       request=write(tmp_path, "request.yaml", REQUEST))
    np.testing.assert_allclose(s.start, [0.5, 0.25])
    np.testing.assert_allclose(s.goal, [-1.0, -0.5])


def test_bad_scene_names_the_file_and_entry(tmp_path):
    bad = write(tmp_path, "bad.yaml", "world:\n  collision_objects:\n    - id: b\n      primitives:\n"
                                      "        - type: box\n          dimensions: [0.2, 0.2]\n"
                                      "      primitive_poses:\n        - position: [0, 0, 0]\n"
                                      "          orientation: [0, 0, 0, 1]\n")
    with pytest.raises(Exception) as e:
        meshgap.RobotScene.from_moveit(ARM, scene=bad)
    assert "bad.yaml" in str(e.value) and "dimensions" in str(e.value)
