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
    doc.level = 7;
    doc.request_subdivision();
    doc.level = 1;
    doc.request_subdivision();
    settle(&mut doc);
    assert_eq!((doc.result_level, doc.result.topo.faces), (1, 16));
}

#[test]
fn a_bad_file_shows_an_error_and_keeps_the_model() {
    let dir = std::env::temp_dir().join(format!("subdiv-viewer-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
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
    let dir = std::env::temp_dir().join(format!("subdiv-viewer-fin-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
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
