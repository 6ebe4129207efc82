"""meshgap.distributed on a local Dask cluster of two worker processes: the answers of Scene.distance in this process
on the same poses (SE(3) and SE(2) problems, a pair of meshes), one scene built per worker, label() to Zarr against
the same single-process computation, resumed after a simulated crash and after a worker killed mid-run, its samplers
near the obstacles and along paths, and bad input (one clear exception each)."""
import os
import shutil
import signal
import threading
import time

import numpy as np
import pytest

try:
    import dask
    import distributed
    import zarr
except ImportError as error:
    pytest.skip("meshgap.distributed needs Debian's python3-dask, python3-distributed and python3-zarr: %s" % error,
                allow_module_level=True)

import meshgap
import meshgap.distributed as md
from conftest import MAPS, box, write_obj

HAND_BOWL = MAPS / "hand_bowl" / "hand_bowl.cfg"
FIELDS = {"distance", "on_a", "on_b", "obstacle", "in_collision", "certified", "open_body"}


def planar_cfg(folder, name="bars"):
    """A planar problem of two boxes (a wall and a bar), as OMPL.app writes 2D ones (no start.z)."""
    folder.mkdir(parents=True, exist_ok=True)
    write_obj(folder / "wall.obj", box(0.3, 6, 0.5, (0, 0, 0.5)))
    write_obj(folder / "bar.obj", box(0.6, 0.2, 0.5, (0.25, 0.1, 0.5)))
    cfg = folder / (name + ".cfg")
    cfg.write_text("[problem]\nname = %s\nrobot = bar.obj\nworld = wall.obj\nstart.x = -3\nstart.y = 0.5\n"
                   "start.theta = 0\nvolume.min.x = -5\nvolume.min.y = -5\nvolume.max.x = 5\nvolume.max.y = 5\n" % name)
    return cfg


def hand_bowl_poses(count, seed):
    """Poses around the bowl (positions in its bounding box grown by the hand's size): free, near and colliding."""
    rng = np.random.default_rng(seed)
    V, _ = meshgap.load_mesh(MAPS / "hand_bowl" / "hand_bowl_a.obj")
    lo, hi = V.min(axis=0) - 40, V.max(axis=0) + 40
    q = rng.normal(size=(count, 4))
    return np.column_stack([rng.uniform(lo, hi, size=(count, 3)), q / np.linalg.norm(q, axis=1, keepdims=True)])


def assert_same(got, want):
    assert set(got) == set(want) == FIELDS
    for name in FIELDS:
        assert got[name].dtype == want[name].dtype and got[name].shape == want[name].shape, name
        assert np.array_equal(got[name], want[name]), name


def test_se3_distances_identical_and_one_build_per_worker(client):
    poses = hand_bowl_poses(3000, seed=1)
    want = meshgap.Scene.from_cfg(HAND_BOWL).distance(poses)
    assert 0 < want["in_collision"].sum() < len(poses) and want["certified"].all()
    r = md.distance(HAND_BOWL, poses, chunks=300)  # 10 tasks; 300 is not a multiple of the batch's block
    assert all(isinstance(a, dask.array.Array) for a in r.values())
    (got,) = dask.compute(r)
    assert_same(got, want)
    # A Dask array in, with chunks of its own; a second computation reuses the workers' scenes.
    (again,) = dask.compute(md.distance(HAND_BOWL, dask.array.from_array(poses, chunks=(500, 7))))
    assert_same(again, want)
    collide = md.in_collision(HAND_BOWL, poses, chunks=400).compute()
    assert np.array_equal(collide, want["in_collision"])
    key = md.problem(HAND_BOWL).key
    builds = client.run(md.scene_builds)
    assert len(builds) == 2
    counts = [b.get(key, 0) for b in builds.values()]
    assert set(counts) <= {0, 1} and sum(counts) >= 1, builds  # 25 tasks, at most one build per worker
    assert key not in md.scene_builds()  # nothing built in this process


def test_se2_and_mesh_pair_identical(client, tmp_path):
    cfg = planar_cfg(tmp_path)
    rng = np.random.default_rng(2)
    poses = np.column_stack([rng.uniform(-2, 2, size=(1500, 2)), rng.uniform(-np.pi, np.pi, 1500)])
    scene = meshgap.Scene.from_cfg(cfg)
    assert scene.planar
    want = scene.distance(poses)
    assert 0 < want["in_collision"].sum() < len(poses)
    (got,) = dask.compute(md.distance(cfg, poses, chunks=256))
    assert_same(got, want)
    # Exact off (the node distance), no depth, no warm start: the same keywords as the batch, the same answers.
    (fast,) = dask.compute(md.distance(cfg, poses, chunks=256, exact=False, depth=False, warm=False))
    assert_same(fast, scene.distance(poses, exact=False, depth=False, warm=False))
    # A pair of mesh files, poses x y z qx qy qz qw.
    pair = (str(tmp_path / "bar.obj"), str(tmp_path / "wall.obj"))
    q = rng.normal(size=(800, 4))
    poses3 = np.column_stack([rng.uniform(-2, 2, size=(800, 3)), q / np.linalg.norm(q, axis=1, keepdims=True)])
    (got,) = dask.compute(md.distance(pair, poses3, chunks=200))
    assert_same(got, meshgap.Scene(*pair).distance(poses3))


def test_robot_states_identical(client, tmp_path):
    # A URDF arm carrying a payload (maps/arm_fixture) and two bodies in SE(2) (maps/swap_se2): (N, dof) states.
    for cfg, count in ((MAPS / "arm_fixture" / "arm_fixture.cfg", 600), (MAPS / "swap_se2" / "swap_se2.cfg", 400)):
        robot = meshgap.RobotScene.from_cfg(cfg)
        bounds = robot.bounds
        low, high = np.maximum(bounds[:, 0], -4.0), np.minimum(bounds[:, 1], 4.0)
        states = np.random.default_rng(5).uniform(low, high, size=(count, robot.dimension))
        want = robot.distance(states)
        assert 0 < want["in_collision"].sum() < count, cfg
        (got,) = dask.compute(md.distance(cfg, states, chunks=128))
        assert set(got) == set(want), cfg
        for name in want:
            assert got[name].dtype == want[name].dtype and got[name].shape == want[name].shape, (cfg, name)
            assert np.array_equal(got[name], want[name]), (cfg, name)
        assert np.array_equal(md.in_collision(cfg, states, chunks=128).compute(), robot.in_collision(states))
    with pytest.raises(ValueError, match=r"\(N, 4\)"):
        md.distance(MAPS / "arm_fixture" / "arm_fixture.cfg", np.zeros((3, 7)))
    with pytest.raises(ValueError, match="robot problem"):
        md.label(MAPS / "arm_fixture" / "arm_fixture.cfg", 10, out=str(tmp_path / "robot.zarr"))
    assert not (tmp_path / "robot.zarr").exists()


def check_store(out, n, chunk, scene, volume, planar):
    """The data set at out against the same computation here: the sampler's poses chunk by chunk, inside the
    volume, and Scene.distance's exact answers at them."""
    group = zarr.open_group(str(out), mode="r")
    assert group["done"][:].all() and len(group["done"]) == -(-n // chunk)
    poses = group["poses"][:]
    assert poses.shape == (n, 3 if planar else 7)
    for i in range(len(group["done"])):
        rows = slice(i * chunk, min(n, (i + 1) * chunk))
        assert np.array_equal(poses[rows], md.uniform_poses(volume, planar, rows.stop - rows.start, 0, i))
    axes = 2 if planar else 3
    assert (poses[:, :axes] >= volume[0]).all() and (poses[:, :axes] <= volume[1]).all()
    if not planar:
        assert np.allclose(np.linalg.norm(poses[:, 3:], axis=1), 1.0)
    want = scene.distance(poses, threads=2)
    assert_same({name: group[name][:] for name in FIELDS}, want)
    return group


def test_label_matches_and_resumes(client, tmp_path):
    cfg = planar_cfg(tmp_path / "problem")
    volume = ((-5.0, -5.0), (5.0, 5.0))
    out = tmp_path / "labels.zarr"
    summary = md.label(cfg, 2300, out=out, chunk=250, progress=False)
    assert summary == {"out": str(out), "chunks": 10, "computed": 10}
    check_store(out, 2300, 250, meshgap.Scene.from_cfg(cfg), volume, True)
    reference = {name: zarr.open_group(str(out))[name][:] for name in FIELDS | {"poses"}}
    # A run killed mid-way: chunks 3 and 9 (the short last one) have no mark, one with its data half overwritten.
    group = zarr.open_group(str(out), mode="r+")
    for i in (3, 9):
        os.remove(out / "done" / str(i))
    group["distance"][750:900] = np.nan
    group["on_a"][750:800] = 0.0
    assert md.label(cfg, 2300, out=out, chunk=250, progress=False)["computed"] == 2
    for name, values in reference.items():
        assert np.array_equal(zarr.open_group(str(out))[name][:], values), name
    assert md.label(cfg, 2300, out=out, chunk=250, progress=False)["computed"] == 0
    # Without a distributed client: local threads, the same data set.
    local = tmp_path / "local.zarr"
    assert md.label(cfg, 2300, out=local, chunk=250, client=False, progress=False)["computed"] == 10
    for name, values in reference.items():
        assert np.array_equal(zarr.open_group(str(local))[name][:], values), name
    # A pair of meshes: 3D poses in the wall's box grown by the bar's reach from its origin (its corner 0.85 0.3 1),
    # the files' coordinates read in float32.
    pair = (str(tmp_path / "problem" / "bar.obj"), str(tmp_path / "problem" / "wall.obj"))
    md.label(pair, 600, out=tmp_path / "pair.zarr", chunk=200, progress=False)
    reach = np.linalg.norm(np.float32([0.85, 0.3, 1.0]).astype(np.float64))
    wall = np.float32([[-0.3, -6, 0], [0.3, 6, 1]]).astype(np.float64)
    check_store(tmp_path / "pair.zarr", 600, 200, meshgap.Scene(*pair), (wall[0] - reach, wall[1] + reach), False)


def test_bad_input(client, tmp_path):
    poses = np.zeros((5, 7))
    with pytest.raises(ValueError, match=r"poses: expected an array of shape \(N, 7\).*got shape \(5, 4\)"):
        md.distance(HAND_BOWL, np.zeros((5, 4)))
    with pytest.raises(ValueError, match=r"poses: expected .*\(N, 7\).*got shape \(7,\)"):
        md.in_collision(HAND_BOWL, np.zeros(7))
    cfg = planar_cfg(tmp_path / "a", name="first")
    with pytest.raises(ValueError, match=r"poses: expected an array of shape \(N, 3\) \(x y theta\)"):
        md.distance(cfg, poses)
    with pytest.raises(FileNotFoundError, match="none.cfg: no such file"):
        md.distance(tmp_path / "none.cfg", poses)
    with pytest.raises(FileNotFoundError, match="none.obj: no such file"):
        md.distance((str(tmp_path / "a" / "bar.obj"), str(tmp_path / "none.obj")), poses)
    with pytest.raises(ValueError, match="source: expected a .cfg path or a"):
        md.distance(42, poses)
    broken = tmp_path / "a" / "broken.cfg"
    broken.write_text(cfg.read_text().replace("wall.obj", "gone.obj"))
    with pytest.raises(FileNotFoundError, match="world mesh '.*gone.obj' does not exist"):
        md.distance(broken, np.zeros((5, 3)))
    # A file gone (or changed) on the workers after the client checked it: the worker names it.
    problem = md.problem(planar_cfg(tmp_path / "b", name="second"))
    (tmp_path / "b" / "wall.obj").unlink()
    with pytest.raises(FileNotFoundError, match=r"wall.obj: no such file on worker .* \(pid \d+\)"):
        md.distance(problem, np.zeros((5, 3)))["distance"].compute()
    problem = md.problem(planar_cfg(tmp_path / "c", name="third"))
    write_obj(tmp_path / "c" / "wall.obj", box(0.3, 5, 0.5, (0, 0, 0.5)))
    with pytest.raises(ValueError, match="wall.obj: the files on worker .* differ from those the client hashed"):
        md.in_collision(problem, np.zeros((5, 3))).compute()
    # label(): nothing written for bad input; a data set of other parameters is refused.
    out = tmp_path / "labels.zarr"
    with pytest.raises(FileNotFoundError, match="none.cfg: no such file"):
        md.label(tmp_path / "none.cfg", 10, out=out)
    with pytest.raises(ValueError, match=r"volume: expected \(\(min...\), \(max...\)\) of 2 axes, max above min"):
        md.label(cfg, 10, out=out, volume=((0, 0), (1, -1)))
    with pytest.raises(ValueError, match="n and chunk: expected positive integers"):
        md.label(cfg, 0, out=out)
    with pytest.raises(ValueError, match="sampler: 'nearby' is not known \\(uniform, near, path\\)"):
        md.label(cfg, 10, out=out, sampler="nearby")
    # No contact in the volume (the bar stays clear of the wall): the near sampler has nothing to bisect.
    with pytest.raises(ValueError, match=r"sampler 'near': 0 of \d+ uniform poses of the volume .* collide"):
        md.label(cfg, 10, out=out, sampler="near", volume=((3, 3), (5, 5)), progress=False)
    assert not list(tmp_path.glob("labels.zarr*"))  # nothing half made
    md.label(cfg, 10, out=out, chunk=5, progress=False)
    with pytest.raises(ValueError, match="labels.zarr: a data set of other parameters"):
        md.label(cfg, 20, out=out, chunk=5, progress=False)
    zarr.open_group(str(out), mode="r+").move("on_a", "on_robot")  # as an older meshgap named it
    with pytest.raises(ValueError, match="labels.zarr: a data set without the fields on_a \\(made by an older"):
        md.label(cfg, 10, out=out, chunk=5, progress=False)
    with pytest.raises(ConnectionError, match="cannot reach the Dask scheduler at tcp://127.0.0.1:1 within 2 s"):
        md.connect("tcp://127.0.0.1:1", timeout=2)


def quaternion_angle(a, b):
    """The rotation angle between unit quaternions, rows of a and b."""
    return 2 * np.arccos(np.clip(np.abs(np.sum(a * b, axis=1)), 0, 1))


def reach(path):
    """The largest distance of the robot's vertices from its origin (read in float32, as the scene reads them)."""
    V, _ = meshgap.load_mesh(path)
    return float(np.linalg.norm(V.astype(np.float32).astype(np.float64), axis=1).max())


def test_label_near_obstacles(client, tmp_path):
    """sampler="near": pairs straddling contact, 2^-24 of a segment of the volume apart; the free end's exact
    clearance is bounded by how far the pair's robot points are apart (clearance is 1-Lipschitz in them), far below
    that of uniform poses."""
    problem = md.problem(HAND_BOWL)
    n, chunk = 600, 200
    md.label(HAND_BOWL, n, out=tmp_path / "near.zarr", chunk=chunk, sampler="near", progress=False)
    md.label(HAND_BOWL, n, out=tmp_path / "uniform.zarr", chunk=chunk, progress=False)
    near, uniform = zarr.open_group(str(tmp_path / "near.zarr")), zarr.open_group(str(tmp_path / "uniform.zarr"))
    assert near.attrs["params"]["sampler"] == "near" and near["done"][:].all()
    poses = near["poses"][:]
    scene = meshgap.Scene.from_cfg(HAND_BOWL)
    want = scene.distance(poses)
    assert_same({name: near[name][:] for name in FIELDS}, want)
    lo, hi = np.asarray(problem.volume[0]), np.asarray(problem.volume[1])
    assert (poses[:, :3] >= lo).all() and (poses[:, :3] <= hi).all()
    free, hit = poses[0::2], poses[1::2]
    assert (~want["in_collision"][0::2]).all() and want["in_collision"][1::2].all()
    moved = np.linalg.norm(free[:, :3] - hit[:, :3], axis=1)
    turned = quaternion_angle(free[:, 3:], hit[:, 3:])
    assert (moved <= np.linalg.norm(hi - lo) / 2 ** 24 * (1 + 1e-9)).all() and (turned <= np.pi / 2 ** 24 + 1e-12).all()
    bound = moved + reach(MAPS / "hand_bowl" / "hand_bowl_b.obj") * turned
    assert (want["distance"][0::2] <= bound + 1e-9).all()
    assert np.abs(want["distance"]).mean() < 1e-3 * np.abs(uniform["distance"][:]).mean()


def test_label_along_paths(client, tmp_path):
    """sampler="path": straight paths of PATH_STATES poses between uniform poses, evenly spaced (translation and
    angle), their clearance changing along a free stretch by no more than the robot's points move."""
    cfg = planar_cfg(tmp_path / "problem")
    n, chunk, states = 500, 200, md.PATH_STATES
    md.label(cfg, n, out=tmp_path / "path.zarr", chunk=chunk, sampler="path", progress=False)
    group = zarr.open_group(str(tmp_path / "path.zarr"))
    poses = group["poses"][:]
    want = meshgap.Scene.from_cfg(cfg).distance(poses)
    assert_same({name: group[name][:] for name in FIELDS}, want)
    assert 0 < want["in_collision"].sum() < n
    assert (np.abs(poses[:, :2]) <= 5).all() and (poses[:, 2] >= -np.pi).all() and (poses[:, 2] < np.pi).all()
    bar = reach(tmp_path / "problem" / "bar.obj")
    paths = 0
    for start in range(0, n, chunk):
        rows = poses[start:min(n, start + chunk)]
        for first in range(0, len(rows), states):
            path = rows[first:first + states]
            d = want["distance"][start + first:start + first + len(path)]
            free = ~want["in_collision"][start + first:start + first + len(path)]
            step = np.diff(path[:, :2], axis=0)
            turn = np.remainder(np.diff(path[:, 2]) + np.pi, 2 * np.pi) - np.pi
            assert np.allclose(step, step[0], atol=1e-12) and np.allclose(turn, turn[0], atol=1e-12)
            assert abs(turn[0]) * (states - 1) <= np.pi + 1e-9  # the shorter arc
            moved = np.linalg.norm(step, axis=1) + bar * np.abs(turn)
            both = free[1:] & free[:-1]
            assert (np.abs(np.diff(d))[both] <= moved[both] + 1e-9).all()
            paths += 1
    assert paths == 7 + 7 + 4  # chunks of 200, 200 and 100 rows: paths of 32 poses, the last of each cut short


def test_label_survives_a_killed_worker(client, tmp_path):
    """Last: it kills a worker process (its nanny starts another)."""
    n, chunk = 16000, 400
    out = tmp_path / "killed.zarr"
    result = {}
    run = threading.Thread(target=lambda: result.update(md.label(HAND_BOWL, n, out=out, chunk=chunk, client=client,
                                                                 progress=False)))
    run.start()
    marks = lambda: len([f for f in os.listdir(out / "done") if not f.startswith(".")]) if out.exists() else 0
    deadline = time.monotonic() + 600  # generous: it only bounds a run that stalls
    while marks() < 3 and run.is_alive() and time.monotonic() < deadline:
        time.sleep(0.05)
    pids = client.run(os.getpid)
    before = marks()
    os.kill(sorted(pids.values())[0], signal.SIGKILL)
    run.join(timeout=600)
    assert not run.is_alive() and result["computed"] == n // chunk
    assert 3 <= before < n // chunk, before  # killed mid-run
    scene = meshgap.Scene.from_cfg(HAND_BOWL)
    problem = md.problem(HAND_BOWL)
    check_store(out, n, chunk, scene, problem.volume, False)
    assert not [name for _, _, names in os.walk(out) for name in names if name.endswith(".partial")]
