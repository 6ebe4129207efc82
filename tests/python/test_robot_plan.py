"""meshgap.plan() on robot problems (maps/arm_fixture: a URDF arm carrying a payload): the same run as meshgap_plan
for the same seed, with optimize="clearance" (the summary, the times aside, and the path file, byte for byte); the
optimised path is free, joins start and goal and is clearer than the planner's path; the clearance objectives."""
import re
import subprocess

import numpy as np
import pytest

import meshgap
from conftest import MAPS, executable

ARM = MAPS / "arm_fixture" / "arm_fixture.cfg"
# RRTConnect's first exact solution comes well under a second; the optimiser converges (a round changes nothing)
# on seed 5 in a few seconds: the limits only end runs that fail anyway, so a busy machine cannot change a verdict.
PLAN_TIME = 300.0


def without_times(text):
    """The summary without what the clock decides: the planning time and the optimiser's."""
    lines = [line for line in text.splitlines() if not line.startswith("planning time")]
    return "\n".join(re.sub(r"^(optimizer +clearance), [0-9.e+-]+ s,", r"\1,", line) for line in lines)


def test_optimize_clearance_is_the_clis_run_and_raises_the_clearance(tmp_path):
    args = [executable("plan"), "--cfg", str(ARM), "--seed", "5", "--time", str(PLAN_TIME), "-q", "--optimize",
            "clearance", "--optimize-time", str(PLAN_TIME), "--summary", str(tmp_path / "cli.txt"), "--out",
            str(tmp_path / "cli.path")]
    cli = subprocess.run(args, capture_output=True, text=True, timeout=900)
    assert cli.returncode == 0, cli.stderr
    path, summary = meshgap.plan(ARM, seed=5, time=PLAN_TIME, optimize="clearance", optimize_time=PLAN_TIME,
                                 summary=tmp_path / "py.txt", out=tmp_path / "py.path")
    assert summary["robot"] and summary["solved"] and summary["exact"]
    assert (tmp_path / "py.txt").read_text() == summary["text"]
    assert without_times(summary["text"]) == without_times((tmp_path / "cli.txt").read_text())
    assert (tmp_path / "py.path").read_bytes() == (tmp_path / "cli.path").read_bytes()
    # The optimised path: the problem's start and goal at its ends, every state free, and its exact clearance over
    # the dense path (the pair that limits it named) above the planner's path's.
    scene = meshgap.RobotScene.from_cfg(ARM)
    assert path.shape == (summary["states"], 4)
    assert np.array_equal(path[0], scene.start) and np.array_equal(path[-1], scene.goal)
    exact = scene.distance(path)["distance"]
    assert (exact > 0).all()
    assert exact.min() >= summary["min_clearance"] - 1e-12
    assert summary["dense_path_free"] and not summary["optimize_failed"]
    assert summary["min_clearance"] > 2 * summary["min_clearance_before"]
    assert re.search(r"^opt before +[0-9.e+-]+ \(exact, over the dense path; link '\w+' and obstacle 0\)$",
                     summary["text"], re.M)
    assert re.search(r"^opt after +%s " % re.escape("%g" % summary["min_clearance"]), summary["text"], re.M)
    assert summary["limiting_pair"] in summary["text"]


@pytest.mark.parametrize("objective", ["max_min_clearance", "clearance", "weighted"])
def test_clearance_objectives_plan_a_robot(objective):
    path, summary = meshgap.plan(ARM, seed=1, time=PLAN_TIME, objective=objective)
    assert summary["solved"] and summary["objective"] == objective
    assert len(path) == summary["states"] and path.shape[1] == 4
    assert np.isfinite(summary["cost"])
    if objective == "max_min_clearance":
        # The cost of a path is its least clearance at the objective's grid states: at least the exact minimum
        # over every state of it (the dense path's, up to its sampling), never more than its vertices' least.
        scene = meshgap.RobotScene.from_cfg(ARM)
        assert summary["cost"] <= scene.distance(path[1:])["distance"].min() + 1e-12
        assert "cost queries" in summary["text"]


def test_robot_plan_refuses_what_a_robot_problem_does_not_take(tmp_path):
    with pytest.raises(ValueError, match="weight"):
        meshgap.plan(ARM, seed=1, objective="length", weight=0.5)
    with pytest.raises(ValueError, match="checker"):
        meshgap.plan(ARM, seed=1, checker="fast")
    with pytest.raises(ValueError, match="sampler"):
        meshgap.plan(ARM, seed=1, sampler="no_such_sampler")
    # The scene export, as for a single body (every link at each exported state), and a sampler accepted; RRTConnect
    # ends at its first solution, so a busy machine cannot change the verdict.
    path, summary = meshgap.plan(ARM, seed=1, planner="rrtconnect", time=PLAN_TIME, sampler="gaussian",
                                 export_glb=tmp_path / "arm.glb", export_states=2)
    assert summary["planner"] == "rrtconnect" and (tmp_path / "arm.glb").stat().st_size > 0
