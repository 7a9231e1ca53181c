"""Turning what the caller passed into the C-contiguous float64 and int64
arrays the native module takes, refusing wrong shapes and dtypes (TypeError,
ValueError) and refused values (SubdivError) before anything large is made.
The native module checks every value again."""

from __future__ import annotations

import numbers
import operator

import numpy as np

from ._subdiv import MAX_THREADS, SubdivError

_I64_MAX = np.iinfo(np.int64).max
_U32_MAX = 2**32 - 1


def native(a, dtype=None) -> np.ndarray:
    """`a` as the native module reads it: C-contiguous and aligned, of
    `dtype` (a copy where it was not; an unpickled or ``frombuffer`` array
    may be unaligned)."""
    return np.require(a, dtype=dtype, requirements=("C", "A"))


def vertices(v) -> np.ndarray:
    """`v` as a C-contiguous float64 array of shape (n, 3)."""
    try:
        a = np.asarray(v)
    except (ValueError, TypeError) as e:
        raise ValueError(f"vertices must be an array of shape (n, 3): {e}") from None
    if a.dtype.kind not in "fiu":
        raise TypeError(f"vertices must be real numbers, got dtype {a.dtype}")
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"vertices must have shape (n, 3), got shape {a.shape}")
    return native(a, np.float64)


def is_float32(v) -> bool:
    """Whether `v` holds float32 (computed and returned in float32; every
    other dtype is computed in float64)."""
    return getattr(v, "dtype", None) == np.float32


def _int_array(a: np.ndarray, what: str) -> np.ndarray:
    """An integer array as int64, refusing floats (never truncated) and
    unsigned values past int64."""
    if a.dtype.kind not in "iu":
        raise TypeError(f"{what} must be integers, got dtype {a.dtype} (float indices are refused, not truncated)")
    if a.dtype.kind == "u" and a.size and int(a.max()) > _I64_MAX:
        raise SubdivError(f"{what}: vertex index {int(a.max())} is out of range")
    return native(a, np.int64)


def _polygon(p, f: int) -> np.ndarray:
    """Face `f` of a list of polygons as int64."""
    try:
        a = np.asarray(p)
    except (ValueError, TypeError) as e:
        raise ValueError(f"face {f} is not a list of vertex indices: {e}") from None
    if a.dtype == object:
        try:
            a = np.asarray(p, dtype=np.int64)
        except OverflowError:
            raise SubdivError(f"face {f} uses a vertex index out of range") from None
        except (ValueError, TypeError) as e:
            raise TypeError(f"face {f} must hold integers: {e}") from None
    if a.ndim != 1:
        raise ValueError(f"face {f} must be a flat list of vertex indices, got shape {a.shape}")
    return _int_array(a, f"face {f}")


def faces(f) -> tuple[np.ndarray, np.ndarray]:
    """`f` ((m, k) integers, or a list of polygons) as flat int64 corners
    and face offsets (m + 1)."""
    a = None
    try:
        a = np.asarray(f)
    except OverflowError:
        raise SubdivError("faces use a vertex index out of range") from None
    except (ValueError, TypeError):
        a = None  # ragged: a list of polygons
    if a is not None and a.dtype != object:
        if a.ndim != 2 or (a.shape[0] and a.shape[1] < 3):
            raise ValueError(f"faces must have shape (m, k), k >= 3, or be a list of polygons, got shape {a.shape}")
        c = _int_array(a, "faces")
        m, k = a.shape
        return c.reshape(-1), np.arange(0, m * k + 1, max(k, 1), dtype=np.int64)[: m + 1]
    if isinstance(f, (str, bytes)) or not hasattr(f, "__iter__"):
        raise TypeError(f"faces must be an integer array or a list of polygons, got {type(f).__name__}")
    polys = [_polygon(p, i) for i, p in enumerate(f)]
    sizes = np.array([len(p) for p in polys], dtype=np.int64)
    starts = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    corners = np.concatenate(polys).astype(np.int64) if polys else np.zeros(0, np.int64)
    return native(corners, np.int64), starts


def creases(c) -> tuple[np.ndarray, np.ndarray]:
    """`None` or `(edges (k, 2) int, sharpness (k,) float)` as flat int64
    edges and float64 sharpness."""
    if c is None:
        return np.zeros(0, np.int64), np.zeros(0, np.float64)
    try:
        edges, sharp = c
    except (TypeError, ValueError):
        raise TypeError("creases must be None or a pair (edges (k, 2) int, sharpness (k,) float)") from None
    e = np.asarray(edges)
    if e.size == 0:
        e = e.astype(np.int64).reshape(0, 2)
    e = _int_array(e, "crease edges")
    if e.ndim != 2 or e.shape[1] != 2:
        raise ValueError(f"crease edges must have shape (k, 2), got shape {e.shape}")
    s = np.asarray(sharp)
    if s.dtype.kind not in "fiu":
        raise TypeError(f"crease sharpness must be real numbers, got dtype {s.dtype}")
    s = native(s, np.float64).reshape(-1) if s.ndim <= 1 else None
    if s is None or len(s) != len(e):
        raise ValueError(f"crease sharpness must have shape ({len(e)},), one per edge")
    return e.reshape(-1), s


def tags(c, holes=None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`creases` of `c`, and `holes` (None or face ids) as flat int64."""
    if holes is None:
        h = np.zeros(0, np.int64)
    else:
        h = np.asarray(holes)
        if h.size == 0:
            h = h.astype(np.int64)
        if h.ndim > 1:
            raise ValueError(f"holes must be a list of face ids, got shape {h.shape}")
        h = _int_array(h.reshape(-1), "holes")
    return creases(c) + (h,)


def levels(n) -> int:
    """A level count: an integer from 0 (refused values: SubdivError)."""
    if isinstance(n, bool) or not isinstance(n, (numbers.Integral, np.integer)):
        raise TypeError(f"levels must be an integer, got {type(n).__name__}")
    n = operator.index(n)
    if n < 0:
        raise SubdivError(f"levels must be 0 or more, got {n}")
    if n > _U32_MAX:
        raise SubdivError(f"levels={n}: the refined mesh would not fit in memory (each level has 4 times the faces)")
    return n


def threads(t) -> int | None:
    """`None` (the shared pool) or a thread count from 1 to MAX_THREADS."""
    if t is None:
        return None
    if isinstance(t, bool) or not isinstance(t, (numbers.Integral, np.integer)):
        raise TypeError(f"threads must be None or an integer, got {type(t).__name__}")
    t = operator.index(t)
    if not 1 <= t <= MAX_THREADS:
        raise SubdivError(f"threads must be between 1 and {MAX_THREADS}, got {t}")
    return t


def name(value, what: str) -> str:
    """A scheme, option or shading name (the library checks which)."""
    if not isinstance(value, str):
        raise TypeError(f"{what} must be a string, got {type(value).__name__}")
    return value


def count(n, what: str) -> int:
    """A non-negative integer count."""
    if isinstance(n, bool) or not isinstance(n, (numbers.Integral, np.integer)):
        raise TypeError(f"{what} must be an integer, got {type(n).__name__}")
    n = operator.index(n)
    if n < 0:
        raise SubdivError(f"{what} must be 0 or more, got {n}")
    if n >= _U32_MAX:
        raise SubdivError(f"{what}={n}: more than the library's 32-bit vertex ids allow")
    return n


def size(s) -> tuple[int, int]:
    """An image size (width, height) of positive integers."""
    try:
        w, h = s
    except (TypeError, ValueError):
        raise TypeError("size must be a pair (width, height)") from None
    return count(w, "width"), count(h, "height")
