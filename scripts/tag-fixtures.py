#!/usr/bin/env python3
"""Writes tests/fixtures/catmark/tagged.obj, the face-varying layout of fvar.obj (three UV
charts, a dart, open chart borders) with every third quad split into two triangles, a
chain of creases of different sharpness and OpenSubdiv's four option tags (boundary
edge-and-corner, face-varying boundaries, smooth triangles, Chaikin creasing), and, given
OpenSubdiv's osd_opts (../shared/bench/native/osd_opts.cpp, which reads the same tags):

    python3 scripts/tag-fixtures.py /tmp/peers/osd_opts

tagged.L2.osd.obj: `osd_opts tagged.obj 2 OUT` (the options from the tags alone);
tagged.flags.L2.osd.obj: the same with the flags `--boundary edge --fvar all --creasing
uniform --triangles catmark`, which override every tag. Both hold the last level's v, vt
and f v/vt lines as osd_opts wrote them (double precision).
"""
import os, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
d = os.path.join(here, "..", "tests", "fixtures", "catmark")
FLAGS = ["--boundary", "edge", "--fvar", "all", "--creasing", "uniform", "--triangles", "catmark"]

def tagged():
    lines = open(os.path.join(d, "fvar.obj")).read().splitlines()
    out = ["# fvar.obj with triangles, creases and option tags: written by scripts/tag-fixtures.py"]
    k = 0
    for l in lines:
        if l.startswith("#") or l.startswith("t "):
            continue
        if l.startswith("f "):
            c = l.split()[1:]
            if k % 3 == 1:
                out += ["f " + " ".join([c[0], c[1], c[2]]), "f " + " ".join([c[0], c[2], c[3]])]
            else:
                out.append(l)
            k += 1
        else:
            out.append(l)
    # a crease chain along y = 2 whose sharpness changes (Chaikin averages it)
    out += ["t crease 2/1/0 10 11 3", "t crease 2/1/0 11 12 1", "t crease 2/1/0 12 13 2.5",
            "t interpolateboundary 1/0/0 1", "t facevaryinginterpolateboundary 1/0/0 4",
            "t smoothtriangles 0/0/1 smooth", "t creasemethod 0/0/1 chaikin"]
    return "\n".join(out) + "\n"

obj = os.path.join(d, "tagged.obj")
open(obj, "w").write(tagged())
if len(sys.argv) > 1:
    for name, flags in (("tagged.L2.osd.obj", []), ("tagged.flags.L2.osd.obj", FLAGS)):
        out = os.path.join(d, name)
        subprocess.run([sys.argv[1], obj, "2", out] + flags, check=True, stdout=subprocess.DEVNULL)
        body = open(out).read()
        head = f"# OpenSubdiv 3.5 catmark, tagged.obj, level 2: osd_opts tagged.obj 2 OUT {' '.join(flags)}\n"
        open(out, "w").write(head + body)
