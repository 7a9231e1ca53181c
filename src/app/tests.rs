//! The viewer's logic without a window: the egui panel runs headless on a
//! viewer, driven by key events; every change goes through the same
//! `Viewer::apply` as in the window, and the worker threads are awaited.
//! (Unit tests of the app, since its internals are not public.)

/// The files the tests use.
pub(super) mod common {
    use std::path::PathBuf;

    /// A fresh directory for one test's files: the process id and the time
    /// the process first asked keep runs apart (a process id alone comes
    /// back in a later run, with that run's files still there).
    pub(crate) fn scratch_dir(name: &str) -> PathBuf {
        static RUN: std::sync::OnceLock<u128> = std::sync::OnceLock::new();
        let run = RUN.get_or_init(|| {
            std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos())
        });
        let d = std::env::temp_dir().join(format!("subdiv-{name}-{}-{run}", std::process::id()));
        std::fs::create_dir_all(&d).expect("temporary directory");
        d
    }

    /// A bundled model, as the command line names it (`bundled:NAME`).
    pub(crate) fn model_path(name: &str) -> PathBuf {
        PathBuf::from(format!("{}{name}", crate::bundled::PREFIX))
    }

    /// The model's mesh and attributes.
    pub(crate) fn load_with_attributes(path: &std::path::Path) -> (crate::Mesh, crate::mesh::attributes::Attributes) {
        let l = crate::bundled::read(path, &Default::default()).expect("readable");
        (l.mesh, l.attributes)
    }
}

use crate::app::doc::{Problem, Request};
use crate::app::{Command, Viewer};
use crate::render::Surface;
use crate::{Error, Scheme};
use glam::Vec3;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

pub(super) fn key(k: egui::Key) -> egui::Event {
    egui::Event::Key { key: k, physical_key: None, pressed: true, repeat: false, modifiers: Default::default() }
}

/// One frame of the panel in a window of `size` points.
pub(super) fn frame_sized(ctx: &egui::Context, v: &mut Viewer, size: egui::Vec2, events: Vec<egui::Event>) {
    let raw = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, size)),
        events,
        ..Default::default()
    };
    let out = ctx.run_ui(raw, |ui| {
        v.ui(ui);
    });
    out.drop_without_applying_deltas();
}

pub(super) fn frame(ctx: &egui::Context, v: &mut Viewer, events: Vec<egui::Event>) {
    frame_sized(ctx, v, egui::vec2(1280.0, 800.0), events);
}

pub(super) fn settle(v: &mut Viewer) {
    let t0 = Instant::now();
    loop {
        v.poll();
        if !v.doc.busy() {
            return;
        }
        assert!(t0.elapsed() < Duration::from_secs(60), "worker did not finish");
        std::thread::sleep(Duration::from_millis(2));
    }
}

pub(super) fn subdivide(v: &mut Viewer, scheme: Scheme, level: u32) {
    v.apply(Command::Subdivide(Request { scheme, level, ..v.doc.request }));
}

fn set_display(v: &mut Viewer, change: impl FnOnce(&mut crate::app::display::Display)) {
    let mut d = v.doc.display;
    change(&mut d);
    v.apply(Command::SetDisplay(d));
}

fn error_text(v: &Viewer) -> Option<String> {
    v.doc.status.error.as_ref().map(ToString::to_string)
}

#[test]
fn keys_toggle_the_view_and_step_levels_on_a_worker() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    frame(&ctx, &mut v, vec![]);
    assert!(v.view.scene_rect.width() > 500.0, "the 3D area takes the rest of the window");
    frame(&ctx, &mut v, vec![key(egui::Key::W)]);
    assert!(v.doc.display.wireframe);
    frame(&ctx, &mut v, vec![key(egui::Key::S)]);
    assert_eq!(v.doc.display.surface, Surface::Flat);
    for _ in 0..3 {
        frame(&ctx, &mut v, vec![key(egui::Key::Plus)]);
    }
    assert_eq!(v.doc.request.level, 3);
    settle(&mut v);
    assert_eq!(v.doc.model.made.level, 3);
    assert_eq!(v.doc.model.result.shown.topo.faces, 4 * 64);
    assert!(v.doc.model.made.stats.is_some());
    frame(&ctx, &mut v, vec![key(egui::Key::Minus)]);
    settle(&mut v);
    assert_eq!((v.doc.request.level, v.doc.model.result.shown.topo.faces), (2, 64));
}

#[test]
fn a_newer_request_supersedes_an_older_one() {
    let mut v = Viewer::new();
    subdivide(&mut v, Scheme::Loop, 8);
    // Supersede it during its last level (7 -> 8, 262,144 faces), so that a
    // result it sent would come after the newer one's.
    let t0 = Instant::now();
    let done = |v: &Viewer| v.doc.jobs.busy.subdividing.as_ref().map_or(8, |b| b.done.load(Ordering::Relaxed));
    while done(&v) < 7 {
        assert!(t0.elapsed() < Duration::from_secs(60), "the level-8 job does not progress");
        std::thread::sleep(Duration::from_millis(1));
    }
    subdivide(&mut v, Scheme::Loop, 1);
    settle(&mut v);
    // Wait until the superseded thread has ended, so that anything it sent is
    // in the channel: it must not replace level 1.
    assert!(v.doc.jobs.wait_for_workers(Duration::from_secs(60)), "the superseded worker did not end");
    v.poll();
    assert!(v.doc.status.error.is_none(), "a superseded result arrived: {:?}", error_text(&v));
    assert_eq!((v.doc.model.made.level, v.doc.model.result.shown.topo.faces), (1, 16));
}

#[test]
fn a_big_level_brings_its_proxy_from_the_same_run() {
    let mut v = Viewer::new();
    subdivide(&mut v, Scheme::Loop, 8); // 262,144 faces: over the proxy threshold
    settle(&mut v);
    assert!(v.doc.status.error.is_none(), "{:?}", error_text(&v));
    assert_eq!(v.doc.model.result.shown.topo.faces, 4 << 16);
    let proxy = v.doc.model.proxy.as_ref().expect("a proxy");
    assert_eq!(proxy.topo.faces, 4 << 14, "level 7: the highest level under the threshold");
    let stats = v.doc.model.made.stats.as_ref().unwrap();
    assert_eq!(stats.faces_per_level.len(), 8, "both legs of the run are in the stats");
    assert_eq!(*stats.faces_per_level.last().unwrap(), 4 << 16);
}

/// The page's way in (a file picked, dropped or fetched): bytes and a
/// name, through the same reading pipeline as a file; a bad one is an
/// error naming it, and the model stays.
#[test]
fn bytes_open_as_a_file_does_and_a_bad_one_is_named() {
    let mut v = Viewer::new();
    let cube = crate::bundled::MODELS.iter().find(|m| m.file_name == "cube.obj").unwrap();
    v.apply(Command::OpenBytes { name: "dropped.obj".into(), bytes: cube.bytes.into() });
    settle(&mut v);
    assert!(v.doc.status.error.is_none(), "{:?}", error_text(&v));
    assert_eq!(v.doc.model.name, "dropped.obj");
    assert_eq!(v.doc.model.control.topo.vertices, 8);
    let bad: std::sync::Arc<[u8]> = b"v 0 0 0\nv 1 0 0\nf 1 2 7\n".as_slice().into();
    v.apply(Command::OpenBytes { name: "page.obj".into(), bytes: bad });
    settle(&mut v);
    let err = error_text(&v).unwrap();
    assert!(err.contains("page.obj") && err.contains(":3"), "{err}");
    assert_eq!(v.doc.model.control.topo.vertices, 8, "the cube stays");
    let offered = v.doc.status.failed.as_ref().expect("offered for repair");
    assert!(offered.bytes.is_some(), "repair reads the same bytes again");
}

#[test]
fn a_bad_file_shows_an_error_and_keeps_the_model() {
    let dir = common::scratch_dir("viewer-test");
    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nf 1 2 7\n").unwrap();
    let mut v = Viewer::new();
    v.apply(Command::Open(bad));
    settle(&mut v);
    assert!(matches!(v.doc.status.error, Some(Problem::Open(_))), "{:?}", error_text(&v));
    let err = error_text(&v).unwrap();
    assert!(err.contains("bad.obj") && err.contains(":3"), "{err}");
    assert_eq!(v.doc.model.control.topo.vertices, 4, "the tetrahedron stays");
    v.apply(Command::DismissError);
    v.doc.request.level = 1;
    v.apply(Command::Open(common::model_path("cube.obj")));
    settle(&mut v);
    assert!(v.doc.status.error.is_none(), "{:?}", error_text(&v));
    assert_eq!(v.doc.model.name, "cube.obj");
    assert_eq!(v.doc.model.made.level, 1);
    assert_eq!(v.doc.model.result.shown.topo.faces, 4 * v.doc.model.control.topo.faces);
    let source = &v.doc.anim.paths_source;
    assert!(source.starts_with("generated"), "the cube has no .paths: {source}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn levels_over_the_memory_limit_are_refused_with_a_reason() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    v.doc.request.limit = Some(200_000);
    let max = v.doc.max_level();
    assert!((2..8).contains(&max), "max level {max}");
    let refusal = v.doc.level_refusal(max + 1).unwrap();
    assert!(matches!(refusal, Error::TooLarge { level, .. } if level == max + 1), "{refusal}");
    assert!(refusal.to_string().contains("limit"));
    subdivide(&mut v, Scheme::Loop, max);
    settle(&mut v);
    frame(&ctx, &mut v, vec![key(egui::Key::Plus)]);
    assert_eq!(v.doc.request.level, max, "+ past the limit does nothing");
    assert!(matches!(v.doc.status.error, Some(Problem::Other(Error::TooLarge { .. }))), "{:?}", error_text(&v));
    assert!(error_text(&v).is_some_and(|e| e.contains("limit")));
}

#[test]
fn a_model_opened_at_a_level_past_the_limit_says_which_level_it_shows() {
    let mut v = Viewer::new();
    v.doc.request.limit = Some(2_000_000);
    v.doc.request.level = 9;
    v.apply(Command::Open(common::model_path("torus.obj")));
    settle(&mut v);
    let max = v.doc.max_level();
    assert!((1..9).contains(&max), "max level {max}");
    assert_eq!(v.doc.model.made.level, max, "the largest level that fits is made");
    let notice = v.doc.status.notice.clone().unwrap_or_default();
    assert!(notice.contains("level 9 does not fit") && notice.contains(&format!("level {max} shown")), "{notice}");
    assert!(notice.contains("limit"), "the reason is given: {notice}");
}

#[test]
fn space_plays_the_tetrahedron_animation() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    subdivide(&mut v, Scheme::Loop, 5);
    frame(&ctx, &mut v, vec![key(egui::Key::Space)]);
    settle(&mut v);
    let p = v.doc.anim.playback.as_mut().expect("animation built");
    assert_eq!(p.clock.frames(), 4 << 5);
    assert!(p.clock.playing);
    assert_eq!(p.player.topology().num_triangles(), 4 << 10);
    let f0 = p.clock.tick(0.0);
    let f1 = p.clock.tick(0.5);
    assert_eq!(f1, f0 + 15, "30 frames/s for half a second");
    frame(&ctx, &mut v, vec![key(egui::Key::Space)]);
    assert!(!v.doc.anim.playing(), "Space pauses");
    v.apply(Command::StopAnimation);
    assert!(v.doc.anim.playback.is_none() && !v.doc.anim.active);
}

#[test]
fn a_non_manifold_file_can_be_repaired_from_the_panel() {
    let dir = common::scratch_dir("viewer-fin");
    let fin = dir.join("fin.obj");
    std::fs::write(&fin, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n").unwrap();
    let mut v = Viewer::new();
    v.apply(Command::Open(fin.clone()));
    settle(&mut v);
    assert!(error_text(&v).is_some_and(|e| e.contains("non-manifold edge")), "{:?}", error_text(&v));
    assert_eq!(v.doc.status.failed.as_ref().map(|i| i.path.as_path()), Some(fin.as_path()), "offered for repair");
    assert_eq!(v.doc.model.control.topo.vertices, 4, "the tetrahedron stays");
    v.apply(Command::RepairAndOpen(fin.into()));
    settle(&mut v);
    assert!(v.doc.status.failed.is_none());
    assert_eq!(v.doc.model.control.topo.faces, 3);
    let notice = v.doc.status.notice.as_deref();
    assert!(notice.is_some_and(|n| n.contains("repaired")), "{notice:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn picking_flip_split_smooth_and_revert_edit_the_control_mesh() {
    use crate::mesh::pick::pick_edge;
    let mut v = Viewer::new();
    let tet = v.doc.model.control.mesh.clone();
    // A ray from outside through the centroid of face 0 hits face 0 first.
    let t0: Vec<Vec3> = tet.ct.v_table()[..3].iter().map(|&i| tet.positions[i as usize]).collect();
    let centroid = (t0[0] + t0[1] + t0[2]) / 3.0;
    let origin = centroid * 5.0;
    let dir = (centroid - origin).normalize();
    let c = pick_edge(&tet, origin, dir).expect("the ray hits");
    assert!(c < 3, "picked corner {c} is not on face 0");
    assert_eq!(pick_edge(&tet, Vec3::new(0.0, 50.0, 0.0), Vec3::Y), None, "pointing away misses");

    v.apply(Command::Pick { origin, dir });
    assert_eq!(*v.doc.model.picked, Some(c));
    v.apply(Command::SplitPicked);
    let control = &v.doc.model.control;
    assert_eq!((control.topo.vertices, control.topo.faces), (5, 6));
    assert!(crate::mesh::topology::check_invariants(&control.mesh.ct).is_ok());
    assert!(v.doc.model.original.is_some());
    v.apply(Command::Smooth(5));
    assert_ne!(v.doc.model.control.mesh.positions, v.doc.model.original.as_ref().unwrap().positions);
    v.apply(Command::Revert);
    let control = &v.doc.model.control;
    assert_eq!((control.topo.vertices, control.topo.faces), (4, 4));
    assert_eq!(control.mesh.positions, tet.positions);
    // The tetrahedron's edges cannot be flipped (every vertex has valence 3).
    v.apply(Command::Pick { origin, dir });
    v.apply(Command::FlipPicked);
    assert!(matches!(v.doc.status.error, Some(Problem::Flip(_))), "{:?}", error_text(&v));
    assert!(error_text(&v).is_some_and(|e| e.starts_with("flip:")));
}

#[test]
fn display_options_recolour_and_renormal_the_result() {
    use crate::app::display::{Coloring, NormalMode};
    use crate::mesh::inspect::colormap;
    let mut v = Viewer::new();
    subdivide(&mut v, Scheme::Midpoint, 2);
    settle(&mut v);
    set_display(&mut v, |d| d.coloring = Coloring::Displacement);
    let colors = v.doc.model.result.colors.clone().expect("colours");
    assert_eq!(colors.len(), v.doc.model.result.shown.mesh.positions.len());
    let zero = Vec3::from(colormap(0.0));
    assert!(colors.iter().all(|c| (*c - zero).length() < 1e-6), "midpoint points lie on the control mesh");
    set_display(&mut v, |d| d.coloring = Coloring::Shells);
    let colors = v.doc.model.result.colors.clone().unwrap();
    assert_eq!(colors[0], zero, "level-0 vertices are dark");
    assert_eq!(*colors.last().unwrap(), Vec3::from(colormap(1.0)), "the newest vertices are bright");
    set_display(&mut v, |d| {
        d.normal_mode = NormalMode::Limit;
        d.snap_limit = true;
    });
    let shown = &v.doc.model.result.shown;
    assert!(shown.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
    assert_ne!(shown.mesh.positions, v.doc.model.raw.mesh.positions, "snapped to the limit");
}

#[test]
fn a_bzc_file_opens_as_a_curve_with_its_construction() {
    use crate::io::bezier::{curve_polyline, de_casteljau, de_casteljau_construction};
    let mut v = Viewer::new();
    v.apply(Command::Open(common::model_path("curve.bzc")));
    settle(&mut v);
    assert!(v.doc.status.error.is_none(), "{:?}", error_text(&v));
    let c = (*v.doc.model.curve).clone().expect("a curve");
    let line = curve_polyline(&c.control, c.segments);
    assert_eq!(line.len(), c.segments + 1);
    assert_eq!(line[0], c.control[0], "starts at the first control point");
    assert!((line[c.segments] - *c.control.last().unwrap()).length() < 1e-6, "ends at the last");
    let (segs, point) = de_casteljau_construction(&c.control, c.t);
    // n control points: levels of n-1, n-2, ..., 1 points: (n-2) + ... + 0 segments.
    let n = c.control.len();
    assert_eq!(segs.len() / 2, (n - 1) * (n - 2) / 2);
    let expect = de_casteljau(&c.control, c.t).unwrap();
    assert!((point.unwrap() - expect).length() < 1e-6);
    assert_eq!(v.doc.model.control.topo.vertices, 4, "the mesh stays loaded underneath");
    v.apply(Command::CloseCurve);
    assert!(v.doc.model.curve.is_none() && v.view.reset, "back to the mesh, with the camera reset");
}

#[test]
fn a_curve_is_framed_for_the_viewport_it_is_drawn_in() {
    // A window taller than wide: the 3D area beside the panel is narrow, so
    // the curve (wider than tall) must be framed by the viewport's width.
    let ctx = egui::Context::default();
    let size = egui::vec2(600.0, 800.0);
    let mut v = Viewer::new();
    frame_sized(&ctx, &mut v, size, vec![]);
    v.apply(Command::Open(common::model_path("curve.bzc")));
    settle(&mut v);
    frame_sized(&ctx, &mut v, size, vec![]);
    let rect = v.view.scene_rect;
    let aspect = rect.width() / rect.height();
    assert!(aspect < 1.0, "the 3D area is {rect:?}");
    let cam = v.view.camera;
    assert!(cam.orthographic && cam.yaw == 0.0 && cam.pitch == 0.0, "seen from the front: {cam:?}");
    let curve = (*v.doc.model.curve).clone().expect("a curve");
    for p in &curve.control {
        let ndc = cam.project(p.extend(0.0), aspect);
        assert!(ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0, "control point {p} is outside the view: {ndc}");
    }
}

#[test]
fn file_colours_are_refined_with_the_mesh() {
    // An affine colour field c(p) = A p + b: every scheme's weights sum to 1,
    // so the refined colours must be c at the refined points, whatever the
    // weights are.
    use crate::app::display::Coloring;
    let field =
        |p: Vec3| Vec3::new(0.5 + 0.2 * p.x + 0.1 * p.y, 0.5 + 0.2 * p.y + 0.1 * p.z, 0.5 + 0.2 * p.z + 0.1 * p.x);
    let corners =
        [Vec3::new(1.0, 1.0, 1.0), Vec3::new(1.0, -1.0, -1.0), Vec3::new(-1.0, 1.0, -1.0), Vec3::new(-1.0, -1.0, 1.0)];
    let mut obj = String::new();
    for p in corners {
        let c = field(p);
        obj += &format!("v {} {} {} {} {} {}\n", p.x, p.y, p.z, c.x, c.y, c.z);
    }
    obj += "f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n";
    let dir = common::scratch_dir("viewer-col");
    let f = dir.join("tet.obj");
    std::fs::write(&f, obj).unwrap();
    let mut v = Viewer::new();
    v.doc.request.level = 2;
    v.apply(Command::Open(f));
    settle(&mut v);
    assert!(v.doc.status.error.is_none(), "{:?}", error_text(&v));
    set_display(&mut v, |d| d.coloring = Coloring::File);
    let got = v.doc.model.result.colors.clone().expect("file colours shown");
    let positions = &v.doc.model.result.shown.mesh.positions;
    assert_eq!(got.len(), positions.len());
    assert_eq!(positions.len(), 4 + 6 + 24, "level 2 of a tetrahedron");
    for (i, (c, p)) in got.iter().zip(positions.iter()).enumerate() {
        assert!((*c - field(*p)).length() < 1e-5, "vertex {i} at {p}: colour {c}, field {}", field(*p));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn texture_coordinates_of_the_file_follow_the_levels() {
    use crate::app::display::Coloring;
    let mut v = Viewer::new();
    v.doc.request.level = 2;
    v.apply(Command::Open(common::model_path("cube_uv.obj")));
    settle(&mut v);
    let attrs = &v.doc.model.attrs;
    assert_eq!(attrs.file.uv.as_ref().map(Vec::len), Some(36));
    assert_eq!(attrs.refined.uv.as_ref().map(Vec::len), Some(3 * v.doc.model.result.shown.mesh.ct.num_triangles()));
    assert_eq!(attrs.file.colors.as_ref().map(Vec::len), Some(8));
    set_display(&mut v, |d| d.coloring = Coloring::Checker);
    assert!(v.doc.model.result.colors.is_none(), "the checker is drawn from the UVs, not vertex colours");
    assert!("checker".parse::<Coloring>().is_ok() && "plaid".parse::<Coloring>().is_err());
}

#[test]
fn the_cursor_maps_into_the_viewport_under_it() {
    let rect = egui::Rect::from_min_size(egui::pos2(100.0, 0.0), egui::vec2(400.0, 200.0));
    let at = |side, x, y| crate::app::view::cursor_ndc(rect, side, egui::pos2(x, y));
    assert_eq!(at(false, 100.0, 0.0), glam::Vec2::new(-1.0, 1.0));
    assert_eq!(at(false, 500.0, 200.0), glam::Vec2::new(1.0, -1.0));
    // side by side: each half has its own NDC square
    assert_eq!(at(true, 200.0, 100.0), glam::Vec2::new(0.0, 0.0), "centre of the left half");
    assert_eq!(at(true, 400.0, 100.0), glam::Vec2::new(0.0, 0.0), "centre of the right half");
    assert_eq!(at(true, 500.0, 0.0), glam::Vec2::new(1.0, 1.0));
}

#[test]
fn snapping_to_the_limit_follows_warrens_beta() {
    // The snapped points must be where repeated subdivision with the same
    // (Warren's) weights converges: computed here by subdividing, not by the
    // limit masks the viewer uses. Valence 5 tells Loop's beta from Warren's.
    let ico = crate::mesh::shapes::icosahedron();
    let warren = crate::Options { loop_beta: crate::LoopBeta::Warren, ..Default::default() };
    let converged = crate::subdivide(&ico, Scheme::Loop, 6, &warren).unwrap().0;
    let mut v = Viewer::new();
    v.doc.adopt("icosahedron.obj".into(), ico.clone(), None);
    v.apply(Command::Subdivide(Request { scheme: Scheme::Loop, level: 0, opts: warren, ..v.doc.request }));
    settle(&mut v);
    set_display(&mut v, |d| d.snap_limit = true);
    for i in 0..ico.positions.len() {
        let d = v.doc.model.result.shown.mesh.positions[i].distance(converged.positions[i]);
        assert!(d < 1e-4, "vertex {i} snapped {d} away from the Warren limit");
    }
}

#[test]
fn a_new_model_is_framed_and_an_edit_keeps_the_view() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    frame(&ctx, &mut v, vec![]);
    let fitted = v.view.camera;
    v.apply(Command::Zoom { factor: 0.7, cursor: glam::Vec2::ZERO, aspect: 1.0 });
    let zoomed = v.view.camera;
    assert!(zoomed.distance < fitted.distance);
    v.apply(Command::Smooth(3));
    frame(&ctx, &mut v, vec![]);
    assert_eq!(v.view.camera, zoomed, "smoothing the control mesh keeps the view");
    v.apply(Command::Open(common::model_path("cube.obj")));
    // the smoothing is unsaved: opening another model asks first
    assert!(v.doc.edit.pending.is_some());
    v.apply(Command::Answer(crate::app::edit::Answer::Discard));
    settle(&mut v);
    frame(&ctx, &mut v, vec![]);
    let mut framed = zoomed;
    let aspect = crate::app::view::viewport_aspect(v.view.scene_rect, false);
    framed.fit_points(&v.doc.model.result.shown.mesh.positions, aspect);
    assert_eq!(v.view.camera, framed, "a new model is framed");
    assert_ne!(v.view.camera.distance, zoomed.distance);
}

/// Fit (and the first view of a model) centres the model in the 3D area
/// beside the panel and fills the tighter of its width and height, at any
/// window size and aspect, in perspective and orthographically.
#[test]
fn fit_centres_the_model_beside_the_panel_at_every_window_size() {
    use crate::render::camera::FIT_FILL;
    let sizes = [(1024.0, 768.0), (1280.0, 800.0), (700.0, 1000.0), (480.0, 900.0), (1800.0, 500.0)];
    for model in ["bundled:torus.obj", "bundled:tetrahedron.obj", "bundled:critter.obj"] {
        for (w, h) in sizes {
            for orthographic in [false, true] {
                let ctx = egui::Context::default();
                let mut v = Viewer::new();
                v.apply(Command::Open(model.into()));
                settle(&mut v);
                v.apply(Command::SetOrthographic(orthographic));
                frame_sized(&ctx, &mut v, egui::vec2(w, h), vec![]);
                v.apply(Command::Orbit(glam::Vec2::new(37.0, -12.0)));
                frame_sized(&ctx, &mut v, egui::vec2(w, h), vec![key(egui::Key::F)]);
                let rect = v.view.scene_rect;
                let what = format!("{model} in {w}x{h}, orthographic {orthographic}");
                assert!(rect.left() > 100.0 && (rect.right() - w).abs() < 1.0, "{what}: the area beside the panel");
                let aspect = crate::app::view::viewport_aspect(rect, false);
                let (mut lo, mut hi) = (glam::Vec2::splat(f32::MAX), glam::Vec2::splat(f32::MIN));
                for &p in &v.doc.model.result.shown.mesh.positions {
                    let q = v.view.camera.project(p, aspect).truncate();
                    (lo, hi) = (lo.min(q), hi.max(q));
                }
                assert!(
                    lo.min_element() >= -FIT_FILL - 1e-3 && hi.max_element() <= FIT_FILL + 1e-3,
                    "{what}: {lo} {hi}"
                );
                assert!((lo + hi).abs().max_element() < 5e-3, "{what}: not centred: {lo} {hi}");
                assert!(((hi - lo) / 2.0).max_element() > FIT_FILL - 5e-3, "{what}: too small: {lo} {hi}");
            }
        }
    }
}

#[test]
fn the_first_window_fits_the_screen() {
    use crate::app::window::initial_size;
    assert_eq!(initial_size(None), (1280.0, 800.0));
    assert_eq!(initial_size(Some((1920.0, 1080.0))), (1280.0, 800.0));
    for (mw, mh) in [(1024.0, 768.0), (800.0, 600.0), (1280.0, 800.0), (1366.0, 768.0), (640.0, 1136.0)] {
        let (w, h) = initial_size(Some((mw, mh)));
        assert!(w <= mw && h <= mh, "{w}x{h} on a {mw}x{mh} screen");
        assert!((w / h - 1.6).abs() < 0.01 || w == 320.0 || h == 240.0, "{w}x{h} keeps the aspect");
    }
}

#[test]
fn creases_are_tagged_edited_drawn_split_and_saved_from_the_viewer() {
    let mut v = Viewer::new();
    v.apply(Command::Open("bundled:cube.obj".into()));
    settle(&mut v);
    // the angle tags the cube's 12 edges (not the diagonals)
    v.apply(Command::AutoCrease(40.0));
    let ct = &v.doc.model.control.mesh.ct;
    let s = crate::subdiv::rules::features::summary(ct, Default::default());
    assert_eq!((s.sharp_edges, s.corners), (12, 8));
    // every change re-subdivides on the worker: the cube stays a cube
    subdivide(&mut v, Scheme::Loop, 2);
    settle(&mut v);
    let raw = &v.doc.model.raw.mesh;
    for q in &raw.positions {
        assert!((0..3).any(|k| q[k].abs() < 1e-5 || (q[k] - 1.0).abs() < 1e-5), "{q} left the cube's faces");
    }
    // drawn cut open along the creases: a point on a cube edge has one copy
    // per side, each with its own face's normal
    let shown = &v.doc.model.result.shown;
    assert!(shown.mesh.positions.len() > raw.positions.len(), "the creases are cut for shading");
    let mid_edge = (0..shown.mesh.positions.len())
        .find(|&i| {
            let q = shown.mesh.positions[i];
            (q - Vec3::new(0.5, 0.0, 0.0)).length() < 1e-5
        })
        .expect("the midpoint of the cube edge (0,0,0)-(1,0,0)");
    let copies: Vec<Vec3> = (0..shown.mesh.positions.len())
        .filter(|&i| shown.mesh.positions[i].distance(shown.mesh.positions[mid_edge]) < 1e-6)
        .map(|i| shown.normals[i])
        .collect();
    assert_eq!(copies.len(), 2, "one vertex per side of the edge");
    for n in &copies {
        assert!(n.abs().max_element() > 0.999, "a side's normal is its face's ({n})");
    }
    // the slider sets a picked edge's sharpness; a click toggles it
    let c = v
        .doc
        .model
        .control
        .mesh
        .ct
        .edge_owners()
        .find(|&c| v.doc.model.control.mesh.ct.edge_sharpness(c) > 0.0)
        .unwrap();
    v.apply(Command::SetSharpness { corner: c, sharpness: 2.5 });
    assert_eq!(v.doc.model.control.mesh.ct.edge_sharpness(c), 2.5);
    v.apply(Command::ClearCreases);
    assert!(v.doc.model.control.mesh.ct.sharpness().is_none());
    set_display(&mut v, |d| {
        d.pick = true;
        d.click_creases = true;
    });
    let cube = v.doc.model.control.mesh.clone();
    // a ray onto the middle of the edge (0,0,0)-(1,0,0), from below-front
    let origin = Vec3::new(0.5, -3.0, -3.0);
    let dir = (Vec3::new(0.5, 0.0, 0.0) - origin).normalize();
    v.apply(Command::Pick { origin, dir });
    let picked = (*v.doc.model.picked).expect("the ray picks an edge");
    assert_eq!(v.doc.model.control.mesh.ct.edge_sharpness(picked), crate::mesh::sharpness::INFINITE);
    assert_eq!(cube.ct.edge_sharpness(picked), 0.0);
    v.apply(Command::Pick { origin, dir });
    assert_eq!(v.doc.model.control.mesh.ct.edge_sharpness(picked), 0.0, "a second click smooths it again");
    v.apply(Command::Pick { origin, dir });
    // saved with its tag
    let path = common::scratch_dir("viewer-creases").join("control.obj");
    v.apply(Command::SaveControl(path.clone()));
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("t crease 2/1/0 ")).count(), 1, "{text}");
    assert!(crate::bundled::load(&path).unwrap().ct.sharpness().is_some());
}

#[test]
fn every_mesh_format_opens_in_the_viewer_with_its_colours() {
    // what a dropped file or the browser hands to Command::Open
    let dir = common::scratch_dir("viewer-formats");
    let (mesh, mut attrs) = common::load_with_attributes(&common::model_path("cube_uv.obj"));
    attrs.colors = Some(mesh.positions.iter().map(|p| p.clamp(glam::Vec3::ZERO, glam::Vec3::ONE)).collect());
    for ext in crate::io::write_extensions() {
        let path = dir.join(format!("cube.{ext}"));
        crate::io::save_with(&path, &mesh, &attrs).unwrap();
        let mut v = Viewer::new();
        v.apply(Command::Open(path));
        settle(&mut v);
        assert!(v.doc.status.error.is_none(), "{ext}: {:?}", error_text(&v));
        assert_eq!(v.doc.model.control.topo.faces, 12, "{ext}");
        let keeps = matches!(ext, "obj" | "glb" | "ply" | "off" | "usda" | "usdc" | "usdz");
        assert_eq!(v.doc.model.attrs.file.colors.is_some(), keeps, "{ext}: colours");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn wire_edges_and_screenshot_settings_reach_the_look_and_the_view() {
    use crate::render::{Shot, WireEdges};
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    frame(&ctx, &mut v, vec![key(egui::Key::W)]);
    assert_eq!(v.doc.display.look().wire_edges, WireEdges::All);
    set_display(&mut v, |d| d.wire_edges = WireEdges::UpTo(0));
    assert_eq!(v.doc.display.look().wire_edges, WireEdges::UpTo(0));
    // the panel (with the wire's edge choice shown) keeps the choice
    frame(&ctx, &mut v, vec![]);
    assert_eq!(v.doc.display.wire_edges, WireEdges::UpTo(0));
    v.apply(Command::SetShot(Shot { scale: 3, transparent: true }));
    assert_eq!(v.view.shot, Shot { scale: 3, transparent: true });
    frame(&ctx, &mut v, vec![key(egui::Key::P)]);
    assert!(v.view.screenshot, "P asks for a screenshot");
}

#[test]
fn the_headless_viewer_plays_the_animation_on_its_own_clock() {
    // the document owns time: no window, no GPU mirror
    let mut v = Viewer::new();
    v.apply(Command::TogglePlay);
    settle(&mut v);
    assert!(v.doc.anim.playing(), "the first plan starts playing");
    let mut last: Option<(usize, Vec<glam::Vec3>)> = None;
    for _ in 0..4 {
        assert!(v.advance(0.1), "a tenth of a second moves the frame");
        let shown = v.doc.anim.shown.expect("a current frame");
        assert!(shown.on_cpu, "without a GPU the document evaluates the frame");
        let p = v.doc.anim.playback.as_ref().unwrap();
        let pos = p.player.evaluated().0.to_vec();
        assert_eq!(pos.len(), p.player.topology().num_vertices());
        if let Some((frame, before)) = &last {
            assert_ne!(shown.frame, *frame);
            assert_ne!(&pos, before, "the surface moves from frame to frame");
        }
        last = Some((shown.frame, pos));
    }
    // paused, time changes nothing; a step does
    v.apply(Command::TogglePlay);
    assert!(!v.advance(0.5));
    let before = v.doc.anim.shown.unwrap().frame;
    v.apply(Command::Step(1));
    assert!(v.advance(0.0));
    let frames = v.doc.anim.playback.as_ref().unwrap().clock.frames();
    assert_eq!(v.doc.anim.shown.unwrap().frame, (before + 1) % frames);
}

#[test]
fn the_gpu_mirror_evaluates_the_frames_with_the_exports_animated_mesh() {
    // the window's sync without a window: the mirror builds the compute
    // passes of the plan, and the frames after the first are evaluated
    // there (not by the document) into the drawn buffers, at level 0 (the
    // control points drawn as they are) as at level 2
    let off = match crate::render::Offscreen::new(8, 8) {
        Ok(o) => o,
        Err(e) if std::env::var_os("SUBDIV_REQUIRE_GPU").is_none() => return eprintln!("SKIPPED: {e}"),
        Err(e) => panic!("SUBDIV_REQUIRE_GPU is set but {e}"),
    };
    let (device, queue) = (&off.gpu.device, &off.gpu.queue);
    for level in [0, 2] {
        let mut v = Viewer::new();
        subdivide(&mut v, Scheme::Loop, level);
        settle(&mut v);
        v.apply(Command::TogglePlay);
        settle(&mut v);
        let mut scene = super::gpu_scene::GpuScene::default();
        let mut on_gpu = Vec::new();
        for _ in 0..5 {
            assert!(v.advance(0.1), "a tenth of a second moves the frame");
            let report = scene.sync(device, queue, &v.doc, 0.05);
            v.apply(Command::Gpu(Box::new(report)));
            let shown = v.doc.anim.shown.expect("a current frame");
            if shown.on_cpu {
                continue;
            }
            assert!(v.doc.anim.on_gpu, "the mirror says it evaluated the frame");
            let drawn = scene.anim.as_ref().expect("the animated mesh").positions(device, queue).unwrap();
            let p = v.doc.anim.playback.as_mut().unwrap();
            let cpu = p.player.evaluate(shown.frame).0;
            let scale = cpu.iter().fold(1.0f32, |s, q| s.max(q.abs().max_element()));
            assert_eq!(drawn.len(), cpu.len());
            let close = drawn.iter().zip(cpu).all(|(g, c)| (*g - *c).abs().max_element() <= 1e-5 * scale);
            assert!(close, "level {level} frame {}: the drawn positions are not the frame's", shown.frame);
            on_gpu.push(shown.frame);
        }
        assert!(on_gpu.len() >= 4, "level {level}: only frames {on_gpu:?} were evaluated on the GPU");
    }
}

#[test]
fn catmull_clark_snaps_and_shades_with_its_own_limit() {
    // A quad cube with a crease (so the result is drawn cut open) at level
    // 1: snapped points are the limit masks' (tests/catmark_limit.rs checks
    // those against OpenSubdiv and convergence), the limit normals are unit
    // and, on the smooth part, those of the mesh five levels finer.
    let text = "v 0 0 0\nv 0 0 1\nv 0 1 0\nv 0 1 1\nv 1 0 0\nv 1 0 1\nv 1 1 0\nv 1 1 1\n\
                f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\nt crease 2/1/0 0 1 10\n";
    let cube = crate::io::read(
        crate::io::Source::Bytes { bytes: text.as_bytes(), name: "creased_cube.obj", folder: None },
        &Default::default(),
    )
    .expect("the cube")
    .mesh;
    let opts = crate::Options::default();
    let level1 = crate::subdivide(&cube, Scheme::CatmullClark, 1, &opts).unwrap().0;
    let converged = crate::subdivide(&cube, Scheme::CatmullClark, 6, &opts).unwrap().0;
    let again = crate::subdivide(&level1, Scheme::CatmullClark, 5, &opts).unwrap().0;
    assert!(
        again.positions.iter().zip(&converged.positions).all(|(a, b)| a.distance(*b) < 1e-5),
        "levels go on from a drawn level"
    );
    let mut v = Viewer::new();
    v.doc.adopt("creased_cube.obj".into(), cube, None);
    v.apply(Command::Subdivide(Request { scheme: Scheme::CatmullClark, level: 1, opts, ..v.doc.request }));
    settle(&mut v);
    assert!(v.doc.model.raw.creased.is_some(), "drawn cut open along the crease");
    set_display(&mut v, |d| {
        d.snap_limit = true;
        d.normal_mode = crate::app::display::NormalMode::Limit;
    });
    let raw = &v.doc.model.raw.mesh;
    let shown = &v.doc.model.result.shown;
    let limit =
        crate::subdiv::eval::catmark_limit::limit_frames(&crate::mesh::poly::PolyMesh::from_mesh(raw), &opts).unwrap();
    for (i, f) in limit.iter().enumerate() {
        assert!(shown.mesh.positions[i].distance(f.position) < 1e-6, "vertex {i} snapped to its limit");
    }
    assert!(shown.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4), "unit normals");
    let fine_normals = converged.vertex_normals();
    let smooth = (0..raw.positions.len()).filter(|&i| raw.ct.sharpness().is_none_or(|s| s.vertex(i as u32) == 0.0));
    let mut checked = 0;
    for i in smooth {
        // the cut mesh numbers the uncut vertices first
        if shown.normals[i].dot(fine_normals[i]) > 0.9999 {
            checked += 1;
        }
    }
    assert!(
        checked > raw.positions.len() / 2,
        "{checked} of {} normals agree with the converged mesh",
        raw.positions.len()
    );
}

#[test]
fn materials_are_drawn_with_their_textures_sampled_per_pixel() {
    use crate::app::display::Coloring;
    let mut off = match crate::render::Offscreen::new(256, 256) {
        Ok(o) => o,
        Err(e) if std::env::var_os("SUBDIV_REQUIRE_GPU").is_none() => return eprintln!("SKIPPED: {e}"),
        Err(e) => panic!("SUBDIV_REQUIRE_GPU is set but {e}"),
    };
    // a cube, each face's texture red on the left half and green on the right
    let dir = common::scratch_dir("viewer-texture");
    let obj = "mtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
               vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl t\nf 5/1 6/2 7/3 8/4\nf 2/1 1/2 4/3 3/4\nf 6/1 2/2 3/3 7/4\n\
               f 1/1 5/2 8/3 4/4\nf 8/1 7/2 3/3 4/4\nf 1/1 2/2 6/3 5/4\n";
    std::fs::write(dir.join("c.obj"), obj).unwrap();
    std::fs::write(dir.join("c.mtl"), "newmtl t\nKd 1 1 1\nmap_Kd t.png\n").unwrap();
    let png = image::RgbImage::from_fn(64, 64, |x, _| image::Rgb(if x < 32 { [255, 0, 0] } else { [0, 255, 0] }));
    png.save(dir.join("t.png")).unwrap();
    let mut v = Viewer::new();
    v.doc.request.level = 1;
    v.apply(Command::Open(dir.join("c.obj")));
    settle(&mut v);
    set_display(&mut v, |d| d.coloring = Coloring::Material);
    settle(&mut v);
    let mut scene = super::gpu_scene::GpuScene::default();
    scene.sync(&off.gpu.device, &off.gpu.queue, &v.doc, 0.05);
    let mesh = scene.result.as_ref().expect("the result is uploaded");
    let uploads = mesh.materials().map(|m| (m.uploaded(), m.mip_level_counts()));
    assert_eq!(uploads, Some((1, vec![7])), "one texture, 64 down to 1");
    let (lo, hi) = v.doc.model.control.mesh.bounds();
    let cam = crate::render::Camera::framing(lo, hi, 1.0);
    let img = off.render_one(cam, mesh, None, v.doc.display.look()).unwrap();
    let count = |f: &dyn Fn(i32, i32, i32) -> bool| {
        img.pixels().filter(|p| f(i32::from(p.0[0]), i32::from(p.0[1]), i32::from(p.0[2]))).count()
    };
    // mostly red or green (lit, highlighted or shadowed), and red and green alike
    let red = count(&|r, g, b| r > 30 && 3 * (r - g.max(b)) > r);
    let green = count(&|r, g, b| g > 30 && 3 * (g - r.max(b)) > g);
    let yellow = count(&|r, g, b| r > 60 && g > 60 && 3 * (r - g).abs() < r.max(g) && 4 * b < 3 * r.min(g));
    assert!(red > 2000 && green > 2000, "red {red}, green {green}");
    // the two meet in a pixel or two: interpolating between samples at the
    // corners blended a band of yellow across every face
    assert!(yellow < (red + green) / 12, "{yellow} yellowish pixels beside {red} red and {green} green");
    // the next level takes the texture over rather than uploading it again
    subdivide(&mut v, Scheme::Loop, 2);
    settle(&mut v);
    scene.sync(&off.gpu.device, &off.gpu.queue, &v.doc, 0.05);
    let next = scene.result.as_ref().and_then(crate::render::GpuMesh::materials).expect("materials at level 2");
    assert_eq!((next.uploaded(), next.mip_level_counts()), (0, vec![7]));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A click (press, then release in the next frame) at `pos`, half a second
/// (of egui's frame clock) after the last one: not a double click.
fn click(ctx: &egui::Context, v: &mut Viewer, pos: egui::Pos2) {
    for _ in 0..30 {
        frame(ctx, v, vec![]);
    }
    let button = |pressed| egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: Default::default(),
    };
    frame(ctx, v, vec![egui::Event::PointerMoved(pos), button(true)]);
    frame(ctx, v, vec![button(false)]);
}

#[test]
fn a_click_picks_a_point_of_the_surface_and_escape_or_empty_space_clears_it() {
    use crate::app::probe::{Target, ray_at};
    use crate::subdiv::pick::{ControlFace, Limit};
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    subdivide(&mut v, Scheme::Loop, 2);
    settle(&mut v);
    frame(&ctx, &mut v, vec![]);
    let rect = v.view.scene_rect;
    // the middle of the 3D area: the framed tetrahedron's centre is behind it
    let at = rect.center() + egui::vec2(7.0, -5.0);
    click(&ctx, &mut v, at);
    let probe = v.doc.model.probe.clone().expect("a click on the surface picks it");
    assert_eq!(probe.ray.target, Target::Result);
    let p = &probe.pick;
    assert_eq!((p.scheme, p.level), (Scheme::Loop, 2));
    let ControlFace::Triangle { face, u, v: w } = p.face else { panic!("Loop names a triangle") };
    assert!(face < 4 && u >= 0.0 && w >= 0.0 && u + w <= 1.0 + 1e-9, "{:?}", p.face);
    // the same pick as the library's for the same pixel
    let again = v.doc.cast(ray_at(&v.view.camera, rect, false, at)).unwrap().expect("hits");
    assert_eq!(&again, p);
    // a closed Loop surface has its exact limit everywhere, near the level-2 hit
    let Limit::Exact(s) = &p.limit else { panic!("{:?}", p.limit) };
    assert!((s.position - p.point.as_dvec3()).length() < 0.1, "{} from {}", s.position, p.point);
    assert_eq!(p.vertex.valence, 3, "every tetrahedron vertex has valence 3");
    assert!(p.to_string().contains(&format!("control face: {face}")));

    // a new level picks again along the same ray
    subdivide(&mut v, Scheme::Loop, 3);
    settle(&mut v);
    let p3 = v.doc.model.probe.as_ref().expect("still picked").pick.clone();
    assert_eq!(p3.level, 3);
    let ControlFace::Triangle { face: f3, u: u3, v: v3 } = p3.face else { panic!("a triangle") };
    // the level-3 surface lies nearer the limit: about the same parameters
    assert_eq!(f3, face, "the same ray lands in the same control face");
    assert!((u3 - u).abs() < 0.05 && (v3 - w).abs() < 0.05, "({u}, {w}) at level 2, ({u3}, {v3}) at 3");

    // Escape clears; so does a click on empty space
    frame(&ctx, &mut v, vec![key(egui::Key::Escape)]);
    assert!(v.doc.model.probe.is_none(), "Escape clears the pick");
    click(&ctx, &mut v, at);
    assert!(v.doc.model.probe.is_some());
    click(&ctx, &mut v, rect.right_top() + egui::vec2(-3.0, 3.0));
    assert!(v.doc.model.probe.is_none(), "a click on empty space clears the pick");
}

#[test]
fn a_pick_far_from_the_origin_is_evaluated_from_the_files_own_digits() {
    use crate::subdiv::pick::Limit;
    use glam::DVec3;
    // an octahedron far out, its points with more digits than f32 keeps
    // there (its spacing is 1/128 at 1e5)
    let at = DVec3::new(1.0e5 + 0.123_456_789, -2.0e5 + 0.987_654_321, 1.5e5 + 0.000_5);
    let unit =
        [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
    let exact: Vec<DVec3> = unit.iter().map(|u| at + DVec3::from_array(*u) * 5.0).collect();
    let faces = "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
    let text: String =
        exact.iter().map(|p| format!("v {:.9} {:.9} {:.9}\n", p.x, p.y, p.z)).collect::<String>() + faces;
    let path = common::scratch_dir("far-pick").join("far.obj");
    std::fs::write(&path, text).unwrap();
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    v.apply(Command::Open(path));
    settle(&mut v);
    assert_eq!(v.doc.model.precise_control(), Some(&exact[..]), "the file's digits are kept");
    subdivide(&mut v, Scheme::Loop, 2);
    settle(&mut v);
    frame(&ctx, &mut v, vec![]);
    let at = v.view.scene_rect.center() + egui::vec2(4.0, -3.0);
    click(&ctx, &mut v, at);
    let p = v.doc.model.probe.clone().expect("a click on the surface picks it").pick;
    let crate::subdiv::pick::ControlFace::Triangle { face, u, v: w } = p.face else { panic!("Loop names a triangle") };
    let Limit::Exact(s) = &p.limit else { panic!("{:?}", p.limit) };
    // the limit from the file's digits, in f64 throughout
    let control = &v.doc.model.control.mesh;
    let ev = crate::Evaluator::new_f64(control, &exact, Scheme::Loop, &Default::default()).unwrap();
    let want = ev.eval(face as usize, u, w).unwrap();
    assert!((s.position - want.position).length() < 1e-9, "{} against {}", s.position, want.position);
    // from the f32 points the limit is off by what f32 loses out there
    let rounded = crate::Evaluator::new(control, Scheme::Loop, &Default::default()).unwrap();
    let off = (rounded.eval(face as usize, u, w).unwrap().position - want.position).length();
    assert!(off > 1e-3, "f32 points would be {off} off: the test means something");
    // a moved vertex makes a new control mesh: its f32 points are the truth then
    v.doc.model.control.set(crate::app::model::Shown::new(std::sync::Arc::new((**control).clone())));
    assert!(v.doc.model.precise_control().is_none());
}

#[test]
fn side_by_side_the_left_viewport_picks_the_control_mesh() {
    use crate::app::probe::Target;
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    subdivide(&mut v, Scheme::Butterfly, 2);
    settle(&mut v);
    set_display(&mut v, |d| d.side_by_side = true);
    frame(&ctx, &mut v, vec![]);
    let rect = v.view.scene_rect;
    let half = rect.width() / 4.0;
    click(&ctx, &mut v, rect.center() - egui::vec2(half, 0.0));
    let probe = v.doc.model.probe.clone().expect("the control mesh is hit");
    assert_eq!((probe.ray.target, probe.pick.level), (Target::Control, 0));
    click(&ctx, &mut v, rect.center() + egui::vec2(half, 0.0));
    let probe = v.doc.model.probe.clone().expect("the result is hit");
    assert_eq!((probe.ray.target, probe.pick.level), (Target::Result, 2));
    let text = probe.pick.to_string();
    assert!(text.contains("limit evaluation: not available for butterfly"), "{text}");
    // with edge picking on, a click picks a control edge instead
    set_display(&mut v, |d| d.pick = true);
    v.apply(Command::ClearSurfacePick);
    click(&ctx, &mut v, rect.center() + egui::vec2(half, 0.0));
    assert!(v.doc.model.probe.is_none());
    assert!(v.doc.model.picked.is_some());
}

#[test]
fn a_creased_result_is_picked_and_its_faces_have_their_exact_limit() {
    use crate::app::probe::{Ray, Target};
    use crate::subdiv::pick::Limit;
    let mut v = Viewer::new();
    v.apply(Command::Open(common::model_path("cube.obj")));
    settle(&mut v);
    v.apply(Command::AutoCrease(40.0));
    subdivide(&mut v, Scheme::Loop, 2);
    settle(&mut v);
    assert!(v.doc.model.result.shown.creased.is_none() && v.doc.model.raw.creased.is_some(), "drawn cut open");
    // onto the middle of the cube's top from above
    let (lo, hi) = v.doc.model.control.mesh.bounds();
    let top = Vec3::new((lo.x + hi.x) / 2.0 + 0.1, hi.y + 3.0, (lo.z + hi.z) / 2.0 - 0.05);
    v.apply(Command::PickSurface(Ray { origin: top, dir: -Vec3::Y, target: Target::Result }));
    let p = &v.doc.model.probe.as_ref().expect("the top is hit").pick;
    // every crease and corner is infinitely sharp: the top's limit is flat
    let Limit::Exact(s) = &p.limit else { panic!("a face at a crease is evaluated: {:?}", p.limit) };
    assert!((s.position.y - f64::from(hi.y)).abs() < 1e-6 && s.normal.y > 1.0 - 1e-9, "{s:?}");
    assert!(p.to_string().contains("limit position"), "{p}");
    // in the animation mode the drawn frame is not the static level: no pick
    v.apply(Command::TogglePlay);
    v.apply(Command::PickSurface(Ray { origin: top, dir: -Vec3::Y, target: Target::Result }));
    assert!(v.doc.status.notice.as_deref().is_some_and(|n| n.contains("animation")));
}

#[test]
fn isolines_live_in_the_display_and_only_change_the_look() {
    use crate::app::display::{Coloring, Isolines};
    use crate::subdiv::eval::color::CurvatureKind;
    let mut v = Viewer::new();
    v.apply(Command::Open(common::model_path("torus.obj")));
    settle(&mut v);
    subdivide(&mut v, Scheme::Loop, 2);
    settle(&mut v);
    set_display(&mut v, |d| d.coloring = Coloring::Curvature(CurvatureKind::Gaussian));
    settle(&mut v);
    let result = &v.doc.model.result;
    let values = result.values.clone().expect("curvature values, coloured per pixel");
    assert!(result.colors.is_none());
    assert_eq!(values.len(), result.shown.mesh.positions.len());
    assert!(values.iter().any(|&t| t > 0.2) && values.iter().any(|&t| t < -0.2), "K of both signs on a torus");
    let (version, look) = (result.version(), v.doc.display.look());
    assert!(look.values && look.colors);
    assert_eq!(look.isolines, 0, "off by default");
    set_display(&mut v, |d| d.isolines = Isolines { on: true, count: 7 });
    assert_eq!(v.doc.model.result.version(), version, "turning isolines on does not recompute the curvature");
    assert_eq!(v.doc.display.look().isolines, 7);
    set_display(&mut v, |d| d.coloring = Coloring::Shells);
    settle(&mut v);
    let look = v.doc.display.look();
    assert_eq!((look.values, look.isolines), (false, 0), "no isolines on colours that are not values");
    assert!(v.doc.display.isolines.on, "the setting stays for the next curvature colouring");
    // the GPU mirror draws them from the document: the same view with and
    // without differs by dark pixels only
    let mut off = match crate::render::Offscreen::new(200, 200) {
        Ok(o) => o,
        Err(e) if std::env::var_os("SUBDIV_REQUIRE_GPU").is_none() => return eprintln!("SKIPPED: {e}"),
        Err(e) => panic!("SUBDIV_REQUIRE_GPU is set but {e}"),
    };
    set_display(&mut v, |d| d.coloring = Coloring::Curvature(CurvatureKind::Mean));
    settle(&mut v);
    let mut scene = super::gpu_scene::GpuScene::default();
    scene.sync(&off.gpu.device, &off.gpu.queue, &v.doc, 0.05);
    let mesh = scene.result.as_ref().expect("the result is uploaded");
    let (lo, hi) = v.doc.model.control.mesh.bounds();
    let cam = crate::render::Camera::framing(lo, hi, 1.0);
    let with = off.render_one(cam, mesh, None, v.doc.display.look()).unwrap();
    let plain = crate::render::Look { isolines: 0, ..v.doc.display.look() };
    let without = off.render_one(cam, mesh, None, plain).unwrap();
    let (mut darker, mut lighter) = (0, 0);
    for (a, b) in with.pixels().zip(without.pixels()) {
        let sum = |p: &image::Rgba<u8>| p.0[..3].iter().map(|&c| i32::from(c)).sum::<i32>();
        darker += usize::from(sum(a) + 30 < sum(b));
        lighter += usize::from(sum(a) > sum(b) + 30);
    }
    assert!(darker > 200 && lighter == 0, "{darker} pixels darkened by isolines, {lighter} lightened");
}

#[test]
fn catmull_clark_colours_by_curvature_over_a_range_the_display_sets() {
    use crate::app::display::Coloring;
    use crate::app::panel::range_field;
    use crate::subdiv::eval::color::{CurvatureKind, HalfWidth};
    let mut v = Viewer::new();
    v.apply(Command::Open(common::model_path("critter.obj")));
    settle(&mut v);
    subdivide(&mut v, Scheme::CatmullClark, 2);
    settle(&mut v);
    assert_eq!(v.doc.model.made.scheme, Scheme::CatmullClark);
    // (the notice of the quads kept for Catmull-Clark)
    v.apply(Command::DismissNotice);
    set_display(&mut v, |d| d.coloring = Coloring::Curvature(CurvatureKind::Mean));
    settle(&mut v);
    let status = (error_text(&v), v.doc.status.notice.clone());
    assert_eq!(status, (None, None), "coloured without an error or a notice");
    let result = &v.doc.model.result;
    let auto = result.values.clone().expect("Catmull-Clark's curvature, coloured per pixel");
    assert_eq!(auto.len(), result.shown.mesh.positions.len());
    let scale = result.scale.expect("the range in use");
    assert!(!scale.set && scale.half > 0.0 && scale.describe().contains("auto"), "{scale:?}");
    // the default range colours most of the critter visibly, both signs
    let tinted = auto.iter().filter(|t| t.abs() >= 0.25).count();
    assert!(tinted * 3 > auto.len(), "{tinted} of {} vertices tinted", auto.len());
    assert!(auto.iter().any(|&t| t > 0.5) && auto.iter().any(|&t| t < -0.25), "convex and saddle regions");
    // the panel's field: empty or auto is the default, else a number above 0
    assert_eq!(range_field(" "), Ok(None));
    assert_eq!(range_field("auto"), Ok(None));
    let wide = range_field("2.5e1").unwrap().expect("a range");
    assert_eq!(wide, HalfWidth::new(25.0).unwrap());
    for bad in ["0", "-3", "NaN", "wide"] {
        assert!(range_field(bad).is_err_and(|e| e.contains("above 0")), "{bad}");
    }
    // a range set through the display colours the same curvature over it
    let set = HalfWidth::new(2.0 * scale.half).unwrap();
    set_display(&mut v, |d| d.range = Some(set));
    let result = &v.doc.model.result;
    let halved = result.values.clone().expect("still coloured");
    assert_eq!(result.scale.map(|s| (s.half, s.set)), Some((set.get(), true)));
    assert!(result.scale.unwrap().describe().ends_with("(set)"));
    for (a, b) in auto.iter().zip(&halved) {
        assert!(a.is_nan() && b.is_nan() || (a / 2.0 - b).abs() < 1e-5, "{a} over a range twice as wide: {b}");
    }
    set_display(&mut v, |d| d.range = None);
    assert_eq!(v.doc.model.result.scale, Some(scale), "back to the default");
    // the panel draws the curvature's bar and field
    let ctx = egui::Context::default();
    frame(&ctx, &mut v, vec![]);
    // a scheme without an exact limit: the result uncoloured, the reason on
    // the status line, no error
    subdivide(&mut v, Scheme::Bilinear, 2);
    settle(&mut v);
    assert!(v.doc.model.result.values.is_none());
    let notice = v.doc.status.notice.clone().expect("why there are no curvature colours");
    assert!(notice.contains("loop and catmull-clark") && notice.contains("bilinear"), "{notice}");
    assert!(v.doc.status.error.is_none(), "{:?}", error_text(&v));
    frame(&ctx, &mut v, vec![]);
}

#[test]
fn a_files_option_tags_become_the_asked_options_unless_the_command_line_gave_them() {
    use crate::mesh::{BoundaryInterpolation, Creasing, attributes::UvInterpolation};
    let tagged = common::scratch_dir("viewer-tags").join("tagged.obj");
    let quads = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nf 1 2 3 4\nf 2 5 6\nf 2 6 3\n";
    let tags = "t interpolateboundary 1/0/0 1\nt facevaryinginterpolateboundary 1/0/0 4\n\
                t smoothtriangles 0/0/1 smooth\nt creasemethod 0/0/1 chaikin\n";
    std::fs::write(&tagged, format!("{quads}{tags}")).unwrap();
    let mut v = Viewer::new();
    v.doc.request.scheme = Scheme::CatmullClark;
    v.doc.request.level = 1;
    // the command line gave --creasing uniform
    v.doc.pinned.creasing = Some(Creasing::Uniform);
    v.apply(Command::Open(tagged.clone()));
    settle(&mut v);
    assert!(v.doc.status.error.is_none(), "{:?}", error_text(&v));
    let opts = v.doc.model.made.opts;
    assert_eq!(opts.boundary, BoundaryInterpolation::EdgeAndCorner, "the file's interpolateboundary");
    assert_eq!(opts.uv, UvInterpolation::Boundaries, "the file's facevaryinginterpolateboundary");
    assert_eq!(opts.triangles, crate::mesh::TriangleSubdivision::Smooth, "the file's smoothtriangles");
    assert_eq!(opts.creasing, Creasing::Uniform, "the flag over the file's creasemethod");
    // a file without tags leaves the options as they are
    v.apply(Command::Open(common::model_path("cube.obj")));
    settle(&mut v);
    assert_eq!(v.doc.model.made.opts.boundary, BoundaryInterpolation::EdgeAndCorner);
}

#[test]
fn a_picked_face_is_punched_as_a_hole_and_filled_again() {
    let mut v = Viewer::new();
    v.apply(Command::Open(common::model_path("critter.obj")));
    settle(&mut v);
    let critter = v.doc.model.control.mesh.clone();
    let faces = v.doc.model.control.topo.faces;
    // a ray straight down onto triangle 0 (half of the file's first quad)
    let t0: Vec<Vec3> = critter.ct.v_table()[..3].iter().map(|&i| critter.positions[i as usize]).collect();
    let normal = (t0[1] - t0[0]).cross(t0[2] - t0[0]).normalize();
    let centroid = (t0[0] + t0[1] + t0[2]) / 3.0;
    v.apply(Command::Pick { origin: centroid + normal * 1e-3, dir: -normal });
    let c = (*v.doc.model.picked).expect("the ray hits the face");
    v.apply(Command::ToggleHolePicked);
    let ct = &v.doc.model.control.mesh.ct;
    // the top quad's two triangles (a fanned quad: joined across the diagonal)
    assert_eq!(ct.holes().len(), 2, "{:?}", ct.holes());
    assert!(ct.is_hole(c / 3));
    assert_eq!(v.doc.model.control.topo.faces, faces, "a hole stays in the table");
    // saved with its tag, the hole comes back as it went
    let path = common::scratch_dir("viewer-holes").join("holed.obj");
    v.apply(Command::SaveControl(path.clone()));
    // (written as the file's quads: one polygon, face 0)
    assert!(std::fs::read_to_string(&path).unwrap().contains("t hole 1/0/0 0\n"));
    assert_eq!(crate::bundled::load(&path).unwrap().ct.holes(), v.doc.model.control.mesh.ct.holes());
    v.apply(Command::ToggleHolePicked);
    assert!(v.doc.model.control.mesh.ct.holes().is_empty(), "filled again");
    assert_eq!(v.doc.model.control.mesh.positions, critter.positions);
}
