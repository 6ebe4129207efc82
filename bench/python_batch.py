#!/usr/bin/python3
"""The Python module's batched queries on OMPL.app's cubicles: its .path interpolated to 10,000 states in
numpy (linear translation, slerp rotation, by arc length with rotation counted in radians, as meshgap_bench_queries
interpolates), then in interleaved rounds so machine load hits both alike:
  1. scene.distance(poses) warm certified, threads=1: wall time per query, against the C++ loop over the same poses
     (build/bench/meshgap_bench_path_loop: Scene::distance with one warm start carried, as the C++ bench's warm
     certified column);
  2. threads=2 against threads=1 wall time;
then 3. resident memory (VmRSS) over 10^6 queries (100 batches of the 10,000 poses).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_batch.py [--build build] [--rounds 5] [--million]
        [--data ../shared/data/omplapp] [--markdown]

--markdown prints the medians as a Markdown table (the form bench/refresh.sh writes into bench/python.md; the rounds'
lines are left out).
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

import numpy as np

import meshgap

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "data", "omplapp"))


def slerp(q0, q1, t):
    d = np.dot(q0, q1)
    if d < 0:
        q1, d = -q1, -d
    if d > 0.9995:
        q = q0 + t * (q1 - q0)
    else:
        a = np.arccos(d)
        q = (np.sin((1 - t) * a) * q0 + np.sin(t * a) * q1) / np.sin(a)
    return q / np.linalg.norm(q)


def interpolate(path, count):
    dt = np.linalg.norm(np.diff(path[:, :3], axis=0), axis=1)
    dots = np.abs(np.sum(path[1:, 3:] * path[:-1, 3:], axis=1)).clip(0, 1)
    s = np.concatenate([[0.0], np.cumsum(dt + 2 * np.arccos(dots) + 1e-12)])
    out = np.empty((count, 7))
    for k, at in enumerate(np.linspace(0, s[-1], count)):
        i = min(np.searchsorted(s, at, side="right") - 1, len(path) - 2)
        t = np.clip((at - s[i]) / (s[i + 1] - s[i]), 0, 1)
        out[k, :3] = (1 - t) * path[i, :3] + t * path[i + 1, :3]
        out[k, 3:] = slerp(path[i, 3:], path[i + 1, 3:], t)
    return out


def rss_mib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default=os.path.join(HERE, "..", "build"))
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--states", type=int, default=10000)
    parser.add_argument("--million", action="store_true", help="also 10^6 queries with VmRSS after each batch")
    parser.add_argument("--data", default=DATA, help="the folder of OMPL.app's cubicles.cfg and cubicles.path")
    parser.add_argument("--markdown", action="store_true", help="the medians as a Markdown table")
    args = parser.parse_args()
    say = (lambda *a: None) if args.markdown else print
    cfg = os.path.join(args.data, "cubicles.cfg")
    scene = meshgap.Scene.from_cfg(cfg)
    poses = interpolate(np.loadtxt(os.path.join(args.data, "cubicles.path")), args.states)
    loop = os.path.join(args.build, "bench", "meshgap_bench_path_loop")
    with tempfile.NamedTemporaryFile("w", suffix=".path", delete=False) as f:
        for p in poses:
            f.write(" ".join("%.17g" % x for x in p) + "\n")
        poses_file = f.name
    scene.distance(poses[:1000])  # warm up this thread
    python_us, cpp_us, one_s, two_s, one_cpu, two_cpu, cpp_cpu_us, busiest = [], [], [], [], [], [], [], []
    for r in range(args.rounds):
        start, cpu = time.perf_counter(), time.process_time()
        result = scene.distance(poses, exact=True, warm=True, threads=1)
        one = time.perf_counter() - start
        one_cpu.append(time.process_time() - cpu)
        python_us.append(one / len(poses) * 1e6)
        one_s.append(one)
        run = subprocess.run([loop, "--cfg", cfg, "--poses", poses_file, "--repeat", "1"], capture_output=True,
                             text=True, check=True)
        cpp_us.append(float(run.stdout.split("median ")[1].split()[0]))
        cpp_cpu_us.append(float(run.stdout.split(" cpu ")[1].split()[0]))
        start, cpu, own = time.perf_counter(), time.process_time(), time.thread_time()
        two = scene.distance(poses, exact=True, warm=True, threads=2)
        two_s.append(time.perf_counter() - start)
        two_cpu.append(time.process_time() - cpu)
        # The calling thread is one of the two workers: its CPU time, and the rest is the other's. On two idle
        # cores the batch would take as long as the busier of the two.
        caller = time.thread_time() - own
        busiest.append(max(caller, two_cpu[-1] - caller))
        assert all(np.array_equal(result[k], two[k]) for k in result)
        say("round %d: wall python %.2f us/query, C++ loop %.2f; CPU python %.2f, C++ %.2f; threads=1 %.3f s, "
              "threads=2 %.3f s wall; load %.1f" % (r + 1, python_us[-1], cpp_us[-1], one_cpu[-1] / len(poses) * 1e6,
                                                   cpp_cpu_us[-1], one, two_s[-1], os.getloadavg()[0]))
    os.unlink(poses_file)
    say("poses %d, certified %d, in collision %d, min distance %.6g" %
          (len(poses), result["certified"].sum(), result["in_collision"].sum(), result["distance"].min()))
    mp, mc = statistics.median(python_us), statistics.median(cpp_us)
    say("median wall per query: python %.2f us, C++ %.2f us, ratio %.3f" % (mp, mc, mp / mc))
    pc, cc = statistics.median(one_cpu) / len(poses) * 1e6, statistics.median(cpp_cpu_us)
    say("median CPU per query: python %.2f us, C++ %.2f us, ratio %.3f" % (pc, cc, pc / cc))
    m1, m2 = statistics.median(one_s), statistics.median(two_s)
    say("median wall: threads=1 %.3f s, threads=2 %.3f s, ratio %.3f" % (m1, m2, m2 / m1))
    say("median CPU (both threads): threads=1 %.3f s, threads=2 %.3f s, ratio %.3f"
          % (statistics.median(one_cpu), statistics.median(two_cpu),
             statistics.median(two_cpu) / statistics.median(one_cpu)))
    say("median CPU of the busier thread with threads=2: %.3f s, %.3f of threads=1's CPU time"
          % (statistics.median(busiest), statistics.median(busiest) / statistics.median(one_cpu)))
    rss = []
    if args.million:
        rss = [rss_mib()]
        for b in range(100):
            scene.distance(poses, threads=1)
            rss.append(rss_mib())
        say("VmRSS MiB: before %.1f, after 1 batch %.1f, after 10 %.1f, after 50 %.1f, after 100 (10^6 queries) %.1f"
              % (rss[0], rss[1], rss[10], rss[50], rss[100]))

    if args.markdown:
        one_cpu_median = statistics.median(one_cpu)
        print("The module's batch against the C++ loop over %d poses of cubicles' path (%d certified, %d colliding), "
              "and threads=2 against threads=1; medians of %d round(s):\n"
              % (len(poses), result["certified"].sum(), result["in_collision"].sum(), args.rounds))
        print("| | median |")
        print("|---|---:|")
        print("| Python batch / C++ loop, per query, CPU time | **%.2f** (%.2f / %.2f µs) |" % (pc / cc, pc, cc))
        print("| Python batch / C++ loop, per query, wall time | %.2f (%.2f / %.2f µs) |" % (mp / mc, mp, mc))
        print("| threads=2 / threads=1, wall time | **%.2f** (%.3f / %.3f s) |" % (m2 / m1, m2, m1))
        print("| busier thread / one-thread CPU time | %.2f |" % (statistics.median(busiest) / one_cpu_median))
        if rss:
            print("| VmRSS before the first batch and after 1, 10, 50, 100 batches (%s queries) | %s MiB |"
                  % ("10^6" if len(poses) == 10000 else "{:,}".format(100 * len(poses)),
                     " / ".join("%.1f" % rss[k] for k in (0, 1, 10, 50, 100))))


if __name__ == "__main__":
    main()
