"""Meshes and helpers shared by the tests (every mesh is made here, no file
outside the repository is read)."""

import os
import subprocess
import sys

import numpy as np
import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MODELS = os.path.join(REPO, "models")

TETRA_V = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
TETRA_F = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])


def bipyramid(k, height=1.0, jitter=0.0, seed=0):
    """A closed bipyramid over a k-gon: apexes 0 (top, valence k) and 1
    (bottom), ring vertices 2..k+1 counter-clockwise seen from the top."""
    rng = np.random.default_rng(seed)
    a = 2 * np.pi * np.arange(k) / k
    ring = np.stack([np.cos(a), np.sin(a), np.zeros(k)], axis=1)
    v = np.vstack([[0, 0, height], [0, 0, -height], ring])
    v = v + jitter * rng.standard_normal(v.shape)
    f = []
    for i in range(k):
        a_, b_ = 2 + i, 2 + (i + 1) % k
        f.append([0, a_, b_])
        f.append([1, b_, a_])
    return v, np.array(f)


def icosahedron():
    t = (1 + 5**0.5) / 2
    v = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
                  [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], float)
    f = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
                  [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5],
                  [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]])
    return v, f


def cube_quads():
    v = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    f = np.array([[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]])
    return v, f


def cube_triangles():
    v, q = cube_quads()
    f = np.vstack([q[:, [0, 1, 2]], q[:, [0, 2, 3]]])
    return v, f


def open_grid(n=4, seed=1):
    """An open height field of (n+1)^2 vertices, two triangles per cell."""
    rng = np.random.default_rng(seed)
    xs, ys = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    v = np.stack([xs.ravel(), ys.ravel(), 0.2 * rng.standard_normal(xs.size)], axis=1).astype(float)
    f = []
    for i in range(n):
        for j in range(n):
            a, b, c, d = i * (n + 1) + j, (i + 1) * (n + 1) + j, (i + 1) * (n + 1) + j + 1, i * (n + 1) + j + 1
            f += [[a, b, c], [a, c, d]]
    return v, np.array(f)


def sphere(levels=3):
    """An icosphere made by midpoint subdivision and projection (our own
    midpoint scheme only makes the topology; the test data is the sphere)."""
    import subdiv

    v, f = icosahedron()
    v2, f2 = subdiv.subdivide(v, f, levels, "midpoint")
    return v2 / np.linalg.norm(v2, axis=1, keepdims=True), f2


def num_edges(f):
    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    return len(np.unique(e, axis=0))


def run_python(code, timeout=120):
    """Runs `code` in a fresh interpreter: an abort or a segfault is a
    non-zero return code there, never a crash of the test run."""
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout)


@pytest.fixture
def tetra():
    return TETRA_V.copy(), TETRA_F.copy()
