"""The library's options from Python, by the command line's names, against
OpenSubdiv 3.5's own output (the repository's fixtures, tests/fixtures/,
written by scripts/*-fixtures.py with osd_opts): boundary "none" and holes,
Catmull-Clark's smooth triangle rule, and the options a file states (Chaikin
creasing among them), read by ``subdiv.load`` into ``Mesh.options`` and
passed back as keywords. The Refiner and the matrix take the same options."""

import os

import numpy as np
import pytest
from conftest import REPO
from scipy.spatial import cKDTree

import subdiv

FIXTURES = os.path.join(REPO, "tests", "fixtures")


def read_obj(path):
    """A fixture's vertices, faces (0-based, lists), crease and hole tags,
    read here (not by subdiv.load: the control meshes are the test data)."""
    v, f, creases, holes = [], [], [], []
    with open(path) as fh:
        for line in fh:
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                v.append([float(x) for x in t[1:4]])
            elif t[0] == "f":
                f.append([int(x.split("/")[0]) - 1 for x in t[1:]])
            elif t[:2] == ["t", "crease"]:
                creases.append(([int(t[3]), int(t[4])], float(t[5])))
            elif t[:2] == ["t", "hole"]:
                holes += [int(x) for x in t[3:]]
    e = np.array([c[0] for c in creases], np.int64).reshape(-1, 2)
    s = np.array([c[1] for c in creases], float)
    return np.array(v), f, (e, s), holes


def same_points(a, b, tol=1e-5):
    """Every point of `a` has one of `b` within `tol`, and the other way round."""
    da, _ = cKDTree(b).query(a)
    db, _ = cKDTree(a).query(b)
    return max(da.max(), db.max()) < tol


def centres(v, faces):
    return np.array([np.mean(v[list(face)], axis=0) for face in faces])


@pytest.mark.parametrize("folder,scheme", [("catmark", "catmull-clark"), ("creases", "loop")])
@pytest.mark.parametrize("boundary", ["edge", "none"])
@pytest.mark.parametrize("level", [1, 2])
def test_holes_and_boundary_none_equal_opensubdiv(folder, scheme, boundary, level):
    V, F, creases, holes = read_obj(os.path.join(FIXTURES, folder, "holes.obj"))
    assert holes, "the fixture has holes"
    ov, of, _, _ = read_obj(os.path.join(FIXTURES, folder, f"holes.{boundary}.L{level}.osd.txt"))
    opts = dict(boundary=boundary, creases=creases, holes=holes)
    V2, F2 = subdiv.subdivide(V, F, level, scheme, **opts)
    assert same_points(V2, ov), "every vertex where OpenSubdiv puts it"
    # the faces OpenSubdiv keeps: the holes' children (and, boundary none,
    # the border's faces) left out
    assert len(F2) == len(of) and same_points(centres(V2, F2), centres(ov, of))
    full = subdiv.subdivide(V, F, level, scheme, boundary=boundary, creases=creases)[1]
    assert len(F2) < len(full), "the holes are left out"
    # the refiner and the matrix take the same options and give the same mesh
    r = subdiv.Refiner(V, F, level, scheme, **opts)
    np.testing.assert_array_equal(r.faces, F2)
    np.testing.assert_allclose(r.vertices, V2, atol=1e-12)
    S, F3 = subdiv.matrix(F, level, scheme, return_faces=True, **opts)
    np.testing.assert_array_equal(F3, F2)
    np.testing.assert_allclose(S @ V, V2, atol=1e-6)


@pytest.mark.parametrize("level", [1, 2])
def test_the_smooth_triangle_rule_equals_opensubdiv(level):
    V, F, creases, _ = read_obj(os.path.join(FIXTURES, "catmark", "tri_quads.obj"))
    for rule in ("catmark", "smooth"):
        ov, _, _, _ = read_obj(os.path.join(FIXTURES, "catmark", f"tri_quads.{rule}.L{level}.osd.txt"))
        V2, _ = subdiv.subdivide(V, F, level, "catmull-clark", triangles=rule, creases=creases)
        assert same_points(V2, ov), rule
        r = subdiv.Refiner(V, F, level, "catmull-clark", triangles=rule, creases=creases)
        np.testing.assert_allclose(r.vertices, V2, atol=1e-12)
        S = subdiv.matrix(F, level, "catmull-clark", triangles=rule, creases=creases)
        np.testing.assert_allclose(S @ V, V2, atol=1e-6)
    smooth = subdiv.subdivide(V, F, level, "catmull-clark", triangles="smooth", creases=creases)[0]
    assert np.abs(smooth - subdiv.subdivide(V, F, level, "catmull-clark", creases=creases)[0]).max() > 1e-3


def test_load_gives_the_options_the_file_states_and_subdivide_takes_them_back():
    path = os.path.join(FIXTURES, "catmark", "tagged.obj")
    m = subdiv.load(path)
    # t interpolateboundary 1, facevaryinginterpolateboundary 4,
    # smoothtriangles smooth, creasemethod chaikin
    assert m.options == {"boundary": "edge-and-corner", "fvar": "boundaries", "triangles": "smooth",
                         "creasing": "chaikin"}
    _, F, creases, _ = read_obj(path)
    for flags, osd in (({}, "tagged.L2.osd.obj"),
                       ({"boundary": "edge", "fvar": "all", "creasing": "uniform", "triangles": "catmark"},
                        "tagged.flags.L2.osd.obj")):
        ov, _, _, _ = read_obj(os.path.join(FIXTURES, "catmark", osd))
        V2, _ = subdiv.subdivide(m.vertices, F, 2, "catmull-clark", creases=creases, **{**m.options, **flags})
        assert same_points(V2, ov), osd
    # a file that states nothing gives no options: the defaults apply
    assert subdiv.load(os.path.join(FIXTURES, "catmark", "cube.obj")).options == {}


def test_the_boundary_names_are_the_librarys():
    V, F, _, _ = read_obj(os.path.join(FIXTURES, "catmark", "holes.obj"))
    results = {b: subdiv.subdivide(V, F, 1, "catmull-clark", boundary=b)[1].shape[0]
               for b in ("edge", "edge-and-corner", "none")}
    assert results["none"] < results["edge"] == results["edge-and-corner"], results
    # the library's aliases, as the command line takes them
    np.testing.assert_array_equal(subdiv.subdivide(V, F, 1, "catmark", boundary="edge-only")[0],
                                  subdiv.subdivide(V, F, 1, "catmull-clark", boundary="edge")[0])
    with pytest.raises(subdiv.SubdivError, match="expected edge, edge-and-corner or none"):
        subdiv.subdivide(V, F, 1, "catmull-clark", boundary="corner-only")
    with pytest.raises(subdiv.SubdivError, match="expected loop or warren"):
        subdiv.Refiner(V, F, 1, "catmull-clark", beta="stam")
