//! Parsers: agreement with tobj, every error names file and line, and no
//! input makes them panic.

mod common;
#[cfg(unix)]
mod hostile_inputs;
use common::*;
use subdiv::io::Topology;
use subdiv::{Error, MeshError, Scheme};

#[test]
fn our_obj_parser_agrees_with_tobj() {
    for name in BUNDLED {
        let path = model_path(name);
        let m = subdiv::bundled::load(&path).unwrap();
        let (tp, tt) = load_tobj(&path);
        let key = |p: glam::Vec3| p.to_array().map(f32::to_bits);
        let mut ours: Vec<_> =
            m.ct.v_table()
                .chunks_exact(3)
                .map(|t| t.iter().map(|&i| key(m.positions[i as usize])).collect::<Vec<_>>())
                .collect();
        let mut theirs: Vec<_> =
            tt.chunks_exact(3).map(|t| t.iter().map(|&i| key(tp[i as usize])).collect::<Vec<_>>()).collect();
        ours.sort();
        theirs.sort();
        assert_eq!(ours, theirs, "{name}");
    }
}

/// Every group's positions and triangles read by tobj (renumbered per
/// group), concatenated: an independent reading of an OBJ.
fn load_tobj(path: &std::path::Path) -> (Vec<glam::Vec3>, Vec<u32>) {
    let opts = tobj::LoadOptions { triangulate: true, single_index: false, ..Default::default() };
    let (models, _) = tobj::load_obj(path, &opts).unwrap();
    let (mut pos, mut tris) = (Vec::new(), Vec::new());
    for m in models {
        let base = pos.len() as u32;
        pos.extend(m.mesh.positions.chunks_exact(3).map(|c| glam::Vec3::new(c[0], c[1], c[2])));
        tris.extend(m.mesh.indices.iter().map(|&i| i + base));
    }
    (pos, tris)
}

fn err_of(text: &str) -> Error {
    mesh_of(text.as_bytes(), "test.obj").map(|_| ()).unwrap_err()
}

#[test]
fn obj_errors_name_the_line() {
    let e = err_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    assert!(matches!(e, Error::Mesh { line: Some(4), source: MeshError::IndexOutOfRange { index: 4, .. }, .. }), "{e}");
    assert!(e.to_string().starts_with("test.obj:4:"), "{e}");
    let e = err_of("v 0 0 0\nv 1 nan 0\n");
    assert!(matches!(e, Error::Mesh { line: Some(2), source: MeshError::NonFinite { .. }, .. }), "{e}");
    let e = err_of("v 0 0 0\nv 1 zero 0\n");
    assert!(matches!(e, Error::Parse { line: 2, .. }), "{e}");
    let e = err_of("");
    assert!(matches!(e, Error::Mesh { source: MeshError::Empty, .. }), "{e}");
    let e = err_of("\u{1}\u{2}garbage\u{7f}\n");
    assert!(matches!(e, Error::Parse { line: 1, .. }), "{e}");
    let e = mesh_of(&[0xff, 0xfe, 0x00, 0x41], "bin.obj").map(|_| ()).unwrap_err();
    assert!(matches!(e, Error::Parse { line: 1, .. }), "{e}");
    // fin: 3 faces on edge (1,2)
    let fin = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
    let e = err_of(fin);
    assert!(matches!(e, Error::Mesh { source: MeshError::NonManifoldEdge { faces: 3, .. }, .. }), "{e}");
    // bowtie at vertex 3 (1-based, as the file numbers it), named with the line of its v record
    let bow = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 2 1 0\nv 2 2 0\nf 1 2 3\nf 3 4 5\n";
    let e = err_of(bow);
    assert!(
        matches!(e, Error::Mesh { line: Some(3), source: MeshError::NonManifoldVertex { vertex: 3, fans: 2 }, .. }),
        "{e}"
    );
    // negative (relative) indices and polygons are accepted
    let l = read_bytes(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n", "q.obj").unwrap();
    assert_eq!((l.mesh.ct.num_triangles(), l.notes.fanned, l.notes.face_sizes[4]), (2, 1, 1));
}

#[test]
fn ct_errors_and_header_guard() {
    let parse = |text: &str, name: &str| mesh_of(text.as_bytes(), name);
    let e = parse("1000000000000\n0 0 0\n", "big.ct").unwrap_err();
    assert!(matches!(e, Error::Parse { line: 1, .. }), "{e}");
    let e = parse("3\n0 0 0\n1 0 0\n0 1 0\n1\n0 1 7\n", "bad.ct").unwrap_err();
    assert!(matches!(e, Error::Mesh { line: Some(6), source: MeshError::IndexOutOfRange { .. }, .. }), "{e}");
    let e = parse("3\n0 0 0\n1 0 0\n0 1 0\n1\n0 1 2\n0 -1 -1\n", "o.ct").unwrap_err();
    assert!(matches!(e, Error::Mesh { source: MeshError::BadOppositeTable { .. }, .. }), "{e}");
    let m = parse("3\n0 0 0\n1 0 0\n0 1 0\n1\n0 1 2\n-1 -1 -1\n", "ok.ct").unwrap();
    assert_eq!(m.ct.num_border_edges(), 3);
}

#[test]
fn ct_stored_o_must_be_the_one_the_faces_define() {
    let parse = |text: &str, name: &str| mesh_of(text.as_bytes(), name);
    // the bundled tetrahedron: lines 11-14 are its O rows; edge (1, 2) is
    // faced by corners 0 and 10
    let head = "4\n1 1 1\n1 -1 -1\n-1 1 -1\n-1 -1 1\n4\n0 1 2\n0 3 1\n0 2 3\n1 3 2\n";
    let rows = |r0: &str, r3: &str| format!("{head}{r0}\n11 2 7\n9 5 1\n{r3}\n");
    let m = parse(&rows("10 8 4", "6 0 3"), "good.ct").unwrap();
    assert_eq!((m.ct.o_entry(0), m.ct.o_entry(10), m.ct.num_border_edges()), (10, 0, 0));
    // an interior edge marked as border on both sides: a valid involution
    // with one fan per vertex (a slit between two interior vertices), but
    // not the table of these faces; refused at the first bad row
    let e = parse(&rows("-1 8 4", "6 -1 3"), "slit.ct").unwrap_err();
    assert!(
        matches!(e, Error::Mesh { line: Some(11), source: MeshError::BadOppositeTable { corner: 0, .. }, .. }),
        "{e}"
    );
    assert!(e.to_string().starts_with("slit.ct:11:"), "{e}");
    // the first row right, the last one not: line 14, corner 10
    let e = parse(&rows("10 8 4", "6 -1 3"), "half.ct").unwrap_err();
    assert!(
        matches!(e, Error::Mesh { line: Some(14), source: MeshError::BadOppositeTable { corner: 10, .. }, .. }),
        "{e}"
    );
    // a square whose diagonal is marked as border on both sides (its ends
    // are boundary vertices, so each would get two fans): the O row's line too
    let sq = "4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2\n0 1 2\n0 2 3\n-1 -1 -1\n-1 -1 -1\n";
    let e = parse(sq, "square.ct").unwrap_err();
    assert!(
        matches!(e, Error::Mesh { line: Some(9), source: MeshError::BadOppositeTable { corner: 1, .. }, .. }),
        "{e}"
    );
    // a corner paired with itself: line 7 of a one-triangle file
    let e = parse("3\n0 0 0\n1 0 0\n0 1 0\n1\n0 1 2\n0 -1 -1\n", "self.ct").unwrap_err();
    assert!(
        matches!(e, Error::Mesh { line: Some(7), source: MeshError::BadOppositeTable { corner: 0, .. }, .. }),
        "{e}"
    );
}

/// Random and mutated inputs never panic (the error path is what is tested);
/// whatever parses also repairs and subdivides. 3000 rounds here; the longer
/// run is the same test with `SUBDIV_FUZZ_ROUNDS=1000000 cargo test --release
/// --test io parsers_never_panic`.
#[test]
fn parsers_never_panic_on_mutated_input() {
    let rounds: usize = std::env::var("SUBDIV_FUZZ_ROUNDS").ok().and_then(|v| v.parse().ok()).unwrap_or(3000);
    let mut seeds: Vec<Vec<u8>> = BUNDLED
        .iter()
        .flat_map(|n| {
            let p = model_path(n);
            [std::fs::read(&p).unwrap(), std::fs::read(p.with_extension("ct")).unwrap()]
        })
        .collect();
    let paths_seed =
        std::fs::read(std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("paths/tetrahedron.paths")).unwrap();
    seeds.push(paths_seed);
    seeds.extend(format_seeds());
    seeds.extend(hostile_seeds());
    // the hostile files of tests/hostile.rs: their mutations probe the
    // guards around each class (the budget below keeps amplification small)
    #[cfg(unix)]
    seeds.extend(hostile_inputs::hostile_seeds().into_iter().map(|(_, b)| b));
    let mut rng = Rng(12345);
    let mut rnd = |n: usize| ((rng.next_f32() + 1.0) * 0.5 * n as f32) as usize % n.max(1);
    let tokens: [&[u8]; 10] = [b"-1", b"0", b"nan", b"1e39", b"\n", b" ", b"f", b"v", b"99999999999", b"/"];
    for round in 0..rounds {
        let mut data = seeds[round % seeds.len()].clone();
        for _ in 0..1 + rnd(6) {
            let at = rnd(data.len());
            match rnd(4) {
                0 => {
                    data.truncate(at);
                }
                1 => {
                    let t = tokens[rnd(tokens.len())];
                    data.splice(at..at, t.iter().copied());
                }
                2 => {
                    if at < data.len() {
                        data[at] = rnd(256) as u8;
                    }
                }
                _ => {
                    let end = (at + rnd(40)).min(data.len());
                    data.drain(at..end);
                }
            }
        }
        if let Ok(m) = fuzz_read(&data, "fuzz.obj", Topology::Refuse).map(|l| l.mesh) {
            let _ = subdiv::subdivide(&m, Scheme::ALL[round % Scheme::ALL.len()], 1, &Default::default());
        }
        if let Ok(m) = fuzz_read(&data, "fuzz.obj", Topology::Repair).map(|l| l.mesh) {
            let (fine, _) =
                subdiv::subdivide(&m, Scheme::ALL[round % Scheme::ALL.len()], 1, &Default::default()).unwrap();
            assert!(subdiv::mesh::check_invariants(&fine.ct).is_ok());
        }
        if let Ok(s) = std::str::from_utf8(&data) {
            let _ = fuzz_read(s.as_bytes(), "fuzz.ct", Topology::Refuse);
            let _ = subdiv::anim::Paths::parse(s, "fuzz.paths");
        }
        // every other reader, by extension and by content sniffing
        for name in ["fuzz.ply", "fuzz.stl", "fuzz.off", "fuzz.glb", "fuzz.gltf", "fuzz.dae", "fuzz"] {
            if let Ok(m) = fuzz_read(&data, name, Topology::Refuse).map(|l| l.mesh) {
                assert!(subdiv::mesh::check_invariants(&m.ct).is_ok(), "{name}");
            }
            if let Ok(m) = fuzz_read(&data, name, Topology::Repair).map(|l| l.mesh) {
                let (fine, _) =
                    subdiv::subdivide(&m, Scheme::ALL[round % Scheme::ALL.len()], 1, &Default::default()).unwrap();
                assert!(subdiv::mesh::check_invariants(&fine.ct).is_ok(), "{name}");
            }
        }
    }
}

/// A fuzz round's read: the pipeline with a budget of a 256 MiB machine
/// (so that an amplifying mutant is refused quickly) and textures decoded.
fn fuzz_read(bytes: &[u8], name: &str, topology: Topology) -> subdiv::Result<subdiv::io::Loaded> {
    let limits = subdiv::io::Limits::for_memory(256 << 20);
    let opts = subdiv::io::ReadOptions { limits, topology, attributes: true, textures: true, time: None };
    subdiv::io::read(subdiv::io::Source::Bytes { bytes, name, folder: None }, &opts)
}

/// Seeds in every mesh format: the bundled models written by each writer,
/// an ASCII PLY, an ASCII STL, a `.gltf` with an embedded buffer and a
/// COLLADA file.
fn format_seeds() -> Vec<Vec<u8>> {
    let dir = scratch_dir("io-fuzz-seeds");
    let mut seeds = Vec::new();
    for name in ["tetrahedron.obj", "cube_uv.obj"] {
        let (mesh, mut attrs) = load_with_attributes(&model_path(name));
        attrs.colors = Some(mesh.positions.iter().map(|p| p.abs().min(glam::Vec3::ONE)).collect());
        for ext in ["ply", "stl", "off", "glb"] {
            let path = dir.join(format!("{name}.{ext}"));
            subdiv::io::save_with(&path, &mesh, &attrs).unwrap();
            seeds.push(std::fs::read(&path).unwrap());
        }
    }
    seeds.push(
        b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n1 1 1 255 0 0\n1 -1 -1 0 255 0\n-1 1 -1 0 0 255\n-1 -1 1 9 9 9\n3 0 1 2\n3 0 2 3\n3 0 3 1\n3 1 3 2\n"
            .to_vec(),
    );
    seeds.push(b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n".to_vec());
    // one triangle: three positions and u16 indices 0 1 2, base64
    seeds.push(br#"{"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[1,2,3]}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],"buffers":[{"byteLength":42,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIA"}],"bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]}"#.to_vec());
    seeds.push(br##"<?xml version="1.0"?><COLLADA><library_geometries><geometry id="g"><mesh><source id="p"><float_array id="pa" count="15">0 0 0 1 0 0 1 1 0 0 1 0 2 0.5 0</float_array><technique_common><accessor source="#pa" count="5" stride="3"/></technique_common></source><vertices id="v"><input semantic="POSITION" source="#p"/></vertices><polylist count="1"><input semantic="VERTEX" source="#v" offset="0"/><vcount>4</vcount><p>0 1 2 3</p></polylist><triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>1 4 2</p></triangles></mesh></geometry></library_geometries></COLLADA>"##.to_vec());
    // the hand-written seeds are valid files: a mutation of a file that
    // does not parse would probe only its first error
    let hand = &seeds[seeds.len() - 4..];
    for (s, (name, triangles)) in hand.iter().zip([("seed.ply", 4), ("seed.stl", 2), ("seed.gltf", 1), ("seed.dae", 3)])
    {
        let m = mesh_of(s, name).unwrap_or_else(|e| panic!("the {name} seed does not parse: {e}"));
        assert_eq!(m.ct.num_triangles(), triangles, "{name}");
    }
    seeds
}

#[test]
fn repairing_loaders_repair_topology_but_keep_data_errors() {
    let dir = scratch_dir("io-repair");
    // a fin in both formats: .ct ids are 0-based, OBJ ids 1-based
    let ct = dir.join("fin.ct");
    std::fs::write(&ct, "5\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3\n0 1 2\n1 0 3\n0 1 4\n").unwrap();
    let obj_path = dir.join("fin.obj");
    std::fs::write(&obj_path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n").unwrap();
    for (path, base, edge) in [(&ct, 0, "(0-1)"), (&obj_path, 1, "(1-2)")] {
        assert!(matches!(
            subdiv::bundled::load(path).unwrap_err(),
            Error::Mesh { source: MeshError::NonManifoldEdge { faces: 3, .. }, .. }
        ));
        let (m, rep) = load_repaired(path).unwrap();
        assert_eq!((m.ct.num_triangles(), m.positions.len()), (3, 9));
        assert_eq!(rep.id_base, base);
        assert!(rep.to_string().contains(edge), "{rep}");
        let (_, all) = analyze(path).unwrap();
        assert_eq!(all.non_manifold_edges.examples, vec![[0, 1]]);
    }
    // data errors are not repaired: they keep the file and line
    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n").unwrap();
    assert!(matches!(
        load_repaired(&bad).unwrap_err(),
        Error::Mesh { line: Some(4), source: MeshError::IndexOutOfRange { .. }, .. }
    ));
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\n").unwrap();
    let e = load_repaired(&bad).unwrap_err();
    assert!(matches!(e, Error::Mesh { source: MeshError::Empty, .. }), "only degenerate faces: {e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[cfg(target_os = "linux")]
#[test]
fn saving_into_a_device_writes_into_it_and_leaves_it_a_device() {
    use std::os::unix::fs::FileTypeExt;
    // a .ply name for the format, pointing at /dev/null
    let link = std::env::temp_dir().join(format!("subdiv-null-{}.ply", std::process::id()));
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink("/dev/null", &link).unwrap();
    let m = subdiv::mesh::icosphere(1);
    subdiv::io::save(&link, &m).unwrap();
    let meta = std::fs::symlink_metadata(&link).unwrap();
    assert!(meta.file_type().is_symlink(), "the link was replaced by a file");
    assert!(std::fs::metadata("/dev/null").unwrap().file_type().is_char_device());
    std::fs::remove_file(&link).unwrap();
}

/// A COLLADA triangle with `inputs` (the `<input>` elements of its
/// `<triangles>`) and index text `p`.
fn dae_with(inputs: &str, p: &str) -> Vec<u8> {
    format!(
        r##"<?xml version="1.0"?><COLLADA><library_geometries><geometry id="g"><mesh><source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array><technique_common><accessor source="#pa" count="3" stride="3"/></technique_common></source><source id="t"><float_array id="ta" count="2">0 0</float_array><technique_common><accessor source="#ta" count="1" stride="18446744073709551615"/></technique_common></source><vertices id="v"><input semantic="POSITION" source="#p"/></vertices><triangles count="1">{inputs}<p>{p}</p></triangles></mesh></geometry></library_geometries></COLLADA>"##
    )
    .into_bytes()
}

/// The hostile files of the regression tests below, as fuzz seeds too: their
/// mutations probe the guards around the overflow.
fn hostile_seeds() -> Vec<Vec<u8>> {
    let vertex = r##"<input semantic="VERTEX" source="#v" offset="0"/>"##;
    vec![
        PLY_TWO_VERTEX_ELEMENTS.to_vec(),
        ply_claiming_faces(2),
        b"OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n".to_vec(),
        dae_with(r##"<input semantic="VERTEX" source="#v" offset="18446744073709551615"/>"##, "0 1 2"),
        dae_with(&format!(r##"{vertex}<input semantic="TEXCOORD" source="#t" offset="1"/>"##), "0 0 1 2 2 3"),
    ]
}

#[test]
fn hostile_collada_offsets_and_strides_are_refused_naming_the_element() {
    let refused = |bytes: Vec<u8>, want: &str| {
        let e = mesh_of(&bytes, "h.dae").map(|_| ()).unwrap_err();
        let s = e.to_string();
        assert!(matches!(e, Error::Format { .. }), "{s}");
        assert!(s.starts_with("h.dae: geometry 'g' triangles 0") && s.contains(want), "want '{want}': {s}");
    };
    let vertex = r##"<input semantic="VERTEX" source="#v" offset="0"/>"##;
    // the triangle itself reads
    assert_eq!(mesh_of(&dae_with(vertex, "0 1 2"), "ok.dae").unwrap().ct.num_triangles(), 1);
    // an offset of u64::MAX: the corner size (offset + 1) overflows
    let max = r##"<input semantic="VERTEX" source="#v" offset="18446744073709551615"/>"##;
    refused(dae_with(max, "0 1 2"), "offset 18446744073709551615 is too large");
    let two = format!(r##"{vertex}<input semantic="NORMAL" source="#v" offset="18446744073709551615"/>"##);
    refused(dae_with(&two, "0 1 2"), "too large");
    // an offset that is no number is refused, not read as 0
    let junk = r##"<input semantic="VERTEX" source="#v" offset="-1"/>"##;
    refused(dae_with(junk, "0 1 2"), "input 0 (VERTEX): offset '-1' is not an index");
    // no inputs at all (a stride of 0)
    refused(dae_with("", "0 1 2"), "no <input>");
    // a texture source whose accessor stride times the index overflows
    let tex = format!(r##"{vertex}<input semantic="TEXCOORD" source="#t" offset="1"/>"##);
    refused(dae_with(&tex, "0 0 1 2 2 3"), "texture coordinate 2 out of range");
}

/// Three vertices, then a second vertex element with texture coordinates:
/// the uv array would be sized from the second and indexed by the first's ids.
const PLY_TWO_VERTEX_ELEMENTS: &[u8] = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n5 5 5 0 0\n3 0 1 2\n";

/// A binary PLY with 3 vertices and one face (13 bytes) whose header claims `faces`.
fn ply_claiming_faces(faces: u64) -> Vec<u8> {
    let mut b = format!("ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face {faces}\nproperty list uchar int vertex_indices\nend_header\n").into_bytes();
    for p in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        b.extend(p.iter().flat_map(|x| x.to_le_bytes()));
    }
    b.push(3);
    b.extend([0u32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    b
}

#[test]
fn hostile_ply_headers_are_refused_before_reading() {
    let err = |bytes: &[u8]| mesh_of(bytes, "h.ply").map(|_| ()).unwrap_err().to_string();
    // a second vertex (or face) element: refused at its header line
    let e = err(PLY_TWO_VERTEX_ELEMENTS);
    assert!(e.starts_with("h.ply: header line 7:") && e.contains("second 'element vertex'"), "{e}");
    let two_faces = String::from_utf8(PLY_TWO_VERTEX_ELEMENTS.to_vec())
        .unwrap()
        .replace("element vertex 1\nproperty float x\nproperty float y\nproperty float z\nproperty float u\nproperty float v\n", "")
        .replace("end_header", "element face 0\nproperty list uchar int vertex_indices\nend_header");
    let e = err(two_faces.as_bytes());
    assert!(e.starts_with("h.ply: header line 9:") && e.contains("second 'element face'"), "{e}");
    // the file itself, with one face, reads
    assert_eq!(mesh_of(&ply_claiming_faces(1), "ok.ply").unwrap().ct.num_triangles(), 1);
    // a face takes at least 1 count byte and 3 indices of 4 bytes: 13 bytes
    // left hold one face, not two (nor 2^31), refused before any is read
    for claim in [2, 1 << 31] {
        let e = err(&ply_claiming_faces(claim));
        assert!(e.starts_with("h.ply: face:") && e.contains(&format!("claims {claim} elements")), "{e}");
        assert!(e.contains("only 13 bytes follow (at least 13 each needed)"), "{e}");
    }
    // ASCII: "3 0 1 2" is the fewest bytes (7, with no newline after the last face)
    let ascii = |faces: &str, body: &str| {
        format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face {faces}\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n{body}"
        )
    };
    let ok = mesh_of(ascii("1", "3 0 1 2").as_bytes(), "a.ply").unwrap();
    assert_eq!(ok.ct.num_triangles(), 1);
    let e = err(ascii("2", "3 0 1 2\n").as_bytes());
    assert!(e.contains("claims 2 elements"), "{e}");
}

#[test]
fn hostile_off_counts_are_refused_together() {
    // 5 vertices (30 bytes or more) and 3 faces (24 or more) each fit in the
    // 36 bytes, but not both
    let text = "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    assert_eq!(text.len(), 36);
    let e = mesh_of(text.as_bytes(), "h.off").map(|_| ()).unwrap_err();
    assert!(matches!(e, Error::Parse { line: 2, .. }), "{e}");
    let e = e.to_string();
    assert!(e.starts_with("h.off:2: the header claims 5 vertices and 3 faces, but the file has only 36 bytes"), "{e}");
    // the right counts read
    let ok = text.replace("5 3 0", "3 1 0");
    assert_eq!(mesh_of(ok.as_bytes(), "ok.off").unwrap().ct.num_triangles(), 1);
}
