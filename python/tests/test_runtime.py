"""The offscreen renderer (the GIL is checked in test_gil.py)."""

import os

import numpy as np
import pytest
from conftest import TETRA_F, TETRA_V

import subdiv


def gpu_or_skip(fn):
    try:
        return fn()
    except subdiv.SubdivError as e:
        if os.environ.get("SUBDIV_REQUIRE_GPU") != "1" and ("adapter" in str(e).lower() or "gpu" in str(e).lower()):
            pytest.skip(f"no GPU adapter: {e}")
        raise


def test_render_offscreen():
    img = gpu_or_skip(lambda: subdiv.render(TETRA_V, TETRA_F, size=(96, 64), levels=3, scheme="butterfly"))
    assert img.dtype == np.uint8 and img.shape == (64, 96, 4)
    centre, corner = img[32, 48, :3].astype(int), img[2, 2, :3].astype(int)
    assert np.abs(centre - corner).sum() > 30, "the object is not drawn"
    wire = subdiv.render(TETRA_V, TETRA_F, size=(96, 64), levels=1, shading="wire")
    assert not np.array_equal(img, wire)


def test_render_quads():
    from conftest import cube_quads

    v, q = cube_quads()
    img = gpu_or_skip(lambda: subdiv.render(v, q, size=(48, 48), levels=2, scheme="catmull-clark", shading="flat"))
    assert img.shape == (48, 48, 4)


@pytest.mark.skipif(not os.environ.get("DISPLAY"), reason="no display (CI runs the tests under Xvfb)")
def test_view_opens_the_window_and_returns(tmp_path):
    from conftest import run_python

    shot = tmp_path / "view.png"
    code = ("import numpy as np, subdiv\n"
            "from conftest import TETRA_V, TETRA_F\n"
            f"subdiv.view(TETRA_V, TETRA_F, levels=2, scheme='loop', frames=5, screenshot={str(shot)!r})\n"
            "print('closed')\n")
    r = run_python(f"import sys; sys.path.insert(0, {os.path.dirname(__file__)!r})\n" + code, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "closed" in r.stdout
    assert shot.exists() and shot.stat().st_size > 1000
