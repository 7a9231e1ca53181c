//! The viewer's logic without a window: the egui panel runs headless on a
//! document, driven by key events, and the worker threads are awaited.
#![cfg(feature = "viewer")]

mod common;

use std::time::{Duration, Instant};
use subdiv::app::doc::Doc;
use subdiv::app::panel::{self, UiState};
use subdiv::render::Surface;

fn key(k: egui::Key) -> egui::Event {
    egui::Event::Key { key: k, physical_key: None, pressed: true, repeat: false, modifiers: Default::default() }
}

fn frame(ctx: &egui::Context, doc: &mut Doc, st: &mut UiState, events: Vec<egui::Event>) {
    let raw = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0))),
        events,
        ..Default::default()
    };
    let out = ctx.run_ui(raw, |ui| {
        panel::show(ui, doc, st);
    });
    out.drop_without_applying_deltas();
}

fn settle(doc: &mut Doc) {
    let t0 = Instant::now();
    loop {
        doc.poll();
        if !doc.busy() {
            return;
        }
        assert!(t0.elapsed() < Duration::from_secs(60), "worker did not finish");
        std::thread::sleep(Duration::from_millis(2));
    }
}

#[test]
fn keys_toggle_the_view_and_step_levels_on_a_worker() {
    let ctx = egui::Context::default();
    let (mut doc, mut st) = (Doc::new(), UiState::new(false));
    frame(&ctx, &mut doc, &mut st, vec![]);
    assert!(st.scene_rect.width() > 500.0, "the 3D area takes the rest of the window");
    frame(&ctx, &mut doc, &mut st, vec![key(egui::Key::W)]);
    assert!(st.wireframe);
    frame(&ctx, &mut doc, &mut st, vec![key(egui::Key::S)]);
    assert_eq!(st.surface, Surface::Flat);
    for _ in 0..3 {
        frame(&ctx, &mut doc, &mut st, vec![key(egui::Key::Plus)]);
    }
    assert_eq!(doc.level, 3);
    settle(&mut doc);
    assert_eq!(doc.result_level, 3);
    assert_eq!(doc.result.topo.faces, 4 * 64);
    assert!(doc.stats.is_some());
    frame(&ctx, &mut doc, &mut st, vec![key(egui::Key::Minus)]);
    settle(&mut doc);
    assert_eq!((doc.level, doc.result.topo.faces), (2, 64));
}

#[test]
fn a_newer_request_supersedes_an_older_one() {
    let mut doc = Doc::new();
    doc.level = 8;
    doc.request_subdivision();
    doc.level = 1;
    doc.request_subdivision();
    settle(&mut doc);
    // The level-8 job finishes later (or stops early); its late result must not replace level 1.
    std::thread::sleep(Duration::from_millis(500));
    doc.poll();
    assert_eq!((doc.result_level, doc.result.topo.faces), (1, 16));
}

#[test]
fn a_big_level_brings_its_proxy_from_the_same_run() {
    let mut doc = Doc::new();
    doc.level = 8; // 262,144 faces: over the proxy threshold
    doc.request_subdivision();
    settle(&mut doc);
    assert!(doc.error.is_none(), "{:?}", doc.error);
    assert_eq!(doc.result.topo.faces, 4 << 16);
    let proxy = doc.proxy.as_ref().expect("a proxy");
    assert_eq!(proxy.topo.faces, 4 << 14, "level 7: the highest level under the threshold");
    let stats = doc.stats.as_ref().unwrap();
    assert_eq!(stats.faces_per_level.len(), 8, "both legs of the run are in the stats");
    assert_eq!(*stats.faces_per_level.last().unwrap(), 4 << 16);
}

#[test]
fn a_bad_file_shows_an_error_and_keeps_the_model() {
    let dir = common::scratch_dir("viewer-test");
    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nf 1 2 7\n").unwrap();
    let mut doc = Doc::new();
    doc.open(bad);
    settle(&mut doc);
    let err = doc.error.clone().expect("an error is shown");
    assert!(err.contains("bad.obj") && err.contains(":3"), "{err}");
    assert_eq!(doc.control.topo.vertices, 4, "the tetrahedron stays");
    doc.error = None;
    doc.level = 1;
    doc.open(common::model_path("cube.obj"));
    settle(&mut doc);
    assert!(doc.error.is_none(), "{:?}", doc.error);
    assert_eq!(doc.name, "cube.obj");
    assert_eq!(doc.result_level, 1);
    assert_eq!(doc.result.topo.faces, 4 * doc.control.topo.faces);
    assert!(doc.paths_source.starts_with("generated"), "the cube has no .paths: {}", doc.paths_source);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn levels_over_the_memory_limit_are_refused_with_a_reason() {
    let ctx = egui::Context::default();
    let (mut doc, mut st) = (Doc::new(), UiState::new(false));
    doc.limit = Some(200_000);
    let max = doc.max_level();
    assert!((2..8).contains(&max), "max level {max}");
    assert!(doc.level_refusal(max + 1).unwrap().contains("limit"));
    doc.level = max;
    doc.request_subdivision();
    settle(&mut doc);
    frame(&ctx, &mut doc, &mut st, vec![key(egui::Key::Plus)]);
    assert_eq!(doc.level, max, "+ past the limit does nothing");
    assert!(doc.error.as_deref().is_some_and(|e| e.contains("limit")), "{:?}", doc.error);
}

#[test]
fn space_plays_the_tetrahedron_animation() {
    let ctx = egui::Context::default();
    let (mut doc, mut st) = (Doc::new(), UiState::new(false));
    doc.level = 5;
    doc.request_subdivision();
    frame(&ctx, &mut doc, &mut st, vec![key(egui::Key::Space)]);
    settle(&mut doc);
    let a = doc.anim.as_mut().expect("animation built");
    assert_eq!(a.clock.frames(), 4 << 5);
    assert!(a.clock.playing);
    assert_eq!(a.player.topology().num_triangles(), 4 << 10);
    let f0 = a.clock.tick(0.0);
    let f1 = a.clock.tick(0.5);
    assert_eq!(f1, f0 + 15, "30 frames/s for half a second");
    frame(&ctx, &mut doc, &mut st, vec![key(egui::Key::Space)]);
    assert!(!doc.anim.as_ref().unwrap().clock.playing, "Space pauses");
    doc.stop_animation();
    assert!(doc.anim.is_none() && !doc.animating);
}

#[test]
fn a_non_manifold_file_can_be_repaired_from_the_panel() {
    let dir = common::scratch_dir("viewer-fin");
    let fin = dir.join("fin.obj");
    std::fs::write(&fin, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n").unwrap();
    let mut doc = Doc::new();
    doc.open(fin.clone());
    settle(&mut doc);
    assert!(doc.error.as_deref().is_some_and(|e| e.contains("non-manifold edge")), "{:?}", doc.error);
    assert_eq!(doc.failed.as_deref(), Some(fin.as_path()), "offered for repair");
    assert_eq!(doc.control.topo.vertices, 4, "the tetrahedron stays");
    doc.open_with(fin, true);
    settle(&mut doc);
    assert!(doc.failed.is_none());
    assert_eq!(doc.control.topo.faces, 3);
    assert!(doc.notice.as_deref().is_some_and(|n| n.contains("repaired")), "{:?}", doc.notice);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn picking_flip_split_smooth_and_revert_edit_the_control_mesh() {
    use glam::Vec3;
    use subdiv::app::doc::pick_edge;
    let mut doc = Doc::new();
    let tet = doc.control.mesh.clone();
    // A ray from outside through the centroid of face 0 hits face 0 first.
    let t0: Vec<Vec3> = tet.ct.v_table()[..3].iter().map(|&i| tet.positions[i as usize]).collect();
    let centroid = (t0[0] + t0[1] + t0[2]) / 3.0;
    let origin = centroid * 5.0;
    let c = pick_edge(&tet, origin, (centroid - origin).normalize()).expect("the ray hits");
    assert!(c < 3, "picked corner {c} is not on face 0");
    assert_eq!(pick_edge(&tet, Vec3::new(0.0, 50.0, 0.0), Vec3::Y), None, "pointing away misses");

    doc.picked = Some(c);
    doc.split_picked();
    assert_eq!((doc.control.topo.vertices, doc.control.topo.faces), (5, 6));
    assert!(subdiv::mesh::topology::check_invariants(&doc.control.mesh.ct).is_ok());
    assert!(doc.original.is_some());
    doc.smooth(5);
    assert_ne!(doc.control.mesh.positions, doc.original.as_ref().unwrap().positions);
    doc.revert();
    assert_eq!((doc.control.topo.vertices, doc.control.topo.faces), (4, 4));
    assert_eq!(doc.control.mesh.positions, tet.positions);
    // The tetrahedron's edges cannot be flipped (every vertex has valence 3).
    doc.picked = Some(0);
    doc.flip_picked();
    assert!(doc.error.as_deref().is_some_and(|e| e.starts_with("flip:")), "{:?}", doc.error);
}

#[test]
fn display_options_recolour_and_renormal_the_result() {
    use subdiv::app::doc::{Coloring, NormalMode};
    use subdiv::mesh::inspect::colormap;
    let mut doc = Doc::new();
    doc.scheme = subdiv::Scheme::Midpoint;
    doc.level = 2;
    doc.request_subdivision();
    settle(&mut doc);
    doc.coloring = Coloring::Displacement;
    doc.refresh_result();
    let colors = doc.result_colors.clone().expect("colours");
    assert_eq!(colors.len(), doc.result.mesh.positions.len());
    let zero = glam::Vec3::from(colormap(0.0));
    assert!(colors.iter().all(|c| (*c - zero).length() < 1e-6), "midpoint points lie on the control mesh");
    doc.coloring = Coloring::Shells;
    doc.refresh_result();
    let colors = doc.result_colors.clone().unwrap();
    assert_eq!(colors[0], zero, "level-0 vertices are dark");
    assert_eq!(*colors.last().unwrap(), glam::Vec3::from(colormap(1.0)), "the newest vertices are bright");
    doc.normal_mode = NormalMode::LoopLimit;
    doc.snap_limit = true;
    doc.refresh_result();
    assert!(doc.result.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
    assert_ne!(doc.result.mesh.positions, doc.raw.mesh.positions, "snapped to the limit");
}

#[test]
fn a_bzc_file_opens_as_a_curve_with_its_construction() {
    let mut doc = Doc::new();
    doc.open(common::model_path("curve.bzc"));
    settle(&mut doc);
    assert!(doc.error.is_none(), "{:?}", doc.error);
    let c = doc.curve.clone().expect("a curve");
    let line = c.polyline();
    assert_eq!(line.len(), c.segments + 1);
    assert_eq!(line[0], c.control[0].extend(0.0), "starts at the first control point");
    assert!((line[c.segments] - c.control.last().unwrap().extend(0.0)).length() < 1e-6, "ends at the last");
    let (segs, point) = c.construction_segments();
    // n control points: levels of n-1, n-2, ..., 1 points: (n-2) + ... + 0 segments.
    let n = c.control.len();
    assert_eq!(segs.len() / 2, (n - 1) * (n - 2) / 2);
    let expect = subdiv::io::bezier::de_casteljau(&c.control, c.t).unwrap().extend(0.0);
    assert!((point.unwrap() - expect).length() < 1e-6);
    assert_eq!(doc.control.topo.vertices, 4, "the mesh stays loaded underneath");
}

#[test]
fn file_colours_are_refined_with_the_mesh() {
    use subdiv::app::doc::Coloring;
    let dir = common::scratch_dir("viewer-col");
    let f = dir.join("tet.obj");
    std::fs::write(
        &f,
        "v 1 1 1 1 0 0\nv 1 -1 -1 0 1 0\nv -1 1 -1 0 0 1\nv -1 -1 1 1 1 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n",
    )
    .unwrap();
    let mut doc = Doc::new();
    doc.level = 2;
    doc.open(f);
    settle(&mut doc);
    assert!(doc.error.is_none(), "{:?}", doc.error);
    doc.coloring = Coloring::File;
    doc.refresh_result();
    let got = doc.result_colors.clone().expect("file colours shown");
    let want = subdiv::subdiv::attributes::refine_colors(
        &doc.control.mesh.ct,
        doc.file_attrs.colors.as_ref().unwrap(),
        subdiv::Scheme::Loop,
        2,
        &Default::default(),
    )
    .unwrap();
    assert_eq!(got, want);
    assert_eq!(got.len(), doc.result.mesh.positions.len());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn texture_coordinates_of_the_file_follow_the_levels() {
    use subdiv::app::doc::Coloring;
    let mut doc = Doc::new();
    doc.level = 2;
    doc.open(common::model_path("cube_uv.obj"));
    settle(&mut doc);
    assert_eq!(doc.file_attrs.uv.as_ref().map(Vec::len), Some(36));
    assert_eq!(doc.raw_attrs.uv.as_ref().map(Vec::len), Some(3 * doc.result.mesh.ct.num_triangles()));
    assert_eq!(doc.file_attrs.colors.as_ref().map(Vec::len), Some(8));
    doc.coloring = Coloring::Checker;
    doc.refresh_result();
    assert!(doc.result_colors.is_none(), "the checker is drawn from the UVs, not vertex colours");
    assert!("checker".parse::<Coloring>().is_ok() && "plaid".parse::<Coloring>().is_err());
}

#[test]
fn the_cursor_maps_into_the_viewport_under_it() {
    let rect = egui::Rect::from_min_size(egui::pos2(100.0, 0.0), egui::vec2(400.0, 200.0));
    let at = |side, x, y| panel::cursor_ndc(rect, side, egui::pos2(x, y));
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
    let ico = subdiv::mesh::shapes::icosahedron();
    let warren = subdiv::Options { loop_beta: subdiv::LoopBeta::Warren, ..Default::default() };
    let converged = subdiv::subdivide(&ico, subdiv::Scheme::Loop, 6, &warren).unwrap().0;
    let mut doc = Doc::new();
    doc.opts = warren;
    doc.adopt("icosahedron.obj".into(), ico.clone(), None);
    settle(&mut doc);
    doc.snap_limit = true;
    doc.refresh_result();
    for v in 0..ico.positions.len() {
        let d = doc.result.mesh.positions[v].distance(converged.positions[v]);
        assert!(d < 1e-4, "vertex {v} snapped {d} away from the Warren limit");
    }
}
