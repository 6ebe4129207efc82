#!/usr/bin/python3
"""Figures and a comparison table from meshgap_bench_paper_reproduction's CSVs.

For each scene and pose (history_<scene>_pos<k>.csv) it draws two figures, like the paper's time histories:
  <scene>_pos<k>_GA.png   comb-GA-wl and comb-GA-nl, best distance against generation (Figs. 7, 10, 13)
  <scene>_pos<k>_SA.png   comb-SA-wl and comb-SA-nl, best distance against iteration  (Figs. 8, 11, 14)
Each figure shows, per algorithm, the best-so-far distance of the median run (solid: runs ranked by final distance,
ties by evaluations, the (N-1)/2-th) and the per-iteration median over all runs (dashed) with the 10-90 % band
across runs (shaded); the enumeration minimum is a black horizontal line. The y axis is logarithmic.

It also prints, from results.csv, a Markdown table of our results beside the paper's Tables III, V and VI.

Needs python3-matplotlib (Debian: apt-get install -y python3-matplotlib). Usage:
    /usr/bin/python3 bench/plot_paper.py [--dir bench/paper]
"""

import argparse
import csv
import glob
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402

TITLES = {
    "battery_fixture": "Battery and fixture",
    "hand_bowl": "Hand and bowl",
    "handshake": "Handshake",
}
UNITS = {"battery_fixture": "cm", "hand_bowl": "mm", "handshake": "mm"}
# The paper's figure numbers for each scene/pose: (GA figure, SA figure).
PAPER_FIGURES = {
    ("battery_fixture", 1): ("Fig. 7", "Fig. 8"),
    ("hand_bowl", 1): ("Fig. 10", "Fig. 11"),
    ("handshake", 1): ("Fig. 13", "Fig. 14"),
}
COLOURS = {"wl": "tab:blue", "nl": "tab:red"}

# The paper's Tables III, V and VI: (minimum, kflops); None where the table gives no value (position 2's kflops and
# 'global region' columns are cut off in our copy of Table III).
PAPER = {
    ("battery_fixture", 1): {
        "comb-GA-wl": (0.0757, 1852), "comb-GA-nl": (0.2345, 147), "comb-SA-wl": (0.0757, 8209),
        "comb-SA-nl": (0.1138, 113), "enumeration": (0.0757, None), "exact": (0.0747, None)},
    ("battery_fixture", 2): {
        "comb-GA-wl": (0.0997, None), "comb-GA-nl": (0.244, None), "comb-SA-wl": (0.0997, None),
        "comb-SA-nl": (0.1746, None), "enumeration": (0.0997, None), "exact": (0.0987, None)},
    ("hand_bowl", 1): {
        "comb-GA-wl": (4.8295, 2430), "comb-GA-nl": (12.433, 155), "comb-SA-wl": (4.8295, 11228),
        "comb-SA-nl": (16.221, 115), "enumeration": (4.8295, None), "exact": (4.7527, None)},
    ("handshake", 1): {
        "comb-GA-wl": (19.3163, 2140), "comb-GA-nl": (28.8090, 152), "comb-SA-wl": (19.3163, 9716),
        "comb-SA-nl": (24.9761, 112), "enumeration": (19.3163, None), "exact": (18.95, None)},
}


def read_history(path):
    """{algorithm: {column: [values by iteration]}}"""
    series = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            s = series.setdefault(row["algorithm"], {"iteration": [], "median_run": [], "median_all": [],
                                                     "p10_all": [], "p90_all": []})
            for key in s:
                s[key].append(int(row[key]) if key == "iteration" else float(row[key]))
    return series


def read_results(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def plot(scene, pose, family, series, results, out_dir):
    algorithms = [f"comb-{family}-wl", f"comb-{family}-nl"]
    algorithms = [a for a in algorithms if a in series]
    if not algorithms:
        return None
    rows = {r["algorithm"]: r for r in results if r["scene"] == scene and int(r["pose"]) == pose}
    enum_distance = float(rows["enumeration"]["enumeration_distance"]) if "enumeration" in rows else None
    unit = UNITS.get(scene, "units")
    runs = next((int(rows[a]["runs"]) for a in algorithms if a in rows), None)

    fig, ax = plt.subplots(figsize=(7.5, 5.6), dpi=120)
    for alg in algorithms:
        s = series[alg]
        colour = COLOURS[alg[-2:]]
        label = alg
        if alg in rows:
            label += f" (success {100 * float(rows[alg]['success_rate']):.0f} %)"
        ax.fill_between(s["iteration"], s["p10_all"], s["p90_all"], color=colour, alpha=0.15, linewidth=0,
                        step="post")
        ax.plot(s["iteration"], s["median_all"], color=colour, linestyle="--", linewidth=1.2, drawstyle="steps-post")
        ax.plot(s["iteration"], s["median_run"], color=colour, linewidth=2.0, label=label,
                drawstyle="steps-post")
    if enum_distance is not None:
        ax.axhline(enum_distance, color="black", linewidth=1.2, linestyle=(0, (1, 1.5)), zorder=4,
                   label=f"enumeration minimum {enum_distance:.4g} {unit}")
    # Legend entries for the line styles.
    ax.plot([], [], color="grey", linewidth=2.0, label="solid: median run")
    ax.plot([], [], color="grey", linestyle="--", linewidth=1.2, label="dashed: per-iteration median of all runs")
    ax.fill_between([], [], [], color="grey", alpha=0.25, label="band: 10–90 % of runs")

    ax.set_yscale("log")
    if enum_distance is not None:
        ax.set_ylim(bottom=0.8 * enum_distance)
    ax.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 3.0, 5.0)))
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.yaxis.set_major_formatter(FuncFormatter(lambda y, _: f"{y:g}"))
    ax.set_xlabel("generation" if family == "GA" else "iteration (trial point; linear to 10, log beyond)")
    ax.set_ylabel(f"best distance so far ({unit}, log scale)")
    title = f"{TITLES.get(scene, scene)}, position {pose}: comb-{family}-wl vs comb-{family}-nl"
    paper_fig = PAPER_FIGURES.get((scene, pose))
    if paper_fig:
        title += f" (paper {paper_fig[0 if family == 'GA' else 1]})"
    ax.set_title(title, fontsize=10)
    if runs:
        ax.text(0.99, 0.99, f"{runs} runs per algorithm", transform=ax.transAxes, ha="right", va="top",
                fontsize=8, color="dimgrey")
    if family == "SA":
        ax.set_xscale("symlog", linthresh=10)
    ax.set_xlim(0, max(max(series[a]["iteration"]) for a in algorithms))
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2, frameon=False)
    fig.tight_layout()
    name = f"{scene}_pos{pose}_{family}.png"
    fig.savefig(os.path.join(out_dir, name))
    plt.close(fig)
    return name


def fmt_num(x, digits=4):
    return "" if x is None else f"{x:.{digits}g}"


def comparison_table(results):
    # Paper time: its own estimate (IV-D), kflops at 1414 Mflop/s (a 3.06 GHz PC, Dongarra 2003), in ms.
    lines = ["| scene | pos | algorithm | paper minimum | our median run | our mean (worst) | our success | "
             "paper kflops | our mean kflops | our mean evaluations | paper time (ms, est.) | our median time (ms) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    keys = sorted({(r["scene"], int(r["pose"])) for r in results}, key=lambda k: (list(TITLES).index(k[0])
                                                                                   if k[0] in TITLES else 99, k[1]))
    for scene, pose in keys:
        paper = PAPER.get((scene, pose), {})
        rows = [r for r in results if r["scene"] == scene and int(r["pose"]) == pose]
        for r in rows:
            alg = r["algorithm"]
            p_min, p_kflops = paper.get(alg, (None, None))
            if alg == "enumeration":
                ours = fmt_num(float(r["enumeration_distance"]), 6) + " | "
                success = ""
            else:
                ours = (f"{float(r['median_distance']):.6g} | {float(r['mean_distance']):.6g} "
                        f"({float(r['worst_distance']):.6g})")
                digits = 2 if alg == "hill-climb" else 0
                success = f"{100 * float(r['success_rate']):.{digits}f} %"
            p_ms = None if p_kflops is None else p_kflops / 1414.0
            lines.append(f"| {scene} | {pose} | {alg} | {fmt_num(p_min, 6)} | {ours} | {success} | "
                         f"{fmt_num(p_kflops, 5)} | {float(r['mean_kflops']):.4g} | "
                         f"{float(r['mean_evaluations']):.4g} | {fmt_num(p_ms, 3)} | {float(r['median_ms']):.3f} |")
        if rows and rows[0]["exact_distance"] not in ("", "nan"):
            p_exact = paper.get("exact", (None, None))[0]
            lines.append(f"| {scene} | {pose} | exact (mesh to mesh) | {fmt_num(p_exact, 6)} | "
                         f"{float(rows[0]['exact_distance']):.6g} (FCL) | | | | | | | |")
    return "\n".join(lines)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--dir", default=os.path.join(here, "paper"),
                        help="folder with results.csv and history_*.csv; PNGs are written there")
    args = parser.parse_args()
    results = read_results(os.path.join(args.dir, "results.csv"))
    written = []
    for path in sorted(glob.glob(os.path.join(args.dir, "history_*_pos*.csv"))):
        m = re.match(r"history_(.+)_pos(\d+)\.csv$", os.path.basename(path))
        if not m:
            continue
        scene, pose = m.group(1), int(m.group(2))
        series = read_history(path)
        for family in ("GA", "SA"):
            name = plot(scene, pose, family, series, results, args.dir)
            if name:
                written.append(name)
    print(comparison_table(results))
    print()
    for name in written:
        print(f"wrote {os.path.join(args.dir, name)}")


if __name__ == "__main__":
    main()
