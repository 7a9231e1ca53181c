//! The egui side panel, the 3D area's mouse and keyboard handling, and the
//! file browser.
//!
//! Every section reads the document and the view and returns the
//! [`Command`]s its widgets asked for; nothing here changes the document.
//! Widgets bound to several display options edit one draft [`Display`],
//! sent as a single [`Command::SetDisplay`] when it changed. Only the
//! panel's own widget state ([`PanelState`]: text fields, the browser's
//! folder) is changed in place.

mod animation;
mod browser;
mod creases;
mod edit;
mod input;
mod inspect;
mod model;
mod overlay;
mod probe;
mod stats;
mod subdivision;
mod tools;

#[cfg(test)]
pub(crate) use inspect::stencil_text;
#[cfg(test)]
pub(crate) use tools::range_field;

use super::command::Command;
use super::display::Display;
use super::doc::Doc;
use super::view::View;
use crate::render::{Surface, WireEdges};
use egui::RichText;
use std::path::PathBuf;

/// Keyboard help shown at the bottom of the panel.
pub(crate) const HELP: &str = "Mouse: left drag orbit, right/middle or shift+drag pan, wheel zoom to cursor, \
click pick a point, double click fit. Keys: E edit the cage (click select, G grab, X/Y/Z axis, A all, Shift+E sharpness), Ctrl+Z undo, Ctrl+S save, I insert an animation key, Q inspect (corners, stencils, splits), Esc clear the pick, W wireframe, S shading, +/- level, F fit, R reset, O ortho, C control mesh, N normals, \
B side by side, T turntable, Space play/pause, Left/Right step frame, P screenshot.";

/// The panel's own widget state.
pub(crate) struct PanelState {
    /// Path typed in the Open field.
    pub(crate) open_path: String,
    /// File browser open, and its directory.
    pub(crate) browser: Option<PathBuf>,
    /// Bundled model files (`bundled:NAME`).
    pub(crate) bundled: Vec<PathBuf>,
    /// Export file or directory.
    pub(crate) export_path: String,
    /// Export image side.
    pub(crate) export_size: u32,
    /// Taubin steps per click.
    pub(crate) smooth_steps: u32,
    /// Dihedral angle above which "Tag" makes edges sharp, degrees.
    pub(crate) crease_angle: f32,
    /// Where "Save control" writes.
    pub(crate) save_path: String,
    /// The curvature range field as typed (empty: auto).
    pub(crate) range_text: String,
    /// Why the range field's entry was refused.
    pub(crate) range_error: Option<String>,
    /// The Edit section's sharpness field.
    pub(crate) sharpness: f32,
    /// The sharpness typed after Shift+E.
    pub(crate) sharpness_text: Option<String>,
    /// Where a Ctrl+drag box started.
    pub(crate) box_start: Option<egui::Pos2>,
    /// A selected handle is being dragged.
    pub(crate) dragging_handle: bool,
    /// The Save As field is shown.
    pub(crate) save_as_open: bool,
    /// The animation key the key rows act on.
    pub(crate) key_index: usize,
    /// Where "Save paths" writes.
    pub(crate) paths_path: String,
}

impl PanelState {
    /// Defaults; `bundled` lists the models compiled into the binary.
    pub(crate) fn new() -> PanelState {
        PanelState {
            open_path: String::new(),
            browser: None,
            bundled: crate::bundled::MODELS.iter().map(|m| PathBuf::from(m.cli_name())).collect(),
            export_path: "subdiv-animation.gif".into(),
            export_size: 480,
            smooth_steps: 10,
            crease_angle: 40.0,
            save_path: "control.obj".into(),
            range_text: String::new(),
            range_error: None,
            sharpness: 2.5,
            sharpness_text: None,
            box_start: None,
            dragging_handle: false,
            save_as_open: false,
            key_index: 0,
            paths_path: "animation.paths".into(),
        }
    }
}

impl Default for PanelState {
    fn default() -> Self {
        PanelState::new()
    }
}

/// `1234567` as `1,234,567`.
fn sep(n: u64) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, ch) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(ch);
    }
    out
}

/// Draws the panel and handles the 3D area's input; returns the 3D area in
/// points and the commands asked for.
pub(crate) fn show(ui: &mut egui::Ui, doc: &Doc, view: &View, panel: &mut PanelState) -> (egui::Rect, Vec<Command>) {
    let mut out = Vec::new();
    let mut display = doc.display;
    egui::Panel::left("controls").default_size(300.0).resizable(true).show(ui, |ui| {
        // the whole panel scrolls, so a small window reaches every section;
        // each section folds, and egui keeps its open state by its title
        egui::ScrollArea::vertical().auto_shrink([false, false]).show(ui, |ui| {
            ui.heading("subdiv");
            out.extend(model::model_section(ui, doc, panel));
            egui::CollapsingHeader::new(RichText::new("Edit").strong())
                .default_open(false)
                .open(doc.edit.on.then_some(true))
                .show(ui, |ui| out.extend(edit::edit_section(ui, doc, panel)));
            section(ui, "Subdivision", true, |ui| out.extend(subdivision::subdivision_section(ui, doc)));
            section(ui, "Display", true, |ui| out.extend(display_section(ui, doc, view, &mut display)));
            section(ui, "Animation", false, |ui| out.extend(animation::animation_section(ui, doc, panel, &display)));
            section(ui, "Picked point", true, |ui| out.extend(probe::probe_section(ui, doc)));
            // open whenever Inspect is on, so that Q shows what it picks
            egui::CollapsingHeader::new(RichText::new("Inspect").strong())
                .default_open(false)
                .open(doc.inspect.on.then_some(true))
                .show(ui, |ui| out.extend(inspect::inspect_section(ui, doc)));
            section(ui, "Surface and tools", false, |ui| {
                out.extend(tools::tools_section(ui, doc, panel, &mut display));
            });
            section(ui, "Sharp features", false, |ui| {
                out.extend(creases::creases_section(ui, doc, panel, &mut display));
            });
            section(ui, "Statistics", true, |ui| out.extend(stats::stats_section(ui, doc, view)));
            ui.separator();
            ui.label(RichText::new(HELP).small().weak());
        });
    });
    let rect = ui.available_rect_before_wrap();
    out.extend(input::scene_input(ui, rect, (doc, view), &mut display, panel));
    overlay::overlay(ui, rect, doc, view, &display);
    edit::handles(ui, rect, doc, view, panel);
    out.extend(edit::dialogs(ui.ctx(), doc));
    out.extend(browser::file_browser(ui.ctx(), panel));
    if display != doc.display {
        out.push(Command::SetDisplay(display));
    }
    (rect, out)
}

/// A foldable section, open at first when `open`.
fn section(ui: &mut egui::Ui, title: &str, open: bool, body: impl FnOnce(&mut egui::Ui)) {
    egui::CollapsingHeader::new(RichText::new(title).strong()).default_open(open).show(ui, body);
}

/// Which edges the wireframe draws: all, the control edges, or those made
/// up to a level (at most the level shown).
fn wire_edges_row(ui: &mut egui::Ui, doc: &Doc, display: &mut Display) {
    let shown = doc.request.level.min(u32::from(u8::MAX)) as u8;
    ui.horizontal_wrapped(|ui| {
        ui.label("Edges");
        ui.selectable_value(&mut display.wire_edges, WireEdges::All, "all");
        ui.selectable_value(&mut display.wire_edges, WireEdges::UpTo(0), "control");
        let mut k = match display.wire_edges {
            WireEdges::UpTo(k) if k > 0 => k,
            _ => shown.max(1),
        };
        let up_to = matches!(display.wire_edges, WireEdges::UpTo(k) if k > 0);
        if ui.selectable_label(up_to, "up to level").clicked() {
            display.wire_edges = WireEdges::UpTo(k);
        }
        if ui.add_enabled(up_to, egui::DragValue::new(&mut k).range(1..=shown.max(1))).changed() {
            display.wire_edges = WireEdges::UpTo(k);
        }
    })
    .response
    .on_hover_text("Edges by the level that made them: control = the control mesh's edges on the surface");
}

/// The screenshot button with its scale and transparency.
fn screenshot_row(ui: &mut egui::Ui, view: &View) -> Vec<Command> {
    let mut out = Vec::new();
    if cfg!(target_arch = "wasm32") {
        return out; // the page has no screenshots (mod.rs)
    }
    let mut shot = view.shot;
    ui.horizontal(|ui| {
        if ui.button("Screenshot (P)").on_hover_text("The 3D area, rendered offscreen").clicked() {
            out.push(Command::Screenshot);
        }
        ui.add(egui::DragValue::new(&mut shot.scale).range(1..=4).suffix("x"));
        ui.checkbox(&mut shot.transparent, "transparent");
    });
    if shot != view.shot {
        out.push(Command::SetShot(shot));
    }
    out
}

/// The surface checks: zebra (reflection lines) and isophotes, with their
/// stripe count and the light bars' angle when one is on.
fn stripes_row(ui: &mut egui::Ui, display: &mut Display) {
    ui.horizontal(|ui| {
        ui.label("Check");
        ui.selectable_value(&mut display.surface, Surface::Zebra, "Zebra").on_hover_text(
            "reflection lines: a kink shows a jump in curvature, a jump in the stripes one in the normal",
        );
        ui.selectable_value(&mut display.surface, Surface::Isophotes, "Isophotes")
            .on_hover_text("bands of equal angle between the normal and the view");
    });
    if matches!(display.surface, Surface::Zebra | Surface::Isophotes) {
        ui.horizontal(|ui| {
            ui.add(egui::Slider::new(&mut display.stripes.count, 2..=48).text("stripes"));
            if display.surface == Surface::Zebra {
                ui.add(egui::Slider::new(&mut display.stripes.angle, -90..=90).text("angle°"));
            }
        });
    }
}

fn display_section(ui: &mut egui::Ui, doc: &Doc, view: &View, display: &mut Display) -> Vec<Command> {
    let mut out = Vec::new();
    ui.horizontal(|ui| {
        ui.label("Shading");
        ui.selectable_value(&mut display.surface, Surface::Smooth, "Phong");
        ui.selectable_value(&mut display.surface, Surface::Flat, "Flat");
        ui.selectable_value(&mut display.surface, Surface::Studio, "Studio");
        ui.selectable_value(&mut display.surface, Surface::Hidden, "None");
    });
    stripes_row(ui, display);
    ui.horizontal_wrapped(|ui| {
        ui.checkbox(&mut display.wireframe, "Wireframe (W)");
        ui.checkbox(&mut display.control, "Control mesh (C)");
        ui.checkbox(&mut display.normals, "Normals (N)");
        ui.checkbox(&mut display.side_by_side, "Side by side (B)");
        let mut ortho = view.camera.orthographic;
        if ui.checkbox(&mut ortho, "Orthographic (O)").changed() {
            out.push(Command::SetOrthographic(ortho));
        }
        ui.checkbox(&mut display.turntable, "Turntable (T)");
        if view.stats.msaa_available {
            ui.checkbox(&mut display.msaa, "Anti-aliasing (MSAA)")
                .on_hover_text("4x multisampling; costly on a software rasteriser with big meshes");
        }
        if !display.msaa {
            ui.checkbox(&mut display.fxaa, "Smooth edges (FXAA)")
                .on_hover_text("a post-process pass over the frame: cheap anti-aliasing where MSAA is off");
        }
    });
    tools::adaptive_row(ui, doc, display);
    if display.wireframe {
        wire_edges_row(ui, doc, display);
    }
    ui.horizontal(|ui| {
        if ui.button("Fit (F)").clicked() {
            out.push(Command::Fit);
        }
        if ui.button("Reset camera (R)").clicked() {
            out.push(Command::ResetCamera);
        }
    });
    out.extend(screenshot_row(ui, view));
    out
}
