#!/usr/bin/python3
"""Writes the generated inputs of meshgap_bench_build as OBJ files in a folder (default /tmp/meshgap_build_inputs):

    world100.obj  100 scattered copies of a closed twisted torus (1,152 triangles each; 115,200 in all), each copy
                  turned at random and placed near the centre of its cell of a 10 x 10 grid (seed 1), never touching
                  another
    dense.obj     one closed twisted torus of 249,600 triangles (a 640 x 195 grid of quads), with a wavy tube

Usage: build_inputs.py [FOLDER]"""
import math
import os
import random
import sys


def torus(nu, nv, major, minor, twist, waves):
    """A closed torus tube: nu x nv quads (two triangles each, outward facing), the tube's cross-section an
    ellipse turned by twist times the angle around the ring and its radius waving waves times around it."""
    vertices, triangles = [], []
    for i in range(nu):
        u = 2.0 * math.pi * i / nu
        turn = twist * u
        radius = minor * (1.0 + 0.25 * math.sin(waves * u))
        for j in range(nv):
            v = 2.0 * math.pi * j / nv
            a, b = 1.6 * radius * math.cos(v), 0.7 * radius * math.sin(v)
            x = a * math.cos(turn) - b * math.sin(turn)
            z = a * math.sin(turn) + b * math.cos(turn)
            vertices.append(((major + x) * math.cos(u), (major + x) * math.sin(u), z))
    for i in range(nu):
        for j in range(nv):
            p, q = i * nv + j, ((i + 1) % nu) * nv + j
            r, s = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
            triangles.append((p, q, r))
            triangles.append((p, r, s))
    return vertices, triangles


def rotation(rng):
    """A uniformly random rotation matrix (from a random unit quaternion)."""
    w, x, y, z = (rng.gauss(0.0, 1.0) for _ in range(4))
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    return ((1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)),
            (2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)),
            (2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)))


def write_obj(path, vertices, triangles):
    with open(path + ".tmp", "w", encoding="ascii") as out:
        out.writelines("v %.9g %.9g %.9g\n" % v for v in vertices)
        out.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in triangles)
    os.replace(path + ".tmp", path)


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "/tmp/meshgap_build_inputs"
    os.makedirs(folder, exist_ok=True)
    rng = random.Random(1)
    part, faces = torus(48, 12, 1.0, 0.25, 1, 3)  # within a ball of radius 1.5
    vertices, triangles = [], []
    for k in range(100):
        R = rotation(rng)
        cell = (k % 10, k // 10, 0)
        centre = [4.0 * c + rng.uniform(-0.4, 0.4) for c in cell]  # cells 4 apart: copies at least 0.2 apart
        offset = len(vertices)
        for p in part:
            vertices.append(tuple(sum(R[r][c] * p[c] for c in range(3)) + centre[r] for r in range(3)))
        triangles.extend((a + offset, b + offset, c + offset) for a, b, c in faces)
    write_obj(os.path.join(folder, "world100.obj"), vertices, triangles)
    vertices, triangles = torus(640, 195, 1.0, 0.25, 2, 7)
    write_obj(os.path.join(folder, "dense.obj"), vertices, triangles)
    print("wrote %s/world100.obj and %s/dense.obj" % (folder, folder))


if __name__ == "__main__":
    main()
