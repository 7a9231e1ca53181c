#!/usr/bin/env python3
"""Loop subdivision from numpy to numpy: subdiv against the Python peers
that are installed (trimesh, libigl, pymeshlab, Open3D), in one run.

    python3 python/bench.py [MESH] [--levels 3]

MESH defaults to the Stanford bunny of the team's shared models, a checkout
beside the repository (not part of it). Each
tool gets the same float64 (n, 3) and int64 (m, 3) arrays and must hand back
arrays; subdiv is timed as the minimum of 5 calls after a warm-up, each peer
as the minimum of 3, the calls interleaved round by round so that a busy
machine slows every tool alike. Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

import subdiv

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT = os.path.join(HERE, "..", "..", "shared", "models", "stanford-bunny-compact.obj")


def ours(v, f, levels):
    return subdiv.subdivide(v, f, levels)


def peers():
    """The installed peers: (name, version, function)."""
    out = []
    try:
        import trimesh

        out.append(("trimesh subdivide_loop", trimesh.__version__,
                    lambda v, f, n: trimesh.remesh.subdivide_loop(v, f, iterations=n)))
    except ImportError:
        pass
    try:
        import igl

        def igl_loop(v, f, n):
            return igl.loop(v, f, n)

        out.append(("libigl igl.loop", _version("libigl"), igl_loop))
    except ImportError:
        pass
    try:
        import pymeshlab

        def meshlab(v, f, n):
            ms = pymeshlab.MeshSet()
            ms.add_mesh(pymeshlab.Mesh(v, f))
            ms.meshing_surface_subdivision_loop(iterations=n, threshold=pymeshlab.PercentageValue(0))
            m = ms.current_mesh()
            return m.vertex_matrix(), m.face_matrix()

        out.append(("pymeshlab loop", _version("pymeshlab"), meshlab))
    except ImportError:
        pass
    try:
        import open3d as o3d

        def open3d(v, f, n):
            m = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(v), o3d.utility.Vector3iVector(f))
            m = m.subdivide_loop(number_of_iterations=n)
            return np.asarray(m.vertices), np.asarray(m.triangles)

        out.append(("Open3D subdivide_loop", o3d.__version__, open3d))
    except ImportError:
        pass
    return out


def _version(dist):
    try:
        from importlib.metadata import version

        return version(dist)
    except Exception:
        return "?"


def timed(fn, v, f, levels):
    t = time.perf_counter()
    out = fn(v, f, levels)
    return time.perf_counter() - t, out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh", nargs="?", default=DEFAULT)
    ap.add_argument("--levels", type=int, default=3)
    a = ap.parse_args()
    m = subdiv.load(a.mesh)
    v, f = np.ascontiguousarray(m.vertices), np.ascontiguousarray(m.faces)
    tools = peers()
    timed(ours, v, f, a.levels)  # warm-up: page faults, thread pool
    load_before = os.getloadavg()[0]
    best = {"subdiv": float("inf")}
    ours_all = []
    faces = {}
    for name, _, _ in tools:
        best[name] = float("inf")
    for rnd in range(5):
        dt, (v2, f2) = timed(ours, v, f, a.levels)
        best["subdiv"], faces["subdiv"] = min(best["subdiv"], dt), len(f2)
        ours_all.append(dt)
        if rnd < 3:
            for name, _, fn in tools:
                dt, (v2, f2) = timed(fn, v, f, a.levels)
                best[name], faces[name] = min(best[name], dt), len(f2)
    print(f"{os.path.basename(a.mesh)}: {len(v)} vertices, {len(f)} faces, Loop level {a.levels}; "
          f"{os.cpu_count()} CPUs, Python {platform.python_version()}, numpy {np.__version__}, "
          f"load average {load_before:.1f} before, {os.getloadavg()[0]:.1f} after\n")
    print("| tool | version | faces out | time (ms) | ours faster by |")
    print("|---|---|---|---|---|")
    versions = {name: ver for name, ver, _ in tools}
    versions["subdiv"] = subdiv.__version__
    for name in sorted(best, key=best.get):
        ratio = best[name] / best["subdiv"]
        print(f"| {name} | {versions[name]} | {faces[name]} | {best[name] * 1e3:.0f} | {ratio:.1f}x |")
    if tools:
        fastest = min(best[n] for n, _, _ in tools)
        print(f"\nsubdiv is {fastest / best['subdiv']:.1f} times faster than the fastest peer "
              f"(its 5 calls: {', '.join(f'{t * 1e3:.0f}' for t in ours_all)} ms).")


if __name__ == "__main__":
    main()
