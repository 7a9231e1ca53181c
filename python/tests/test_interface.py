"""The interface of subdiv.subdivide: shapes, dtypes, numbering, schemes
and options."""

import numpy as np
import pytest
from conftest import TETRA_F, TETRA_V, bipyramid, cube_quads, cube_triangles, icosahedron, num_edges, open_grid

import subdiv


def test_version_and_error_type():
    assert isinstance(subdiv.__version__, str) and subdiv.__version__.count(".") == 2
    assert issubclass(subdiv.SubdivError, ValueError)
    assert subdiv.SubdivError.__module__ == "subdiv"


@pytest.mark.parametrize("scheme", subdiv.TRIANGLE_SCHEMES)
def test_one_level_counts_and_types(scheme):
    v, f = icosahedron()
    v2, f2 = subdiv.subdivide(v, f, 1, scheme)
    assert v2.dtype == np.float64 and f2.dtype == np.int64
    assert v2.shape == (len(v) + num_edges(f), 3)
    assert f2.shape == (4 * len(f), 3)
    assert f2.min() == 0 and f2.max() == len(v2) - 1


def test_levels_multiply_faces():
    v, f = icosahedron()
    for levels in range(4):
        v2, f2 = subdiv.subdivide(v, f, levels)
        assert len(f2) == len(f) * 4**levels
        # a closed genus-0 mesh: V - E + F = 2
        assert len(v2) - num_edges(f2) + len(f2) == 2


def test_level_zero_is_the_input():
    v, f = icosahedron()
    v2, f2 = subdiv.subdivide(v, f, 0)
    np.testing.assert_allclose(v2, v, rtol=1e-7)
    assert np.array_equal(f2, f)


def test_midpoint_values_exact():
    v = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0]], float)
    v2, f2 = subdiv.subdivide(v, [[0, 1, 2]], 1, "midpoint")
    assert np.array_equal(v2[:3], v)
    assert sorted(map(tuple, v2[3:])) == [(0, 1, 0), (1, 0, 0), (1, 1, 0)]
    # every new triangle keeps the input's orientation (+z normal)
    n = np.cross(v2[f2[:, 1]] - v2[f2[:, 0]], v2[f2[:, 2]] - v2[f2[:, 0]])
    assert np.all(n[:, 2] > 0)


def test_vertex_order_kept_and_unreferenced_carried():
    v, f = icosahedron()
    extra = np.array([[7.0, 8.0, 9.0]])
    # an unused vertex at position 5: every later id shifts by one
    vx = np.vstack([v[:5], extra, v[5:]])
    fx = np.where(f >= 5, f + 1, f)
    a2, af = subdiv.subdivide(v, f, 2)
    b2, bf = subdiv.subdivide(vx, fx, 2)
    assert len(b2) == len(a2) + 1
    assert np.array_equal(b2[5], extra[0])  # carried unchanged
    keep = np.r_[0:5, 6:len(b2)]
    np.testing.assert_array_equal(b2[keep], a2)
    np.testing.assert_array_equal(np.where(bf > 5, bf - 1, bf), af)


def test_input_rows_are_the_refined_input_vertices():
    # Loop at a regular interior vertex of valence 6: 5/8 v + 1/16 sum(ring)
    # (beta 1/16); the apex of a hexagonal bipyramid is one.
    v, f = bipyramid(6, jitter=0.05)
    v2, _ = subdiv.subdivide(v, f, 1)
    expect = 10 / 16 * v[0] + 1 / 16 * v[2:8].sum(axis=0)
    np.testing.assert_allclose(v2[0], expect, rtol=1e-6, atol=1e-6)


def test_beta_names_differ_at_valence_5():
    v, f = bipyramid(5, jitter=0.05)
    a, _ = subdiv.subdivide(v, f, 1, beta="loop")
    b, _ = subdiv.subdivide(v, f, 1, beta="warren")
    # Warren: beta = 3/(8n) = 3/40 at n = 5
    np.testing.assert_allclose(b[0], (1 - 5 * 3 / 40) * v[0] + 3 / 40 * v[2:7].sum(0), atol=1e-6)
    c = np.cos(2 * np.pi / 5)
    beta = (5 / 8 - (3 / 8 + c / 4) ** 2) / 5
    np.testing.assert_allclose(a[0], (1 - 5 * beta) * v[0] + beta * v[2:7].sum(0), atol=1e-6)


def test_boundary_edge_and_corner_pins_one_face_corners():
    v, f = open_grid(3)
    a, _ = subdiv.subdivide(v, f, 1, boundary="edge")
    b, _ = subdiv.subdivide(v, f, 1, boundary="edge-and-corner")
    # grid corner 3 (i=0, j=3) lies in one triangle
    counts = np.bincount(f.ravel(), minlength=len(v))
    corner = int(np.flatnonzero(counts == 1)[0])
    np.testing.assert_allclose(b[corner], v[corner], rtol=1e-7)  # float32 rounding only
    assert not np.allclose(a[corner], v[corner])


def test_creases_follow_the_curve_rule():
    v, f = cube_triangles()
    # crease the four edges around the face x = -1 (vertices 0, 1, 3, 2)
    edges = np.array([[0, 1], [1, 3], [3, 2], [2, 0]])
    v2, _ = subdiv.subdivide(v, f, 1, creases=(edges, np.full(4, 10.0)))
    # a crease vertex with two crease edges: 3/4 v + 1/8 (a + b)
    np.testing.assert_allclose(v2[0], 0.75 * v[0] + 0.125 * (v[1] + v[2]), atol=1e-6)
    smooth, _ = subdiv.subdivide(v, f, 1)
    assert not np.allclose(smooth[0], v2[0])


def test_semi_sharp_crease_lies_between():
    v, f = cube_triangles()
    edges = np.array([[0, 1], [1, 3], [3, 2], [2, 0]])
    sharp, _ = subdiv.subdivide(v, f, 1, creases=(edges, np.full(4, 10.0)))
    smooth, _ = subdiv.subdivide(v, f, 1)
    half, _ = subdiv.subdivide(v, f, 1, creases=(edges, np.full(4, 0.5)))
    t = np.linalg.norm(half[0] - smooth[0]) / np.linalg.norm(sharp[0] - smooth[0])
    assert 0.3 < t < 0.7


@pytest.mark.parametrize("scheme", subdiv.POLYGON_SCHEMES)
def test_quads_as_array_and_as_lists(scheme):
    v, q = cube_quads()
    a, fa = subdiv.subdivide(v, q, 2, scheme)
    b, fb = subdiv.subdivide(v, q.tolist(), 2, scheme)
    assert fa.shape == (6 * 16, 4) and fa.dtype == np.int64
    assert np.array_equal(a, b) and np.array_equal(fa, fb)
    # one level: n + edges + faces vertices
    v1, f1 = subdiv.subdivide(v, q, 1, scheme)
    assert len(v1) == 8 + 12 + 6 and f1.shape == (24, 4)


def test_catmull_clark_mixed_polygons_and_known_points():
    # a cube whose top face is split into two triangles
    v, q = cube_quads()
    faces = [list(x) for x in q if list(x) != [1, 5, 7, 3]] + [[1, 5, 7], [1, 7, 3]]
    v2, f2 = subdiv.subdivide(v, faces, 1, "catmull-clark")
    assert f2.shape == (5 * 4 + 2 * 3, 4)
    # the plain cube: a corner of valence 3 goes to (n-2)/n v + Σe/n² + Σf/n² = (5/9) v in magnitude
    c2, _ = subdiv.subdivide(v, q, 1, "catmull-clark")
    np.testing.assert_allclose(c2[0], v[0] * 5 / 9, atol=1e-6)


def test_triangle_scheme_refuses_polygons():
    v, q = cube_quads()
    with pytest.raises(subdiv.SubdivError, match="triangles"):
        subdiv.subdivide(v, q, 1, "loop")


def test_repair_mends_a_non_manifold_edge():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], float)
    f = np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    with pytest.raises(subdiv.SubdivError, match=r"\(0, 1\)|\(1, 0\)"):
        subdiv.subdivide(v, f, 1)
    v2, f2 = subdiv.subdivide(v, f, 1, repair=True)
    assert f2.shape == (12, 3)
    assert np.isfinite(v2).all()


def test_threads_give_identical_results():
    v, f = icosahedron()
    v2, f2 = subdiv.subdivide(v, f, 5, threads=None)
    for t in (1, 2, 3):
        a, b = subdiv.subdivide(v, f, 5, threads=t)
        assert np.array_equal(a, v2) and np.array_equal(b, f2)


def test_every_function_takes_threads_and_gives_the_same_bits(tmp_path):
    # one thread per call is what a pool of workers asks for; the results
    # are those of the shared pool
    v, f = subdiv.subdivide(*icosahedron(), 3)
    same = lambda a, b: all(np.array_equal(x, y) and x.dtype == y.dtype for x, y in zip(a, b))
    uv = np.full((len(f), 2), 0.25)
    for t in (1, 2):
        assert same(subdiv.limit(v, f, threads=t), subdiv.limit(v, f))
        assert same(subdiv.evaluate(v, f, np.arange(len(f)), uv, threads=t), subdiv.evaluate(v, f, np.arange(len(f)), uv))
        assert (subdiv.matrix(f, 2, threads=t) != subdiv.matrix(f, 2)).nnz == 0
        subdiv.save(tmp_path / f"t{t}.ply", v, f, threads=t)
        assert subdiv.load(tmp_path / f"t{t}.ply", threads=t) == subdiv.load(tmp_path / f"t{t}.ply")
        r = subdiv.Refiner(v, f, 2, threads=t)
        q = subdiv.Refiner(v, f, 2)
        assert same([r.move([0], v[[0]] + 1)], [q.move([0], v[[0]] + 1)]) and r == q
    assert (tmp_path / "t1.ply").read_bytes() == (tmp_path / "t2.ply").read_bytes()


def unaligned(a):
    """A copy of `a` whose data starts one byte off its dtype's alignment (as an
    array unpickled from a network frame or read by ``np.frombuffer`` may)."""
    raw = bytearray(a.nbytes + 1)
    out = np.frombuffer(raw, dtype=a.dtype, count=a.size, offset=1).reshape(a.shape)
    out[...] = a
    assert not out.flags.aligned
    return out


def test_unaligned_arrays_are_taken():
    v, f = icosahedron()
    uv = np.full((len(f), 2), 0.25)
    want = subdiv.subdivide(v, f, 2)
    assert all(np.array_equal(x, y) for x, y in zip(subdiv.subdivide(unaligned(v), unaligned(f), 2), want))
    p, _ = subdiv.evaluate(unaligned(v), f, unaligned(np.arange(len(f))), unaligned(uv))
    assert np.array_equal(p, subdiv.evaluate(v, f, np.arange(len(f)), uv)[0])
    assert np.array_equal(subdiv.limit(v, f, creases=(unaligned(f[:2, :2]), unaligned(np.ones(2))))[0],
                          subdiv.limit(v, f, creases=(f[:2, :2], np.ones(2)))[0])
    r, q = subdiv.Refiner(unaligned(v), f, 2), subdiv.Refiner(v, f, 2)
    assert np.array_equal(r.move(unaligned(np.array([1])), unaligned(v[[1]] + 1)), q.move([1], v[[1]] + 1))
    assert np.array_equal(r.vertices, q.vertices)


def test_array_likes_and_dtypes():
    a, fa = subdiv.subdivide(TETRA_V.tolist(), TETRA_F.tolist(), 1)
    b, fb = subdiv.subdivide(TETRA_V.astype(np.float32), TETRA_F.astype(np.uint16), 1)
    c, fc = subdiv.subdivide(np.asfortranarray(TETRA_V), TETRA_F[:, :].astype(np.int32), 1)
    assert np.array_equal(a, b) and np.array_equal(a, c)
    assert np.array_equal(fa, fb) and np.array_equal(fa, fc)
