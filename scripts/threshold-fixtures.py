#!/usr/bin/env python3
"""Writes the sharpness-threshold fixtures and, given OpenSubdiv's osd_opts
(../shared/bench/native/osd_opts.cpp: g++ -O2 -std=c++17 osd_opts.cpp -o osd_opts -losdCPU),
its results:

    python3 scripts/threshold-fixtures.py /tmp/peers/osd_opts

An open 6x6 grid whose crease paths meet at every threshold Sdc::Crease compares
against: edges of sharpness 0.1, 0.5, 0.7, 1 (the s <= 1 / s < 1 boundary, and
Chaikin's 3/4 s + 1/4 avg - 1 around it), 1.2, 2.5, 9.5 and 10 (infinite), corners
of 0.5 and 1, a semi-sharp tag on a border edge. tests/fixtures/catmark/thresholds.obj holds it as quads (Catmull-Clark),
tests/fixtures/creases/thresholds.obj as triangles (Loop). Each gets
thresholds.{uniform,chaikin}.L{1,2,3}.osd.txt: "# faces N", then the last level's
"v x y z" lines as `osd_opts IN LEVELS OUT --scheme S --creasing C` wrote them
(double precision).
"""
import os, random, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
N = 6

def vid(i, j):
    return j * N + i

def grid(quads):
    random.seed(3)
    out = ["# sharpness thresholds: written by scripts/threshold-fixtures.py"]
    for j in range(N):
        for i in range(N):
            out.append(f"v {i} {j} {random.uniform(-0.2, 0.2):.6f}")
    for j in range(N - 1):
        for i in range(N - 1):
            a, b, c, d = vid(i, j) + 1, vid(i + 1, j) + 1, vid(i + 1, j + 1) + 1, vid(i, j + 1) + 1
            out += [f"f {a} {b} {c} {d}"] if quads else [f"f {a} {b} {c}", f"f {a} {c} {d}"]
    tags = []
    tags += [(vid(i, 2), vid(i + 1, 2), s) for i, s in enumerate([2.5, 1, 2.5, 1, 0.5])]
    tags += [(vid(3, j), vid(3, j + 1), s) for j, s in enumerate([1, 1, 2.5, 1, 0.7])]
    tags += [(vid(i, 4), vid(i + 1, 4), s) for i, s in enumerate([10, 9.5, 1.2, 0.1])]
    # a semi-sharp tag on a border edge (infinitely sharp whatever it says) beside a
    # semi-sharp interior edge: Chaikin's average at their vertex leaves the border out
    tags += [(vid(0, 0), vid(1, 0), 0.5), (vid(1, 0), vid(1, 1), 1.5)]
    out += [f"t crease 2/1/0 {a} {b} {s}" for a, b, s in tags]
    out += [f"t corner 1/1/0 {vid(1, 1)} 1", f"t corner 1/1/0 {vid(4, 1)} 0.5"]
    return "\n".join(out) + "\n"

def main():
    osd = sys.argv[1] if len(sys.argv) > 1 else None
    for folder, scheme, quads in (("catmark", "catmark", True), ("creases", "loop", False)):
        d = os.path.join(here, "..", "tests", "fixtures", folder)
        obj = os.path.join(d, "thresholds.obj")
        open(obj, "w").write(grid(quads))
        if not osd:
            continue
        for creasing in ("uniform", "chaikin"):
            for level in (1, 2, 3):
                tmp = os.path.join(d, ".osd.tmp.obj")
                subprocess.run([osd, obj, str(level), tmp, "--scheme", scheme, "--creasing", creasing],
                               check=True, stdout=subprocess.DEVNULL)
                lines = open(tmp).read().splitlines()
                os.remove(tmp)
                faces = sum(1 for l in lines if l.startswith("f "))
                head = f"# OpenSubdiv 3.5 {scheme}, thresholds.obj, level {level}, {creasing}: " \
                       f"osd_opts thresholds.obj {level} OUT --scheme {scheme} --creasing {creasing}"
                body = [l for l in lines if l.startswith("v ")]
                name = os.path.join(d, f"thresholds.{creasing}.L{level}.osd.txt")
                open(name, "w").write("\n".join([head, f"# faces {faces}"] + body) + "\n")

main()
