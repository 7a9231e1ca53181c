"""subdiv.matrix: S @ V equals subdivide's points, on the same faces."""

import numpy as np
import pytest
import scipy.sparse as sp
from conftest import bipyramid, cube_quads, cube_triangles, icosahedron, open_grid

import subdiv

CASES = [
    ("loop", icosahedron, {}),
    ("loop", open_grid, {"beta": "warren"}),
    ("loop", open_grid, {"boundary": "edge-and-corner"}),
    ("midpoint", icosahedron, {}),
    ("butterfly", open_grid, {}),
    ("modified-butterfly", icosahedron, {}),
    ("jarek", lambda: bipyramid(5), {}),
    ("catmull-clark", cube_quads, {}),
    ("bilinear", cube_quads, {}),
    ("loop", cube_triangles, {"creases": (np.array([[0, 1], [1, 3]]), np.array([10.0, 1.5]))}),
]


@pytest.mark.parametrize("scheme,make,opts", CASES, ids=[f"{c[0]}-{i}" for i, c in enumerate(CASES)])
@pytest.mark.parametrize("levels", [0, 1, 3])
def test_s_times_v_is_subdivide(scheme, make, opts, levels):
    v, f = make()
    s, f2 = subdiv.matrix(f, levels, scheme, return_faces=True, **opts)
    assert sp.issparse(s) and s.format == "csr" and s.shape[1] == len(v)
    v2, g2 = subdiv.subdivide(v, f, levels, scheme, **opts)
    assert s.shape[0] == len(v2)
    assert np.array_equal(f2, g2)
    scale = np.abs(v).max()
    np.testing.assert_allclose(s @ v, v2, rtol=1e-6, atol=1e-6 * scale)
    # a different V through the same S: the matrix does not depend on positions
    w = np.random.default_rng(0).standard_normal(v.shape)
    w2, _ = subdiv.subdivide(w, f, levels, scheme, **opts)
    np.testing.assert_allclose(s @ w, w2, rtol=1e-6, atol=1e-5)
    np.testing.assert_allclose(np.asarray(s.sum(axis=1)).ravel(), 1.0, atol=1e-5)


def test_default_returns_the_matrix_only():
    v, f = icosahedron()
    s = subdiv.matrix(f, 2)
    assert sp.isspmatrix_csr(s)


def test_unreferenced_vertices_get_identity_rows():
    v, f = icosahedron()
    s = subdiv.matrix(f, 1, n_vertices=len(v) + 2)
    assert s.shape[1] == len(v) + 2
    vx = np.vstack([v, [[5, 5, 5], [6, 6, 6]]])
    v2, _ = subdiv.subdivide(vx, f, 1)
    np.testing.assert_allclose(s @ vx, v2, rtol=1e-6, atol=1e-6)
    assert s[len(v), len(v)] == 1.0 and s[len(v)].nnz == 1


def test_matrix_refuses_what_subdivide_refuses():
    with pytest.raises(subdiv.SubdivError):
        subdiv.matrix([[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    with pytest.raises(subdiv.SubdivError, match="n_vertices"):
        subdiv.matrix([[0, 1, 2]], n_vertices=2**40)
    with pytest.raises(subdiv.SubdivError):
        subdiv.matrix([[0, 1, 2]], n_vertices=2)
