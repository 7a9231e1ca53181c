"""subdiv.Refiner: edits equal a fresh subdivision of the edited mesh, undo
gives the same bits back, float32 stays float32 and float64 keeps its
digits, the support is where a move reaches, bad input is refused;
``vertices`` is a read-only view the edits update in place, an edit returns
the rows it changed and runs without the GIL."""

import threading
import time

import numpy as np
import pytest
from conftest import open_grid

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
    first = r.vertices.copy()
    moved = V.copy()
    moved[[1, 3]] += [[0.25, -0.5, 0.125], [0.0, 0.3, 0.0]]
    r.move([1, 3], moved[[1, 3]])
    V1 = r.vertices.copy()
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
    r64.move([0], [far[0] + [1e-3, 0, 0]])
    V64 = r64.vertices
    moved = far.copy()
    moved[0] += [1e-3, 0, 0]
    exact = subdiv.subdivide(moved, OCT_F, levels=2)[0]
    assert np.abs(V64 - exact).max() < 1e-9, "a million units out, float64 keeps the millimetre"
    r32 = subdiv.Refiner(OCT_V.astype(np.float32), OCT_F, levels=2)
    assert r32.vertices.dtype == np.float32
    r32.move([0], np.array([[1.5, 0, 0]], np.float32))
    assert r32.vertices.dtype == np.float32


def test_a_crease_equals_subdividing_with_it_and_is_undone():
    r = subdiv.Refiner(CUBE_V, CUBE_F, levels=2, scheme="catmull-clark")
    smooth = r.vertices.copy()
    r.set_sharpness(0, 1, 2.5)
    V = r.vertices
    expected = subdiv.subdivide(CUBE_V, CUBE_F, levels=2, scheme="catmull-clark",
                                creases=(np.array([[0, 1]]), np.array([2.5])))[0]
    np.testing.assert_allclose(V, expected, atol=1e-6)
    assert np.abs(V - smooth).max() > 1e-3
    r.undo()
    np.testing.assert_array_equal(r.vertices, smooth)


def test_the_support_is_where_a_move_reaches():
    r = subdiv.Refiner(OCT_V, OCT_F, levels=2)
    before = r.vertices.copy()
    support = r.support(4)
    r.move([4], [[0.1, 0.2, 1.7]])
    after = r.vertices
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


def test_set_sharpness_refuses_what_subdivide_refuses():
    r = subdiv.Refiner(CUBE_V, CUBE_F, levels=1, scheme="catmull-clark")
    before = r.vertices.copy()
    for bad in (np.nan, -1.0, np.inf, -np.inf):
        with pytest.raises(subdiv.SubdivError) as sub:
            subdiv.subdivide(CUBE_V, CUBE_F, scheme="catmull-clark", creases=([[0, 1]], [bad]))
        with pytest.raises(subdiv.SubdivError) as ref:
            r.set_sharpness(0, 1, bad)
        # one validation: the same words after the element each names
        why = str(sub.value).split(" has ", 1)[1]
        assert str(ref.value) == f"edge 0-1 has {why}", (str(ref.value), str(sub.value))
        assert why.endswith("it must be finite and at least 0")
    np.testing.assert_array_equal(r.vertices, before)
    assert not r.undo(), "no step was made"


def _with_an_unused_vertex(V, F, at):
    """V with a vertex no face uses inserted at row ``at`` (the refiner then
    renumbers: the library drops it, the package puts it back)."""
    V2 = np.insert(V, at, [[7.0, 8.0, 9.0]], axis=0)
    return V2, np.where(F >= at, F + 1, F)


@pytest.mark.parametrize("unused", [False, True])
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_vertices_is_a_read_only_view_that_the_edits_update_in_place(dtype, unused):
    V, F = (_with_an_unused_vertex(OCT_V, OCT_F, 2) if unused else (OCT_V, OCT_F))
    V = V.astype(dtype)
    r = subdiv.Refiner(V, F, levels=2)
    view = r.vertices
    assert view.dtype == dtype and not view.flags.writeable
    with pytest.raises(ValueError):
        view[0, 0] = 1.0
    with pytest.raises(ValueError):
        view.flags.writeable = True  # its base exposes no writable buffer
    assert r.vertices is view or np.shares_memory(r.vertices, view), "no copy"
    moved = V.copy()
    moved[4] = np.array([0.1, 0.2, 1.7], dtype)
    rows = r.move([4], moved[[4]])
    # the array taken before the move shows the moved surface
    expected = subdiv.subdivide(moved, F, levels=2)[0]
    np.testing.assert_allclose(view, expected, atol=1e-6 if dtype == np.float32 else 1e-12)
    if unused:
        np.testing.assert_array_equal(view[2], V[2], "the unused vertex is carried as given")
    r.set_sharpness(0, 2 + unused, 3.0)
    creased = subdiv.subdivide(moved, F, levels=2, creases=([[0, 2 + unused]], [3.0]))[0]
    np.testing.assert_allclose(view, creased, atol=1e-6 if dtype == np.float32 else 1e-12)
    r.undo()
    r.undo()
    np.testing.assert_allclose(view, subdiv.subdivide(V, F, levels=2)[0], atol=1e-6 if dtype == np.float32 else 1e-12)
    del r
    assert np.isfinite(view).all(), "the view keeps the refiner alive"
    assert rows.dtype == np.int64


@pytest.mark.parametrize("unused", [False, True])
def test_an_edit_returns_the_rows_it_changed(unused):
    V, F = open_grid(6)
    if unused:
        V, F = _with_an_unused_vertex(V, F, 5)
    r = subdiv.Refiner(V, F, levels=3)
    n2 = len(r.vertices)
    for edit in (lambda: r.move([10], [V[10] + [0, 0, 0.5]]), lambda: r.set_sharpness(int(F[9, 0]), int(F[9, 1]), 2.0),
                 lambda: r.move([20, 21, 22], V[[20, 21, 22]] - 0.25)):
        before = r.vertices.copy()
        rows = edit()
        after = r.vertices
        changed = np.flatnonzero(np.any(after != before, axis=1))
        assert rows.dtype == np.int64 and rows.ndim == 1
        assert len(changed) > 0 and set(changed) <= set(rows.tolist()), "every changed row is listed"
        assert len(rows) < n2 // 2, "a local edit lists a part of the surface"
        assert len(np.unique(rows)) == len(rows) and rows.min() >= 0 and rows.max() < n2


def test_an_edit_runs_without_the_gil():
    # a counter thread must keep running through a long edit: with the GIL
    # held by the native code it stops for the whole of it (or, the edit
    # being two native calls as it was, for the longer one: gaps of 0.44 to
    # 0.54 of the call were measured); released, its gaps are the
    # scheduler's, a few milliseconds
    V, F = open_grid(100)
    r = subdiv.Refiner(V, F, levels=3)
    ids = np.arange(len(V))
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(time.perf_counter())

    t = threading.Thread(target=count)
    t.start()
    gaps = []
    try:
        for k in range(6):
            t0 = time.perf_counter()
            r.move(ids, V + [0, 0, 0.01 * (k + 1)])
            t1 = time.perf_counter()
            inside = [t0] + [x for x in ticks if t0 < x < t1] + [t1]
            if t1 - t0 > 0.05:
                gaps.append(max(np.diff(inside)) / (t1 - t0))
            if gaps and min(gaps) < 0.25:
                break
    finally:
        stop.set()
        t.join()
    assert gaps, "no edit took long enough to tell"
    assert min(gaps) < 0.25, f"the counter stopped for most of every edit (largest gap / edit: {gaps})"
