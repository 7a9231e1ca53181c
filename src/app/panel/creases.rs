//! The sharp features section: what the control mesh has (counts), the
//! boundary and creasing options, tagging by angle, the picked edge's
//! sharpness, and saving the control mesh with its tags.

use super::PanelState;
use crate::app::command::Command;
use crate::app::display::Display;
use crate::app::doc::Doc;
use crate::mesh::sharpness::INFINITE;
use crate::mesh::{BoundaryInterpolation, Creasing};
use egui::RichText;

/// The section; display toggles edit the draft `display`.
pub(crate) fn creases_section(
    ui: &mut egui::Ui,
    doc: &Doc,
    panel: &mut PanelState,
    display: &mut Display,
) -> Vec<Command> {
    let mut out = Vec::new();
    let ct = &doc.model.control.mesh.ct;
    let s = crate::subdiv::rules::features::summary(ct, doc.request.opts.boundary);
    ui.label(
        RichText::new(format!(
            "{} sharp edges ({} infinite), {} sharp vertices; {} corners, {} darts, {} crease vertices",
            s.sharp_edges, s.infinite_edges, s.sharp_vertices, s.corners, s.darts, s.crease_vertices
        ))
        .small(),
    );
    out.extend(options(ui, doc));
    ui.horizontal(|ui| {
        let slider = ui.add(egui::Slider::new(&mut panel.crease_angle, 1.0..=120.0).suffix("°").text("angle"));
        if slider.drag_stopped() || ui.button("Tag").on_hover_text(TAG_HELP).clicked() {
            out.push(Command::AutoCrease(panel.crease_angle));
        }
        if ui.add_enabled(ct.sharpness().is_some(), egui::Button::new("Clear")).clicked() {
            out.push(Command::ClearCreases);
        }
    });
    ui.checkbox(&mut display.sharp_edges, "Show sharp edges (magenta)");
    ui.checkbox(&mut display.click_creases, "A picking click toggles the crease")
        .on_hover_text("with \"Pick control edges\" on: a click makes the edge infinitely sharp, or smooth again");
    if let Some(c) = *doc.model.picked {
        let mut sharpness = ct.sharpness().map_or(0.0, |s| s.corner(c));
        let border = ct.o(c).is_none();
        let slider = egui::Slider::new(&mut sharpness, 0.0..=INFINITE).text("picked edge's sharpness");
        if ui.add_enabled(!border, slider).on_hover_text(SHARPNESS_HELP).changed() {
            out.push(Command::SetSharpness { corner: c, sharpness });
        }
    }
    ui.horizontal(|ui| {
        ui.add(egui::TextEdit::singleline(&mut panel.save_path).desired_width(150.0));
        if ui.button("Save control").on_hover_text("the control mesh as OBJ or .ct, with its sharpness tags").clicked()
        {
            out.push(Command::SaveControl(panel.save_path.clone().into()));
        }
    });
    out
}

const TAG_HELP: &str = "make every edge whose faces' normals differ by more than the angle infinitely sharp \
(replaces earlier angle tags; the file's own tags stay)";
const SHARPNESS_HELP: &str = "0 smooth, up to 10 semi-sharp (sharp for about that many levels), 10 infinitely sharp";

/// Boundary interpolation and the creasing method: a new request when changed.
fn options(ui: &mut egui::Ui, doc: &Doc) -> Option<Command> {
    let mut req = doc.request;
    let mut changed = false;
    ui.horizontal(|ui| {
        egui::ComboBox::from_id_salt("boundary")
            .selected_text(match req.opts.boundary {
                BoundaryInterpolation::EdgeOnly => "boundary: edges",
                BoundaryInterpolation::EdgeAndCorner => "boundary: edges and corners",
                BoundaryInterpolation::None => "boundary: none (border faces left out)",
            })
            .show_ui(ui, |ui| {
                changed |=
                    ui.selectable_value(&mut req.opts.boundary, BoundaryInterpolation::EdgeOnly, "edges").changed();
                changed |= ui
                    .selectable_value(&mut req.opts.boundary, BoundaryInterpolation::EdgeAndCorner, "edges and corners")
                    .changed();
                changed |= ui
                    .selectable_value(
                        &mut req.opts.boundary,
                        BoundaryInterpolation::None,
                        "none (border faces left out)",
                    )
                    .changed();
            });
        egui::ComboBox::from_id_salt("creasing")
            .selected_text(match req.opts.creasing {
                Creasing::Uniform => "creasing: uniform",
                Creasing::Chaikin => "creasing: Chaikin",
            })
            .show_ui(ui, |ui| {
                changed |= ui.selectable_value(&mut req.opts.creasing, Creasing::Uniform, "uniform").changed();
                changed |= ui.selectable_value(&mut req.opts.creasing, Creasing::Chaikin, "Chaikin").changed();
            });
    });
    changed.then_some(Command::Subdivide(req))
}
