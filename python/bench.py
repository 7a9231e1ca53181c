#!/usr/bin/env python3
"""Loop subdivision from numpy to numpy: subdiv against the Python peers
that are installed (trimesh, libigl, pymeshlab, Open3D), in one run; with
--edits, the costs of editing through subdiv.Refiner instead; with
--threads, what two threads of a ThreadPoolExecutor do against one.

    python3 python/bench.py [MESH] [--levels 3]
    python3 python/bench.py --edits [MESH] [--levels 2]
    python3 python/bench.py --threads [MESH_OR_FOLDER ...] [--levels 2]

MESH defaults to the Stanford bunny of the team's shared models, a checkout
beside the repository (not part of it). Each
tool gets the same float64 (n, 3) and int64 (m, 3) arrays and must hand back
arrays; subdiv is timed as the minimum of 5 calls after a warm-up, each peer
as the minimum of 3, the calls interleaved round by round so that a busy
machine slows every tool alike. Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import concurrent.futures
import glob
import os
import platform
import tempfile
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


def ms(fn):
    """`fn()`'s wall time in milliseconds."""
    t = time.perf_counter()
    fn()
    return (time.perf_counter() - t) * 1e3


def edits(v, f, levels, rounds=5, later=20):
    """subdiv.Refiner on (v, f) at `levels`, float64 and float32 input: its
    construction, and three edits: one vertex moved, 100 vertices moved
    (the 100 nearest one vertex, a brush), an edge's sharpness set. Each
    edit is timed first on a fresh refiner, then `later` times again on the
    same place (a drag: the minimum) and `later` times elsewhere (another
    vertex, brush or edge each time, spread over the mesh: the median),
    then undone. Minima over `rounds` rounds, which interleave the dtypes."""
    rng = np.random.default_rng(1)
    near = lambda i: np.argsort(np.linalg.norm(v - v[i], axis=1))[:100]
    spots = rng.choice(len(v), later, replace=False)
    faces = rng.choice(len(f), later + 1, replace=False)
    brushes = [near(i) for i in [0, *spots]]
    edges = [(int(f[k, 0]), int(f[k, 1])) for k in faces]
    best, spread = {}, {}

    def keep(key, t):
        best[key] = min(best.get(key, float("inf")), t)

    for _ in range(rounds):
        for dtype in (np.float64, np.float32):
            w = v.astype(dtype)
            name = np.dtype(dtype).name
            d = lambda k: np.asarray(1e-3 * (k % 7 + 1), dtype)
            edit = {
                "one vertex": lambda r, at, k: r.move([[0, *spots][at]], w[[[0, *spots][at]]] + d(k)),
                "100 vertices": lambda r, at, k: r.move(brushes[at], w[brushes[at]] + d(k)),
                "sharpness": lambda r, at, k: r.set_sharpness(*edges[at], 1.0 + k % 3),
            }
            for what, fn in edit.items():
                r = None

                def build():
                    nonlocal r
                    r = subdiv.Refiner(w, f, levels)

                keep((name, "construction"), ms(build))
                keep((name, f"{what}, first"), ms(lambda: fn(r, 0, 0)))
                for k in range(1, later + 1):
                    keep((name, f"{what}, again"), ms(lambda: fn(r, 0, k)))
                times = [ms(lambda: fn(r, at, 0)) for at in range(1, later + 1)]
                keep((name, f"{what}, elsewhere"), float(np.median(times)))
                keep((name, f"{what}, undo"), ms(r.undo))
                if what == "one vertex":
                    best[(name, "rows")] = (len(fn(r, 0, 1)), len(r.vertices))
    return best


def print_edits(path, v, f, levels, best):
    print(f"{os.path.basename(path)}: {len(v)} vertices, {len(f)} faces, Loop level {levels}; "
          f"{os.cpu_count()} CPUs, Python {platform.python_version()}, numpy {np.__version__}, "
          f"load average {os.getloadavg()[0]:.1f}\n")
    print("| subdiv.Refiner | float64 (ms) | float32 (ms) |")
    print("|---|---|---|")
    rows = ["construction"] + [f"{e}, {k}" for e in ("one vertex", "100 vertices", "sharpness")
                               for k in ("first", "again", "elsewhere", "undo")]
    for what in rows:
        print(f"| {what} | {best[('float64', what)]:.2f} | {best[('float32', what)]:.2f} |")
    n, total = best[("float64", "rows")]
    print(f"\na one-vertex move re-evaluates {n} of the {total} refined rows (the rows it returns).")


def model_files(args):
    """The mesh files named, those of the folders named (default: the
    repository's models/ and the shared models), USD and Bezier patches aside."""
    args = args or [os.path.join(HERE, "..", "models"), os.path.dirname(DEFAULT)]
    out = []
    for a in args:
        found = sorted(glob.glob(os.path.join(a, "*"))) if os.path.isdir(a) else [a]
        out += [p for p in found if p.endswith((".obj", ".ct", ".ply", ".off", ".stl"))]
    return out


def thread_tasks(paths, levels, out_dir):
    """name -> the tasks (callables) of one workload over the models, each
    call on one thread of its own (``threads=1``) but "threads=None" (the
    shared pool, as a caller who leaves it out)."""
    meshes = []
    for p in paths:
        try:
            m = subdiv.load(p)
            meshes.append((p, m.vertices, m.faces))
        except subdiv.SubdivError:
            pass
    rng = np.random.default_rng(3)
    fine = [subdiv.subdivide(v, f, 1) for _, v, f in meshes]
    points = [(rng.integers(0, len(f), 20_000), rng.uniform(0, 0.5, (20_000, 2))) for _, _, f in meshes]
    refiners = [subdiv.Refiner(v, f, levels, threads=1) for _, v, f in meshes]
    brushes = [rng.choice(len(v), min(100, len(v)), replace=False) for _, v, _ in meshes]

    def pipeline(p, k):
        m = subdiv.load(p, threads=1)
        v2, f2 = subdiv.subdivide(m.vertices, m.faces, levels, threads=1)
        subdiv.save(os.path.join(out_dir, f"{k}.ply"), v2, f2, threads=1)

    def edits(r, v, ids):
        for k in range(20):
            r.move(ids, v[ids] + 1e-3 * (k + 1))

    return {
        f"subdivide, level {levels}": [lambda v=v, f=f: subdiv.subdivide(v, f, levels, threads=1)
                                       for _, v, f in meshes],
        f"subdivide, level {levels}, threads=None": [lambda v=v, f=f: subdiv.subdivide(v, f, levels)
                                                     for _, v, f in meshes],
        "limit (of level 1)": [lambda v=v, f=f: subdiv.limit(v, f, threads=1) for v, f in fine],
        "evaluate, 20,000 points": [lambda v=v, f=f, q=q: subdiv.evaluate(v, f, *q, threads=1)
                                    for (_, v, f), q in zip(meshes, points)],
        f"load + subdivide level {levels} + save (.ply)": [lambda p=p, k=k: pipeline(p, k)
                                                           for k, (p, _, _) in enumerate(meshes)],
        f"Refiner level {levels}: 20 moves of 100 vertices": [
            lambda r=r, v=v, ids=ids: edits(r, v, ids) for r, (_, v, _), ids in zip(refiners, meshes, brushes)],
    }, sum(len(f) for _, _, f in meshes)


def threads(paths, levels, rounds=5, repeat=3):
    """Every workload run by a ThreadPoolExecutor of 1 and of 2 threads,
    the pools and rounds interleaved; the minimum wall time of each."""
    with tempfile.TemporaryDirectory() as out_dir:
        tasks, faces = thread_tasks(paths, levels, out_dir)
        pools = {w: concurrent.futures.ThreadPoolExecutor(max_workers=w) for w in (1, 2)}
        best = {}
        for name, work in tasks.items():
            work = work * repeat
            for task in work[: len(work) // repeat]:
                task()  # warm-up: pages, caches, files
            for _ in range(rounds):
                for w, pool in pools.items():
                    t = time.perf_counter()
                    list(pool.map(lambda task: task(), work))
                    best[(name, w)] = min(best.get((name, w), float("inf")), time.perf_counter() - t)
        for pool in pools.values():
            pool.shutdown()
    print(f"{len(paths)} models ({faces} faces, each workload {repeat} times over), level {levels}; "
          f"{os.cpu_count()} CPUs, Python {platform.python_version()}, numpy {np.__version__}, "
          f"load average {os.getloadavg()[0]:.1f}; minima of {rounds} interleaved rounds\n")
    print("| ThreadPoolExecutor | 1 thread (s) | 2 threads (s) | speed-up |")
    print("|---|---|---|---|")
    for name in tasks:
        one, two = best[(name, 1)], best[(name, 2)]
        print(f"| {name} | {one:.3f} | {two:.3f} | {one / two:.2f}x |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh", nargs="*", help=f"default: {DEFAULT} (with --threads: models/ and its folder)")
    ap.add_argument("--levels", type=int, default=None, help="default: 3, with --edits and --threads 2")
    ap.add_argument("--edits", action="store_true", help="time subdiv.Refiner's edits instead")
    ap.add_argument("--threads", action="store_true", help="1 against 2 threads of a ThreadPoolExecutor")
    a = ap.parse_args()
    if a.threads:
        threads(model_files(a.mesh), 2 if a.levels is None else a.levels)
        return
    if len(a.mesh) > 1:
        ap.error("one mesh at a time, but with --threads")
    a.mesh = a.mesh[0] if a.mesh else DEFAULT
    m = subdiv.load(a.mesh)
    v, f = np.ascontiguousarray(m.vertices), np.ascontiguousarray(m.faces)
    if a.edits:
        levels = 2 if a.levels is None else a.levels
        print_edits(a.mesh, v, f, levels, edits(v, f, levels))
        return
    a.levels = 3 if a.levels is None else a.levels
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
