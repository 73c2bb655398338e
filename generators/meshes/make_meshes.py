#!/usr/bin/env python3
"""Writes the tree generator's part meshes, trunk.obj and leaf.obj, next to this file.

Both are closed solids centred at the origin with smooth outward vertex normals:
- trunk: an octagonal prism spanning [-0.5, 0.5] on every axis (flats on the x and z
  axes), sides smooth, caps flat; scaled by its scope like every part mesh;
- leaf: a lens-shaped leaf about 0.48 x 0.98 x 0.15, widest near its base, pointing
  along +y, emitted unscaled.

Run: python3 generators/meshes/make_meshes.py
"""

import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def fmt(x):
    s = f"{x:.6f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def write(name, header, positions, normals, faces):
    """faces: lists of (position index, normal index), 0-based."""
    lines = [f"# {line}" for line in header] + [f"o {name}"]
    lines += ["v " + " ".join(fmt(c) for c in p) for p in positions]
    lines += ["vn " + " ".join(fmt(c) for c in n) for n in normals]
    lines += ["f " + " ".join(f"{v + 1}//{n + 1}" for v, n in f) for f in faces]
    with open(os.path.join(HERE, f"{name}.obj"), "w", newline="\n") as out:
        out.write("\n".join(lines) + "\n")


def trunk():
    sides = 8
    radius = 0.5 / math.cos(math.pi / sides)
    angles = [math.pi / sides + 2 * math.pi * k / sides for k in range(sides)]
    ring = [(radius * math.cos(a), -radius * math.sin(a)) for a in angles]
    positions = [(x, y, z) for y in (-0.5, 0.5) for (x, z) in ring]
    normals = [(math.cos(a), 0.0, -math.sin(a)) for a in angles] + [(0, -1, 0), (0, 1, 0)]
    faces = []
    for k in range(sides):
        k1 = (k + 1) % sides
        faces.append([(k, k), (k1, k1), (sides + k1, k1), (sides + k, k)])
    faces.append([(k, sides) for k in reversed(range(sides))])
    faces.append([(sides + k, sides + 1) for k in range(sides)])
    write("trunk", ["Branch part of the tree generator: an octagonal prism spanning [-0.5, 0.5].",
                    "Written by make_meshes.py."], positions, normals, faces)


def leaf():
    rings, around = 12, 8
    half_len, half_width, half_thick = 0.49, 0.24, 0.075
    # Rings denser towards the tips; the profile is rounded at the base, pointed at
    # the tip and widest at about a third of the length.
    us = [0.5 - 0.5 * math.cos(math.pi * i / (rings + 1)) for i in range(1, rings + 1)]
    profile = [math.sin(math.pi * u ** 0.7) for u in us]
    peak = max(profile)
    positions = []
    for u, f in zip(us, profile):
        y = -half_len + 2 * half_len * u
        w, h = half_width * f / peak, half_thick * f / peak
        for j in range(around):
            t = 2 * math.pi * j / around
            positions.append((w * math.cos(t), y, -h * math.sin(t)))
    bottom, top = len(positions), len(positions) + 1
    positions += [(0.0, -half_len, 0.0), (0.0, half_len, 0.0)]
    tris = []
    for i in range(rings - 1):
        for j in range(around):
            j1 = (j + 1) % around
            a, b = i * around + j, i * around + j1
            c, d = a + around, b + around
            tris += [(a, b, d), (a, d, c)]
    last = (rings - 1) * around
    for j in range(around):
        j1 = (j + 1) % around
        tris.append((bottom, j1, j))
        tris.append((top, last + j, last + j1))
    # Smooth normals: area-weighted face normals summed at each vertex.
    acc = [[0.0, 0.0, 0.0] for _ in positions]
    for t in tris:
        p = [positions[i] for i in t]
        e1 = [p[1][k] - p[0][k] for k in range(3)]
        e2 = [p[2][k] - p[0][k] for k in range(3)]
        n = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
             e1[0] * e2[1] - e1[1] * e2[0])
        for i in t:
            for k in range(3):
                acc[i][k] += n[k]
    normals = []
    for n in acc:
        length = math.sqrt(sum(c * c for c in n))
        normals.append(tuple(c / length for c in n))
    faces = [[(i, i) for i in t] for t in tris]
    write("leaf", ["Leaf part of the tree generator: about 0.48 x 0.98 x 0.15, centred,",
                   "pointing along +y. Written by make_meshes.py."], positions, normals, faces)


if __name__ == "__main__":
    trunk()
    leaf()
