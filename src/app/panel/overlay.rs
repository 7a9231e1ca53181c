//! Text over the 3D area: what is shown, a running task, the drop target.

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
    } else {
        format!("{} level {}", doc.model.made.scheme.name(), doc.model.made.level)
    }
}
