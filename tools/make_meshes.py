#!/usr/bin/env python3
"""Writes the OBJ meshes of lesson 35 (lessons/meshes/): a cube whose faces share its eight
corners, a 24-sided cylinder whose caps share the rim vertices, with and without
smoothing groups, and an open bowl (its inside is back faces). None has `vn` lines, so
shadelab computes every normal.

Run from the repository root: python3 tools/make_meshes.py
"""
import math
import os

OUT = os.path.join(os.path.dirname(__file__), "..", "lessons", "meshes")


def write(name, header, verts, faces):
    with open(os.path.join(OUT, name), "w") as f:
        f.write(header)
        for p in verts:
            f.write("v %g %g %g\n" % p)
        for face in faces:
            # A string is a directive (`s 1`, `s off`); a list is a face, 0-based here.
            f.write(face + "\n" if isinstance(face, str) else "f " + " ".join(str(i + 1) for i in face) + "\n")


def main():
    os.makedirs(OUT, exist_ok=True)
    # Corner i has x, y, z = bits 0, 1, 2 of i, mapped to ±1; quads counter-clockwise from outside.
    cube = [((i & 1) * 2 - 1, ((i >> 1) & 1) * 2 - 1, ((i >> 2) & 1) * 2 - 1) for i in range(8)]
    quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    write("cube.obj", "# A cube whose six faces share its eight corners; no vn, no smoothing groups.\n"
          "# Written by tools/make_meshes.py.\n", cube, quads)

    n = 24
    verts = [(round(math.sin(2 * math.pi * i / n), 6), y, round(math.cos(2 * math.pi * i / n), 6))
             for y in (-1, 1) for i in range(n)]
    verts += [(0, -1, 0), (0, 1, 0)]
    sides = [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    caps = [c for i in range(n) for c in ([2 * n, (i + 1) % n, i], [2 * n + 1, n + i, n + (i + 1) % n])]
    write("cylinder-groups.obj", "# A 24-sided cylinder whose caps share the rim vertices with the sides. The sides are\n"
          "# smoothing group 1, the caps `s off` (flat). Written by tools/make_meshes.py.\n",
          verts, ["s 1"] + sides + ["s off"] + caps)
    write("cylinder.obj", "# The same cylinder without smoothing groups (no `s` lines, no vn).\n"
          "# Written by tools/make_meshes.py.\n", verts, sides + caps)

    # A hemisphere of radius 1 open at the top (rim at y = 0, bottom at y = -1): rings of 48
    # vertices from the rim down, one vertex at the bottom; faces counter-clockwise from outside.
    seg, rings = 48, 12
    bowl = []
    for r in range(rings):
        t = (math.pi / 2) * r / rings
        bowl += [(round(math.cos(t) * math.cos(2 * math.pi * s / seg), 6), round(-math.sin(t), 6),
                  round(math.cos(t) * math.sin(2 * math.pi * s / seg), 6)) for s in range(seg)]
    bowl.append((0, -1, 0))
    at = lambda r, s: r * seg + s % seg
    faces = [[at(r, s), at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)] for r in range(rings - 1) for s in range(seg)]
    faces += [[at(rings - 1, s), at(rings - 1, s + 1), rings * seg] for s in range(seg)]
    write("bowl.obj", "# An open hemispherical bowl (radius 1, rim at y = 0): seen from above, its inside is\n"
          "# back faces. Written by tools/make_meshes.py.\n", bowl, faces)


if __name__ == "__main__":
    main()
