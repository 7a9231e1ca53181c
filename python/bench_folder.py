#!/usr/bin/env python3
"""A folder of models refined to level 2 and written, ten ways: a serial
Python loop of load, subdivide and save, the same in a ThreadPoolExecutor of
2 threads, a serial loop and a ThreadPoolExecutor(2) of the one native call
`subdivide_file`, Dask's LocalCluster of 2 worker processes a task per file
(load, subdivide and save; subdivide_file) and by docs/dask.md's recipe
(subdivide_file, tasks of several files), a loop of `subdiv subdivide` processes, and `subdiv batch`
on 1 thread and on all cores where the binary has it.

    python3 python/bench_folder.py make DIR [--count 300]
    python3 python/bench_folder.py run DIR [--levels 2] [--rounds 3] [--cli PATH]

`make` fills DIR with the repository's bundled meshes, the team's shared
models beside the repository (when there) and generated ones (noisy
icospheres, bipyramids, open grids of several sizes, as OBJ, PLY and OFF).
`run` times each way in a process of its own, the ways interleaved round by
round, every output written as binary PLY into a fresh folder; each figure is
the minimum over the rounds (the wall time from the first file read to the
last written, the cluster's start counted apart), with the peak resident
memory of the largest process. Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import glob
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

import subdiv

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.join(HERE, "..", "..", "shared", "models")
KINDS = (".obj", ".ct", ".ply", ".off", ".stl")


def icosphere(levels, rng, noise):
    t = (1 + 5**0.5) / 2
    v = np.array([[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
                  [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]], float)
    f = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
                  [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5],
                  [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]])
    v, f = subdiv.subdivide(v, f, levels, "midpoint")
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    return v * (1 + noise * rng.standard_normal((len(v), 1))), f


def bipyramid(k, rng):
    a = 2 * np.pi * np.arange(k) / k
    v = np.vstack([[0, 0, 1], [0, 0, -1], np.stack([np.cos(a), np.sin(a), np.zeros(k)], axis=1)])
    f = [[0, 2 + i, 2 + (i + 1) % k] for i in range(k)] + [[1, 2 + (i + 1) % k, 2 + i] for i in range(k)]
    return v + 0.05 * rng.standard_normal(v.shape), np.array(f)


def grid(n, rng):
    xs, ys = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    v = np.stack([xs.ravel(), ys.ravel(), 0.3 * rng.standard_normal(xs.size)], axis=1).astype(float)
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    a = (i * (n + 1) + j).ravel()
    b, c, d = a + n + 1, a + n + 2, a + 1
    return v, np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])


def make(folder, count):
    os.makedirs(folder, exist_ok=True)
    copied = sorted(glob.glob(os.path.join(HERE, "..", "models", "*")))
    copied += sorted(glob.glob(os.path.join(SHARED, "*.obj"))) + sorted(glob.glob(os.path.join(SHARED, "*", "*.obj")))
    n = 0
    for p in copied:
        if p.endswith(KINDS) and "nonmanifold" not in p:
            shutil.copy(p, os.path.join(folder, f"{n:04d}-{os.path.basename(p)}"))
            n += 1
    rng = np.random.default_rng(7)
    k = 0
    while n < count:
        kind = k % 3
        if kind == 0:
            v, f = icosphere(1 + k % 5, rng, 0.05)
        elif kind == 1:
            v, f = bipyramid(3 + k % 40, rng)
        else:
            v, f = grid(4 + 6 * (k % 12), rng)
        subdiv.save(os.path.join(folder, f"{n:04d}-gen{k}{('.obj', '.ply', '.off')[k % 3]}"), v, f)
        n, k = n + 1, k + 1
    print(f"{n} models in {folder}")


def refine_to(path, out_dir, levels=2, threads=1):
    """One file refined by the options it states and written as PLY: its
    output faces, or its error (docs/dask.md's function, writing on the worker)."""
    try:
        m = subdiv.load(path, threads=threads)
        polygonal = m.options.get("scheme") in subdiv.POLYGON_SCHEMES and m.polygons is not None
        v2, f2 = subdiv.subdivide(m.vertices, m.polygons if polygonal else m.faces, levels, threads=threads,
                                  **m.options)
        subdiv.save(os.path.join(out_dir, os.path.basename(path) + ".ply"), v2, f2, threads=threads)
        return len(f2), None
    except subdiv.SubdivError as e:
        return 0, str(e)


def refine_files(paths, out_dir, levels=2):
    """docs/dask.md's function: each file of `paths` refined by the options
    it states and written into `out_dir` as PLY, one native call each: its
    line, or its error."""
    lines = []
    for path in paths:
        out = os.path.join(out_dir, os.path.basename(path) + ".ply")
        try:
            lines.append(subdiv.subdivide_file(path, out, levels, threads=1))
        except subdiv.SubdivError as e:
            lines.append({"input": path, "output": out, "status": "failed", "error": str(e)})
    return lines


def tasks(paths, task_bytes=2 << 20):
    """docs/dask.md's chunks: consecutive files of about `task_bytes` bytes
    together (a larger file alone), so that each task runs long against
    Dask's own work per task."""
    out, size = [], task_bytes
    for p in paths:
        n = os.path.getsize(p)
        if size + n > task_bytes:
            out.append([])
            size = 0
        out[-1].append(p)
        size += n
    return out


def native_one(path, out_dir, levels):
    """One file by the native call: (faces, error)."""
    line = refine_files([path], out_dir, levels)[0]
    return line.get("faces", 0), line.get("error")


def dask_way(name, paths, out_dir, levels):
    """A Dask way: its seconds, the cluster's start and (faces, error) per file."""
    import logging

    from dask.distributed import Client, LocalCluster

    t0 = time.perf_counter()
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                      silence_logs=logging.ERROR) as cluster, Client(cluster) as client:
        client.wait_for_workers(2)
        start = time.perf_counter() - t0
        t = time.perf_counter()
        if name == "Dask, a task per file (arrays)":
            done = client.gather(client.map(refine_to, paths, out_dir=out_dir, levels=levels))
        elif name == "Dask, a task per file (subdivide_file)":
            done = client.gather(client.map(native_one, paths, out_dir=out_dir, levels=levels))
        else:
            chunks = client.gather(client.map(refine_files, tasks(paths), out_dir=out_dir, levels=levels))
            done = [(line.get("faces", 0), line.get("error")) for chunk in chunks for line in chunk]
        seconds = time.perf_counter() - t
    return seconds, start, done


def models(folder):
    return sorted(p for p in glob.glob(os.path.join(folder, "*")) if p.endswith(KINDS))


def way(name, folder, out_dir, levels, cli):
    """One way run in this process: {"seconds", "start", "faces", "failed"}."""
    paths = models(folder)
    start = 0.0
    if name == "serial loop":
        t = time.perf_counter()
        done = [refine_to(p, out_dir, levels, threads=None) for p in paths]
    elif name == "ThreadPoolExecutor(2)":
        import concurrent.futures

        with concurrent.futures.ThreadPoolExecutor(2) as pool:
            t = time.perf_counter()
            done = list(pool.map(lambda p: refine_to(p, out_dir, levels), paths))
    elif name == "serial subdivide_file":
        t = time.perf_counter()
        done = [native_one(p, out_dir, levels) for p in paths]
    elif name == "ThreadPoolExecutor(2) subdivide_file":
        import concurrent.futures

        with concurrent.futures.ThreadPoolExecutor(2) as pool:
            t = time.perf_counter()
            done = list(pool.map(lambda p: native_one(p, out_dir, levels), paths))
    elif name.startswith("Dask"):
        seconds, start, done = dask_way(name, paths, out_dir, levels)
        return {"seconds": seconds, "start": start, "faces": sum(f for f, _ in done),
                "failed": sum(e is not None for _, e in done)}
    elif name == "subdiv subdivide loop":
        t = time.perf_counter()
        done = []
        for p in paths:
            out = os.path.join(out_dir, os.path.basename(p) + ".ply")
            r = subprocess.run([cli, "subdivide", p, out, "-n", str(levels), "--json"], capture_output=True, text=True)
            done.append((json.loads(r.stdout).get("faces", 0) if r.returncode == 0 and r.stdout.strip() else 0,
                         None if r.returncode == 0 else r.stderr))
    elif name.startswith("subdiv batch"):
        threads = ["--threads", "1"] if name.endswith("(1 thread)") else []
        t = time.perf_counter()
        r = subprocess.run([cli, *threads, "batch", folder, "--out", out_dir, "-n", str(levels), "--format", "ply", "--json"],
                           capture_output=True, text=True)
        seconds = time.perf_counter() - t
        summary = json.loads(r.stdout) if r.stdout.strip().startswith("{") else {}
        return {"seconds": seconds, "start": 0.0, "faces": summary.get("faces", 0), "failed": summary.get("failed")}
    else:
        raise SystemExit(f"unknown way {name!r}")
    seconds = time.perf_counter() - t
    return {"seconds": seconds, "start": start, "faces": sum(f for f, _ in done),
            "failed": sum(e is not None for _, e in done)}


def run(folder, levels, rounds, cli):
    ways = ["serial loop", "ThreadPoolExecutor(2)", "serial subdivide_file", "ThreadPoolExecutor(2) subdivide_file",
            "Dask, a task per file (arrays)", "Dask, a task per file (subdivide_file)",
            "Dask, the recipe (subdivide_file, tasks of 2 MB)"]
    if cli:
        ways.append("subdiv subdivide loop")
        if subprocess.run([cli, "batch", "--help"], capture_output=True).returncode == 0:
            ways += ["subdiv batch (1 thread)", "subdiv batch"]
    paths = models(folder)
    best = {}
    for _ in range(rounds):
        for w in ways:
            out_dir = tempfile.mkdtemp(prefix="bench-folder-")
            # each way in a fresh process: cold as a user's run, its own peak memory
            args = [sys.executable, os.path.abspath(__file__), "_way", w, folder, out_dir, str(levels), cli or ""]
            proc = subprocess.Popen(args, stdout=subprocess.PIPE, text=True)
            out = proc.stdout.read()
            _, status, usage = os.wait4(proc.pid, 0)
            proc.returncode = status
            if status == 0:
                r = json.loads(out.strip().splitlines()[-1])
                r["peak_mb"] = usage.ru_maxrss / 1024  # KiB on Linux: the largest process of the tree
                if w not in best or r["seconds"] < best[w]["seconds"]:
                    best[w] = r
            shutil.rmtree(out_dir)
    print(f"{len(paths)} models in {folder}, level {levels}; {os.cpu_count()} CPUs, Python "
          f"{platform.python_version()}, subdiv {subdiv.__version__}, load average {os.getloadavg()[0]:.1f}; "
          f"minima of {rounds} interleaved rounds\n")
    print("| way | files/s | faces/s (M) | time (s) | start (s) | failed | peak RSS (MB) |")
    print("|---|---|---|---|---|---|---|")
    for w in ways:
        r = best.get(w)
        if r is None:
            print(f"| {w} | failed | | | | | |")
            continue
        print(f"| {w} | {len(paths) / r['seconds']:.0f} | {r['faces'] / r['seconds'] / 1e6:.2f} | "
              f"{r['seconds']:.2f} | {r['start']:.2f} | {r['failed']} | {r['peak_mb']:.0f} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    m = sub.add_parser("make")
    m.add_argument("dir")
    m.add_argument("--count", type=int, default=300)
    r = sub.add_parser("run")
    r.add_argument("dir")
    r.add_argument("--levels", type=int, default=2)
    r.add_argument("--rounds", type=int, default=3)
    r.add_argument("--cli", default=None, help="a subdiv binary: adds its loop (and `subdiv batch` if it has it)")
    if sys.argv[1:2] == ["_way"]:  # one way, in the process run() started
        name, folder, out_dir, levels, cli = sys.argv[2:7]
        print(json.dumps(way(name, folder, out_dir, int(levels), cli or None)))
        return
    a = ap.parse_args()
    if a.cmd == "make":
        make(a.dir, a.count)
    else:
        run(a.dir, a.levels, a.rounds, a.cli)


if __name__ == "__main__":
    main()
