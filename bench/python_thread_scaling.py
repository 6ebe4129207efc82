#!/usr/bin/python3
"""Threads sharing one scene in a Python batch against as many single-thread processes: scene.distance(poses,
threads=T) in one process against T processes each answering its share of the poses with threads=1, alternating,
REPS times each; each process answers its poses --repeat times. Every process loads the scene, makes the poses and warms up before a common start, so only the
queries are timed; throughput is the poses answered over the wall time from the first start to the last end.

Streams: "path" (OMPL.app cubicles' .path interpolated to --states poses, warm certified: each thread carries its
warm start across the blocks it takes) or "random" (uniform poses in the cfg's volume, random rotations, fixed seed).

    PYTHONPATH=build/python /usr/bin/python3 bench/python_thread_scaling.py [--threads 2] [--states 20000]
        [--reps 5] [--repeat 10] [--stream path|random] [--cfg ../shared/data/omplapp/cubicles.cfg] [--markdown]

--markdown prints the medians as one Markdown table row, under its header (the form bench/refresh.sh writes into
bench/scaling.md; the runs' lines are left out).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "data", "omplapp"))


def make_poses(cfg, stream, count):
    import meshgap
    from python_batch import interpolate

    scene = meshgap.Scene.from_cfg(cfg)
    if stream == "path":
        return scene, interpolate(np.loadtxt(os.path.splitext(cfg)[0] + ".path"), count)
    rng = np.random.default_rng(7)
    b = scene.bounds
    poses = np.empty((count, 7))
    poses[:, :3] = rng.uniform(b[:3, 0], b[:3, 1], size=(count, 3))
    q = rng.normal(size=(count, 4))
    poses[:, 3:] = q / np.linalg.norm(q, axis=1)[:, None]
    return scene, poses


def child(args):
    """Answers poses [first, last) with --threads threads after a 'go' line on stdin; prints its times as JSON."""
    scene, poses = make_poses(args.cfg, args.stream, args.states)
    mine = poses[args.first:args.last]
    scene.distance(mine[:512], exact=True, warm=True, threads=args.threads)  # warm up: the node layers, the threads
    print("ready", flush=True)
    sys.stdin.readline()
    start, cpu = time.time(), time.process_time()
    for _ in range(args.repeat):
        scene.distance(mine, exact=True, warm=True, threads=args.threads)
    end = time.time()
    print(json.dumps({"start": start, "end": end, "cpu": time.process_time() - cpu}), flush=True)


def run(args, shares, threads):
    """The poses split into \e shares processes of \e threads threads each: (poses per second, CPU seconds)."""
    env = dict(os.environ)
    # The children run in this folder (to import python_batch): the module's path made absolute.
    env["PYTHONPATH"] = os.pathsep.join(os.path.abspath(p) for p in env.get("PYTHONPATH", "").split(os.pathsep) if p)
    cuts = [round(k * args.states / shares) for k in range(shares + 1)]
    procs = [subprocess.Popen([sys.executable, os.path.abspath(__file__), "--child", "--cfg", args.cfg, "--stream",
                               args.stream, "--states", str(args.states), "--first", str(cuts[k]), "--last",
                               str(cuts[k + 1]), "--threads", str(threads), "--repeat", str(args.repeat)],
                              stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                              env=env, cwd=HERE) for k in range(shares)]
    for p in procs:
        assert p.stdout.readline().strip() == "ready"
    for p in procs:
        p.stdin.write("go\n")
        p.stdin.flush()
    times = [json.loads(p.stdout.readline()) for p in procs]
    for p in procs:
        p.wait()
    wall = max(t["end"] for t in times) - min(t["start"] for t in times)
    return args.repeat * args.states / wall, sum(t["cpu"] for t in times)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--states", type=int, default=20000)
    parser.add_argument("--reps", type=int, default=5)
    parser.add_argument("--repeat", type=int, default=10, help="batches each process answers in a run")
    parser.add_argument("--stream", choices=["path", "random"], default="path")
    parser.add_argument("--cfg", default=os.path.join(DATA, "cubicles.cfg"))
    parser.add_argument("--markdown", action="store_true", help="the medians as a Markdown table")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--first", type=int, default=0, help=argparse.SUPPRESS)
    parser.add_argument("--last", type=int, default=0, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        return child(args)
    if not os.path.isfile(args.cfg):
        sys.exit("skipped: %s is not a file" % args.cfg)
    ratios, cpu_ratios = [], []
    for r in range(args.reps):
        threaded, threaded_cpu = run(args, 1, args.threads)
        separate, separate_cpu = run(args, args.threads, 1)
        ratios.append(threaded / separate)
        cpu_ratios.append(threaded_cpu / separate_cpu)
        if not args.markdown:
            print("run %d: %d threads %.0f poses/s (CPU %.2f s), %d processes %.0f poses/s (CPU %.2f s); load %.1f"
                  % (r + 1, args.threads, threaded, threaded_cpu, args.threads, separate, separate_cpu,
                     os.getloadavg()[0]), flush=True)
    if args.markdown:
        print("Python batch, threads against processes (medians of the runs):\n")
        print("| stream | threads | poses x batches | runs | threads / processes, throughput | CPU time |")
        print("|---|---:|---:|---:|---:|---:|")
        print("| %s | %d | %d x %d | %d | **%.2f** | %.2f |" % (
            args.stream, args.threads, args.states, args.repeat, args.reps, statistics.median(ratios),
            statistics.median(cpu_ratios)))
        return
    print("median throughput, threads / processes: %.2f; CPU time, threads / processes: %.2f"
          % (statistics.median(ratios), statistics.median(cpu_ratios)))


if __name__ == "__main__":
    main()
