"""meshgap_benchmark on a robot problem file: the checkers of a robot (certified, certified-search, discrete, fcl) each
run and write OMPL's .log, every solved path is checked by FCL on every pair along the densely interpolated path, and
the valid paths per minute it prints agree with the runs the .log files record; certified's runs record what the
certification of the answer did."""
import re
import subprocess

import pytest

from conftest import cli_error, executable
from test_robot_scene import files, write_cfg  # noqa: F401  (files: the fixture)


def log_runs(log):
    """Per run of an OMPL .log: its property values by name (the names listed before the runs)."""
    lines = log.read_text().splitlines()
    at = next(i for i, line in enumerate(lines) if line.endswith("common properties"))
    at += 1 + int(lines[at].split()[0])
    count = int(lines[at].split()[0])
    names = lines[at + 1:at + 1 + count]
    at += 1 + count
    runs = int(lines[at].split()[0])
    rows = [line.strip().rstrip(";").split("; ") for line in lines[at + 1:at + 1 + runs]]
    return [dict(zip(names, row)) for row in rows]


def test_robot_benchmark_grid(files, tmp_path):  # noqa: F811
    cfg = write_cfg(files)
    out = tmp_path / "logs"
    run = subprocess.run([executable("benchmark"), "--cfg", str(cfg), "--planner", "rrtconnect", "--runs", "2",
                          "--time", "20", "--seed", "3", "--out", str(out)], capture_output=True, text=True,
                         timeout=600)
    assert run.returncode == 0, run.stderr
    for checker in ("meshgap-certified", "meshgap-certified-search", "meshgap-discrete", "fcl"):
        runs = log_runs(out / ("boxarm_problem.RRTConnect.%s.log" % checker))
        assert len(runs) == 2
        solved = [r for r in runs if r["solved BOOLEAN"] == "1"]
        free = [r for r in solved if r.get("fcl path collision free BOOLEAN") == "1"]
        assert len(free) == len(solved) == 2, (checker, runs)
        line = re.search(r"RRTConnect\[%s\]: 2 runs, (\d+) solved, (\d+) free by FCL's dense check" % checker,
                         run.stderr)
        assert line and (int(line.group(1)), int(line.group(2))) == (len(solved), len(free)), run.stderr
        if checker == "meshgap-certified":
            for r in solved:
                refused = int(r["certified answer motions refused INTEGER"])
                assert int(r["certified answer motions INTEGER"]) >= 1, r
                assert int(r["certified answer searches INTEGER"]) >= 1, r
                assert refused == int(r["certified answer motions repaired INTEGER"]) + \
                    int(r["certified answer paths rejected INTEGER"]), r


def test_robot_benchmark_bad_checker(files):  # noqa: F811
    cfg = str(write_cfg(files))
    message = cli_error([executable("benchmark"), "--cfg", cfg, "--planner", "rrtconnect", "--checker", "fast"])
    assert message == ("--checker: unknown checker 'fast'; valid names: certified, certified-search, discrete, "
                       "fcl"), message


def test_robot_benchmark_bodies_with_certified_motions(tmp_path):
    """Several rigid bodies (maps/swap_se2): the certified motion validator bounds every kind of robot, so the
    default grid has both certified checkers, and every run is solved."""
    from conftest import MAPS
    cfg = str(MAPS / "swap_se2" / "swap_se2.cfg")
    out = tmp_path / "logs"
    run = subprocess.run([executable("benchmark"), "--cfg", cfg, "--planner", "rrtconnect", "--runs", "1",
                          "--time", "20", "--seed", "2", "--out", str(out)], capture_output=True, text=True,
                         timeout=600)
    assert run.returncode == 0, run.stderr
    assert sorted(p.name for p in out.iterdir()) == ["swap_se2.RRTConnect.fcl.log",
                                                     "swap_se2.RRTConnect.meshgap-certified-search.log",
                                                     "swap_se2.RRTConnect.meshgap-certified.log",
                                                     "swap_se2.RRTConnect.meshgap-discrete.log"]
    for log in out.iterdir():
        assert log_runs(log)[0]["solved BOOLEAN"] == "1"
