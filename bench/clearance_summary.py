#!/usr/bin/env python3
"""The planning tables of bench/planning.md from meshgap_benchmark .log files (bench/clearance_table.sh writes them).

    python3 bench/clearance_summary.py solve DIR/solve/*.log
    python3 bench/clearance_summary.py clearance DIR/clearance/*/*.log

solve: one row per problem and checker: runs, exact solutions, exact solutions whose every densely interpolated
state FCL finds collision-free, median and largest planning time (OMPL's "time": solve() only).

clearance: one row per map, planner, objective, path kind and checker: runs, exact solutions, the median over the
exact solutions of the path's minimum clearance by FCL (0 for a path FCL finds colliding) and of its length. The
objective and the path kind come from the .log's folder, named OBJECTIVE.raw (the planner's own path) or
OBJECTIVE.simplified (OMPL's simplifier run on it). Then, per map, whether RRT*'s median beats every RRTConnect row's.
"""
import os
import statistics
import sys
from collections import defaultdict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from planning_summary import number, read_log  # noqa: E402


def split(planner):
    """'RRTConnect[meshgap-certified]' -> ('RRTConnect', 'meshgap-certified')."""
    base, _, checker = planner.partition('[')
    return base[len('geometric_'):] if base.startswith('geometric_') else base, checker.rstrip(']')


def collect(paths, key):
    runs = defaultdict(list)
    for path in paths:
        for experiment, planner, planner_runs in read_log(path):
            runs[key(path, experiment, planner)].extend(planner_runs)
    return runs


def fmt(x, digits=4):
    return '-' if x is None else '{:.{}g}'.format(x, digits)


def median(values):
    return statistics.median(values) if values else None


def solve(paths):
    runs = collect(paths, lambda path, experiment, planner: (experiment,) + split(planner))
    print('| problem | planner | checker | runs | exact | FCL-free (of exact) | all FCL-free | median time (s) '
          '| largest time (s) |')
    print('|---|---|---|---:|---:|---:|---|---:|---:|')
    for (experiment, planner, checker), rs in sorted(runs.items(), key=lambda kv: kv[0][0].lower()):
        exact = [r for r in rs if r.get('solved BOOLEAN') == '1' and r.get('approximate solution BOOLEAN') != '1']
        free = [r for r in exact if r.get('fcl path collision free BOOLEAN') == '1']
        times = [number(r, 'time REAL') for r in rs]
        times = [t for t in times if t is not None]
        print('| {} | {} | {} | {} | {} | {} | {} | {} | {} |'.format(
            experiment, planner, checker, len(rs), len(exact), len(free),
            'yes' if exact and len(free) == len(exact) == len(rs) else 'no', fmt(median(times), 3),
            fmt(max(times) if times else None, 3)))


def clearance(paths):
    def key(path, experiment, planner):
        objective, _, kind = os.path.basename(os.path.dirname(os.path.abspath(path))).partition('.')
        return (experiment,) + split(planner) + (objective, kind)

    runs = collect(paths, key)
    rows = []
    for (experiment, planner, checker, objective, kind), rs in runs.items():
        exact = [r for r in rs if r.get('solved BOOLEAN') == '1' and r.get('approximate solution BOOLEAN') != '1']
        least = [number(r, 'fcl path min clearance REAL') if r.get('fcl path collision free BOOLEAN') == '1' else 0.0
                 for r in exact]
        length_key = 'simplified solution length REAL' if kind == 'simplified' else 'solution length REAL'
        lengths = [number(r, length_key) for r in exact]
        rows.append(dict(map=experiment, planner=planner, checker=checker, objective=objective, kind=kind,
                         runs=len(rs), exact=len(exact), clearance=median([x for x in least if x is not None]),
                         length=median([x for x in lengths if x is not None])))
    rows.sort(key=lambda r: (r['map'], r['planner'] != 'RRTstar', r['kind'], r['checker']))
    print('| map | planner | objective | path | checker | runs | exact | median path min clearance (FCL) '
          '| median length |')
    print('|---|---|---|---|---|---:|---:|---:|---:|')
    for r in rows:
        print('| {} | {} | {} | {} | {} | {} | {} | {} | {} |'.format(
            r['map'], r['planner'], r['objective'], r['kind'], r['checker'], r['runs'], r['exact'],
            fmt(r['clearance']), fmt(r['length'])))
    print()
    for experiment in sorted({r['map'] for r in rows}):
        star = [r for r in rows if r['map'] == experiment and r['planner'] == 'RRTstar']
        connect = [r for r in rows if r['map'] == experiment and r['planner'] == 'RRTConnect']
        for s in star:
            if s['clearance'] is None or s['exact'] * 2 <= s['runs']:
                verdict = 'no: RRT* has an exact path in {} of {} runs'.format(s['exact'], s['runs'])
            else:
                beaten = [c for c in connect if c['clearance'] is not None and s['clearance'] > c['clearance']]
                verdict = '{} ({} of {} RRTConnect rows below {})'.format(
                    'yes' if connect and len(beaten) == len(connect) else 'no', len(beaten), len(connect),
                    fmt(s['clearance']))
            print('* {}: RRT* ({}, {}) median min clearance above RRTConnect\'s: {}'.format(
                experiment, s['objective'], s['checker'], verdict))


if __name__ == '__main__':
    if len(sys.argv) < 3 or sys.argv[1] not in ('solve', 'clearance'):
        sys.exit('usage: clearance_summary.py solve|clearance FILE.log...')
    (solve if sys.argv[1] == 'solve' else clearance)(sys.argv[2:])
