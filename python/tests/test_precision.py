"""Precision is the caller's: float64 in is computed and returned in float64,
float32 in in float32; the subdivision matrix's weights are float64."""

import numpy as np
import subdiv


def bipyramid(c):
    """A closed bipyramid over a pentagon, centred a distance c out."""
    a = 2 * np.pi * np.arange(5) / 5
    ring = np.stack([0.7 * np.cos(a) + 0.01 * np.arange(5), 0.7 * np.sin(a), 0.0123456789 * np.arange(5)], axis=1)
    v = np.vstack([ring, [[0.01, -0.02, 1.1], [0.0, 0.03, -0.9]]]) + c
    f = [[k, (k + 1) % 5, 5] for k in range(5)] + [[(k + 1) % 5, k, 6] for k in range(5)]
    return v, np.array(f)


def test_float64_is_kept_and_interpolating_schemes_keep_the_input_bit_for_bit():
    v, f = bipyramid(1e6)
    for scheme in ("midpoint", "butterfly", "modified-butterfly"):
        v2, _ = subdiv.subdivide(v, f, 2, scheme)
        assert v2.dtype == np.float64
        assert np.array_equal(v2[: len(v)], v), scheme
    # an edge point of midpoint is the float64 average of its ends
    v1, _ = subdiv.subdivide(v, f, 1, "midpoint")
    mids = {tuple(x) for x in v1[len(v):]}
    assert tuple((v[0] + v[1]) / 2) in mids


def test_far_from_the_origin_float64_equals_the_float64_matrix():
    v, f = bipyramid(1e6)
    s = subdiv.matrix(f, 2, "loop")
    assert s.dtype == np.float64
    assert np.abs(np.asarray(s.sum(axis=1)).ravel() - 1).max() < 1e-15
    v2, _ = subdiv.subdivide(v, f, 2, "loop")
    # the same weights applied two ways in float64: rounding apart only
    assert np.abs(v2 - s @ v).max() < 1e-9
    # float32 cannot: its spacing out here is 0.06
    v32, _ = subdiv.subdivide(v.astype(np.float32), f, 2, "loop")
    assert v32.dtype == np.float32
    assert np.abs(v32.astype(np.float64) - s @ v).max() > 1e-3


def test_float32_is_computed_and_returned_in_float32():
    v, f = bipyramid(0.0)
    v32, f32 = subdiv.subdivide(v.astype(np.float32), f, 2, "catmull-clark")
    v64, f64 = subdiv.subdivide(v, f, 2, "catmull-clark")
    assert v32.dtype == np.float32 and v64.dtype == np.float64
    assert np.array_equal(f32, f64)
    assert np.abs(v32 - v64).max() < 1e-5


def test_evaluate_takes_float64_control_points_as_given():
    # an affine net's Loop limit on a regular patch is the same affine map,
    # so the exact value is known; a million units out float32 misses it
    n = 9
    a, b = np.array([0.7, -0.2, 0.13]), np.array([0.31, 0.9, 0.05])
    c = np.array([1e6 + 0.123456789, 1e6 - 0.987654321, 1e6 + 0.5])
    v = np.array([c + a * (k % n) + b * (k // n) for k in range(n * n)])
    f = []
    for j in range(n - 1):
        for i in range(n - 1):
            p, q, r, s = j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i
            f += [[p, q, r], [p, r, s]]
    f = np.array(f)
    t = [k for k in range(len(f)) if all(2 <= x % n < 7 and 2 <= x // n < 7 for x in f[k])]
    uv = np.tile([[0.2, 0.3]], (len(t), 1))
    exact = v[f[t, 0]] * 0.5 + v[f[t, 1]] * 0.2 + v[f[t, 2]] * 0.3
    p64, _ = subdiv.evaluate(v, f, t, uv)
    p32, _ = subdiv.evaluate(v.astype(np.float32), f, t, uv)
    assert p64.dtype == np.float64 and p32.dtype == np.float32
    assert np.abs(p64 - exact).max() / 1.7e6 < 1e-12
    assert np.abs(p32.astype(np.float64) - exact).max() / 1.7e6 > 1e-9


def test_limit_keeps_the_dtype_and_float64_is_exact_far_out():
    v, f = bipyramid(1e6)
    p64, n64 = subdiv.limit(v, f)
    p32, _ = subdiv.limit(v.astype(np.float32), f)
    assert p64.dtype == np.float64 and n64.dtype == np.float64 and p32.dtype == np.float32
    # the limit is the limit of the levels: S^k applied, nearing it (Loop level 6 from matrix)
    s = subdiv.matrix(f, 6, "loop")
    near = (s @ v)[: len(v)]
    assert np.abs(p64 - near).max() < 1e-3
    assert np.abs(p64 - near).max() < np.abs(p32.astype(np.float64) - near).max()
