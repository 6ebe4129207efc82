#!/usr/bin/python3
"""Pictures of meshgap's benchmarks, as PNG files in bench/figures/ (Debian's python3-matplotlib).

  /usr/bin/python3 bench/plot_benchmarks.py --scaling scaling.csv \
      --clearance NAME=clearance.csv [--clearance NAME=other.csv ...] [--db benchmark.db] [--out bench/figures]

* --scaling: the CSV of `meshgap_bench_scaling --csv FILE`: query time against mesh size, log-log, meshgap
  (cold and warm certified, fast, collision-only) and FCL (distance, collision): scaling_query_time.png; and the
  preprocessing time and heap memory per part: scaling_preprocessing.png.
* --clearance: the CSV of `meshgap_plan --clearance-csv FILE` (index,arc_length,fraction,<state>,clearance,
  in_collision): the exact clearance along the planned path, one line per file, colliding states marked:
  clearance_along_path.png.
* --db: an OMPL benchmark database (`ompl_benchmark_statistics`' SQLite schema: tables plannerConfigs, runs,
  progress with columns time and best_cost): each planner's best cost against time, the median over runs (a run
  without a solution yet counts as infinite) with the runs themselves faint, one panel per experiment name: planner_cost_vs_time.png. Skipped with a message without --db.
"""

import argparse
import csv
import math
import os
import sqlite3
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DPI = 100


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def save(fig, out, name, layout=True):
    path = os.path.join(out, name)
    if layout:
        fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    print(f"wrote {path} ({os.path.getsize(path) // 1024} KiB)")


def plot_scaling(path, out):
    rows = read_csv(path)
    tri = [int(r["triangles"]) for r in rows]
    fig, ax = plt.subplots(figsize=(7, 4.6))
    series = [
        ("cold_us", "meshgap certified, cold", "tab:blue", "-", "o"),
        ("warm_us", "meshgap certified, warm", "tab:blue", "--", "s"),
        ("fast_us", "meshgap fast (node level)", "tab:cyan", ":", "^"),
        ("collision_us", "meshgap collision-only", "tab:green", "-", "D"),
        ("fcl_distance_us", "FCL distance", "tab:red", "-", "o"),
        ("fcl_collision_us", "FCL collision", "tab:orange", "-", "D"),
    ]
    for key, label, color, style, marker in series:
        ax.plot(tri, [float(r[key]) for r in rows], style, color=color, marker=marker, label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("triangles per body (both bodies the same refined mesh)")
    ax.set_ylabel("time per query, median (µs)")
    ax.set_title("Query time against mesh size")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, out, "scaling_query_time.png")

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.6))
    parts = [("graph", "surface graph"), ("distances", "mesh distances"), ("bvh", "triangle BVH"),
             ("body", "Body::build (no distances)"), ("fcl_build", "FCL BVH")]
    for key, label in parts:
        ax1.plot(tri, [max(float(r[key + "_s"]), 1e-6) for r in rows], marker="o", label=label)
        mem_key = key + "_bytes" if key != "fcl_build" else "fcl_bytes"
        ax2.plot(tri, [max(float(r[mem_key]), 1.0) / 2**20 for r in rows], marker="o", label=label)
    for ax, what in ((ax1, "build time (s)"), (ax2, "heap retained (MiB)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("triangles")
        ax.set_ylabel(what)
        ax.grid(True, which="both", alpha=0.3)
    for r in rows:  # where the mesh distances switch from the dense table to on-demand searches
        ax2.annotate(r["distances"].replace("_", " "), (int(r["triangles"]), float(r["distances_bytes"]) / 2**20),
                     textcoords="offset points", xytext=(4, -10), fontsize=7, color="tab:orange")
    ax1.set_title("Preprocessing time")
    ax2.set_title("Preprocessing memory")
    handles, labels = ax1.get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(parts), fontsize=8)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    save(fig, out, "scaling_preprocessing.png", layout=False)


def plot_clearance(specs, out):
    fig, axes = plt.subplots(len(specs), 1, figsize=(7, 1.2 + 2.0 * len(specs)), sharex=True, squeeze=False)
    for ax, spec in zip(axes[:, 0], specs):
        name, _, path = spec.rpartition("=")
        name = name or os.path.splitext(os.path.basename(path))[0]
        rows = read_csv(path)
        s = [float(r["fraction"]) for r in rows]
        c = [float(r["clearance"]) for r in rows]
        ax.plot(s, c, color="tab:blue", linewidth=1.2)
        hits = [(x, y) for x, y, r in zip(s, c, rows) if r["in_collision"] == "1"]
        if hits:
            ax.plot([h[0] for h in hits], [h[1] for h in hits], "x", color="red",
                    label=f"{len(hits)} colliding states")
            ax.legend(fontsize=8)
        i = min(range(len(c)), key=c.__getitem__)
        ax.plot([s[i]], [c[i]], "o", color="tab:red", markersize=4)
        ax.annotate(f"min {c[i]:.3g}", (s[i], c[i]), textcoords="offset points", xytext=(6, 6), fontsize=8)
        ax.axhline(0.0, color="black", linewidth=0.6)
        ax.set_ylabel("clearance")
        ax.set_title(f"{name} ({len(rows)} states)", fontsize=9)
        ax.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel("fraction of the path's length")
    fig.suptitle("Exact clearance along planned paths (meshgap_plan --clearance-csv)", fontsize=10)
    save(fig, out, "clearance_along_path.png")


def median(values):
    v = sorted(values)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def plot_db(path, out):
    db = sqlite3.connect(path)
    tables = {r[0] for r in db.execute("SELECT name FROM sqlite_master WHERE type='table'")}
    if "progress" not in tables or "runs" not in tables:
        print(f"{path}: no progress table (planners that report no best cost): cost plot skipped")
        return
    columns = {r[1] for r in db.execute("PRAGMA table_info(progress)")}
    if not {"time", "best_cost"} <= columns:
        print(f"{path}: progress has no best_cost column: cost plot skipped")
        return
    has_experiments = "experiments" in tables
    query = ("SELECT {exp}, plannerConfigs.name, progress.runid, progress.time, progress.best_cost "
             "FROM progress JOIN runs ON progress.runid = runs.id "
             "JOIN plannerConfigs ON runs.plannerid = plannerConfigs.id {join} "
             "ORDER BY progress.runid, progress.time").format(
        exp="experiments.name" if has_experiments else "''",
        join="JOIN experiments ON runs.experimentid = experiments.id" if has_experiments else "")
    data = {}
    for exp, planner, run, t, cost in db.execute(query):
        if cost is None or t is None:
            continue
        cost = float(cost)
        if not math.isfinite(cost):
            continue
        data.setdefault(exp, {}).setdefault(planner, {}).setdefault(run, []).append((float(t), cost))
    if not data:
        print(f"{path}: no finite best cost recorded: cost plot skipped")
        return
    fig, axes = plt.subplots(1, len(data), figsize=(6 * len(data), 4.2), squeeze=False)
    for ax, (exp, planners) in zip(axes[0], sorted(data.items())):
        for k, (planner, runs) in enumerate(sorted(planners.items())):
            color = f"C{k}"
            for samples in runs.values():
                ax.plot([p[0] for p in samples], [p[1] for p in samples], color=color, alpha=0.2, linewidth=0.8)
            # Median over runs on a common time grid; a run without a solution yet counts as infinite cost, so the
            # median appears once more than half the runs have one.
            end = max(p[0] for samples in runs.values() for p in samples)
            grid = [end * i / 100 for i in range(101)]
            med = []
            for t in grid:
                now = [next((c for (u, c) in reversed(samples) if u <= t), math.inf) for samples in runs.values()]
                m = median(now)
                med.append(m if math.isfinite(m) else float("nan"))
            ax.plot(grid, med, color=color, linewidth=2, label=f"{planner} ({len(runs)} runs)")
        ax.set_xlabel("time (s)")
        ax.set_ylabel("best cost")
        ax.set_title(exp or "benchmark")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    save(fig, out, "planner_cost_vs_time.png")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scaling", help="CSV of meshgap_bench_scaling --csv")
    parser.add_argument("--clearance", action="append", default=[],
                        help="[NAME=]CSV of meshgap_plan --clearance-csv (repeatable)")
    parser.add_argument("--db", help="OMPL benchmark SQLite database (optional)")
    parser.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "figures"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.scaling:
        plot_scaling(args.scaling, args.out)
    else:
        print("no --scaling CSV: query-time plot skipped")
    if args.clearance:
        plot_clearance(args.clearance, args.out)
    else:
        print("no --clearance CSV: clearance plot skipped")
    if args.db:
        if not os.path.exists(args.db):
            sys.exit(f"error: {args.db}: no such file")
        plot_db(args.db, args.out)
    else:
        print("no --db: planner cost plot skipped (give an OMPL benchmark database, e.g. from ompl_benchmark_statistics)")


if __name__ == "__main__":
    main()
