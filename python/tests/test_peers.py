"""Equality with the Python peers on closed meshes: trimesh's
subdivide_loop (Loop's beta) and libigl's loop (Warren's beta), as point
sets and as face sets. Peers are test dependencies; a test of a peer skips
only when its import fails.

On open meshes libigl's boundary rules are ours (3/4 v + 1/8 (a + b) at a
border vertex, the midpoint of a border edge): compared as above. trimesh takes
as a border vertex's curve neighbours every neighbour that lies on the border
(trimesh/remesh.py, subdivide_loop), so it differs at a border vertex joined to
another border vertex by an interior edge; the test checks that it differs
there and only there."""

import numpy as np
import pytest
from conftest import bipyramid, icosahedron, open_grid, sphere
from scipy.spatial import cKDTree

import subdiv


def closed_meshes():
    yield "icosahedron", icosahedron()
    yield "bipyramid-7", bipyramid(7, jitter=0.03)  # valences 7 and 4
    yield "bipyramid-3", bipyramid(3, jitter=0.03, seed=2)  # valence 3
    v, f = sphere(2)
    rng = np.random.default_rng(3)
    yield "bumpy-sphere", (v * (1 + 0.05 * rng.standard_normal((len(v), 1))), f)


def match(ours_v, ours_f, theirs_v, theirs_f, tol):
    """Asserts the two meshes are the same point set (a bijection within
    `tol`) and, through it, the same set of oriented faces."""
    assert ours_v.shape == theirs_v.shape and ours_f.shape == theirs_f.shape
    d, idx = cKDTree(theirs_v).query(ours_v)
    assert d.max() < tol, f"points differ by {d.max()}"
    assert len(np.unique(idx)) == len(ours_v), "not a bijection"

    def canon(f):
        r = np.argmin(f, axis=1)
        rolled = np.array([np.roll(row, -k) for row, k in zip(f, r)])
        return set(map(tuple, rolled))

    assert canon(idx[ours_f]) == canon(theirs_f)


@pytest.mark.parametrize("name,mesh", list(closed_meshes()), ids=[n for n, _ in closed_meshes()])
@pytest.mark.parametrize("levels", [1, 3])
def test_equal_to_trimesh(name, mesh, levels):
    trimesh = pytest.importorskip("trimesh")
    v, f = mesh
    tv, tf = trimesh.remesh.subdivide_loop(v, f, iterations=levels)
    ov, of = subdiv.subdivide(v, f, levels, beta="loop")
    match(ov, of, tv, tf, tol=1e-5 * np.abs(v).max())


@pytest.mark.parametrize("name,mesh", list(closed_meshes()), ids=[n for n, _ in closed_meshes()])
@pytest.mark.parametrize("levels", [1, 3])
def test_equal_to_libigl(name, mesh, levels):
    igl = pytest.importorskip("igl")
    v, f = mesh
    iv, if_ = igl.loop(np.ascontiguousarray(v, float), np.ascontiguousarray(f, np.int64), levels)
    ov, of = subdiv.subdivide(v, f, levels, beta="warren")
    match(ov, of, iv, if_, tol=1e-5 * np.abs(v).max())


def test_the_betas_really_differ():
    # guards the two tests above against comparing something insensitive to beta
    v, f = icosahedron()
    a, _ = subdiv.subdivide(v, f, 1, beta="loop")
    b, _ = subdiv.subdivide(v, f, 1, beta="warren")
    assert np.abs(a - b).max() > 1e-3


@pytest.mark.parametrize("levels", [1, 3])
def test_equal_to_libigl_on_an_open_mesh(levels):
    igl = pytest.importorskip("igl")
    v, f = open_grid(4)
    iv, if_ = igl.loop(v, f.astype(np.int64), levels)
    ov, of = subdiv.subdivide(v, f, levels, beta="warren")
    match(ov, of, iv, if_, tol=1e-5)


def test_trimesh_differs_on_an_open_mesh_only_where_its_rule_does():
    trimesh = pytest.importorskip("trimesh")
    v, f = open_grid(4)
    tv, tf = trimesh.remesh.subdivide_loop(v, f, iterations=1)
    ov, _ = subdiv.subdivide(v, f, 1)
    d, _ = cKDTree(tv).query(ov)
    differ = set(np.flatnonzero(d > 1e-5).tolist())
    # border vertices with an interior edge to another border vertex
    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    edges, count = np.unique(e, axis=0, return_counts=True)
    border = set(edges[count == 1].ravel().tolist())
    inner = edges[count == 2]
    ambiguous = {int(x) for a, b in inner if a in border and b in border for x in (a, b)}
    assert ambiguous, "the grid must have such vertices for this test to mean anything"
    assert differ == ambiguous
