#!/usr/bin/env python3
"""Writes the crease test meshes (tests/fixtures/creases/*.obj, OpenSubdiv's OBJ tags)
and, given OpenSubdiv's osd_bench (../shared/bench/native/build.sh), its Loop results.

    python3 scripts/crease-fixtures.py [/tmp/subdiv-peers/osd_bench]

Each case CASE.obj gets CASE.OPTS.L<n>.osd.txt: the vertex positions ("v x y z") of
OpenSubdiv 3.5's uniform Loop refinement at level n, written by
`osd_bench CASE.obj n loop OUT [--corners] [--chaikin]` (faces dropped: tests/creases.rs
matches the points as a set, since OpenSubdiv numbers edges differently).
"""
import math, os, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
out = os.path.join(here, "..", "tests", "fixtures", "creases")
os.makedirs(out, exist_ok=True)

def write(name, verts, faces, creases=(), corners=(), note=""):
    with open(os.path.join(out, name + ".obj"), "w") as f:
        f.write(f"# {note}\n# written by scripts/crease-fixtures.py\n")
        for v in verts:
            f.write("v %.9g %.9g %.9g\n" % v)
        for t in faces:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))
        for a, b, s in creases:
            f.write(f"t crease 2/1/0 {a} {b} {s}\n")
        for v, s in corners:
            f.write(f"t corner 1/1/0 {v} {s}\n")

# A: the unit cube, its 12 edges infinitely sharp (face diagonals smooth)
cube_v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
cube_f = [(0,1,3),(0,3,2),(4,6,7),(4,7,5),(0,4,5),(0,5,1),(2,3,7),(2,7,6),(0,2,6),(0,6,4),(1,5,7),(1,7,3)]
def cube_edges():
    es = set()
    for t in cube_f:
        for i in range(3):
            a, b = sorted((t[i], t[(i + 1) % 3]))
            d = sum(abs(cube_v[a][k] - cube_v[b][k]) for k in range(3))
            if d == 1:
                es.add((a, b))
    return sorted(es)
write("cube_sharp", cube_v, cube_f, [(a, b, 10) for a, b in cube_edges()], note="cube, 12 edges infinitely sharp")

# B: tetrahedron with semi-sharp edges and a semi-sharp corner
tet_v = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]
tet_f = [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)]
write("tet_semi", tet_v, tet_f, [(0, 1, 1.5), (0, 2, 2.7), (1, 2, 0.4)], [(3, 1.2)],
      note="tetrahedron, semi-sharp edges 1.5, 2.7, 0.4 and a corner of 1.2")

# C: icosphere (1 level) with a closed crease loop, a dart and a semi-sharp edge
def icosphere1():
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0,11,5),(0,5,1),(0,1,7),(0,7,10),(0,10,11),(1,5,9),(5,11,4),(11,10,2),(10,7,6),(7,1,8),
         (3,9,4),(3,4,2),(3,2,6),(3,6,8),(3,8,9),(4,9,5),(2,4,11),(6,2,10),(8,6,7),(9,8,1)]
    mids = {}
    def mid(a, b):
        k = (min(a, b), max(a, b))
        if k not in mids:
            p = [(v[a][i] + v[b][i]) / 2 for i in range(3)]
            l = math.sqrt(sum(x * x for x in p))
            v.append(tuple(x / l for x in p)); mids[k] = len(v) - 1
        return mids[k]
    g = []
    for a, b, c in f:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        g += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    return v, g
ico_v, ico_f = icosphere1()
def edges_of(faces):
    es = set()
    for t in faces:
        for i in range(3):
            es.add(tuple(sorted((t[i], t[(i + 1) % 3]))))
    return es
ico_e = edges_of(ico_f)
# the loop: edges whose both ends have |z| small, i.e. the equator-ish band z ~ 0
eq = [e for e in sorted(ico_e) if abs(ico_v[e[0]][2]) < 0.01 and abs(ico_v[e[1]][2]) < 0.01]
top = max(range(len(ico_v)), key=lambda i: ico_v[i][2])
dart = sorted(e for e in ico_e if top in e)[0]
other = sorted(e for e in ico_e if top in e)[2]
write("ico_crease", ico_v, ico_f, [(a, b, 2) for a, b in eq] + [(dart[0], dart[1], 10), (other[0], other[1], 0.7)],
      note="icosphere, a crease loop of sharpness 2, an infinitely sharp dart, a 0.7 edge")

# D: an open wavy grid: boundary corners, an interior sharp line, a semi-sharp line ending inside
n = 5
grid_v = [(i, j, 0.3 * math.sin(i) * math.cos(0.7 * j)) for j in range(n + 1) for i in range(n + 1)]
vid = lambda i, j: j * (n + 1) + i
grid_f = []
for j in range(n):
    for i in range(n):
        grid_f += [(vid(i, j), vid(i + 1, j), vid(i + 1, j + 1)), (vid(i, j), vid(i + 1, j + 1), vid(i, j + 1))]
line = [(vid(2, j), vid(2, j + 1), 10) for j in range(n)]
semi = [(vid(i, 3), vid(i + 1, 3), 1.3) for i in range(2, 4)]
write("grid_open", grid_v, grid_f, line + semi, note="open 5x5 grid, a sharp line across, a 1.3 line ending inside")

# E: a coarse torus with a semi-sharp loop around the tube
R, r, nu, nv = 1.0, 0.4, 8, 6
tor_v = [((R + r * math.cos(2 * math.pi * b / nv)) * math.cos(2 * math.pi * a / nu),
          (R + r * math.cos(2 * math.pi * b / nv)) * math.sin(2 * math.pi * a / nu),
          r * math.sin(2 * math.pi * b / nv)) for a in range(nu) for b in range(nv)]
tid = lambda a, b: (a % nu) * nv + (b % nv)
tor_f = []
for a in range(nu):
    for b in range(nv):
        tor_f += [(tid(a, b), tid(a + 1, b), tid(a + 1, b + 1)), (tid(a, b), tid(a + 1, b + 1), tid(a, b + 1))]
loop = [(tid(0, b), tid(0, b + 1), 3.2) for b in range(nv)]
write("torus_semi", tor_v, tor_f, loop, note="8x6 torus, a loop of sharpness 3.2 around the tube")

# which options and levels each case is compared at
CASES = [("cube_sharp", [""], 3), ("tet_semi", ["", "--chaikin"], 3), ("ico_crease", ["", "--chaikin"], 2),
         ("grid_open", ["", "--corners"], 3), ("torus_semi", ["", "--chaikin"], 2)]
if len(sys.argv) > 1:
    osd = sys.argv[1]
    for name, opts, levels in CASES:
        for opt in opts:
            for lv in range(1, levels + 1):
                tag = (opt.strip("-") or "uniform")
                res = os.path.join(out, f"{name}.{tag}.L{lv}.osd.txt")
                tmp = res + ".tmp.obj"
                cmd = [osd, os.path.join(out, name + ".obj"), str(lv), "loop", tmp] + ([opt] if opt else [])
                subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
                with open(tmp) as f, open(res, "w") as g:
                    g.write(f"# OpenSubdiv 3.5 Loop, {name}.obj, level {lv}, {tag}: osd_bench {name}.obj {lv} loop OUT {opt}\n")
                    for l in f:
                        if l.startswith("v "):
                            g.write(l)
                os.remove(tmp)
