//! OpenSubdiv's option tags in OBJ (`t interpolateboundary`, `t
//! facevaryinginterpolateboundary`, `t smoothtriangles`, `t creasemethod`):
//! read as the subdivision's options, overridden by the flags, written back
//! where they are not the defaults, and equal to OpenSubdiv reading the same
//! tags (tests/fixtures/catmark/tagged.*, scripts/tag-fixtures.py).
#![cfg(feature = "cli")]

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use subdiv::mesh::{BoundaryInterpolation, Creasing, UvInterpolation};
use subdiv::mesh::{ShapeOptions, TriangleSubdivision};

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark").join(name)
}

/// Runs `subdiv subdivide IN OUT ARGS` and returns OUT's text.
fn subdivide(input: &Path, out: &str, args: &[&str]) -> String {
    let path = common::scratch_dir("shape_tags").join(out);
    let st = Command::new(env!("CARGO_BIN_EXE_subdiv"))
        .arg("subdivide")
        .arg(input)
        .arg(&path)
        .args(["-s", "catmull-clark"])
        .args(args)
        .output()
        .unwrap();
    assert!(st.status.success(), "{args:?}: {}", String::from_utf8_lossy(&st.stderr));
    std::fs::read_to_string(&path).unwrap()
}

use common::obj_corners as corners;

/// The worst texture-space distance from a corner of `a` to the nearest
/// corner of `b` at the same position (infinite where none is there).
fn worst(a: &[([f64; 3], [f64; 2])], b: &[([f64; 3], [f64; 2])]) -> f64 {
    let d = |p: &[f64], q: &[f64]| p.iter().zip(q).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt();
    a.iter()
        .map(|(p, t)| b.iter().filter(|(q, _)| d(p, q) < 1e-5).map(|(_, u)| d(t, u)).fold(f64::INFINITY, f64::min))
        .fold(0.0, f64::max)
}

#[test]
fn the_tags_alone_and_the_flags_over_them_equal_opensubdiv() {
    let flags = ["--boundary", "edge", "--fvar", "all", "--creasing", "uniform", "--triangles", "catmark"];
    let tags = corners(&subdivide(&fixture("tagged.obj"), "tags.obj", &["-n", "2"]));
    let over = corners(&subdivide(&fixture("tagged.obj"), "flags.obj", &[&["-n", "2"][..], &flags].concat()));
    let osd = |name: &str| corners(&std::fs::read_to_string(fixture(name)).unwrap());
    for (ours, theirs, what) in
        [(&tags, osd("tagged.L2.osd.obj"), "tags"), (&over, osd("tagged.flags.L2.osd.obj"), "flags")]
    {
        assert_eq!(ours.len(), theirs.len(), "{what}: corners");
        let (a, b) = (worst(ours, &theirs), worst(&theirs, ours));
        assert!(a < 1e-5 && b < 1e-5, "{what}: {a} / {b} from OpenSubdiv's (positions and texture coordinates)");
    }
    // the tags change the surface: the flags' result is not the tags'
    assert!(worst(&tags, &over) > 1e-3, "the option tags changed nothing");
}

#[test]
fn the_options_are_written_back_unless_they_are_the_defaults() {
    let read = |text: &str| {
        let src = subdiv::io::Source::Bytes { bytes: text.as_bytes(), name: "out.obj", folder: None };
        subdiv::io::read(src, &Default::default()).unwrap().attributes.options
    };
    let file = read(&std::fs::read_to_string(fixture("tagged.obj")).unwrap());
    let stated = ShapeOptions {
        boundary: Some(BoundaryInterpolation::EdgeAndCorner),
        fvar: Some(UvInterpolation::Boundaries),
        triangles: Some(TriangleSubdivision::Smooth),
        creasing: Some(Creasing::Chaikin),
        scheme: None,
    };
    assert_eq!(file, stated);
    // a level-0 round trip keeps every tag
    let same = subdivide(&fixture("tagged.obj"), "n0.obj", &["-n", "0"]);
    assert_eq!(read(&same), stated);
    // a flag that sets the default leaves its tag out; another flag replaces its tag
    let changed =
        subdivide(&fixture("tagged.obj"), "n0flags.obj", &["-n", "0", "--boundary", "edge", "--fvar", "none"]);
    assert!(!changed.contains("t interpolateboundary"), "the default boundary is not written");
    assert_eq!(read(&changed), ShapeOptions { boundary: None, fvar: Some(UvInterpolation::None), ..stated });
    // a file without tags gets none
    let plain = subdivide(&fixture("fvar.obj"), "plain.obj", &["-n", "1"]);
    assert!(!plain.lines().any(|l| l.starts_with("t ")), "no option was asked for");
}

#[test]
fn bad_option_tags_are_refused_naming_the_line() {
    for (tag, want) in [
        ("t interpolateboundary 1/0/0 3", "0, 1 or 2"),
        ("t interpolateboundary 0/0/1 edge", "0, 1 or 2"),
        ("t facevaryinginterpolateboundary 1/0/0 6", "0 to 5"),
        ("t smoothtriangles 0/0/1 round", "catmark or smooth"),
        ("t creasemethod 0/0/1", "normal or chaikin"),
    ] {
        let text = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n{tag}\n");
        let src = subdiv::io::Source::Bytes { bytes: text.as_bytes(), name: "bad.obj", folder: None };
        let e = subdiv::io::read(src, &Default::default()).unwrap_err().to_string();
        assert!(e.contains("bad.obj:5:") && e.contains(want), "{tag}: {e}");
        assert_eq!(e.lines().count(), 1, "{e}");
    }
}

/// Every name `name` gives reads back through the one `FromStr`, and an
/// unknown name's message lists every one of them.
fn names_read_back<T: std::str::FromStr<Err = String> + PartialEq + std::fmt::Debug + Copy>(
    all: &[T],
    name: impl Fn(T) -> &'static str,
) {
    let e = "nope".parse::<T>().unwrap_err();
    assert!(e.contains("'nope'"), "{e}");
    for &x in all {
        assert_eq!(name(x).parse::<T>(), Ok(x));
        assert!(e.contains(name(x)), "{e} lists {}", name(x));
    }
}

#[test]
fn every_option_name_reads_back_and_an_unknown_one_is_refused_listing_them() {
    use subdiv::{LoopBeta, Scheme};
    names_read_back(&Scheme::ALL, Scheme::name);
    names_read_back(&[LoopBeta::Loop, LoopBeta::Warren], LoopBeta::name);
    let boundaries =
        [BoundaryInterpolation::EdgeOnly, BoundaryInterpolation::EdgeAndCorner, BoundaryInterpolation::None];
    names_read_back(&boundaries, BoundaryInterpolation::name);
    names_read_back(&UvInterpolation::ALL, UvInterpolation::name);
    names_read_back(&[TriangleSubdivision::Catmark, TriangleSubdivision::Smooth], TriangleSubdivision::name);
    names_read_back(&[Creasing::Uniform, Creasing::Chaikin], Creasing::name);
}
