//! The adaptive display in the viewer without a window: the limit
//! tessellated for the view on a worker, again when the view or the cage
//! changes, the uniform level back when it is off or the scheme has no
//! limit.

use super::tests::{common, frame, settle, subdivide};
use crate::Scheme;
use crate::app::{Command, Viewer};

/// Turns the adaptive display on or off.
fn set_adaptive(v: &mut Viewer, on: bool) {
    let mut d = v.doc.display;
    d.adaptive = on;
    v.apply(Command::SetDisplay(d));
}

/// A frame (which asks for the view's tessellation) and its worker.
fn frame_and_wait(ctx: &egui::Context, v: &mut Viewer) -> usize {
    frame(ctx, v, vec![]);
    settle(v);
    let a = v.doc.adaptive_shown().expect("a tessellation is drawn");
    assert!(a.stats.met && a.stats.worst <= super::adaptive::PIXELS, "{:?}", a.stats);
    let shown = &v.doc.model.result.shown;
    assert!(std::sync::Arc::ptr_eq(&shown.mesh, &a.shown.mesh), "the result drawn is the tessellation");
    assert_eq!(shown.topo.boundary_loops, 0, "a closed cage gives a closed surface");
    assert_eq!(shown.normals.len(), shown.mesh.positions.len());
    shown.topo.faces
}

/// A viewer showing the bundled `model` under `scheme` at `level`, with the
/// adaptive display on and its first tessellation drawn.
fn adaptive_viewer(ctx: &egui::Context, model: &str, scheme: Scheme, level: u32) -> Viewer {
    let mut v = Viewer::new();
    v.apply(Command::Open(common::model_path(model)));
    settle(&mut v);
    subdivide(&mut v, scheme, level);
    settle(&mut v);
    frame(ctx, &mut v, vec![]);
    set_adaptive(&mut v, true);
    frame_and_wait(ctx, &mut v);
    v
}

#[test]
fn the_adaptive_display_follows_the_view_and_the_cage() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    v.apply(Command::Open(common::model_path("torus.obj")));
    settle(&mut v);
    subdivide(&mut v, Scheme::Loop, 1);
    settle(&mut v);
    let level = v.doc.model.result.shown.topo.faces;
    frame(&ctx, &mut v, vec![]);
    set_adaptive(&mut v, true);
    let fitted = frame_and_wait(&ctx, &mut v);
    // the same view again asks for nothing
    frame(&ctx, &mut v, vec![]);
    assert!(v.doc.jobs.busy.tessellating.is_none(), "an unchanged view is not tessellated again");
    // nearer: finer
    v.apply(Command::Zoom { factor: 0.5, cursor: glam::Vec2::ZERO, aspect: 1.0 });
    let near = frame_and_wait(&ctx, &mut v);
    assert!(near > fitted, "zoomed in: {near} triangles, fitted {fitted}");
    // an edit of the cage is tessellated again
    let before = v.doc.model.result.shown.mesh.clone();
    v.apply(Command::Smooth(2));
    settle(&mut v);
    frame_and_wait(&ctx, &mut v);
    assert!(!std::sync::Arc::ptr_eq(&before, &v.doc.model.result.shown.mesh), "the edit was tessellated");
    // off: the uniform level is drawn again
    set_adaptive(&mut v, false);
    assert!(v.doc.adaptive_shown().is_none());
    assert_eq!(v.doc.model.result.shown.topo.faces, level);
}

#[test]
fn a_scheme_without_a_limit_shows_its_level_and_says_why() {
    let ctx = egui::Context::default();
    let mut v = Viewer::new();
    subdivide(&mut v, Scheme::Butterfly, 2);
    settle(&mut v);
    let level = v.doc.model.result.shown.topo.faces;
    frame(&ctx, &mut v, vec![]);
    set_adaptive(&mut v, true);
    frame(&ctx, &mut v, vec![]);
    settle(&mut v);
    assert!(v.doc.adaptive_shown().is_none());
    assert_eq!(v.doc.model.result.shown.topo.faces, level);
    let notice = v.doc.status.notice.clone().unwrap_or_default();
    assert!(notice.starts_with("adaptive display:"), "{notice}");
}

#[test]
fn a_pick_on_the_adaptive_display_is_the_limit_at_its_own_point() {
    use crate::app::probe::ray_at;
    use crate::subdiv::pick::{ControlFace, Limit};
    for (model, scheme) in [("torus.obj", Scheme::Loop), ("cube.obj", Scheme::CatmullClark)] {
        let ctx = egui::Context::default();
        let mut v = adaptive_viewer(&ctx, model, scheme, 0);
        let rect = v.view.scene_rect;
        let at = rect.center() + egui::vec2(rect.width() * 0.12, rect.height() * 0.05);
        v.apply(Command::PickSurface(ray_at(&v.view.camera, rect, false, at)));
        let p = v.doc.model.probe.as_ref().expect("the ray hits the surface").pick.clone();
        let Limit::Exact(s) = &p.limit else { panic!("{model}: no limit: {:?}", p.limit) };
        // the drawn point lies on a flat triangle within the tolerance of the limit at its (u, v)
        let tol = v.doc.adaptive_shown().expect("drawn").stats.measured;
        let d = s.position.distance(p.point.as_dvec3());
        assert!(d <= 2.0 * tol + 1e-6, "{model}: the hit is {d} from the limit at its point (measured {tol})");
        let on_face = match p.face {
            ControlFace::Triangle { .. } => scheme == Scheme::Loop,
            ControlFace::Polygon { ptex, .. } => scheme == Scheme::CatmullClark && ptex.is_some(),
        };
        assert!(on_face, "{model}: {:?}", p.face);
    }
}

#[test]
fn an_edit_in_a_still_view_makes_again_only_what_it_reaches() {
    use crate::app::edit::{Axis, EditAction};
    let ctx = egui::Context::default();
    let mut v = adaptive_viewer(&ctx, "torus.obj", Scheme::Loop, 1);
    let fresh = v.doc.adaptive_shown().expect("drawn").stats;
    let drawn = v.doc.adaptive_shown().expect("drawn").shown.mesh.clone();
    let start = v.doc.model.control.mesh.positions[7];
    // one control vertex moved a little along y
    v.apply(Command::Edit(EditAction::Toggle));
    v.apply(Command::Edit(EditAction::Select { ids: vec![7], add: false }));
    v.apply(Command::Edit(EditAction::Grab { anchor: glam::Vec2::ZERO }));
    v.apply(Command::Edit(EditAction::Constrain(Axis::Y)));
    v.apply(Command::Edit(EditAction::Typed("0.05".into())));
    v.apply(Command::Edit(EditAction::Confirm));
    settle(&mut v);
    frame_and_wait(&ctx, &mut v);
    let again = v.doc.adaptive_shown().expect("drawn").stats;
    // the torus has 512 vertices; one reaches a few dozen of its faces
    assert!(again.evaluations * 10 < fresh.evaluations, "after the edit {again:?}, fresh {fresh:?}");
    // the vertex did move, and what is drawn is the edited cage's limit
    // (frame_and_wait checked the new tessellation within its pixels)
    let moved = v.doc.model.control.mesh.positions[7] - start;
    assert!((moved - glam::Vec3::Y * 0.05).length() < 1e-6, "moved by {moved}");
    assert!(!std::sync::Arc::ptr_eq(&drawn, &v.doc.adaptive_shown().expect("drawn").shown.mesh));
}

#[test]
fn the_curvature_colouring_is_the_limit_s_own_on_the_adaptive_display() {
    use crate::app::display::Coloring;
    use crate::subdiv::eval::color::{CurvatureKind, vertex_areas};
    let ctx = egui::Context::default();
    let mut v = adaptive_viewer(&ctx, "cube.obj", Scheme::CatmullClark, 0);
    assert!(v.doc.model.result.values.is_none(), "uncoloured");
    let mut d = v.doc.display;
    d.coloring = Coloring::Curvature(CurvatureKind::Gaussian);
    v.apply(Command::SetDisplay(d));
    frame_and_wait(&ctx, &mut v);
    let t = v.doc.adaptive_shown().expect("drawn");
    let (kind, k) = t.curvature.clone().expect("the curvature came with the tessellation");
    assert_eq!(kind, CurvatureKind::Gaussian);
    let mesh = &t.shown.mesh;
    assert_eq!(k.len(), mesh.positions.len());
    // none at the extraordinary vertices themselves (the cube's triangles'
    // centres and its corners of valence other than 4: no curvature there)
    let cage = &v.doc.model.control.mesh;
    let most = cage.positions.len() + cage.ct.num_triangles();
    let corners = k.iter().filter(|k| !k.is_finite()).count();
    assert!(corners <= most, "{corners} vertices without a curvature");
    // Gauss-Bonnet: a closed surface of genus 0 has total curvature 4 pi
    let areas = vertex_areas(&mesh.ct, &mesh.positions);
    let total: f64 = k.iter().zip(areas).filter(|(k, _)| k.is_finite()).map(|(k, a)| k * a).sum();
    let four_pi = 4.0 * std::f64::consts::PI;
    assert!((total - four_pi).abs() < 0.05 * four_pi, "total curvature {total}, not 4 pi");
    // and it is what is drawn: values of its sign (the shader clamps them to the range)
    let values = v.doc.model.result.values.clone().expect("values drawn");
    assert_eq!(values.len(), mesh.positions.len());
    let same = |(t, k): (&f32, &f64)| k.abs() < 1e-9 || (f64::from(*t) > 0.0) == (*k > 0.0);
    assert!(values.iter().zip(k.iter()).filter(|(_, k)| k.is_finite()).all(same), "the colours are not K's");
    // the colouring off: the geometry drawn stands, nothing is asked again
    let mut d = v.doc.display;
    d.coloring = Coloring::None;
    v.apply(Command::SetDisplay(d));
    frame(&ctx, &mut v, vec![]);
    assert!(v.doc.jobs.busy.tessellating.is_none(), "the same geometry tessellated again");
    assert!(v.doc.model.result.values.is_none(), "uncoloured again");
}
