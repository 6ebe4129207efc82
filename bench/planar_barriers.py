#!/usr/bin/env python3
"""A planar (SE(2)) OMPL.app-style problem for bench/optimize_defaults.sh: four barriers 0.05 thick across
[-5, 5]^2, each with a gap of 1 (alternately high and low), six thin posts between them, and an L-shaped robot
(the scene of PlanOptimizeCliTest's BarriersProblem). Writes barriers.cfg, barriers_env.obj and barriers_robot.obj.

    bench/planar_barriers.py OUT_DIR
"""
import os
import sys


def box(centre, half, vertices, faces):
    """Append the closed box centre +- half (outward-facing triangles)."""
    base = len(vertices)
    for dx in (-1, 1):
        for dy in (-1, 1):
            for dz in (-1, 1):
                vertices.append((centre[0] + dx * half[0], centre[1] + dy * half[1], centre[2] + dz * half[2]))
    # corner index: 4 * (dx > 0) + 2 * (dy > 0) + (dz > 0)
    for a, b, c, d in [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]:
        faces.append((base + a, base + b, base + c))
        faces.append((base + a, base + c, base + d))


def write_obj(path, vertices, faces):
    with open(path, "w") as f:
        for v in vertices:
            f.write("v %.6f %.6f %.6f\n" % v)
        for t in faces:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: planar_barriers.py OUT_DIR")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    vertices, faces = [], []
    for x, gap in [(-3, 2.5), (-1, -2.5), (1, 2.5), (3, -2.5)]:
        low, high = gap - 0.5, gap + 0.5
        box((x, (low - 5) / 2, 0.5), (0.025, (low + 5) / 2, 0.5), vertices, faces)
        box((x, (high + 5) / 2, 0.5), (0.025, (5 - high) / 2, 0.5), vertices, faces)
    for x, y in [(-2, 0), (0, 0), (2, 0), (-2, -3), (0, 3), (2, -3)]:
        box((x, y, 0.5), (0.3, 0.025, 0.5), vertices, faces)
    write_obj(os.path.join(out, "barriers_env.obj"), vertices, faces)
    vertices, faces = [], []
    box((0, 0, 0.5), (0.3, 0.05, 0.25), vertices, faces)
    box((-0.25, 0.15, 0.5), (0.05, 0.15, 0.25), vertices, faces)
    write_obj(os.path.join(out, "barriers_robot.obj"), vertices, faces)
    with open(os.path.join(out, "barriers.cfg"), "w") as f:
        f.write("[problem]\nname = barriers\nrobot = barriers_robot.obj\nworld = barriers_env.obj\n"
                "start.x = -4.3\nstart.y = -3.5\nstart.theta = 0\n"
                "goal.x = 4.3\ngoal.y = 3.5\ngoal.theta = 1.5707963267948966\n"
                "volume.min.x = -5\nvolume.min.y = -5\nvolume.max.x = 5\nvolume.max.y = 5\n")


if __name__ == "__main__":
    main()
