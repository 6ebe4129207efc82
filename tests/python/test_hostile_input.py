"""Hostile and unusual input to the Python module: each gives the right answer or one clear exception (never a crash,
a hang or a silent wrong answer). Arrays too large to copy, link indices past any integer, trimesh-like objects and
float32 vertices, planner parameters by either spelling."""
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import meshgap
from conftest import MAPS, box, merged

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
