"""meshgap.plan(): a valid path (its states free, start and goal at its ends, the dense clearance the scene's), the
same bad-input messages as meshgap_plan, an SE(2) problem, and the report it can write; every meshgap_plan flag is a
keyword of plan(), the same seed gives the same summary and files from both, and optimize="clearance" raises the
path's clearance."""
import re
import subprocess

import numpy as np
import pytest

import meshgap
from conftest import MAPS, RESOURCES, box, cli_error, executable, merged, write_obj

HAND_BOWL = MAPS / "hand_bowl" / "hand_bowl.cfg"
SLOTTED_WALL = MAPS / "slotted_wall" / "slotted_wall.cfg"
# RRTConnect returns at its first exact solution (well under a second on these maps): the limit only ends a search
# that fails anyway, so a busy machine cannot change a verdict.
PLAN_TIME = 300.0


def same_pose(a, b):
    """Equal poses, a quaternion and its negative being the same rotation."""
    if len(a) == 3:
        return np.allclose(a[:2], b[:2], atol=1e-9) and np.isclose(np.cos(a[2] - b[2]), 1.0, atol=1e-12)
    return np.allclose(a[:3], b[:3], atol=1e-9) and abs(abs(np.dot(a[3:], b[3:])) - 1.0) < 1e-9


def test_plan_returns_a_valid_path(tmp_path):
    report = tmp_path / "plan.html" if meshgap.REPORT_AVAILABLE else None
    path, summary = meshgap.plan(HAND_BOWL, planner="rrtconnect", time=PLAN_TIME, seed=3, report=report)
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
    first, _ = meshgap.plan(HAND_BOWL, seed=11, time=PLAN_TIME)
    again, _ = meshgap.plan(HAND_BOWL, seed=11, time=PLAN_TIME)
    assert np.array_equal(first, again)


def test_fast_checker_plans_a_free_path():
    """checker="fast", as meshgap_plan --checker fast: validity is still exact, so every state is free."""
    path, summary = meshgap.plan(HAND_BOWL, checker="fast", time=PLAN_TIME, seed=3)
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
    path, summary = meshgap.plan(tmp_path / "gap.cfg", time=PLAN_TIME)
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
    ({"optimize_rounds": 3}, None, r"^optimize_rounds: applies to optimize only$"),
    ({"optimize": "clearance", "checker": "fast"}, None, r"^optimize: clearance needs checker certified"),
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


def help_flags():
    """meshgap_plan's flags as its --help lists them: {name: whether it takes a value}."""
    run = subprocess.run([executable("plan"), "--help"], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    flags = {}
    for line in run.stdout.splitlines():
        m = re.match(r"^  (?:-\w \[ )?--([a-z][\w-]*)(?: \])?( arg)?", line)
        if m:
            flags[m.group(1)] = m.group(2) is not None
    assert len(flags) > 15, run.stdout
    return flags


def test_every_flag_is_a_keyword():
    """Each flag of meshgap_plan --help is a keyword of plan() (dashes as underscores) taking the same kind of value,
    and plan() has no other keyword but params (Python's dict of planner parameters); --help is the CLI's own."""
    flags = help_flags()
    # MoveIt's files (--urdf, --srdf, --scene, --request) are not plan() keywords yet: Python reads them through
    # meshgap.RobotScene.from_moveit, and a robot .cfg's scene = / request = keys reach plan() through cfg.
    moveit = {"urdf", "srdf", "scene", "request"}
    keywords = {name.replace("-", "_"): takes_value for name, takes_value in flags.items()
                if name != "help" and name not in moveit}
    assert set(meshgap.PLAN_KEYWORDS) == set(keywords) | {"params"}
    # An unknown keyword is refused, naming it and listing the valid ones.
    with pytest.raises(TypeError) as raised:
        meshgap.plan(HAND_BOWL, optimise=None)
    message = str(raised.value)
    assert message.startswith("plan() got an unexpected keyword argument 'optimise'; valid: ")
    assert set(message.split("valid: ")[1].split(", ")) == set(keywords) | {"params"}
    # Each one is taken (a value of the wrong type is refused with the keyword's name, not as unknown); a flag
    # without a value is a bool.
    for keyword, takes_value in keywords.items():
        if keyword == "cfg":
            continue
        with pytest.raises(ValueError) as raised:
            meshgap.plan(HAND_BOWL, **{keyword: object()})
        assert str(raised.value).startswith(keyword + ": expected "), str(raised.value)
        assert ("expected a bool" in str(raised.value)) == (not takes_value), (keyword, str(raised.value))


def without_times(text):
    """The summary without what the clock decides: the planning, query and optimiser times."""
    lines = [line for line in text.splitlines() if not line.startswith(("planning time", "query time"))]
    return "\n".join(re.sub(r"^(optimizer +clearance), [0-9.e+-]+ s,", r"\1,", line) for line in lines)


@pytest.mark.parametrize("flags", [
    {"seed": 7},
    {"seed": 2, "motion": "clearance", "optimize": "clearance", "optimize_time": 300.0, "dense": 2},
])
def test_cli_and_plan_give_the_same_run(tmp_path, flags):
    """The same flags and seed: meshgap_plan and plan() print the same summary (the times aside) and write the same
    path, clearance CSV and scene (.glb), byte for byte."""
    args = [executable("plan"), "--cfg", str(SLOTTED_WALL), "--time", str(PLAN_TIME), "-q"]
    for keyword, value in flags.items():
        args += ["--" + keyword.replace("_", "-"), str(value)]
    cli = subprocess.run(args + ["--out", str(tmp_path / "cli.path"), "--clearance-csv", str(tmp_path / "cli.csv"),
                                 "--summary", str(tmp_path / "cli.txt"), "--export-glb", str(tmp_path / "cli.glb"),
                                 "--export-states", "3"], capture_output=True, text=True, timeout=600)
    assert cli.returncode == 0, cli.stderr
    path, summary = meshgap.plan(SLOTTED_WALL, time=PLAN_TIME, out=tmp_path / "py.path",
                                 clearance_csv=str(tmp_path / "py.csv"), summary=tmp_path / "py.txt",
                                 export_glb=tmp_path / "py.glb", export_states=3, **flags)
    assert summary["solved"] and summary["exact"]
    assert (tmp_path / "py.txt").read_text() == summary["text"]
    assert without_times(summary["text"]) == without_times((tmp_path / "cli.txt").read_text())
    assert ("optimizer" in summary["text"]) == ("optimize" in flags)
    assert (tmp_path / "py.path").read_bytes() == (tmp_path / "cli.path").read_bytes()
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    assert (tmp_path / "py.glb").read_bytes() == (tmp_path / "cli.glb").read_bytes()
    assert len(path) == summary["states"] == len(
        [line for line in (tmp_path / "cli.path").read_text().splitlines() if line.strip()])


def test_optimize_clearance_raises_the_minimum_clearance():
    """optimize="clearance" (certified motions): the optimised path is free at every dense state, still joins start
    and goal, and its least clearance (the scene's exact distance) is above the planner's path's, same seed."""
    scene = meshgap.Scene.from_cfg(SLOTTED_WALL)
    plain_path, plain = meshgap.plan(SLOTTED_WALL, seed=2, motion="clearance", time=PLAN_TIME)
    path, summary = meshgap.plan(SLOTTED_WALL, seed=2, motion="clearance", time=PLAN_TIME, optimize="clearance",
                                 optimize_time=300.0)
    assert plain["solved"] and summary["solved"]
    assert same_pose(path[0], scene.start) and same_pose(path[-1], scene.goal)
    dense = summary["dense"]["poses"]
    assert not scene.in_collision(dense).any()
    exact = scene.distance(dense)["distance"]
    assert summary["min_clearance"] == pytest.approx(exact.min(), rel=1e-9)
    assert exact.min() > 1.5 * scene.distance(plain["dense"]["poses"])["distance"].min()
    assert re.search(r"^opt clearance +[0-9.e+-]+ -> [0-9.e+-]+", summary["text"], re.M)


def test_every_kind_is_one_run_with_one_summary_and_the_path_files_rows(tmp_path):
    """A single body and a robot go through the same run: the summary dict has the same keys (the single body's
    checker adds its counters), the dense path and the limiting pair for both, and the path's rows are the .path file's
    numbers, exactly (a single body's quaternions as the planner's states hold them)."""
    arm = MAPS / "arm_fixture" / "arm_fixture.cfg"
    body_path, body = meshgap.plan(HAND_BOWL, seed=1, time=PLAN_TIME, out=tmp_path / "body.path")
    arm_path, robot = meshgap.plan(arm, seed=1, time=PLAN_TIME, out=tmp_path / "arm.path", optimize="clearance",
                                   optimize_time=1.0)
    counters = {"validity_calls", "clearance_calls", "query_time"}
    assert counters <= set(body) and not counters & set(robot)
    assert set(body) - counters == set(robot) - {"min_clearance_before", "limiting_pair_before", "optimize_failed"}
    assert body["robot"] == "one body in SE(3)" and robot["robot"].startswith("URDF 'arm4'")
    assert body["limiting_pair"] == "link 'robot' and obstacle 0" and robot["limiting_pair"] in robot["text"]
    assert robot["min_clearance_before"] <= robot["min_clearance"] + 1e-9 and not robot["optimize_failed"]
    for path, summary, file in ((body_path, body, "body.path"), (arm_path, robot, "arm.path")):
        assert np.array_equal(np.loadtxt(tmp_path / file, ndmin=2), path)
        dense = summary["dense"]
        assert dense["poses"].shape == (len(dense["clearance"]), path.shape[1])
        assert summary["min_clearance"] == dense["clearance"].min()
        assert summary["min_clearance_arc_length"] == dense["arc_length"][dense["clearance"].argmin()]
