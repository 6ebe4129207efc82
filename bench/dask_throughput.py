#!/usr/bin/python3
"""meshgap.distributed's throughput against the single-process threaded batch, on the same machine, and a projection
to more workers from the measured costs.

For each problem: poses uniform in its volume (meshgap.distributed.uniform_poses, seed 1), Scene.distance's
keywords of meshgap.distributed.distance (exact, warm, depth):
  1. scene build: Scene.from_cfg, median of 3;
  2. the single-process batch: Scene.distance(poses, threads=1) and threads=2, poses per second;
  3. Dask: a distributed.LocalCluster of 1 and of 2 worker processes (one thread each), md.distance(cfg, poses,
     chunks=C) computed for each chunk size C, each worker's scene built beforehand (its build timed apart on
     each worker: files checked and hashed, then Scene.from_cfg);
  4. the engine's own costs: the round trip of one empty task (client.submit, result; 2 workers), and empty tasks
     per second through the scheduler with 1 and 2 workers (client.map over 2,000, gathered);
then a projection to 8, 64 and 512 workers: each worker computes a chunk in C x (the per-pose CPU time of the
threads=1 batch) plus the engine's cost per chunk (what a chunk took on one worker beyond that CPU time), the
scheduler passes at most the empty tasks per second measured through two workers (divided by md.distance's tasks
per chunk in its optimised graph), and the results
(88 bytes a pose, plus 56 bytes of poses sent out) cross a 1 Gbit/s link at the client (an assumption, stated).
Rounds are interleaved (each measurement once per round), medians of --rounds.

    PYTHONPATH=build/python nice -n 5 /usr/bin/python3 bench/dask_throughput.py [--poses 20000] [--rounds 3]
        [--chunks 100,1000,10000] [--problems maps/hand_bowl/hand_bowl.cfg,../shared/data/omplapp/cubicles.cfg]
"""
import argparse
import os
import statistics
import time

import numpy as np

import meshgap
import meshgap.distributed as md

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
DEFAULT_PROBLEMS = [os.path.join(ROOT, "maps", "hand_bowl", "hand_bowl.cfg"),
                    os.path.normpath(os.path.join(ROOT, "..", "shared", "data", "omplapp", "cubicles.cfg"))]
LINK = 125e6  # bytes per second at the client: 1 Gbit/s (an assumption)
RESULT_BYTES = 8 * sum(width for _, _, width in md.FIELDS)


def noop(x=None):
    return x


def worker_build(p):
    """On a worker: the time it takes to build its scene of p (dropped first, then built as a task builds it)."""
    import meshgap.distributed
    meshgap.distributed._scenes.pop(p.key, None)
    start = time.perf_counter()
    meshgap.distributed.scene(p)
    return time.perf_counter() - start


def timed(f):
    start = time.perf_counter()
    f()
    return time.perf_counter() - start


def cluster(workers):
    import distributed
    c = distributed.LocalCluster(n_workers=workers, processes=True, threads_per_worker=1, dashboard_address=":0")
    return c, distributed.Client(c)


def dask_rate(client, cfg, poses, chunk):
    import dask
    return len(poses) / timed(lambda: dask.compute(md.distance(cfg, poses, chunks=chunk)))


def engine_costs(clients, rounds):
    """The round trip of one empty task (2 workers), and empty tasks per second through 1 and 2 workers."""
    trips = []
    for _ in range(50 * rounds):
        trips.append(timed(lambda: clients[2].submit(noop, np.random.random(), pure=False).result()))
    per_second = {}
    for _ in range(rounds):
        for workers, client in clients.items():
            per_second.setdefault(workers, []).append(
                2000 / timed(lambda: client.gather(client.map(noop, range(2000), pure=False))))
    return statistics.median(trips), {w: statistics.median(v) for w, v in per_second.items()}


def tasks_per_chunk(cfg, poses, chunk):
    """Tasks of md.distance's optimised graph per chunk of poses (the pose slice, the scene's call, the fields)."""
    import dask.base
    r = md.distance(cfg, poses, chunks=chunk)
    return len(dask.base.collections_to_dsk(list(r.values()), optimize_graph=True)) / -(-len(poses) // chunk)


def measure(cfg, args, clients):
    name = os.path.splitext(os.path.basename(cfg))[0]
    p = md.problem(cfg)
    poses = md.uniform_poses(p.volume, p.planar, args.poses, 1, 0)
    scene = meshgap.Scene.from_cfg(cfg)
    builds = [timed(lambda: meshgap.Scene.from_cfg(cfg)) for _ in range(3)]
    first = {}
    for workers, client in clients.items():  # the slowest worker's build of its scene (files checked and hashed)
        first[workers] = max(client.run(worker_build, p).values())
    rates, cpu = {}, []
    for _ in range(args.rounds):
        for threads in (1, 2):
            start = time.process_time()
            rates.setdefault(("batch", threads), []).append(
                len(poses) / timed(lambda: scene.distance(poses, threads=threads)))
            if threads == 1:
                cpu.append((time.process_time() - start) / len(poses))
        for workers, client in clients.items():
            for chunk in args.chunks:
                rates.setdefault((workers, chunk), []).append(dask_rate(client, cfg, poses, chunk))
    per_chunk = {chunk: tasks_per_chunk(cfg, poses, chunk) for chunk in args.chunks}
    return (name, p, statistics.median(builds), first, {k: statistics.median(v) for k, v in rates.items()},
            statistics.median(cpu), per_chunk)


def project(per_pose, task_cost, tasks_per_second, chunk, workers):
    """Poses per second of workers workers on chunks of chunk poses, and what limits it."""
    compute = workers * chunk / (chunk * per_pose + task_cost)
    scheduler = tasks_per_second * chunk
    link = LINK / (RESULT_BYTES + 56)
    limits = {"workers' compute": compute, "scheduler": scheduler, "client link": link}
    limit = min(limits, key=limits.get)
    return limits[limit], limit


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--poses", type=int, default=20000)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--chunks", default="100,1000,10000")
    parser.add_argument("--problems", default=",".join(DEFAULT_PROBLEMS))
    args = parser.parse_args()
    args.chunks = [int(c) for c in args.chunks.split(",")]
    print("load average before: %.2f %.2f %.2f" % os.getloadavg())
    clients = {}
    try:
        for workers in (1, 2):
            clients[workers] = cluster(workers)
        task_trip, tasks_per_second = engine_costs({w: c for w, (_, c) in clients.items()}, args.rounds)
        results = [measure(cfg, args, {w: c for w, (_, c) in clients.items()}) for cfg in args.problems.split(",")]
    finally:
        for c, client in clients.values():
            client.close()
            c.close()
    print("load average after: %.2f %.2f %.2f" % os.getloadavg())
    print("\nThe engine's own costs:\n")
    print("| empty task round trip (2 workers) | empty tasks per second, 1 worker | 2 workers |")
    print("|---:|---:|---:|")
    print("| %.2f ms | %.0f /s | %.0f /s |\n" % (task_trip * 1e3, tasks_per_second[1], tasks_per_second[2]))
    print("Cells: poses per second; in bold, Dask against the batch with as many threads as worker processes "
          "(1 worker: threads=1; 2 workers: threads=2), and threads=2 against threads=1.\n")
    print("| problem | scene build | scene build on the workers (slowest), 1 / 2 workers | batch threads=1 | "
          "batch threads=2 | " + " | ".join("Dask %s worker%s, chunk %d" % (w, "s" if w > 1 else "", c)
                                           for w in (1, 2) for c in args.chunks) + " |")
    print("|---|---:|---:|---:|---:|" + "---:|" * (2 * len(args.chunks)))
    projections = []
    for name, p, build, first, rates, per_pose, tasks in results:
        one = rates[("batch", 1)]
        cells = ["%.0f (**%.2f**)" % (rates[(w, c)], rates[(w, c)] / (one * w if w == 1 else rates[("batch", 2)]))
                 for w in (1, 2) for c in args.chunks]
        print("| %s | %.0f ms | %.0f / %.0f ms | %.0f | %.0f (**%.2f**) | %s |" % (
            name, build * 1e3, first[1] * 1e3, first[2] * 1e3, one, rates[("batch", 2)], rates[("batch", 2)] / one,
            " | ".join(cells)))
        for chunk in args.chunks:
            # The engine's cost per chunk: what a chunk takes on one worker beyond its poses' CPU time.
            chunk_cost = max(0.0, chunk / rates[(1, chunk)] - chunk * per_pose)
            row = [name, chunk, per_pose * 1e6, chunk * per_pose * 1e3, tasks[chunk], chunk_cost * 1e3]
            for workers in (8, 64, 512):
                row.append(project(per_pose, chunk_cost, tasks_per_second[2] / tasks[chunk], chunk, workers))
            projections.append(row)
    print("\nProjection to more workers (poses per second, and what limits it; the client's link assumed 1 Gbit/s):\n")
    print("| problem | chunk | per pose (CPU) | per chunk (CPU) | tasks per chunk | engine per chunk (1 worker) | "
          "8 workers | 64 workers | 512 workers |")
    print("|---|---:|---:|---:|---:|---:|---|---|---|")
    for name, chunk, pose_us, chunk_ms, tasks, task_ms, *cells in projections:
        print("| %s | %d | %.1f µs | %.2f ms | %.1f | %.2f ms | %s |" % (
            name, chunk, pose_us, chunk_ms, tasks, task_ms,
            " | ".join("%.3g /s (%s)" % (rate, limit) for rate, limit in cells)))


if __name__ == "__main__":
    main()
