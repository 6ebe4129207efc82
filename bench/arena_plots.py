#!/usr/bin/env python3
"""The plots Planner Arena draws, from the SQLite database OMPL's ompl_benchmark_statistics makes of meshgap_benchmark
.log files, as one PNG per experiment (problem): the share of runs solved exactly and the time per planner, and box
plots of the path's length and of its minimum clearance by FCL (meshgap_benchmark's "fcl path min clearance") where
the runs have them.

    ompl_benchmark_statistics -d runs.db DIR/*/*.log
    /usr/bin/python3 bench/arena_plots.py runs.db OUT_DIR [--prefix NAME]

A planner is a plannerConfigs name (e.g. "geometric_RRTstar[meshgap-certified-cmv]"); the same name in several .log
files of one experiment (e.g. one objective per folder) is one box. Writes OUT_DIR/PREFIX<experiment>.png (small:
80 dpi). Exits 1 with one message on a missing or malformed database, or one without runs.
"""
import argparse
import os
import sqlite3
import sys

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402


def fail(message):
    print('error: ' + message, file=sys.stderr)
    sys.exit(1)


def short(name):
    """'geometric_RRTstar[meshgap-certified-cmv]' -> 'RRTstar[meshgap-certified-cmv]'."""
    return name[len('geometric_'):] if name.startswith('geometric_') else name


def columns(cur):
    cur.execute('PRAGMA table_info(runs)')
    return {row[1] for row in cur.fetchall()}


def experiment_runs(cur, experiment_id, have):
    """{planner: [run dict]} of one experiment, planners in the order they first appear."""
    wanted = [c for c in ('time', 'solved', 'approximate_solution', 'best_cost', 'solution_length',
                          'fcl_path_min_clearance', 'fcl_path_collision_free') if c in have]
    cur.execute('SELECT plannerConfigs.name, {} FROM runs JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id '
                'WHERE runs.experimentid = ? ORDER BY runs.id'.format(', '.join('runs.' + c for c in wanted)),
                (experiment_id,))
    planners = {}
    for row in cur.fetchall():
        planners.setdefault(short(row[0]), []).append(dict(zip(wanted, row[1:])))
    return planners


def exact(run):
    return run.get('solved') == 1 and run.get('approximate_solution') != 1


def box(ax, labels, values, ylabel):
    data = [v if v else [float('nan')] for v in values]
    ax.boxplot(data, sym='k+', whis=1.5)
    ax.set_xticks(range(1, len(labels) + 1))
    ax.set_xticklabels(labels, rotation=25, ha='right', fontsize=7)
    ax.set_ylabel(ylabel)
    ax.yaxis.grid(True, color='lightgrey')
    top = ax.get_ylim()[1]
    for i, v in enumerate(values):  # Planner Arena's count of runs without a value, above each box
        ax.text(i + 1, top, 'n={}'.format(len(v)), ha='center', va='bottom', fontsize=7)


def common_part(labels):
    """The labels' common beginning up to its last '[' or ',' (e.g. 'BKPIECE1[meshgap-certified,' when only the
    sampler differs), and the labels without it (and without the ']' it opened); ('', labels) if none."""
    if len(labels) < 2:
        return '', labels
    prefix = os.path.commonprefix(labels)
    cut = max(prefix.rfind('['), prefix.rfind(','))
    if cut < 0:
        return '', labels
    prefix = prefix[:cut + 1]
    opened = '[' in prefix
    return prefix, [l[len(prefix):-1] if opened and l.endswith(']') else l[len(prefix):] for l in labels]


def plot_experiment(name, planners, path):
    runs = [planners[p] for p in planners]
    common, labels = common_part(list(planners))
    if common:
        name = '{}: {}...{}'.format(name, common, ']' if '[' in common else '')
    panels = [('solved exactly (%)', None), ('time (s)', 'time')]
    # Path length, not OMPL's best cost: the planners of one experiment optimise different objectives (RRT*'s
    # max-min clearance cost and a length are not one axis); length is the cost every run shares.
    if any(r.get('solution_length') is not None for rs in runs for r in rs):
        panels.append(('path length (exact runs)', 'solution_length'))
    if any(r.get('fcl_path_min_clearance') is not None for rs in runs for r in rs):
        panels.append(('min clearance by FCL (exact runs)', 'fcl_path_min_clearance'))
    fig, axes = plt.subplots(1, len(panels), figsize=(3.2 * len(panels) + 0.5, 4.2))
    for ax, (ylabel, key) in zip(axes, panels):
        if key is None:
            share = [100.0 * sum(exact(r) for r in rs) / len(rs) for rs in runs]
            ax.bar(range(1, len(labels) + 1), share, 0.5)
            ax.set_ylim(0, 105)
            ax.set_xticks(range(1, len(labels) + 1))
            ax.set_xticklabels(labels, rotation=25, ha='right', fontsize=7)
            ax.set_ylabel(ylabel)
            ax.yaxis.grid(True, color='lightgrey')
        elif key == 'time':
            box(ax, labels, [[r['time'] for r in rs if r.get('time') is not None] for rs in runs], ylabel)
        else:
            box(ax, labels, [[r[key] for r in rs if exact(r) and r.get(key) is not None] for rs in runs], ylabel)
    fig.suptitle(name, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('database', help='SQLite database written by ompl_benchmark_statistics')
    parser.add_argument('out_dir', help='where the PNG files go')
    parser.add_argument('--prefix', default='', help='prefix of the PNG file names')
    args = parser.parse_args()
    if not os.path.isfile(args.database):
        fail('{}: no such database'.format(args.database))
    try:
        conn = sqlite3.connect('file:{}?mode=ro'.format(args.database), uri=True)
        cur = conn.cursor()
        have = columns(cur)
        if not have:
            fail('{}: not a benchmark database (no runs table)'.format(args.database))
        cur.execute('SELECT id, name FROM experiments ORDER BY id')
        experiments = cur.fetchall()
    except sqlite3.DatabaseError as e:
        fail('{}: not a benchmark database ({})'.format(args.database, e))
    # One figure per experiment name (several .log files of one problem are one experiment in the plots).
    merged = {}
    for experiment_id, name in experiments:
        for planner, rs in experiment_runs(cur, experiment_id, have).items():
            merged.setdefault(name, {}).setdefault(planner, []).extend(rs)
    if not any(merged.values()):
        fail('{}: no runs'.format(args.database))
    os.makedirs(args.out_dir, exist_ok=True)
    for name, planners in merged.items():
        path = os.path.join(args.out_dir, '{}{}.png'.format(args.prefix, name.replace('/', '_').replace(' ', '_')))
        plot_experiment(name, planners, path)
        print(path)


if __name__ == '__main__':
    main()
