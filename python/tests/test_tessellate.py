"""subdiv.tessellate: the limit surface within a tolerance, crack-free,
its vertices the limit at their own (face, uv), and bad tolerances refused."""

import collections

import numpy as np
import pytest
from conftest import cube_quads, icosahedron

import subdiv


def closed(F):
    """Every directed edge once and its reverse once: no crack, no T-junction."""
    edges = collections.Counter((int(a), int(b)) for t in F for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])))
    return all(k == 1 and edges.get((b, a)) == 1 for (a, b), k in edges.items())


def test_loop_vertices_are_the_limit_at_their_points_and_the_mesh_is_closed():
    V, F = icosahedron()
    P, T, N, face, uv = subdiv.tessellate(V, F, "2e-3x")
    assert P.shape[1] == 3 and T.shape[1] == 3 and N.shape == P.shape and uv.shape == (len(P), 2)
    assert face.shape == (len(P),) and face.dtype == np.int64
    assert closed(T)
    Q, M = subdiv.evaluate(V, F, face, uv)
    assert np.allclose(Q, P, atol=1e-12) and np.allclose(M, N, atol=1e-9)
    # finer asked, more triangles
    finer = subdiv.tessellate(V, F, "2e-4x")[1]
    assert len(finer) > 2 * len(T)
    # the same as a distance: the fraction is of the control points' box's diagonal
    diagonal = np.linalg.norm(V.max(axis=0) - V.min(axis=0))
    same = subdiv.tessellate(V, F, 2e-3 * diagonal)[1]
    assert np.array_equal(same, T)


def test_catmull_clark_on_quads():
    V, F = cube_quads()
    P, T, N, face, uv = subdiv.tessellate(V, F, "1e-2x", scheme="catmull-clark")
    assert closed(T)
    Q, _ = subdiv.evaluate(V, F, face, uv, scheme="catmull-clark")
    assert np.allclose(Q, P, atol=1e-12)
    assert face.max() < 6, "a quad is one ptex face"


@pytest.mark.parametrize("bad", [0, -1.0, float("nan"), "x", "1e-3y", None])
def test_bad_tolerances_are_refused(bad):
    V, F = icosahedron()
    with pytest.raises(ValueError, match="tolerance"):
        subdiv.tessellate(V, F, bad)


def test_a_scheme_without_a_limit_is_refused():
    V, F = icosahedron()
    with pytest.raises(subdiv.SubdivError):
        subdiv.tessellate(V, F, "1e-2x", scheme="butterfly")
