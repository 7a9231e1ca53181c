//! Every mesh format against OBJ: written and read back the same (up to each
//! format's precision), subdivided the same whichever format the mesh came
//! in, the readers' special cases (PLY encodings and colours, STL welding and
//! sniffing, glTF node transforms and embedded buffers, COLLADA polylists)
//! and their refusals: errors name the file and the element, and header
//! counts the file cannot hold are refused before anything is allocated.

mod common;
use common::*;
use glam::{Vec2, Vec3};
use subdiv::mesh::Attributes;
use subdiv::{Error, Scheme, io};

/// Each point of `a` has one of `b` within `tol`, and both have as many.
fn same_points(a: &[Vec3], b: &[Vec3], tol: f32, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: vertex counts");
    let mut sorted: Vec<Vec3> = b.to_vec();
    sorted.sort_by(|p, q| p.x.total_cmp(&q.x));
    for p in a {
        let lo = sorted.partition_point(|q| q.x < p.x - tol);
        let near = sorted[lo..].iter().take_while(|q| q.x <= p.x + tol).any(|q| (*q - *p).abs().max_element() <= tol);
        assert!(near, "{what}: {p} has no counterpart within {tol}");
    }
}

const OUT: [&str; 6] = ["obj", "ct", "ply", "stl", "off", "glb"];

#[test]
fn every_format_round_trips_and_subdivides_like_obj() {
    let dir = scratch_dir("formats-rt");
    for name in BUNDLED {
        let mesh = bundled(name);
        let (fine, _) = subdiv::subdivide(&mesh, Scheme::Loop, 2, &Default::default()).unwrap();
        for ext in OUT {
            let path = dir.join(format!("{name}.{ext}"));
            io::save(&path, &mesh).unwrap();
            let back = subdiv::bundled::load(&path).unwrap_or_else(|e| panic!("{name}.{ext}: {e}"));
            let what = format!("{name} via .{ext}");
            assert_eq!(back.ct.num_triangles(), mesh.ct.num_triangles(), "{what}");
            assert_eq!(back.ct.num_border_edges(), mesh.ct.num_border_edges(), "{what}");
            // every format stores f32 or its shortest exact decimal form
            same_points(&back.positions, &mesh.positions, 0.0, &what);
            let (fine_back, _) = subdiv::subdivide(&back, Scheme::Loop, 2, &Default::default()).unwrap();
            same_points(&fine_back.positions, &fine.positions, 1e-5, &format!("{what}, subdivided"));
        }
    }
}

#[test]
fn attributes_survive_the_formats_that_keep_them() {
    let dir = scratch_dir("formats-attr");
    let (mesh, attrs) = load_with_attributes(&model_path("cube_uv.obj"));
    let uv = attrs.uv.clone().expect("cube_uv.obj has texture coordinates");
    let colors: Vec<Vec3> = mesh.positions.iter().map(|p| (*p * 0.5 + 0.25).clamp(Vec3::ZERO, Vec3::ONE)).collect();
    let attrs =
        Attributes { uv: Some(uv.clone()), colors: Some(colors.clone()), materials: None, options: Default::default() };
    for (ext, keeps_uv, tol) in
        [("obj", true, 1e-6), ("glb", true, 0.0), ("ply", false, 0.5 / 255.0), ("off", false, 0.0)]
    {
        let path = dir.join(format!("cube_uv.{ext}"));
        io::save_with(&path, &mesh, &attrs).unwrap();
        let (back, got) = with_attributes(&std::fs::read(&path).unwrap(), path.to_str().unwrap()).unwrap();
        assert_eq!(back.ct.num_triangles(), mesh.ct.num_triangles(), "{ext}");
        assert_eq!(back.positions.len(), mesh.positions.len(), "{ext}: welded back to the OBJ's vertices");
        // colour of each vertex, found by position
        let got_c = got.colors.as_ref().unwrap_or_else(|| panic!("{ext}: colours lost"));
        for (p, c) in back.positions.iter().zip(got_c) {
            let i = mesh.positions.iter().position(|q| q == p).unwrap();
            assert!((colors[i] - *c).abs().max_element() <= tol + 1e-6, "{ext}: colour {c} for {}", colors[i]);
        }
        if keeps_uv {
            let got_uv = got.uv.as_ref().unwrap_or_else(|| panic!("{ext}: texture coordinates lost"));
            // corners keep their order: triangle t's corner k is the same corner
            for (c, (&v, t)) in back.ct.v_table().iter().zip(got_uv).enumerate() {
                assert_eq!(back.positions[v as usize], mesh.positions[mesh.ct.v_table()[c] as usize]);
                assert!((*t - uv[c]).abs().max_element() < 1e-6, "{ext}: corner {c}");
            }
        }
    }
}

/// The tetrahedron as PLY text in `enc`, with uchar colours.
fn ply_tetra(enc: &str, big: bool) -> Vec<u8> {
    let m = bundled("tetrahedron.obj");
    let mut out = format!(
        "ply\nformat {enc} 1.0\ncomment made in a test\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face {}\nproperty list uchar int vertex_indices\nelement extra 1\nproperty double weight\nend_header\n",
        m.positions.len(),
        m.ct.num_triangles()
    )
    .into_bytes();
    let f = |x: f32| if big { x.to_be_bytes() } else { x.to_le_bytes() };
    let i = |x: u32| if big { x.to_be_bytes() } else { x.to_le_bytes() };
    for (k, p) in m.positions.iter().enumerate() {
        let rgb = [(k * 60) as u8, 255, 0];
        if enc == "ascii" {
            out.extend(format!("{} {} {} {} {} {}\n", p.x, p.y, p.z, rgb[0], rgb[1], rgb[2]).bytes());
        } else {
            p.to_array().iter().for_each(|&x| out.extend(f(x)));
            out.extend(rgb);
        }
    }
    for t in m.ct.v_table().chunks(3) {
        if enc == "ascii" {
            out.extend(format!("3 {} {} {}\n", t[0], t[1], t[2]).bytes());
        } else {
            out.push(3);
            t.iter().for_each(|&v| out.extend(i(v)));
        }
    }
    if enc == "ascii" {
        out.extend(b"0.5\n");
    } else {
        out.extend(if big { 0.5f64.to_be_bytes() } else { 0.5f64.to_le_bytes() });
    }
    out
}

#[test]
fn glb_texture_coordinates_use_the_gltf_convention() {
    // OBJ's v runs up the image, glTF's down: the .glb stores 1 - v
    let dir = scratch_dir("formats-glb-uv");
    let (mesh, attrs) = load_with_attributes(&model_path("cube_uv.obj"));
    let uv = attrs.uv.clone().unwrap();
    let path = dir.join("cube_uv.glb");
    io::save_with(&path, &mesh, &attrs).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json = std::str::from_utf8(&bytes[20..20 + json_len]).unwrap();
    let bin = &bytes[20 + json_len + 8..];
    // the TEXCOORD_0 accessor is the third (after POSITION and NORMAL), its view follows theirs
    assert!(json.contains("\"TEXCOORD_0\":2"), "{json}");
    let n = mesh.ct.v_table().len();
    let at = 2 * 12 * n;
    let f = |k: usize| f32::from_le_bytes(bin[at + 4 * k..at + 4 * k + 4].try_into().unwrap());
    for (c, t) in uv.iter().enumerate() {
        assert_eq!((f(2 * c), f(2 * c + 1)), (t.x, 1.0 - t.y), "corner {c}");
    }
}

#[test]
fn ply_reads_ascii_and_both_binary_encodings_with_colours() {
    let tetra = bundled("tetrahedron.obj");
    for (enc, big) in [("ascii", false), ("binary_little_endian", false), ("binary_big_endian", true)] {
        let bytes = ply_tetra(enc, big);
        let (m, a) = with_attributes(&bytes, "t.ply").unwrap_or_else(|e| panic!("{enc}: {e}"));
        assert_eq!(m.positions, tetra.positions, "{enc}");
        assert_eq!(m.ct.v_table(), tetra.ct.v_table(), "{enc}");
        let c = a.colors.unwrap();
        assert_eq!(c[1], Vec3::new(60.0 / 255.0, 1.0, 0.0), "{enc}");
        // truncated: the element and the file are named
        let e = mesh_of(&bytes[..bytes.len() - 12], "cut.ply").unwrap_err().to_string();
        assert!(e.contains("cut.ply") && (e.contains("face") || e.contains("extra")), "{enc}: {e}");
    }
}

#[test]
fn stl_is_welded_and_told_apart_by_content() {
    let dir = scratch_dir("formats-stl");
    let cube = bundled("cube.obj");
    let bin = dir.join("cube.stl");
    io::save(&bin, &cube).unwrap();
    let bytes = std::fs::read(&bin).unwrap();
    assert_eq!(bytes.len(), 84 + 50 * 12);
    // an ASCII version of the same soup
    let mut text = String::from("solid cube\n");
    for t in cube.ct.v_table().chunks(3) {
        text.push_str("  facet normal 0 0 0\n    outer loop\n");
        for &v in t {
            let p = cube.positions[v as usize];
            text.push_str(&format!("      vertex {} {} {}\n", p.x, p.y, p.z));
        }
        text.push_str("    endloop\n  endfacet\n");
    }
    text.push_str("endsolid cube\n");
    // a binary file whose header starts with "solid" is still binary
    let mut solid_bin = bytes.clone();
    solid_bin[..5].copy_from_slice(b"solid");
    for (what, data, name) in [
        ("binary", bytes.clone(), "c.stl"),
        ("ascii", text.into_bytes(), "c.stl"),
        ("binary saying solid", solid_bin, "c.stl"),
        ("binary without extension", bytes.clone(), "c"),
    ] {
        let m = mesh_of(&data, name).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_eq!(
            (m.positions.len(), m.ct.num_triangles(), m.ct.num_border_edges()),
            (8, 12, 0),
            "{what}: welded, closed"
        );
    }
    let e = mesh_of(&bytes[..84 + 50 * 5], "short.stl").unwrap_err().to_string();
    assert!(e.contains("short.stl") && e.contains("facets") && e.contains("12"), "{e}");
    let e = mesh_of(b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n", "a.stl").unwrap_err();
    assert!(e.to_string().contains("a.stl:5"), "{e}");
}

#[test]
fn off_reads_polygons_and_colours() {
    let text = "OFF\n# a unit square pyramid\n5 5 8\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n4 3 2 1 0\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";
    let m = mesh_of(text.as_bytes(), "p.off").unwrap();
    assert_eq!((m.positions.len(), m.ct.num_triangles(), m.ct.num_border_edges()), (5, 6, 0));
    let c = "COFF\n3 1 0\n0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n";
    let (_, a) = with_attributes(c.as_bytes(), "c.off").unwrap();
    assert_eq!(a.colors.unwrap(), vec![Vec3::X, Vec3::Y, Vec3::Z]);
    let e = mesh_of(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", "r.off").unwrap_err().to_string();
    assert!(e.contains("r.off:6") && e.contains("index 7"), "{e}");
}

fn b64(data: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in data.chunks(3) {
        let n =
            (u32::from(c[0]) << 16) | (u32::from(*c.get(1).unwrap_or(&0)) << 8) | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            s.push(if k <= c.len() { A[(n >> (18 - 6 * k) & 63) as usize] as char } else { '=' });
        }
    }
    s
}

/// A `.gltf` with the tetrahedron in a base64 buffer, drawn by two nodes: one
/// translated, one child mirrored (scale -1 in x) under a scaled parent.
fn gltf_text(count: usize) -> String {
    let m = bundled("tetrahedron.obj");
    let mut bin: Vec<u8> = m.positions.iter().flat_map(|p| p.to_array()).flat_map(f32::to_le_bytes).collect();
    let pos_len = bin.len();
    bin.extend(m.ct.v_table().iter().flat_map(|&i| (i as u16).to_le_bytes()));
    let (lo, hi) = m.bounds();
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,1]}}],
        "nodes":[{{"mesh":0,"translation":[10,0,0]}},{{"scale":[2,2,2],"children":[2]}},{{"mesh":0,"scale":[-1,1,1]}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
        "buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}],
        "bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{pos_len}}},{{"buffer":0,"byteOffset":{pos_len},"byteLength":{}}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":{count},"type":"VEC3","min":[{},{},{}],"max":[{},{},{}]}},
                     {{"bufferView":1,"componentType":5123,"count":12,"type":"SCALAR"}}]}}"#,
        bin.len(),
        b64(&bin),
        bin.len() - pos_len,
        lo.x,
        lo.y,
        lo.z,
        hi.x,
        hi.y,
        hi.z
    )
}

#[test]
fn gltf_takes_every_mesh_node_with_its_transform() {
    let tetra = bundled("tetrahedron.obj");
    let m = mesh_of(gltf_text(4).as_bytes(), "two.gltf").unwrap();
    assert_eq!((m.positions.len(), m.ct.num_triangles()), (8, 8), "two copies");
    let mut want: Vec<Vec3> = tetra.positions.iter().map(|p| *p + Vec3::new(10.0, 0.0, 0.0)).collect();
    want.extend(tetra.positions.iter().map(|p| *p * Vec3::new(-2.0, 2.0, 2.0)));
    same_points(&m.positions, &want, 1e-6, "node transforms");
    // the mirrored copy's winding is flipped back: it is closed and outward (positive volume)
    let vol: f32 =
        m.ct.v_table()
            .chunks(3)
            .map(|t| m.positions[t[0] as usize].dot(m.positions[t[1] as usize].cross(m.positions[t[2] as usize])) / 6.0)
            .sum();
    let tvol: f32 = tetra
        .ct
        .v_table()
        .chunks(3)
        .map(|t| {
            tetra.positions[t[0] as usize].dot(tetra.positions[t[1] as usize].cross(tetra.positions[t[2] as usize]))
                / 6.0
        })
        .sum();
    assert!((vol - 9.0 * tvol).abs() < 1e-3 * tvol.abs(), "volume {vol}, want 9 x {tvol}");
    // a material's base colour factor becomes the group's diffuse colour
    let red = gltf_text(4).replace("\"indices\":1}", "\"indices\":1,\"material\":0}").replace(
        "\"buffers\"",
        "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0,0,1]}}],\"buffers\"",
    );
    let (_, a) = with_attributes(red.as_bytes(), "red.gltf").unwrap();
    let g = a.materials.expect("material groups from the glTF materials");
    assert_eq!((g.face, g.list.len(), g.list[0].diffuse), (vec![0; 8], 1, Vec3::X));
    // what the fuzzer found panicking inside the gltf crate is refused, naming the element
    let missing = gltf_text(4).replace("\"POSITION\":0", "\"POSITION\":7");
    let e = mesh_of(missing.as_bytes(), "m.gltf").unwrap_err().to_string();
    assert!(e.contains("m.gltf") && e.contains("mesh 0 primitive 0") && e.contains("accessor 7"), "{e}");
    let bytes_not_floats = gltf_text(4).replacen("\"componentType\":5126", "\"componentType\":5121", 1);
    let e = mesh_of(bytes_not_floats.as_bytes(), "u8.gltf").unwrap_err().to_string();
    assert!(e.contains("u8.gltf") && e.contains("accessor 0") && e.contains("not allowed"), "{e}");
    let float_indices = gltf_text(4).replace("\"componentType\":5123", "\"componentType\":5126");
    let e = mesh_of(float_indices.as_bytes(), "fi.gltf").unwrap_err().to_string();
    assert!(e.contains("fi.gltf") && e.contains("accessor 1"), "{e}");
    // an accessor claiming more than its view holds is refused, naming it
    let e = mesh_of(gltf_text(1_000_000_000_000).as_bytes(), "big.gltf").unwrap_err().to_string();
    assert!(e.contains("big.gltf") && e.contains("accessor 0"), "{e}");
}

const DAE: &str = r##"<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <library_geometries>
    <geometry id="pyr" name="pyramid"><mesh>
      <source id="pyr-pos"><float_array id="pyr-pos-a" count="15">0 0 0 1 0 0 1 1 0 0 1 0 0.5 0.5 1</float_array>
        <technique_common><accessor source="#pyr-pos-a" count="5" stride="3"/></technique_common></source>
      <source id="pyr-uv"><float_array id="pyr-uv-a" count="4">0 0 1 1</float_array>
        <technique_common><accessor source="#pyr-uv-a" count="2" stride="2"/></technique_common></source>
      <vertices id="pyr-v"><input semantic="POSITION" source="#pyr-pos"/></vertices>
      <polylist count="1"><input semantic="VERTEX" source="#pyr-v" offset="0"/><input semantic="TEXCOORD" source="#pyr-uv" offset="1" set="0"/>
        <vcount>4</vcount><p>3 0 2 1 1 1 0 0</p></polylist>
      <triangles count="4"><input semantic="VERTEX" source="#pyr-v" offset="0"/><input semantic="TEXCOORD" source="#pyr-uv" offset="1" set="0"/>
        <p>0 0 1 0 4 1 1 0 2 0 4 1 2 0 3 0 4 1 3 0 0 0 4 1</p></triangles>
    </mesh></geometry>
    <geometry id="tri"><mesh>
      <source id="tri-pos"><float_array id="tri-pos-a" count="9">5 0 0 6 0 0 5 1 0</float_array>
        <technique_common><accessor source="#tri-pos-a" count="3" stride="3"/></technique_common></source>
      <vertices id="tri-v"><input semantic="POSITION" source="#tri-pos"/></vertices>
      <triangles count="1"><input semantic="VERTEX" source="#tri-v" offset="0"/><p>0 1 2</p></triangles>
    </mesh></geometry>
  </library_geometries>
</COLLADA>"##;

#[test]
fn collada_reads_triangles_and_polylists_of_every_geometry() {
    let m = mesh_of(DAE.as_bytes(), "pyr.dae").unwrap();
    assert_eq!((m.positions.len(), m.ct.num_triangles()), (8, 7), "pyramid (quad base fanned) + a triangle");
    assert_eq!(subdiv::mesh::topology(&m.ct).components, 2);
    // the second geometry has no texture coordinates: its corners get (0, 0)
    let (_, a) = with_attributes(DAE.as_bytes(), "pyr.dae").unwrap();
    assert_eq!(a.uv.as_ref().map(|u| (u.len(), u[18..] == [Vec2::ZERO; 3])), Some((21, true)));
    let one = DAE.split("<geometry id=\"tri\">").next().unwrap().to_string() + "</library_geometries></COLLADA>";
    let (p, a) = with_attributes(one.as_bytes(), "one.dae").unwrap();
    assert_eq!((p.ct.num_triangles(), p.ct.num_border_edges()), (6, 0));
    let uv = a.uv.unwrap();
    assert_eq!(uv.len(), 18);
    assert_eq!(&uv[..3], &[Vec2::ZERO, Vec2::ONE, Vec2::ONE], "the polylist's first fan triangle");
    let bad = DAE.replace("0 1 2</p>", "0 1 9</p>");
    let e = mesh_of(bad.as_bytes(), "bad.dae").unwrap_err().to_string();
    assert!(e.contains("bad.dae") && e.contains("9"), "{e}");
    let e = mesh_of(b"<COLLADA><library_geometries>", "x.dae").unwrap_err().to_string();
    assert!(e.contains("x.dae") && e.contains("XML"), "{e}");
}

#[test]
fn huge_header_counts_are_refused_before_allocating() {
    // l.ply: 16 bytes after the vertices, enough for one face record, whose
    // list count (2^32 - 1) is refused
    let cases: [(&str, Vec<u8>, &str); 5] = [
        ("h.ply", b"ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n".to_vec(), "vertex"),
        ("a.ply", b"ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n".to_vec(), "vertex"),
        ("l.ply", b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty uchar x\nproperty uchar y\nproperty uchar z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n\0\0\0\0\0\0\0\0\0\xff\xff\xff\xff\0\0\0\0\0\0\0\0\0\0\0\0".to_vec(), "face 0"),
        ("h.off", b"OFF\n1000000000000 1 0\n0 0 0\n".to_vec(), "vertices"),
        ("h.stl", { let mut b = vec![0u8; 84]; b[80..84].copy_from_slice(&u32::MAX.to_le_bytes()); b }, "facets"),
    ];
    for (name, bytes, element) in cases {
        let e = mesh_of(&bytes, name).unwrap_err();
        assert!(matches!(e, Error::Format { .. }), "{name}: {e:?}");
        let e = e.to_string();
        assert!(e.contains(name) && e.contains(element), "{name}: {e}");
    }
}

#[test]
fn unknown_output_extensions_list_every_writer() {
    let e = io::save(std::path::Path::new("x.gltf"), &bundled("cube.obj")).unwrap_err().to_string();
    for ext in io::write_extensions() {
        assert!(e.contains(&format!(".{ext}")), "{e}");
    }
    let keeps = |name: &str| io::keeps(std::path::Path::new(name));
    // glTF keeps the material groups (a stage's prims among them) as meshes, one a group
    assert!(keeps("a.glb").uv && keeps("a.glb").colors && keeps("a.glb").materials);
    // only USD keeps a refined level's holes
    assert!(keeps("a.usda").holes && !keeps("a.obj").holes && !keeps("a.glb").holes);
    assert_eq!(keeps("a.stl"), io::Keeps::default(), "STL keeps no attribute");
    assert!(keeps("a.ply").colors && !keeps("a.ply").uv, "PLY keeps colours, not texture coordinates");
    assert!(keeps("a.obj").uv && keeps("a.obj").colors && keeps("a.obj").materials);
}
