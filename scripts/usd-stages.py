#!/usr/bin/env python3
"""Writes the USD stages of tests/fixtures/usd/ that test what a stage says beyond one mesh,
with Pixar's USD (PyPI usd-core: `pip install usd-core`), and, given OpenSubdiv's osd_opts
(../shared/bench/native/osd_opts.cpp, built with `g++ -O2 -std=c++17 osd_opts.cpp -o osd_opts
-losdCPU`), OpenSubdiv's refinement of each prim:

    python3 scripts/usd-stages.py /tmp/peers/osd_opts

- two.usda: /a/loop (subdivisionScheme loop) and /b/smooth (catmullClark,
  triangleSubdivisionRule smooth), the same closed bipyramid of 10 triangles, /b under a
  translate and a rotation. two.a.L2.osd.obj and two.b.L2.osd.obj: each prim's world-space cage
  (from USD's ComputeLocalToWorldTransform) refined twice by osd_opts with the prim's scheme
  and options (--scheme loop; --scheme catmark --triangles smooth).
- none.usda: a box of 24 quads (2 x 2 a side) with subdivisionScheme none.
- mixed.usda: that box (none) beside a catmullClark box under a translate; mixed.cc.L2.osd.obj
  is OpenSubdiv's level 2 of the second.
- seams.usdc: the box again (catmullClark), primvars:st faceVarying and indexed: each side its
  own chart of 3 x 3 values, 54 values for 96 corners. seams-grid.usda: a 6 x 6 grid whose st
  has a seam down its middle column (two charts sharing no value), indexed. seams.L1.osd.obj:
  OpenSubdiv's level 1 of the box with its face-varying values (osd_opts --fvar corners-plus1,
  USD's default), one vt per value.
- animated.usda: a tetrahedron whose points have time samples at 1, 2 and 3 (and a different
  default value), startTimeCode 1, endTimeCode 3, upAxis Z, metersPerUnit 0.01.
- colors.usda: two quads with displayColor per face (uniform), a second prim with one
  constant displayColor and a third with displayColor per vertex.
- instanced.usda: an instanceable reference to a prototype mesh, twice, under two transforms.
- pointinstancer.usda: a PointInstancer with one prototype mesh.
"""
import math, os, subprocess, sys
from pxr import Gf, Sdf, Usd, UsdGeom, Vt

here = os.path.dirname(os.path.abspath(__file__))
d = os.path.join(here, "..", "tests", "fixtures", "usd")
os.makedirs(d, exist_ok=True)
osd = sys.argv[1] if len(sys.argv) > 1 else None


def bipyramid(stage, path, scheme, **tokens):
    m = UsdGeom.Mesh.Define(stage, path)
    ring = [Gf.Vec3f(math.cos(2 * math.pi * k / 5), math.sin(2 * math.pi * k / 5), 0.0) for k in range(5)]
    pts = ring + [Gf.Vec3f(0, 0, 1.2), Gf.Vec3f(0, 0, -0.8)]
    faces = [[k, (k + 1) % 5, 5] for k in range(5)] + [[(k + 1) % 5, k, 6] for k in range(5)]
    m.CreatePointsAttr(pts)
    m.CreateFaceVertexCountsAttr([3] * len(faces))
    m.CreateFaceVertexIndicesAttr([v for f in faces for v in f])
    m.CreateSubdivisionSchemeAttr(scheme)
    for name, value in tokens.items():
        m.GetPrim().GetAttribute(name).Set(value)
    return m


def box(stage, path, scheme, st=False):
    """A cube of side 2 with 2 x 2 quads a side: 26 points, 24 quads; with st, each side a chart."""
    m = UsdGeom.Mesh.Define(stage, path)
    pts, ids = [], {}

    def vid(p):
        if p not in ids:
            ids[p] = len(pts)
            pts.append(Gf.Vec3f(*p))
        return ids[p]

    faces, uvs, uvi = [], [], []
    for axis in range(3):
        for sign in (-1, 1):
            base = len(uvs)
            uvs += [Gf.Vec2f(i / 2.0 * 0.3 + 0.33 * axis, j / 2.0 * 0.3 + 0.5 * (sign > 0)) for j in range(3) for i in range(3)]
            for j in range(2):
                for i in range(2):
                    quad = []
                    for (a, b) in [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]:
                        p = [0, 0, 0]
                        u, v = (axis + 1) % 3, (axis + 2) % 3
                        p[axis], p[u], p[v] = sign, a - 1, b - 1
                        quad.append((vid(tuple(p)), base + 3 * b + a))
                    if sign < 0:
                        quad.reverse()
                    faces.append([q[0] for q in quad])
                    uvi += [q[1] for q in quad]
    m.CreatePointsAttr(pts)
    m.CreateFaceVertexCountsAttr([4] * len(faces))
    m.CreateFaceVertexIndicesAttr([v for f in faces for v in f])
    m.CreateSubdivisionSchemeAttr(scheme)
    if st:
        pv = UsdGeom.PrimvarsAPI(m)
        p = pv.CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.faceVarying)
        p.Set(uvs)
        p.SetIndices(Vt.IntArray(uvi))
    return m


def grid(stage, path):
    """A 6 x 6 grid of quads whose st has a seam down the middle column."""
    m = UsdGeom.Mesh.Define(stage, path)
    n = 6
    pts = [Gf.Vec3f(x, y, 0.1 * math.sin(x + y)) for y in range(n + 1) for x in range(n + 1)]
    faces = [[(n + 1) * y + x, (n + 1) * y + x + 1, (n + 1) * (y + 1) + x + 1, (n + 1) * (y + 1) + x]
             for y in range(n) for x in range(n)]
    vals, key = [], {}

    def value(v, right):
        x, y = v % (n + 1), v // (n + 1)
        k = (v, right if x == n // 2 else None)
        if k not in key:
            key[k] = len(vals)
            vals.append(Gf.Vec2f(x / n + (0.05 if right and x == n // 2 else 0.0), y / n))
        return key[k]

    idx = []
    for f, face in enumerate(faces):
        right = (f % n) >= n // 2
        idx += [value(v, right) for v in face]
    m.CreatePointsAttr(pts)
    m.CreateFaceVertexCountsAttr([4] * len(faces))
    m.CreateFaceVertexIndicesAttr([v for f in faces for v in f])
    pv = UsdGeom.PrimvarsAPI(m)
    p = pv.CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.faceVarying)
    p.Set(vals)
    p.SetIndices(Vt.IntArray(idx))
    return m


def osd_cage(prim, fvar=False):
    """One prim as an OBJ with OpenSubdiv's tags: world positions, faces as authored (right-handed)."""
    m = UsdGeom.Mesh(prim)
    world = UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
    out = ["# %s for osd_opts: written by scripts/usd-stages.py" % prim.GetPath()]
    for p in m.GetPointsAttr().Get():
        q = world.Transform(Gf.Vec3d(p))
        out.append("v %.17g %.17g %.17g" % (q[0], q[1], q[2]))
    counts, idx = m.GetFaceVertexCountsAttr().Get(), m.GetFaceVertexIndicesAttr().Get()
    st = UsdGeom.PrimvarsAPI(m).GetPrimvar("st")
    sti = st.GetIndices() if fvar else None
    if fvar:
        out += ["vt %.17g %.17g" % (t[0], t[1]) for t in st.Get()]
    k = 0
    for n in counts:
        if fvar:
            out.append("f " + " ".join("%d/%d" % (idx[c] + 1, sti[c] + 1) for c in range(k, k + n)))
        else:
            out.append("f " + " ".join("%d" % (idx[c] + 1) for c in range(k, k + n)))
        k += n
    return "\n".join(out) + "\n"


def refine(prim, name, levels, *flags, fvar=False):
    cage = os.path.join(d, name + ".osd-cage.obj")
    open(cage, "w").write(osd_cage(prim, fvar))
    if osd:
        out = os.path.join(d, name + ".L%d.osd.obj" % levels)
        subprocess.run([osd, cage, str(levels), out, *flags], check=True, stdout=subprocess.DEVNULL)
        text = open(out).read()
        head = "# OpenSubdiv 3.5, %s level %d: osd_opts %s.osd-cage.obj %d OUT %s\n" % (
            prim.GetPath(), levels, name, levels, " ".join(flags))
        open(out, "w").write(head + text)


# two prims, two schemes
s = Usd.Stage.CreateNew(os.path.join(d, "two.usda"))
UsdGeom.Xform.Define(s, "/a")
bipyramid(s, "/a/loop", "loop")
b = UsdGeom.Xform.Define(s, "/b")
b.AddTranslateOp().Set(Gf.Vec3d(3.0, 0.5, 0.0))
b.AddRotateYOp().Set(25.0)
bipyramid(s, "/b/smooth", "catmullClark", triangleSubdivisionRule="smooth")
s.GetRootLayer().Save()
refine(s.GetPrimAtPath("/a/loop"), "two.a", 2, "--scheme", "loop", "--boundary", "edge-and-corner")
refine(s.GetPrimAtPath("/b/smooth"), "two.b", 2, "--scheme", "catmark", "--triangles", "smooth",
       "--boundary", "edge-and-corner")

# subdivisionScheme none, alone and beside a smooth prim
s = Usd.Stage.CreateNew(os.path.join(d, "none.usda"))
box(s, "/Box", "none")
s.GetRootLayer().Save()
s = Usd.Stage.CreateNew(os.path.join(d, "mixed.usda"))
box(s, "/Flat", "none")
x = UsdGeom.Xform.Define(s, "/Right")
x.AddTranslateOp().Set(Gf.Vec3d(4.0, 0.0, 0.0))
box(s, "/Right/Round", "catmullClark")
s.GetRootLayer().Save()
refine(s.GetPrimAtPath("/Right/Round"), "mixed.cc", 2, "--scheme", "catmark", "--boundary", "edge-and-corner")

# UV seams, indexed
s = Usd.Stage.CreateInMemory()
box(s, "/Box", "catmullClark", st=True)
s.GetRootLayer().Export(os.path.join(d, "seams.usdc"))
refine(s.GetPrimAtPath("/Box"), "seams", 1, "--scheme", "catmark", "--boundary", "edge-and-corner",
       "--fvar", "corners-plus1", fvar=True)
s = Usd.Stage.CreateNew(os.path.join(d, "seams-grid.usda"))
grid(s, "/Grid")
s.GetRootLayer().Save()

# time samples and stage metadata
s = Usd.Stage.CreateNew(os.path.join(d, "animated.usda"))
s.SetStartTimeCode(1)
s.SetEndTimeCode(3)
UsdGeom.SetStageUpAxis(s, UsdGeom.Tokens.z)
UsdGeom.SetStageMetersPerUnit(s, 0.01)
m = UsdGeom.Mesh.Define(s, "/Tet")
tet = [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]
m.CreateFaceVertexCountsAttr([3] * 4)
m.CreateFaceVertexIndicesAttr([0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2])
m.CreateSubdivisionSchemeAttr("loop")
pa = m.CreatePointsAttr([Gf.Vec3f(0.5 * x, 0.5 * y, 0.5 * z) for x, y, z in tet])
for t in (1, 2, 3):
    pa.Set([Gf.Vec3f(x + t, y, z) for x, y, z in tet], t)
s.GetRootLayer().Save()

# displayColor per face, constant and per vertex
s = Usd.Stage.CreateNew(os.path.join(d, "colors.usda"))
for k, (interp, values) in enumerate([
        ("uniform", [(1, 0, 0), (0, 0, 1)]),
        ("constant", [(0, 1, 0)]),
        ("vertex", [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1)])]):
    m = UsdGeom.Mesh.Define(s, "/P%d" % k)
    m.CreatePointsAttr([Gf.Vec3f(x + 3 * k, y, 0) for x, y in [(0, 0), (1, 0), (1, 1), (0, 1), (2, 0), (2, 1)]])
    m.CreateFaceVertexCountsAttr([4, 4])
    m.CreateFaceVertexIndicesAttr([0, 1, 2, 3, 1, 4, 5, 2])
    m.CreateDisplayColorPrimvar(interp).Set([Gf.Vec3f(*c) for c in values])
s.GetRootLayer().Save()

# instances
s = Usd.Stage.CreateNew(os.path.join(d, "instanced.usda"))
proto = s.DefinePrim("/Prototype", "Xform")
s.GetRootLayer().GetPrimAtPath("/Prototype").specifier = Sdf.SpecifierClass
bipyramid(s, "/Prototype/Shape", "loop")
for k, tx in enumerate([0.0, 4.0]):
    inst = UsdGeom.Xform.Define(s, "/Inst%d" % k)
    inst.AddTranslateOp().Set(Gf.Vec3d(tx, 0, 0))
    inst.GetPrim().GetReferences().AddInternalReference("/Prototype")
    inst.GetPrim().SetInstanceable(True)
s.GetRootLayer().Save()
s = Usd.Stage.CreateNew(os.path.join(d, "pointinstancer.usda"))
pi = UsdGeom.PointInstancer.Define(s, "/Scatter")
bipyramid(s, "/Scatter/Protos/Shape", "loop")
pi.CreatePrototypesRel().SetTargets(["/Scatter/Protos/Shape"])
pi.CreateProtoIndicesAttr([0, 0])
pi.CreatePositionsAttr([Gf.Vec3f(0, 0, 0), Gf.Vec3f(3, 0, 0)])
s.GetRootLayer().Save()
print("wrote the stages in", os.path.normpath(d))
