#!/usr/bin/env python3
"""The table of docs/tessellation.md: `subdiv tessellate` beside uniform levels.

    python3 scripts/tess-vs-uniform.py SUBDIV MODEL TOL [subdiv options...]

For the tolerance TOL (absolute, or `1e-4x` of the bounding box's diagonal)
prints the adaptive tessellation's triangles, the distance it measured and
its time, then for each uniform level L = 1, 2, ... (`subdiv subdivide -n L`)
its triangles and its vertices' largest distance from their own limit points
(`subdiv limit` of the level: the exact limit at each vertex's parameter)
and its edges' midpoints' distance from the exact limit at their parameter
(the limit of the vertex the next level makes on the edge), until both are
below TOL: the first uniform level within TOL, measured as the adaptive one
is (its vertices and edges' midpoints; the adaptive also at triangle centres).
Needs numpy and the subdiv Python package (for reading the meshes).
"""
import os
import re
import subprocess
import sys
import tempfile
import time

import numpy as np

import subdiv


def run(cmd):
    t = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, check=True)
    return p.stdout + p.stderr, time.time() - t


def main():
    exe, model, tol, extra = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    tmp = tempfile.mkdtemp()
    out, _ = run([exe, "tessellate", model, os.path.join(tmp, "t.ply"), "-t", tol, "--stats", *extra])
    stats = dict(re.findall(r"(\w+)=(\S+)", out))
    t_abs = float(stats["tolerance"])
    print(f"{model} tolerance {t_abs:.3e}: adaptive {stats['triangles']} triangles, measured {float(stats['measured']):.3e}, "
          f"met {stats['met']}, {float(stats['tessellate_ms']):.0f} ms")
    level_files = {}

    def level(n):
        """Level n and its limit: written once, read as Mesh objects."""
        if n not in level_files:
            # PLY is smaller and faster; OBJ keeps the crease tags `limit` needs
            ext = "obj" if "--crease-angle" in extra else "ply"
            a, b = os.path.join(tmp, f"l{n}.{ext}"), os.path.join(tmp, f"l{n}lim.{ext}")
            out, _ = run([exe, "--threads", "1", "subdivide", model, a, "-n", str(n), "--stats", *extra])
            ms = float(re.search(r"subdivide_ms=(\S+)", out).group(1))
            run([exe, "limit", a, b, *limit_flags])
            level_files[n] = (subdiv.load(a), subdiv.load(b), ms)
            os.remove(a)
            os.remove(b)
        return level_files[n]

    # the crease tags ride in the levels' OBJ files: limit reads them there
    limit_flags = [x for i, x in enumerate(extra) if x != "--crease-angle" and (i == 0 or extra[i - 1] != "--crease-angle")]
    first = {}
    for n in range(1, 7):
        m, lim, ms = level(n)
        tris = len(m.faces)
        if tris * 4 > 30_000_000:
            print(f"  uniform level {n + 1} would be past 30 M triangles: stopped")
            break
        err_v = float(np.max(np.linalg.norm(m.vertices - lim.vertices, axis=1)))
        err_e = edge_error(m, level(n + 1)[1])
        level_files.pop(n - 1, None)
        print(f"  uniform level {n}: {tris} triangles, distance at vertices {err_v:.3e}, at edge midpoints {err_e:.3e}, "
              f"subdivide {ms:.0f} ms (1 thread)")
        for key, err in (("vertices", err_v), ("vertices and edge midpoints", max(err_v, err_e))):
            if err <= t_abs and key not in first:
                first[key] = (n, tris)
        if len(first) == 2:
            break
    for key, (n, tris) in first.items():
        print(f"  first uniform level within the tolerance at its {key}: {n}; adaptive/uniform = "
              f"{int(stats['triangles']) / tris:.3f}")

def edges_of(m):
    """The undirected edges of a level's faces (its polygons where it has them: a
    quad's diagonals are not edges)."""
    faces = m.polygons if m.polygons is not None and not isinstance(m.polygons, list) else m.faces
    k = faces.shape[1]
    e = np.concatenate([np.stack([faces[:, i], faces[:, (i + 1) % k]], axis=1) for i in range(k)])
    return np.unique(np.sort(e, axis=1), axis=0)


def edge_error(m, finer_limit):
    """The largest distance between the midpoint of an edge of level m and the
    exact limit at its parameter: the limit of the next level's vertex made on
    that edge (the one new vertex whose only old neighbours are the edge's ends)."""
    old = len(m.vertices)
    e = edges_of(finer_limit)
    e = e[(e[:, 0] < old) & (e[:, 1] >= old)]  # old -> new
    new, first = np.unique(e[:, 1], return_index=True)
    counts = np.bincount(e[:, 1] - old, minlength=len(finer_limit.vertices) - old)
    order = np.argsort(e[:, 1], kind="stable")
    ends = e[order]
    # the new vertices with two old neighbours are the edge points
    two = np.flatnonzero(counts == 2) + old
    start = np.searchsorted(ends[:, 1], two)
    a, b = ends[start, 0], ends[start + 1, 0]
    mid = 0.5 * (m.vertices[a] + m.vertices[b])
    return float(np.max(np.linalg.norm(mid - finer_limit.vertices[two], axis=1)))

if __name__ == "__main__":
    main()
