//! The subdivision section: scheme, its options, level, progress.

use super::sep;
use crate::app::command::Command;
use crate::app::doc::{Doc, MAX_LEVEL, Request};
use crate::subdiv::{LoopBeta, UvInterpolation};
use crate::{Scheme, error::human_bytes};
use egui::{Color32, RichText};
use std::sync::atomic::Ordering;

/// Scheme, Warren's beta or the tension, and the level: one
/// [`Command::Subdivide`] when any of them changed (the tension only when
/// its slider is let go; while it is dragged, [`Command::SetTension`]).
pub(crate) fn subdivision_section(ui: &mut egui::Ui, doc: &Doc) -> Option<Command> {
    let mut req = doc.request;
    let mut changed = false;
    let mut tension_moved = false;
    egui::ComboBox::from_label("Scheme").selected_text(req.scheme.name()).show_ui(ui, |ui| {
        for s in Scheme::TRIANGLE {
            changed |= ui.selectable_value(&mut req.scheme, s, s.name()).changed();
        }
        ui.separator();
        for s in Scheme::POLYGON {
            changed |= ui.selectable_value(&mut req.scheme, s, s.name()).changed();
        }
    });
    match req.scheme {
        Scheme::Loop => {
            let mut warren = req.opts.loop_beta == LoopBeta::Warren;
            if ui.checkbox(&mut warren, "Warren's beta").changed() {
                req.opts.loop_beta = if warren { LoopBeta::Warren } else { LoopBeta::Loop };
                changed = true;
            }
        }
        Scheme::CatmullClark => {
            let hint = "how texture coordinates are refined (OpenSubdiv's face-varying interpolation): \
                        the scheme on their UV charts, which of the charts' corners, junctions and borders \
                        stay fixed, or bilinear in every face (all)";
            egui::ComboBox::from_label("UVs")
                .selected_text(req.opts.uv.name())
                .show_ui(ui, |ui| {
                    for mode in UvInterpolation::ALL {
                        changed |= ui.selectable_value(&mut req.opts.uv, mode, mode.name()).changed();
                    }
                })
                .response
                .on_hover_text(hint);
        }
        Scheme::ModifiedButterfly => {
            let slider = ui.add(egui::Slider::new(&mut req.opts.tension, -0.05..=0.1).text("tension w"));
            tension_moved = slider.changed();
            changed |= slider.drag_stopped();
        }
        _ => {}
    }
    changed |= level_row(ui, doc, &mut req);
    if changed { Some(Command::Subdivide(req)) } else { tension_moved.then_some(Command::SetTension(req.opts.tension)) }
}

/// − slider +, the predicted size, why higher levels are disabled, progress;
/// whether the level changed.
fn level_row(ui: &mut egui::Ui, doc: &Doc, req: &mut Request) -> bool {
    let mut changed = false;
    let max = doc.max_level();
    ui.horizontal(|ui| {
        if ui.add_enabled(req.level > 0, egui::Button::new("−")).clicked() {
            req.level -= 1;
            changed = true;
        }
        changed |= ui.add(egui::Slider::new(&mut req.level, 0..=max).text("level")).changed();
        if ui.add_enabled(req.level < max, egui::Button::new("+")).clicked() {
            req.level += 1;
            changed = true;
        }
    });
    let faces = doc.predicted_faces(req.level);
    let what = match (req.scheme.is_polygonal(), req.level) {
        (false, _) => "triangles",
        (true, 0) => "polygons",
        (true, _) => "quads",
    };
    ui.label(format!("level {}: {} {what}", req.level, sep(faces)));
    if max < MAX_LEVEL {
        let why = doc.level_refusal(max + 1).map(|e| e.to_string()).unwrap_or_default();
        ui.label(
            RichText::new(format!("levels above {max} are disabled: {why}"))
                .small()
                .color(Color32::from_rgb(230, 170, 60)),
        );
    } else if let Some(limit) = req.limit {
        ui.label(RichText::new(format!("memory limit {}", human_bytes(limit))).small().weak());
    }
    if let Some(b) = &doc.jobs.busy.subdividing {
        ui.horizontal(|ui| {
            ui.spinner();
            let d = b.done.load(Ordering::Relaxed);
            ui.add(
                egui::ProgressBar::new(d as f32 / b.total.max(1) as f32).text(format!("{} ({d}/{})", b.what, b.total)),
            );
        });
    }
    changed
}
