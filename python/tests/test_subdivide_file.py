"""subdiv.subdivide_file: one file read, refined and written in one native
call, the command line's own per-file path (subdiv::subdivide_file), so
its output is the bytes `subdiv subdivide` writes; a bad file raises
SubdivError naming it and leaves no output behind."""

import os
import shutil
import subprocess

import numpy as np
import pytest
from conftest import MODELS, REPO, bipyramid, cube_quads, open_grid

import subdiv


def cli():
    """The command line to compare with: $SUBDIV_CLI, else the repository's
    release or debug build (skipped where none is built)."""
    for p in (os.environ.get("SUBDIV_CLI"), os.path.join(REPO, "target", "release", "subdiv"),
              os.path.join(REPO, "target", "debug", "subdiv")):
        if p and os.access(p, os.X_OK):
            return p
    pytest.skip("no subdiv binary built (cargo build --release) and no $SUBDIV_CLI")


def inputs(tmp):
    """Bundled models (triangles, quads, tags) and generated ones in three formats."""
    paths = [os.path.join(MODELS, n) for n in ("cube.obj", "cube_uv.obj", "torus.ct", "lprism.obj", "critter.obj")]
    subdiv.save(str(tmp / "bip.ply"), *bipyramid(9, jitter=0.05, seed=3))
    subdiv.save(str(tmp / "grid.off"), *open_grid(5, seed=2))
    subdiv.save(str(tmp / "quads.obj"), *cube_quads())
    return paths + [str(tmp / n) for n in ("bip.ply", "grid.off", "quads.obj")]


CASES = [
    ("ply", 2, {}, []),
    ("obj", 1, {}, []),
    ("obj", 2, {"scheme": "catmull-clark"}, ["--scheme", "catmull-clark"]),
    ("ply", 1, {"boundary": "edge-and-corner", "beta": "warren"}, ["--boundary", "edge-and-corner", "--warren"]),
    ("obj", 1, {"precision": "f64"}, ["--precision", "f64"]),
    ("off", 0, {}, []),
]


@pytest.mark.parametrize("ext,levels,kw,flags", CASES)
def test_the_output_is_the_bytes_subdiv_subdivide_writes(ext, levels, kw, flags, tmp_path):
    binary = cli()
    for path in inputs(tmp_path):
        name = os.path.basename(path)
        ours, theirs = tmp_path / f"ours-{name}.{ext}", tmp_path / f"cli-{name}.{ext}"
        done = subdiv.subdivide_file(path, ours, levels, threads=1, **kw)
        r = subprocess.run([binary, "-q", "subdivide", path, str(theirs), "-n", str(levels), *flags],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        assert ours.read_bytes() == theirs.read_bytes(), f"{name} -> .{ext} {kw}"
        assert done["output_bytes"] == theirs.stat().st_size


def test_the_output_equals_subdivide_of_the_loaded_arrays(tmp_path):
    """Triangle meshes refined in float32 by subdivide() from load()'s arrays
    give the vertices and faces the file holds, bit for bit."""
    for path in inputs(tmp_path)[:4] + [str(tmp_path / "bip.ply"), str(tmp_path / "grid.off")]:
        m = subdiv.load(path)
        if m.options.get("scheme") in subdiv.POLYGON_SCHEMES or m.polygons is not None:
            continue
        out = tmp_path / (os.path.basename(path) + ".ply")
        done = subdiv.subdivide_file(path, out, 2, threads=1)
        v2, f2 = subdiv.subdivide(m.vertices.astype(np.float32), m.faces, 2, threads=1, **m.options)
        back = subdiv.load(out)
        assert np.array_equal(back.vertices, v2.astype(np.float64)), path
        assert np.array_equal(back.faces, f2), path
        assert (done["vertices"], done["faces"], done["input_vertices"]) == (len(v2), len(f2), len(m.vertices))


def test_the_result_is_a_manifest_line(tmp_path):
    out = tmp_path / "t.obj"
    done = subdiv.subdivide_file(os.path.join(MODELS, "tetrahedron.obj"), out, levels=3)
    assert set(done) == {"input", "output", "status", "scheme", "levels", "input_vertices", "input_faces", "vertices",
                         "faces", "output_bytes", "seconds"}
    assert done["status"] == "done" and done["scheme"] == "loop" and done["levels"] == 3
    assert (done["input_vertices"], done["input_faces"], done["faces"]) == (4, 4, 4 * 64)
    assert done["output"] == str(out) and done["output_bytes"] == out.stat().st_size
    assert 0 < done["seconds"] < 10
    back = subdiv.load(out)
    assert back.faces.shape == (256, 3) and len(back.vertices) == done["vertices"]


def test_bundled_models_and_the_files_scheme(tmp_path):
    done = subdiv.subdivide_file("bundled:cube.obj", tmp_path / "c.obj", 1)
    assert done["faces"] == subdiv.load(tmp_path / "c.obj").faces.shape[0]
    # an explicit scheme over the file's: quads out
    quads = subdiv.subdivide_file(os.path.join(MODELS, "cube.obj"), tmp_path / "q.obj", 1, "catmull-clark")
    assert quads["scheme"] == "catmull-clark"
    assert subdiv.load(tmp_path / "q.obj").polygons.shape[1] == 4


def test_the_threads_change_no_byte(tmp_path):
    path = str(tmp_path / "bip.ply")
    subdiv.save(path, *bipyramid(40, jitter=0.05, seed=1))
    outs = []
    for t in (1, 2, None):
        out = tmp_path / f"out{t}.ply"
        subdiv.subdivide_file(path, out, 4, threads=t)
        outs.append(out.read_bytes())
    assert outs[0] == outs[1] == outs[2]


def test_a_bad_file_raises_subdiv_error_naming_it_and_writes_nothing(tmp_path):
    bad = tmp_path / "broken.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nf 1 2 7\n")
    out = tmp_path / "out.ply"
    with pytest.raises(subdiv.SubdivError, match="broken.obj"):
        subdiv.subdivide_file(bad, out)
    assert sorted(os.listdir(tmp_path)) == ["broken.obj"], "no output, no temporary file"
    with pytest.raises(subdiv.SubdivError, match="missing.obj"):
        subdiv.subdivide_file(tmp_path / "missing.obj", out)
    # a non-manifold mesh: refused unless repaired
    fin = tmp_path / "fin.obj"
    fin.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n")
    with pytest.raises(subdiv.SubdivError, match="fin.obj"):
        subdiv.subdivide_file(fin, out)
    assert not out.exists()
    assert subdiv.subdivide_file(fin, out, repair=True)["status"] == "done" and out.exists()


def test_a_failed_call_leaves_the_old_output_whole(tmp_path):
    """Atomic: the output is replaced only by a whole file; a refusal (too
    many levels for memory) leaves what was there and no temporary file."""
    src = os.path.join(MODELS, "cube.obj")
    out = tmp_path / "out.obj"
    out.write_text("the old output\n")
    with pytest.raises(subdiv.SubdivError, match="cube.obj") as e:
        subdiv.subdivide_file(src, out, levels=30)
    assert "memory" in str(e.value) or "bytes" in str(e.value), e.value
    assert out.read_text() == "the old output\n"
    assert sorted(os.listdir(tmp_path)) == ["out.obj"]
    # an output in a folder that does not exist: refused, nothing made
    with pytest.raises(subdiv.SubdivError, match="cube.obj"):
        subdiv.subdivide_file(src, tmp_path / "no" / "such" / "out.obj")
    assert not (tmp_path / "no").exists()
    with pytest.raises(subdiv.SubdivError, match="cube.obj"):
        subdiv.subdivide_file(src, tmp_path / "out.xyz")


def test_bad_arguments_are_refused_before_reading(tmp_path):
    src, out = os.path.join(MODELS, "cube.obj"), tmp_path / "o.obj"
    with pytest.raises(subdiv.SubdivError, match="plaid"):
        subdiv.subdivide_file(src, out, scheme="plaid")
    with pytest.raises(subdiv.SubdivError, match="sideways"):
        subdiv.subdivide_file(src, out, boundary="sideways")
    with pytest.raises(subdiv.SubdivError, match="precision"):
        subdiv.subdivide_file(src, out, precision="f16")
    with pytest.raises(subdiv.SubdivError, match="levels"):
        subdiv.subdivide_file(src, out, levels=-1)
    with pytest.raises(TypeError):
        subdiv.subdivide_file(src, out, levels=1.5)
    with pytest.raises(TypeError):
        subdiv.subdivide_file(src, out, scheme=3)
    with pytest.raises(subdiv.SubdivError, match="threads"):
        subdiv.subdivide_file(src, out, threads=0)
    with pytest.raises(subdiv.SubdivError, match="time"):
        subdiv.subdivide_file(src, out, time=float("nan"))
    assert not out.exists()


def test_the_file_options_and_the_callers(tmp_path):
    """A file's tags are taken where no keyword is given; a keyword takes
    their place (as the command line's flags)."""
    src = tmp_path / "tagged.obj"
    subdiv.save(src, *open_grid(4, seed=5))
    with open(src, "a") as f:
        f.write("t interpolateboundary 1/0/0 1\n")  # edge-and-corner
    a, b, c = tmp_path / "a.obj", tmp_path / "b.obj", tmp_path / "c.obj"
    subdiv.subdivide_file(src, a, 1)
    subdiv.subdivide_file(src, b, 1, boundary="edge")
    subdiv.subdivide_file(src, c, 1, boundary="edge-and-corner")
    assert a.read_bytes() == c.read_bytes()
    va, vb = subdiv.load(a).vertices, subdiv.load(b).vertices
    assert va.shape == vb.shape and not np.array_equal(va, vb), "the corners move under boundary=edge"
