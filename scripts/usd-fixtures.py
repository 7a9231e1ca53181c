#!/usr/bin/env python3
"""Writes tests/fixtures/usd/stage.usda, stage.usdc and stage.usdz with Pixar's USD
(PyPI usd-core: `pip install usd-core`), and, given OpenSubdiv's osd_opts
(../shared/bench/native/osd_opts.cpp), the OpenSubdiv result of the same cage:

    python3 scripts/usd-fixtures.py /tmp/peers/osd_opts

The stage: /World (an Xform: translate, rotateZ, scale) holding /World/Body, a bumped 4x3
grid of quads with a crease chain (sharpness 2) and an infinitely sharp crease, a corner
(3), a hole, st faceVarying and indexed, displayColor per vertex, interpolateBoundary and
faceVaryingLinearInterpolation left unauthored (USD's defaults, edgeAndCorner and
cornersPlus1, apply), and /World/Group/Lid under a second Xform, a box open at the bottom,
leftHanded, with st per vertex, one constant displayColor and interpolateBoundary authored.

stage.L2.osd.obj: the cage as OpenSubdiv sees it (points through their world transforms
computed by USD, the leftHanded faces reversed, tags for the creases, corner and hole,
`t interpolateboundary 1/0/0 1` and `t facevaryinginterpolateboundary 1/0/0 2`), written
to stage.osd-cage.obj and refined by `osd_opts stage.osd-cage.obj 2 OUT` (Catmull-Clark,
double precision); it holds the last level's v, vt and f v/vt lines.
"""
import math, os, subprocess, sys
from pxr import Gf, Sdf, Usd, UsdGeom, UsdUtils, Vt

here = os.path.dirname(os.path.abspath(__file__))
d = os.path.join(here, "..", "tests", "fixtures", "usd")
os.makedirs(d, exist_ok=True)


def body(stage):
    m = UsdGeom.Mesh.Define(stage, "/World/Body")
    pts = [Gf.Vec3f(x, y, 0.15 * math.sin(x + 2 * y)) for y in range(4) for x in range(5)]
    faces = [[5 * y + x, 5 * y + x + 1, 5 * y + x + 6, 5 * y + x + 5] for y in range(3) for x in range(4)]
    m.CreatePointsAttr(pts)
    m.CreateFaceVertexCountsAttr([4] * len(faces))
    m.CreateFaceVertexIndicesAttr([v for f in faces for v in f])
    m.CreateCreaseIndicesAttr([6, 7, 8, 11, 12])
    m.CreateCreaseLengthsAttr([3, 2])
    m.CreateCreaseSharpnessesAttr([2.0, 10.0])
    m.CreateCornerIndicesAttr([0])
    m.CreateCornerSharpnessesAttr([3.0])
    m.CreateHoleIndicesAttr([10])
    pv = UsdGeom.PrimvarsAPI(m)
    st = pv.CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.faceVarying)
    st.Set([Gf.Vec2f(x / 4.0, y / 3.0) for y in range(4) for x in range(5)])
    st.SetIndices(Vt.IntArray([v for f in faces for v in f]))
    col = [Gf.Vec3f(x / 4.0, y / 3.0, 0.5) for y in range(4) for x in range(5)]
    m.CreateDisplayColorPrimvar(UsdGeom.Tokens.vertex).Set(col)
    return m


def lid(stage):
    g = UsdGeom.Xform.Define(stage, "/World/Group")
    g.AddTranslateOp().Set(Gf.Vec3d(1.0, 0.5, 0.4))
    g.AddRotateXOp().Set(20.0)
    m = UsdGeom.Mesh.Define(stage, "/World/Group/Lid")
    pts = [Gf.Vec3f(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    # outward with the left-hand rule: clockwise seen from outside
    faces = [[4, 5, 7, 6], [0, 1, 5, 4], [1, 3, 7, 5], [3, 2, 6, 7], [2, 0, 4, 6]]
    faces = [list(reversed(f)) for f in faces]
    m.CreatePointsAttr(pts)
    m.CreateFaceVertexCountsAttr([4] * len(faces))
    m.CreateFaceVertexIndicesAttr([v for f in faces for v in f])
    m.CreateOrientationAttr(UsdGeom.Tokens.leftHanded)
    m.CreateInterpolateBoundaryAttr(UsdGeom.Tokens.edgeAndCorner)
    pv = UsdGeom.PrimvarsAPI(m)
    st = pv.CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.vertex)
    st.Set([Gf.Vec2f(0.5 * x + 0.25 * z, 0.5 * y) for z in (0, 1) for y in (0, 1) for x in (0, 1)])
    m.CreateDisplayColorPrimvar(UsdGeom.Tokens.constant).Set([Gf.Vec3f(1.0, 0.2, 0.1)])
    return m


def author(path):
    stage = Usd.Stage.CreateNew(path)
    w = UsdGeom.Xform.Define(stage, "/World")
    w.AddTranslateOp().Set(Gf.Vec3d(1.0, 2.0, 3.0))
    w.AddRotateZOp().Set(30.0)
    w.AddScaleOp().Set(Gf.Vec3f(2.0, 2.0, 2.0))
    stage.SetDefaultPrim(w.GetPrim())
    body(stage)
    lid(stage)
    stage.GetRootLayer().Save()
    return stage


def osd_cage(stage):
    """The stage as one OBJ with OpenSubdiv's tags (world positions, right-handed faces)."""
    out = ["# the cage of stage.usda for osd_opts: written by scripts/usd-fixtures.py"]
    vt, faces, tags, base_v, base_f = [], [], [], 0, 0
    for prim in stage.Traverse():
        if not prim.IsA(UsdGeom.Mesh):
            continue
        m = UsdGeom.Mesh(prim)
        world = UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
        pts = m.GetPointsAttr().Get()
        for p in pts:
            q = world.Transform(Gf.Vec3d(p))
            out.append("v %.17g %.17g %.17g" % (q[0], q[1], q[2]))
        counts, idx = m.GetFaceVertexCountsAttr().Get(), m.GetFaceVertexIndicesAttr().Get()
        # one vt per value of st, shared as USD shares it (by vertex, or by st's indices)
        st = UsdGeom.PrimvarsAPI(m).GetPrimvar("st")
        vals, sti = st.Get(), st.GetIndices()
        per_vertex = st.GetInterpolation() == UsdGeom.Tokens.vertex
        base_t = len(vt)
        vt += ["vt %.17g %.17g" % (t[0], t[1]) for t in vals]
        left = m.GetOrientationAttr().Get() == UsdGeom.Tokens.leftHanded
        k = 0
        for n in counts:
            order = [k] + ([k + n - j for j in range(1, n)] if left else [k + j for j in range(1, n)])
            face = []
            for c in order:
                t = idx[c] if per_vertex else (sti[c] if sti else c)
                face.append("%d/%d" % (base_v + idx[c] + 1, base_t + t + 1))
            faces.append("f " + " ".join(face))
            k += n
        ci, cl, cs = (m.GetCreaseIndicesAttr().Get() or [], m.GetCreaseLengthsAttr().Get() or [],
                      m.GetCreaseSharpnessesAttr().Get() or [])
        at = 0
        for length, s in zip(cl, cs):
            for a, b in zip(ci[at:at + length], ci[at + 1:at + length]):
                tags.append("t crease 2/1/0 %d %d %g" % (base_v + a, base_v + b, s))
            at += length
        for v, s in zip(m.GetCornerIndicesAttr().Get() or [], m.GetCornerSharpnessesAttr().Get() or []):
            tags.append("t corner 1/1/0 %d %g" % (base_v + v, s))
        for f in m.GetHoleIndicesAttr().Get() or []:
            tags.append("t hole 1/0/0 %d" % (base_f + f))
        base_v += len(pts)
        base_f += len(counts)
    tags += ["t interpolateboundary 1/0/0 1", "t facevaryinginterpolateboundary 1/0/0 2"]
    return "\n".join(out + vt + faces + tags) + "\n"


usda = os.path.join(d, "stage.usda")
stage = author(usda)
Usd.Stage.Open(usda).Export(os.path.join(d, "stage.usdc"))
UsdUtils.CreateNewUsdzPackage(os.path.join(d, "stage.usdc"), os.path.join(d, "stage.usdz"))
cage = os.path.join(d, "stage.osd-cage.obj")
open(cage, "w").write(osd_cage(stage))
if len(sys.argv) > 1:
    out = os.path.join(d, "stage.L2.osd.obj")
    subprocess.run([sys.argv[1], cage, "2", out], check=True, stdout=subprocess.DEVNULL)
    body_text = open(out).read()
    open(out, "w").write("# OpenSubdiv 3.5 catmark, stage.osd-cage.obj, level 2: osd_opts stage.osd-cage.obj 2 OUT\n" + body_text)
