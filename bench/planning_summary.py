#!/usr/bin/env python3
"""Summarise meshgap_benchmark .log files (OMPL's format) as a Markdown table, one row per problem and planner entry.

    python3 bench/planning_summary.py results/*.log
    python3 bench/planning_summary.py --control results/*.log

--control: for control problems (no planner reaches OMPL's default goal threshold, so runs end approximate), per
problem a table of runs, exact and approximate solutions, the goal distance of each run (OMPL's "solution
difference"), and the checker's validity calls and query time (medians).

Valid paths per minute = runs with an exact solution that FCL finds collision-free at every densely interpolated
state, divided by the planning time of all runs (OMPL's "time" property: solve() only, not simplification), in
minutes. "x FCL" is that throughput over the same planner's with the fcl checker on the same problem. Reads the .log
files directly (no database needed); several files of one planner entry (shards, slices) are added up.
"""
import re
import statistics
import sys
from collections import defaultdict


def read_log(path):
    """Yield (experiment, planner, [run dict]) for each planner block of an OMPL .log file."""
    with open(path) as f:
        lines = [line.rstrip('\n') for line in f]
    i = 0
    while not lines[i].startswith('Experiment '):  # after an optional "OMPL version ..." line
        i += 1
    experiment = lines[i][len('Experiment '):]
    while not lines[i].endswith(' planners'):
        i += 1
    count = int(lines[i].split()[0])
    i += 1
    for _ in range(count):
        planner = lines[i]
        i += 1
        i += int(lines[i].split()[0]) + 1  # common properties
        n = int(lines[i].split()[0])
        names = lines[i + 1:i + 1 + n]
        i += n + 1
        runs = []
        for _ in range(int(lines[i].split()[0])):
            i += 1
            values = lines[i].split('; ')[:-1]
            runs.append(dict(zip(names, values)))
        i += 1
        if lines[i] != '.':  # progress data
            i += int(lines[i].split()[0]) + 1
            i += int(lines[i].split()[0]) + 1
        i += 1
        yield experiment, planner, runs


def number(run, key):
    value = run.get(key, '')
    return float(value) if value not in ('', 'nan', 'inf') else None


def main(paths):
    runs = defaultdict(list)
    for path in paths:
        for experiment, planner, planner_runs in read_log(path):
            runs[(experiment, planner)].extend(planner_runs)
    rows = {}
    for (experiment, planner), rs in sorted(runs.items()):
        m = re.match(r'(?:geometric_)?(.*)\[(.*)\]$', planner)
        base, checker = (m.group(1), m.group(2)) if m else (planner, '')
        exact = [r for r in rs if r.get('solved BOOLEAN') == '1']
        valid = [r for r in exact if r.get('fcl path collision free BOOLEAN') == '1']
        minutes = sum(number(r, 'time REAL') or 0.0 for r in rs) / 60.0
        query = [number(r, 'checker mean query time REAL') for r in rs]
        query = [q for q in query if q is not None]
        clearance = [number(r, 'fcl path min clearance REAL') for r in valid]
        rows[(experiment, base, checker)] = dict(
            runs=len(rs), exact=len(exact), valid=len(valid),
            median=statistics.median([number(r, 'time REAL') for r in rs]),
            throughput=len(valid) / minutes if minutes > 0 else 0.0,
            query=statistics.median(query) * 1e6 if query else None,
            clearance=min(clearance) if clearance else None)
    print('| problem | planner | checker | runs | exact | FCL-valid | median time (s) | valid paths/min | x FCL '
          '| median mean query (us) | least FCL path clearance |')
    print('|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|')
    for (experiment, base, checker), row in rows.items():
        peer = rows.get((experiment, base, 'fcl'))
        ratio = row['throughput'] / peer['throughput'] if peer and peer['throughput'] > 0 else None
        print('| {} | {} | {} | {} | {} | {} | {:.3g} | {:.3g} | {} | {} | {} |'.format(
            experiment, base, checker, row['runs'], row['exact'], row['valid'], row['median'], row['throughput'],
            '{:.2f}'.format(ratio) if ratio is not None else '-',
            '{:.3g}'.format(row['query']) if row['query'] is not None else '-',
            '{:.4g}'.format(row['clearance']) if row['clearance'] is not None else '-'))


def control(paths):
    runs = defaultdict(list)
    for path in paths:
        for experiment, planner, planner_runs in read_log(path):
            runs[(experiment, planner)].extend(planner_runs)
    for problem in sorted({experiment for experiment, _ in runs}):
        rows = sorted((planner, rs) for (experiment, planner), rs in runs.items() if experiment == problem)
        print('%s (%d runs in all):' % (problem, sum(len(rs) for _, rs in rows)))
        print()
        print('| planner | runs | exact | approximate | goal distance per run | validity calls (median) | '
              'query time (median) |')
        print('|---|---|---|---|---|---|---|')
        for planner, rs in rows:
            exact = sum(1 for r in rs if r.get('solved BOOLEAN') == '1' and r.get('approximate solution BOOLEAN') != '1')
            approximate = sum(1 for r in rs if r.get('approximate solution BOOLEAN') == '1')
            goal = [number(r, 'solution difference REAL') for r in rs]
            calls = [number(r, 'checker validity calls INTEGER') for r in rs]
            query = [number(r, 'checker query time REAL') for r in rs]
            print('| {} | {} | {} | {} | {} | {} | {} |'.format(
                re.sub(r'^control_|\[.*\]$', '', planner), len(rs), exact, approximate,
                ', '.join('{:.3g}'.format(g) if g is not None else '-' for g in goal),
                '{:,.0f}'.format(statistics.median(c for c in calls if c is not None))
                if any(c is not None for c in calls) else '-',
                '{:.3g} s'.format(statistics.median(q for q in query if q is not None))
                if any(q is not None for q in query) else '-'))
        print()


if __name__ == '__main__':
    args = sys.argv[1:]
    if not args or args == ['--control']:
        sys.exit('usage: planning_summary.py [--control] FILE.log...')
    if args[0] == '--control':
        control(args[1:])
    else:
        main(args)
