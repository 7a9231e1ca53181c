#!/usr/bin/env python3
"""Writes the hole fixtures and, given OpenSubdiv's osd_opts
(../shared/bench/native/osd_opts.cpp: g++ -O2 -std=c++17 osd_opts.cpp -o osd_opts -losdCPU),
its results:

    python3 scripts/hole-fixtures.py /tmp/peers/osd_opts

An open 6x6 grid with a semi-sharp crease and two faces tagged as holes (OpenSubdiv's
`t hole`), as quads (tests/fixtures/catmark/holes.obj, Catmull-Clark) and as triangles
(tests/fixtures/creases/holes.obj, Loop). Each gets holes.{edge,none}.L{1,2}.osd.txt:
"# faces N", the last level's "v x y z" lines and its "f" lines (faces of holes left
out, as OpenSubdiv's TopologyLevel::IsFaceHole says), written by
`osd_opts holes.obj LEVELS OUT --scheme S --boundary B` in double precision.
"""
import os, random, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
N = 6

def vid(i, j):
    return j * N + i

def grid(quads):
    random.seed(11)
    out = ["# holes: written by scripts/hole-fixtures.py"]
    for j in range(N):
        for i in range(N):
            out.append(f"v {i} {j} {random.uniform(-0.2, 0.2):.6f}")
    for j in range(N - 1):
        for i in range(N - 1):
            a, b, c, d = vid(i, j) + 1, vid(i + 1, j) + 1, vid(i + 1, j + 1) + 1, vid(i, j + 1) + 1
            out += [f"f {a} {b} {c} {d}"] if quads else [f"f {a} {b} {c}", f"f {a} {c} {d}"]
    out.append(f"t crease 2/1/0 {vid(1, 2)} {vid(2, 2)} 2.0")
    # two inner faces, one of them at the border (0-based face ids)
    out.append("t hole 2/0/0 7 12" if quads else "t hole 3/0/0 14 15 24")
    return "\n".join(out) + "\n"

def main():
    osd = sys.argv[1] if len(sys.argv) > 1 else None
    for folder, scheme, quads in (("catmark", "catmark", True), ("creases", "loop", False)):
        d = os.path.join(here, "..", "tests", "fixtures", folder)
        obj = os.path.join(d, "holes.obj")
        open(obj, "w").write(grid(quads))
        if not osd:
            continue
        for boundary in ("edge", "none"):
            for level in (1, 2):
                tmp = os.path.join(d, ".osd.tmp.obj")
                subprocess.run([osd, obj, str(level), tmp, "--scheme", scheme, "--boundary", boundary],
                               check=True, stdout=subprocess.DEVNULL)
                lines = open(tmp).read().splitlines()
                os.remove(tmp)
                faces = [l for l in lines if l.startswith("f ")]
                head = f"# OpenSubdiv 3.5 {scheme}, holes.obj, level {level}, boundary {boundary}: " \
                       f"osd_opts holes.obj {level} OUT --scheme {scheme} --boundary {boundary}"
                body = [l for l in lines if l.startswith("v ")] + faces
                name = os.path.join(d, f"holes.{boundary}.L{level}.osd.txt")
                open(name, "w").write("\n".join([head, f"# faces {len(faces)}"] + body) + "\n")

main()
