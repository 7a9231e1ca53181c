"""Pickling, for process pools and clusters (multiprocessing, Dask, Ray):
a Mesh, its Prims and a Refiner unpickle to equal objects, equality compares
what they hold (not identity), and a Refiner comes back with its history."""

import copy
import os
import pickle

import numpy as np
import pytest
from conftest import MODELS, REPO, cube_quads, icosahedron, open_grid

import subdiv

USD = os.path.join(REPO, "tests", "fixtures", "usd")


def round_trip(x):
    return pickle.loads(pickle.dumps(x, protocol=pickle.HIGHEST_PROTOCOL))


def same_bytes(a, b):
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


@pytest.mark.parametrize("path", [os.path.join(MODELS, "cube_uv.obj"), os.path.join(MODELS, "critter.obj"),
                                  os.path.join(MODELS, "torus.obj"), os.path.join(USD, "two.usda"),
                                  os.path.join(USD, "mixed.usda")])
def test_a_loaded_mesh_unpickles_to_an_equal_mesh(path):
    m = subdiv.load(path)
    back = round_trip(m)
    assert back is not m and back == m and not (back != m)
    for k in ("vertices", "faces"):
        assert same_bytes(getattr(back, k), getattr(m, k))
    assert back.options == m.options and back.prims == m.prims
    assert copy.deepcopy(m) == m


def test_the_fixtures_cover_attributes_polygons_and_prims(tmp_path):
    # what the round trip above is worth: those files hold each part
    uv = subdiv.load(os.path.join(MODELS, "cube_uv.obj"))
    assert uv.uv is not None and uv.colors is not None
    assert isinstance(subdiv.load(os.path.join(MODELS, "critter.obj")).polygons, np.ndarray)
    # polygons of mixed sizes load as a list of arrays
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]], float)
    subdiv.save(tmp_path / "mixed.obj", v, [[0, 1, 2, 3], [1, 4, 2]])
    mixed = subdiv.load(tmp_path / "mixed.obj")
    assert isinstance(mixed.polygons, list) and mixed == round_trip(mixed)
    two = subdiv.load(os.path.join(USD, "two.usda"))
    assert len(two.prims) == 2 and two.options
    assert two.prims[0] == round_trip(two.prims[0]) and two.prims[0] != two.prims[1]


def test_mesh_equality_compares_every_field():
    v, f = icosahedron()
    m = subdiv.Mesh(v, f, options={"scheme": "loop"})
    assert m == subdiv.Mesh(v.copy(), f.copy(), options={"scheme": "loop"})
    moved = v.copy()
    moved[3, 1] += 1e-12
    assert m != subdiv.Mesh(moved, f, options={"scheme": "loop"})
    assert m != subdiv.Mesh(v, f, options={"scheme": "catmull-clark"})
    assert m != subdiv.Mesh(v.astype(np.float32), f, options={"scheme": "loop"}), "the dtype counts"
    assert m != subdiv.Mesh(v, f, colors=np.zeros_like(v), options={"scheme": "loop"})
    ragged = [np.array([0, 1, 2]), np.array([0, 2, 3, 4])]
    with_polys = subdiv.Mesh(v, f, polygons=ragged)
    assert with_polys == round_trip(with_polys)
    assert with_polys != subdiv.Mesh(v, f, polygons=[ragged[0], ragged[1][::-1]])
    p = subdiv.Prim("/a", {"scheme": "loop"}, [0, 1], np.eye(4))
    assert p != subdiv.Prim("/a", {"scheme": "loop"}, [0, 1], 2 * np.eye(4))
    assert subdiv.Mesh(v, f, prims=[p]) != subdiv.Mesh(v, f, prims=[subdiv.Prim("/b", {}, [0, 1], np.eye(4))])


def edited(dtype=np.float64, scheme="loop"):
    """A refiner with moves, a crease, undos, a redo and a step undone that
    a later edit threw away: each kind of history."""
    if scheme == "loop":
        V, F = open_grid(8)
    else:
        V, F = cube_quads()
    V = V.astype(dtype)
    r = subdiv.Refiner(V, F, levels=2, scheme=scheme, creases=([F[0, :2]], [2.0]))
    r.move([1, 2], V[[1, 2]] + [0, 0, 0.3])
    r.set_sharpness(int(F[1, 0]), int(F[1, 1]), 1.5)
    r.move([0], V[[0]] - 0.2)
    r.undo()
    r.move([3], V[[3]] + 0.1)  # the undone move is gone for good
    r.move([4], V[[4]] * 1.5)
    r.set_sharpness(int(F[2, 1]), int(F[2, 2]), 10)
    r.undo()
    r.undo()
    return r, V, F


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("scheme", ["loop", "catmull-clark"])
def test_a_refiner_unpickles_with_its_vertices_faces_and_history(dtype, scheme):
    r, V, F = edited(dtype, scheme)
    back = round_trip(r)
    assert back == r and back is not r
    assert same_bytes(back.vertices, r.vertices) and back.vertices.dtype == dtype
    assert same_bytes(back.faces, r.faces)
    # the same history: every undo and redo gives the same bits on both
    states = [r.vertices.copy()]
    while r.undo():
        assert back.undo()
        assert same_bytes(back.vertices, r.vertices)
        states.append(r.vertices.copy())
    assert not back.undo()
    assert len(states) == 4, "three steps were done"
    while r.redo():
        assert back.redo()
        assert same_bytes(back.vertices, r.vertices)
    assert not back.redo()
    assert back == r
    # and they go on alike
    rows = r.move([5], V[[5]] + 0.05)
    assert same_bytes(back.move([5], V[[5]] + 0.05), rows)
    assert same_bytes(back.vertices, r.vertices)


def test_an_unpickled_refiner_equals_one_refined_from_its_state():
    # the replayed history is the state, not an approximation of it: a fresh
    # refiner given the same steps without the detours has the same vertices
    r, V, F = edited()
    back = round_trip(r)
    fresh = subdiv.Refiner(V, F, levels=2, creases=([F[0, :2]], [2.0]))
    fresh.move([1, 2], V[[1, 2]] + [0, 0, 0.3])
    fresh.set_sharpness(int(F[1, 0]), int(F[1, 1]), 1.5)
    fresh.move([3], V[[3]] + 0.1)
    assert same_bytes(back.vertices, fresh.vertices)


def test_refiner_equality_follows_the_history_and_the_arguments():
    V, F = icosahedron()
    a, b = subdiv.Refiner(V, F, levels=2), subdiv.Refiner(V.copy(), F.copy(), levels=2)
    assert a == b
    assert a != subdiv.Refiner(V, F, levels=3)
    assert a != subdiv.Refiner(V, F, levels=2, beta="warren")
    assert a != subdiv.Refiner(V.astype(np.float32), F, levels=2)
    a.move([0], V[[0]] * 2)
    assert a != b
    b.move([0], V[[0]] * 2)
    assert a == b
    a.undo()
    assert a != b, "a redo step differs"
    b.undo()
    assert a == b


def test_a_refiner_keeps_its_own_copy_of_the_arguments():
    V, F = icosahedron()
    r = subdiv.Refiner(V, F, levels=1)
    pos = V[[2]] + 1.0
    r.move([2], pos)
    V[:] = 0
    F[:] = 0
    pos[:] = 0
    back = round_trip(r)
    assert same_bytes(back.vertices, r.vertices) and same_bytes(back.faces, r.faces)


def test_a_pickle_of_another_layout_is_refused():
    V, F = icosahedron()
    state = subdiv.Refiner(V, F).__getstate__()
    state["version"] = 999
    r = subdiv.Refiner.__new__(subdiv.Refiner)
    with pytest.raises(subdiv.SubdivError, match="another version"):
        r.__setstate__(state)


def test_subdiv_error_pickles():
    # a worker's failure comes back to the client as the same exception
    with pytest.raises(subdiv.SubdivError) as e:
        subdiv.subdivide([[0, 0, 0]], [[0, 0, 0]])
    back = round_trip(e.value)
    assert type(back) is subdiv.SubdivError and str(back) == str(e.value)
