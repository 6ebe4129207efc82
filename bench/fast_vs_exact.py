#!/usr/bin/python3
"""Scene.distance(exact=False) ("fast") against exact=True on the same poses: a random stream (poses uniform in the
cfg's volume, unrelated to each other) and a path stream (straight paths of 32 evenly spaced poses between uniform
ones, meshgap.distributed.path_poses()), per problem. Each problem's scene is built afresh, then "first" times one
call per mode on its first poses (what a user's first call pays: a body's mesh distances are built on first use by a
node search), and the rounds time both modes on the whole stream, interleaved, their medians reported, per pose.

    PYTHONPATH=build/python /usr/bin/python3 bench/fast_vs_exact.py [--poses 200] [--rounds 3] [CFG ...]

(default: the maps and the OMPL.app problems found in ../shared/data/omplapp). Prints one row per problem and stream:
median seconds per pose of each mode, their ratio fast/exact, and the first calls' times; with --markdown, as a
Markdown table (the form bench/refresh.sh writes into bench/queries.md).
"""
import argparse
import os
import statistics
import sys
import time

import numpy as np

import meshgap
import meshgap.distributed as md

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT = [os.path.join(HERE, "..", "maps", m, m + ".cfg") for m in
           ("hand_bowl", "twisted", "battery_fixture", "slotted_wall")] + \
          [os.path.join(HERE, "..", "..", "shared", "data", "omplapp", n + ".cfg") for n in
           ("cubicles", "Twistycool", "Easy", "Abstract", "bugtrap")]


def volume(cfg):
    """The cfg's volume ((min x y z), (max x y z)), read from its text (as meshgap.distributed reads it)."""
    keys = md._read_cfg(cfg)
    return tuple(tuple(float(keys["volume.%s.%s" % (end, a)]) for a in "xyz") for end in ("min", "max"))


def timed(scene, poses, exact):
    start = time.perf_counter()
    scene.distance(poses, exact=exact)
    return time.perf_counter() - start


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cfg", nargs="*")
    parser.add_argument("--poses", type=int, default=200)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--markdown", action="store_true", help="a Markdown table")
    args = parser.parse_args()
    if args.markdown:
        row = "| %s | %s | %.3g | %.3g | %.2f | %.3g | %.3g |"
        print("Fast mode against the exact query, %d poses a stream, medians of %d rounds:\n" % (args.poses, args.rounds))
        print("| problem | stream | exact s/pose | fast s/pose | fast/exact | first exact (20 poses, s) | "
              "first fast (20 poses, s) |")
        print("|---|---|---:|---:|---:|---:|---:|")
    else:
        row = "%-16s %-7s %12.3g %12.3g %9.2f %12.3g %12.3g"
        print("%-16s %-7s %12s %12s %9s %12s %12s" % ("problem", "stream", "exact s/pose", "fast s/pose", "fast/exact",
                                                      "first exact", "first fast"))
    for cfg in [os.path.normpath(c) for c in (args.cfg or DEFAULT) if os.path.exists(c)]:
        name = os.path.splitext(os.path.basename(cfg))[0]
        box = volume(cfg)
        streams = {"random": md.uniform_poses(box, False, args.poses, 1, 0),
                   "path": md.path_poses(box, False, args.poses, 1, 0)}
        scene = meshgap.Scene.from_cfg(cfg)  # afresh: the first calls pay what a first use pays
        first = {exact: timed(scene, streams["random"][:20], exact) for exact in (True, False)}
        for stream, poses in streams.items():
            times = {True: [], False: []}
            for _ in range(args.rounds):
                for exact in (True, False):
                    times[exact].append(timed(scene, poses, exact) / len(poses))
            e, f = statistics.median(times[True]), statistics.median(times[False])
            print(row % (name, stream, e, f, f / e, first[True], first[False]), flush=True)


if __name__ == "__main__":
    sys.exit(main())
