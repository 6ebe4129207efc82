"""Hostile and unusual input to the Python module: each gives the right answer or one clear exception (never a crash,
a hang or a silent wrong answer). Arrays too large to copy, link indices past any integer, trimesh-like objects and
float32 vertices, planner parameters by either spelling."""
import os
import pathlib
import re
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import meshgap
from conftest import MAPS, box, merged, write_obj

ARM = MAPS / "arm_fixture" / "arm_fixture.cfg"
ROWS = 2 ** 56  # a broadcast view of this many rows cannot be copied (2^61 bytes and more) on any machine


def run_python(code):
    """Run code in a fresh interpreter (a crash there fails the test, not the test process): (exit code, stdout,
    stderr)."""
    run = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, timeout=300)
    return run.returncode, run.stdout.decode(), run.stderr.decode()


@pytest.mark.parametrize("method", ["distance", "in_collision", "link_poses"])
def test_robot_states_too_large_to_copy_raise_memory_error(method):
    code, out, err = run_python("""
        import numpy as np, meshgap
        s = meshgap.RobotScene.from_cfg(%r)
        try:
            s.%s(np.broadcast_to(s.start, (%d, s.dimension)))
        except MemoryError as e:
            print("MemoryError", e)
        """ % (str(ARM), method, ROWS))
    assert code == 0 and out.startswith("MemoryError"), (code, out, err)


@pytest.mark.parametrize("method", ["distance", "in_collision"])
def test_scene_poses_too_large_to_copy_raise_memory_error(method):
    code, out, err = run_python("""
        import numpy as np, meshgap
        s = meshgap.Scene.from_cfg(%r)
        try:
            s.%s(np.broadcast_to(s.start, (%d, 7)))
        except MemoryError as e:
            print("MemoryError", e)
        """ % (str(MAPS / "hand_bowl" / "hand_bowl.cfg"), method, ROWS))
    assert code == 0 and out.startswith("MemoryError poses: cannot allocate"), (code, out, err)


def test_mesh_arrays_too_large_to_copy_raise_memory_error():
    V, F = box(1, 1, 1)
    huge = np.broadcast_to(V[0], (ROWS, 3))
    with pytest.raises(MemoryError, match="robot V: cannot allocate .* GB for %d vertices" % ROWS):
        meshgap.Scene((huge, F), box(1, 1, 1, center=(5, 0, 0)))
    with pytest.raises(MemoryError):
        meshgap.Scene((V, np.broadcast_to(F[0], (ROWS, 3))), box(1, 1, 1, center=(5, 0, 0)))


HAND_BOWL = MAPS / "hand_bowl" / "hand_bowl.cfg"


def test_plan_params_by_planner_dot_name_as_the_cli():
    """params takes PLANNER.NAME (meshgap_plan --param's spelling) as it takes NAME: the same run; a parameter of
    another planner is refused as meshgap_plan refuses it."""
    run = lambda params, planner="rrtconnect": meshgap.plan(HAND_BOWL, planner=planner, time=5.0, seed=3,
                                                             params=params)
    bare, bare_summary = run({"range": 40})
    dotted, dotted_summary = run({"rrtconnect.range": 40})
    upper, _ = run({"RRTConnect.range": 40})
    other, _ = run({"range": 400})
    assert bare_summary["solved"] and dotted_summary["solved"]
    np.testing.assert_array_equal(bare, dotted)
    np.testing.assert_array_equal(bare, upper)
    assert bare.shape != other.shape or not np.array_equal(bare, other)  # the parameter does change the run
    with pytest.raises(ValueError, match=r"'rrt.range=40': the planner is rrtconnect, not rrt"):
        run({"rrt.range": 40})
    with pytest.raises(ValueError, match=r"nosuch"):
        run({"rrtconnect.nosuch": 1})
    _, summary = run({"prm.max_nearest_neighbors": 8}, planner="prm")
    assert summary["planner"] == "prm"


class TrimeshLike:
    """What trimesh.Trimesh offers the module: .vertices (n, 3) and .faces (m, 3)."""

    def __init__(self, V, F):
        self.vertices, self.faces = V, F


def test_meshes_trimesh_like_float32_and_integer_vertices():
    robot, world = box(0.5, 0.5, 0.5), merged(box(1, 1, 1, center=(4, 0, 0)), box(1, 2, 1, center=(-5, 1, 0)))
    poses = np.array([[0, 0, 0, 0, 0, 0, 1], [1.5, 0.5, 0, 0, 0, 0.3826834323650898, 0.9238795325112867],
                      [-3.2, 0, 0.25, 0, 0, 0, 1]], dtype=np.float64)
    want = meshgap.Scene(robot, world).distance(poses)["distance"]
    # Every coordinate of these boxes is exact in float32 and as an integer multiple: the same meshes.
    forms = [(TrimeshLike(*robot), TrimeshLike(*world)),
             ((robot[0].astype(np.float32), robot[1].astype(np.int32)), (world[0].astype(np.float32), world[1])),
             ((robot[0].tolist(), robot[1].tolist()), TrimeshLike(world[0].astype(np.float32),
                                                                  world[1].astype(np.uint32)))]
    for r, w in forms:
        np.testing.assert_array_equal(meshgap.Scene(r, w).distance(poses)["distance"], want)
    doubled = (2 * robot[0]).astype(np.int64), robot[1]
    np.testing.assert_array_equal(meshgap.Scene(doubled, world).robot_mesh[0], 2 * robot[0])
    with pytest.raises(ValueError, match=r"^world.vertices: expected shape \(n, 3\), got \(16, 2\)$"):
        meshgap.Scene(robot, TrimeshLike(world[0][:, :2], world[1]))
    with pytest.raises(ValueError, match=r"^robot.faces: dtype float64, expected an integer type$"):
        meshgap.Scene(TrimeshLike(robot[0], robot[1].astype(np.float64)), world)
    with pytest.raises(ValueError, match=r"^robot V: dtype <U1, expected real numbers$"):
        meshgap.Scene((np.full((8, 3), "a"), robot[1]), world)
    with pytest.raises(ValueError, match=r"^robot.faces: row 0: vertex index -1 is out of range \[0, 8\)$"):
        meshgap.Scene(TrimeshLike(robot[0], np.where(np.arange(12)[:, None] == 0, -1, robot[1])), world)


def test_scene_bounds_are_the_cfg_volume(tmp_path):
    s = meshgap.Scene.from_cfg(HAND_BOWL)
    np.testing.assert_array_equal(s.bounds, [[-276, 361], [-276, 276], [-126, 234], [-1, 1], [-1, 1], [-1, 1],
                                             [-1, 1]])
    write_obj(tmp_path / "wall.obj", box(0.3, 2, 0.5, (0, 3, 0.5)))
    write_obj(tmp_path / "bar.obj", box(0.6, 0.2, 0.5))
    (tmp_path / "planar.cfg").write_text("[problem]\nrobot = bar.obj\nworld = wall.obj\nstart.x = -3\nstart.y = 0.5\n"
                                         "start.theta = 0\nvolume.min.x = -4\nvolume.min.y = -2\nvolume.max.x = 4\n"
                                         "volume.max.y = 2\n")
    planar = meshgap.Scene.from_cfg(tmp_path / "planar.cfg")
    assert planar.planar
    np.testing.assert_array_equal(planar.bounds, [[-4, 4], [-2, 2], [-np.pi, np.pi]])
    assert meshgap.Scene(box(1, 1, 1), box(1, 1, 1, center=(5, 0, 0))).bounds is None


def test_index_past_any_integer_names_index_and_range():
    arm = meshgap.RobotScene.from_cfg(ARM)
    links = len(arm.link_names)
    with pytest.raises(ValueError, match=r"^link: index %d is out of range \[0, %d\)$" % (2 ** 70, links)):
        arm.link_mesh(2 ** 70)
    with pytest.raises(ValueError, match=r"^link: index -1 is out of range \[0, %d\)$" % links):
        arm.link_mesh(-1)
    with pytest.raises(ValueError, match=r"^link: expected a link's name \(str\) or index \(int\), got float$"):
        arm.link_mesh(1.0)
    np.testing.assert_array_equal(arm.link_mesh(np.int64(1))[1], arm.link_mesh(arm.link_names[1])[1])
    s = meshgap.Scene.from_cfg(HAND_BOWL)
    for scene in (arm, s):
        with pytest.raises(ValueError, match=r"^obstacle_mesh: index %d is out of range \[0, %d\)$" % (
                2 ** 70, scene.obstacles)):
            scene.obstacle_mesh(2 ** 70)
        with pytest.raises(ValueError, match=r"^obstacle_mesh: index -3 is out of range"):
            scene.obstacle_mesh(-3)


def dask_or_skip():
    return pytest.importorskip("dask", reason="meshgap.distributed needs Debian's python3-dask")


def test_distributed_chunks_must_be_positive():
    dask_or_skip()
    import meshgap.distributed as md
    poses = np.tile(meshgap.Scene.from_cfg(HAND_BOWL).start, (10, 1))
    for chunks in (0, -5, 2.5, True, "8"):
        with pytest.raises(ValueError, match=r"^chunks: expected a positive integer \(rows per task\) or None, got "):
            md.distance(HAND_BOWL, poses, chunks=chunks)
        with pytest.raises(ValueError, match=r"^chunks: expected a positive integer"):
            md.in_collision(HAND_BOWL, poses, chunks=chunks)


def test_distributed_bad_row_is_named_by_its_row_of_the_whole_array():
    dask = dask_or_skip()
    import meshgap.distributed as md
    arm = meshgap.RobotScene.from_cfg(ARM)
    states = np.tile(arm.start, (1000, 1))
    states[700, 1] = np.nan
    with pytest.raises(ValueError, match=r"^states\[700\]: state has a NaN"):
        dask.compute(md.distance(ARM, states, chunks=256), scheduler="sync")
    with pytest.raises(ValueError, match=r"^states\[700\]: state has a NaN"):
        md.in_collision(ARM, states, chunks=256).compute(scheduler="sync")
    poses = np.tile(meshgap.Scene.from_cfg(HAND_BOWL).start, (1000, 1))
    poses[700, 2] = np.inf
    with pytest.raises(ValueError, match=r"^poses\[700\]: pose has a NaN or infinite number$"):
        dask.compute(md.distance(HAND_BOWL, poses, chunks=256), scheduler="sync")
    with pytest.raises(ValueError, match=r"^poses\[700\]: pose has a NaN"):
        md.in_collision(HAND_BOWL, poses, chunks=256).compute(scheduler="sync")
    poses[700, 2] = 0.0
    poses[100, 6] = 2.0  # in the first chunk: its row is the array's
    with pytest.raises(ValueError, match=r"^poses\[100\]: quaternion"):
        dask.compute(md.distance(HAND_BOWL, poses, chunks=256), scheduler="sync")


def can_make_a_folder_in(folder):
    try:
        (folder / "probe").mkdir()
    except PermissionError:
        return False
    (folder / "probe").rmdir()
    return True


def test_label_into_a_folder_it_cannot_write_names_the_folder(tmp_path):
    dask_or_skip()
    pytest.importorskip("zarr", reason="label() needs Debian's python3-zarr")
    import meshgap.distributed as md
    read_only = tmp_path / "read-only"
    read_only.mkdir()
    read_only.chmod(0o555)
    folder = next((f for f in (read_only, pathlib.Path("/sys")) if not can_make_a_folder_in(f)), None)
    if folder is None:  # root writes in any folder of its own
        pytest.skip("no folder this user cannot write in (%s and /sys are writable)" % read_only)
    out = folder / "labels.zarr"
    with pytest.raises(PermissionError, match=r"^%s: cannot create the data set in %s: " % (re.escape(str(out)),
                                                                                            re.escape(str(folder)))):
        md.label(HAND_BOWL, 100, out=out, chunk=50, client=False, progress=False)
    notfolder = tmp_path / "file"
    notfolder.write_text("")
    with pytest.raises(NotADirectoryError, match=r"file/labels.zarr: cannot create the data set in .*file: "):
        md.label(HAND_BOWL, 100, out=notfolder / "labels.zarr", chunk=50, client=False, progress=False)
    read_only.chmod(0o755)


def test_campaign_file_of_garbage_or_huge_lines_names_the_file_and_cuts_the_echo(tmp_path):
    pytest.importorskip("distributed", reason="meshgap.campaign needs Debian's python3-distributed")
    import meshgap.campaign as mc
    garbage = tmp_path / "garbage.cfg"
    garbage.write_bytes(bytes(range(256)) * 8)
    with pytest.raises(ValueError, match=r"^%s: not a campaign file: not UTF-8 text \(byte 0x80 at offset 128\)$"
                       % re.escape(str(garbage))):
        mc.read_file(garbage)
    huge = "x" * 30_000_000
    cases = {"line.cfg": (huge + "\n", r":1: not a campaign file: 'x{79}\.\.\. \(30000002 characters\)$"),
             "runs.cfg": ("[campaign]\nproblems = a.cfg\nplanners = rrt\nruns = 1%s\n" % huge,
                          r": runs = '1x{78}\.\.\. \(30000003 characters\) is not a number$"),
             "key.cfg": ("[campaign]\nproblems = a.cfg\nplanners = rrt\n%s = 1\n" % huge,
                         r": unknown key 'x{79}\.\.\. \(30000002 characters\) in \[campaign\]"),
             "problem.cfg": ("[campaign]\nplanners = rrt\nproblems = %s\n" % huge, r"x{100}\.\.\. \(30")}
    for name, (text, message) in cases.items():
        path = tmp_path / name
        path.write_text(text)
        with pytest.raises((ValueError, FileNotFoundError)) as error:
            mc.grid(**{k: v for k, v in mc.read_file(path).items() if k in ("problems", "planners", "runs")})
        assert len(str(error.value)) < 2000 and re.search(message, str(error.value)), (name, str(error.value)[:300])
        assert str(error.value).startswith(str(path if name != "problem.cfg" else tmp_path)), name
