"""meshgap.Scene: batched distance and collision against analytic box distances, the meshgap_distance CLI's answers,
threads, warm starts, and bad input (one clear exception, the CLI's message)."""
import subprocess

import numpy as np
import pytest

import meshgap
from conftest import MAPS, RESOURCES, box, cli_error, executable, merged, omplapp, write_obj

ROBOT_HALF = np.array([0.5, 0.25, 0.375])  # exact in float32, as mesh files are read
WORLD = [((1.0, 1.5, 0.5), (4.0, 0.0, 0.0)), ((0.375, 0.375, 2.0), (-3.0, 1.0, 0.5))]  # half sizes, centre


@pytest.fixture(scope="module")
def boxes():
    robot = box(*ROBOT_HALF)
    world = merged(*[box(*h, center=c) for h, c in WORLD])
    return meshgap.Scene(robot, world)


def quaternion_z(angle):
    return np.array([0.0, 0.0, np.sin(angle / 2), np.cos(angle / 2)])


def analytic(translation, robot_half):
    """Distance from an axis-aligned robot box (half sizes robot_half, centred at translation) to each world box, and
    whether it overlaps one (strictly)."""
    out = []
    for half, centre in WORLD:
        gap = np.abs(np.asarray(translation) - centre) - (np.asarray(half) + robot_half)
        out.append((np.linalg.norm(np.maximum(gap, 0.0)), bool(np.all(gap < 0))))
    return out


def random_box_poses(rng, count, planar=False):
    """Translations around the boxes (some overlapping), rotations by quarter turns about z (the robot box stays
    axis-aligned, its x and y half sizes swapped on odd turns)."""
    t = rng.uniform([-5.5, -3.0, -1.5], [6.5, 3.5, 3.0], size=(count, 3))
    turns = rng.integers(0, 4, size=count)
    if planar:
        t[:, 2] = 0.0
        return np.column_stack([t[:, 0], t[:, 1], turns * np.pi / 2]), t, turns
    q = np.array([quaternion_z(k * np.pi / 2) for k in turns])
    return np.column_stack([t, q]), t, turns


def check_against_boxes(scene, poses, t, turns):
    r = scene.distance(poses)
    assert set(r) == {"distance", "on_a", "on_b", "obstacle", "in_collision", "certified", "open_body"}
    assert not r["open_body"].any()  # closed boxes
    assert r["on_a"].shape == (len(poses), 3) and r["distance"].dtype == np.float64
    free = 0
    for i in range(len(poses)):
        half = ROBOT_HALF[[1, 0, 2]] if turns[i] % 2 else ROBOT_HALF
        answers = analytic(t[i], half)
        collides = any(c for _, c in answers)
        assert r["in_collision"][i] == collides, (i, poses[i])
        assert r["certified"][i]
        if collides:
            assert r["distance"][i] <= 0.0
            continue
        free += 1
        d = min(a for a, _ in answers)
        assert r["distance"][i] == pytest.approx(d, rel=1e-9, abs=1e-9), (i, poses[i])
        if abs(answers[0][0] - answers[1][0]) > 1e-6:
            assert r["obstacle"][i] == int(np.argmin([a for a, _ in answers]))
        # Witness points: as far apart as the distance, one on the robot box's surface, one on the obstacle's.
        assert np.linalg.norm(r["on_a"][i] - r["on_b"][i]) == pytest.approx(d, rel=1e-9, abs=1e-9)
        local = np.abs(r["on_a"][i] - t[i])
        assert np.all(local <= half + 1e-9) and np.any(np.abs(local - half) <= 1e-9)
        h, c = WORLD[r["obstacle"][i]]
        local = np.abs(r["on_b"][i] - c)
        assert np.all(local <= np.asarray(h) + 1e-9) and np.any(np.abs(local - h) <= 1e-9)
    return free


def test_distance_matches_analytic_boxes(boxes):
    assert boxes.obstacles == 2 and boxes.robot_triangles == 12 and boxes.world_triangles == 24
    poses, t, turns = random_box_poses(np.random.default_rng(1), 400)
    free = check_against_boxes(boxes, poses, t, turns)
    assert 50 < free < 400  # both kinds of pose were tested


def test_se2_poses_match_analytic_boxes(boxes):
    poses, t, turns = random_box_poses(np.random.default_rng(2), 300, planar=True)
    assert poses.shape == (300, 3)
    check_against_boxes(boxes, poses, t, turns)


def test_quaternion_order_is_x_y_z_w(boxes):
    # A quarter turn about x swaps the robot box's y and z half sizes: (0.5, 0.25, 0.375) -> (0.5, 0.375, 0.25).
    s = np.sqrt(0.5)
    pose = np.array([[4.0, 0.0, 0.5 + 0.25 + 0.1, s, 0.0, 0.0, s]])  # 0.1 above the first world box
    assert boxes.distance(pose)["distance"][0] == pytest.approx(0.1, abs=1e-12)


def test_in_collision_matches_distance(boxes):
    poses, _, _ = random_box_poses(np.random.default_rng(3), 500)
    collide = boxes.in_collision(poses)
    assert collide.dtype == np.bool_ and collide.shape == (500,)
    assert np.array_equal(collide, boxes.distance(poses)["in_collision"])
    assert np.array_equal(collide, boxes.in_collision(poses, threads=3))


def path_poses(scene, count, seed):
    """Poses from the cfg's start towards its goal, with rotations jittered about the start's."""
    rng = np.random.default_rng(seed)
    s = np.linspace(0.0, 1.0, count)[:, None]
    poses = (1 - s) * scene.start + s * scene.goal
    poses[:, 3:] += rng.normal(scale=0.05, size=(count, 4)).cumsum(axis=0) / np.sqrt(count)
    poses[:, 3:] /= np.linalg.norm(poses[:, 3:], axis=1)[:, None]
    return poses


@pytest.fixture(scope="module")
def hand_bowl():
    return meshgap.Scene.from_cfg(MAPS / "hand_bowl" / "hand_bowl.cfg")


def test_threads_give_identical_answers(hand_bowl):
    poses = path_poses(hand_bowl, 3 * meshgap.SCENE_BATCH_BLOCK + 17, seed=4)
    one = hand_bowl.distance(poses, threads=1)
    for threads in (2, 3):
        other = hand_bowl.distance(poses, threads=threads)
        for key in one:
            assert np.array_equal(one[key], other[key]), (threads, key)
    assert one["in_collision"].any() and not one["in_collision"].all()


def test_warm_start_changes_no_answer(hand_bowl):
    poses = path_poses(hand_bowl, 300, seed=5)
    warm, cold = hand_bowl.distance(poses, warm=True), hand_bowl.distance(poses, warm=False)
    assert np.array_equal(warm["in_collision"], cold["in_collision"])
    np.testing.assert_allclose(warm["distance"], cold["distance"], rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("stream,warm", [("path", True), ("path", False), ("random", True)])
def test_fast_mode_falls_back_to_the_exact_query(hand_bowl, stream, warm):
    """exact=False never runs the node-level search from scratch, which costs 1.4 to 140 times the exact query per
    pose (and seconds on a body's first use): the exact query answers, bit for bit, certified (the mode chosen);
    the collision verdicts exact either way."""
    if stream == "path":
        poses = path_poses(hand_bowl, 200, seed=6)
    else:
        rng = np.random.default_rng(11)
        q = rng.normal(size=(120, 4))
        poses = np.column_stack([rng.uniform(-276, 361, 120), rng.uniform(-276, 276, 120),
                                 rng.uniform(-126, 234, 120), q / np.linalg.norm(q, axis=1, keepdims=True)])
    exact, fast = hand_bowl.distance(poses), hand_bowl.distance(poses, exact=False, warm=warm)
    for name in ("distance", "obstacle", "in_collision", "certified", "on_a", "on_b"):
        np.testing.assert_array_equal(fast[name], exact[name], err_msg=name)
    assert fast["certified"].all()


def test_depth_skipped_gives_the_verdict_and_the_same_free_answers(hand_bowl):
    poses = path_poses(hand_bowl, 300, seed=7)
    full, verdict = hand_bowl.distance(poses), hand_bowl.distance(poses, depth=False)
    collide = full["in_collision"]
    assert collide.any() and not collide.all()
    assert np.array_equal(verdict["in_collision"], collide) and verdict["certified"].all()
    assert np.array_equal(verdict["distance"][~collide], full["distance"][~collide])
    # In collision: a zero below zero (the verdict alone, as FCL's 0), where the full answer has a depth.
    assert np.all(verdict["distance"][collide] == -np.finfo(float).tiny)
    assert np.all(full["distance"][collide] < 0)
    assert np.array_equal(verdict["distance"], hand_bowl.distance(poses, depth=False, threads=2)["distance"])


def write_path(path, poses):
    with open(path, "w") as out:
        for p in poses:
            out.write(" ".join("%.17g" % x for x in p) + "\n")


@pytest.mark.parametrize("cfg", ["hand_bowl", "cubicles"])
def test_distance_matches_the_cli(tmp_path, cfg):
    """The same poses through meshgap_distance --cfg --poses --exact (robot and world as two bodies, enumeration then
    the exact refinement: another code path than the scene's)."""
    cli = executable("distance")
    path = MAPS / cfg / (cfg + ".cfg") if cfg == "hand_bowl" else omplapp(cfg + ".cfg")
    scene = meshgap.Scene.from_cfg(str(path))
    if cfg == "cubicles":
        poses = np.loadtxt(omplapp("cubicles.path"))
    else:
        poses = path_poses(scene, 120, seed=7)
    write_path(tmp_path / "poses.path", poses)
    run = subprocess.run([cli, "--cfg", str(path), "--poses", str(tmp_path / "poses.path"), "--exact", "-q"],
                         capture_output=True, text=True, timeout=300, check=True)
    rows = np.genfromtxt(run.stdout.splitlines(), delimiter=",", names=True)
    r = scene.distance(poses)
    assert np.array_equal(r["in_collision"], rows["in_collision"].astype(bool))
    free = ~r["in_collision"]
    assert free.sum() > len(poses) // 4
    np.testing.assert_allclose(r["distance"][free], rows["distance"][free], rtol=1e-9, atol=1e-9)


def test_open_meshes_are_counted_warned_and_flagged(capfd):
    """A world of a box without its lid (4 boundary edges, by hand) and a closed box: counted, warned about once,
    and every answer whose obstacle is the open box flagged; nothing is inside the open box (analytic gaps)."""
    V, F = box(1.0, 1.0, 1.0)
    lid = np.all(np.isin(F, [1, 3, 5, 7]), axis=1)  # the two triangles of the face z = +1
    assert lid.sum() == 2
    capfd.readouterr()
    scene = meshgap.Scene(box(0.25, 0.25, 0.25), merged((V, F[~lid]), box(1.0, 1.0, 1.0, center=(5.0, 0.0, 0.0))))
    err = capfd.readouterr().err
    assert err.count("not a closed surface") == 1, err
    assert "world: not a closed surface: 4 boundary edges" in err and "0 non-manifold edges" in err, err
    assert scene.robot_edges == {"boundary_edges": 0, "non_manifold_edges": 0}
    assert scene.world_edges == {"boundary_edges": 4, "non_manifold_edges": 0}
    assert scene.open_obstacles == [0]
    q = [0.0, 0.0, 0.0, 1.0]
    r = scene.distance(np.array([[0.1, -0.2, 0.05] + q, [5.1, 0.0, 0.0] + q, [6.5, 0.0, 0.0] + q, [0, 0, 1.0] + q]))
    # Inside the open box: free, 0.55 from the wall y = -1; poking out of its open top: free, 0.75 from the walls.
    assert list(r["in_collision"]) == [False, True, False, False]
    assert list(r["open_body"]) == [True, False, False, True]
    assert r["distance"][0] == pytest.approx(0.55, abs=1e-12)
    assert r["distance"][2] == pytest.approx(0.25, abs=1e-12)
    assert r["distance"][3] == pytest.approx(0.75, abs=1e-12)


def test_empty_batch(boxes):
    r = boxes.distance(np.zeros((0, 7)))
    assert r["distance"].shape == (0,) and r["on_a"].shape == (0, 3)
    assert boxes.in_collision(np.zeros((0, 3))).shape == (0,)


def test_meshes_from_files_equal_meshes_from_arrays(tmp_path, boxes):
    write_obj(tmp_path / "robot.obj", box(*ROBOT_HALF))
    write_obj(tmp_path / "world.obj", merged(*[box(*h, center=c) for h, c in WORLD]))
    from_files = meshgap.Scene(str(tmp_path / "robot.obj"), tmp_path / "world.obj")  # str or os.PathLike
    poses, _, _ = random_box_poses(np.random.default_rng(8), 100)
    np.testing.assert_array_equal(from_files.distance(poses)["distance"], boxes.distance(poses)["distance"])
    V, F = meshgap.load_mesh(tmp_path / "robot.obj")
    assert V.shape == (8, 3) and F.shape == (12, 3)


BAD_POSES = [
    (np.zeros((4, 5)), r"^poses: expected an array of shape \(N, 7\) .* got shape \(4, 5\)$"),
    (np.zeros(7), r"^poses: expected .* got shape \(7,\)$"),
    (np.zeros((2, 7, 1)), r"^poses: expected .* got shape \(2, 7, 1\)$"),
    (np.zeros((3, 7), dtype=np.float32), r"^poses: dtype float32, expected float64"),
    (np.zeros((3, 7), dtype=np.int64), r"^poses: dtype int64, expected float64"),
    ([[0.0] * 7], r"^poses: expected a numpy array"),
    (np.array([[0, 0, 0, 0, 0, 0, 1], [0, np.nan, 0, 0, 0, 0, 1.0]]), r"^poses\[1\]: pose has a NaN or infinite"),
    (np.array([[0.0, 0.0, np.inf]]), r"^poses\[0\]: pose has a NaN or infinite"),
    (np.array([[0, 0, 0, 0, 0, 0, 2.0]]), r"^poses\[0\]: quaternion \(qx qy qz qw\) is not of unit length"),
]


@pytest.mark.parametrize("poses,message", BAD_POSES)
def test_bad_poses_are_refused(boxes, poses, message):
    with pytest.raises(ValueError, match=message):
        boxes.distance(poses)
    with pytest.raises(ValueError, match=message):
        boxes.in_collision(poses)


def test_bad_threads_are_refused(boxes):
    with pytest.raises(ValueError, match="^threads: must be at least 1"):
        boxes.distance(np.zeros((1, 3)), threads=0)


def test_non_unit_quaternion_within_tolerance_is_normalised(boxes):
    a = boxes.distance(np.array([[4.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]]))["distance"]
    b = boxes.distance(np.array([[4.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0005]]))["distance"]
    assert a[0] == pytest.approx(b[0], abs=1e-12)


def test_bad_meshes_are_refused(tmp_path):
    V, F = box(1, 1, 1)
    with pytest.raises(ValueError, match=r"^robot F: row 0: vertex index 8 is out of range \[0, 8\)$"):
        meshgap.Scene((V, F + 8 * (np.arange(12) == 0)[:, None]), (V, F))
    with pytest.raises(ValueError, match=r"^world V: dtype complex128, expected real numbers$"):
        meshgap.Scene((V, F), (V.astype(np.complex128), F))
    with pytest.raises(ValueError, match=r"^world F: dtype float64, expected an integer type$"):
        meshgap.Scene((V, F), (V, F.astype(np.float64)))
    with pytest.raises(ValueError, match=r"^robot V: expected shape \(n, 3\), got \(8, 2\)$"):
        meshgap.Scene((V[:, :2].copy(), F), (V, F))
    with pytest.raises(ValueError, match=r"^robot: expected a file path or a \(V, F\) pair"):
        meshgap.Scene((V, F, F), (V, F))
    with pytest.raises(ValueError, match=r"^robot: expected a file path \(str or os.PathLike\), got int$"):
        meshgap.Scene(3, (V, F))
    with pytest.raises(FileNotFoundError, match=r"nowhere.obj: no such file$"):
        meshgap.Scene(str(tmp_path / "nowhere.obj"), (V, F))
    with pytest.raises(ValueError, match=r"garbage.obj: "):
        meshgap.Scene(str(RESOURCES / "bad" / "garbage.obj"), (V, F))


@pytest.mark.parametrize("cfg,error", [("missing_mesh.cfg", FileNotFoundError), ("truncated.cfg", ValueError),
                                       ("nan_value.cfg", ValueError), ("unknown_key.cfg", ValueError),
                                       ("no_such.cfg", FileNotFoundError), ("garbage.obj", ValueError)])
def test_bad_cfg_gives_the_cli_message(cfg, error):
    """The same one-line message as meshgap_distance --cfg prints after "error: "."""
    path = str(RESOURCES / "bad" / cfg)
    with pytest.raises(error) as raised:
        meshgap.Scene.from_cfg(path)
    assert str(raised.value) == cli_error([executable("distance"), "--cfg", path, "-q"])


def test_the_gil_is_released_during_a_batch(hand_bowl):
    """Python code runs while a batch runs in another thread. Holding the GIL, the batch would let no Python line run
    from its start to its end (only around the call, at the interpreter's switch interval, a few ms): so count the
    main thread's loop turns timed in the middle half of the batch's run."""
    import threading
    import time
    poses = path_poses(hand_bowl, 600, seed=9)
    span, done = [], threading.Event()

    def batch():
        span.append(time.perf_counter())
        hand_bowl.distance(poses)
        span.append(time.perf_counter())
        done.set()

    worker = threading.Thread(target=batch)
    worker.start()
    turns = []
    while not done.is_set():
        turns.append(time.perf_counter())
    worker.join()
    start, end = span
    middle = [t for t in turns if start + (end - start) / 4 < t < end - (end - start) / 4]
    assert end - start > 0.02 and len(middle) > 100, (end - start, len(middle))
