//! The viewer on USD stages: each prim refined by the scheme its stage
//! states (prims of different schemes apart, `subdivisionScheme none` as
//! its cage), the prim a pick hits, the stage's time samples as the
//! animation. The stages are written by the tests themselves.

use crate::Scheme;
use crate::app::probe::{Ray, Target};
use crate::app::tests::{settle, subdivide};
use crate::app::{Command, Viewer};
use glam::Vec3;

/// A closed bipyramid of 10 triangles as a Mesh prim at `path`, moved by
/// `dx`, with `attributes` (USD text).
fn bipyramid(path: &str, dx: f32, attributes: &str) -> String {
    let mut points: Vec<String> = (0..5)
        .map(|k| {
            let a = std::f32::consts::TAU * k as f32 / 5.0;
            format!("({}, {}, 0)", a.cos() + dx, a.sin())
        })
        .collect();
    points.push(format!("({dx}, 0, 1.2)"));
    points.push(format!("({dx}, 0, -0.8)"));
    let faces: Vec<String> = (0..5)
        .map(|k| format!("{}, {}, 5", k, (k + 1) % 5))
        .chain((0..5).map(|k| format!("{}, {}, 6", (k + 1) % 5, k)))
        .collect();
    format!(
        "def Mesh \"{path}\"\n{{\n    point3f[] points = [{}]\n    int[] faceVertexCounts = [{}]\n    int[] faceVertexIndices = [{}]\n{attributes}\n}}\n",
        points.join(", "),
        ["3"; 10].join(", "),
        faces.join(", ")
    )
}

/// A stage of `prims` written to a scratch file `name`.
fn stage(name: &str, prims: &[String]) -> std::path::PathBuf {
    let path = crate::app::tests::common::scratch_dir("stage").join(name);
    std::fs::write(&path, format!("#usda 1.0\n\n{}", prims.join("\n"))).expect("written");
    path
}

fn open(v: &mut Viewer, path: std::path::PathBuf) {
    v.apply(Command::Open(path));
    settle(v);
    assert!(v.doc.status.error.is_none(), "{:?}", v.doc.status.error);
}

/// The probe's prim after a pick straight down onto `(x, y)`.
fn prim_under(v: &mut Viewer, x: f32, y: f32) -> Option<String> {
    v.apply(Command::PickSurface(Ray { origin: Vec3::new(x, y, 5.0), dir: -Vec3::Z, target: Target::Result }));
    v.doc.model.probe.as_ref().and_then(|p| p.prim.clone())
}

#[test]
fn every_prim_is_drawn_by_its_own_scheme_and_a_pick_names_its_prim() {
    let mut v = Viewer::new();
    let loop_prim = bipyramid("Round", 0.0, "    uniform token subdivisionScheme = \"loop\"");
    let cc_prim = bipyramid("Square", 3.0, "    uniform token subdivisionScheme = \"catmullClark\"");
    open(&mut v, stage("two.usda", &[loop_prim, cc_prim]));
    assert!(v.doc.request.by_file, "the stage's schemes are followed");
    let scheme = v.doc.request.scheme;
    subdivide(&mut v, scheme, 2);
    settle(&mut v);
    assert!(v.doc.model.made.by_prim);
    // Loop's 160 triangles beside Catmull-Clark's 120 quads (240 triangles drawn)
    assert_eq!(v.doc.model.raw.mesh.ct.num_triangles(), 160 + 240);
    assert_eq!(prim_under(&mut v, 0.1, 0.1).as_deref(), Some("/Round"));
    assert_eq!(prim_under(&mut v, 3.1, 0.1).as_deref(), Some("/Square"));
    let probe = v.doc.model.probe.as_ref().expect("picked");
    assert!(probe.on_cage, "prims refined apart are traced on the cage");
    // a scheme picked in the panel refines every prim with it
    assert_eq!(v.doc.request.scheme, Scheme::Loop, "the first prim's scheme is shown");
    subdivide(&mut v, Scheme::CatmullClark, 2);
    settle(&mut v);
    assert!(!v.doc.request.by_file && !v.doc.model.made.by_prim);
    assert_eq!(v.doc.model.raw.mesh.ct.num_triangles(), 2 * 240, "120 quads each");
    assert_eq!(prim_under(&mut v, 3.1, 0.1).as_deref(), Some("/Square"), "traced through the one refiner");
}

#[test]
fn a_prim_that_says_none_is_drawn_as_its_cage_at_every_level() {
    let mut v = Viewer::new();
    open(&mut v, stage("none.usda", &[bipyramid("Flat", 0.0, "    uniform token subdivisionScheme = \"none\"")]));
    let scheme = v.doc.request.scheme;
    subdivide(&mut v, scheme, 3);
    settle(&mut v);
    assert_eq!(v.doc.model.raw.mesh.ct.num_triangles(), 10, "the cage as it is");
    assert_eq!(v.doc.model.raw.mesh.positions, v.doc.model.control.mesh.positions);
}

#[test]
fn a_stages_time_samples_are_its_animation() {
    let mut v = Viewer::new();
    let points = |t: f32| format!("[({t}, 0, 0), (1, {t}, 0), (0, 1, 0), (0, 0, 1)]");
    let tet = format!(
        "def Mesh \"Tet\"\n{{\n    point3f[] points.timeSamples = {{ 1: {}, 2: {}, 4: {} }}\n    int[] faceVertexCounts = [3, 3, 3, 3]\n    int[] faceVertexIndices = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]\n}}\n",
        points(0.0),
        points(0.5),
        points(-0.5)
    );
    open(&mut v, stage("anim.usda", &[tet]));
    let paths = &v.doc.anim.paths;
    assert_eq!(paths.keys_per_vertex, 3);
    let xs: Vec<f32> = paths.polygon(0).iter().map(|p| p.x).collect();
    assert_eq!(xs, [0.0, 0.5, -0.5], "vertex 0 at each sample");
    assert!(v.doc.anim.paths_source.contains("3 time samples"), "{}", v.doc.anim.paths_source);
    assert_eq!(v.doc.anim.refine, 0, "the samples as they are");
}
