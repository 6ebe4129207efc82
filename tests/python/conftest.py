"""Shared helpers of the Python module's tests (run by CTest with PYTHONPATH at the built module and the paths of
the executables in MESHGAP_*_CLI; see tests/python/CMakeLists.txt)."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
MAPS = SOURCE_DIR / "maps"
# The optional shared data folder (CMake's MESHGAP_SHARED_DATA_DIR, ../shared/data by default).
SHARED_DATA = pathlib.Path(os.environ.get("MESHGAP_SHARED_DATA_DIR", SOURCE_DIR / ".." / "shared" / "data"))
OMPLAPP = (SHARED_DATA / "omplapp").resolve()
RESOURCES = SOURCE_DIR / "tests" / "resources"


def executable(name):
    """Path of a meshgap executable from the environment CTest sets, or skip."""
    path = os.environ.get("MESHGAP_%s_CLI" % name.upper())
    if not path or not os.path.exists(path):
        pytest.skip("meshgap_%s not built (MESHGAP_%s_CLI unset): planners off?" % (name, name.upper()))
    return path


def omplapp(name):
    """An OMPL.app problem file in ../shared/data/omplapp, or skip with a message."""
    path = OMPLAPP / name
    if not path.exists():
        pytest.skip("%s not found: the public OMPL.app problems are looked for in %s" % (name, OMPLAPP))
    return path


def box(hx, hy, hz, center=(0.0, 0.0, 0.0)):
    """A closed axis-aligned box of half sizes hx, hy, hz as (V, F), outward winding."""
    c = np.asarray(center, dtype=np.float64)
    V = np.array([[x, y, z] for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)], dtype=np.float64) + c
    # vertex index = 4 * (x > 0) + 2 * (y > 0) + (z > 0)
    F = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]], dtype=np.int64)
    return V, F


def merged(*meshes):
    V, F, offset = [], [], 0
    for v, f in meshes:
        V.append(v)
        F.append(f + offset)
        offset += len(v)
    return np.vstack(V), np.vstack(F)


def write_obj(path, mesh):
    V, F = mesh
    with open(path, "w") as out:
        for v in V:
            out.write("v %.17g %.17g %.17g\n" % tuple(v))
        for f in F:
            out.write("f %d %d %d\n" % tuple(f + 1))


def cli_error(args):
    """Run an executable expected to fail; return its one error message (without "error: ")."""
    run = subprocess.run(args, capture_output=True, timeout=120)
    stderr = run.stderr.decode("utf-8", "backslashreplace")
    assert run.returncode == 1, (args, run.returncode, stderr)
    lines = [line for line in stderr.splitlines() if line.startswith("error: ")]
    assert len(lines) == 1, stderr
    return lines[0][len("error: "):]


@pytest.fixture(scope="module")
def client():
    """A Dask client on a LocalCluster of 2 worker processes, one thread each, for a test module's tests."""
    import distributed  # here, not at the top: modules without Dask skip before they ask for it

    cluster = distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=":0")
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()
