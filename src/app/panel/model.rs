//! The model section: the curve's controls, the bundled models, opening a
//! file, repair.

use super::PanelState;
use crate::app::command::Command;
use crate::app::doc::{BUILTIN_NAME, Doc};
use egui::RichText;

/// The shown Bezier curve's controls (nothing when no curve is shown).
fn curve_section(ui: &mut egui::Ui, doc: &Doc) -> Option<Command> {
    let mut c = (*doc.model.curve).clone()?;
    ui.label(
        RichText::new(format!(
            "Bezier curve: {} ({} control points, degree {})",
            c.name,
            c.control.len(),
            c.control.len() - 1
        ))
        .strong(),
    );
    let mut changed = ui.add(egui::Slider::new(&mut c.segments, 1..=512).text("segments")).changed();
    changed |= ui.checkbox(&mut c.construction, "de Casteljau construction").changed();
    changed |= ui.add_enabled(c.construction, egui::Slider::new(&mut c.t, 0.0..=1.0).text("t")).changed();
    let back = ui.button("Back to the mesh").clicked();
    ui.separator();
    if back { Some(Command::CloseCurve) } else { changed.then_some(Command::EditCurve(c)) }
}

/// The Open field and the file browser (the desktop).
#[cfg(not(target_arch = "wasm32"))]
fn open_field(ui: &mut egui::Ui, doc: &Doc, panel: &mut PanelState, out: &mut Vec<Command>) {
    use egui::Key;
    use std::path::PathBuf;
    ui.horizontal(|ui| {
        let edit = ui
            .add(egui::TextEdit::singleline(&mut panel.open_path).hint_text("path/to/model.obj").desired_width(170.0));
        let enter = edit.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
        if (ui.button("Open").clicked() || enter) && !panel.open_path.trim().is_empty() {
            out.push(Command::Open(PathBuf::from(panel.open_path.trim())));
        }
        if ui.button("Browse…").clicked() {
            let start = doc.model.path.as_ref().and_then(|p| p.parent().map(|d| d.to_path_buf()));
            panel.browser = Some(start.or_else(|| std::env::current_dir().ok()).unwrap_or_else(|| PathBuf::from("/")));
        }
    });
    ui.label(
        RichText::new(
            "…or drop a file on the window (.obj .ply .stl .off .gltf .glb .dae .ct, .bez patches, .bzc curves)",
        )
        .small()
        .weak(),
    );
}

/// The page's file picker (the browser: no paths, no folders).
#[cfg(target_arch = "wasm32")]
fn open_field(ui: &mut egui::Ui, _: &Doc, _: &mut PanelState, _: &mut Vec<Command>) {
    if ui.button("Open a file…").clicked() {
        crate::app::page::pick_file();
    }
    ui.label(
        RichText::new("…or drop one on the page (.obj .ply .stl .off .gltf .glb .dae .usda .usdc .usdz .ct), or name it by URL: ?model=https://…")
            .small()
            .weak(),
    );
}

/// Bundled models, the Open field and browser, repair.
pub(crate) fn model_section(ui: &mut egui::Ui, doc: &Doc, panel: &mut PanelState) -> Vec<Command> {
    let mut out: Vec<Command> = curve_section(ui, doc).into_iter().collect();
    let model = &doc.model;
    ui.label(RichText::new(format!("Model: {}", model.name)).strong());
    egui::ComboBox::from_id_salt("model").selected_text("Bundled models").show_ui(ui, |ui| {
        if ui.selectable_label(model.path.is_none(), BUILTIN_NAME).clicked() {
            out.push(Command::OpenBuiltin);
        }
        for p in &panel.bundled {
            let name = p.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            if ui.selectable_label(model.path.as_ref() == Some(p), name).clicked() {
                out.push(Command::Open(p.clone()));
            }
        }
    });
    open_field(ui, doc, panel, &mut out);
    let mut repair = doc.repair_on_open;
    if ui
        .checkbox(&mut repair, "Repair on open")
        .on_hover_text(
            "split non-manifold edges and vertices, orient faces consistently, drop degenerate and duplicate faces",
        )
        .changed()
    {
        out.push(Command::SetRepairOnOpen(repair));
    }
    if let Some(p) = &doc.status.failed
        && ui.button("Repair and open").on_hover_text(p.path.display().to_string()).clicked()
    {
        out.push(Command::RepairAndOpen(p.clone()));
    }
    if let Some(b) = &doc.jobs.busy.loading {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label(&b.what);
        });
    }
    out
}
