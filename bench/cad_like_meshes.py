#!/usr/bin/env python3
"""Meshes that look like CAD exports, for meshgap_bench_queries --robot/--world: binary STL (each triangle with its
own three corners, as CAD tools write it), many parts in one file, some of them open (tubes without caps, boxes
without a lid, sheets), finely tessellated. Written to a folder of your choice (they are large: keep them out of the
repository).

    bench/cad_like_meshes.py OUTDIR [--seed 1]

writes OUTDIR/cad_gripper.stl (a robot about its origin: a closed torus, an open wrist tube, two closed fingers, an
open cover sheet, a closed sphere; 21,240 triangles in 6 parts), OUTDIR/cad_assembly.stl (a world of 136
parts, 50,320 triangles: a closed base plate, four open tubes, 100 closed bolts, 20 lidless boxes, 10 wavy open
sheets, one closed bracket) and OUTDIR/cad_big.stl (one closed bumpy torus of 250,000 triangles, for load and
build).
"""

import argparse
import math
import os
import random
import struct


def grid(nu, nv, point, closed_u=False, closed_v=False):
    """Triangles of a (nu x nv)-cell grid surface point(i, j) (i in 0..nu, j in 0..nv); closed directions wrap."""
    tris = []
    for i in range(nu):
        for j in range(nv):
            i1 = (i + 1) % nu if closed_u else i + 1
            j1 = (j + 1) % nv if closed_v else j + 1
            a, b, c, d = point(i, j), point(i1, j), point(i1, j1), point(i, j1)
            tris.append((a, b, c))
            tris.append((a, c, d))
    return tris


def torus(big, small, nu, nv, bump=0.0):
    def p(i, j):
        u, v = 2 * math.pi * i / nu, 2 * math.pi * j / nv
        r = small * (1 + bump * math.sin(7 * u) * math.sin(5 * v))
        return ((big + r * math.cos(v)) * math.cos(u), (big + r * math.cos(v)) * math.sin(u), r * math.sin(v))

    return grid(nu, nv, p, True, True)


def sphere(radius, nu, nv):
    def p(i, j):
        u, v = 2 * math.pi * i / nu, math.pi * j / nv
        if j == 0 or j == nv:  # the poles: one point each, so the surface is closed
            return (0.0, 0.0, radius * math.cos(v))
        return (radius * math.sin(v) * math.cos(u), radius * math.sin(v) * math.sin(u), radius * math.cos(v))

    # u turns about +z, v runs from the north pole down: flip each triangle to wind it outward.
    return [(t[0], t[2], t[1]) for t in grid(nu, nv, p, True, False) if len(set(t)) == 3]


def tube(radius, height, segments, rings, caps):
    def p(i, j):
        u = 2 * math.pi * i / segments
        return (radius * math.cos(u), radius * math.sin(u), height * j / rings)

    tris = grid(segments, rings, p, True, False)
    if caps:
        for i in range(segments):
            tris.append(((0.0, 0.0, 0.0), p((i + 1) % segments, 0), p(i, 0)))
            tris.append(((0.0, 0.0, height), p(i, rings), p((i + 1) % segments, rings)))
    return tris


def box(sx, sy, sz, n, lid=True):
    """An axis-aligned box [0,s], each face an n x n grid, wound outward; without its top face if not lid."""
    faces = [
        lambda a, b: (a * sx, b * sy, 0.0),  # bottom (seen from below: a, b swapped below)
        lambda a, b: (a * sx, b * sy, sz),
        lambda a, b: (a * sx, 0.0, b * sz),
        lambda a, b: (a * sx, sy, b * sz),
        lambda a, b: (0.0, a * sy, b * sz),
        lambda a, b: (sx, a * sy, b * sz),
    ]
    outward_flip = [True, False, False, True, True, False]
    tris = []
    for k, f in enumerate(faces):
        if k == 1 and not lid:
            continue
        for t in grid(n, n, lambda i, j: f(i / n, j / n)):
            tris.append((t[0], t[2], t[1]) if outward_flip[k] else t)
    return tris


def sheet(sx, sy, n, wave):
    return grid(n, n, lambda i, j: (sx * i / n, sy * j / n, wave * math.sin(3 * i / n) * math.cos(2 * j / n)))


def rotation(rng):
    q = [rng.gauss(0, 1) for _ in range(4)]
    w, x, y, z = (c / math.sqrt(sum(c * c for c in q)) for c in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def place(tris, offset, rot=None):
    def move(p):
        if rot is not None:
            p = tuple(sum(rot[r][c] * p[c] for c in range(3)) for r in range(3))
        return (p[0] + offset[0], p[1] + offset[1], p[2] + offset[2])

    return [tuple(move(p) for p in t) for t in tris]


def write_stl(path, tris):
    with open(path + ".part", "wb") as f:
        f.write(b"meshgap cad-like test mesh".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0.0, 0.0, 0.0))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")
    os.replace(path + ".part", path)
    print(f"{path}: {len(tris)} triangles")


def gripper():
    tris = place(torus(0.06, 0.02, 120, 40), (0, 0, 0))
    tris += place(tube(0.03, 0.12, 64, 20, caps=False), (0, 0, 0.02))
    tris += place(box(0.015, 0.03, 0.12, 10), (0.03, -0.015, -0.14))
    tris += place(box(0.015, 0.03, 0.12, 10), (-0.045, -0.015, -0.14))
    tris += place(sheet(0.1, 0.1, 40, 0.01), (-0.05, -0.05, 0.16))
    tris += place(sphere(0.025, 60, 30), (0, 0, 0.2))
    return tris


def assembly(rng):
    tris = place(box(1.0, 0.8, 0.02, 20), (0, 0, 0))  # the base plate
    for x, y in ((0.05, 0.05), (0.95, 0.05), (0.05, 0.75), (0.95, 0.75)):
        tris += place(tube(0.02, 0.6, 48, 30, caps=False), (x, y, 0.02))
    for _ in range(100):  # bolts, closed
        tris += place(tube(0.006, 0.03, 16, 1, caps=True), (rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.7), 0.02))
    for _ in range(20):  # lidless boxes, open
        tris += place(box(0.08, 0.06, 0.05, 6, lid=False),
                      (rng.uniform(0.1, 0.8), rng.uniform(0.1, 0.6), rng.uniform(0.1, 0.5)), rotation(rng))
    for k in range(10):  # wavy sheets, open
        tris += place(sheet(0.3, 0.2, 30, 0.02), (rng.uniform(0.0, 0.7), rng.uniform(0.0, 0.6), 0.3 + 0.03 * k))
    tris += place(torus(0.08, 0.015, 60, 20), (0.5, 0.4, 0.7))  # a bracket ring, closed
    return tris


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("outdir")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    os.makedirs(args.outdir, exist_ok=True)
    rng = random.Random(args.seed)
    write_stl(os.path.join(args.outdir, "cad_gripper.stl"), gripper())
    write_stl(os.path.join(args.outdir, "cad_assembly.stl"), assembly(rng))
    write_stl(os.path.join(args.outdir, "cad_big.stl"), torus(0.3, 0.08, 500, 250, bump=0.1))


if __name__ == "__main__":
    main()
