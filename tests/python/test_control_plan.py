"""meshgap.plan() on control problems (a 'control' key): the kinematic car, blimp and quadrotor of maps/ and OMPL.app's
BugTrap_dcar, planned as meshgap_plan plans them: the path is the model's states one propagation step apart (the
rows --out writes, number for number), starting at the cfg's start, in the volume and certified free; the summary
dict agrees with the summary text. Bad input: a geometric planner or a geometric option, one ValueError naming it."""
import numpy as np
import pytest

import meshgap
from conftest import MAPS, omplapp

# (problem, columns of a state: the pose's reals, then the model's velocities)
PROBLEMS = [(MAPS / "car_chicane" / "car_chicane.cfg", "kinematic_car", 3),
            (MAPS / "blimp_window" / "blimp_window.cfg", "blimp", 11),
            (MAPS / "quadrotor_window" / "quadrotor_window.cfg", "quadrotor", 13)]


def read_rows(path):
    return np.array([[float(v) for v in line.split()] for line in path.read_text().splitlines() if line.strip()])


@pytest.mark.parametrize("cfg,model,width", PROBLEMS, ids=[p[1] for p in PROBLEMS])
def test_plan_writes_the_path_it_returns(tmp_path, cfg, model, width):
    path, summary = meshgap.plan(cfg, seed=2, time=2, out=tmp_path / "p.path", summary=tmp_path / "s.txt")
    assert summary["control"] == model and summary["planner"] == "kpiece" and summary["checker"] == "certified"
    assert summary["solved"]
    assert path.shape == (summary["states"], width)
    assert np.array_equal(path, read_rows(tmp_path / "p.path"))
    assert (tmp_path / "s.txt").read_text() == summary["text"]
    assert "problem         %s (control: %s)" % (cfg.stem, model) in summary["text"]
    assert ("solved          yes (exact)" in summary["text"]) == summary["exact"]
    assert summary["min_clearance"] > 0.0
    assert summary["goal_distance"] >= 0.0 and summary["duration"] > 0.0
    # The first state is the cfg's start, at rest (the velocities follow the SE(3) pose's 7 numbers).
    assert path[0, 0] == (-4.5 if model == "kinematic_car" else -3.0)
    assert width == 3 or np.all(path[0, 7:] == 0.0)


def test_plan_bugtrap_dynamic_car():
    cfg = omplapp("BugTrap_dcar.cfg")
    path, summary = meshgap.plan(cfg, planner="est", seed=1, time=2)
    assert summary["control"] == "dynamic_car" and summary["planner"] == "est"
    assert summary["solved"] and path.shape == (summary["states"], 5)
    assert np.allclose(path[0], [6.0, 12.0, 0.0, 0.0, 0.0])


def test_bad_input_names_the_keyword():
    cfg = PROBLEMS[1][0]
    with pytest.raises(ValueError, match="planner rrtconnect: not a control planner"):
        meshgap.plan(cfg, planner="rrtconnect", time=1)
    with pytest.raises(ValueError, match="objective: applies to geometric problems only"):
        meshgap.plan(cfg, objective="length", time=1)
