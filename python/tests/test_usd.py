"""USD through the package, read back by Pixar's usd-core (skipped without it): a
mesh saved as .usda is the Mesh usd-core reads, and the fixture stage authored by
usd-core (tests/fixtures/usd, scripts/usd-fixtures.py) loads with its prims'
world transforms applied."""
import os

import numpy as np
import pytest

import subdiv

pxr = pytest.importorskip("pxr")
from pxr import Usd, UsdGeom  # noqa: E402

FIXTURES = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "fixtures", "usd")


def test_a_saved_usda_is_the_mesh_usd_core_reads(tmp_path):
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]], float)
    quads = [[0, 1, 2, 3], [1, 4, 5, 2]]
    path = str(tmp_path / "q.usda")
    subdiv.save(path, v, quads)
    stage = Usd.Stage.Open(path)
    meshes = [UsdGeom.Mesh(p) for p in stage.Traverse() if p.IsA(UsdGeom.Mesh)]
    assert len(meshes) == 1
    m = meshes[0]
    assert list(m.GetFaceVertexCountsAttr().Get()) == [4, 4]
    pts = np.array(m.GetPointsAttr().Get(), float)
    idx = np.array(m.GetFaceVertexIndicesAttr().Get()).reshape(-1, 4)
    assert np.allclose(pts[idx], v[np.array(quads)])
    # our defaults, not USD's, are written
    assert m.GetInterpolateBoundaryAttr().Get() == "edgeOnly"


def test_the_fixture_stage_loads_in_world_space():
    path = os.path.join(FIXTURES, "stage.usda")
    ours = subdiv.load(path)
    stage = Usd.Stage.Open(path)
    world = []
    for prim in stage.Traverse():
        if prim.IsA(UsdGeom.Mesh):
            xf = UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
            world += [list(xf.Transform(p)) for p in UsdGeom.Mesh(prim).GetPointsAttr().Get()]
    assert np.allclose(ours.vertices, np.array(world), atol=1e-5)


def _bin():
    """The command line built beside the package (cargo test --release builds it)."""
    root = os.path.join(os.path.dirname(__file__), "..", "..")
    path = os.environ.get("SUBDIV_BIN") or os.path.join(root, "target", "release", "subdiv")
    if not os.path.exists(path):
        pytest.skip("the subdiv binary is not built (cargo build --release)")
    return path


def _key(p):
    return tuple(round(float(x), 4) for x in p)


def _face(points):
    """A face as its corner points, rotated to start at the smallest."""
    k = points.index(min(points))
    return tuple(points[k:] + points[:k])


def _meshes(path):
    """Every Mesh prim of the stage at `path`, in world space and
    right-handed: faces, crease edges, corners, holes, options, st."""
    stage = Usd.Stage.Open(path)
    out = {}
    for prim in stage.Traverse():
        if not prim.IsA(UsdGeom.Mesh):
            continue
        m = UsdGeom.Mesh(prim)
        xf = UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
        pts = [_key(xf.Transform(p)) for p in m.GetPointsAttr().Get()]
        counts, idx = list(m.GetFaceVertexCountsAttr().Get()), list(m.GetFaceVertexIndicesAttr().Get())
        left = m.GetOrientationAttr().Get() == "leftHanded"
        pv = UsdGeom.PrimvarsAPI(prim).GetPrimvar("st")
        st = pv.ComputeFlattened() if pv.IsDefined() else None
        per_vertex = pv.IsDefined() and pv.GetInterpolation() in ("vertex", "varying")
        faces, uv, at = [], {}, 0
        for n in counts:
            ids = idx[at:at + n]
            corners = [(pts[i], None if st is None else _key(st[i] if per_vertex else st[at + k]))
                       for k, i in enumerate(ids)]
            if left:
                corners.reverse()
            faces.append(_face([c[0] for c in corners]))
            uv.update({(faces[-1], c[0]): c[1] for c in corners})
            at += n
        edges, at = {}, 0
        cs = list(m.GetCreaseSharpnessesAttr().Get() or [])
        ci, cl = list(m.GetCreaseIndicesAttr().Get() or []), list(m.GetCreaseLengthsAttr().Get() or [])
        per_edge = len(cs) != len(cl)
        e = 0
        for c, n in enumerate(cl):
            for k in range(n - 1):
                s = cs[e] if per_edge else cs[c]
                edges[frozenset((pts[ci[at + k]], pts[ci[at + k + 1]]))] = round(s, 4)
                e += 1
            at += n
        ib = m.GetInterpolateBoundaryAttr().Get()
        uses = {}
        for i in idx:
            uses[pts[i]] = uses.get(pts[i], 0) + 1
        corners = {pts[i]: round(s, 4) for i, s in zip(m.GetCornerIndicesAttr().Get() or [],
                                                      m.GetCornerSharpnessesAttr().Get() or [])
                   if not (ib == "edgeAndCorner" and uses[pts[i]] == 1)}
        holes = sorted(faces[h] for h in (m.GetHoleIndicesAttr().Get() or []))
        options = (m.GetSubdivisionSchemeAttr().Get(), ib, m.GetFaceVaryingLinearInterpolationAttr().Get(),
                   m.GetTriangleSubdivisionRuleAttr().Get())
        out[str(prim.GetPath())] = (sorted(faces), edges, corners, holes, options, uv)
    return out


@pytest.mark.parametrize("ext", ["usda", "usdc", "usdz"])
def test_a_level_0_round_trip_keeps_every_attribute_as_usd_core_reads_it(tmp_path, ext):
    import subprocess
    src = os.path.join(FIXTURES, "stage.usda")
    out = str(tmp_path / f"out.{ext}")
    subprocess.run([_bin(), "subdivide", src, out, "-n", "0"], check=True, capture_output=True)
    theirs, ours = _meshes(src), _meshes(out)
    assert sorted(ours) == sorted(theirs)
    names = ("faces", "creases", "corners", "holes", "options", "st")
    for path in theirs:
        for name, a, b in zip(names, ours[path], theirs[path]):
            assert a == b, f"{ext} {path}: {name}"


def _run(*args):
    import subprocess
    subprocess.run([_bin(), *args], check=True, capture_output=True)


def _obj_faces(path):
    """The faces of an OBJ (OpenSubdiv's fixtures) as rotated tuples of rounded points."""
    v, faces = [], []
    for line in open(path):
        t = line.split()
        if t and t[0] == "v":
            v.append(_key([float(x) for x in t[1:4]]))
        elif t and t[0] == "f":
            faces.append(_face([v[int(c.split("/")[0]) - 1] for c in t[1:]]))
    return sorted(faces)


@pytest.mark.parametrize("ext", ["usda", "usdc"])
def test_each_prim_is_written_with_its_scheme_and_transform_as_opensubdiv_refines_it(tmp_path, ext):
    out = str(tmp_path / f"two.{ext}")
    _run("subdivide", os.path.join(FIXTURES, "two.usda"), out, "-n", "2")
    ours = _meshes(out)
    assert sorted(ours) == ["/a/loop", "/b/smooth"]
    assert ours["/a/loop"][4][0] == "loop" and ours["/b/smooth"][4][0] == "catmullClark"
    assert ours["/b/smooth"][4][3] == "smooth"
    # in world space (usd-core's transforms), each prim is OpenSubdiv's refinement of it
    for path, fixture in [("/a/loop", "two.a.L2.osd.obj"), ("/b/smooth", "two.b.L2.osd.obj")]:
        a, b = ours[path][0], _obj_faces(os.path.join(FIXTURES, fixture))
        assert [len(f) for f in a] == [len(f) for f in b], path
        pa, pb = np.array([p for f in a for p in f]), np.array([p for f in b for p in f])
        near = np.min(np.linalg.norm(pa[:, None, :] - pb[None, :, :], axis=2), axis=1)
        assert near.max() < 2e-4, path  # the points rounded to 1e-4
    stage = Usd.Stage.Open(out)
    smooth = stage.GetPrimAtPath("/b/smooth")
    assert UsdGeom.Xformable(smooth).GetOrderedXformOps(), "its transform is an xformOp, not baked in"


def _st(path, prim):
    """The st values and indices usd-core reads at `prim`."""
    stage = Usd.Stage.Open(path)  # held: a prim does not keep its stage alive
    pv = UsdGeom.PrimvarsAPI(stage.GetPrimAtPath(prim)).GetPrimvar("st")
    assert pv.GetInterpolation() == "faceVarying"
    # the indices up to a renumbering: each value by its first use
    first = {}
    return len(pv.Get()), [first.setdefault(i, len(first)) for i in pv.GetIndices()]


@pytest.mark.parametrize("ext", ["usda", "usdc"])
def test_uv_seams_survive_writing_as_usd_core_reads_them(tmp_path, ext):
    for name, prim in [("seams.usdc", "/Box"), ("seams-grid.usda", "/Grid")]:
        src = os.path.join(FIXTURES, name)
        out = str(tmp_path / f"{name}.{ext}")
        _run("subdivide", src, out, "-n", "0")
        theirs, ours = _st(src, prim), _st(out, prim)
        assert ours == theirs, name
    # level 1 of the box: OpenSubdiv's 150 face-varying values, shared
    out = str(tmp_path / f"seams.L1.{ext}")
    _run("subdivide", os.path.join(FIXTURES, "seams.usdc"), out, "-n", "1")
    values, indices = _st(out, "/Box")
    osd = sum(1 for line in open(os.path.join(FIXTURES, "seams.L1.osd.obj")) if line.startswith("vt "))
    assert (values, len(indices)) == (osd, 4 * 96)


def test_a_stages_prims_load_with_their_own_options_and_refine_as_opensubdiv():
    m = subdiv.load(os.path.join(FIXTURES, "two.usda"))
    assert [p.path for p in m.prims] == ["/a/loop", "/b/smooth"]
    loop, smooth = m.prims
    assert loop.options["scheme"] == "loop" and smooth.options["scheme"] == "catmull-clark"
    assert smooth.options["triangles"] == "smooth"
    assert len(loop.faces) == len(smooth.faces) == 10
    assert not np.allclose(smooth.transform, np.eye(4)), "the second prim's transform"
    # each prim refined by its own options is OpenSubdiv's refinement of it
    for p, fixture in [(loop, "two.a.L2.osd.obj"), (smooth, "two.b.L2.osd.obj")]:
        faces = m.faces[p.faces]
        used = np.unique(faces)
        local = np.searchsorted(used, faces)
        v2, f2 = subdiv.subdivide(m.vertices[used], local, levels=2, **p.options)
        theirs = _obj_faces(os.path.join(FIXTURES, fixture))
        assert len(f2) == len(theirs), p.path
        pts = np.array([q for f in theirs for q in f])
        near = np.min(np.linalg.norm(v2[:, None, :] - pts[None, :, :], axis=2), axis=1)
        assert near.max() < 2e-4, p.path


def test_load_reads_a_stage_at_a_time_code():
    path = os.path.join(FIXTURES, "animated.usda")
    assert subdiv.load(path).vertices[0][0] == pytest.approx(2.0)  # startTimeCode 1
    assert subdiv.load(path, time=2.5).vertices[0][0] == pytest.approx(3.5)
    with pytest.raises(subdiv.SubdivError):
        subdiv.load(path, time=float("nan"))
