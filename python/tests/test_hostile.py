"""Every hostile input, each in its own interpreter: an abort or a segfault
fails the test instead of killing the run. Refused values raise
SubdivError naming the problem; wrong shapes and dtypes TypeError or
ValueError."""

import os
import sys
import textwrap

import pytest
from conftest import run_python

PRELUDE = textwrap.dedent("""
    import sys, time
    import numpy as np
    import subdiv
    TV = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], float)
    TF = np.array([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]])
    V5 = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], float)
    def bad(x):
        v = TV.copy(); v[2, 1] = x; return v
""")

# (case, call, expected exception, regex the message must match)
CASES = [
    ("non-manifold edge", "subdiv.subdivide(V5, [[0, 1, 2], [1, 0, 3], [0, 1, 4]])", "SubdivError",
     r"non-manifold edge \((0, 1|1, 0)\)"),
    ("edge of three faces, repaired", "print(subdiv.subdivide(V5, [[0, 1, 2], [1, 0, 3], [0, 1, 4]], repair=True)[1].shape)",
     None, r"\(12, 3\)"),
    ("duplicate face", "subdiv.subdivide(TV, np.vstack([TF, TF[:1]]))", "SubdivError", r"edge|orientation"),
    ("duplicate face, repaired", "print(subdiv.subdivide(TV, np.vstack([TF, TF[:1]]), repair=True)[1].shape)",
     None, r"\(16, 3\)"),
    ("index out of range", "subdiv.subdivide(TV, [[0, 1, 4], [0, 2, 3]])", "SubdivError", r"face 0 .*index 4.* 4 vertices"),
    ("negative index", "subdiv.subdivide(TV, [[0, 1, -1]])", "SubdivError", r"negative vertex index -1"),
    ("index 2**40", "subdiv.subdivide(TV, np.array([[0, 1, 2**40]]))", "SubdivError", r"index 1099511627776"),
    ("index 2**70", "subdiv.subdivide(TV, [[0, 1, 2**70]])", "SubdivError", r"out of range"),
    ("uint64 index 2**64-1", "subdiv.subdivide(TV, np.array([[0, 1, 2**64 - 1]], np.uint64))", "SubdivError",
     r"out of range"),
    ("NaN coordinate", "subdiv.subdivide(bad(np.nan), TF)", "SubdivError", r"vertex 2 .*non-finite"),
    ("infinite coordinate", "subdiv.subdivide(bad(-np.inf), TF)", "SubdivError", r"vertex 2 .*non-finite"),
    ("coordinate past float32", "subdiv.subdivide(bad(1e300), TF)", "SubdivError", r"vertex 2 .*single precision"),
    ("unknown scheme", "subdiv.subdivide(TV, TF, 1, 'sqrt3')", "SubdivError", r"unknown scheme 'sqrt3'"),
    ("unknown beta", "subdiv.subdivide(TV, TF, beta='stam')", "SubdivError", r"unknown beta 'stam'"),
    ("unknown boundary", "subdiv.subdivide(TV, TF, boundary='nope')", "SubdivError",
     r"unknown boundary interpolation 'nope' \(expected edge, edge-and-corner or none\)"),
    ("unknown fvar", "subdiv.subdivide(TV, TF, fvar='nope')", "SubdivError", r"face-varying .*'nope'.*corners-plus1"),
    ("unknown triangles", "subdiv.subdivide(TV, TF, triangles='nope')", "SubdivError", r"'nope'.*catmark or smooth"),
    ("unknown creasing", "subdiv.subdivide(TV, TF, creasing='nope')", "SubdivError", r"'nope'.*uniform or chaikin"),
    ("a name of a megabyte", "subdiv.subdivide(TV, TF, boundary='x' * 10**6)", "SubdivError",
     r"^unknown boundary interpolation 'x+\.\.\.x+' \(expected edge, edge-and-corner or none\)$"),
    ("hole out of range", "subdiv.subdivide(TV, TF, holes=[4])", "SubdivError", r"hole 0 names face 4, but there are 4"),
    ("hole negative", "subdiv.subdivide(TV, TF, holes=[-1])", "SubdivError", r"hole 0 names face -1"),
    ("float holes", "subdiv.subdivide(TV, TF, holes=[0.5])", "TypeError", r"holes"),
    ("holes with repair", "subdiv.subdivide(TV, TF, holes=[0], repair=True)", "SubdivError", r"holes .*repair"),
    ("refiner sharpness NaN", "subdiv.Refiner(TV, TF).set_sharpness(0, 1, np.nan)", "SubdivError",
     r"edge 0-1 has sharpness NaN: it must be finite and at least 0"),
    ("levels=-1", "subdiv.subdivide(TV, TF, -1)", "SubdivError", r"levels"),
    ("levels=50 within a second",
     "t = time.time()\ntry:\n    subdiv.subdivide(TV, TF, 50)\nfinally:\n    assert time.time() - t < 1.0",
     "SubdivError", r"memory|too large|fit"),
    ("levels=2**40", "subdiv.subdivide(TV, TF, 2**40)", "SubdivError", r"memory"),
    ("levels=1.5", "subdiv.subdivide(TV, TF, 1.5)", "TypeError", r"levels"),
    ("float faces", "subdiv.subdivide(TV, TF.astype(float))", "TypeError", r"float"),
    ("faces (m, 2)", "subdiv.subdivide(TV, TF[:, :2])", "ValueError", r"shape"),
    ("faces 1-D", "subdiv.subdivide(TV, TF.ravel())", "ValueError", r"shape"),
    ("vertices (n, 2)", "subdiv.subdivide(TV[:, :2], TF)", "ValueError", r"\(n, 3\)"),
    ("vertices of strings", "subdiv.subdivide([['a', 'b', 'c']] * 4, TF)", "TypeError", r"dtype"),
    ("vertices ragged", "subdiv.subdivide([[0, 1, 2], [1, 2]], TF)", "ValueError", r"vertices"),
    ("faces None", "subdiv.subdivide(TV, None)", "TypeError|ValueError", r"faces"),
    ("empty input", "subdiv.subdivide(np.zeros((0, 3)), np.zeros((0, 3), int))", "SubdivError", r"no triangles"),
    ("degenerate face", "subdiv.subdivide(TV, [[0, 0, 1]])", "SubdivError", r"degenerate"),
    ("threads=0", "subdiv.subdivide(TV, TF, threads=0)", "SubdivError", r"threads"),
    ("threads=-1", "subdiv.subdivide(TV, TF, threads=-1)", "SubdivError", r"threads"),
    ("threads=10**6", "subdiv.subdivide(TV, TF, threads=10**6)", "SubdivError", r"threads"),
    ("limit threads=0", "subdiv.limit(TV, TF, threads=0)", "SubdivError", r"threads"),
    ("evaluate threads=-1", "subdiv.evaluate(TV, TF, [0], [[0.2, 0.2]], threads=-1)", "SubdivError", r"threads"),
    ("matrix threads=10**6", "subdiv.matrix(TF, threads=10**6)", "SubdivError", r"threads"),
    ("load threads=1.5", "subdiv.load('x.obj', threads=1.5)", "TypeError", r"threads"),
    ("save threads=0", "subdiv.save('x.obj', TV, TF, threads=0)", "SubdivError", r"threads"),
    ("Refiner threads=0", "subdiv.Refiner(TV, TF, threads=0)", "SubdivError", r"threads"),
    ("crease NaN", "subdiv.subdivide(TV, TF, creases=([[0, 1]], [np.nan]))", "SubdivError", r"sharpness"),
    ("crease not an edge", "subdiv.subdivide(V5, [[0, 1, 2]], creases=([[3, 4]], [1.0]))", "SubdivError",
     r"crease|edge"),
    ("crease index out of range", "subdiv.subdivide(TV, TF, creases=([[0, 9]], [1.0]))", "SubdivError", r"crease"),
    ("crease shape", "subdiv.subdivide(TV, TF, creases=([[0, 1, 2]], [1.0]))", "ValueError", r"\(k, 2\)"),
    ("matrix n_vertices 2**40", "subdiv.matrix(TF, n_vertices=2**40)", "SubdivError", r"n_vertices"),
    ("matrix levels=50", "subdiv.matrix(TF, 50)", "SubdivError", r"memory|too large|fit"),
    ("limit of quads", "subdiv.limit(TV, [[0, 1, 2, 3]])", "SubdivError", r"triangles"),
    ("limit non-manifold", "subdiv.limit(V5, [[0, 1, 2], [1, 0, 3], [0, 1, 4]])", "SubdivError", r"non-manifold"),
    ("load a missing file", "subdiv.load('/nonexistent/x.obj')", "SubdivError", r"x\.obj"),
    ("load garbage", "open('g.ply', 'wb').write(b'ply\\nformat binary_little_endian 1.0\\nelement vertex 99999999999\\nend_header\\n')\n"
     "subdiv.load('g.ply')", "SubdivError", r"g\.ply"),
    ("save unknown extension", "subdiv.save('x.unknown', TV, TF)", "SubdivError", r"x\.unknown"),
    ("render size 0", "subdiv.render(TV, TF, size=(0, 10))", "SubdivError", r"size|width"),
    ("render size huge", "subdiv.render(TV, TF, size=(10**6, 10**6))", "SubdivError", r"size"),
    ("render unknown shading", "subdiv.render(TV, TF, shading='toon', size=(8, 8))", "SubdivError", r"shading"),
]

RUNNER = textwrap.dedent("""
    try:
    {body}
    except Exception as e:
        print("RAISED", type(e).__name__, "|", e)
    else:
        print("RETURNED")
""")


@pytest.mark.parametrize("case,call,expect,pattern", CASES, ids=[c[0] for c in CASES])
def test_hostile(case, call, expect, pattern, tmp_path):
    import re

    body = textwrap.indent(call, "    ")
    code = PRELUDE + f"import os\nos.chdir({str(tmp_path)!r})\n" + RUNNER.replace("{body}", body)
    r = run_python(code)
    assert r.returncode == 0, f"the interpreter died ({r.returncode}): {r.stderr[-2000:]}"
    out = r.stdout.strip().splitlines()
    assert out, r.stderr[-2000:]
    last = out[-1]
    if expect is None:
        assert last == "RETURNED", last
        assert re.search(pattern, r.stdout), r.stdout
        return
    assert last.startswith("RAISED"), f"nothing raised: {r.stdout}"
    name, msg = last[len("RAISED "):].split(" | ", 1)
    assert re.fullmatch(expect, name), f"{name}: {msg}"
    assert re.search(pattern, msg), f"{name}: {msg}"


def test_view_without_a_display_raises():
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    import subprocess

    code = PRELUDE + RUNNER.replace("{body}", "    subdiv.view(TV, TF, frames=1)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, env=env)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "RAISED SubdivError" in r.stdout, r.stdout


@pytest.mark.parametrize("threads", ["None", "1", "2"])
def test_a_panic_becomes_subdiv_error(threads):
    r = run_python(PRELUDE + RUNNER.replace("{body}", f"    subdiv._subdiv._panic_for_tests({threads})"))
    assert r.returncode == 0, f"the interpreter died ({r.returncode}): {r.stderr[-2000:]}"
    assert "RAISED SubdivError | internal error" in r.stdout and "deliberate panic" in r.stdout, r.stdout


def test_the_native_module_checks_what_it_is_given():
    # a direct caller of the private module, past the Python layer's checks
    tags = "(np.zeros(0, np.int64), np.zeros(0), np.zeros(0, np.int64))"
    names = "('loop', 'loop', 'edge', 'corners-only', 'catmark', 'uniform')"
    code = PRELUDE + RUNNER.replace("{body}", "    subdiv._subdiv.subdivide_arrays((np.zeros((6, 2)), np.arange(3), np.array([0, 3])), "
                                    f"{tags}, {names}, 1, (False, True), None)")
    r = run_python(code)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "RAISED TypeError | vertices must have shape (n, 3)" in r.stdout, r.stdout
    code = PRELUDE + RUNNER.replace("{body}", "    subdiv._subdiv.subdivide_arrays((TV, np.array([0, 1, 2]), np.array([0, 7])), "
                                    f"{tags}, {names}, 1, (False, True), None)")
    r = run_python(code)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "RAISED SubdivError | face offsets" in r.stdout, r.stdout
