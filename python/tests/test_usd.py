"""USD through the package, read back by Pixar's usd-core (skipped without it): a
mesh saved as .usda is the Mesh usd-core reads, and the fixture stage authored by
usd-core (tests/fixtures/usd, scripts/usd-fixtures.py) loads with its prims'
world transforms applied."""
import os

import numpy as np
import pytest

import subdiv

pxr = pytest.importorskip("pxr")
from pxr import Usd, UsdGeom  # noqa: E402

FIXTURES = os.path.join(os.path.dirname(__file__), "..", "..", "tests", "fixtures", "usd")


def test_a_saved_usda_is_the_mesh_usd_core_reads(tmp_path):
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]], float)
    quads = [[0, 1, 2, 3], [1, 4, 5, 2]]
    path = str(tmp_path / "q.usda")
    subdiv.save(path, v, quads)
    stage = Usd.Stage.Open(path)
    meshes = [UsdGeom.Mesh(p) for p in stage.Traverse() if p.IsA(UsdGeom.Mesh)]
    assert len(meshes) == 1
    m = meshes[0]
    assert list(m.GetFaceVertexCountsAttr().Get()) == [4, 4]
    pts = np.array(m.GetPointsAttr().Get(), float)
    idx = np.array(m.GetFaceVertexIndicesAttr().Get()).reshape(-1, 4)
    assert np.allclose(pts[idx], v[np.array(quads)])
    # our defaults, not USD's, are written
    assert m.GetInterpolateBoundaryAttr().Get() == "edgeOnly"


def test_the_fixture_stage_loads_in_world_space():
    path = os.path.join(FIXTURES, "stage.usda")
    ours = subdiv.load(path)
    stage = Usd.Stage.Open(path)
    world = []
    for prim in stage.Traverse():
        if prim.IsA(UsdGeom.Mesh):
            xf = UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
            world += [list(xf.Transform(p)) for p in UsdGeom.Mesh(prim).GetPointsAttr().Get()]
    assert np.allclose(ours.vertices, np.array(world), atol=1e-5)
