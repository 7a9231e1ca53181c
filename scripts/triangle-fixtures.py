#!/usr/bin/env python3
"""Writes tests/fixtures/catmark/tri_quads.obj (an open 5x5 grid of quads, every third
split into two triangles, a semi-sharp crease) and, given OpenSubdiv's osd_opts
(../shared/bench/native/osd_opts.cpp), its Catmull-Clark results with either triangle
rule:

    python3 scripts/triangle-fixtures.py /tmp/peers/osd_opts

tri_quads.{catmark,smooth}.L{1,2}.osd.txt: "# faces N", then the last level's "v x y z"
lines as `osd_opts tri_quads.obj LEVELS OUT --triangles T` wrote them (double precision).
"""
import os, random, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
d = os.path.join(here, "..", "tests", "fixtures", "catmark")
N = 5

def vid(i, j):
    return j * N + i

def mesh():
    random.seed(5)
    out = ["# quads and triangles: written by scripts/triangle-fixtures.py"]
    for j in range(N):
        for i in range(N):
            out.append(f"v {i} {j} {random.uniform(-0.3, 0.3):.6f}")
    for j in range(N - 1):
        for i in range(N - 1):
            a, b, c, e = vid(i, j) + 1, vid(i + 1, j) + 1, vid(i + 1, j + 1) + 1, vid(i, j + 1) + 1
            out += [f"f {a} {b} {c}", f"f {a} {c} {e}"] if (i + j) % 3 == 0 else [f"f {a} {b} {c} {e}"]
    out.append(f"t crease 2/1/0 {vid(1, 2)} {vid(2, 2)} 1.5")
    return "\n".join(out) + "\n"

obj = os.path.join(d, "tri_quads.obj")
open(obj, "w").write(mesh())
if len(sys.argv) > 1:
    for rule in ("catmark", "smooth"):
        for level in (1, 2):
            tmp = os.path.join(d, ".osd.tmp.obj")
            subprocess.run([sys.argv[1], obj, str(level), tmp, "--triangles", rule], check=True, stdout=subprocess.DEVNULL)
            lines = open(tmp).read().splitlines()
            os.remove(tmp)
            faces = sum(1 for l in lines if l.startswith("f "))
            head = f"# OpenSubdiv 3.5 catmark, tri_quads.obj, level {level}, triangles {rule}: " \
                   f"osd_opts tri_quads.obj {level} OUT --triangles {rule}"
            body = [l for l in lines if l.startswith("v ")]
            name = os.path.join(d, f"tri_quads.{rule}.L{level}.osd.txt")
            open(name, "w").write("\n".join([head, f"# faces {faces}"] + body) + "\n")
