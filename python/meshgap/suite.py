"""A MotionBenchMaker-format suite: every problem of every scenario (problems/<scenario>/sceneNNNN.yaml and
requestNNNN.yaml, MoveIt planning scenes and motion plan requests; a folder, or the shipped .tar.bz2 read as it is)
run by meshgap_benchmark for planners x checkers x runs, then one table per scenario and planner[checker]:

    runs, solved, median and p95 planning time (over the solved runs), valid paths per minute (runs solved whose path
    FCL finds free along the densely interpolated path, per minute of planning), paths colliding under that dense FCL
    check, and the least exact clearance meshgap finds along the dense paths (negative: a path in collision).

    python3 -m meshgap.suite ../shared/data/mbm/ur5/problems.tar.bz2 --urdf ../shared/data/mbm/ur5/ur5.urdf \\
        --srdf ../shared/data/mbm/ur5/ur5.srdf [--planners rrtconnect] [--checkers certified,discrete,fcl] \\
        [--scenarios box_ur5,cage_ur5] [--limit 10] [--time 10] [--runs 1] [--seed 1] [--out suite]

Writes OUT/<scenario>/<NNNN>/*.log (OMPL's .log files, one per planner[checker]), OUT/summary.md (the table, also
printed), OUT/comparison.md (when both ran: meshgap-certified over fcl per scenario, valid paths per minute and
median planning time, and the median scenario's; also printed) and OUT/results.db (every .log loaded by
ompl_benchmark_statistics, for Planner Arena; skipped with a note when ompl-demos is missing). --urdf and --srdf
default to the only *.urdf and *.srdf beside the archive or folder. meshgap_benchmark is found as meshgap.campaign
finds it ($MESHGAP_BENCHMARK, beside the package, or on PATH). Progress goes to stderr, one line a problem. Also
runs as a file, without the compiled package: python3 python/meshgap/suite.py ... --executable
build/planners/meshgap_benchmark. With --tables-of OUT[,OUT...] it plans nothing and prints the tables of the .log
files earlier runs left in those folders: an interrupted run's finished problems, or runs over different scenarios
(on two machines, or side by side) read as one.
"""
import argparse
import glob
import math
import os
import re
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time

_PROBLEM = re.compile(r"^scene(\d+)\.yaml$")


def read_log(path):
    """{planner name: [{property: value}, ...]} of the runs an OMPL .log holds (property names without their type)."""
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = f.read().split("\n")
    planners, i = {}, 0
    while i < len(lines):
        m = re.match(r"^(\d+) planners$", lines[i])
        i += 1
        if not m:
            continue
        for _ in range(int(m.group(1))):
            name = lines[i]
            i += 1
            common = int(lines[i].split()[0])
            i += common + 1
            count = int(lines[i].split()[0])
            names = [" ".join(l.split()[:-1]) for l in lines[i + 1:i + 1 + count]]
            i += count + 1
            runs = int(lines[i].split()[0])
            rows = []
            for line in lines[i + 1:i + 1 + runs]:
                values = [v.strip() for v in line.split(";")]
                rows.append(dict(zip(names, values)))
            i += runs + 1
            while i < len(lines) and lines[i] != ".":
                i += 1  # progress properties, if any
            planners.setdefault(re.sub(r"^geometric_", "", name), []).extend(rows)
        break
    return planners


def _number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return float("nan")


def percentile(values, q):
    """The q-th percentile (0..100) of values, linearly interpolated; nan for none."""
    if not values:
        return float("nan")
    v = sorted(values)
    k = (len(v) - 1) * q / 100.0
    lo, hi = int(math.floor(k)), int(math.ceil(k))
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def summarize(runs):
    """The row of one scenario and planner[checker] from its runs' properties."""
    solved = [r for r in runs if r.get("solved") == "1"]
    times = [_number(r.get("time")) for r in solved]
    free = [r for r in solved if r.get("fcl path collision free") == "1"]
    colliding = [r for r in solved if r.get("fcl path collision free") == "0"]
    clearance = [_number(r.get("path min clearance")) for r in solved if r.get("path min clearance")]
    seconds = sum(_number(r.get("time")) for r in runs)
    return {"runs": len(runs), "solved": len(solved), "median": percentile(times, 50), "p95": percentile(times, 95),
            "valid_per_minute": 60.0 * len(free) / seconds if seconds > 0 else float("nan"),
            "colliding": len(colliding), "checked": len(free) + len(colliding),
            "min_clearance": min(clearance) if clearance else float("nan")}


def problems_of(folder, scenarios=None, limit=None):
    """[(scenario, number, scene, request)] of a problems/ folder (or a folder holding problems/)."""
    root = os.path.join(folder, "problems") if os.path.isdir(os.path.join(folder, "problems")) else folder
    found = []
    for scenario in sorted(os.listdir(root)):
        path = os.path.join(root, scenario)
        if not os.path.isdir(path) or (scenarios and scenario not in scenarios):
            continue
        numbers = sorted(m.group(1) for m in map(_PROBLEM.match, os.listdir(path)) if m)
        for n in numbers[:limit] if limit else numbers:
            request = os.path.join(path, "request%s.yaml" % n)
            if not os.path.exists(request):
                raise ValueError("%s: scene%s.yaml has no request%s.yaml" % (path, n, n))
            found.append((scenario, n, os.path.join(path, "scene%s.yaml" % n), request))
    if scenarios:
        missing = set(scenarios) - {p[0] for p in found}
        if missing:
            raise ValueError("%s: no scenario %s" % (root, ", ".join(sorted(missing))))
    if not found:
        raise ValueError("%s: no problems (problems/<scenario>/sceneNNNN.yaml and requestNNNN.yaml)" % root)
    return found


def _beside(source, pattern, what):
    folder = os.path.dirname(os.path.abspath(source)) if os.path.isfile(source) else source
    found = sorted(glob.glob(os.path.join(folder, pattern)))
    if len(found) != 1:
        raise ValueError("%s: give --%s (found %d %s files beside it)" % (source, what, len(found), pattern))
    return found[0]


def run_problem(executable, args, scenario, number, scene, request, out):
    """meshgap_benchmark on one problem; its .log files in out/<scenario>/<number>."""
    folder = os.path.join(out, scenario, number)
    os.makedirs(folder, exist_ok=True)
    command = [executable, "--urdf", args.urdf, "--scene", scene, "--request", request, "--planner",
               ",".join(args.planners), "--checker", ",".join(args.checkers), "--runs", str(args.runs), "--time",
               str(args.time), "--seed", str(args.seed), "--out", folder]
    if args.srdf:
        command[3:3] = ["--srdf", args.srdf]
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if done.returncode != 0:
        errors = [l for l in done.stderr.splitlines() if l.startswith("error")]
        raise RuntimeError("%s: meshgap_benchmark failed: %s" % (request, errors[-1] if errors else done.stderr[-400:]))
    return folder


def table(rows):
    """The Markdown table of {(scenario, planner): row}."""
    out = ["| scenario | planner[checker] | runs | solved | median s | p95 s | valid paths / min | colliding (dense "
           "FCL) | min clearance |", "|---|---|---|---|---|---|---|---|---|"]
    for (scenario, planner), r in sorted(rows.items()):
        out.append("| %s | %s | %d | %d | %.3g | %.3g | %.1f | %d of %d | %.4g |" % (
            scenario, planner, r["runs"], r["solved"], r["median"], r["p95"], r["valid_per_minute"], r["colliding"],
            r["checked"], r["min_clearance"]))
    return "\n".join(out)


def comparison(rows, subject="meshgap-certified", peer="fcl"):
    """The Markdown table of subject / peer per scenario and planner, from the rows of table(): valid paths per minute
    and median planning time, each as the subject's over the peer's (inf where the peer has none), then the median
    scenario's of each. "" when no scenario has both checkers."""
    pairs = []
    for (scenario, planner), r in sorted(rows.items()):
        name, _, checker = planner.partition("[")
        other = rows.get((scenario, "%s[%s]" % (name, peer)))
        if checker.rstrip("]") != subject or other is None:
            continue
        rate = r["valid_per_minute"] / other["valid_per_minute"] if other["valid_per_minute"] > 0 else math.inf
        median = r["median"] / other["median"] if other["median"] > 0 else math.inf
        pairs.append((scenario, name, rate, median))
    if not pairs:
        return ""
    out = ["| scenario | planner | valid paths / min, %s / %s | median s, %s / %s |" % (subject, peer, subject, peer),
           "|---|---|---|---|"]
    out += ["| %s | %s | %.3g | %.3g |" % p for p in pairs]
    out.append("| median scenario | | %.3g | %.3g |" % (statistics.median(p[2] for p in pairs),
                                                     statistics.median(p[3] for p in pairs)))
    return "\n".join(out)


def logs_of(folders):
    """{(scenario, planner): [runs]} of the OMPL .log files a run wrote into each folder (FOLDER/<scenario>/<NNNN>/),
    folders read in turn (each its own scenarios, or more runs of the same ones)."""
    logs = {}
    for folder in folders:
        if not os.path.isdir(folder):
            raise ValueError("%s: no such folder" % folder)
        found = sorted(glob.glob(os.path.join(folder, "*", "*", "*.log")))
        if not found:
            raise ValueError("%s: no <scenario>/<NNNN>/*.log in it (not a suite's --out)" % folder)
        for log in found:
            scenario = os.path.basename(os.path.dirname(os.path.dirname(log)))
            for planner, runs in read_log(log).items():
                logs.setdefault((scenario, planner), []).extend(runs)
    return logs


def print_tables(logs, out=None):
    """The table and the comparison of logs (logs_of()'s form), printed; into out/summary.md and
    out/comparison.md when out is given."""
    rows = {key: summarize(runs) for key, runs in logs.items()}
    text, versus = table(rows), comparison(rows)
    if out:
        with open(os.path.join(out, "summary.md"), "w", encoding="utf-8") as f:
            f.write(text + "\n")
        if versus:
            with open(os.path.join(out, "comparison.md"), "w", encoding="utf-8") as f:
                f.write(versus + "\n")
    print(text)
    if versus:
        print("\n" + versus)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m meshgap.suite", description=__doc__.split("\n\n")[0])
    parser.add_argument("problems", nargs="?", help="a MotionBenchMaker problems folder or its .tar.bz2")
    parser.add_argument("--urdf")
    parser.add_argument("--srdf")
    parser.add_argument("--planners", default="rrtconnect", help="comma-separated (default rrtconnect)")
    parser.add_argument("--checkers", default="certified,discrete,fcl", help="comma-separated")
    parser.add_argument("--scenarios", help="comma-separated scenario folders (default: all)")
    parser.add_argument("--limit", type=int, help="problems per scenario (default: all)")
    parser.add_argument("--time", type=float, default=10.0, help="seconds per run (default 10)")
    parser.add_argument("--runs", type=int, default=1, help="runs per problem, planner and checker (default 1)")
    parser.add_argument("--seed", type=int, default=1, help="OMPL's seed (default 1)")
    parser.add_argument("--out", default="suite", help="folder of the .log files and summary.md (default suite)")
    parser.add_argument("--executable", help="meshgap_benchmark (default: as meshgap.campaign finds it)")
    parser.add_argument("--database", default="results.db",
                        help="the SQLite database of every .log, in --out (default results.db; needs ompl-demos' "
                             "ompl_benchmark_statistics, else skipped with a note; '' for none)")
    parser.add_argument("--tables-of", metavar="FOLDER[,FOLDER...]",
                        help="no planning: the tables of the .log files earlier runs wrote into these --out folders "
                             "(an interrupted run's, or runs over different scenarios), printed")
    args = parser.parse_args(argv)
    if args.tables_of is not None:
        try:
            print_tables(logs_of([f for f in args.tables_of.split(",") if f] or [""]))
            return 0
        except (ValueError, OSError) as e:
            print("error: %s" % e, file=sys.stderr)
            return 1
    if args.problems is None:
        parser.error("the problems folder or archive is needed (or --tables-of)")
    try:
        from .campaign import find_executable, load_database
    except ImportError:  # run as a file (python3 python/meshgap/suite.py), without the package
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        from campaign import find_executable, load_database
    try:
        args.planners = [p for p in args.planners.split(",") if p]
        args.checkers = [c for c in args.checkers.split(",") if c]
        if args.limit is not None and args.limit < 1:
            raise ValueError("--limit must be at least 1")
        if not os.path.exists(args.problems):
            raise ValueError("%s: no such folder or archive" % args.problems)
        args.urdf = os.path.abspath(args.urdf or _beside(args.problems, "*.urdf", "urdf"))
        args.srdf = os.path.abspath(args.srdf) if args.srdf else _beside(args.problems, "*.srdf", "srdf")
        executable = find_executable(args.executable)
        scenarios = set(args.scenarios.split(",")) if args.scenarios else None
        with tempfile.TemporaryDirectory(prefix="meshgap_suite_") as tmp:
            folder = args.problems
            if os.path.isfile(folder):
                with tarfile.open(folder) as archive:
                    archive.extractall(tmp)
                folder = tmp
            problems = problems_of(folder, scenarios, args.limit)
            start, rows, logs = time.time(), {}, {}
            for k, (scenario, number, scene, request) in enumerate(problems):
                print("[%7.1f s] %d of %d: %s %s" % (time.time() - start, k + 1, len(problems), scenario, number),
                      file=sys.stderr, flush=True)
                out = run_problem(executable, args, scenario, number, scene, request, args.out)
                for log in sorted(glob.glob(os.path.join(out, "*.log"))):
                    for planner, runs in read_log(log).items():
                        logs.setdefault((scenario, planner), []).extend(runs)
        print_tables(logs, args.out)
        if args.database:
            try:
                # One experiment per .log: problems of different scenarios share their file names.
                load_database(sorted(glob.glob(os.path.join(args.out, "*", "*", "*.log"))),
                              os.path.join(args.out, args.database), merge=False)
            except FileNotFoundError as e:
                print("note: no database: %s" % e, file=sys.stderr)
        return 0
    except (ValueError, RuntimeError, OSError, tarfile.TarError) as e:
        print("error: %s" % e, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
