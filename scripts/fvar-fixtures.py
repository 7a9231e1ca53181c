#!/usr/bin/env python3
"""Writes the face-varying fixtures and, given OpenSubdiv's osd_opts
(../shared/bench/native/osd_opts.cpp: g++ -O2 -std=c++17 osd_opts.cpp -o osd_opts -losdCPU),
their results in every FVarLinearInterpolation mode:

    python3 scripts/fvar-fixtures.py /tmp/peers/osd_opts

A 4x4 quad grid with three UV charts meeting at one inner vertex (a junction of three
charts), a seam cut from the border ending inside a chart (a dart) and open chart
borders, the values perturbed so that no rule reproduces them by chance: as quads
(tests/fixtures/catmark/fvar.obj, Catmull-Clark) and as triangles
(tests/fixtures/creases/fvar.obj, Loop). Each gets fvar.MODE.L2.osd.obj, the last
level's v, vt and f v/vt lines as `osd_opts fvar.obj 2 OUT --scheme S --fvar MODE`
wrote them (double precision).
"""
import os, random, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
N = 5
MODES = ("none", "corners-only", "corners-plus1", "corners-plus2", "boundaries", "all")

def vid(i, j):
    return j * N + i

def layout():
    random.seed(2)
    verts = [(i, j, random.uniform(-0.2, 0.2)) for j in range(N) for i in range(N)]
    vts, index, faces = [], {}, []
    random.seed(9)
    for j in range(N - 1):
        for i in range(N - 1):
            f = [vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)]
            chart = "A" if (i < 2 and j < 2) else ("B" if j < 2 else "C")
            side = "up" if (chart == "C" and j >= 3) else "dn"
            corners = []
            for v in f:
                x, y, _ = verts[v]
                key = (chart, v, side) if (chart == "C" and (x, y) == (0, 3)) else (chart, v)
                if key not in index:
                    off = {"A": (0, 0), "B": (0.5, 0.02), "C": (0.03, 0.5)}[chart]
                    index[key] = len(vts)
                    vts.append((x * 0.11 + off[0] + random.uniform(-0.02, 0.02),
                                y * 0.11 + off[1] + random.uniform(-0.02, 0.02)))
                corners.append(index[key])
            faces.append(list(zip(f, corners)))
    return verts, vts, faces

def obj(quads):
    verts, vts, faces = layout()
    out = ["# three UV charts, a dart, open chart borders: written by scripts/fvar-fixtures.py"]
    out += ["v %d %d %.6f" % p for p in verts]
    out += ["vt %.6f %.6f" % t for t in vts]
    for f in faces:
        tri = [f] if quads else [[f[0], f[1], f[2]], [f[0], f[2], f[3]]]
        out += ["f " + " ".join(f"{v + 1}/{t + 1}" for v, t in face) for face in tri]
    return "\n".join(out) + "\n"

def main():
    osd = sys.argv[1] if len(sys.argv) > 1 else None
    for folder, scheme, quads in (("catmark", "catmark", True), ("creases", "loop", False)):
        d = os.path.join(here, "..", "tests", "fixtures", folder)
        path = os.path.join(d, "fvar.obj")
        open(path, "w").write(obj(quads))
        for mode in MODES if osd else ():
            out = os.path.join(d, f"fvar.{mode}.L2.osd.obj")
            subprocess.run([osd, path, "2", out, "--scheme", scheme, "--fvar", mode], check=True, stdout=subprocess.DEVNULL)

main()
