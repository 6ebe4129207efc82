"""meshgap.plan(): a valid path (its states free, start and goal at its ends, the dense clearance the scene's), the
same bad-input messages as meshgap_plan, an SE(2) problem, and the report it can write."""
import numpy as np
import pytest

import meshgap
from conftest import MAPS, RESOURCES, box, cli_error, executable, merged, write_obj

HAND_BOWL = MAPS / "hand_bowl" / "hand_bowl.cfg"


def same_pose(a, b):
    """Equal poses, a quaternion and its negative being the same rotation."""
    if len(a) == 3:
        return np.allclose(a[:2], b[:2], atol=1e-9) and np.isclose(np.cos(a[2] - b[2]), 1.0, atol=1e-12)
    return np.allclose(a[:3], b[:3], atol=1e-9) and abs(abs(np.dot(a[3:], b[3:])) - 1.0) < 1e-9


def test_plan_returns_a_valid_path(tmp_path):
    report = tmp_path / "plan.html" if meshgap.REPORT_AVAILABLE else None
    path, summary = meshgap.plan(HAND_BOWL, planner="rrtconnect", time=20.0, seed=3, report=report)
    assert summary["solved"] and summary["exact"] and summary["problem"] == "hand_bowl" and not summary["planar"]
    assert summary["checker"] == "certified"
    assert path.ndim == 2 and path.shape[1] == 7 and len(path) == summary["states"] >= 2
    scene = meshgap.Scene.from_cfg(HAND_BOWL)
    assert same_pose(path[0], scene.start) and same_pose(path[-1], scene.goal)
    dense = summary["dense"]
    assert not scene.in_collision(path).any() and not scene.in_collision(dense["poses"]).any()
    # The summary's clearance is the scene's exact distance at the dense states, and its minimum.
    np.testing.assert_allclose(scene.distance(dense["poses"])["distance"], dense["clearance"], rtol=1e-9, atol=1e-9)
    assert summary["min_clearance"] == dense["clearance"].min() > 0 and summary["dense_path_free"]
    assert np.all(np.diff(dense["arc_length"]) >= 0)
    # Length: the sum of SE(3) distances (translation + rotation) is at least the translation's.
    assert summary["length"] >= np.linalg.norm(np.diff(path[:, :3], axis=0), axis=1).sum() - 1e-9
    assert report is None or report.stat().st_size > 100000


def test_same_seed_same_path():
    first, _ = meshgap.plan(HAND_BOWL, seed=11, time=20.0)
    again, _ = meshgap.plan(HAND_BOWL, seed=11, time=20.0)
    assert np.array_equal(first, again)


def test_fast_checker_plans_a_free_path():
    """checker="fast", as meshgap_plan --checker fast: validity is still exact, so every state is free."""
    path, summary = meshgap.plan(HAND_BOWL, checker="fast", time=20.0, seed=3)
    assert summary["checker"] == "fast" and summary["solved"]
    assert not meshgap.Scene.from_cfg(HAND_BOWL).in_collision(path).any()


def test_plan_with_clearance_objective_and_params():
    path, summary = meshgap.plan(str(HAND_BOWL), planner="rrtstar", objective="max_min_clearance", time=0.5,
                                 params={"use_k_nearest": False, "range": 50}, motion="clearance")
    assert summary["objective"] == "max_min_clearance" and summary["planner"] == "rrtstar"
    if summary["solved"]:
        assert path.shape[1] == 7


def test_planar_problem(tmp_path):
    # A wall with a gap in the plane, a bar robot (OMPL.app 2D conventions: no start.z, theta is the yaw).
    write_obj(tmp_path / "wall.obj", merged(box(0.3, 2.25, 0.5, (0, 2.75, 0.5)), box(0.3, 2.25, 0.5, (0, -2.75, 0.5))))
    write_obj(tmp_path / "bar.obj", box(0.6, 0.2, 0.5, (0.25, 0.1, 0.5)))
    (tmp_path / "gap.cfg").write_text(
        "[problem]\nname = gap\nrobot = bar.obj\nworld = wall.obj\nstart.x = -3\nstart.y = 0.5\n"
        "start.theta = 1.5707963267948966\ngoal.x = 3\ngoal.y = -0.5\ngoal.theta = -1.5707963267948966\n"
        "volume.min.x = -5\nvolume.min.y = -5\nvolume.max.x = 5\nvolume.max.y = 5\n")
    path, summary = meshgap.plan(tmp_path / "gap.cfg", time=10.0)
    assert summary["solved"] and summary["planar"] and path.shape[1] == 3
    scene = meshgap.Scene.from_cfg(tmp_path / "gap.cfg")
    assert scene.planar and scene.start.shape == (3,)
    assert same_pose(path[0], scene.start) and same_pose(path[-1], scene.goal)
    assert not scene.in_collision(summary["dense"]["poses"]).any()
    # Through the gap (|y| < 0.5 at the wall): the path's smallest clearance cannot exceed the gap's half width.
    assert 0 < summary["min_clearance"] <= 0.5


@pytest.mark.parametrize("kwargs,flag,message", [
    ({"planner": "nosuch"}, ["--planner", "nosuch"], "planner"),
    ({"objective": "nosuch"}, ["--objective", "nosuch"], "objective"),
    ({"params": {"nosuch": "1"}}, None, r"^params: "),
    ({"time": -1.0}, None, r"^time: must be positive"),
    ({"checker": "both"}, None, r"^checker: 'both' is not certified or fast$"),
    ({"mode": "fast"}, None, r"^mode: renamed: use checker='certified' or checker='fast'$"),
    ({"checker": "fast", "motion": "clearance"}, None, r"^motion: clearance needs checker certified"),
])
def test_bad_plan_arguments(kwargs, flag, message):
    with pytest.raises(ValueError, match=message) as raised:
        meshgap.plan(HAND_BOWL, **{"time": 0.1, **kwargs})
    if flag:  # the planner and objective names are checked by the library: the CLI's message
        assert str(raised.value) == cli_error([executable("plan"), "--cfg", str(HAND_BOWL), "-q"] + flag)


@pytest.mark.parametrize("cfg,error", [("missing_mesh.cfg", FileNotFoundError), ("start_outside.cfg", ValueError),
                                       ("no_such.cfg", FileNotFoundError), ("corrupt.stl", ValueError)])
def test_bad_cfg_gives_the_cli_message(cfg, error):
    path = str(RESOURCES / "bad" / cfg)
    with pytest.raises(error) as raised:
        meshgap.plan(path, time=0.1)
    assert str(raised.value) == cli_error([executable("plan"), "--cfg", path, "-q", "--time", "0.1"])
