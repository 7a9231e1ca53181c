"""subdiv.limit: Loop limit positions and normals against hand-computed
masks at a valence-5 and a valence-6 vertex, and against deep subdivision."""

import numpy as np
import pytest
from conftest import bipyramid, icosahedron

import subdiv


def loop_beta(n):
    return (5 / 8 - (3 / 8 + np.cos(2 * np.pi / n) / 4) ** 2) / n


def hand_limit(v, ring, beta):
    """v_inf = (1 - n chi) v + chi sum(ring), chi = 1 / (n + 3 / (8 beta))."""
    n = len(ring)
    chi = 1 / (n + 3 / (8 * beta))
    return (1 - n * chi) * v + chi * ring.sum(axis=0)


def hand_normal(ring):
    """normalize(t1 x t2), t1 = sum cos(2 pi i/n) p_i, t2 = sum sin(2 pi i/n) p_i,
    the ring counter-clockwise seen from outside."""
    n = len(ring)
    a = 2 * np.pi * np.arange(n) / n
    t = np.cross(np.cos(a) @ ring, np.sin(a) @ ring)
    return t / np.linalg.norm(t)


@pytest.mark.parametrize("k", [5, 6])
def test_limit_at_valence(k):
    v, f = bipyramid(k, jitter=0.05, seed=k)
    p, n = subdiv.limit(v, f)
    ring = v[2:2 + k]  # counter-clockwise seen from above: outside for the top apex
    if k == 6:  # the regular mask: 1/2 v + 1/12 sum
        np.testing.assert_allclose(p[0], v[0] / 2 + ring.sum(0) / 12, atol=1e-6)
    np.testing.assert_allclose(p[0], hand_limit(v[0], ring, loop_beta(k)), atol=1e-6)
    np.testing.assert_allclose(n[0], hand_normal(ring), atol=1e-5)


def test_valence_5_numbers():
    # the icosahedron's vertices all have valence 5: beta(5) = 0.0840932...,
    # chi = 1 / (5 + 3 / (8 beta)) = 0.1057157..., ring of vertex 0: 11, 5, 1, 7, 10
    v, f = icosahedron()
    p, n = subdiv.limit(v, f)
    chi = 0.1057157
    assert abs(1 / (5 + 3 / (8 * loop_beta(5))) - chi) < 1e-6
    np.testing.assert_allclose(p[0], (1 - 5 * chi) * v[0] + chi * v[[11, 5, 1, 7, 10]].sum(0), atol=1e-5)
    # by symmetry every limit normal is the radial direction
    np.testing.assert_allclose(n, v / np.linalg.norm(v, axis=1, keepdims=True), atol=1e-6)


def test_warren_limit_mask():
    v, f = bipyramid(5, jitter=0.05, seed=9)
    p, _ = subdiv.limit(v, f, beta="warren")
    np.testing.assert_allclose(p[0], 0.5 * v[0] + 0.1 * v[2:7].sum(0), atol=1e-6)


def test_limit_is_where_subdivision_converges():
    v, f = bipyramid(5, jitter=0.1, seed=4)
    p, n = subdiv.limit(v, f)
    deep, f6 = subdiv.subdivide(v, f, 6)
    np.testing.assert_allclose(deep[:len(v)], p, atol=2e-4)
    # the normal of the fine faces around vertex 0 approaches the limit normal
    around = f6[(f6 == 0).any(axis=1)]
    fn = np.cross(deep[around[:, 1]] - deep[around[:, 0]], deep[around[:, 2]] - deep[around[:, 0]]).sum(0)
    assert np.dot(fn / np.linalg.norm(fn), n[0]) > 0.999


def test_unreferenced_vertex_keeps_position_zero_normal():
    v, f = icosahedron()
    vx = np.vstack([v, [[3.0, 2.0, 1.0]]])
    p, n = subdiv.limit(vx, f)
    assert np.array_equal(p[-1], [3.0, 2.0, 1.0]) and np.array_equal(n[-1], [0, 0, 0])


def test_boundary_and_corner_masks():
    from conftest import open_grid

    v, f = open_grid(3, seed=5)
    p, _ = subdiv.limit(v, f)
    # a boundary vertex with two border neighbours a, b: 2/3 v + 1/6 (a + b); vertex 1
    # (i=0, j=1) lies between 0 and 2 on the border j-axis
    np.testing.assert_allclose(p[1], 2 / 3 * v[1] + (v[0] + v[2]) / 6, atol=1e-6)
    counts = np.bincount(f.ravel(), minlength=len(v))
    corner = int(np.flatnonzero(counts == 1)[0])
    pc, _ = subdiv.limit(v, f, boundary="edge-and-corner")
    np.testing.assert_allclose(pc[corner], v[corner], rtol=1e-7)
    assert not np.allclose(p[corner], v[corner])


def test_crease_limit_mask():
    from conftest import cube_triangles

    v, f = cube_triangles()
    edges = np.array([[0, 1], [1, 3], [3, 2], [2, 0]])
    p, _ = subdiv.limit(v, f, creases=(edges, np.full(4, 10.0)))
    np.testing.assert_allclose(p[0], 2 / 3 * v[0] + (v[1] + v[2]) / 6, atol=1e-6)


def test_evaluate_is_the_exact_limit_at_corners_and_refuses_bad_points():
    # the exact limit at a triangle's corner is the limit position of that vertex
    V = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    P_lim, N_lim = subdiv.limit(V, F)
    P, N = subdiv.evaluate(V, F, [0, 0, 0], [[0, 0], [1, 0], [0, 1]])
    assert np.allclose(P, P_lim[F[0]], atol=1e-6)
    assert np.allclose(N, N_lim[F[0]], atol=1e-5)
    # curvature: a convex closed surface, H > 0 and K > 0 away from its vertices
    P, N, H, K = subdiv.evaluate(V, F, [1, 2, 3], [[0.2, 0.3], [0.4, 0.4], [0.1, 0.6]], curvature=True)
    assert P.shape == (3, 3) and H.shape == (3,) and (H > 0).all() and (K > 0).all()
    assert np.allclose(np.linalg.norm(N, axis=1), 1)
    for face, uv, what in [([4], [[0.1, 0.1]], "face 4"), ([0], [[0.7, 0.7]], "triangle"), ([-1], [[0.1, 0.1]], "face -1")]:
        with pytest.raises(subdiv.SubdivError, match=what):
            subdiv.evaluate(V, F, face, uv)
    with pytest.raises(TypeError):
        subdiv.evaluate(V, F, [0.5], [[0.1, 0.1]])
    with pytest.raises(ValueError):
        subdiv.evaluate(V, F, [0, 1], [[0.1, 0.1]])


def bspline(t):
    """The uniform cubic B-spline basis at t in [0, 1]."""
    return np.array([(1 - t) ** 3, 3 * t**3 - 6 * t**2 + 4, -3 * t**3 + 3 * t**2 + 3 * t + 1, t**3]) / 6


def height_grid():
    """A 5 x 5 grid of vertices (4 x 4 quads), heights in eighths (exact in
    float32); quad (i, j) lists (i, j), (i+1, j), (i+1, j+1), (i, j+1)."""
    rng = np.random.default_rng(7)
    z = rng.integers(-8, 9, size=(5, 5)) / 8
    V = np.array([[i, j, z[i, j]] for j in range(5) for i in range(5)], float)
    idx = lambda i, j: j * 5 + i  # noqa: E731
    F = np.array([[idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)] for j in range(4) for i in range(4)])
    return V, F, idx


def test_catmull_clark_evaluation_is_the_bicubic_patch_and_follows_creases():
    V, F, idx = height_grid()
    P = V.reshape(5, 5, 3).transpose(1, 0, 2)  # P[i, j] = vertex (i, j)
    # an interior quad (1, 1) is the bicubic B-spline patch of its 4 x 4 points
    face, uv = 1 * 4 + 1, (0.3, 0.7)
    want = np.einsum("k,l,klc->c", bspline(uv[0]), bspline(uv[1]), P[0:4, 0:4])
    got, n = subdiv.evaluate(V, F, [face], [uv], scheme="catmull-clark")
    np.testing.assert_allclose(got[0], want, atol=1e-9)
    assert abs(np.linalg.norm(n[0]) - 1) < 1e-12
    # an infinitely sharp crease along row j = 2: on its edges the surface is
    # the cubic B-spline curve of the row's points
    edges = np.array([[idx(i, 2), idx(i + 1, 2)] for i in range(4)])
    creases = (edges, np.full(4, 10.0))
    for u in (0.0, 0.25, 0.6):
        # quad (1, 2) starts at vertex (1, 2): its edge v = 0 runs along the row
        got, _ = subdiv.evaluate(V, F, [2 * 4 + 1], [[u, 0.0]], scheme="catmull-clark", creases=creases)
        np.testing.assert_allclose(got[0], bspline(u) @ P[0:4, 2], atol=1e-9)
        smooth, _ = subdiv.evaluate(V, F, [2 * 4 + 1], [[u, 0.0]], scheme="catmull-clark")
        assert not np.allclose(smooth[0], got[0], atol=1e-6), "the crease changes the surface"
    # the corner of the open grid stays put only with edge-and-corner
    corner, _ = subdiv.evaluate(V, F, [0], [[0.0, 0.0]], scheme="catmull-clark", boundary="edge-and-corner")
    np.testing.assert_allclose(corner[0], V[0], atol=1e-9)
    edge, _ = subdiv.evaluate(V, F, [0], [[0.0, 0.0]], scheme="catmull-clark")
    assert not np.allclose(edge[0], V[0], atol=1e-6)
    # unit-square points, not barycentric ones; polygons for Loop and
    # schemes without an exact evaluation refused by name
    subdiv.evaluate(V, F, [5], [[0.9, 0.9]], scheme="catmull-clark")
    with pytest.raises(subdiv.SubdivError, match="unit square"):
        subdiv.evaluate(V, F, [5], [[1.2, 0.1]], scheme="catmull-clark")
    with pytest.raises(subdiv.SubdivError, match="triangles"):
        subdiv.evaluate(V, F, [5], [[0.2, 0.1]])
    for scheme in ("bilinear", "butterfly"):
        faces = F if scheme == "bilinear" else np.array([[0, 1, 6], [0, 6, 5]])
        with pytest.raises(subdiv.SubdivError, match=scheme):
            subdiv.evaluate(V, faces, [0], [[0.2, 0.1]], scheme=scheme)
