//! Editing the cage through the viewer's own input: keys into the headless
//! panel, the same `Viewer::apply` as the window. A grab moves the surface,
//! undo gives back the first surface bit for bit and redo the moved one,
//! Ctrl+S writes every moved vertex with the faces and tags unchanged, and
//! the recovery file brings back edits that were never saved.

use super::edit::{Answer, EditAction, Pending, falloff};
use super::recovery::{Recovery, recovery_file};
use super::tests::{frame, key, settle, subdivide};
use super::{Command, Viewer};
use crate::Scheme;
use egui::{Event, Key, Modifiers};
use glam::Vec3;
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("subdiv-edit-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temporary directory");
    d
}

fn chord(k: Key, modifiers: Modifiers) -> Event {
    Event::Key { key: k, physical_key: None, pressed: true, repeat: false, modifiers }
}

/// One frame with the modifiers held, then one with them released.
fn frame_with(ctx: &egui::Context, v: &mut Viewer, modifiers: Modifiers, events: Vec<Event>) {
    let mut all = vec![Event::ModifiersChanged(modifiers)];
    all.extend(events);
    frame(ctx, v, all);
    frame(ctx, v, vec![Event::ModifiersChanged(Modifiers::NONE)]);
}

/// A cube with one crease, written to `dir`, opened in a viewer whose
/// recovery files go to `dir/state`.
fn open_cube(dir: &Path) -> (Viewer, PathBuf) {
    let path = dir.join("cube.obj");
    let v = "v 0 0 0\nv 0 0 1\nv 0 1 0\nv 0 1 1\nv 1 0 0\nv 1 0 1\nv 1 1 0\nv 1 1 1\n";
    let f = "f 1 2 4 3\nf 5 7 8 6\nf 1 5 6 2\nf 3 4 8 7\nf 1 3 7 5\nf 2 6 8 4\n";
    std::fs::write(&path, format!("{v}{f}t crease 2/1/0 0 1 2.5\n")).unwrap();
    let mut v = Viewer::new();
    v.doc.edit.recovery = Some(Recovery::Folder(dir.join("state")));
    v.apply(Command::Open(path.clone()));
    settle(&mut v);
    assert!(v.doc.model.control.mesh.ct.sharpness().is_some(), "the crease tag was read");
    (v, path)
}

/// E, A, then `G Z 0.25 Return`.
fn grab_all_up(ctx: &egui::Context, v: &mut Viewer, distance: &str) {
    frame(ctx, v, vec![key(Key::E)]);
    assert!(v.doc.edit.on, "E enters the edit mode");
    frame(ctx, v, vec![key(Key::A)]);
    frame(ctx, v, vec![key(Key::G)]);
    assert!(v.doc.edit.grab.is_some(), "G grabs the selection");
    frame(ctx, v, vec![key(Key::Z), Event::Text(distance.into())]);
    frame(ctx, v, vec![key(Key::Enter)]);
    assert!(v.doc.edit.grab.is_none(), "Return confirms");
}

#[test]
fn a_typed_grab_moves_the_surface_and_undo_and_redo_give_back_the_same_bits() {
    let dir = scratch("grab");
    let ctx = egui::Context::default();
    let (mut v, _) = open_cube(&dir);
    subdivide(&mut v, Scheme::CatmullClark, 2);
    settle(&mut v);
    let worker = v.doc.model.raw.mesh.positions.clone();
    let cage = v.doc.model.control.mesh.positions.clone();
    // the worker's refiner is kept, for the drawn level: the edit mode
    // takes it over instead of refining again
    let kept = v.doc.edit_refiner().expect("the worker's refiner is kept for the edit mode");
    assert_eq!(kept.positions(), &worker[..]);
    frame(&ctx, &mut v, vec![key(Key::E)]);
    // in the edit mode the refiner draws the level: the worker's surface
    // up to rounding
    let first = v.doc.model.raw.mesh.positions.clone();
    assert!(first.iter().zip(&worker).all(|(a, b)| a.distance(*b) < 1e-6));
    frame(&ctx, &mut v, vec![key(Key::E)]);
    grab_all_up(&ctx, &mut v, "0.25");
    let moved_cage = &v.doc.model.control.mesh.positions;
    for (a, b) in moved_cage.iter().zip(&cage) {
        assert_eq!(*a, *b + Vec3::new(0.0, 0.0, 0.25), "every vertex moved 0.25 along Z");
    }
    // the drawn level is the subdivision of the moved cage
    let (fresh, _) = crate::subdivide(
        &crate::mesh::poly::PolyMesh::from_mesh(&v.doc.model.control.mesh),
        Scheme::CatmullClark,
        2,
        &v.doc.model.made.opts,
    )
    .unwrap();
    let moved = v.doc.model.raw.mesh.positions.clone();
    let near = |p: &Vec3| fresh.positions.iter().any(|q| q.distance(*p) < 1e-5);
    assert!(moved.iter().all(near), "the surface follows the cage");
    assert!(moved.iter().zip(&first).all(|(a, b)| (*a - *b - Vec3::new(0.0, 0.0, 0.25)).length() < 1e-5));
    assert_eq!(v.doc.edit.history.done.len(), 1);
    assert!(v.doc.edit.history.dirty());
    frame_with(&ctx, &mut v, Modifiers::COMMAND, vec![chord(Key::Z, Modifiers::COMMAND)]);
    assert_eq!(v.doc.model.raw.mesh.positions, first, "undo gives back the first surface exactly");
    assert_eq!(v.doc.model.control.mesh.positions, cage);
    assert!(!v.doc.edit.history.dirty(), "back where the file is");
    let redo = Modifiers { command: true, shift: true, ..Default::default() };
    frame_with(&ctx, &mut v, redo, vec![chord(Key::Z, redo)]);
    assert_eq!(v.doc.model.raw.mesh.positions, moved, "redo gives back the moved one");
    frame_with(&ctx, &mut v, Modifiers::COMMAND, vec![chord(Key::Z, Modifiers::COMMAND)]);
    frame_with(&ctx, &mut v, Modifiers::COMMAND, vec![chord(Key::Y, Modifiers::COMMAND)]);
    assert_eq!(v.doc.model.raw.mesh.positions, moved, "Ctrl+Y redoes too");
}

#[test]
fn ctrl_s_writes_every_moved_vertex_with_its_faces_and_tags() {
    let dir = scratch("save");
    let ctx = egui::Context::default();
    let (mut v, path) = open_cube(&dir);
    let before = crate::io::read(crate::io::Source::File(&path), &Default::default()).unwrap();
    grab_all_up(&ctx, &mut v, "0.25");
    let recovery = recovery_file(&dir.join("state"), Some(&path));
    assert!(recovery.is_file(), "the edit is in the recovery file at once");
    frame_with(&ctx, &mut v, Modifiers::COMMAND, vec![chord(Key::S, Modifiers::COMMAND)]);
    assert!(!v.doc.edit.history.dirty(), "saved: {:?}", v.doc.status.error);
    assert!(!recovery.exists(), "a save removes the recovery file");
    let after = crate::io::read(crate::io::Source::File(&path), &Default::default()).unwrap();
    for (a, b) in after.mesh.positions.iter().zip(&before.mesh.positions) {
        assert_eq!(*a, *b + Vec3::new(0.0, 0.0, 0.25));
    }
    assert_eq!(after.mesh.ct.v_table(), before.mesh.ct.v_table(), "the same faces");
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 6, "still six quads:\n{text}");
    assert_eq!(after.mesh.ct.sharpness().map(|s| s.to_tags(&after.mesh.ct)).unwrap().creases.len(), 1);
    assert!(
        std::fs::read_dir(&dir).unwrap().all(|e| {
            let name = e.unwrap().file_name().to_string_lossy().into_owned();
            name == "cube.obj" || name == "state"
        }),
        "nothing else is written beside the model"
    );
}

#[test]
fn unsaved_edits_are_recovered_in_a_new_session_or_discarded() {
    let dir = scratch("recover");
    let ctx = egui::Context::default();
    let (mut v, path) = open_cube(&dir);
    grab_all_up(&ctx, &mut v, "-1.5");
    let moved = v.doc.model.control.mesh.positions.clone();
    drop(v); // as if killed: nothing was saved
    let (mut again, _) = reopen(&dir, &path);
    assert!(again.doc.edit.offer, "the recovery file is offered");
    frame(&ctx, &mut again, vec![key(Key::Enter)]);
    assert_eq!(again.doc.model.control.mesh.positions, moved, "Return recovers the edit");
    assert!(again.doc.edit.history.dirty(), "recovered edits are unsaved");
    drop(again);
    let (mut third, _) = reopen(&dir, &path);
    frame(&ctx, &mut third, vec![key(Key::Escape)]);
    assert!(!third.doc.edit.offer);
    assert!(!recovery_file(&dir.join("state"), Some(&path)).exists(), "Esc discards it");
    assert_ne!(third.doc.model.control.mesh.positions, moved);
}

fn reopen(dir: &Path, path: &Path) -> (Viewer, PathBuf) {
    let mut v = Viewer::new();
    v.doc.edit.recovery = Some(Recovery::Folder(dir.join("state")));
    v.apply(Command::Open(path.to_path_buf()));
    settle(&mut v);
    (v, path.to_path_buf())
}

#[test]
fn a_failed_save_keeps_the_edits_and_says_why() {
    let dir = scratch("fail");
    let ctx = egui::Context::default();
    let (mut v, _) = open_cube(&dir);
    grab_all_up(&ctx, &mut v, "1");
    v.apply(Command::Edit(EditAction::SaveAs(dir.join("no such folder").join("cube.obj"))));
    assert!(v.doc.edit.history.dirty(), "still unsaved");
    let why = v.doc.status.error.as_ref().map(ToString::to_string).unwrap_or_default();
    assert!(why.contains("not saved") && why.contains("no such folder"), "{why}");
    // opening another model asks first; Cancel stays, Discard goes on
    v.apply(Command::Open("bundled:torus.obj".into()));
    assert_eq!(v.doc.edit.pending, Some(Pending::Open(PathBuf::from("bundled:torus.obj").into())));
    v.apply(Command::Answer(Answer::Cancel));
    assert!(v.doc.edit.pending.is_none() && v.doc.model.name == "cube.obj");
    v.apply(Command::Open("bundled:torus.obj".into()));
    v.apply(Command::Answer(Answer::Discard));
    settle(&mut v);
    assert_eq!(v.doc.model.name, "torus.obj");
}

#[test]
fn a_proportional_grab_moves_the_neighbours_by_the_falloff() {
    let mut v = Viewer::new();
    v.apply(Command::Open("bundled:torus.obj".into()));
    settle(&mut v);
    let start = v.doc.model.control.mesh.positions.clone();
    let (radius, picked) = (0.8, 0u32);
    v.apply(Command::Edit(EditAction::Toggle));
    v.apply(Command::Edit(EditAction::Select { ids: vec![picked], add: false }));
    v.apply(Command::Edit(EditAction::SetProportional(true)));
    v.apply(Command::Edit(EditAction::ScaleRadius(radius / v.doc.edit.radius)));
    v.apply(Command::Edit(EditAction::Grab { anchor: glam::Vec2::ZERO }));
    v.apply(Command::Edit(EditAction::Constrain(super::edit::Axis::Y)));
    v.apply(Command::Edit(EditAction::Typed("1".into())));
    v.apply(Command::Edit(EditAction::Confirm));
    let now = &v.doc.model.control.mesh.positions;
    let (mut inside, mut outside) = (0, 0);
    for (i, (a, b)) in now.iter().zip(&start).enumerate() {
        let d = start[picked as usize].distance(*b);
        let w = if i as u32 == picked { 1.0 } else { falloff(d, radius) };
        assert!((*a - *b - Vec3::Y * w).length() < 1e-6, "vertex {i} at {d}: moved {}", *a - *b);
        if d < radius { inside += 1 } else { outside += 1 }
    }
    assert!(inside > 2 && outside > 2, "{inside} within the radius, {outside} beyond");
    // Esc during a grab puts everything back
    v.apply(Command::Edit(EditAction::Grab { anchor: glam::Vec2::ZERO }));
    v.apply(Command::Edit(EditAction::Typed("3".into())));
    let moved = v.doc.model.control.mesh.positions.clone();
    v.apply(Command::Edit(EditAction::Cancel));
    assert_ne!(moved, v.doc.model.control.mesh.positions);
    assert_eq!(v.doc.edit.history.done.len(), 1, "a cancelled grab is no step");
}

#[test]
fn shift_e_sets_the_sharpness_of_the_selected_vertices_and_undo_clears_it() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    frame(&ctx, &mut v, vec![key(Key::E)]);
    v.apply(Command::Edit(EditAction::Select { ids: vec![1, 2], add: false }));
    let shift = Modifiers::SHIFT;
    frame_with(&ctx, &mut v, shift, vec![chord(Key::E, shift)]);
    frame(&ctx, &mut v, vec![Event::Text("3.5".into())]);
    frame(&ctx, &mut v, vec![key(Key::Enter)]);
    let s = v.doc.model.control.mesh.ct.sharpness().expect("corners tagged");
    assert_eq!((s.vertex(1), s.vertex(2), s.vertex(0)), (3.5, 3.5, 0.0));
    assert_eq!(v.doc.edit.history.done.last().map(|(_, s)| s.label().to_string()), Some("sharpness".into()));
    v.apply(Command::Edit(EditAction::Undo));
    assert!(v.doc.model.control.mesh.ct.sharpness().is_none());
}

#[test]
fn a_typed_or_set_sharpness_below_0_or_not_finite_is_refused_and_changes_nothing() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    frame(&ctx, &mut v, vec![key(Key::E)]);
    v.apply(Command::Edit(EditAction::Select { ids: vec![1, 2], add: false }));
    let shift = Modifiers::SHIFT;
    frame_with(&ctx, &mut v, shift, vec![chord(Key::E, shift)]);
    frame(&ctx, &mut v, vec![Event::Text("-1".into())]);
    frame(&ctx, &mut v, vec![key(Key::Enter)]);
    let why = |v: &Viewer| v.doc.status.error.as_ref().map(ToString::to_string).unwrap_or_default();
    let expected = crate::mesh::checked_sharpness(-1.0).unwrap_err();
    assert!(why(&v).contains(&format!("the selected vertices' {expected}")), "{}", why(&v));
    assert!(v.doc.model.control.mesh.ct.sharpness().is_none(), "no corner tagged");
    assert!(v.doc.edit.history.done.is_empty(), "no step");
    // an edge's sharpness (the Creases panel's value) goes through the same check
    v.apply(Command::DismissError);
    let ct = &v.doc.model.control.mesh.ct;
    let c = ct.edge_owners().next().unwrap();
    let (a, b) = (ct.vtx(crate::mesh::n(c)), ct.vtx(crate::mesh::p(c)));
    v.apply(Command::SetSharpness { corner: c, sharpness: f32::NAN });
    let expected = crate::mesh::checked_sharpness(f64::NAN).unwrap_err();
    assert!(why(&v).contains(&format!("edge {a}-{b} has {expected}")), "{}", why(&v));
    assert!(v.doc.model.control.mesh.ct.sharpness().is_none() && v.doc.edit.history.done.is_empty());
}

#[test]
fn keys_typed_within_one_frame_are_taken_in_their_order() {
    // xdotool or a fast typist: `E A G Z 0.5 Return` and a Ctrl+Z whose
    // Ctrl is up again before the frame ends
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    let cage = v.doc.model.control.mesh.positions.clone();
    let events = vec![key(Key::E), key(Key::A), key(Key::G), key(Key::Z), Event::Text("0.5".into()), key(Key::Enter)];
    frame(&ctx, &mut v, events);
    let moved = &v.doc.model.control.mesh.positions;
    assert!(moved.iter().zip(&cage).all(|(a, b)| *a == *b + Vec3::new(0.0, 0.0, 0.5)), "moved 0.5 along Z");
    let surface = v.doc.display.surface;
    frame(&ctx, &mut v, vec![chord(Key::Z, Modifiers::COMMAND), Event::ModifiersChanged(Modifiers::NONE)]);
    assert_eq!(v.doc.model.control.mesh.positions, cage, "Ctrl+Z undid it");
    frame(&ctx, &mut v, vec![chord(Key::S, Modifiers::COMMAND)]);
    assert_eq!(v.doc.display.surface, surface, "Ctrl+S is not S (the shading)");
}

#[test]
fn in_the_edit_mode_a_sharpness_change_re_records_the_drawn_level_locally() {
    let mut v = Viewer::new();
    v.apply(Command::Open("bundled:torus.obj".into()));
    settle(&mut v);
    subdivide(&mut v, Scheme::Loop, 2);
    settle(&mut v);
    v.apply(Command::Edit(EditAction::Toggle));
    let ct = &v.doc.model.control.mesh.ct;
    let c = ct.edge_owners().next().unwrap();
    v.apply(Command::SetSharpness { corner: c, sharpness: 3.0 });
    assert!(!v.doc.busy(), "no subdivision was started");
    assert_eq!(v.doc.model.made.level, 2, "the drawn level stayed");
    assert_eq!(v.doc.model.control.mesh.ct.edge_sharpness(c), 3.0);
    let local = v.doc.model.raw.mesh.positions.clone();
    let (fresh, _) = crate::subdivide(&*v.doc.model.control.mesh, Scheme::Loop, 2, &v.doc.model.made.opts).unwrap();
    let diff = local.iter().zip(&fresh.positions).map(|(a, b)| a.distance(*b)).fold(0.0, f32::max);
    assert!(diff < 1e-5, "the local re-recording is the subdivision of the tagged cage ({diff})");
    assert!(v.doc.model.raw.creased.is_some(), "the crease is drawn as one");
    v.apply(Command::Edit(EditAction::Undo));
    settle(&mut v);
    assert_eq!(v.doc.model.control.mesh.ct.edge_sharpness(c), 0.0, "undone");
}

#[test]
fn keys_are_inserted_from_the_cage_undone_and_saved_for_animate() {
    use crate::app::keys::KeyAction;
    let dir = scratch("keys");
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    let k = v.doc.anim.paths.keys_per_vertex;
    let last: Vec<Vec3> = (0..4).map(|i| v.doc.anim.paths.polygon(i)[k - 1]).collect();
    frame(&ctx, &mut v, vec![key(Key::E)]);
    v.apply(Command::Edit(EditAction::Select { ids: vec![0], add: false }));
    frame(&ctx, &mut v, vec![key(Key::G), key(Key::Z), Event::Text("0.5".into()), key(Key::Enter)]);
    let moved = v.doc.model.control.mesh.positions[0];
    frame(&ctx, &mut v, vec![key(Key::I)]);
    let paths = &v.doc.anim.paths;
    assert_eq!(paths.keys_per_vertex, k + 1, "I inserted a key");
    assert_eq!(paths.polygon(0)[k], moved, "the selected vertex keyed where the cage has it");
    for (i, held) in last.iter().enumerate().skip(1) {
        assert_eq!(paths.polygon(i)[k], *held, "vertex {i} holds its last key");
    }
    frame_with(&ctx, &mut v, Modifiers::COMMAND, vec![chord(Key::Z, Modifiers::COMMAND)]);
    assert_eq!(v.doc.anim.paths.keys_per_vertex, k, "undone");
    v.apply(Command::Edit(EditAction::Redo));
    assert_eq!(v.doc.anim.paths.keys_per_vertex, k + 1, "redone");
    v.apply(Command::Key(KeyAction::Delete(0)));
    assert_eq!(v.doc.anim.paths.keys_per_vertex, k);
    let file = dir.join("edited.paths");
    v.apply(Command::Key(KeyAction::Save(file.clone())));
    let read = crate::anim::paths::Paths::load(&file, &Default::default()).unwrap();
    assert_eq!(read, v.doc.anim.paths, "the saved paths read back the same");
    read.check_model(&v.doc.model.control.mesh, "edited.paths").unwrap();
    // the animation plays through the new keys
    frame(&ctx, &mut v, vec![key(Key::Space)]);
    settle(&mut v);
    assert!(v.doc.anim.playback.as_ref().is_some_and(|p| p.player.frame_count() >= k));
}
