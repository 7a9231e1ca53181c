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
