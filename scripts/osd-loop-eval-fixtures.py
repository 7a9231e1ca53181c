#!/usr/bin/env python3
"""Writes the Loop limit-evaluation fixtures tests/fixtures/loop_eval/ with OpenSubdiv 3.5's
osd_loop_eval (scripts/osd-loop-eval.cpp, built with
`g++ -O2 -std=c++17 scripts/osd-loop-eval.cpp -losdCPU -o /tmp/peers/osd_loop_eval` against
Debian's libosd-dev 3.5.0):

    python3 scripts/osd-loop-eval-fixtures.py [/tmp/peers/osd_loop_eval]

Cases (points only on REGULAR faces, i.e. faces whose three vertices are interior with
valence 6 or on the border with 4 neighbours (three faces), where OpenSubdiv's patch is one
quartic box spline, PatchDescriptor::LOOP, at depth 0, with phantom points beyond a border):
  torus          models/torus.obj (bundled, 512 vertices, 1024 triangles, all valence 6; not copied)
  torus_sheared  a 12 x 9 torus grid with R = 2, r = 0.6, the rows sheared by a quarter cell
                 per ring and the vertices jittered (fixed seed): all valence 6, uneven triangles
  icosphere      an icosahedron split 1:4 twice, projected on the ellipsoid with semi-axes
                 (1.3, 1, 0.8) and jittered: 12 valence-5 vertices (the surface is irregular),
                 points only on the 260 of 320 faces that have no valence-5 vertex
  open_grid      a 9 x 7 vertex grid, triangulated with every diagonal the same way, bumped
                 and jittered: an open mesh whose border vertices have 4 neighbours (but the
                 corners), points on the faces without a corner vertex (the border faces
                 among them are OpenSubdiv's regular boundary patches)
For each: CASE.obj (generated cases only), CASE.points.txt (200 points "f u v", fixed seed,
uniform in the triangle, u, v, 1-u-v > 1e-3 and none of them a multiple of 1/1024), and
CASE.osd.txt, written by `osd_loop_eval eval MESH CASE.points.txt OUT` (isolation level 4):
"# regular R irregular I", then per point "x y z dux duy duz dvx dvy dvz duux duuy duuz duvx
duvy duvz dvvx dvvy dvvz" (%.17g of OpenSubdiv's double results; derivatives with respect to
the barycentric (u, v): point = (1-u-v) c0 + u c1 + v c2, c0 c1 c2 the face's corners as
listed). Every fixture starts with one comment line naming the command that made it.

Before writing, the script checks (and prints): the (u, v) convention (OpenSubdiv's values at
(0,0), (1,0), (0,1) of every face against the Loop limit positions of its corners c0, c1, c2,
from both osd_loop_eval limit (PrimvarRefiner::Limit) and the limit mask
(1 - n chi) v + chi sum(neighbours), chi = 1/(n + 3/(8 beta))), and the derivatives against
central differences of the positions / first derivatives (h = 1e-5).
"""
import math, os, random, subprocess, sys, tempfile

here = os.path.dirname(os.path.abspath(__file__))
root = os.path.normpath(os.path.join(here, ".."))
outdir_rel = os.path.join("tests", "fixtures", "loop_eval")
outdir = os.path.join(root, outdir_rel)
exe = sys.argv[1] if len(sys.argv) > 1 else "/tmp/peers/osd_loop_eval"
exe_name = "osd_loop_eval"
ORIGIN = "OpenSubdiv 3.5 (Debian libosd-dev)"
NPTS = 200
LEVEL = 4


def read_obj(path):
    verts, faces = [], []
    for l in open(path):
        t = l.split()
        if not t:
            continue
        if t[0] == "v":
            verts.append(tuple(float(x) for x in t[1:4]))
        elif t[0] == "f":
            faces.append(tuple(int(x.split("/")[0]) - 1 for x in t[1:]))
    return verts, faces


def write_obj(path, note, verts, faces):
    with open(path, "w") as f:
        f.write(f"# python3 scripts/osd-loop-eval-fixtures.py: input of {exe_name} ({ORIGIN})\n# {note}\n")
        for v in verts:
            f.write("v %.17g %.17g %.17g\n" % v)
        for fc in faces:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in fc))


def neighbours(verts, faces):
    """1-ring of each vertex and the border neighbours of each border vertex; asserts a
    consistently oriented manifold (each directed edge once, at most two faces an edge)."""
    edges = {}
    for fc in faces:
        for k in range(3):
            a, b = fc[k], fc[(k + 1) % 3]
            edges[(a, b)] = edges.get((a, b), 0) + 1
    assert all(c == 1 for c in edges.values()), "not a consistently oriented manifold"
    nb = [set() for _ in verts]
    border = [[] for _ in verts]
    for a, b in edges:
        nb[a].add(b)
        nb[b].add(a)
        if (b, a) not in edges:
            border[a].append(b)
            border[b].append(a)
    return nb, border


def open_grid():
    rng = random.Random(4242)
    n, m = 9, 7
    verts = []
    for j in range(m):
        for i in range(n):
            x, y = i + rng.uniform(-0.15, 0.15), j + rng.uniform(-0.15, 0.15)
            verts.append((x, y, 0.6 * math.sin(0.7 * x) * math.cos(0.9 * y) + rng.uniform(-0.05, 0.05)))
    idx = lambda i, j: j * n + i
    faces = []
    for j in range(m - 1):
        for i in range(n - 1):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            faces += [(a, b, c), (a, c, d)]
    return verts, faces


def torus_sheared():
    rng = random.Random(20240611)
    n, m, R, r = 12, 9, 2.0, 0.6
    verts = []
    for i in range(n):          # around the big circle
        for j in range(m):      # around the tube, sheared by a quarter cell per ring
            a = 2 * math.pi * (i + rng.uniform(-0.12, 0.12)) / n
            b = 2 * math.pi * (j + 0.25 * i + rng.uniform(-0.12, 0.12)) / m
            rr = r * (1 + rng.uniform(-0.08, 0.08))
            verts.append(((R + rr * math.cos(b)) * math.cos(a), (R + rr * math.cos(b)) * math.sin(a), rr * math.sin(b)))
    # the shear is geometric only: ring i's vertex j sits at tube angle j + i/4 cells, so ring
    # n-1 = 11 (at j + 2.75) connects to ring 0 shifted by 3 cells (0.25 n = 3) to close up
    idx = lambda i, j: (i % n) * m + (j % m)
    faces = []
    for i in range(n):
        s = 3 if i == n - 1 else 0
        for j in range(m):
            a, d = idx(i, j), idx(i, j + 1)
            b, c = idx(i + 1, j + s), idx(i + 1, j + 1 + s)
            faces += [(a, b, c), (a, c, d)]
    return verts, faces


def icosphere():
    rng = random.Random(77)
    t = (1 + 5 ** 0.5) / 2
    verts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
             (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
             (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    norm = lambda p: tuple(x / math.sqrt(sum(y * y for y in p)) for x in p)
    verts = [norm(v) for v in verts]
    for _ in range(2):
        mid = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                mid[key] = len(verts)
                verts.append(norm(tuple((x + y) / 2 for x, y in zip(verts[a], verts[b]))))
            return mid[key]
        nf = []
        for a, b, c in faces:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = nf
    verts = [(1.3 * x * (1 + rng.uniform(-0.04, 0.04)), y * (1 + rng.uniform(-0.04, 0.04)),
              0.8 * z * (1 + rng.uniform(-0.04, 0.04))) for x, y, z in verts]
    return verts, faces


def limit_positions(verts, nb, border):
    out = []
    for i, p in enumerate(verts):
        if border[i]:
            a, b = border[i]
            out.append(tuple(2 / 3 * p[k] + (verts[a][k] + verts[b][k]) / 6 for k in range(3)))
            continue
        n = len(nb[i])
        beta = (5 / 8 - (3 / 8 + math.cos(2 * math.pi / n) / 4) ** 2) / n
        chi = 1 / (n + 3 / (8 * beta))
        out.append(tuple((1 - n * chi) * p[a] + chi * sum(verts[j][a] for j in nb[i]) for a in range(3)))
    return out


def run_eval(mesh, pts, level=LEVEL):
    with tempfile.TemporaryDirectory() as d:
        pf, of = os.path.join(d, "p.txt"), os.path.join(d, "o.txt")
        with open(pf, "w") as f:
            for fi, u, v in pts:
                f.write("%d %.17g %.17g\n" % (fi, u, v))
        subprocess.check_call([exe, "eval", mesh, pf, of, "--level", str(level)], cwd=root)
        lines = open(of).read().splitlines()
    assert lines[0].startswith("# regular ")
    return lines[0], [list(map(float, l.split())) for l in lines[1:]]


def check(case, mesh, verts, faces, nb, regular_faces, pts):
    # (u, v) convention: corners of every face against the limit positions (on an open mesh
    # only the regular faces: OpenSubdiv's end caps at irregular border vertices approximate)
    checked = regular_faces if any(nb[1]) else range(len(faces))
    corner_pts = [(fi, u, v) for fi in range(len(faces)) for u, v in ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0))]
    _, rows = run_eval(mesh, corner_pts)
    with tempfile.TemporaryDirectory() as d:
        lf = os.path.join(d, "l.txt")
        subprocess.check_call([exe, "limit", mesh, lf], cwd=root)
        osd_lim = [tuple(map(float, l.split())) for l in open(lf)]
    mask_lim = limit_positions(verts, nb[0], nb[1])
    e_osd = e_mask = 0.0
    for fi in checked:
        fc = faces[fi]
        for k in range(3):
            p = rows[3 * fi + k][:3]
            e_osd = max(e_osd, max(abs(a - b) for a, b in zip(p, osd_lim[fc[k]])))
            e_mask = max(e_mask, max(abs(a - b) for a, b in zip(p, mask_lim[fc[k]])))
    print(f"{case}: corners (0,0),(1,0),(0,1) of {len(checked)} of {len(faces)} faces vs limit of c0,c1,c2: "
          f"max |diff| {e_osd:.3g} (PrimvarRefiner::Limit), {e_mask:.3g} (limit mask formula)")
    assert e_osd < 1e-12 and e_mask < 1e-12
    # derivatives against central differences
    h = 1e-5
    fd_pts = []
    for fi, u, v in pts:
        fd_pts += [(fi, u + h, v), (fi, u - h, v), (fi, u, v + h), (fi, u, v - h)]
    _, base = run_eval(mesh, pts)
    _, fd = run_eval(mesh, fd_pts)
    e1 = e2 = 0.0
    for k, r in enumerate(base):
        up, um, vp, vm = fd[4 * k:4 * k + 4]
        scale1 = max(1e-300, max(abs(x) for x in r[3:9]))
        scale2 = max(1e-300, max(abs(x) for x in r[9:18]))
        for a in range(3):
            e1 = max(e1, abs((up[a] - um[a]) / (2 * h) - r[3 + a]) / scale1)
            e1 = max(e1, abs((vp[a] - vm[a]) / (2 * h) - r[6 + a]) / scale1)
            e2 = max(e2, abs((up[3 + a] - um[3 + a]) / (2 * h) - r[9 + a]) / scale2)   # duu
            e2 = max(e2, abs((vp[3 + a] - vm[3 + a]) / (2 * h) - r[12 + a]) / scale2)  # duv = d/dv du
            e2 = max(e2, abs((up[6 + a] - um[6 + a]) / (2 * h) - r[12 + a]) / scale2)  # duv = d/du dv
            e2 = max(e2, abs((vp[6 + a] - vm[6 + a]) / (2 * h) - r[15 + a]) / scale2)  # dvv
    print(f"{case}: {len(pts)} points, central differences h = {h}: max relative error "
          f"first derivatives {e1:.3g}, second derivatives {e2:.3g}")
    assert e1 < 1e-6 and e2 < 1e-6


def make_points(seed, faces_ok):
    rng = random.Random(seed)
    pts = []
    while len(pts) < NPTS:
        fi = rng.choice(faces_ok)
        u, v = rng.random(), rng.random()
        if u + v > 1:
            u, v = 1 - u, 1 - v
        w = 1 - u - v
        if min(u, v, w) < 1e-3 or any((x * 1024).is_integer() for x in (u, v)):
            continue
        pts.append((fi, u, v))
    return pts


def main():
    os.makedirs(outdir, exist_ok=True)
    cases = [("torus", "models/torus.obj", None, 1),
             ("torus_sheared", None, torus_sheared(), 2),
             ("icosphere", None, icosphere(), 3),
             ("open_grid", None, open_grid(), 4)]
    for case, mesh, gen, seed in cases:
        if gen is not None:
            verts, faces = gen
            mesh = os.path.join(outdir_rel, case + ".obj")
            write_obj(os.path.join(root, mesh),
                      {"torus_sheared": "a 12 x 9 triangulated torus, R = 2, r = 0.6, rings sheared by a quarter "
                                        "cell and jittered: closed, every vertex valence 6",
                       "icosphere": "an icosahedron split 1:4 twice, on the ellipsoid (1.3, 1, 0.8), jittered: "
                                    "closed, 12 valence-5 vertices, the rest valence 6",
                       "open_grid": "a 9 x 7 grid, every diagonal the same way, bumped and jittered: open, "
                                    "interior valence 6, border vertices 4 neighbours but the corners"}[case],
                      verts, faces)
        verts, faces = read_obj(os.path.join(root, mesh))
        nb = neighbours(verts, faces)
        val = [len(s) for s in nb[0]]
        ok = [val[v] == (4 if nb[1][v] else 6) for v in range(len(verts))]
        regular = [fi for fi, fc in enumerate(faces) if all(ok[c] for c in fc)]
        print(f"{case}: {len(verts)} vertices, {len(faces)} faces, valences "
              f"{sorted(set(val))}, {len(regular)} regular faces")
        pts = make_points(seed, regular)
        check(case, mesh, verts, faces, nb, regular, pts)

        pts_rel = os.path.join(outdir_rel, case + ".points.txt")
        osd_rel = os.path.join(outdir_rel, case + ".osd.txt")
        with open(os.path.join(root, pts_rel), "w") as f:
            f.write(f"# python3 scripts/osd-loop-eval-fixtures.py: {NPTS} points 'f u v' on regular faces of "
                    f"{mesh} (random.Random({seed})), input of {exe_name} ({ORIGIN})\n")
            for fi, u, v in pts:
                f.write("%d %.17g %.17g\n" % (fi, u, v))
        cmd = [exe, "eval", mesh, pts_rel, osd_rel + ".tmp", "--level", str(LEVEL)]
        subprocess.check_call(cmd, cwd=root)
        body = open(os.path.join(root, osd_rel + ".tmp")).read()
        os.remove(os.path.join(root, osd_rel + ".tmp"))
        assert body.startswith(f"# regular {NPTS} irregular 0\n"), body.splitlines()[0]
        shown = " ".join([exe_name, "eval", mesh, pts_rel, osd_rel, "--level", str(LEVEL)])
        with open(os.path.join(root, osd_rel), "w") as f:
            f.write(f"# {shown}  ({ORIGIN}, scripts/osd-loop-eval.cpp)\n")
            f.write(body)
        for rel in ([mesh] if gen is not None else []) + [pts_rel, osd_rel]:
            size = os.path.getsize(os.path.join(root, rel))
            assert size < 100_000, (rel, size)
            print(f"  wrote {rel} ({size} bytes)")


if __name__ == "__main__":
    main()
