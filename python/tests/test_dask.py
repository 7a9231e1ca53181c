"""The recipe of docs/dask.md: a folder of models refined on a Dask
LocalCluster of worker processes (client.map over tasks of several files,
each file one subdivide_file call, the lines gathered) writes exactly the
files of the serial run and the same lines, a bad file its own error; the
arrays' variant gives the serial arrays byte for byte; Meshes and Refiners
travel between processes. Skipped only without dask."""

import logging
import os
import shutil

import numpy as np
import pytest
from conftest import MODELS, bipyramid, cube_quads, open_grid

import subdiv

distributed = pytest.importorskip("dask.distributed")


def refine_files(paths, out_dir, levels=2):
    """docs/dask.md's function: each file of `paths` refined by the options
    it states and written into `out_dir`, its line or its error (one bad
    file never stops the others)."""
    lines = []
    for path in paths:
        out = os.path.join(out_dir, os.path.basename(path) + ".ply")
        try:
            lines.append(subdiv.subdivide_file(path, out, levels, threads=1))
        except subdiv.SubdivError as e:
            lines.append({"input": path, "output": out, "status": "failed", "error": str(e)})
    return lines


def tasks(paths, files_per_task):
    """docs/dask.md's chunks: `paths` in lists of `files_per_task`."""
    return [paths[i:i + files_per_task] for i in range(0, len(paths), files_per_task)]


def refine(path, levels=2):
    """docs/dask.md's variant that ships the arrays back: one file refined
    by the options it states, or its error."""
    try:
        m = subdiv.load(path)
        polygonal = m.options.get("scheme") in subdiv.POLYGON_SCHEMES and m.polygons is not None
        v2, f2 = subdiv.subdivide(m.vertices, m.polygons if polygonal else m.faces, levels, threads=1, **m.options)
        return {"path": path, "vertices": v2, "faces": f2, "error": None, "pid": os.getpid()}
    except subdiv.SubdivError as e:
        return {"path": path, "vertices": None, "faces": None, "error": str(e), "pid": os.getpid()}


def folder(tmp):
    """The bundled models that are meshes, generated ones, and a file that is none."""
    for name in sorted(os.listdir(MODELS)):
        if name.endswith((".obj", ".ct")):
            shutil.copy(os.path.join(MODELS, name), tmp / name)
    for k in range(3, 15):
        subdiv.save(str(tmp / f"bipyramid{k}.ply"), *bipyramid(k, jitter=0.05, seed=k))
    for n in (3, 6, 12):
        subdiv.save(str(tmp / f"grid{n}.off"), *open_grid(n, seed=n))
    subdiv.save(str(tmp / "cube.quads.obj"), *cube_quads())
    (tmp / "broken.obj").write_text("v 0 0 0\nv 1 0 0\nf 1 2 7\n")
    return sorted(str(p) for p in tmp.iterdir())


def same(a, b):
    return a is b is None or (a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes())


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=logging.ERROR) as cluster, distributed.Client(cluster) as c:
        yield c


def test_the_recipe_writes_the_files_of_the_serial_run(client, tmp_path):
    (tmp_path / "in").mkdir()
    paths = folder(tmp_path / "in")
    serial_dir, dask_dir = tmp_path / "serial", tmp_path / "dask"
    serial_dir.mkdir()
    dask_dir.mkdir()
    serial = refine_files(paths, str(serial_dir))
    chunks = tasks(paths, 4)
    assert len(chunks) >= 6
    done = client.gather(client.map(lambda c: (os.getpid(), refine_files(c, str(dask_dir))), chunks))
    gathered = [line for _, lines in done for line in lines]
    assert os.getpid() not in {pid for pid, _ in done}, "the work was done in the worker processes"
    assert [d["input"] for d in gathered] == paths
    drop = ("seconds", "output")
    for s, d in zip(serial, gathered):
        assert {k: v for k, v in s.items() if k not in drop} == {k: v for k, v in d.items() if k not in drop}
    written = sorted(os.listdir(serial_dir))
    assert written == sorted(os.listdir(dask_dir)) and len(written) == len(paths) - 1
    for name in written:
        assert (serial_dir / name).read_bytes() == (dask_dir / name).read_bytes(), name
    failed = [d for d in gathered if d["status"] == "failed"]
    assert [os.path.basename(d["input"]) for d in failed] == ["broken.obj"]
    assert "broken.obj" in failed[0]["error"], "the error names the file"
    assert sum(d["faces"] for d in gathered if d["status"] == "done") > 10_000


def test_a_folder_through_dask_equals_the_serial_run(client, tmp_path):
    paths = folder(tmp_path)
    assert len(paths) >= 25
    serial = [refine(p) for p in paths]
    gathered = client.gather(client.map(refine, paths))
    assert [r["path"] for r in gathered] == paths
    for s, d in zip(serial, gathered):
        assert s["error"] == d["error"], s["path"]
        assert same(s["vertices"], d["vertices"]) and same(s["faces"], d["faces"]), s["path"]
    # the work was done in the worker processes, not in this one
    assert os.getpid() not in {d["pid"] for d in gathered}
    failed = [d for d in gathered if d["error"]]
    assert [os.path.basename(d["path"]) for d in failed] == ["broken.obj"]
    assert "broken.obj" in failed[0]["error"], "the error names the file"
    assert sum(len(d["faces"]) for d in gathered if d["faces"] is not None) > 10_000


def test_meshes_and_refiners_travel_between_processes(client):
    path = os.path.join(MODELS, "cube_uv.obj")
    assert client.submit(subdiv.load, path).result() == subdiv.load(path)
    v, f = open_grid(6)
    r = subdiv.Refiner(v, f, levels=2)
    r.move([3], v[[3]] + 0.5)
    # the refiner goes to a worker (pickled), is edited there, and comes back
    back = client.submit(lambda q: (q.move([4], v[[4]] - 0.5), q)[1], r).result()
    r.move([4], v[[4]] - 0.5)
    assert back == r
    assert back.undo() and r.undo() and np.array_equal(back.vertices, r.vertices)


def test_a_worker_error_reaches_the_client_as_subdiv_error(client):
    with pytest.raises(subdiv.SubdivError, match="levels"):
        client.submit(subdiv.subdivide, [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], -1).result()
