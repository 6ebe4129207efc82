"""meshgap.RobotScene: a URDF arm of boxes whose link poses are composed here by hand, its whole-robot distances,
per-link and per-pair clearances checked against analytic box distances (quarter turns keep every box axis-aligned),
threads, payloads, and bad input (one clear exception)."""
import math

import numpy as np
import pytest

import meshgap
from conftest import RESOURCES, box, merged, write_obj

# The arm: a fixed base box; "upper" turns about z (revolute "turn") on top of it; "slider" hangs from the upper
# arm's far end, facing back (a half turn about z), and slides along its own x ("slide", prismatic), so it can reach
# the base; "tool" sits on the slider by a fixed joint turned a quarter about z. Boxes as (half sizes, centre) in
# their link's frame.
LINKS = {
    "base": ((0.5, 0.5, 0.25), (0.0, 0.0, 0.25)),
    "upper": ((1.0, 0.25, 0.25), (1.0, 0.0, 0.25)),
    "slider": ((0.25, 0.25, 0.7), (0.0, 0.0, -0.2)),
    "tool": ((0.1, 0.2, 0.05), (0.0, 0.0, 0.6)),
}
URDF = """<?xml version="1.0"?>
<robot name="boxarm">
  {links}
  <joint name="turn" type="revolute">
    <origin xyz="0 0 0.5" rpy="0 0 0"/>
    <parent link="base"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit lower="-3.5" upper="3.5" effort="1" velocity="1"/>
  </joint>
  <joint name="slide" type="prismatic">
    <origin xyz="2 0 0.5" rpy="0 0 3.141592653589793"/>
    <parent link="upper"/><child link="slider"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="2.5" effort="1" velocity="1"/>
  </joint>
  <joint name="mount" type="fixed">
    <origin xyz="0 0 0.5" rpy="0 0 1.5707963267948966"/>
    <parent link="slider"/><child link="tool"/>
  </joint>
</robot>
"""
# The world: two boxes (half sizes, centre).
WORLD = [((0.5, 0.5, 0.75), (0.0, 2.75, 0.75)), ((0.5, 1.0, 1.0), (-3.0, 0.0, 1.0))]


def urdf_text():
    links = []
    for name, (half, centre) in LINKS.items():
        size = " ".join("%.17g" % (2 * h) for h in half)
        xyz = " ".join("%.17g" % c for c in centre)
        links.append('<link name="%s"><collision><origin xyz="%s" rpy="0 0 0"/><geometry><box size="%s"/>'
                     "</geometry></collision></link>" % (name, xyz, size))
    return URDF.format(links="\n  ".join(links))


def rot_z(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def transform(R, t):
    X = np.eye(4)
    X[:3, :3] = R
    X[:3, 3] = t
    return X


def link_frames(turn, slide):
    """Every link frame's world pose, composed by hand from the URDF above."""
    base = np.eye(4)
    upper = base @ transform(np.eye(3), (0, 0, 0.5)) @ transform(rot_z(turn), (0, 0, 0))
    slider = upper @ transform(rot_z(math.pi), (2, 0, 0.5)) @ transform(np.eye(3), (slide, 0, 0))
    tool = slider @ transform(rot_z(math.pi / 2), (0, 0, 0.5))
    return {"base": base, "upper": upper, "slider": slider, "tool": tool}


def world_boxes(turn, slide):
    """Each link's box in the world as (half sizes, centre), for turns by quarter turns (axis-aligned boxes)."""
    out = {}
    for name, X in link_frames(turn, slide).items():
        half, centre = LINKS[name]
        R = np.round(X[:3, :3])  # a quarter-turn rotation: a signed permutation
        out[name] = (np.abs(R) @ np.asarray(half), X[:3, :3] @ np.asarray(centre) + X[:3, 3])
    return out


def box_gap(a, b):
    """Distance between two axis-aligned boxes (half sizes, centre), and whether they overlap (strictly)."""
    gap = np.abs(np.asarray(a[1]) - b[1]) - (np.asarray(a[0]) + b[0])
    return float(np.linalg.norm(np.maximum(gap, 0.0))), bool(np.all(gap < 0))


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("boxarm")
    (folder / "boxarm.urdf").write_text(urdf_text())
    write_obj(folder / "world.obj", merged(*[box(*h, center=c) for h, c in WORLD]))
    return folder


@pytest.fixture(scope="module")
def arm(files):
    return meshgap.RobotScene.from_urdf(files / "boxarm.urdf", world=files / "world.obj")


def quarter_turn_states(rng, count):
    turns = rng.integers(-2, 3, size=count) * (math.pi / 2)
    return np.column_stack([turns, rng.uniform(-1.0, 2.5, size=count)])


def test_model(arm):
    assert arm.dimension == 2 and arm.state_names == ["turn", "slide"]
    assert arm.link_names == ["base", "upper", "slider", "tool"] and arm.obstacles == 2
    # Links joined by a joint are never checked against each other.
    assert sorted(arm.self_pairs) == [("base", "slider"), ("base", "tool"), ("upper", "tool")]
    np.testing.assert_array_equal(arm.bounds, [[-3.5, 3.5], [-1.0, 2.5]])
    assert arm.start is None and arm.goal is None and "boxarm" in repr(arm)


def test_link_poses_composed_by_hand(arm):
    rng = np.random.default_rng(3)
    states = np.column_stack([rng.uniform(-3.5, 3.5, 50), rng.uniform(-1.0, 2.5, 50)])
    poses = arm.link_poses(states)
    assert poses.shape == (50, 4, 4, 4)
    for i, (turn, slide) in enumerate(states):
        frames = link_frames(turn, slide)
        for k, name in enumerate(arm.link_names):
            np.testing.assert_allclose(poses[i, k], frames[name], atol=1e-12)


def test_distance_matches_analytic_boxes(arm):
    states = quarter_turn_states(np.random.default_rng(7), 300)
    r = arm.distance(states)
    names = arm.link_names
    pairs = [(names.index(a), names.index(b)) for a, b in arm.self_pairs]
    collisions = 0
    for i, (turn, slide) in enumerate(states):
        boxes = world_boxes(turn, slide)
        per_link = [[box_gap(boxes[n], (np.asarray(h), np.asarray(c))) for h, c in WORLD] for n in names]
        per_pair = [box_gap(boxes[names[a]], boxes[names[b]]) for a, b in pairs]
        collides = any(c for g in per_link for _, c in g) or any(c for _, c in per_pair)
        collisions += collides
        assert r["in_collision"][i] == collides, (i, states[i])
        assert r["certified"][i]
        for k in range(len(names)):
            if not any(c for _, c in per_link[k]):
                d = min(g for g, _ in per_link[k])
                assert r["link_obstacle_distance"][i, k] == pytest.approx(d, rel=1e-9, abs=1e-9), (i, k)
            else:
                assert r["link_obstacle_distance"][i, k] <= 0.0
        for p, (g, c) in enumerate(per_pair):
            if c:
                assert r["self_pair_distance"][i, p] <= 0.0
            else:
                assert r["self_pair_distance"][i, p] == pytest.approx(g, rel=1e-9, abs=1e-9), (i, p)
        # A link's clearance: the least of its pairs; the whole robot's: the least of all.
        for k in range(len(names)):
            mine = [r["link_obstacle_distance"][i, k]] + [r["self_pair_distance"][i, p]
                                                          for p, (a, b) in enumerate(pairs) if k in (a, b)]
            assert r["link_clearance"][i, k] == min(mine)
        assert r["distance"][i] == r["link_clearance"][i].min()
        if collides:
            continue
        check_attaining_pair(r, i, boxes, names, pairs)
    assert 30 <= collisions <= 270  # both verdicts well represented


def check_attaining_pair(r, i, boxes, names, pairs):
    """The reported pair attains the distance, and the witness points lie on its two boxes that far apart."""
    d = r["distance"][i]
    link = r["link"][i]
    if r["self_pair"][i]:
        other = r["other_link"][i]
        assert r["obstacle"][i] == -1 and (link, other) in pairs
        assert r["self_pair_distance"][i, pairs.index((link, other))] == d
        second = boxes[names[other]]
    else:
        assert r["other_link"][i] == -1 and 0 <= r["obstacle"][i] < len(WORLD)
        assert r["link_obstacle_distance"][i, link] == d
        h, c = WORLD[r["obstacle"][i]]
        second = (np.asarray(h), np.asarray(c))
        assert box_gap(boxes[names[link]], second)[0] == pytest.approx(d, rel=1e-9, abs=1e-9)
    assert np.linalg.norm(r["on_a"][i] - r["on_b"][i]) == pytest.approx(d, rel=1e-9, abs=1e-9)
    for point, (half, centre) in ((r["on_a"][i], boxes[names[link]]), (r["on_b"][i], second)):
        local = np.abs(point - centre)
        assert np.all(local <= half + 1e-9) and np.any(np.abs(local - half) <= 1e-9)


def test_minimum_only_and_threads_agree(arm):
    rng = np.random.default_rng(11)
    states = np.column_stack([rng.uniform(-3.5, 3.5, 700), rng.uniform(-1.0, 2.5, 700)])
    full = arm.distance(states)
    fast = arm.distance(states, every_pair=False)
    assert "link_clearance" not in fast
    np.testing.assert_array_equal(fast["in_collision"], full["in_collision"])
    free = ~full["in_collision"]
    np.testing.assert_allclose(fast["distance"][free], full["distance"][free], rtol=1e-12, atol=1e-12)
    threaded = arm.distance(states, threads=3)
    for key in ("distance", "link_clearance", "self_pair_distance", "in_collision"):
        np.testing.assert_array_equal(threaded[key], full[key])
    np.testing.assert_array_equal(arm.in_collision(states), full["in_collision"])
    np.testing.assert_array_equal(arm.in_collision(states, threads=2), full["in_collision"])


def test_self_collision_off(arm):
    # The slider pulled back over the base: only the base-slider pair collides.
    state = np.array([[0.0, 2.25]])
    assert arm.in_collision(state)[0]
    r = arm.distance(state)
    assert r["self_pair"][0] and r["in_collision"][0]
    assert {r["link"][0], r["other_link"][0]} == {0, 2}
    assert not arm.in_collision(state, self_collision=False)[0]
    off = arm.distance(state, self_collision=False)
    assert not off["in_collision"][0] and np.all(np.isinf(off["self_pair_distance"]))
    boxes = world_boxes(0.0, 2.25)
    expected = min(box_gap(boxes[n], (np.asarray(h), np.asarray(c)))[0] for n in LINKS for h, c in WORLD)
    assert off["distance"][0] == pytest.approx(expected, rel=1e-9)


def test_attached_payload(files):
    # A small cube fixed to the tool, 0.3 above it: checked against the world and every link but the tool.
    payload = box(0.05, 0.05, 0.05)
    scene = meshgap.RobotScene.from_urdf(files / "boxarm.urdf", world=files / "world.obj",
                                         attach=(payload, "tool", [0, 0, 0.9, 0, 0, 0, 1]))
    assert scene.link_names[-1] == "payload"
    assert ("tool", "payload") not in scene.self_pairs and ("base", "payload") in scene.self_pairs
    states = quarter_turn_states(np.random.default_rng(5), 100)
    r = scene.distance(states)
    poses = scene.link_poses(states)
    k = scene.link_names.index("payload")
    for i, (turn, slide) in enumerate(states):
        centre = link_frames(turn, slide)["tool"] @ np.array([0, 0, 0.9, 1.0])
        np.testing.assert_allclose(poses[i, k][:3, 3], centre[:3], atol=1e-12)
        gaps = [box_gap((np.full(3, 0.05), centre[:3]), (np.asarray(h), np.asarray(c))) for h, c in WORLD]
        if not any(c for _, c in gaps):
            assert r["link_obstacle_distance"][i, k] == pytest.approx(min(g for g, _ in gaps), rel=1e-9, abs=1e-9)


def test_package_path_and_srdf(files, tmp_path):
    srdf = tmp_path / "boxarm.srdf"
    srdf.write_text('<robot name="boxarm"><disable_collisions link1="base" link2="slider" reason="never"/></robot>')
    scene = meshgap.RobotScene.from_urdf(files / "boxarm.urdf", srdf=srdf, package_path=[str(tmp_path)])
    assert ("base", "slider") not in scene.self_pairs and scene.obstacles == 0
    assert not scene.in_collision(np.array([[0.0, 2.25]]))[0]


@pytest.mark.parametrize("states, message", [
    (np.zeros((3, 3)), "states: expected an array of shape (N, 2) (one state per row: turn slide), got shape (3, 3)"),
    (np.zeros(2), "states: expected an array of shape (N, 2) (one state per row: turn slide), got shape (2,)"),
    (np.array([[0.0, 0.0], [0.0, np.nan]]), "states[1]: state has a NaN or infinite number (slide)"),
    (np.zeros((2, 2), dtype=np.float32), "states: dtype float32, expected float64"),
    ([[0.0, 0.0]], "states: expected a numpy array of shape (N, 2)"),
])
def test_bad_states(arm, states, message):
    for call in (arm.distance, arm.in_collision, arm.link_poses):
        with pytest.raises(ValueError) as error:
            call(states)
        assert str(error.value).startswith(message), str(error.value)


def test_bad_input(files, tmp_path):
    urdf = files / "boxarm.urdf"
    with pytest.raises(ValueError, match="unknown parent|no frame|nowhere"):
        meshgap.RobotScene.from_urdf(urdf, attach=(box(0.1, 0.1, 0.1), "nowhere", [0, 0, 0, 0, 0, 0, 1]))
    with pytest.raises(ValueError, match="attach pose: expected 7 numbers"):
        meshgap.RobotScene.from_urdf(urdf, attach=(box(0.1, 0.1, 0.1), "tool", [0, 0, 0]))
    with pytest.raises(FileNotFoundError):
        meshgap.RobotScene.from_urdf(tmp_path / "missing.urdf")
    srdf = tmp_path / "bad.srdf"
    srdf.write_text('<robot name="boxarm"><disable_collisions link1="base" link2="elbow"/></robot>')
    with pytest.raises(ValueError, match="elbow"):
        meshgap.RobotScene.from_urdf(urdf, srdf=srdf)
    with pytest.raises(ValueError, match="threads: must be at least 1"):
        meshgap.RobotScene.from_urdf(urdf).distance(np.zeros((1, 2)), threads=0)


def write_cfg(folder, extra=()):
    """The arm among the world as a robot problem file, the payload cube on the tool."""
    write_obj(folder / "payload.obj", box(0.05, 0.05, 0.05))
    lines = ["[problem]", "name = boxarm_problem", "robot.urdf = boxarm.urdf", "world = world.obj",
             "attach = payload.obj tool 0 0 0.9 0 0 0 1", "start.joints = 0.5 1.0", "goal.joints = -2.5 0.25"]
    path = folder / "boxarm.cfg"
    path.write_text("\n".join(lines + list(extra)) + "\n")
    return path


def test_from_cfg_is_from_urdf(files):
    scene = meshgap.RobotScene.from_cfg(write_cfg(files))
    same = meshgap.RobotScene.from_urdf(files / "boxarm.urdf", world=files / "world.obj",
                                        attach=(files / "payload.obj", "tool", (0, 0, 0.9, 0, 0, 0, 1)))
    assert scene.name == "boxarm_problem" and scene.link_names == same.link_names
    assert scene.self_pairs == same.self_pairs and scene.obstacles == 2
    np.testing.assert_array_equal(scene.start, [0.5, 1.0])
    np.testing.assert_array_equal(scene.goal, [-2.5, 0.25])
    rng = np.random.default_rng(13)
    states = np.column_stack([rng.uniform(-3.5, 3.5, 200), rng.uniform(-1.0, 2.5, 200)])
    a, b = scene.distance(states), same.distance(states)
    for key in ("distance", "link_clearance", "self_pair_distance", "in_collision", "link", "obstacle"):
        np.testing.assert_array_equal(a[key], b[key])
    # The payload's pose: the tool's frame composed by hand, then 0.9 up.
    poses = scene.link_poses(np.array([scene.start]))
    expected = link_frames(*scene.start)["tool"] @ transform(np.eye(3), (0, 0, 0.9))
    np.testing.assert_allclose(poses[0, scene.link_names.index("payload")], expected, atol=1e-12)


def test_robot_scene_takes_every_problem_and_scene_refuses_robots(files):
    cfg = write_cfg(files)
    with pytest.raises(ValueError, match="robot problem .*meshgap.RobotScene.from_cfg"):
        meshgap.Scene.from_cfg(cfg)
    # A single body is a robot of one link: its answers are the single-body scene's, pose for pose.
    single = files / "single.cfg"
    single.write_text("[problem]\nrobot = payload.obj\nworld = world.obj\nstart.x = 0\nstart.y = 0\nstart.z = 5\n"
                      "goal.x = 0\ngoal.y = 2.75\ngoal.z = 0.75\n")  # the goal inside a box of the world
    robot, body = meshgap.RobotScene.from_cfg(single), meshgap.Scene.from_cfg(single)
    assert robot.link_names == ["robot"] and robot.dimension == 7 and robot.obstacles == body.obstacles
    np.testing.assert_allclose(robot.start, [0, 0, 5, 0, 0, 0, 1], atol=1e-15)
    np.testing.assert_allclose(robot.goal, [0, 2.75, 0.75, 0, 0, 0, 1], atol=1e-15)
    rng = np.random.default_rng(5)
    s = rng.uniform(0, 1, (300, 1))
    poses = (1 - s) * robot.start + s * robot.goal
    poses[:, :3] += rng.normal(scale=0.5, size=(300, 3))
    poses[:, 3:] = rng.normal(size=(300, 4))
    poses[:, 3:] /= np.linalg.norm(poses[:, 3:], axis=1, keepdims=True)
    a, b = robot.distance(poses), body.distance(poses)
    np.testing.assert_array_equal(a["in_collision"], b["in_collision"])
    assert 0 < a["in_collision"].sum() < len(poses)
    np.testing.assert_allclose(a["distance"], b["distance"], rtol=1e-12, atol=1e-12)
    with pytest.raises(FileNotFoundError):
        meshgap.RobotScene.from_cfg(files / "missing.cfg")
    bad = files / "bad.cfg"
    bad.write_text(cfg.read_text().replace("start.joints = 0.5 1.0", "start.joints = 0.5"))
    with pytest.raises(ValueError, match="start.joints"):
        meshgap.RobotScene.from_cfg(bad)


def test_batch_equals_meshgap_distance_cli(files, tmp_path):
    """The batch against the C++ whole-robot answer meshgap_distance prints for the same problem file and states."""
    from conftest import executable
    import subprocess
    cli = executable("distance")
    cfg = write_cfg(files)
    scene = meshgap.RobotScene.from_cfg(cfg)
    rng = np.random.default_rng(17)
    states = np.column_stack([rng.uniform(-3.5, 3.5, 40), rng.uniform(-1.0, 2.5, 40)])
    path = tmp_path / "states.txt"
    path.write_text("".join("%r %r\n" % tuple(q) for q in states))
    run = subprocess.run([cli, "--cfg", str(cfg), "--poses", str(path), "--exact"], capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    rows = distance_csv(run.stdout, scene)
    assert len(rows) == len(states)
    r = scene.distance(states)
    for i, row in enumerate(rows):
        assert int(row["index"]) == i
        assert float(row["distance"]) == pytest.approx(r["distance"][i], rel=1e-9, abs=1e-12), (i, row)
        assert int(row["in_collision"]) == int(r["in_collision"][i])
        assert row["link"] == scene.link_names[r["link"][i]]
        assert row["other_link"] == (scene.link_names[r["other_link"][i]] if r["self_pair"][i] else "")
        assert row["obstacle"] == ("" if r["self_pair"][i] else str(r["obstacle"][i]))
        for side, key in (("a", "on_a"), ("b", "on_b")):
            np.testing.assert_allclose([float(row["witness_%s_%s" % (side, c)]) for c in "xyz"], r[key][i],
                                       rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose([float(row["clearance_" + n]) for n in scene.link_names], r["link_clearance"][i],
                                   rtol=1e-9, atol=1e-12)


def distance_csv(text, scene):
    """The rows of meshgap_distance --poses on a robot problem, as dicts; the header checked against the link names."""
    import csv
    import io
    reader = csv.DictReader(io.StringIO(text))
    assert reader.fieldnames[:7] == ["index", "distance", "in_collision", "certified", "link", "other_link",
                                     "obstacle"]
    assert reader.fieldnames[13:] == ["clearance_" + n for n in scene.link_names]
    return list(reader)


@pytest.mark.parametrize("name, dimension", [("arm_fixture", 4), ("swap_se2", 6), ("swap_se3", 14)])
def test_maps_batch_equals_meshgap_distance_cli(tmp_path, name, dimension):
    """Every kind of robot problem of maps/ (a URDF arm with its payload, two bodies in SE(2), two in SE(3)): the
    batch at states between start and goal (linear, quaternions renormalised) against meshgap_distance's answers."""
    from conftest import MAPS, executable
    import subprocess
    cli = executable("distance")
    cfg = MAPS / name / (name + ".cfg")
    scene = meshgap.RobotScene.from_cfg(cfg)
    assert scene.dimension == dimension and len(scene.state_names) == dimension
    quaternion = np.array([n.rsplit(".", 1)[-1] in ("qx", "qy", "qz", "qw") for n in scene.state_names])
    assert np.all(scene.bounds[quaternion] == [-1.0, 1.0]) and quaternion.sum() == (8 if name == "swap_se3" else 0)
    states = np.linspace(scene.start, scene.goal, 25)
    for first in np.flatnonzero(quaternion)[::4]:
        q = states[:, first:first + 4]
        states[:, first:first + 4] = q / np.linalg.norm(q, axis=1)[:, None]
    path = tmp_path / "states.txt"
    path.write_text("".join(" ".join("%r" % x for x in q) + "\n" for q in states))
    run = subprocess.run([cli, "--cfg", str(cfg), "--poses", str(path), "--exact"], capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    rows = distance_csv(run.stdout, scene)
    r = scene.distance(states)
    assert not r["in_collision"][[0, -1]].any()  # start and goal are free
    np.testing.assert_allclose([float(row["distance"]) for row in rows], r["distance"], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose([[float(row["clearance_" + n]) for n in scene.link_names] for row in rows],
                               r["link_clearance"], rtol=1e-9, atol=1e-12)


def test_planar_and_floating_joints_name_and_bound_their_numbers(files):
    """mobile.urdf: a planar base with a revolute arm, a floating drone, a planar slider; the state numbers are named
    per joint value, bounded by the shoulder's limits and +-1 for the quaternion, unbounded elsewhere (the problem's
    volume bounds the positions in the planner's space)."""
    scene = meshgap.RobotScene.from_urdf(RESOURCES / "robot" / "meshgap_test_description" / "urdf" / "mobile.urdf",
                                         world=files / "world.obj")
    assert scene.state_names == ["drive.x", "drive.y", "drive.theta", "shoulder", "fly.x", "fly.y", "fly.z",
                                 "fly.qx", "fly.qy", "fly.qz", "fly.qw", "wall.x", "wall.y", "wall.theta"]
    inf = np.inf
    np.testing.assert_array_equal(scene.bounds, [[-inf, inf]] * 3 + [[-1, 1]] + [[-inf, inf]] * 3 + [[-1, 1]] * 4 +
                                  [[-inf, inf]] * 3)
    # The base driven 1 along its plane's x (the joint frame turned 0.3 about z), then turned a quarter.
    state = np.zeros(14)
    state[[0, 2, 10]] = [1.0, math.pi / 2, 1.0]
    base = scene.link_poses(state[None, :])[0, scene.link_names.index("base")]
    np.testing.assert_allclose(base[:3, 3], [math.cos(0.3), math.sin(0.3), 0.05], atol=1e-12)
    np.testing.assert_allclose(base[:2, 0], [math.cos(0.3 + math.pi / 2), math.sin(0.3 + math.pi / 2)], atol=1e-12)
