#!/usr/bin/env python3
"""The table of docs/tessellation.md: `subdiv tessellate` beside uniform levels.

    python3 scripts/tess-vs-uniform.py SUBDIV MODEL TOL [subdiv options...]

For the tolerance TOL (absolute, or `1e-4x` of the bounding box's diagonal)
prints the adaptive tessellation's triangles, the distance it measured and
its time, then for each uniform level L = 1, 2, ... (`subdiv subdivide -n L`)
its triangles and its vertices' largest distance from their own limit points
(`subdiv limit` of the level: the exact limit at each vertex's parameter),
until that distance is below TOL: the first uniform level within TOL. The
vertices' distance is a lower bound of a uniform level's error (its
triangles' insides are farther still), so the ratio is in uniform's favour.
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
    for level in range(1, 7):
        a, b = os.path.join(tmp, f"l{level}.obj"), os.path.join(tmp, f"l{level}lim.obj")
        out, secs = run([exe, "--threads", "1", "subdivide", model, a, "-n", str(level), "--stats", *extra])
        ms = float(re.search(r"subdivide_ms=(\S+)", out).group(1))
        run([exe, "limit", a, b, *[x for x in extra if x != "--crease-angle" and not x.replace('.', '').isdigit()]])
        m, lim = subdiv.load(a), subdiv.load(b)
        err = float(np.max(np.linalg.norm(np.asarray(m.vertices) - np.asarray(lim.vertices), axis=1)))
        tris = len(m.faces)
        print(f"  uniform level {level}: {tris} triangles, vertices' distance {err:.3e}, subdivide {ms:.0f} ms (1 thread)")
        if err <= t_abs:
            print(f"  first uniform level within the tolerance: {level}; adaptive/uniform = {int(stats['triangles']) / tris:.3f}")
            break
        os.remove(a)
        os.remove(b)


if __name__ == "__main__":
    main()
