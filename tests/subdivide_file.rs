//! `subdiv::subdivide_file`, the one per-file path of `subdiv subdivide`,
//! of every file of `subdiv batch` and of Python's `subdivide_file`: it
//! writes what `subdivide_model` and `save_refined` write from the file as
//! read, takes the file's options under the caller's flags, tells `admit`
//! what it will need before it refines, and leaves no file where it fails.

mod common;
use common::*;
use std::path::Path;
use subdiv::io::{self, ReadOptions};
use subdiv::mesh::{Attributes, BoundaryInterpolation, FileScheme, ShapeOptions};
use subdiv::{Demand, FileJob, Flags, Model, Refinement, Scheme, subdivide_file, subdivide_model};

/// What the library writes for `input` by hand: read, the default flags
/// over the file's options, the attributes the output keeps,
/// `subdivide_model`, `save_refined` (the options written as refined).
fn by_hand(input: &Path, output: &Path, levels: u32) {
    let loaded = subdiv::bundled::read(input, &ReadOptions::default()).expect("reads");
    let s = Flags::default().over(loaded.attributes.options);
    // the attributes the output's format keeps, the others dropped first
    let (a, keeps) = (loaded.attributes.clone(), io::keeps(output));
    let attrs = Attributes {
        uv: a.uv.filter(|_| keeps.uv),
        colors: a.colors.filter(|_| keeps.colors),
        materials: a.materials.filter(|_| keeps.materials),
        options: a.options,
    }
    .with_options(s.shape());
    let model = Model { precise: loaded.precise.as_deref(), ..Model::new(&loaded.mesh, &attrs) };
    let how = Refinement { scheme: s.scheme(), levels, opts: s.options(), f64: false, dest: io::destination(output) };
    let fine = subdivide_model(&model, &how).expect("refines");
    io::save_refined(output, &fine).expect("writes");
}

#[test]
fn it_writes_what_subdivide_model_and_save_refined_write() {
    let dir = scratch_dir("subdivide-file");
    for name in ["cube_uv.obj", "torus.obj", "lprism.ct", "critter.obj"] {
        for ext in ["obj", "ply"] {
            let (ours, theirs) = (dir.join(format!("a-{name}.{ext}")), dir.join(format!("b-{name}.{ext}")));
            let job = FileJob { levels: 2, ..FileJob::default() };
            let s = subdivide_file(&model_path(name), &ours, &job, &mut |_| Ok(())).expect("subdivides");
            by_hand(&model_path(name), &theirs, 2);
            let (a, b) = (std::fs::read(&ours).expect("written"), std::fs::read(&theirs).expect("written"));
            assert!(a == b, "{name} -> .{ext}: the bytes differ");
            let back = subdiv::bundled::read(&ours, &ReadOptions::default()).expect("reads back");
            assert_eq!(back.mesh.positions.len(), s.vertices, "{name} -> .{ext}");
            assert_eq!(s.levels, 2);
        }
    }
}

#[test]
fn admit_is_told_the_demand_before_anything_is_written_and_may_refuse() {
    let dir = scratch_dir("subdivide-file-admit");
    let out = dir.join("refused.ply");
    let mut told = None;
    let mut refuse = |d: &Demand| {
        told = Some(*d);
        Err(subdiv::Error::Usage("no memory for it".into()))
    };
    let job = FileJob { levels: 3, ..FileJob::default() };
    let e = subdivide_file(&model_path("torus.obj"), &out, &job, &mut refuse).expect_err("refused");
    assert!(e.to_string().contains("no memory for it"), "{e}");
    assert!(!out.exists(), "nothing written");
    let d = told.expect("admit was called");
    let torus = bundled("torus.obj");
    assert_eq!(d.parts, 1);
    assert_eq!(d.faces, torus.ct.num_triangles() as u64 * 64);
    assert!(d.peak >= d.least && d.least > 0, "{d:?}");
    // admitted, the same job writes, and says what it wrote
    let s = subdivide_file(&model_path("torus.obj"), &out, &job, &mut |_| Ok(())).expect("admitted");
    assert_eq!((s.input_vertices, s.input_faces), (torus.positions.len(), torus.ct.num_triangles()));
    assert_eq!(s.faces, torus.ct.num_triangles() * 64);
    assert!(out.exists());
}

#[test]
fn a_bad_file_is_named_and_leaves_no_file() {
    let dir = scratch_dir("subdivide-file-bad");
    let bad = dir.join("broken.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nf 1 2 7\n").expect("written");
    let out = dir.join("out.obj");
    let e = subdivide_file(&bad, &out, &FileJob::default(), &mut |_| Ok(())).expect_err("refused");
    assert!(e.to_string().contains("broken.obj"), "{e}");
    // a refusal of the budget leaves an older output as it was
    std::fs::write(&out, "old\n").expect("written");
    let job = FileJob { levels: 30, ..FileJob::default() };
    assert!(subdivide_file(&model_path("cube.obj"), &out, &job, &mut |_| Ok(())).is_err());
    assert_eq!(std::fs::read_to_string(&out).expect("still there"), "old\n");
    let mut left: Vec<_> = std::fs::read_dir(&dir).expect("listed").flatten().map(|e| e.file_name()).collect();
    left.sort();
    assert_eq!(left, ["broken.obj", "out.obj"], "no temporary file");
}

#[test]
fn the_flags_take_the_place_of_the_files_options() {
    let file = ShapeOptions {
        boundary: Some(BoundaryInterpolation::EdgeAndCorner),
        scheme: Some(FileScheme::CatmullClark),
        ..ShapeOptions::default()
    };
    let none = Flags::default().over(file);
    assert_eq!(none.scheme(), Scheme::CatmullClark, "the file's scheme where no flag says one");
    assert_eq!(none.options().boundary, BoundaryInterpolation::EdgeAndCorner);
    let flags =
        Flags { scheme: Some(Scheme::Loop), boundary: Some(BoundaryInterpolation::EdgeOnly), ..Flags::default() };
    let over = flags.over(file);
    assert_eq!(over.scheme(), Scheme::Loop);
    assert_eq!(over.options().boundary, BoundaryInterpolation::EdgeOnly);
    // a file that says `none` is the cage unless a scheme is given
    let cage = ShapeOptions { scheme: Some(FileScheme::None), ..ShapeOptions::default() };
    assert!(!Flags::default().over(cage).subdivides());
    assert!(flags.over(cage).subdivides());
}
