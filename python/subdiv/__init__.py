"""subdiv: subdivision surfaces from numpy.

Loop (Loop's or Warren's beta), midpoint, butterfly, modified butterfly and
Jarek on triangle meshes; Catmull-Clark and bilinear on polygon meshes;
creases, limit positions and normals, stencil matrices, every file format
of the ``subdiv`` command line, and an offscreen renderer. The work is done
by the Rust library ``subdiv`` (the same code as the command line), with the
GIL released; nothing you pass can crash the interpreter: refused values
raise :class:`SubdivError`.

>>> import numpy as np, subdiv
>>> V = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
>>> F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
>>> V2, F2 = subdiv.subdivide(V, F, levels=2)
>>> V2.shape, F2.shape
((34, 3), (64, 3))
"""

from __future__ import annotations

import os

import numpy as np

from . import _checks, _subdiv
from ._subdiv import SubdivError, __version__

SubdivError.__module__ = "subdiv"

__all__ = [
    "SubdivError",
    "evaluate",
    "Mesh",
    "Prim",
    "Refiner",
    "subdivide",
    "matrix",
    "limit",
    "tessellate",
    "load",
    "save",
    "subdivide_file",
    "render",
    "view",
    "TRIANGLE_SCHEMES",
    "POLYGON_SCHEMES",
    "__version__",
]

#: The schemes of triangle meshes: faces ``(m, 3)`` in, ``(4m, 3)`` out per level.
TRIANGLE_SCHEMES = ("midpoint", "loop", "butterfly", "modified-butterfly", "jarek")
#: The schemes of polygon meshes: faces of any size in, quads ``(m2, 4)`` out.
POLYGON_SCHEMES = ("catmull-clark", "bilinear")


#: The layout of a pickled :class:`Refiner` (another is refused on unpickling).
_PICKLE_VERSION = 1


def _same(a, b) -> bool:
    """Equal values: arrays of the same dtype and shape, element by element
    (NaN equal to NaN), lists and tuples item by item, anything else by ``==``."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        if not (isinstance(a, np.ndarray) and isinstance(b, np.ndarray)) or (a.dtype, a.shape) != (b.dtype, b.shape):
            return False
        return bool(np.array_equal(a, b, equal_nan=a.dtype.kind in "fc"))
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return type(a) is type(b) and len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return bool(a == b)


def _own(arrays, dtypes):
    """Arrays of `dtypes` as the native module reads them (copies where they were not)."""
    return tuple(_checks.native(a, d) for a, d in zip(arrays, dtypes))


def _names(scheme, beta, boundary):
    return (_checks.name(scheme, "scheme"), _checks.name(beta, "beta"), _checks.name(boundary, "boundary"))


def _options(scheme="loop", beta="loop", boundary="edge", fvar="corners-only", triangles="catmark",
             creasing="uniform"):
    """The scheme and the option names, in the order the native module takes
    them (the library parses each, as the command line's flags)."""
    return _names(scheme, beta, boundary) + (_checks.name(fvar, "fvar"), _checks.name(triangles, "triangles"),
                                             _checks.name(creasing, "creasing"))


def subdivide(vertices, faces, levels=1, scheme="loop", *, beta="loop", boundary="edge", fvar="corners-only",
              triangles="catmark", creasing="uniform", creases=None, holes=None, repair=False, threads=None):
    """Subdivide a mesh ``levels`` times.

    Parameters
    ----------
    vertices : array-like (n, 3) of float
    faces : array-like (m, 3) of int for the triangle schemes; for
        ``catmull-clark`` and ``bilinear`` also (m, k) arrays or lists of
        polygons of any size.
    levels : int, 0 or more.
    scheme : ``"loop"`` (default), ``"midpoint"``, ``"butterfly"``,
        ``"modified-butterfly"``, ``"jarek"``, ``"catmull-clark"``, ``"bilinear"``.
    beta : ``"loop"`` (Loop's original vertex weights, as trimesh) or
        ``"warren"`` (as libigl and Open3D).
    boundary : ``"edge"``, ``"edge-and-corner"`` (boundary vertices with
        one face stay put) or ``"none"`` (the faces at the border left out,
        their vertices still shaping the rest).
    fvar : how texture coordinates are refined (``"none"``, ``"corners-only"``,
        ``"corners-plus1"``, ``"corners-plus2"``, ``"boundaries"``, ``"all"``);
        checked, but these arrays carry no texture coordinates.
    triangles : ``"catmark"`` or ``"smooth"``, Catmull-Clark's rule on triangles.
    creasing : ``"uniform"`` or ``"chaikin"``, how semi-sharp creases decay.
    creases : None or ``(edges (k, 2) int, sharpness (k,) float)``;
        sharpness 10 or more is infinitely sharp, below decays a level at a time.
    holes : None or face ids (rows of ``faces``) left out of the surface.
    repair : repair a non-manifold mesh instead of refusing it (the vertex
        order is then the repaired mesh's).
    threads : None (all cores) or the number of threads; the result is the
        same bit for bit.

    Returns
    -------
    V2 : float64 (n2, 3). Row ``i < n`` is the refined position of input
        vertex ``i``; vertices no face uses are carried unchanged.
    F2 : int64 (m2, 3) (triangle schemes) or (m2, 4) (quads).
        At one level of a triangle scheme ``n2 = n + edges``, ``m2 = 4 m``.

    Raises
    ------
    SubdivError : a non-manifold mesh (naming the edge's vertex ids), an
        index out of range, a non-finite coordinate, an unknown name, a
        level count that does not fit in memory (refused before allocating).
    TypeError, ValueError : wrong shapes or dtypes (float faces are refused).

    Examples
    --------
    >>> import numpy as np, subdiv
    >>> V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)
    >>> V2, F2 = subdiv.subdivide(V, [[0, 1, 2]], levels=1, scheme="midpoint")
    >>> V2[3:].tolist()  # one point per edge, the edge opposite corner 0 first
    [[0.5, 0.5, 0.0], [0.0, 0.5, 0.0], [0.5, 0.0, 0.0]]
    """
    v, single = _checks.vertices(vertices), _checks.is_float32(vertices)
    corners, starts = _checks.faces(faces)
    mesh = (v, corners, starts)
    names = _options(scheme, beta, boundary, fvar, triangles, creasing)
    v2, f2 = _subdiv.subdivide_arrays(mesh, _checks.tags(creases, holes), names, _checks.levels(levels),
                                      (bool(repair), not single), _checks.threads(threads))
    # float32 in: computed in float32, handed back as float32 (exactly)
    return (v2.astype(np.float32) if single else v2), f2


class Refiner:
    """A mesh refined ``levels`` times once, then edited: control vertices
    moved, edges creased, steps undone, each edit evaluating again only the
    refined vertices it reaches (OpenSubdiv's ``TopologyRefiner`` with its
    stencil table, updated locally), with the GIL released.

    Parameters are those of :func:`subdivide` (``repair`` aside: the
    vertex ids are the caller's; ``threads`` serves the construction and
    every edit). Float32 vertices are refined in float32;
    float64 ones in float64 (the control rows as given, the rules' float64
    weights).

    ``vertices`` is a read-only view that the edits update in place (in
    the input's dtype, never copied); ``move`` and ``set_sharpness`` return
    the rows they changed.

    A refiner pickles (and ``copy.deepcopy`` copies it) as its arguments and
    its history: unpickling refines anew and replays the steps, so the copy
    has the same vertices, faces, undo and redo, and compares equal (``==``:
    the same arguments, history and vertices).

    >>> import numpy as np, subdiv
    >>> V = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    >>> F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    >>> r = subdiv.Refiner(V, F, levels=2)
    >>> V2 = r.vertices  # a live view
    >>> before = V2.copy()
    >>> rows = r.move([0], [[2.0, 2.0, 2.0]])
    >>> V2.shape, r.faces.shape, bool((V2[rows] != before[rows]).any())
    ((34, 3), (64, 3), True)
    >>> r.undo(), bool((V2 == before).all())
    (True, True)
    """

    def __init__(self, vertices, faces, levels=1, scheme="loop", *, beta="loop", boundary="edge",
                 fvar="corners-only", triangles="catmark", creasing="uniform", creases=None, holes=None,
                 threads=None):
        single = _checks.is_float32(vertices)
        v = _checks.vertices(vertices)
        corners, starts = _checks.faces(faces)
        names = _options(scheme, beta, boundary, fvar, triangles, creasing)
        tags = _checks.tags(creases, holes)
        # the arguments as checked, copied (the caller may change its arrays
        # later): what a pickle holds, with the history
        own = tuple(np.array(a, copy=True) for a in (v, corners, starts) + tags)
        self._setup(own[:3], own[3:], names, _checks.levels(levels), single, _checks.threads(threads))

    def _setup(self, mesh, tags, names, levels, single, threads):
        # as the native module takes them (an unpickled array may come in any layout)
        mesh, tags = _own(mesh, (np.float64, np.int64, np.int64)), _own(tags, (np.int64, np.float64, np.int64))
        self._args = (mesh, tags, tuple(names), int(levels), bool(single))
        self._threads = threads
        self._native = _subdiv.NativeRefiner(mesh, tags, names, levels, not single, threads)
        self._single = bool(single)
        self._vertices = self._native.vertices()
        # the library's history mirrored: the steps done, and those undone
        # (the next to redo last), each ("move", ids, positions) or
        # ("sharpness", v0, v1, s) as the library got it
        self._done, self._undone = [], []

    def _edit(self, step):
        kind = step[0]
        if kind == "move":
            step = ("move",) + _own(step[1:], (np.int64, np.float64))
            rows = self._native.move_vertices(step[1], step[2])
        elif kind == "sharpness":
            rows = self._native.set_sharpness(step[1], step[2], step[3])
        else:
            raise ValueError(f"unknown step {kind!r} in a Refiner's history")
        self._done.append(step)
        self._undone.clear()
        return rows

    def __getstate__(self):
        """What a pickle holds: the constructor's arguments as checked and the
        history (done and undone steps); unpickling builds the refiner
        anew and replays it, so vertices, undo and redo are the same."""
        mesh, tags, names, levels, single = self._args
        return {"version": _PICKLE_VERSION, "mesh": mesh, "tags": tags, "names": names, "levels": levels,
                "single": single, "threads": self._threads, "done": list(self._done),
                "undone": list(self._undone)}

    def __setstate__(self, state):
        if not isinstance(state, dict) or state.get("version") != _PICKLE_VERSION:
            raise SubdivError("this pickle of a Refiner comes from another version of subdiv")
        self._setup(state["mesh"], state["tags"], state["names"], state["levels"], state["single"],
                    state["threads"])
        undone = state["undone"]
        # the undone steps redone in the order redo would take them, then undone
        for step in list(state["done"]) + undone[::-1]:
            self._edit(step)
        for _ in undone:
            self.undo()

    def __eq__(self, other):
        """Refiners are equal when built from the same arguments with the same
        history (done and undone steps) and so the same refined vertices."""
        if not isinstance(other, Refiner):
            return NotImplemented
        a, b = self._args, other._args
        return (a[2:] == b[2:] and _same(list(a[0] + a[1]), list(b[0] + b[1]))
                and _same(self._done, other._done) and _same(self._undone, other._undone)
                and _same(self._vertices, other._vertices))

    __hash__ = None

    @property
    def vertices(self):
        """The refined vertices ``(n2, 3)``, in the input's dtype: a
        read-only view of the refiner's own points (or, where vertices no
        face uses are put back, of its copy in your numbering) that every
        edit updates in place. Take ``.copy()`` to keep a state."""
        return self._vertices

    @property
    def faces(self):
        """The refined faces: int64 ``(m2, 3)`` or ``(m2, 4)`` (holes left out)."""
        return self._native.faces()

    def move(self, ids, positions):
        """Moves control vertices ``ids`` (k,) to ``positions`` (k, 3); one
        step of the history. Returns the rows of :attr:`vertices` it
        evaluated again (int64, those that changed among them)."""
        ids = np.asarray(ids)
        if ids.dtype.kind not in "iu":
            raise TypeError("ids must be integers")
        ids = _checks.native(ids, np.int64).reshape(-1)
        pos = _checks.vertices(positions)
        if pos.shape[0] != ids.shape[0]:
            raise ValueError(f"{ids.shape[0]} ids but {pos.shape[0]} positions")
        return self._edit(("move", ids.copy(), pos.copy()))

    def set_sharpness(self, v0, v1, sharpness):
        """The sharpness of the edge ``v0``-``v1`` (0 smooth, 10 or more
        infinitely sharp; NaN, infinities and negative values are refused as
        :func:`subdivide` refuses them); one step of the history. Returns the
        rows of :attr:`vertices` it evaluated again."""
        return self._edit(("sharpness", int(v0), int(v1), float(sharpness)))

    def undo(self) -> bool:
        """Undoes the last move or sharpness; whether there was one."""
        done = self._native.undo()
        if done:
            self._undone.append(self._done.pop())
        return done

    def redo(self) -> bool:
        """Redoes the last undone step; whether there was one."""
        done = self._native.redo()
        if done:
            self._done.append(self._undone.pop())
        return done

    def support(self, vertex):
        """The refined vertices that control vertex ``vertex`` moves (int64, sorted)."""
        return np.sort(self._native.support(int(vertex)))


def matrix(faces, levels=1, scheme="loop", *, n_vertices=None, beta="loop", boundary="edge", triangles="catmark",
           creasing="uniform", creases=None, holes=None, return_faces=False, threads=None):
    """The subdivision matrix ``S`` (scipy.sparse.csr_matrix, (n2, n)):
    ``S @ V`` equals ``subdivide(V, faces, levels, scheme, ...)[0]`` for
    any float64 ``V`` of ``n`` rows (to double precision: the weights are the
    rules' own, in float64, and each row sums to 1 within 1e-15), on the
    same faces ``F2``. It is composed from the library's stencil plan, level
    by level.

    Parameters
    ----------
    faces, levels, scheme, beta, boundary, triangles, creasing, creases,
    holes : as :func:`subdivide`.
    n_vertices : the number of control vertices (default: the largest index
        in ``faces`` plus one); vertices no face uses get an identity row.
    return_faces : also return ``F2``, the faces of ``subdivide``.
    threads : as for :func:`subdivide` (the plan's threads; scipy composes).

    Returns
    -------
    S : scipy.sparse.csr_matrix, float64 (n2, n); or ``(S, F2)`` with
        ``return_faces=True``, ``F2`` int64 (m2, 3) or (m2, 4).

    Examples
    --------
    >>> import numpy as np, subdiv
    >>> F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    >>> S = subdiv.matrix(F, levels=1)
    >>> S.shape, bool(np.allclose(S.sum(axis=1), 1))
    ((10, 4), True)
    """
    from ._matrix import compose

    corners, starts = _checks.faces(faces)
    if n_vertices is None:
        n = int(corners.max()) + 1 if corners.size else 0
    else:
        n = _checks.count(n_vertices, "n_vertices")
    names = _options(scheme, beta, boundary, triangles=triangles, creasing=creasing)
    plan = _subdiv.plan_levels((corners, starts), n, _checks.tags(creases, holes), names, _checks.levels(levels),
                               _checks.threads(threads))
    s, f2 = compose(*plan)
    return (s, f2) if return_faces else s


def limit(vertices, faces, *, beta="loop", boundary="edge", creases=None, threads=None):
    """Loop limit positions and unit limit normals of every vertex
    (``beta``, ``boundary``, ``creases`` and ``threads`` as for :func:`subdivide`).

    Returns
    -------
    P : (n, 3), the point of the limit surface each vertex converges to, in the
        vertices' dtype (float64 rows are taken as given).
    N : (n, 3), unit normals (zero for a vertex no face uses).

    Examples
    --------
    >>> import numpy as np, subdiv
    >>> V = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    >>> F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    >>> P, N = subdiv.limit(V, F)
    >>> bool(np.allclose(np.linalg.norm(N, axis=1), 1))
    True
    """
    v = _checks.vertices(vertices)
    corners, starts = _checks.faces(faces)
    names = (_checks.name(beta, "beta"), _checks.name(boundary, "boundary"))
    single = _checks.is_float32(vertices)
    p, n = _subdiv.limit_arrays((v, corners, starts), _checks.tags(creases), names, not single,
                                _checks.threads(threads))
    # float64 in: the limit of the rows as given; float32: computed and handed back in float32
    return (p.astype(np.float32), n.astype(np.float32)) if single else (p, n)


def evaluate(vertices, faces, face, uv, *, scheme="loop", beta="loop", boundary="edge", triangles="catmark",
             creasing="uniform", creases=None, curvature=False, threads=None):
    """The exact limit surface at points of the control faces, as ``subdiv
    eval`` computes it.

    Loop (``scheme="loop"``, triangles): a point is a control triangle
    ``face[i]`` (its index in ``faces``) and barycentric ``uv[i] = (u, v)``:
    the point ``(1-u-v) c0 + u c1 + v c2`` of the triangle's corners in the
    order ``faces`` lists them. Catmull-Clark (``scheme="catmull-clark"``,
    polygons as ``subdivide`` takes them): ``face[i]`` is a ptex face (a
    quad is one, an n-gon n, one per corner, in face order) and ``uv[i]``
    lies in its unit square, corner 0 of a quad at (0, 0), 1 at (1, 0), 2
    at (1, 1). Exact at any point (no fixed-level approximation), borders,
    creases and corners included (``beta``, ``boundary``, ``triangles``,
    ``creasing``, ``creases`` and ``threads`` as for :func:`subdivide`).

    Returns
    -------
    P : (k, 3), limit positions, in the vertices' dtype: float64 control
        points are evaluated as given (in float64), float32 ones as float32.
    N : (k, 3), unit normals (on the side the winding makes the front).
    H, K : (k,), mean and Gaussian curvature, only with
        ``curvature=True`` (``H > 0`` on a convex surface with outward normals;
        NaN at an extraordinary vertex itself).

    Raises
    ------
    SubdivError : a face out of range, a point outside its face, a scheme
        without an exact evaluation (the interpolating ones, bilinear), a mesh
        the library refuses.

    Examples
    --------
    >>> import numpy as np, subdiv
    >>> V = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    >>> F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    >>> P, N, H, K = subdiv.evaluate(V, F, [0, 1], [[0.2, 0.3], [0.5, 0.5]], curvature=True)
    >>> bool((H > 0).all() and (K > 0).all())
    True
    """
    v = _checks.vertices(vertices)
    corners, starts = _checks.faces(faces)
    f = _checks._int_array(np.atleast_1d(np.asarray(face)), "face")
    if f.ndim != 1:
        raise ValueError(f"face must be one index per point, got shape {f.shape}")
    w = np.asarray(uv)
    if w.dtype.kind not in "fiu":
        raise TypeError(f"uv must be real numbers, got dtype {w.dtype}")
    w = _checks.native(np.atleast_2d(w), np.float64)
    if w.ndim != 2 or w.shape != (f.shape[0], 2):
        raise ValueError(f"uv must have shape ({f.shape[0]}, 2), got shape {w.shape}")
    single = _checks.is_float32(vertices)
    names = _options(scheme, beta, boundary, triangles=triangles, creasing=creasing)
    p, n, hk = _subdiv.evaluate_arrays((v, corners, starts), _checks.tags(creases), names, (f, w),
                                       (bool(curvature), not single), _checks.threads(threads))
    # float64 control points are evaluated as given; float32 ones as float32,
    # the results handed back in float32
    dtype = np.float32 if single else np.float64
    p, n = p.astype(dtype, copy=False), n.astype(dtype, copy=False)
    if curvature:
        return p, n, hk[:, 0].astype(dtype), hk[:, 1].astype(dtype)
    return p, n



def tessellate(vertices, faces, tolerance="1e-4x", *, scheme="loop", beta="loop", boundary="edge",
               triangles="catmark", creasing="uniform", creases=None, threads=None):
    """The exact limit surface as a crack-free triangle mesh, fine only where
    it bends, as ``subdiv tessellate`` makes it: every vertex on the limit,
    every triangle measured within ``tolerance`` of it (at its centre and its
    edges' midpoints, against the limit at the same ``(u, v)``).

    ``tolerance`` is a distance in the mesh's units (``1e-3``) or a fraction
    of the control points' bounding-box diagonal (``"1e-4x"``, the default).
    ``scheme`` is ``"loop"`` (triangles) or ``"catmull-clark"`` (polygons, as
    :func:`subdivide` takes them); the other options as for :func:`subdivide`.
    A warning says when the tolerance was not met within the rounds allowed.

    Returns
    -------
    V : (k, 3) float64, points on the limit surface.
    F : (t, 3) int64, triangles, counter-clockwise seen from the front.
    N : (k, 3) float64, the limit's unit normals there.
    face, uv : (k,) int64 and (k, 2) float64, each vertex's control face and
        ``(u, v)`` on it, the points :func:`evaluate` takes (Loop: control
        triangle; Catmull-Clark: ptex face): attributes evaluated later
        without refining.

    Examples
    --------
    >>> import numpy as np, subdiv
    >>> V = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    >>> F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    >>> P, T, N, face, uv = subdiv.tessellate(V, F, "1e-3x")
    >>> bool(np.allclose(subdiv.evaluate(V, F, face, uv)[0], P))
    True
    """
    v = _checks.vertices(vertices)
    corners, starts = _checks.faces(faces)
    if isinstance(tolerance, bool) or not isinstance(tolerance, (str, int, float, np.integer, np.floating)):
        raise ValueError(f"tolerance {tolerance!r}: a positive distance, or a fraction of the diagonal such as '1e-4x'")
    # read by the library, as the command line reads it
    t = tolerance if isinstance(tolerance, str) else repr(float(tolerance))
    names = _options(scheme, beta, boundary, triangles=triangles, creasing=creasing)
    p, n, tri, face, uv, (asked, measured, met) = _subdiv.tessellate_arrays(
        (v, corners, starts), _checks.tags(creases), names, t, not _checks.is_float32(vertices),
        _checks.threads(threads))
    if not met:
        import warnings
        warnings.warn(f"the largest distance measured, {measured:g}, is over the tolerance {asked:g}", stacklevel=2)
    return p, tri, n, face[:, 0], uv


class Mesh:
    """What :func:`load` read.

    Attributes
    ----------
    vertices : float64 (n, 3)
    faces : int64 (m, 3), triangles (polygons fanned)
    uv : float64 (m, 3, 2) per triangle corner, or None
    colors : float64 (n, 3) linear RGB in [0, 1], or None
    polygons : the file's polygons when they are not all triangles: an int64
        (m, k) array when all have k corners, else a list of int64 arrays; None
        for a triangle mesh.
    options : the subdivision options the file states (OBJ's ``t
        interpolateboundary``, ``t facevaryinginterpolateboundary``, ``t
        smoothtriangles``, ``t creasemethod``, USD's ``subdivisionScheme``
        and interpolation attributes), by the names :func:`subdivide` takes
        (``scheme``, ``boundary``, ``fvar``, ``triangles``, ``creasing``),
        only those the file states: ``subdivide(m.vertices, m.faces,
        **m.options)``. A file whose scheme is ``none`` says
        ``scheme="none"``, which :func:`subdivide` refuses (the cage is the
        surface). The options of the whole file (a stage's first prim's).
    prims : a USD stage's Mesh prims, each a :class:`Prim` with its own path,
        options (the names above), triangles (rows of ``faces``) and 4 x 4
        local-to-world transform (the vertices are already in world space);
        empty for other formats. ``subdivide(m.vertices, m.faces[p.faces],
        **p.options)`` refines one prim by its own rules.
    """

    __slots__ = ("vertices", "faces", "uv", "colors", "polygons", "options", "prims")

    def __init__(self, vertices, faces, uv=None, colors=None, polygons=None, options=None, prims=()):
        self.vertices, self.faces, self.uv, self.colors, self.polygons = vertices, faces, uv, colors, polygons
        self.options = {} if options is None else dict(options)
        self.prims = list(prims)

    def __eq__(self, other):
        """Equal arrays (dtype, shape, values), options and prims."""
        if not isinstance(other, Mesh):
            return NotImplemented
        return all(_same(getattr(self, k), getattr(other, k)) for k in Mesh.__slots__)

    __hash__ = None

    def __reduce__(self):
        return (Mesh, tuple(getattr(self, k) for k in Mesh.__slots__))

    def __repr__(self):
        extra = "".join(f", {k}" for k in ("uv", "colors", "polygons") if getattr(self, k) is not None)
        return f"subdiv.Mesh({len(self.vertices)} vertices, {len(self.faces)} triangles{extra})"


class Prim:
    """One Mesh prim of a USD stage (see :attr:`Mesh.prims`): ``path``,
    ``options`` (a dict by :func:`subdivide`'s names), ``faces`` (int64 ids of
    the mesh's triangles), ``transform`` (float64 (4, 4), column vectors)."""

    __slots__ = ("path", "options", "faces", "transform")

    def __init__(self, path, options, faces, transform):
        self.path, self.options = path, dict(options)
        self.faces = np.asarray(faces, dtype=np.int64)
        self.transform = np.asarray(transform, dtype=np.float64).reshape(4, 4)

    def __eq__(self, other):
        """Equal paths, options, faces and transforms."""
        if not isinstance(other, Prim):
            return NotImplemented
        return all(_same(getattr(self, k), getattr(other, k)) for k in Prim.__slots__)

    __hash__ = None

    def __reduce__(self):
        return (Prim, tuple(getattr(self, k) for k in Prim.__slots__))

    def __repr__(self):
        return f"subdiv.Prim({self.path!r}, {len(self.faces)} triangles, {self.options})"


def load(path, *, repair=False, time=None, threads=None) -> Mesh:
    """Read a mesh file (OBJ with MTL, ``.ct``, PLY, STL, OFF, glTF/GLB,
    COLLADA, Bezier patches), the format chosen by the extension, else by
    the content. Vertices no face uses are dropped. ``repair=True`` mends a
    non-manifold mesh (as ``subdivide``'s ``repair``; attributes are then dropped).
    ``time`` reads a USD stage's sampled points at that time code (default:
    its ``startTimeCode``, else its first sample). A stage's prims come in
    :attr:`Mesh.prims`, each with its own options. ``threads`` as for
    :func:`subdivide` (one thread per call where a pool of workers reads
    many files side by side).

    Raises :class:`SubdivError` naming the file, the line or element and the
    problem (also for a mesh that is not manifold).

    >>> import subdiv, tempfile, os
    >>> p = os.path.join(tempfile.mkdtemp(), "t.obj")
    >>> subdiv.save(p, [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    >>> subdiv.load(p).faces.tolist()
    [[0, 1, 2]]
    """
    t = None if time is None else float(time)
    v, f, uv, colors, polys, options, prims = _subdiv.load_file(path, bool(repair), t, _checks.threads(threads))
    if uv is not None:
        uv = uv.reshape(-1, 3, 2)
    if polys is not None:
        corners, starts = polys[0].reshape(-1), polys[1].reshape(-1)
        sizes = np.diff(starts)
        if sizes.size and np.all(sizes == sizes[0]):
            polys = corners.reshape(-1, int(sizes[0]))
        else:
            polys = np.split(corners, starts[1:-1])
    return Mesh(v, f, uv, colors, polys, dict(options), [Prim(*p) for p in prims])


def save(path, vertices, faces, *, threads=None) -> None:
    """Write a mesh, the format chosen by the extension (``.obj``, ``.ply``,
    ``.off``, ``.stl``, ``.glb``, ``.ct``); polygons (quads, lists) are kept as
    polygons by OBJ, PLY, OFF and ``.ct``. The file is written atomically.
    The mesh must be manifold (vertices no face uses are dropped).
    ``threads`` as for :func:`subdivide`."""
    v = _checks.vertices(vertices)
    corners, starts = _checks.faces(faces)
    _subdiv.save_file(path, (v, corners, starts), _checks.threads(threads))


def subdivide_file(input, output, levels=1, scheme=None, *, beta="loop", boundary=None, fvar=None, triangles=None,
                   creasing=None, repair=False, precision="f32", time=None, threads=None) -> dict:
    """Read the model ``input``, refine it ``levels`` times and write it to
    ``output`` (the format by its extension, written atomically: no partial
    file is ever left), in one native call with the GIL released: exactly
    what ``subdiv subdivide INPUT OUTPUT`` writes, and what ``subdiv batch``
    writes for each file (the library's one call, ``subdiv::subdivide_file``).

    Nothing is copied into Python: the refinement's own tables are written
    (the texture coordinates, colours and materials too where the format
    keeps them), which makes a folder of files a loop of these calls
    (docs/dask.md).

    Parameters
    ----------
    input : a mesh file (every format :func:`load` reads) or ``"bundled:NAME"``.
    output : the file written (``.obj``, ``.ply``, ``.off``, ``.stl``, ``.glb``,
        ``.ct``, ``.usda``, ...); its folder must exist.
    levels : int, 0 or more (a file that says ``subdivisionScheme none`` gets none).
    scheme : None (the file's ``subdivisionScheme``, else ``"loop"``) or a
        scheme name as for :func:`subdivide`.
    beta : ``"loop"`` or ``"warren"``, as for :func:`subdivide`.
    boundary, fvar, triangles, creasing : None (the option the file states,
        else the default) or a name as for :func:`subdivide`, taking the
        place of the file's.
    repair : mend a non-manifold mesh instead of refusing it.
    precision : ``"f32"`` (the default, as the command line) or ``"f64"``
        (from the file's own digits, written at full precision by OBJ and PLY).
    time : the time code a USD stage's sampled points are read at.
    threads : as for :func:`subdivide` (``1`` where a pool of workers runs
        many files side by side).

    Returns
    -------
    dict : what a line of ``subdiv batch``'s manifest says of the file:
        ``input``, ``output``, ``status`` (``"done"``), ``scheme``,
        ``levels``, ``input_vertices``, ``input_faces``, ``vertices``,
        ``faces``, ``output_bytes`` and ``seconds``.

    Raises
    ------
    SubdivError : the library's one-line message, naming ``input``: a file
        that cannot be read or is not manifold, an unknown name, a level
        count that does not fit in memory, an output that cannot be written.

    Examples
    --------
    >>> import subdiv, tempfile, os
    >>> d = tempfile.mkdtemp()
    >>> subdiv.save(os.path.join(d, "t.obj"), [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    >>> r = subdiv.subdivide_file(os.path.join(d, "t.obj"), os.path.join(d, "t2.ply"), levels=2)
    >>> r["status"], r["faces"], subdiv.load(os.path.join(d, "t2.ply")).faces.shape
    ('done', 16, (16, 3))
    """
    names = (None if scheme is None else _checks.name(scheme, "scheme"), _checks.name(beta, "beta"))
    names += tuple(None if x is None else _checks.name(x, w) for x, w in
                   ((boundary, "boundary"), (fvar, "fvar"), (triangles, "triangles"), (creasing, "creasing")))
    if precision not in ("f32", "f64"):
        raise SubdivError(f"precision must be 'f32' or 'f64', got {precision!r}")
    t = None if time is None else float(time)
    in_path, out_path = os.fspath(input), os.fspath(output)
    scheme_done, levels_done, nv, nf, v2, f2, size, seconds = _subdiv.subdivide_file(
        (in_path, out_path), _checks.levels(levels), names, (bool(repair), precision == "f64"), t,
        _checks.threads(threads))
    return {"input": in_path, "output": out_path, "status": "done", "scheme": scheme_done, "levels": levels_done,
            "input_vertices": nv, "input_faces": nf, "vertices": v2, "faces": f2, "output_bytes": size,
            "seconds": seconds}


def _viewer():
    if not _subdiv.HAS_VIEWER:
        raise SubdivError("this build of subdiv has no viewer (built without the 'viewer' feature)")


def render(vertices, faces, *, size=(640, 480), shading="phong", levels=0, scheme="loop", beta="loop",
           boundary="edge", creases=None):
    """Render the mesh (subdivided ``levels`` times with ``scheme``)
    offscreen, the camera framing it.

    shading : ``"phong"``, ``"flat"``, ``"studio"``, ``"wire"`` or ``"phong+wire"``.

    Returns an RGBA image, numpy uint8 (height, width, 4). Needs a GPU
    adapter; Mesa's software Vulkan (lavapipe) suffices.

    >>> import numpy as np, subdiv
    >>> V = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    >>> F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    >>> subdiv.render(V, F, size=(64, 48), levels=2).shape  # doctest: +SKIP
    (48, 64, 4)
    """
    _viewer()
    v = _checks.vertices(vertices)
    corners, starts = _checks.faces(faces)
    w, h = _checks.size(size)
    names = _names(scheme, beta, boundary) + (_checks.name(shading, "shading"),)
    return _subdiv.render_image((v, corners, starts), _checks.tags(creases), names, _checks.levels(levels),
                                (w, h))


def view(vertices, faces, *, levels=0, scheme="loop", beta="loop", boundary="edge", wireframe=False,
         control=False, frames=None, screenshot=None) -> None:
    """Open the viewer's window on the mesh; return when it is closed (as
    ``polyscope.show()``). The window's panel changes the scheme, the level,
    the shading and more (keys: docs/viewer.md).

    wireframe, control : start with the wireframe, or the control mesh, shown.
    frames : close the window by itself after this many frames (scripts,
        tests); ``screenshot`` then saves the last one as a PNG.

    Needs a display (or Xvfb) and a GPU adapter, else raises SubdivError;
    one window per process (winit cannot make a second event loop)."""
    _viewer()
    v = _checks.vertices(vertices)
    corners, starts = _checks.faces(faces)
    frames = None if frames is None else _checks.count(frames, "frames")
    shot = None if screenshot is None else str(screenshot)
    _subdiv.view_window((v, corners, starts), _names(scheme, beta, boundary), _checks.levels(levels),
                        (bool(wireframe), bool(control)), (frames, shot))
