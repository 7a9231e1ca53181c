"""subdiv.load and subdiv.save: round trips through every written format,
and the reading of the formats that are only read (from the repository's
models and from text made here)."""

import os

import numpy as np
import pytest
from conftest import MODELS, cube_quads, icosahedron

import subdiv

WRITTEN = ["obj", "ply", "off", "stl", "glb", "ct"]
POLYGONS_KEPT = ["obj", "ply", "off", "ct"]


def same_surface(v1, f1, v2, f2, tol=1e-6):
    """The same triangles (as position triples, any rotation) on both sides."""
    def tris(v, f):
        out = set()
        for t in f:
            p = [tuple(np.round(v[i] / tol).astype(np.int64)) for i in t]
            k = p.index(min(p))
            out.add(tuple(p[k:] + p[:k]))
        return out
    return tris(v1, f1) == tris(v2, f2)


@pytest.mark.parametrize("ext", WRITTEN)
def test_round_trip_triangles(ext, tmp_path):
    v, f = icosahedron()
    path = tmp_path / f"ico.{ext}"
    subdiv.save(path, v, f)
    m = subdiv.load(str(path))
    assert m.vertices.dtype == np.float64 and m.faces.dtype == np.int64
    assert m.faces.shape == f.shape and m.vertices.shape == v.shape
    assert same_surface(m.vertices, m.faces, v.astype(np.float32).astype(float), f)


@pytest.mark.parametrize("ext", POLYGONS_KEPT)
def test_round_trip_quads(ext, tmp_path):
    v, q = cube_quads()
    path = tmp_path / f"cube.{ext}"
    subdiv.save(path, v, q)
    m = subdiv.load(path)
    assert m.polygons is not None and m.polygons.shape == (6, 4)
    assert {frozenset(map(tuple, v[p])) for p in q} == {frozenset(map(tuple, m.vertices[p])) for p in m.polygons}
    # Catmull-Clark of what was read equals that of what was written
    a, _ = subdiv.subdivide(m.vertices, m.polygons, 2, "catmull-clark")
    b, _ = subdiv.subdivide(v, q, 2, "catmull-clark")
    assert np.allclose(np.sort(a, axis=0), np.sort(b, axis=0), atol=1e-6)


def test_subdivided_mesh_round_trip(tmp_path):
    v, f = icosahedron()
    v2, f2 = subdiv.subdivide(v, f, 2)
    subdiv.save(tmp_path / "l2.ply", v2, f2)
    m = subdiv.load(tmp_path / "l2.ply")
    assert same_surface(m.vertices, m.faces, v2, f2, tol=1e-5)


@pytest.mark.parametrize("name", ["tetrahedron.obj", "tetrahedron.ct", "torus.obj", "cube_uv.obj", "teapot.bez",
                                  "critter.obj"])
def test_repository_models_load(name):
    # the teapot's patches meet at non-manifold points: it needs the repair
    m = subdiv.load(os.path.join(MODELS, name), repair=name.endswith(".bez"))
    assert len(m.vertices) and len(m.faces) and np.isfinite(m.vertices).all()
    assert m.faces.max() < len(m.vertices)
    if name == "cube_uv.obj":
        assert m.uv is not None and m.uv.shape == (len(m.faces), 3, 2)


COLLADA = """<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
 <library_geometries><geometry id="g"><mesh>
  <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
   <technique_common><accessor source="#pa" count="3" stride="3">
    <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
   </accessor></technique_common></source>
  <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
  <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
 </mesh></geometry></library_geometries>
 <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#g"/></node></visual_scene>
 </library_visual_scenes><scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"""


def test_collada_is_read(tmp_path):
    (tmp_path / "t.dae").write_text(COLLADA)
    m = subdiv.load(tmp_path / "t.dae")
    assert m.faces.tolist() == [[0, 1, 2]]
    assert np.array_equal(m.vertices, [[0, 0, 0], [1, 0, 0], [0, 1, 0]])


def test_colours_are_read(tmp_path):
    (tmp_path / "c.off").write_text("COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2\n")
    m = subdiv.load(tmp_path / "c.off")
    assert m.colors is not None and m.colors.shape == (3, 3)
    assert m.colors[0, 0] > 0.9 and m.colors[0, 1] < 0.1


def test_save_refuses_non_manifold(tmp_path):
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], float)
    with pytest.raises(subdiv.SubdivError, match="non-manifold"):
        subdiv.save(tmp_path / "x.obj", v, [[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    assert not (tmp_path / "x.obj").exists()


def test_load_refuses_or_repairs_the_teapot():
    with pytest.raises(subdiv.SubdivError, match="teapot.bez.*non-manifold"):
        subdiv.load(os.path.join(MODELS, "teapot.bez"))


def test_gltf_text_is_read(tmp_path):
    import json

    pos = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32).tobytes()
    (tmp_path / "t.bin").write_bytes(pos)
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"uri": "t.bin", "byteLength": len(pos)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    (tmp_path / "t.gltf").write_text(json.dumps(doc))
    m = subdiv.load(tmp_path / "t.gltf")
    assert m.faces.shape == (1, 3)
    assert sorted(map(tuple, m.vertices)) == [(0, 0, 0), (0, 1, 0), (1, 0, 0)]
