"""meshgap.suite on a small MotionBenchMaker-format folder (the test arm among a block, two problems): the table's
rows from meshgap_benchmark's .log files, the same from the folder packed as .tar.bz2, and one error for bad input.
Skips without meshgap_benchmark (MESHGAP_BENCHMARK_CLI)."""
import os
import tarfile

import pytest

from meshgap import suite

HERE = os.path.dirname(os.path.abspath(__file__))
ARM = os.path.join(HERE, "..", "resources", "robot", "problems", "arm2.urdf")
ARM_SRDF = os.path.join(HERE, "..", "resources", "robot", "problems", "arm2.srdf")
SCENE = """world:
  collision_objects:
    - id: block
      primitives:
        - type: box
          dimensions: [0.2, 0.2, 0.2]
      primitive_poses:
        - position: [1.2, 0, 0.2]
          orientation: [0, 0, 0, 1]
"""
REQUEST = """start_state:
  joint_state: {name: [yaw, elbow], position: [0, 0]}
goal_constraints:
  - joint_constraints:
      - {joint_name: yaw, position: %s}
      - {joint_name: elbow, position: -0.5}
"""


@pytest.fixture
def benchmark():
    path = os.environ.get("MESHGAP_BENCHMARK_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("meshgap_benchmark not built (MESHGAP_BENCHMARK_CLI)")
    return path


def problems(root):
    folder = os.path.join(root, "problems", "block_arm2")
    os.makedirs(folder)
    for n, yaw in (("0001", 1.5), ("0002", -1.5)):
        with open(os.path.join(folder, "scene%s.yaml" % n), "w") as f:
            f.write(SCENE)
        with open(os.path.join(folder, "request%s.yaml" % n), "w") as f:
            f.write(REQUEST % yaw)
    return os.path.join(root, "problems")


def run(benchmark, source, out, *extra):
    return suite.main([source, "--urdf", ARM, "--srdf", ARM_SRDF, "--checkers", "certified,discrete", "--time", "2",
                       "--out", out, "--executable", benchmark] + list(extra))


def rows(out):
    with open(os.path.join(out, "summary.md")) as f:
        return [l.split("|")[1:-1] for l in f.read().splitlines()[2:]]


def test_table_from_a_folder_and_from_its_archive(benchmark, tmp_path, capsys):
    folder = problems(str(tmp_path / "data"))
    assert run(benchmark, folder, str(tmp_path / "a")) == 0
    table = rows(str(tmp_path / "a"))
    assert [r[1].strip() for r in table] == ["RRTConnect[meshgap-certified]", "RRTConnect[meshgap-discrete]"]
    for r in table:
        assert r[0].strip() == "block_arm2"
        assert (int(r[2]), int(r[3])) == (2, 2)  # runs, solved
        assert r[7].strip() in ("0 of 2", "0 of 0")  # none colliding under the dense check (FCL, when built)
        assert float(r[8]) > 0.0  # the least exact clearance along the paths
    if os.path.exists(str(tmp_path / "a" / "results.db")):  # ompl_benchmark_statistics (ompl-demos) found
        import sqlite3
        with sqlite3.connect(str(tmp_path / "a" / "results.db")) as db:
            assert db.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 4
    for n in ("0001", "0002"):
        logs = os.listdir(str(tmp_path / "a" / "block_arm2" / n))
        assert sorted(logs) == ["request%s.RRTConnect.meshgap-certified.log" % n,
                                "request%s.RRTConnect.meshgap-discrete.log" % n]
    # The tables of the run's folder read back, and of its problems split over two folders, are the run's own.
    import shutil
    for n, part in (("0001", "x"), ("0002", "y")):
        shutil.copytree(str(tmp_path / "a" / "block_arm2" / n), str(tmp_path / part / "block_arm2" / n))
    with open(str(tmp_path / "a" / "summary.md")) as f:
        summary = f.read()
    for folders in (str(tmp_path / "a"), "%s,%s" % (tmp_path / "x", tmp_path / "y")):
        capsys.readouterr()
        assert suite.main(["--tables-of", folders]) == 0
        assert capsys.readouterr().out == summary
    assert suite.main(["--tables-of", str(tmp_path / "data")]) == 1
    assert "not a suite's --out" in capsys.readouterr().err
    archive = str(tmp_path / "problems.tar.bz2")
    with tarfile.open(archive, "w:bz2") as t:
        t.add(folder, arcname="problems")
    assert run(benchmark, archive, str(tmp_path / "b"), "--limit", "1") == 0
    assert [(r[0].strip(), r[1].strip(), int(r[2])) for r in rows(str(tmp_path / "b"))] == \
        [("block_arm2", r[1].strip(), 1) for r in table]


def test_bad_input_is_one_error(benchmark, tmp_path, capsys):
    folder = problems(str(tmp_path / "data"))
    assert run(benchmark, folder, str(tmp_path / "a"), "--scenarios", "nowhere") == 1
    assert "no scenario nowhere" in capsys.readouterr().err
    os.remove(os.path.join(folder, "block_arm2", "request0002.yaml"))
    assert run(benchmark, folder, str(tmp_path / "a")) == 1
    assert "scene0002.yaml has no request0002.yaml" in capsys.readouterr().err


def test_log_reader_and_percentiles():
    assert suite.percentile([1.0, 2.0, 3.0, 4.0], 50) == 2.5
    assert suite.percentile([5.0], 95) == 5.0
    row = suite.summarize([{"solved": "1", "time": "2", "fcl path collision free": "1", "path min clearance": "0.1"},
                           {"solved": "1", "time": "1", "fcl path collision free": "0", "path min clearance": "-0.01"},
                           {"solved": "0", "time": "3"}])
    assert (row["runs"], row["solved"], row["colliding"], row["checked"]) == (3, 2, 1, 2)
    assert row["valid_per_minute"] == 60.0 * 1 / 6.0
    assert row["min_clearance"] == -0.01
    assert row["median"] == 1.5


def test_comparison_is_each_scenarios_ratio_and_the_median_scenarios():
    def row(rate, median):
        return {"valid_per_minute": rate, "median": median}
    rows = {("a", "RRTConnect[meshgap-certified]"): row(30.0, 0.2), ("a", "RRTConnect[fcl]"): row(10.0, 0.4),
            ("b", "RRTConnect[meshgap-certified]"): row(5.0, 1.0), ("b", "RRTConnect[fcl]"): row(20.0, 0.5),
            ("c", "RRTConnect[meshgap-certified]"): row(8.0, 0.3), ("c", "RRTConnect[fcl]"): row(0.0, 0.0),
            ("d", "RRTConnect[meshgap-certified]"): row(1.0, 1.0),  # no peer: no row
            ("a", "RRTConnect[meshgap-discrete]"): row(99.0, 0.01)}
    lines = suite.comparison(rows).splitlines()
    cells = [[c.strip() for c in l.split("|")[1:-1]] for l in lines[2:]]
    assert cells == [["a", "RRTConnect", "3", "0.5"], ["b", "RRTConnect", "0.25", "2"],
                     ["c", "RRTConnect", "inf", "inf"], ["median scenario", "", "3", "2"]]
    assert suite.comparison({("a", "RRTConnect[fcl]"): row(1.0, 1.0)}) == ""
