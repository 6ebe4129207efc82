"""Benchmark campaigns on Dask: the grid problems x planners x checkers x samplers x run batches, one Dask task per
cell, each running meshgap_benchmark for that cell with its own seed; then every .log into one SQLite database with
OMPL's ompl_benchmark_statistics, for Planner Arena.

    import meshgap.campaign as mc
    client = meshgap.distributed.connect()          # or connect("tcp://HOST:8786")
    summary = mc.run(["maps/hand_bowl/hand_bowl.cfg"], ["rrtconnect", "rrt"], checkers=["certified", "fcl"],
                     runs=20, batch=5, time=10, seed=1, out="campaign")
    summary = mc.run_file("campaign.cfg")           # the same from a campaign file

or from a shell: python3 -m meshgap.campaign campaign.cfg [--scheduler tcp://HOST:8786].

A campaign file is INI (Python's configparser) with one section [campaign]; lists are comma- or newline-separated and
relative paths are taken from the file's folder:

    [campaign]
    problems = maps/hand_bowl/hand_bowl.cfg, ../shared/data/omplapp/Easy.cfg   # required
    planners = rrtconnect, rrt                     # required: meshgap_benchmark's --planner names
    checkers = certified, fcl                      # default: certified
    samplers = uniform, narrow_passage             # default: none (each problem's own valid-state sampler)
    runs = 20                                      # runs per (problem, planner, checker, sampler); default 10
    batch = 5                                      # runs per cell, i.e. per task; default: all of them
    time = 10                                      # seconds per run; default 10
    memory = 4096                                  # MB per run; default 4096
    seed = 1                                       # the campaign's seed (positive); default 1
    out = campaign                                 # the folder of the logs and the database; default campaign
    database = results.db                          # in out; default results.db
    retries = 3                                    # Dask's retries of a failed cell; default 3
    param = rrtconnect.range=5                     # meshgap_benchmark --param, repeatable by lines; default none

A cell is (problem, planner, checker, sampler, batch b of B); it writes OUT/<problem>.<planner>.<checker>[.<sampler>]
.b<b>of<B>.log, an OMPL log of its runs, seeded with a seed drawn from the campaign's seed and the cell's name (the
same cell gets the same seed in any campaign, whatever else it holds). meshgap_benchmark writes into a folder of the
cell's own (OUT/.cells/...), and the task moves the log into place once it holds all the cell's runs: a log in OUT is
complete, a cell whose log is there is never rerun, and a cell failed (non-zero exit, or runs missing) or lost with its
worker is run again by Dask (retries= for failures; a lost worker's tasks go to the others). A log already in OUT of
other settings (runs, seed, time or memory) is refused before anything runs: one folder, one campaign. meshgap_benchmark is
found by executable=, else $MESHGAP_BENCHMARK, else beside the package (a build tree's planners/, an install's bin/),
else on PATH; problems and the executable must be at the same paths on every worker, and OUT a folder they share.
Needs Debian's python3-dask and python3-distributed, and ompl-demos for the database.
"""
import configparser
import contextlib
import glob
import hashlib
import math
import os
import re
import shutil
import socket
import subprocess
import sys
import tempfile

CAMPAIGN_KEYS = ("problems", "planners", "checkers", "samplers", "runs", "batch", "time", "memory", "seed", "out",
                 "database", "retries", "param")


def find_executable(executable=None):
    """The path of meshgap_benchmark: executable, else $MESHGAP_BENCHMARK, else beside the package (build tree:
    build/planners/; install: PREFIX/bin/), else on PATH. FileNotFoundError saying where it was looked for."""
    if executable is not None:
        path = os.path.abspath(os.fspath(executable))
        if not os.path.isfile(path) or not os.access(path, os.X_OK):
            raise FileNotFoundError("%s: meshgap_benchmark not found there (or not executable)" % path)
        return path
    looked = []
    if os.environ.get("MESHGAP_BENCHMARK"):
        return find_executable(os.environ["MESHGAP_BENCHMARK"])
    package = os.path.dirname(os.path.abspath(__file__))
    candidates = [os.path.join(package, "..", "..", "planners", "meshgap_benchmark")]
    parent = package
    for _ in range(5):  # PREFIX/lib/python3/dist-packages/meshgap -> PREFIX/bin
        parent = os.path.dirname(parent)
        candidates.append(os.path.join(parent, "bin", "meshgap_benchmark"))
    for path in candidates:
        path = os.path.normpath(path)
        looked.append(path)
        if os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    found = shutil.which("meshgap_benchmark")
    if found:
        return os.path.abspath(found)
    raise FileNotFoundError("meshgap_benchmark not found: give executable=, or set MESHGAP_BENCHMARK (looked beside "
                            "the package: %s; and on PATH)" % ", ".join(looked))


def _dask():
    """meshgap.distributed, imported on first use (it needs Dask; importing meshgap does not)."""
    from . import distributed
    return distributed


def _cut(text, limit=80):
    """text for an error message, cut to its first limit characters (an input may be megabytes long)."""
    return text if len(text) <= limit else text[:limit] + "... (%d characters)" % len(text)


def _shown(value):
    """repr(value) for an error message, cut (_cut())."""
    return _cut(repr(value))


def _names(value, what):
    if value is None:
        return []
    if isinstance(value, str):
        value = [v for v in re.split(r"[,\n]", value)]
    names = [str(v).strip() for v in value if str(v).strip()]
    if len(set(names)) != len(names):
        raise ValueError("%s: %s names one twice" % (what, _shown(value)))
    return names


def _safe(name):
    return re.sub(r"[^A-Za-z0-9_+-]", "_", name)


class Cell:
    """One task of a campaign: its problem's cfg, planner, checker, sampler ("" for the problem's own), batch b of B,
    the runs it holds, its seed and the name of its log."""

    def __init__(self, cfg, stem, planner, checker, sampler, b, batches, runs, seed):
        self.cfg, self.planner, self.checker, self.sampler = cfg, planner, checker, sampler
        self.b, self.batches, self.runs, self.seed = b, batches, runs, seed
        self.name = "%s.%s.%s%s.b%dof%d" % (stem, _safe(planner), _safe(checker),
                                            "." + _safe(sampler) if sampler else "", b, batches)

    def __repr__(self):
        return "<meshgap.campaign.Cell %s, %d runs, seed %d>" % (self.name, self.runs, self.seed)


def cell_seed(seed, name):
    """A cell's seed: from the campaign's seed and the cell's name, in [1, 2^31 - 1] (meshgap_benchmark's 0 is
    "random")."""
    digest = hashlib.sha256(("%d/%s" % (seed, name)).encode()).digest()
    return int.from_bytes(digest[:8], "little") % (2 ** 31 - 1) + 1


def grid(problems, planners, checkers=("certified",), samplers=(), runs=10, batch=None, seed=1):
    """The cells of a campaign, in order (problem, planner, checker, sampler, batch). ValueError for an empty or
    repeated list, or runs, batch or seed that are not positive integers; FileNotFoundError for a missing problem
    file (or one of its meshes)."""
    problems = [os.fspath(p) for p in ([problems] if isinstance(problems, (str, os.PathLike)) else problems)]
    planners, checkers = _names(planners, "planners"), _names(checkers, "checkers")
    samplers = _names(samplers, "samplers") or [""]
    for what, value in (("runs", runs), ("batch", runs if batch is None else batch), ("seed", seed)):
        if isinstance(value, bool) or not isinstance(value, int) or value <= 0:
            raise ValueError("%s: expected a positive integer, got %s" % (what, _shown(value)))
    if not problems or not planners or not checkers:
        raise ValueError("a campaign needs problems, planners and checkers (got %d, %d, %d)" % (
            len(problems), len(planners), len(checkers)))
    batch = runs if batch is None else min(batch, runs)
    cells, stems, _md = [], {}, _dask()
    for path in problems:
        p = _md.problem(path)  # FileNotFoundError naming the cfg or its mesh
        if p.kind != "cfg":
            raise ValueError("problems: %s is not a .cfg path" % _shown(path))
        stem = _safe(_md._read_cfg(p.files[0]).get("name") or os.path.splitext(os.path.basename(p.files[0]))[0])
        if stems.setdefault(stem, p.files[0]) != p.files[0]:
            raise ValueError("problems: %s and %s are both named %s" % (stems[stem], p.files[0], stem))
        batches = -(-runs // batch)
        for planner in planners:
            for checker in checkers:
                for sampler in samplers:
                    for b in range(1, batches + 1):
                        count = min(batch, runs - (b - 1) * batch)
                        cell = Cell(p.files[0], stem, planner, checker, sampler, b, batches, count, 0)
                        cell.seed = cell_seed(seed, cell.name)
                        cells.append(cell)
    return cells


def _read_log(path):
    """The text of an OMPL .log (bytes that are not UTF-8 replaced)."""
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


def _planner_runs(text):
    """The run count of each planner of an OMPL .log's text, in order: per planner, its name, "<K> common
    properties" and K lines, "<P> properties for each run" and P lines, "<N> runs" and N rows of run data, then (an
    optimizing planner's) "<Q> progress properties for each run", Q lines, "<M> runs" and M rows of progress data,
    and "."; None when the text is not of that form."""
    lines = text.splitlines()
    count = lambda line, tail: int(line[:-len(tail)]) if re.fullmatch(r"\d+" + re.escape(tail), line) else None
    start = next((k for k, line in enumerate(lines) if count(line, " planners") is not None), None)
    if start is None:
        return None
    i, runs = start + 1, []
    try:
        for _ in range(count(lines[start], " planners")):
            i += 1  # the planner's name
            for tail in (" common properties", " properties for each run"):
                n = count(lines[i], tail)
                if n is None:
                    return None
                i += 1 + n
            n = count(lines[i], " runs")
            if n is None:
                return None
            runs.append(n)
            i += 1 + n
            progress = count(lines[i], " progress properties for each run")
            if progress is not None:
                i += 1 + progress
                m = count(lines[i], " runs")
                if m is None:
                    return None
                i += 1 + m
            if lines[i] != ".":
                return None
            i += 1
    except IndexError:
        return None
    return runs


def log_runs(path):
    """The number of runs an OMPL .log holds (each of its planners' run data; the progress data of an optimizing
    planner, a second "<N> runs" block, is not counted again), or None when it has none, its planners hold
    different counts, or it is not of OMPL's form."""
    runs = _planner_runs(_read_log(path))
    return runs[0] if runs and len(set(runs)) == 1 else None


def _log_settings(path):
    """(runs, seed, seconds per run, MB per run) of an OMPL .log, None for what it lacks."""
    text = _read_log(path)
    found = lambda pattern: re.findall(pattern, text, re.MULTILINE)
    runs, seed = _planner_runs(text), found(r"^(\d+) is the random seed$")
    time, memory = found(r"^(\S+) seconds per run$"), found(r"^(\S+) MB per run$")
    return (runs[0] if runs and len(set(runs)) == 1 else None, int(seed[0]) if seed else None,
            float(time[0]) if time else None, float(memory[0]) if memory else None)


def _check_present(cells, out, time, memory):
    """The logs already in out must be those of these cells (runs, seed, time and memory); ValueError naming the
    first that is not (a campaign of other settings: choose another out)."""
    for cell in cells:
        path = os.path.join(out, cell.name + ".log")
        if os.path.isfile(path):
            got = _log_settings(path)
            want = (cell.runs, cell.seed, time, memory)
            if got[0] != want[0] or got[1] != want[1] or got[2] is None or not math.isclose(got[2], time) or \
                    got[3] is None or not math.isclose(got[3], memory):
                raise ValueError("%s: a log of other settings (runs, seed, seconds, MB: %s; this campaign's cell: %s);"
                                 " choose another out" % (path, got, want))


def _arguments(executable, cell, time, memory, params, out):
    args = [executable, "--cfg", cell.cfg, "--planner", cell.planner, "--checker", cell.checker, "--runs",
            str(cell.runs), "--time", repr(float(time)), "--memory", repr(float(memory)), "--seed", str(cell.seed),
            "--out", out]
    if cell.sampler:
        args += ["--sampler", cell.sampler]
    for param in params:
        args += ["--param", param]
    return args


def _die_with_parent():
    """In the child: be killed when the worker that started it dies (Linux), so a lost cell leaves no orphan."""
    try:
        import ctypes
        import signal
        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):
        pass


def _error_line(stderr):
    lines = [line[len("error: "):] for line in stderr.splitlines() if line.startswith("error: ")]
    return lines[-1] if lines else (stderr.strip().splitlines() or ["(no message)"])[-1]


def run_cell(cell, out, executable, time, memory, params):
    """Run one cell (what each task does): meshgap_benchmark into the cell's own folder, then its log moved to
    OUT/<cell>.log once it holds all the cell's runs. Returns "done", or "present" when the log was already there;
    RuntimeError (retried by Dask) when the run failed or its log misses runs."""
    final = os.path.join(out, cell.name + ".log")
    if os.path.isfile(final):
        return "present"
    where = "%s-%d" % (socket.gethostname(), os.getpid())
    folder = os.path.join(out, ".cells", "%s.%s" % (cell.name, where))
    if not os.path.isfile(executable):
        raise FileNotFoundError("%s: no such file on worker %s" % (executable, where))
    shutil.rmtree(folder, ignore_errors=True)
    for attempt in range(3):  # another cell may remove an empty OUT/.cells between the two mkdirs of makedirs
        try:
            os.makedirs(folder)
            break
        except FileNotFoundError:
            if attempt == 2:
                raise
    try:
        run = subprocess.run(_arguments(executable, cell, time, memory, params, folder), stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, preexec_fn=_die_with_parent)
        stderr = run.stderr.decode("utf-8", "backslashreplace")
        if run.returncode != 0:
            raise RuntimeError("%s: meshgap_benchmark failed on %s (exit %d): %s" % (
                cell.name, where, run.returncode, _error_line(stderr)))
        logs = glob.glob(os.path.join(folder, "*.log"))
        runs = log_runs(logs[0]) if len(logs) == 1 else None
        if runs != cell.runs:
            raise RuntimeError("%s: meshgap_benchmark wrote %d logs, %s runs (expected one log of %d runs): %s" % (
                cell.name, len(logs), runs, cell.runs, stderr.strip().splitlines()[-1:]))
        os.replace(logs[0], final)  # the folder is in OUT: the same file system, an atomic rename
    finally:
        shutil.rmtree(folder, ignore_errors=True)
        with contextlib.suppress(OSError):
            os.rmdir(os.path.dirname(folder))  # OUT/.cells once no cell runs: none left behind by a failed campaign
    return "done"


def _check(cells, executable, params):
    """Run meshgap_benchmark once per problem on a slice of the grid it holds no run of (--shard n/n past the
    grid's end): it reads the cfg, checks the planner, checker and sampler names and --param, allocates the
    planners, and runs nothing. ValueError with its message on the first problem it refuses."""
    by_problem = {}
    for cell in cells:
        by_problem.setdefault(cell.cfg, cell)
    planners = ",".join(dict.fromkeys(c.planner for c in cells))
    checkers = ",".join(dict.fromkeys(c.checker for c in cells))
    samplers = ",".join(dict.fromkeys(c.sampler for c in cells if c.sampler))
    slots = len(planners.split(",")) * len(checkers.split(",")) * (len(samplers.split(",")) if samplers else 1)
    with tempfile.TemporaryDirectory(prefix="meshgap-campaign-check-") as scratch:
        for cfg in by_problem:
            args = [executable, "--cfg", cfg, "--planner", planners, "--checker", checkers, "--runs", "1",
                    "--shard", "%d/%d" % (slots + 1, slots + 1), "--out", scratch]
            args += ["--sampler", samplers] if samplers else []
            for param in params:
                args += ["--param", param]
            run = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
            if run.returncode != 0:
                raise ValueError("%s: %s" % (cfg, _error_line(run.stderr.decode("utf-8", "backslashreplace"))))


def _statistics():
    found = shutil.which("ompl_benchmark_statistics") or shutil.which("ompl_benchmark_statistics.py")
    if not found:
        raise FileNotFoundError("ompl_benchmark_statistics not found on PATH (Debian: apt-get install ompl-demos)")
    return found


def _merge_experiments(path):
    """One experiment per problem: ompl_benchmark_statistics makes one per .log; the runs of the logs of the same
    experiment name are moved to the first, whose total time becomes their sum and run count the most runs of one
    planner configuration (its seed stays the first log's; each cell's seed is in its log)."""
    import sqlite3
    with sqlite3.connect(path) as db:
        db.executescript("""
            UPDATE runs SET experimentid = (SELECT MIN(b.id) FROM experiments a JOIN experiments b ON a.name = b.name
                                            WHERE a.id = runs.experimentid);
            UPDATE experiments SET totaltime = (SELECT SUM(b.totaltime) FROM experiments b
                                                WHERE b.name = experiments.name)
                WHERE id IN (SELECT experimentid FROM runs);
            DELETE FROM experiments WHERE id NOT IN (SELECT experimentid FROM runs);
            UPDATE experiments SET runcount = (SELECT MAX(n) FROM (SELECT COUNT(*) AS n FROM runs
                                               WHERE runs.experimentid = experiments.id GROUP BY plannerid));
            """)


def load_database(logs, database, merge=True):
    """Load OMPL .log files into one SQLite database with ompl_benchmark_statistics (Planner Arena reads it),
    written beside database under a temporary name and renamed into place: never half made. merge: one experiment
    per problem (_merge_experiments()), so Planner Arena shows a problem's planners, checkers and batches together."""
    database = os.path.abspath(os.fspath(database))
    temporary = "%s.tmp-%s-%d" % (database, socket.gethostname(), os.getpid())
    if os.path.exists(temporary):
        os.remove(temporary)
    run = subprocess.run([_statistics(), *logs, "-d", temporary], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE)
    if run.returncode != 0 or not os.path.isfile(temporary):
        if os.path.exists(temporary):
            os.remove(temporary)
        raise RuntimeError("%s: ompl_benchmark_statistics failed (exit %d): %s" % (
            database, run.returncode, run.stderr.decode("utf-8", "backslashreplace").strip()[-2000:]))
    try:
        if merge:
            _merge_experiments(temporary)
    except Exception:
        os.remove(temporary)
        raise
    os.replace(temporary, database)
    return database


def run(problems, planners, checkers=("certified",), samplers=(), runs=10, batch=None, time=10.0, memory=4096.0,
        seed=1, out="campaign", database="results.db", params=(), retries=3, client=None, timeout=10,
        executable=None, progress=True, check=True):
    """Run a campaign on the current distributed Client (or client: a Client, or a scheduler's address
    "tcp://HOST:8786", ConnectionError when it is not reached within timeout seconds): one task per cell not done yet (see the
    module's help), retried up to retries times when it fails, with Dask's progress bar; then every cell's log into
    OUT/database. Bad input (a problem file missing, an unknown planner, checker or sampler, a bad --param: checked
    first by meshgap_benchmark on the client when check is true; meshgap_benchmark or ompl_benchmark_statistics
    missing; no client; a log in out of other settings: runs, seed, time or memory) raises before anything is
    written. Returns {"cells", "ran", "present", "logs",
    "database"}: ran counts the cells this call ran."""
    cells = grid(problems, planners, checkers, samplers, runs, batch, seed)
    params = [str(p) for p in ([params] if isinstance(params, str) else params)]
    if not (0 < float(time) < math.inf and 0 < float(memory) < math.inf):
        raise ValueError("time and memory: expected positive finite numbers, got %s, %s" % (_shown(time),
                                                                                          _shown(memory)))
    executable = find_executable(executable)
    _statistics()
    client = _dask().connect(client, timeout) if isinstance(client, str) else _dask()._current_client(client)
    if client is None:
        raise ValueError("no Dask client: connect one first (meshgap.distributed.connect()) or give client=")
    out = os.path.abspath(os.fspath(out))
    if check:
        _check(cells, executable, params)
    _check_present(cells, out, float(time), float(memory))
    created = not os.path.exists(out)
    os.makedirs(out, exist_ok=True)
    todo = [c for c in cells if not os.path.isfile(os.path.join(out, c.name + ".log"))]
    futures = []
    try:
        if todo:
            futures = client.map(run_cell, todo, out=out, executable=executable, time=float(time),
                                 memory=float(memory), params=params, retries=retries, pure=False,
                                 key=["meshgap-cell-%s-%s" % (c.name, os.urandom(4).hex()) for c in todo])
            if progress:
                from distributed import progress as show
                show(futures)
            client.gather(futures)
    except BaseException:
        client.cancel(futures)  # the cells not run yet; a cell running finishes (its log is complete or absent)
        raise
    finally:
        # The folders of runs killed with their worker, or of a campaign that failed; an out this call made and
        # left empty goes too.
        shutil.rmtree(os.path.join(out, ".cells"), ignore_errors=True)
        if created:
            with contextlib.suppress(OSError):
                os.rmdir(out)
    logs = [os.path.join(out, c.name + ".log") for c in cells]
    missing = [path for path in logs if not os.path.isfile(path)]
    if missing:
        raise RuntimeError("%d cells have no log after the run: %s" % (len(missing), ", ".join(missing[:5])))
    db = load_database(logs, os.path.join(out, database))
    return {"cells": len(cells), "ran": len(todo), "present": len(cells) - len(todo), "logs": logs, "database": db}


def read_file(path):
    """The keywords of run() from a campaign file (see the module's help). FileNotFoundError, or ValueError naming
    the file and the key."""
    path = os.path.abspath(os.fspath(path))
    if not os.path.isfile(path):
        raise FileNotFoundError("%s: no such file" % _cut(path, 1000))
    parser = configparser.ConfigParser(inline_comment_prefixes=("#", ";"), interpolation=None)
    try:
        parser.read(path, encoding="utf-8")
    except UnicodeDecodeError as error:
        raise ValueError("%s: not a campaign file: not UTF-8 text (byte 0x%02x at offset %d)" % (
            path, error.object[error.start], error.start)) from None
    except (configparser.ParsingError, configparser.MissingSectionHeaderError) as error:
        line, text = (error.lineno, error.line) if isinstance(error, configparser.MissingSectionHeaderError) else \
            error.errors[0]
        raise ValueError("%s:%d: not a campaign file: %s" % (path, line, _shown(text.strip() if isinstance(
            text, str) else text))) from None
    except configparser.Error as error:
        raise ValueError("%s: not a campaign file: %s" % (path, _cut(str(error), 200))) from None
    if not parser.has_section("campaign"):
        raise ValueError("%s: no [campaign] section" % path)
    section = parser["campaign"]
    unknown = [k for k in section if k not in CAMPAIGN_KEYS]
    if unknown:
        raise ValueError("%s: unknown key %s in [campaign]; valid keys: %s" % (path, _shown(unknown[0]),
                                                                              ", ".join(CAMPAIGN_KEYS)))
    for key in ("problems", "planners"):
        if not section.get(key, "").strip():
            raise ValueError("%s: missing required key '%s' in [campaign]" % (path, key))
    folder = os.path.dirname(path)
    kwargs = {"problems": [os.path.join(folder, p) for p in _names(section["problems"], "problems")],
              "planners": _names(section["planners"], "planners")}
    for key in ("checkers", "samplers"):
        if key in section:
            kwargs[key] = _names(section[key], key)
    for key, kind in (("runs", int), ("batch", int), ("seed", int), ("retries", int), ("time", float),
                      ("memory", float)):
        if key in section:
            try:
                kwargs[key] = kind(section[key])
            except ValueError:
                raise ValueError("%s: %s = %s is not a number" % (path, key, _shown(section[key]))) from None
    if "out" in section:
        kwargs["out"] = os.path.join(folder, section["out"])
    else:
        kwargs["out"] = os.path.join(folder, "campaign")
    if "database" in section:
        kwargs["database"] = section["database"]
    if "param" in section:
        kwargs["params"] = [line.strip() for line in section["param"].splitlines() if line.strip()]
    return kwargs


def run_file(path, **kwargs):
    """run() with the keywords of a campaign file, and kwargs over them (e.g. client=, executable=)."""
    settings = read_file(path)
    settings.update(kwargs)
    return run(**settings)


def main(argv=None):
    import argparse
    parser = argparse.ArgumentParser(prog="python3 -m meshgap.campaign", description="Run a benchmark campaign "
                                     "file on Dask (a local cluster, or --scheduler).")
    parser.add_argument("campaign", help="the campaign file (INI, section [campaign])")
    parser.add_argument("--scheduler", help="tcp://HOST:8786 (default: a local cluster of worker processes)")
    parser.add_argument("--workers", type=int, help="worker processes of the local cluster (default: Dask's)")
    parser.add_argument("--executable", help="meshgap_benchmark (default: $MESHGAP_BENCHMARK, beside the package, "
                        "PATH)")
    args = parser.parse_args(argv)
    try:
        settings = read_file(args.campaign)
        local = {} if args.workers is None else {"n_workers": args.workers, "threads_per_worker": 1}
        with _dask().connect(args.scheduler, **local) as client:
            summary = run(client=client, executable=args.executable, **settings)
    except (OSError, ValueError, RuntimeError) as error:
        print("error: %s" % error, file=sys.stderr)
        return 1
    print("%d cells (%d run now, %d already done); database %s" % (summary["cells"], summary["ran"],
                                                                   summary["present"], summary["database"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
