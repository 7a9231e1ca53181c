//! USD stages in and out: the stage of tests/fixtures/usd (authored by
//! Pixar's USD, scripts/usd-fixtures.py) read as .usda, .usdc and .usdz,
//! each subdivided with the scheme and options its attributes state and
//! compared with OpenSubdiv's refinement of the same cage; written back
//! and read again; hostile stages refused in one line naming the file.
#![cfg(feature = "cli")]

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use subdiv::io::{ReadOptions, Source};
use subdiv::mesh::BoundaryInterpolation;
use subdiv::mesh::FileScheme;
use subdiv::mesh::UvInterpolation;

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/usd").join(name)
}

/// Runs `subdiv ARGS`, returning (success, stderr).
fn run(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_subdiv")).args(args).output().unwrap();
    (out.status.success(), String::from_utf8_lossy(&out.stderr).into_owned())
}

/// Runs `subdiv subdivide IN OUT ARGS` and returns OUT's path.
fn subdivide(input: &Path, out: &str, args: &[&str]) -> PathBuf {
    let path = common::scratch_dir("usd").join(out);
    let (ok, err) = run(&[&["subdivide", input.to_str().unwrap(), path.to_str().unwrap()][..], args].concat());
    assert!(ok, "{args:?}: {err}");
    path
}

use common::obj_corners as corners;

/// The worst distance from a corner of `a` to the nearest corner of `b`
/// (position and texture coordinate together).
fn worst(a: &[([f64; 3], [f64; 2])], b: &[([f64; 3], [f64; 2])]) -> f64 {
    let d = |(p, t): &([f64; 3], [f64; 2]), (q, u): &([f64; 3], [f64; 2])| {
        let dp: f64 = p.iter().zip(q).map(|(x, y)| (x - y) * (x - y)).sum();
        let dt: f64 = t.iter().zip(u).map(|(x, y)| (x - y) * (x - y)).sum();
        (dp + dt).sqrt()
    };
    a.iter().map(|x| b.iter().map(|y| d(x, y)).fold(f64::INFINITY, f64::min)).fold(0.0, f64::max)
}

#[test]
fn every_form_of_the_stage_reads_its_prims_attributes_and_options() {
    for name in ["stage.usda", "stage.usdc", "stage.usdz"] {
        let r = subdiv::io::read_raw(Source::File(&fixture(name)), &ReadOptions::default()).unwrap();
        let raw = &r.raw;
        assert_eq!(r.format.name, "USD", "{name}");
        // the grid's 20 points and the box's 8; 12 quads and 5
        assert_eq!((raw.positions.len(), raw.num_faces()), (28, 17), "{name}");
        let names: Vec<&str> = raw.material_list.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["/World/Body", "/World/Group/Lid"], "{name}");
        assert_eq!(raw.materials.as_ref().unwrap().iter().filter(|&&m| m == 1).count(), 5, "{name}");
        // a chain of two edges and one more; the corner; the hole
        assert_eq!(raw.tags.creases.len(), 3, "{name}");
        assert_eq!(raw.tags.corners.len(), 1, "{name}");
        assert_eq!(raw.holes.iter().map(|h| h.0).collect::<Vec<_>>(), [10], "{name}");
        // USD's defaults where nothing is authored: not OpenSubdiv's
        assert_eq!(raw.options.boundary, Some(BoundaryInterpolation::EdgeAndCorner), "{name}");
        assert_eq!(raw.options.fvar, Some(UvInterpolation::CornersPlus1), "{name}");
        assert_eq!(raw.options.scheme, Some(FileScheme::CatmullClark), "{name}");
        assert_eq!(raw.uv.as_ref().map(Vec::len), Some(raw.corners.len()), "{name}");
        let colors = raw.colors.as_ref().unwrap();
        // the box's one constant colour on each of its points
        assert!(colors[20..].iter().all(|c| (c.x - 1.0).abs() < 1e-6 && (c.y - 0.2).abs() < 1e-6), "{name}");
    }
}

#[test]
fn the_stage_subdivides_as_opensubdiv_refines_its_cage() {
    let osd = corners(&std::fs::read_to_string(fixture("stage.L2.osd.obj")).unwrap());
    for name in ["stage.usda", "stage.usdc", "stage.usdz"] {
        // no --scheme: the stage's catmullClark and its options decide
        let out = subdivide(&fixture(name), &format!("{name}.L2.obj"), &["-n", "2"]);
        let ours = corners(&std::fs::read_to_string(out).unwrap());
        assert_eq!(ours.len(), osd.len(), "{name}: corners");
        let (a, b) = (worst(&ours, &osd), worst(&osd, &ours));
        assert!(a < 1e-4 && b < 1e-4, "{name}: {a} / {b} from OpenSubdiv's (positions and texture coordinates)");
    }
    // the options matter: OpenSubdiv's defaults (edge only) give another surface
    let other = subdivide(&fixture("stage.usda"), "edge.L2.obj", &["-n", "2", "--boundary", "edge"]);
    let other = corners(&std::fs::read_to_string(other).unwrap());
    assert!(worst(&other, &osd) > 1e-3, "interpolateBoundary changed nothing");
}

/// The creases of `raw` as sorted (low id, high id, sharpness).
fn creases(raw: &subdiv::io::RawMesh) -> Vec<(u32, u32, f32)> {
    let mut c: Vec<_> = raw.tags.creases.iter().map(|c| (c.v0.min(c.v1), c.v0.max(c.v1), c.sharpness)).collect();
    c.sort_by(|a, b| a.partial_cmp(b).unwrap());
    c
}

/// The raw mesh of the USD file at `path`.
fn raw(path: &Path) -> subdiv::io::RawMesh {
    subdiv::io::read_raw(Source::File(path), &ReadOptions::default()).unwrap().raw
}

#[test]
fn a_level_0_round_trip_keeps_the_prims_and_every_attribute() {
    let cage = raw(&fixture("stage.usda"));
    for ext in ["usda", "usdc", "usdz"] {
        let out = subdivide(&fixture("stage.usdc"), &format!("n0.{ext}"), &["-n", "0"]);
        let back = raw(&out);
        assert_eq!(back.positions.len(), cage.positions.len(), "{ext}");
        for (p, q) in back.positions.iter().zip(&cage.positions) {
            assert!((*p - *q).length() < 1e-5, "{ext}: {p} / {q}");
        }
        assert_eq!(back.face_starts, cage.face_starts, "{ext}");
        assert_eq!(back.corners, cage.corners, "{ext}");
        assert_eq!(creases(&back), creases(&cage), "{ext}");
        // the cage's one corner (vertex 0, 3) is a vertex of one face: under
        // edgeAndCorner it is infinitely sharp whatever its own value, so USD's
        // implied corner stands for it and nothing is written
        assert_eq!(cage.tags.corners.len(), 1, "{ext}");
        assert!(back.tags.corners.is_empty(), "{ext}: {:?}", back.tags.corners);
        assert_eq!(back.holes, cage.holes, "{ext}");
        assert_eq!(back.options, cage.options, "{ext}");
        assert_eq!(back.uv, cage.uv, "{ext}");
        assert_eq!(back.colors, cage.colors, "{ext}");
        let names = |r: &subdiv::io::RawMesh| r.material_list.iter().map(|m| m.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(&back), names(&cage), "{ext}");
    }
}

#[test]
fn a_refined_stage_keeps_its_prims_scheme_and_decayed_creases() {
    let out = subdivide(&fixture("stage.usda"), "L1.usda", &["-n", "1"]);
    let back = raw(&out);
    assert_eq!(back.num_faces(), 4 * 17, "every quad of level 1");
    let names: Vec<&str> = back.material_list.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["/World/Body", "/World/Group/Lid"]);
    assert_eq!(back.options.scheme, Some(FileScheme::CatmullClark));
    // the chain's halves at 2 - 1, the infinite crease's halves still infinite
    let mut s: Vec<f32> = back.tags.creases.iter().map(|c| c.sharpness).collect();
    s.sort_by(f32::total_cmp);
    assert_eq!(s, [1.0, 1.0, 1.0, 1.0, 10.0, 10.0]);
    // the hole's four children
    assert_eq!(back.holes.len(), 4);
    // an explicit --scheme, even the default's name, overrides the stage's
    let looped = subdivide(&fixture("stage.usda"), "loop.L1.obj", &["-n", "1", "-s", "loop"]);
    let text = std::fs::read_to_string(looped).unwrap();
    assert!(text.lines().filter(|l| l.starts_with("f ")).all(|l| l.split_whitespace().count() == 4), "triangles");
}

/// `subdiv info FILE ARGS`'s error line.
fn refused(path: &Path, args: &[&str]) -> String {
    let (ok, err) = run(&[&["info", path.to_str().unwrap()][..], args].concat());
    assert!(!ok, "{} was read", path.display());
    assert_eq!(err.trim_end().lines().count(), 1, "not one line: {err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// A stage of one triangle under `sub`, in `dir` as `name`, with `extra`
/// metadata lines (sublayers).
fn stage(dir: &Path, name: &str, header: &str) -> PathBuf {
    let text = format!(
        "#usda 1.0\n(\n{header}\n)\n\ndef Mesh \"T\"\n{{\n    point3f[] points = [(0,0,0), (1,0,0), (0,1,0)]\n    int[] faceVertexCounts = [3]\n    int[] faceVertexIndices = [0, 1, 2]\n}}\n"
    );
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn hostile_stages_are_refused_in_one_line_naming_the_file() {
    let root = common::scratch_dir("usd_hostile");
    let dir = root.join("stage");
    std::fs::create_dir_all(&dir).unwrap();
    stage(&root, "outside.usda", "");
    // a sublayer and a reference outside the folder
    let out = stage(&dir, "out.usda", "    subLayers = [@../outside.usda@]");
    let e = refused(&out, &[]);
    assert!(e.contains("out.usda") && e.contains("outside.usda") && e.contains("out of the stage's folder"), "{e}");
    let reference = dir.join("ref.usda");
    std::fs::write(&reference, "#usda 1.0\ndef \"R\" (references = @/etc/passwd@) {}\n").unwrap();
    let e = refused(&reference, &[]);
    assert!(e.contains("ref.usda") && e.contains("passwd"), "{e}");
    // a cycle of sublayers
    stage(&dir, "a.usda", "    subLayers = [@./b.usda@]");
    stage(&dir, "b.usda", "    subLayers = [@./a.usda@]");
    let e = refused(&dir.join("a.usda"), &[]);
    assert!(e.contains("a.usda"), "{e}");
    // a truncated crate file and garbage bytes
    let bytes = std::fs::read(fixture("stage.usdc")).unwrap();
    for (name, b) in [("cut.usdc", bytes[..bytes.len() / 2].to_vec()), ("garbage.usdc", vec![0x5a; 4000])] {
        let p = dir.join(name);
        std::fs::write(&p, b).unwrap();
        let e = refused(&p, &[]);
        assert!(e.contains(name), "{e}");
    }
    let mut lying = bytes.clone();
    lying[16..24].copy_from_slice(&u64::MAX.to_le_bytes());
    let p = dir.join("lying.usdc");
    std::fs::write(&p, lying).unwrap();
    assert!(refused(&p, &[]).contains("table of contents"));
    // more faces than the budget allows
    let e = refused(&fixture("stage.usda"), &["--limit", "faces=10"]);
    assert!(e.contains("stage.usda") && e.contains("faces limit"), "{e}");
}

#[test]
fn a_stage_read_from_memory_follows_no_reference() {
    let text = "#usda 1.0\n(\n    subLayers = [@./other.usda@]\n)\n";
    let src = Source::Bytes { bytes: text.as_bytes(), name: "mem.usda", folder: None };
    let e = subdiv::io::read(src, &ReadOptions::default()).unwrap_err().to_string();
    assert!(e.contains("mem.usda") && e.contains("other.usda"), "{e}");
}

/// The start of section `name` in the crate file `bytes` (its table of
/// contents: a count, then 16-byte names with a start and a size each).
fn section(bytes: &[u8], name: &str) -> usize {
    let u64_at = |at: usize| u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) as usize;
    let toc = u64_at(16);
    (0..u64_at(toc))
        .map(|k| toc + 8 + 32 * k)
        .find(|&e| bytes[e..e + 16].split(|&b| b == 0).next() == Some(name.as_bytes()))
        .map(|e| u64_at(e + 16))
        .unwrap()
}

#[test]
fn a_crate_file_claiming_more_elements_than_it_can_hold_is_refused_before_allocating() {
    let dir = common::scratch_dir("usd-counts");
    let good = std::fs::read(fixture("stage.usdc")).unwrap();
    for (name, at) in [("TOKENS", 0), ("SPECS", 0), ("PATHS", 8)] {
        let mut bytes = good.clone();
        let start = section(&bytes, name) + at;
        bytes[start..start + 8].copy_from_slice(&(1u64 << 40).to_le_bytes());
        let path = dir.join(format!("{name}.usdc"));
        std::fs::write(&path, &bytes).unwrap();
        let err = refused(&path, &[]);
        assert!(err.contains(&format!("{name}.usdc")) && err.contains("more than the file's size"), "{name}: {err}");
    }
}

/// The faces of an OBJ as corner positions, by object (`o` lines; `""`
/// before the first).
fn objects(text: &str) -> Vec<(String, Vec<Vec<[f64; 3]>>)> {
    let num = |l: &str| -> Vec<f64> { l.split_whitespace().map(|x| x.parse().unwrap()).collect() };
    let v: Vec<Vec<f64>> = text.lines().filter_map(|l| l.strip_prefix("v ")).map(num).collect();
    let mut out: Vec<(String, Vec<Vec<[f64; 3]>>)> = Vec::new();
    for l in text.lines() {
        if let Some(name) = l.strip_prefix("o ") {
            out.push((name.trim().to_string(), Vec::new()));
        } else if let Some(f) = l.strip_prefix("f ") {
            if out.is_empty() {
                out.push((String::new(), Vec::new()));
            }
            let face = f
                .split_whitespace()
                .map(|c| {
                    let p = &v[c.split('/').next().unwrap().parse::<usize>().unwrap() - 1];
                    [p[0], p[1], p[2]]
                })
                .collect();
            out.last_mut().unwrap().1.push(face);
        }
    }
    out
}

/// The worst distance from a corner of `a` to the nearest corner of `b`, both ways.
fn apart(a: &[Vec<[f64; 3]>], b: &[Vec<[f64; 3]>]) -> f64 {
    let flat =
        |x: &[Vec<[f64; 3]>]| -> Vec<([f64; 3], [f64; 2])> { x.iter().flatten().map(|p| (*p, [0.0; 2])).collect() };
    let (a, b) = (flat(a), flat(b));
    worst(&a, &b).max(worst(&b, &a))
}

/// The faces of OpenSubdiv's refinement in the fixture `name`.
fn osd_faces(name: &str) -> Vec<Vec<[f64; 3]>> {
    objects(&std::fs::read_to_string(fixture(name)).unwrap()).remove(0).1
}

#[test]
fn each_prim_is_refined_by_its_own_scheme_as_opensubdiv_refines_it() {
    // /a/loop says loop, /b/smooth catmullClark with the smooth triangle rule
    let out = subdivide(&fixture("two.usda"), "two.L2.obj", &["-n", "2"]);
    let objs = objects(&std::fs::read_to_string(out).unwrap());
    let names: Vec<&str> = objs.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["/a/loop", "/b/smooth"]);
    for ((name, faces), (osd, sides)) in objs.iter().zip([("two.a.L2.osd.obj", 3), ("two.b.L2.osd.obj", 4)]) {
        let theirs = osd_faces(osd);
        assert_eq!(faces.len(), theirs.len(), "{name}: faces");
        assert!(faces.iter().all(|f| f.len() == sides), "{name}: faces of {sides}");
        let d = apart(faces, &theirs);
        assert!(d < 1e-5, "{name}: {d} from OpenSubdiv's");
    }
    // written as a stage: each prim its own scheme, its points under its transform
    let usd = subdivide(&fixture("two.usda"), "two.L2.usda", &["-n", "2"]);
    let back = subdiv::io::read_raw(Source::File(&usd), &ReadOptions::default()).unwrap().raw;
    let scene = back.scene.as_ref().expect("a scene");
    let schemes: Vec<_> = scene.prims.iter().map(|p| (p.path.as_str(), p.options.scheme)).collect();
    assert_eq!(schemes, [("/a/loop", Some(FileScheme::Loop)), ("/b/smooth", Some(FileScheme::CatmullClark))]);
    assert_eq!(scene.prims[1].options.triangles, Some(subdiv::mesh::TriangleSubdivision::Smooth));
    assert_ne!(scene.prims[1].transform, scene.prims[0].transform, "the second prim's transform is kept");
    let text = std::fs::read_to_string(&usd).unwrap();
    assert!(text.contains("xformOp:transform"), "{text}");
    // in world space the stage read back is the refinement written as OBJ
    let mut faces = Vec::new();
    for f in 0..back.num_faces() {
        let c = back.face_starts[f] as usize..back.face_starts[f + 1] as usize;
        faces.push(back.corners[c].iter().map(|&v| back.positions[v as usize].as_dvec3().to_array()).collect());
    }
    let all: Vec<Vec<[f64; 3]>> = objs.iter().flat_map(|(_, f)| f.clone()).collect();
    assert!(apart(&faces, &all) < 1e-5);
    // a --scheme flag refines every prim with it
    let looped = subdivide(&fixture("two.usda"), "two.loop.obj", &["-n", "2", "-s", "loop"]);
    let objs = objects(&std::fs::read_to_string(looped).unwrap());
    assert!(objs.iter().all(|(_, f)| f.len() == 160 && f.iter().all(|f| f.len() == 3)));
}

#[test]
fn a_glb_of_a_stage_has_a_mesh_a_prim() {
    let out = subdivide(&fixture("two.usda"), "two.glb", &["-n", "1"]);
    let bytes = std::fs::read(out).unwrap();
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json = std::str::from_utf8(&bytes[20..20 + len]).unwrap();
    assert_eq!(json.matches("\"primitives\"").count(), 2, "{json}");
    assert!(json.contains("\"name\":\"/a/loop\"") && json.contains("\"name\":\"/b/smooth\""), "{json}");
    // and it reads back: 40 triangles and 30 quads fanned
    let back =
        subdiv::io::read(Source::Bytes { bytes: &bytes, name: "two.glb", folder: None }, &ReadOptions::default());
    assert_eq!(back.unwrap().mesh.ct.num_triangles(), 40 + 60);
}

#[test]
fn subdivision_scheme_none_is_the_cage_at_every_level() {
    let cage = raw(&fixture("none.usda"));
    assert_eq!(cage.num_faces(), 24);
    for levels in ["0", "2"] {
        let out = subdivide(&fixture("none.usda"), &format!("none.{levels}.usda"), &["-n", levels]);
        let back = raw(&out);
        assert_eq!((back.num_faces(), back.positions.len()), (24, 26), "level {levels}");
        assert_eq!(back.positions, cage.positions);
        assert_eq!(back.options.scheme, Some(FileScheme::None));
    }
    // beside a smooth prim, only that one is refined
    let out = subdivide(&fixture("mixed.usda"), "mixed.L2.obj", &["-n", "2"]);
    let objs = objects(&std::fs::read_to_string(out).unwrap());
    assert_eq!(objs[0].0, "/Flat");
    assert_eq!(objs[0].1.len(), 24, "the none prim as it is");
    assert_eq!(objs[1].0, "/Right/Round");
    let theirs = osd_faces("mixed.cc.L2.osd.obj");
    assert_eq!(objs[1].1.len(), theirs.len());
    assert!(apart(&objs[1].1, &theirs) < 1e-5);
    // info says so
    let out = Command::new(env!("CARGO_BIN_EXE_subdiv")).args(["info"]).arg(fixture("mixed.usda")).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("/Flat (24 faces; subdivisionScheme none: not subdivided"), "{text}");
    assert!(text.contains("/Right/Round (24 faces; subdivisionScheme catmullClark)"), "{text}");
}

/// The values and the indices of `primvars:st` in a `.usda` text.
fn st_of(text: &str) -> (usize, Vec<usize>) {
    let list = |key: &str| -> &str {
        let at = text.find(key).unwrap_or_else(|| panic!("no {key}")) + key.len();
        &text[at..at + text[at..].find(']').unwrap()]
    };
    let values = list("texCoord2f[] primvars:st = [").matches('(').count();
    let indices = list("int[] primvars:st:indices = [").split(',').map(|x| x.trim().parse().unwrap()).collect();
    (values, indices)
}

#[test]
fn uv_seams_survive_writing_at_every_level() {
    // the box: each side a chart of 3 x 3 values, 54 values for 96 corners
    let cage = std::fs::read_to_string(fixture("seams-grid.usda")).unwrap();
    let (grid_values, grid_indices) = st_of(&cage);
    for (input, values) in [("seams.usdc", 54), ("seams-grid.usda", grid_values)] {
        for ext in ["usda", "usdc"] {
            let out = subdivide(&fixture(input), &format!("{input}.n0.{ext}"), &["-n", "0"]);
            // read the crate file back through a text layer written by the same code
            let text = match ext {
                "usda" => std::fs::read_to_string(out).unwrap(),
                _ => std::fs::read_to_string(subdivide(&out, &format!("{input}.again.usda"), &["-n", "0"])).unwrap(),
            };
            let (n, indices) = st_of(&text);
            assert_eq!(n, values, "{input} as .{ext}: values");
            assert_eq!(indices.len(), if input == "seams.usdc" { 96 } else { grid_indices.len() });
        }
    }
    // the grid's indices are the authored ones (same faces, same order)
    let text = std::fs::read_to_string(subdivide(&fixture("seams-grid.usda"), "grid.n0.usda", &["-n", "0"])).unwrap();
    assert_eq!(st_of(&text).1, grid_indices);
    // level 1: OpenSubdiv's face-varying values, one per vt (the charts' 5 x 5 a side)
    let osd = std::fs::read_to_string(fixture("seams.L1.osd.obj")).unwrap();
    let osd_values = osd.lines().filter(|l| l.starts_with("vt ")).count();
    assert_eq!(osd_values, 150);
    let text = std::fs::read_to_string(subdivide(&fixture("seams.usdc"), "seams.L1.usda", &["-n", "1"])).unwrap();
    assert_eq!(st_of(&text).0, osd_values);
    let obj = std::fs::read_to_string(subdivide(&fixture("seams.usdc"), "seams.L1.obj", &["-n", "1"])).unwrap();
    assert_eq!(obj.lines().filter(|l| l.starts_with("vt ")).count(), osd_values, "OBJ's vt");
    let (ours, theirs) = (corners(&obj), corners(&osd));
    assert_eq!(ours.len(), theirs.len());
    let (a, b) = (worst(&ours, &theirs), worst(&theirs, &ours));
    assert!(a < 1e-5 && b < 1e-5, "{a} / {b} from OpenSubdiv's positions and texture coordinates");
}

#[test]
fn points_are_read_at_the_stages_time_and_its_metadata_kept() {
    // sampled at 1, 2, 3 (x moved by t), a default value at half size
    let at = |args: &[&str]| {
        let opts = ReadOptions { time: args.first().map(|t| t.parse().unwrap()), ..Default::default() };
        subdiv::io::read(Source::File(&fixture("animated.usda")), &opts).unwrap()
    };
    let x_of_first = |l: &subdiv::io::Loaded| l.mesh.positions[0].x;
    assert_eq!(x_of_first(&at(&[])), 2.0, "startTimeCode 1: 1 + 1");
    assert_eq!(x_of_first(&at(&["2.5"])), 3.5, "linear between the samples");
    assert_eq!(x_of_first(&at(&["9"])), 4.0, "held after the last");
    let scene = at(&[]).attributes.scene().cloned().expect("a scene");
    assert_eq!((scene.time, scene.times.clone()), (Some(1.0), vec![1.0, 2.0, 3.0]));
    assert_eq!(scene.up_axis, Some(subdiv::mesh::UpAxis::Z));
    assert_eq!(scene.meters_per_unit, Some(0.01));
    // the command line's --time, and the metadata written back
    let out = subdivide(&fixture("animated.usda"), "t2.usda", &["-n", "1", "--time", "2"]);
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("upAxis = \"Z\"") && text.contains("metersPerUnit = 0.01"), "{text}");
    let back = raw(&out);
    let (lo, hi) = back.positions.iter().fold((f32::MAX, f32::MIN), |(lo, hi), p| (lo.min(p.x), hi.max(p.x)));
    assert!(lo > 0.9 && hi < 3.1 && hi > 2.0, "refined at t = 2: x in [{lo}, {hi}]");
}

#[test]
fn instances_are_expanded_and_point_instancers_refused_by_name() {
    let r = raw(&fixture("instanced.usda"));
    let scene = r.scene.as_ref().unwrap();
    let paths: Vec<&str> = scene.prims.iter().map(|p| p.path.as_str()).collect();
    assert_eq!(paths, ["/Inst0/Shape", "/Inst1/Shape"]);
    assert_eq!(r.num_faces(), 20);
    let xs: Vec<f32> = r.positions.iter().map(|p| p.x).collect();
    assert!(xs[..7].iter().all(|&x| x < 1.5) && xs[7..].iter().all(|&x| x > 2.5), "under their translates: {xs:?}");
    let e = refused(&fixture("pointinstancer.usda"), &[]);
    assert!(e.contains("pointinstancer.usda") && e.contains("/Scatter") && e.contains("PointInstancer"), "{e}");
}

#[test]
fn display_colors_per_face_and_per_vertex_are_read_and_written() {
    let r = raw(&fixture("colors.usda"));
    // /P0's two faces red and blue, as two groups of its prim
    let diffuse: Vec<[f32; 3]> =
        (0..2).map(|f| r.material_list[r.materials.as_ref().unwrap()[f] as usize].diffuse.to_array()).collect();
    assert_eq!(diffuse, [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]);
    assert!(r.scene.as_ref().unwrap().prims[0].face_colors);
    // /P1's constant green and /P2's per vertex are vertex colours
    let colors = r.colors.as_ref().unwrap();
    assert_eq!(colors[6].to_array(), [0.0, 1.0, 0.0]);
    assert_eq!(colors[13].to_array(), [1.0, 0.0, 0.0]);
    for levels in ["0", "1"] {
        let out = subdivide(&fixture("colors.usda"), &format!("colors.{levels}.usda"), &["-n", levels]);
        let text = std::fs::read_to_string(&out).unwrap();
        assert!(text.contains("interpolation = \"uniform\""), "{text}");
        let back = raw(&out);
        let m = back.materials.as_ref().unwrap();
        let faces = if levels == "0" { 2 } else { 8 };
        let red = (0..faces).filter(|&f| back.material_list[m[f] as usize].diffuse == glam::Vec3::X).count();
        assert_eq!(red, faces / 2, "level {levels}: half of /P0's faces are red");
    }
}
