//! Text over the 3D area: what is shown, a running task, the drop target;
//! the marker of the picked point.

use crate::app::display::Display;
use crate::app::doc::Doc;
use crate::app::view::View;
use egui::Color32;

/// What each viewport shows (with this frame's `display`), how long a running task has taken, "Drop to open".
pub(crate) fn overlay(ui: &mut egui::Ui, rect: egui::Rect, doc: &Doc, view: &View, display: &Display) {
    let painter = ui.painter_at(rect);
    let font = egui::FontId::proportional(14.0);
    let weak = Color32::from_gray(170);
    let corner = rect.left_top() + egui::vec2(10.0, 8.0);
    if display.side_by_side {
        let half = rect.width() / 2.0;
        painter.text(corner, egui::Align2::LEFT_TOP, "control mesh", font.clone(), weak);
        painter.text(corner + egui::vec2(half, 0.0), egui::Align2::LEFT_TOP, label(doc), font.clone(), weak);
        painter.line_segment([rect.center_top(), rect.center_bottom()], egui::Stroke::new(1.0, Color32::from_gray(60)));
    } else {
        painter.text(corner, egui::Align2::LEFT_TOP, label(doc), font.clone(), weak);
    }
    marker(&painter, rect, doc, view, display);
    inspect_marks(&painter, rect, doc, view, display);
    let busy = &doc.jobs.busy;
    if let Some(b) = busy.subdividing.as_ref().or(busy.loading.as_ref()).or(busy.building.as_ref()) {
        let secs = b.since.elapsed().as_secs_f32();
        if secs > 0.15 {
            painter.text(
                rect.right_top() + egui::vec2(-10.0, 8.0),
                egui::Align2::RIGHT_TOP,
                format!("{}… {:.1} s", b.what, secs),
                font,
                Color32::from_rgb(240, 200, 90),
            );
        }
    }
    if view.hovering_file {
        painter.rect_filled(rect.shrink(20.0), 8.0, Color32::from_black_alpha(150));
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "Drop to open",
            egui::FontId::proportional(28.0),
            Color32::WHITE,
        );
    }
}

/// The curve, the animation frame, or the scheme and level shown.
fn label(doc: &Doc) -> String {
    if let Some(c) = &*doc.model.curve {
        format!("{}: Bezier curve of degree {}", c.name, c.control.len().saturating_sub(1))
    } else if doc.anim.active {
        match &doc.anim.playback {
            Some(p) => format!(
                "{} level {} — frame {}/{}",
                doc.request.scheme.name(),
                doc.request.level,
                p.clock.frame() + 1,
                p.clock.frames()
            ),
            None => "building the animation…".into(),
        }
    } else if doc.adaptive_shown().is_some() {
        format!("{} limit, adaptive: within {} px", doc.request.scheme.name(), crate::app::adaptive::PIXELS)
    } else {
        format!("{} level {}", doc.model.made.scheme.name(), doc.model.made.level)
    }
}

/// A ring at the picked point, in the viewport it was picked in, with the
/// limit normal as a short line where the limit is evaluated (drawn over
/// the surface: the point shows through what hides it).
fn marker(painter: &egui::Painter, rect: egui::Rect, doc: &Doc, view: &View, display: &Display) {
    use crate::app::probe::Target;
    use crate::app::view::viewport_aspect;
    use crate::subdiv::pick::Limit;
    let Some(probe) = &doc.model.probe else { return };
    let mut vp = rect;
    if display.side_by_side {
        vp.set_width(rect.width() / 2.0);
        if probe.ray.target == Target::Result {
            vp = vp.translate(egui::vec2(vp.width(), 0.0));
        }
    }
    let aspect = viewport_aspect(rect, display.side_by_side);
    let to_screen = |p: glam::Vec3| {
        let ndc = view.camera.project(p, aspect);
        ((0.0..=1.0).contains(&ndc.z) && ndc.is_finite()).then(|| {
            egui::pos2(vp.left() + (ndc.x + 1.0) * 0.5 * vp.width(), vp.top() + (1.0 - ndc.y) * 0.5 * vp.height())
        })
    };
    let p = &probe.pick;
    let Some(at) = to_screen(p.point) else { return };
    let accent = Color32::from_rgb(255, 200, 40);
    if let Limit::Exact(s) = &p.limit
        && let Some(tip) = to_screen(p.point + s.normal.as_vec3() * 0.15 * view.camera.radius)
    {
        painter.line_segment([at, tip], egui::Stroke::new(2.0, accent));
    }
    painter.circle_stroke(at, 6.0, egui::Stroke::new(3.0, Color32::from_black_alpha(160)));
    painter.circle_stroke(at, 6.0, egui::Stroke::new(1.5, accent));
}

/// The inspector's marks (render/inspect.rs, the same as `subdiv render
/// --corner/--stencil` draws) over the result's viewport, its caption under
/// the viewport's label.
fn inspect_marks(painter: &egui::Painter, rect: egui::Rect, doc: &Doc, view: &View, display: &Display) {
    use crate::render::overlay::{Anchor, Prim, Viewport, project};
    let Some(overlay) = doc.inspect_overlay() else { return };
    let mut vp = rect;
    if display.side_by_side {
        vp.set_width(rect.width() / 2.0);
        vp = vp.translate(egui::vec2(vp.width(), 0.0));
    }
    let viewport = Viewport {
        min: glam::Vec2::new(vp.left(), vp.top()),
        size: glam::Vec2::new(vp.width(), vp.height()),
        scale: 1.0,
    };
    let pos = |p: glam::Vec2| egui::pos2(p.x, p.y);
    let color = |c: [u8; 4]| Color32::from_rgba_unmultiplied(c[0], c[1], c[2], c[3]);
    let font = egui::FontId::proportional(13.0);
    for prim in project(&overlay, &view.camera, &viewport, 28.0) {
        match prim {
            Prim::Line { a, b, width, color: c } => {
                painter.line_segment([pos(a), pos(b)], egui::Stroke::new(width, color(c)));
            }
            Prim::Triangle { p, color: c } => {
                painter.add(egui::Shape::convex_polygon(p.map(pos).to_vec(), color(c), egui::Stroke::NONE));
            }
            Prim::Circle { c, r, color: k } => {
                painter.circle_filled(pos(c), r, color(k));
            }
            Prim::CircleStroke { c, r, width, color: k } => {
                painter.circle_stroke(pos(c), r, egui::Stroke::new(width, color(k)));
            }
            Prim::Text { at, anchor, text, color: c } => {
                let align = match anchor {
                    Anchor::LeftCenter => egui::Align2::LEFT_CENTER,
                    Anchor::RightCenter => egui::Align2::RIGHT_CENTER,
                    Anchor::Center => egui::Align2::CENTER_CENTER,
                    Anchor::LeftTop => egui::Align2::LEFT_TOP,
                };
                let galley = painter.layout_no_wrap(text, font.clone(), color(c));
                let r = align.anchor_size(pos(at), galley.size());
                painter.rect_filled(r.expand(2.0), 3.0, Color32::from_black_alpha(170));
                painter.galley(r.min, galley, color(c));
            }
        }
    }
}
