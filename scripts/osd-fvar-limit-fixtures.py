#!/usr/bin/env python3
"""Writes the Catmull-Clark face-varying test meshes (tests/fixtures/catmark/{cube,grid,ngons}_uv.obj:
polygons with "vt" texture coordinates and "f v/vt" corners) and, given OpenSubdiv's
osd_fvar_limit (scripts/osd-fvar-limit.cpp, built with
`g++ -O2 -std=c++17 scripts/osd-fvar-limit.cpp -losdCPU -o /tmp/peers/osd_fvar_limit` against
Debian's libosd-dev 3.5.0), OpenSubdiv 3.5's face-varying and limit results:

    python3 scripts/osd-fvar-limit-fixtures.py [/tmp/peers/osd_fvar_limit]

Face-varying: CASE.uv.FVAR[.vtxcorners|.chaikin].L<n>.osd.txt, written by
`osd_fvar_limit uv CASE.obj n FVAR OUT [--corners] [--chaikin]`, FVAR "all" = FVAR_LINEAR_ALL,
"corners" = FVAR_LINEAR_CORNERS_ONLY, ".vtxcorners" = VTX_BOUNDARY_EDGE_AND_CORNER (else
EDGE_ONLY), ".chaikin" = CREASE_CHAIKIN (else uniform creasing; cube_creases_uv.obj carries
cube_creases.obj's tags); the UVs refined level by level with PrimvarRefiner::InterpolateFaceVarying. Lines:
"# faces F" (faces at level n), then per face at level n (OpenSubdiv's order) and per corner
(in order) "c x y z u v": the corner's refined position and its face-varying value.

Limit: CASE.limit.OPTS.L<n>.osd.txt for the existing catmark meshes (cube, ngons, grid,
grid_dart, cube_creases, written by scripts/catmark-fixtures.py), written by
`osd_fvar_limit limit CASE.obj n OUT [--corners] [--chaikin] --e0`: uniform refinement to n,
then PrimvarRefiner::Limit(src, pos, tan1, tan2) on level n. Lines: "# vertices N", then per
vertex at level n (OpenSubdiv's order) "l px py pz lx ly lz tx ty tz sx sy sz ex ey ez": the
refined position, the limit position, tan1 and tan2 as OpenSubdiv returns them (not
normalized), and the refined position of the other end of the vertex's edge 0 in OpenSubdiv's
vertex-edge order (the frame of its tangent masks).

Every fixture starts with one comment line naming the command (and, for limit, how many
semi-sharp edges and vertices remain at level n: OpenSubdiv's Limit takes those as infinitely
sharp). Numbers are %.9g of OpenSubdiv's float results.
"""
import math, os, subprocess, sys

here = os.path.dirname(os.path.abspath(__file__))
out = os.path.join(here, "..", "tests", "fixtures", "catmark")
os.makedirs(out, exist_ok=True)


def write_uv(name, verts, uvs, faces, note=""):
    """faces: lists of (vertex, uv) index pairs, 0-based."""
    with open(os.path.join(out, name + ".obj"), "w") as f:
        f.write(f"# {note}\n# written by scripts/osd-fvar-limit-fixtures.py\n")
        for v in verts:
            f.write("v %.9g %.9g %.9g\n" % tuple(v))
        for t in uvs:
            f.write("vt %.9g %.9g\n" % tuple(t))
        for face in faces:
            f.write("f " + " ".join(f"{v + 1}/{t + 1}" for v, t in face) + "\n")
    # every face's UV polygon turns counter-clockwise (no flipped charts)
    for face in faces:
        p = [uvs[t] for _, t in face]
        area = sum(p[i][0] * p[(i + 1) % len(p)][1] - p[(i + 1) % len(p)][0] * p[i][1] for i in range(len(p)))
        assert area > 0, (name, face)


# A: the unit cube (as cube.obj) with a cross-shaped unfolding on a 4 x 3 grid of cells:
# the top (z=1) in the middle, y=0 below it, y=1 above it, x=0 left, x=1 and then z=0 right.
# Vertices 1, 3, 5, 7 (the top) keep one UV; 4 and 6 get two, 0 and 2 three.
cube_v = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
cube_f = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
unfold = [  # per face: vertex -> cell-grid point
    lambda x, y, z: (z, 1 + y),             # x=0: left of the top
    lambda x, y, z: (2 + (1 - z), 1 + y),   # x=1: right of the top
    lambda x, y, z: (1 + x, z),             # y=0: below
    lambda x, y, z: (1 + x, 2 + (1 - z)),   # y=1: above
    lambda x, y, z: (3 + (1 - x), 1 + y),   # z=0: right of x=1
    lambda x, y, z: (1 + x, 1 + y),         # z=1: the top, in the middle
]
cube_uv, cube_uvf = [], []
for face, g in zip(cube_f, unfold):
    corners = []
    for v in face:
        gx, gy = g(*cube_v[v])
        t = (gx / 4.0, gy / 3.0)
        if t not in cube_uv:
            cube_uv.append(t)
        corners.append((v, cube_uv.index(t)))
    cube_uvf.append(corners)
assert len(cube_uv) == 14
write_uv("cube_uv", cube_v, cube_uv, cube_uvf,
         note="the quad cube with a cross-shaped UV unfolding: seams, 1 to 3 UVs a vertex")

# B: an open 3 x 3 quad grid, vertex (1, 1) raised: UV = (x, y) / 3, one UV a vertex
grid_v = [(i, j, 0.5 if (i, j) == (1, 1) else 0.0) for j in range(4) for i in range(4)]
grid_uv = [(i / 3.0, j / 3.0) for j in range(4) for i in range(4)]
grid_f = [[(k, k) for k in (j * 4 + i, j * 4 + i + 1, (j + 1) * 4 + i + 1, (j + 1) * 4 + i)]
          for j in range(3) for i in range(3)]
write_uv("grid_uv", grid_v, grid_uv, grid_f,
         note="an open 3 x 3 quad grid, one interior vertex raised; UV = xy / 3")

# C: ngons.obj (a hexagonal prism, top hexagon, bottom triangle + pentagon, six side quads)
# with the sides as a strip u = k/6 (a seam between k = 6 and k = 0), the top hexagon and the
# bottom pair as discs: vertices 0 and 6 get three UVs, the others two.
hexv = [(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3), 0.0) for k in range(6)]
ngon_v = hexv + [(x, y, 1.0) for (x, y, _) in hexv]
ngon_f = [tuple(range(6, 12)), (2, 1, 0), (0, 5, 4, 3, 2)]
ngon_f += [(k, (k + 1) % 6, 6 + (k + 1) % 6, 6 + k) for k in range(6)]
with open(os.path.join(out, "ngons.obj")) as f:  # the same mesh as ngons.obj
    assert [tuple(int(i) - 1 for i in l.split()[1:]) for l in f if l.startswith("f ")] == ngon_f
ngon_uv = [(k / 6.0, 0.0) for k in range(7)] + [(k / 6.0, 0.5) for k in range(7)]   # strip
ngon_uv += [(0.25 + 0.2 * x, 0.75 + 0.2 * y) for (x, y, _) in hexv]                  # top disc
ngon_uv += [(0.75 + 0.2 * x, 0.75 - 0.2 * y) for (x, y, _) in hexv]                  # bottom disc
ngon_uvf = [[(v, 14 + (v - 6)) for v in ngon_f[0]]]
ngon_uvf += [[(v, 20 + v) for v in face] for face in ngon_f[1:3]]
for k in range(6):
    ngon_uvf.append([(k, k), ((k + 1) % 6, k + 1), (6 + (k + 1) % 6, 7 + k + 1), (6 + k, 7 + k)])
write_uv("ngons_uv", ngon_v, ngon_uv, ngon_uvf,
         note="ngons.obj with a UV strip round the sides and two discs: seams, faces of 3 to 6")

# D: cube_uv's unfolding with cube_creases.obj's tags (infinite and semi-sharp creases, a
# semi-sharp corner): the mesh's sharpness through the face-varying rules
with open(os.path.join(out, "cube_uv.obj")) as f:
    body = [l for l in f if not l.startswith("#")]
with open(os.path.join(out, "cube_creases.obj")) as f:
    tags = [l for l in f if l.startswith("t ")]
with open(os.path.join(out, "cube_creases_uv.obj"), "w") as f:
    f.write("# cube_uv.obj's cross unfolding with cube_creases.obj's creases and corner\n")
    f.write("# written by scripts/osd-fvar-limit-fixtures.py\n")
    f.writelines(body + tags)

uv_cases = [  # (case, fvar, flags, suffix, levels)
    ("cube_uv", "all", [], "", [2]),
    ("cube_uv", "corners", [], "", [2]),
    ("grid_uv", "all", [], "", [2]),
    ("grid_uv", "corners", [], "", [2]),
    ("grid_uv", "corners", ["--corners"], ".vtxcorners", [2]),
    ("ngons_uv", "all", [], "", [2]),
    ("ngons_uv", "corners", [], "", [2]),
    ("cube_creases_uv", "all", [], "", [2]),
    ("cube_creases_uv", "corners", [], "", [2]),
    ("cube_creases_uv", "corners", ["--chaikin"], ".chaikin", [3]),
]
limit_cases = [  # (case, opts, flags, levels)
    ("cube", "uniform", [], [1, 2]),
    ("ngons", "uniform", [], [1]),
    ("grid", "uniform", [], [1]),
    ("grid", "corners", ["--corners"], [1]),
    ("grid_dart", "uniform", [], [1]),
    ("cube_creases", "uniform", [], [2, 3]),
    ("cube_creases", "chaikin", ["--chaikin"], [3]),
]


def run(cmd, dst, head):
    tmp = dst + ".tmp"
    r = subprocess.run([tmp if a == "OUT" else a for a in cmd], check=True, capture_output=True, text=True)
    with open(tmp) as f, open(dst, "w") as g:
        g.write(head + "\n")
        g.write(f.read())
    os.remove(tmp)
    return r.stdout.strip()


if len(sys.argv) > 1:
    osd = sys.argv[1]
    for name, fvar, flags, suffix, levels in uv_cases:
        for n in levels:
            dst = os.path.join(out, f"{name}.uv.{fvar}{suffix}.L{n}.osd.txt")
            cmd = [osd, "uv", os.path.join(out, name + ".obj"), str(n), fvar, "OUT"] + flags
            run(cmd, dst, f"# OpenSubdiv 3.5 catmark face-varying, {name}.obj, level {n}: "
                          f"osd_fvar_limit uv {name}.obj {n} {fvar} OUT {' '.join(flags)}".rstrip())
    for name, opts, flags, levels in limit_cases:
        for n in levels:
            dst = os.path.join(out, f"{name}.limit.{opts}.L{n}.osd.txt")
            cmd = [osd, "limit", os.path.join(out, name + ".obj"), str(n), "OUT"] + flags + ["--e0"]
            # the semi-sharp count is only known after the run: write, then prepend the line
            note = run(cmd, dst, "")
            with open(dst) as f:
                body = f.read()[1:]
            with open(dst, "w") as f:
                f.write(f"# OpenSubdiv 3.5 catmark limit, {name}.obj, level {n}, {opts}: "
                        f"osd_fvar_limit limit {name}.obj {n} OUT {' '.join(flags + ['--e0'])} ({note})\n")
                f.write(body)
    print("wrote OpenSubdiv's face-varying and limit results into", out)
