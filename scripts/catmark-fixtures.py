#!/usr/bin/env python3
"""Writes the Catmull-Clark test meshes (tests/fixtures/catmark/*.obj, polygons with
OpenSubdiv's OBJ tags) and, given OpenSubdiv's osd_bench (../shared/bench/native/build.sh),
its catmark results.

    python3 scripts/catmark-fixtures.py [/tmp/subdiv-peers/osd_bench]

Each case CASE.obj gets CASE.OPTS.L<n>.osd.txt: the vertex positions ("v x y z") of
OpenSubdiv 3.5's uniform refinement at level n, written by
`osd_bench CASE.obj n catmark OUT [--corners] [--chaikin]` (catmark keeps the polygons as
read, with OpenSubdiv's default triangle rule; faces dropped: tests/catmull_clark.rs
matches the points as a set, and checks the counts, since OpenSubdiv numbers the new
vertices differently).
"""
import os, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
out = os.path.join(here, "..", "tests", "fixtures", "catmark")
os.makedirs(out, exist_ok=True)

def write(name, verts, faces, creases=(), corners=(), note=""):
    with open(os.path.join(out, name + ".obj"), "w") as f:
        f.write(f"# {note}\n# written by scripts/catmark-fixtures.py\n")
        for v in verts:
            f.write("v %.9g %.9g %.9g\n" % tuple(v))
        for face in faces:
            f.write("f " + " ".join(str(i + 1) for i in face) + "\n")
        for a, b, s in creases:
            f.write(f"t crease 2/1/0 {a} {b} {s}\n")
        for v, s in corners:
            f.write(f"t corner 1/1/0 {v} {s}\n")

# A: the unit cube as six quads (every vertex valence 3, extraordinary)
cube_v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
cube_f = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
write("cube", cube_v, cube_f, note="a quad cube: smooth Catmull-Clark")

# B: a hexagonal prism whose bottom is cut into a triangle and a pentagon: faces of
# 3, 4, 5 and 6 corners, closed, at level 0 (OpenSubdiv's TRI_SUB_CATMARK for the triangle)
import math
hexv = [(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3), 0.0) for k in range(6)]
ngon_v = hexv + [(x, y, 1.0) for (x, y, _) in hexv]
ngon_f = [tuple(range(6, 12)), (2, 1, 0), (0, 5, 4, 3, 2)]
ngon_f += [(k, (k + 1) % 6, 6 + (k + 1) % 6, 6 + k) for k in range(6)]
write("ngons", ngon_v, ngon_f, note="faces of 3, 4, 5 and 6 corners, closed")

# C: an open 4 x 3 grid of quads with a bump: boundaries (edge only / edge and corner)
grid_v = []
for j in range(4):
    for i in range(5):
        grid_v.append((i, j, 0.3 * math.sin(i * 1.3) * math.cos(j * 0.9)))
grid_f = [(j * 5 + i, j * 5 + i + 1, (j + 1) * 5 + i + 1, (j + 1) * 5 + i) for j in range(3) for i in range(4)]
write("grid", grid_v, grid_f, note="an open 4 x 3 quad grid: boundary rules")

# D: the cube with creases: an infinitely sharp loop of 4 edges (the top square), a
# semi-sharp chain (1.3 and 2.2), a semi-sharp edge (1.7) meeting the infinite loop, and a
# sharp corner; uniform and Chaikin decay. The values keep every decayed sharpness away
# from 0 by more than float rounding: with 1.5 and 2.3 a Chaikin value reaches 0 within
# 1e-7 at level 2, and which side of 0 it lands on is a matter of rounding order.
write("cube_creases", cube_v, cube_f,
      creases=[(1, 5, 10), (5, 7, 10), (7, 3, 10), (3, 1, 10), (0, 2, 1.3), (2, 6, 2.2), (0, 1, 1.7)],
      corners=[(4, 2.5)], note="creases infinite and semi-sharp, a corner")

# E: the grid with one interior sharp edge ending inside: a dart at each end
write("grid_dart", grid_v, grid_f, creases=[(6, 7, 10), (7, 8, 0.7)],
      note="an interior crease of two edges (one semi-sharp below 1): darts")

cases = [
    ("cube", "uniform", [], [1, 2, 3]),
    ("ngons", "uniform", [], [1, 2]),
    ("grid", "uniform", [], [2]),
    ("grid", "corners", ["--corners"], [2]),
    ("cube_creases", "uniform", [], [2, 3]),
    ("cube_creases", "chaikin", ["--chaikin"], [3]),
    ("grid_dart", "uniform", [], [2]),
]

if len(sys.argv) > 1:
    osd = sys.argv[1]
    for name, opts, flags, levels in cases:
        for n in levels:
            dst = os.path.join(out, f"{name}.{opts}.L{n}.osd.txt")
            tmp = dst + ".obj"
            subprocess.run([osd, os.path.join(out, name + ".obj"), str(n), "catmark", tmp] + flags,
                           check=True, stdout=subprocess.DEVNULL)
            with open(tmp) as f, open(dst, "w") as g:
                g.write(f"# OpenSubdiv 3.5 catmark, {name}.obj, level {n}, {opts}: "
                        f"osd_bench {name}.obj {n} catmark OUT {' '.join(flags)}\n")
                lines = f.readlines()
                g.write("# faces %d\n" % sum(1 for l in lines if l.startswith("f ")))
                g.writelines(l for l in lines if l.startswith("v "))
            os.remove(tmp)
    print("wrote OpenSubdiv's points into", out)
