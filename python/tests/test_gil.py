"""Every function that works on a mesh runs without the GIL, so that the
threads of a ThreadPoolExecutor run side by side: a counting thread keeps
running through a long call of each (with the GIL held it would stop for the
whole call). This checks the GIL, not a speed: the speed-up of two threads
over one is measured by ``python/bench.py --threads`` (docs/performance.md)."""

import threading
import time

import numpy as np
import pytest
from conftest import icosahedron, sphere

import subdiv

PAUSE = 0.001  # a pause of the counter longer than this is recorded


class Counter:
    """A thread that counts as fast as it can and records every pause
    longer than PAUSE as (start, end)."""

    def __init__(self):
        self.pauses, self.stop = [], threading.Event()
        self.thread = threading.Thread(target=self._run, daemon=True)

    def _run(self):
        last = time.perf_counter()
        while not self.stop.is_set():
            now = time.perf_counter()
            if now - last > PAUSE:
                self.pauses.append((last, now))
            last = now

    def longest_within(self, t0, t1):
        """The longest pause inside [t0, t1]; a pause that is still going on
        when the call returns is recorded once the counter runs again."""
        time.sleep(0.02)  # lets the counter record a pause it was in
        inside = [min(b, t1) - max(a, t0) for a, b in list(self.pauses) if b > t0 and a < t1]
        return max(inside, default=0.0)

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.stop.set()
        self.thread.join()


def released(call, tries=5, least=0.05):
    """The smallest share of a call the counter stood still for, over up
    to `tries` calls that each take at least `least` seconds."""
    call()  # warm-up: pages, caches, the pool's threads
    shares = []
    with Counter() as c:
        for _ in range(tries):
            t0 = time.perf_counter()
            call()
            t1 = time.perf_counter()
            if t1 - t0 >= least:
                shares.append(c.longest_within(t0, t1) / (t1 - t0))
            if shares and min(shares) < 0.25:
                break
    assert shares, f"no call took {least} s: too small a workload to tell"
    return min(shares)


def big():
    v, f = icosahedron()
    return subdiv.subdivide(v, f, 7)  # 328k triangles


def workloads(tmp):
    """name -> a call of at least 0.05 s on this machine's two cores."""
    v, f = icosahedron()
    V, F = big()
    sv, sf = sphere(4)
    rng = np.random.default_rng(0)
    faces = rng.integers(0, len(sf), 400_000)
    uv = rng.uniform(0, 0.5, (len(faces), 2))
    obj = str(tmp / "big.obj")
    subdiv.save(obj, V, F)
    # one refiner for the edits (each leaves it ready for the others): a
    # small cage refined deep, so that an edit reaches much of 1.3 M faces
    edited = subdiv.Refiner(v, f, levels=8)
    every = np.arange(len(v))
    edited.move(every, v * 1.1)
    scale = iter(np.linspace(1.01, 2, 1000))
    return {
        "subdivide": lambda: subdiv.subdivide(v, f, 8, threads=1),
        "subdivide catmull-clark": lambda: subdiv.subdivide(v, f, 8, "catmull-clark", threads=1),
        "evaluate": lambda: subdiv.evaluate(sv, sf, faces, uv, curvature=True),
        "limit": lambda: subdiv.limit(V, F),
        # the native half (scipy composes the levels after it, on its own terms)
        "matrix": lambda: subdiv._subdiv.plan_levels(subdiv._checks.faces(f), len(v), subdiv._checks.tags(None),
                                                     subdiv._options(), 8, None),
        "load": lambda: subdiv.load(obj),
        "save": lambda: subdiv.save(str(tmp / "out.obj"), V, F),
        "subdivide_file": lambda: subdiv.subdivide_file(obj, str(tmp / "fine.ply"), 1, threads=1),
        "Refiner": lambda: subdiv.Refiner(v, f, levels=8),
        "Refiner.move": lambda: edited.move(every, v * next(scale)),
        "Refiner.undo+redo": lambda: (edited.undo(), edited.redo()),
        "Refiner.set_sharpness": lambda: (edited.set_sharpness(int(f[0, 0]), int(f[0, 1]), 3.0), edited.undo()),
    }


NAMES = ["subdivide", "subdivide catmull-clark", "evaluate", "limit", "matrix", "load", "save", "subdivide_file",
         "Refiner", "Refiner.move", "Refiner.undo+redo", "Refiner.set_sharpness"]


@pytest.fixture(scope="module")
def calls(tmp_path_factory):
    return workloads(tmp_path_factory.mktemp("gil"))


@pytest.mark.parametrize("name", NAMES)
def test_a_long_call_lets_another_thread_run(name, calls):
    share = released(calls[name])
    # held, the counter stops for the whole call (share 1); released, its
    # pauses are the scheduler's and the GIL's switch interval (5 ms)
    assert share < 0.25, f"{name}: the counting thread stood still for {share:.0%} of the call"
