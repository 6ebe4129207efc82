"""meshgap.campaign on a local Dask cluster of two worker processes: a small campaign (two maps, two planners, two
checkers, two batches of two runs) ends with every cell's complete log, seeded as specified, and one database of
one experiment per problem; a second call, from a campaign file, reruns nothing; a campaign during which a worker is
killed ends with the same logs as the undisturbed one (timings aside); a failing cell is retried; bad input raises
one clear exception and writes nothing."""
import ast
import hashlib
import os
import signal
import sqlite3
import sys
import threading
import time

import pytest

try:
    import distributed
except ImportError as error:
    pytest.skip("meshgap.campaign needs Debian's python3-dask and python3-distributed: %s" % error,
                allow_module_level=True)

import meshgap.campaign as mc
from conftest import MAPS, SOURCE_DIR, cli_error, executable

PROBLEMS = [MAPS / "twisted" / "twisted.cfg", MAPS / "hand_bowl" / "hand_bowl.cfg"]
PLANNERS = ["rrtconnect", "rrt"]
CHECKERS = ["certified", "fast"]
# Each run ends by solving (these maps take milliseconds), well within the limit: the runs are the same in any
# process with the same seed, timings aside.
SETTINGS = dict(problems=PROBLEMS, planners=PLANNERS, checkers=CHECKERS, runs=4, batch=2, time=5.0, seed=7)
OMPL_NAMES = {"rrtconnect": "RRTConnect", "rrt": "RRT"}
LABELS = {"certified": "meshgap-certified", "fast": "meshgap-fast"}


@pytest.fixture(scope="module")
def reference(client, tmp_path_factory):
    out = tmp_path_factory.mktemp("reference") / "campaign"
    summary = mc.run(out=out, client=client, executable=executable("benchmark"), progress=False, **SETTINGS)
    return out, summary


def parse_log(path):
    """An OMPL .log as (experiment, seed, [(planner, common properties, run property names, run rows)])."""
    lines = path.read_text().splitlines()
    experiment = next(line[len("Experiment "):] for line in lines if line.startswith("Experiment "))
    seed = next(line.split()[0] for line in lines if line.endswith("is the random seed"))
    planners, i = [], next(k for k, line in enumerate(lines) if line.endswith(" planners")) + 1
    while i < len(lines) and lines[i] != "":
        name = lines[i]
        common = int(lines[i + 1].split()[0])
        settings = lines[i + 2:i + 2 + common]
        i += 2 + common
        count = int(lines[i].split()[0])
        names = lines[i + 1:i + 1 + count]
        i += 1 + count
        runs = int(lines[i].split()[0])
        rows = [[v.strip() for v in line.split(";")[:-1]] for line in lines[i + 1:i + 1 + runs]]
        i += 1 + runs
        while i < len(lines) and lines[i] != ".":
            i += 1
        planners.append((name, settings, names, rows))
        i += 1
    return experiment, seed, planners


def timeless(path):
    """A log's contents without what depends on the clock: run properties named with time or memory, and the
    measures of runs that ended by the time limit (unsolved)."""
    experiment, seed, planners = parse_log(path)
    out = []
    for name, settings, names, rows in planners:
        keep = [k for k, n in enumerate(names) if "time" not in n and "memory" not in n]
        solved = names.index("solved BOOLEAN")
        out.append((name, settings, [names[k] for k in keep],
                    [[row[k] for k in keep] if row[solved] == "1" else ["unsolved"] for row in rows]))
    return experiment, seed, out


def expected_cells():
    """The grid, named and seeded as the campaign's format specifies (independently of the module)."""
    cells = {}
    for cfg in PROBLEMS:
        stem = cfg.stem
        for planner in PLANNERS:
            for checker in CHECKERS:
                for b in (1, 2):
                    name = "%s.%s.%s.b%dof2" % (stem, planner, checker, b)
                    digest = hashlib.sha256(("7/%s" % name).encode()).digest()
                    cells[name] = (stem, planner, checker, int.from_bytes(digest[:8], "little") % (2 ** 31 - 1) + 1)
    return cells


def test_campaign_complete_database_and_no_rerun(client, reference, tmp_path):
    out, summary = reference
    cells = expected_cells()
    assert summary["cells"] == summary["ran"] == len(cells) == 16 and summary["present"] == 0
    assert sorted(p.name for p in out.glob("*.log")) == sorted(name + ".log" for name in cells)
    assert not (out / ".cells").exists()
    for name, (stem, planner, checker, seed) in cells.items():
        experiment, logged_seed, planners = parse_log(out / (name + ".log"))
        assert experiment == stem and logged_seed == str(seed), name
        assert len(planners) == 1
        title, settings, names, rows = planners[0]
        assert title == "geometric_%s[%s]" % (OMPL_NAMES[planner], LABELS[checker])
        assert "checker = %s" % LABELS[checker] in settings
        assert len(rows) == 2 and all(len(row) == len(names) for row in rows)
        assert all(row[names.index("solved BOOLEAN")] == "1" for row in rows), name
    # One database, one experiment per problem holding all its cells' runs.
    db = sqlite3.connect(str(out / "results.db"))
    experiments = dict(db.execute("SELECT name, id FROM experiments").fetchall())
    assert sorted(experiments) == ["hand_bowl", "twisted"]
    for stem, experiment in experiments.items():
        rows = db.execute("SELECT p.name, COUNT(*) FROM runs r JOIN plannerConfigs p ON r.plannerid = p.id "
                          "WHERE r.experimentid = ? GROUP BY p.name", (experiment,)).fetchall()
        assert sorted(rows) == sorted(("geometric_%s[%s]" % (OMPL_NAMES[p], LABELS[c]), 4)
                                      for p in PLANNERS for c in CHECKERS), (stem, rows)
        assert db.execute("SELECT runcount FROM experiments WHERE id = ?", (experiment,)).fetchone()[0] == 4
    assert db.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 32
    db.close()
    # The same campaign from a file: nothing rerun, not a log touched.
    stamps = {p.name: (p.stat().st_ino, p.stat().st_mtime_ns) for p in out.glob("*.log")}
    campaign = tmp_path / "campaign.cfg"
    campaign.write_text("[campaign]\nproblems = %s\n    %s\nplanners = rrtconnect, rrt\ncheckers = certified, fast  # two\n"
                        "runs = 4\nbatch = 2\ntime = 5\nseed = 7\nout = %s\n" % (
                            os.path.relpath(PROBLEMS[0], tmp_path), PROBLEMS[1], out))
    again = mc.run_file(campaign, client=client, executable=executable("benchmark"), progress=False)
    assert (again["cells"], again["ran"], again["present"]) == (16, 0, 16)
    assert stamps == {p.name: (p.stat().st_ino, p.stat().st_mtime_ns) for p in out.glob("*.log")}
    # One cell's log removed: only that cell runs again, with its own seed: the same runs.
    gone = out / "hand_bowl.rrt.fast.b2of2.log"
    before = timeless(gone)
    gone.unlink()
    third = mc.run_file(campaign, client=client, executable=executable("benchmark"), progress=False)
    assert (third["ran"], third["present"]) == (1, 15)
    assert timeless(gone) == before
    # The same folder with other settings: refused, nothing touched.
    with pytest.raises(ValueError, match=r"twisted.rrtconnect.certified.b1of2.log: a log of other settings"):
        mc.run(out=out, client=client, executable=executable("benchmark"), progress=False,
               **dict(SETTINGS, time=4.0))
    with pytest.raises(ValueError, match=r"twisted.rrtconnect.certified.b1of2.log: a log of other settings"):
        mc.run(out=out, client=client, executable=executable("benchmark"), progress=False, **dict(SETTINGS, seed=8))
    stamps[gone.name] = (gone.stat().st_ino, gone.stat().st_mtime_ns)
    assert stamps == {p.name: (p.stat().st_ino, p.stat().st_mtime_ns) for p in out.glob("*.log")}


def test_bad_input_writes_nothing(client, tmp_path):
    out = tmp_path / "campaign"
    bench = executable("benchmark")
    common = dict(SETTINGS, out=out, executable=bench, progress=False)
    with pytest.raises(ConnectionError, match="cannot reach the Dask scheduler at tcp://127.0.0.1:1 within 2 s"):
        mc.run(client="tcp://127.0.0.1:1", timeout=2, **common)
    with pytest.raises(FileNotFoundError, match="none.cfg: no such file"):
        mc.run(client=client, **dict(common, problems=[PROBLEMS[0], tmp_path / "none.cfg"]))
    with pytest.raises(ValueError, match=r"hand_bowl.cfg: planner: unknown planner 'rrtfast'; valid names: .*rrtconnect"):
        mc.run(client=client, **dict(common, problems=[PROBLEMS[1]], planners=["rrtconnect", "rrtfast"]))
    with pytest.raises(ValueError, match=r"--checker: unknown checker 'exact'"):
        mc.run(client=client, **dict(common, checkers=["exact"]))
    with pytest.raises(FileNotFoundError, match="nowhere/meshgap_benchmark: meshgap_benchmark not found there"):
        mc.run(client=client, **dict(common, executable=tmp_path / "nowhere" / "meshgap_benchmark"))
    with pytest.raises(ValueError, match="batch: expected a positive integer, got 0"):
        mc.run(client=client, **dict(common, batch=0))
    campaign = tmp_path / "bad.cfg"
    campaign.write_text("[campaign]\nproblems = a.cfg\nplanners = rrt\nrun = 3\n")
    with pytest.raises(ValueError, match="bad.cfg: unknown key 'run' in \\[campaign\\]"):
        mc.run_file(campaign, client=client)
    # From a shell: one error line, exit 1.
    assert cli_error([sys.executable, "-m", "meshgap.campaign", str(tmp_path / "none.cfg")]) == \
        "%s: no such file" % (tmp_path / "none.cfg")
    assert cli_error([sys.executable, "-m", "meshgap.campaign", str(campaign)]).startswith(
        "%s: unknown key 'run' in [campaign]" % campaign)
    assert not out.exists() and not list(tmp_path.glob("campaign*"))


def readme_campaign():
    """The campaign example of README.md: its code block that calls mc.run, parsed."""
    text = (SOURCE_DIR / "README.md").read_text()
    blocks = [b.split("\n", 1)[1] for b in text.split("```")[1::2] if b.startswith("python\n")]
    found = [b for b in blocks if "mc.run(" in b]
    assert len(found) == 1, "README.md: expected one python block calling mc.run, found %d" % len(found)
    return ast.parse(found[0])


def test_readme_campaign_runs_as_written(client, tmp_path, monkeypatch):
    """README.md's campaign, run as written from a folder where its paths hold (maps/ the repository's), its grid
    (problems, planners, checkers, seed, out) the README's own; only its size (runs, batch, seconds per run) is made
    small. It names rrtstar, an optimizing planner whose logs hold its progress data, a second "<N> runs" block."""
    tree = readme_campaign()
    calls = [n for n in ast.walk(tree) if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute) and
             n.func.attr == "run" and isinstance(n.func.value, ast.Name) and n.func.value.id == "mc"]
    assert len(calls) == 1
    call = calls[0]
    written = {k.arg: ast.literal_eval(k.value) for k in call.keywords}
    problems, planners = (ast.literal_eval(a) for a in call.args)
    assert set(written) == {"checkers", "runs", "batch", "time", "seed", "out"}, written
    assert "rrtstar" in planners
    small = {"runs": 2, "batch": 1, "time": 0.5}
    for k in call.keywords:
        if k.arg in small:
            k.value = ast.Constant(small[k.arg])
    (tmp_path / "maps").symlink_to(MAPS)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MESHGAP_BENCHMARK", executable("benchmark"))
    exec(compile(ast.fix_missing_locations(tree), "README.md", "exec"), {})
    out = tmp_path / written["out"]
    cells = len(problems) * len(planners) * len(written["checkers"]) * small["runs"] // small["batch"]
    logs = sorted(out.glob("*.log"))
    assert len(logs) == cells == 8 and not (out / ".cells").exists()
    assert all(mc.log_runs(log) == 1 for log in logs), [(log.name, mc.log_runs(log)) for log in logs]
    assert any("progress properties for each run" in log.read_text() for log in logs)  # rrtstar's
    db = sqlite3.connect(str(out / "results.db"))
    assert db.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == cells
    db.close()


def test_log_runs_counts_run_data_once(tmp_path):
    """An optimizing planner's log names "<N> runs" twice (run data, then progress data): N runs, not None; a log
    cut short, or whose planners hold different counts, has no count."""
    def log(planners):
        lines = ["Experiment e", "1 is the random seed", "%d planners" % len(planners)]
        for name, runs, progress in planners:
            lines += [name, "1 common properties", "range = 1", "2 properties for each run", "time REAL",
                      "solved BOOLEAN", "%d runs" % runs] + ["0.1; 1; "] * runs
            if progress is not None:
                lines += ["1 progress properties for each run", "time REAL", "%d runs" % progress] + \
                    ["0.05,;0.1,;"] * progress
            lines.append(".")
        path = tmp_path / ("%d.log" % len(list(tmp_path.iterdir())))
        path.write_text("\n".join(lines) + "\n")
        return path

    assert mc.log_runs(log([("geometric_RRTstar", 3, 3)])) == 3
    assert mc.log_runs(log([("geometric_RRT", 2, None)])) == 2
    assert mc.log_runs(log([("a", 2, 2), ("b", 2, None)])) == 2
    assert mc.log_runs(log([("a", 2, 2), ("b", 3, None)])) is None
    cut = log([("geometric_RRTstar", 3, 3)])
    cut.write_text(cut.read_text()[:-20])
    assert mc.log_runs(cut) is None
    assert mc._log_settings(log([("geometric_RRTstar", 4, 4)]))[:2] == (4, 1)


def flaky(folder, real):
    """A meshgap_benchmark that fails the first time it runs a cell (by its --seed; marked in folder), then runs the
    real one."""
    folder.mkdir()
    script = folder / "flaky_benchmark"
    script.write_text("""#!/bin/sh
seed=""; previous=""
for a in "$@"; do [ "$previous" = "--seed" ] && seed="$a"; previous="$a"; done
if [ -n "$seed" ] && [ ! -e "%s/tried.$seed" ]; then
    : > "%s/tried.$seed"; echo "error: a simulated failure" >&2; exit 1
fi
exec "%s" "$@"
""" % (folder, folder, real))
    script.chmod(0o755)
    return script


def test_failed_cell_retried(client, tmp_path):
    settings = dict(SETTINGS, problems=[PROBLEMS[0]], planners=["rrtconnect"], checkers=["certified"], runs=2,
                    batch=1)
    script = flaky(tmp_path / "a", executable("benchmark"))
    # No retry: the first failure is the campaign's, naming the cell; no database.
    out = tmp_path / "once"
    with pytest.raises(RuntimeError, match=r"twisted.rrtconnect.certified.b\dof2: meshgap_benchmark failed on .* "
                                           r"\(exit 1\): a simulated failure"):
        mc.run(out=out, client=client, executable=script, retries=0, progress=False, **settings)
    assert not (out / "results.db").exists()
    # Nothing left behind: no OUT/.cells, and the folder this call made, empty, removed (a cell still running when
    # the campaign failed removes its own folder as it ends: waited for, up to a bound).
    deadline = time.monotonic() + 60
    while out.exists() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not (out / ".cells").exists() and not out.exists()
    # One retry: every cell fails once, then runs; the logs are the real executable's.
    script = flaky(tmp_path / "b", executable("benchmark"))
    out = tmp_path / "retried"
    summary = mc.run(out=out, client=client, executable=script, retries=1, progress=False, **settings)
    assert (summary["cells"], summary["ran"]) == (2, 2)
    assert len(list((tmp_path / "b").glob("tried.*"))) == 2
    assert [mc.log_runs(out / ("twisted.rrtconnect.certified.b%dof2.log" % b)) for b in (1, 2)] == [1, 1]
    assert sqlite3.connect(str(out / "results.db")).execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 2


def benchmark_processes(out):
    """The meshgap_benchmark processes running for the campaign at out."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open("/proc/%s/cmdline" % pid, "rb") as f:
                args = f.read().split(b"\0")
        except OSError:
            continue
        if args and args[0].endswith(b"meshgap_benchmark") and any(str(out).encode() in a for a in args):
            found.append(int(pid))
    return found


def test_campaign_survives_a_killed_worker(client, reference, tmp_path):
    """Last: it kills a worker process (its nanny starts another)."""
    out = tmp_path / "killed"
    result = {}
    run = threading.Thread(target=lambda: result.update(mc.run(out=out, client=client, progress=False,
                                                               executable=executable("benchmark"), **SETTINGS)))
    run.start()
    logs = lambda: len(list(out.glob("*.log"))) if out.exists() else 0
    deadline = time.monotonic() + 600  # generous: it only bounds a run that stalls
    while (logs() < 2 or not benchmark_processes(out)) and run.is_alive() and time.monotonic() < deadline:
        time.sleep(0.01)
    victims = [pid for pid in client.run(os.getpid).values()]
    running = benchmark_processes(out)
    before = logs()
    os.kill(sorted(victims)[0], signal.SIGKILL)
    run.join(timeout=600)
    assert not run.is_alive() and result["ran"] == 16 and result["present"] == 0, result
    assert 2 <= before < 16 and running, (before, running)  # killed mid-campaign, with cells running
    reference_out, _ = reference
    names = sorted(p.name for p in reference_out.glob("*.log"))
    assert sorted(p.name for p in out.glob("*.log")) == names
    for name in names:
        assert timeless(out / name) == timeless(reference_out / name), name
    assert not (out / ".cells").exists()
    time.sleep(0.5)
    assert not benchmark_processes(out)  # the killed worker's cell died with it
    db = sqlite3.connect(str(out / "results.db"))
    assert db.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 32
    db.close()
