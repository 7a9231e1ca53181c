"""subdiv.Refiner: edits equal a fresh subdivision of the edited mesh, undo
gives the same bits back, float32 stays float32 and float64 keeps its
digits, the support is where a move reaches, bad input is refused."""

import numpy as np
import pytest

import subdiv

OCT_V = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)
OCT_F = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
CUBE_V = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
CUBE_F = np.array([[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]])


@pytest.mark.parametrize("scheme,V,F", [("loop", OCT_V, OCT_F), ("modified-butterfly", OCT_V, OCT_F),
                                        ("catmull-clark", CUBE_V, CUBE_F)])
def test_a_move_equals_subdividing_the_moved_mesh(scheme, V, F):
    r = subdiv.Refiner(V, F, levels=3, scheme=scheme)
    V0, F0 = subdiv.subdivide(V, F, levels=3, scheme=scheme)
    np.testing.assert_array_equal(r.faces, F0)
    np.testing.assert_allclose(r.vertices, V0, atol=1e-12)
    first = r.vertices
    moved = V.copy()
    moved[[1, 3]] += [[0.25, -0.5, 0.125], [0.0, 0.3, 0.0]]
    V1 = r.move([1, 3], moved[[1, 3]])
    np.testing.assert_allclose(V1, subdiv.subdivide(moved, F, levels=3, scheme=scheme)[0], atol=1e-12)
    assert V1.dtype == np.float64
    assert r.undo()
    # the same bits as before the move (subdivide's one-shot passes may sum
    # in another order than the refiner's rows, within rounding)
    np.testing.assert_array_equal(r.vertices, first)
    assert r.redo()
    np.testing.assert_array_equal(r.vertices, V1)
    assert not r.redo()


def test_float32_stays_float32_and_float64_keeps_its_digits():
    far = OCT_V + 1e6
    r64 = subdiv.Refiner(far, OCT_F, levels=2)
    V64 = r64.move([0], [far[0] + [1e-3, 0, 0]])
    moved = far.copy()
    moved[0] += [1e-3, 0, 0]
    exact = subdiv.subdivide(moved, OCT_F, levels=2)[0]
    assert np.abs(V64 - exact).max() < 1e-9, "a million units out, float64 keeps the millimetre"
    r32 = subdiv.Refiner(OCT_V.astype(np.float32), OCT_F, levels=2)
    assert r32.vertices.dtype == np.float32
    V32 = r32.move([0], np.array([[1.5, 0, 0]], np.float32))
    assert V32.dtype == np.float32


def test_a_crease_equals_subdividing_with_it_and_is_undone():
    r = subdiv.Refiner(CUBE_V, CUBE_F, levels=2, scheme="catmull-clark")
    smooth = r.vertices
    V = r.set_sharpness(0, 1, 2.5)
    expected = subdiv.subdivide(CUBE_V, CUBE_F, levels=2, scheme="catmull-clark",
                                creases=(np.array([[0, 1]]), np.array([2.5])))[0]
    np.testing.assert_allclose(V, expected, atol=1e-6)
    assert np.abs(V - smooth).max() > 1e-3
    r.undo()
    np.testing.assert_array_equal(r.vertices, smooth)


def test_the_support_is_where_a_move_reaches():
    r = subdiv.Refiner(OCT_V, OCT_F, levels=2)
    before = r.vertices
    support = r.support(4)
    after = r.move([4], [[0.1, 0.2, 1.7]])
    moved = np.flatnonzero(np.any(after != before, axis=1))
    assert set(moved) <= set(support.tolist()) and len(moved) > len(support) // 2
    assert len(support) < len(before)


def test_bad_edits_are_refused():
    r = subdiv.Refiner(OCT_V, OCT_F, levels=1)
    with pytest.raises(subdiv.SubdivError):
        r.move([6], [[0, 0, 0]])
    with pytest.raises(subdiv.SubdivError):
        r.move([0], [[np.nan, 0, 0]])
    with pytest.raises(ValueError):
        r.move([0, 1], [[0, 0, 0]])
    with pytest.raises(TypeError):
        r.move([0.5], [[0, 0, 0]])
    with pytest.raises(subdiv.SubdivError):
        r.set_sharpness(0, 1, 2.0)  # not an edge of the octahedron
    assert not r.undo()
