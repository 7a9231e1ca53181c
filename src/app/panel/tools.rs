//! The surface and tools section: normals, limit snapping, colouring,
//! smoothing, picking and editing control edges.

use super::PanelState;
use crate::app::command::Command;
use crate::app::display::{Coloring, Display, NormalMode};
use crate::app::doc::Doc;
use egui::RichText;

/// Normals, snapping and colouring edit the draft `display`; the tools return commands.
pub(crate) fn tools_section(
    ui: &mut egui::Ui,
    doc: &Doc,
    panel: &mut PanelState,
    display: &mut Display,
) -> Vec<Command> {
    egui::ComboBox::from_label("Normals").selected_text(display.normal_mode.name()).show_ui(ui, |ui| {
        for m in NormalMode::ALL {
            ui.selectable_value(&mut display.normal_mode, m, m.name());
        }
    });
    ui.checkbox(&mut display.snap_limit, "Snap to limit positions").on_hover_text(
        "move every vertex to its limit point: on the Catmull-Clark surface for Catmull-Clark, else on Loop's",
    );
    // the curvature colourings exist for the schemes with an exact limit
    let refusal = crate::subdiv::eval::color::check_scheme(doc.model.made.scheme).err();
    egui::ComboBox::from_label("Colour").selected_text(display.coloring.name()).show_ui(ui, |ui| {
        for c in Coloring::ALL {
            match (&refusal, c) {
                (Some(why), Coloring::Curvature(_)) => {
                    let item = ui.add_enabled_ui(false, |ui| ui.selectable_value(&mut display.coloring, c, c.name()));
                    item.inner.on_disabled_hover_text(why.to_string());
                }
                _ => {
                    ui.selectable_value(&mut display.coloring, c, c.name());
                }
            }
        }
    });
    if let Coloring::Curvature(_) = display.coloring {
        isolines_control(ui, display);
        range_control(ui, panel, display);
    }
    coloring_legend(ui, doc, display);
    let mut out = Vec::new();
    ui.horizontal(|ui| {
        ui.add(egui::DragValue::new(&mut panel.smooth_steps).range(1..=200).suffix(" steps"));
        if ui.button("Smooth (Taubin)").on_hover_text("lambda 0.6307, mu -0.6732 on the control mesh").clicked() {
            out.push(Command::Smooth(panel.smooth_steps));
        }
        if ui.add_enabled(doc.model.original.is_some(), egui::Button::new("Revert")).clicked() {
            out.push(Command::Revert);
        }
    });
    ui.checkbox(&mut display.pick, "Pick control edges (click)");
    if let Some((a, b)) = doc.model.picked_edge() {
        ui.horizontal(|ui| {
            ui.label(format!("edge ({a}, {b})"));
            if ui.button("Flip").clicked() {
                out.push(Command::FlipPicked);
            }
            if ui.button("Split").clicked() {
                out.push(Command::SplitPicked);
            }
            let hole = doc.model.picked_face_is_hole();
            let label = if hole { "Fill hole" } else { "Punch hole" };
            let tip = "the face of the edge leaves the surface (its vertices still shape the rest), or comes back";
            if ui.button(label).on_hover_text(tip).clicked() {
                out.push(Command::ToggleHolePicked);
            }
        });
    }
    out
}

/// The isolines over a curvature colouring: on or off, and how many per
/// side of zero.
fn isolines_control(ui: &mut egui::Ui, display: &mut Display) {
    let iso = &mut display.isolines;
    ui.horizontal(|ui| {
        ui.checkbox(&mut iso.on, "Isolines").on_hover_text(
            "contour lines of the curvature at evenly spaced levels of the colour range; the zero level is the wider line",
        );
        let slider = egui::Slider::new(&mut iso.count, 1..=crate::subdiv::eval::color::MAX_ISOLINES).suffix(" per side");
        ui.add_enabled(iso.on, slider).on_hover_text("levels evenly spaced between 0 and each end of the range");
    });
}

/// The half-width of the curvature colours' range: a number, or empty for
/// the default percentile. Taken when the field loses focus (Enter); a bad
/// entry is shown beside it and changes nothing.
fn range_control(ui: &mut egui::Ui, panel: &mut PanelState, display: &mut Display) {
    let id = ui.make_persistent_id("curvature range");
    if !ui.memory(|m| m.has_focus(id)) && panel.range_error.is_none() {
        // show what is in use (set by --range, or by an earlier entry)
        panel.range_text = display.range.map(|r| r.to_string()).unwrap_or_default();
    }
    ui.horizontal(|ui| {
        ui.label("Range ±");
        let field = egui::TextEdit::singleline(&mut panel.range_text).id(id).hint_text("auto").desired_width(70.0);
        let response = ui.add(field).on_hover_text(format!(
            "the colours span [-R, R]; empty: auto, the {}th percentile of |curvature| by area",
            crate::subdiv::eval::color::PERCENTILE
        ));
        if response.lost_focus() {
            match range_field(&panel.range_text) {
                Ok(r) => {
                    display.range = r;
                    panel.range_error = None;
                }
                Err(e) => panel.range_error = Some(e),
            }
        }
    });
    if let Some(e) = &panel.range_error {
        ui.label(RichText::new(e).small().color(egui::Color32::from_rgb(220, 90, 80)));
    }
}

/// What the range field holds: empty (or `auto`) for the default
/// percentile, else a half-width above 0.
pub(crate) fn range_field(text: &str) -> Result<Option<crate::subdiv::eval::color::HalfWidth>, String> {
    match text.trim() {
        "" | "auto" => Ok(None),
        t => t.parse().map(Some),
    }
}

/// What the colours mean, or why there are none.
fn coloring_legend(ui: &mut egui::Ui, doc: &Doc, display: &Display) {
    let m = &doc.model;
    let coloring = display.coloring;
    if let Coloring::Curvature(kind) = coloring {
        match (&m.result.values, m.result.scale) {
            (Some(_), Some(scale)) => curvature_bar(ui, (kind, scale), m.made.scheme, display.look().isolines),
            _ => {
                let why = crate::subdiv::eval::color::check_scheme(m.made.scheme).err();
                let text = why.map_or_else(|| "no curvature: the colouring failed".into(), |e| e.to_string());
                ui.label(RichText::new(text).small());
            }
        }
        return;
    }
    let text = match coloring {
        Coloring::Shells => format!("dark: level 0 vertices … bright: level {}", m.made.level),
        Coloring::Displacement => format!("dark: on the control mesh … bright: {:.4} away", m.result.color_max),
        Coloring::File if m.attrs.file.colors.is_none() => {
            "this model has no vertex colours (OBJ `v x y z r g b`)".into()
        }
        Coloring::Checker if m.attrs.file.uv.is_none() => {
            "this model has no texture coordinates (OBJ `vt`); try models/cube_uv.obj".into()
        }
        Coloring::Checker => "UVs per corner (seams kept), linear inside each triangle".into(),
        Coloring::Material => match &m.attrs.file.materials {
            None => "this model has no materials (OBJ `usemtl` with an `mtllib`)".into(),
            Some(g) => format!(
                "{} materials; textures sampled at the corners of the shown mesh (sharper with each level)",
                g.list.len()
            ),
        },
        Coloring::File | Coloring::None | Coloring::Curvature(_) => return,
    };
    ui.label(RichText::new(text).small());
}

/// The curvature colours' bar: the diverging map from `-range` (blue)
/// through 0 (white) to `range` (red), with its numbers and a tick at each
/// of `isolines` levels per side (none for 0), under a caption saying the
/// curvature and the range in use (set, or the default percentile).
fn curvature_bar(
    ui: &mut egui::Ui,
    (kind, scale): (crate::subdiv::eval::color::CurvatureKind, crate::subdiv::eval::color::Scale),
    scheme: crate::Scheme,
    isolines: u8,
) {
    use crate::subdiv::eval::color::{diverging, short};
    ui.label(RichText::new(format!("{}, {}", kind.words(), scale.describe())).small());
    let (rect, _) = ui.allocate_exact_size(egui::vec2(ui.available_width().min(220.0), 12.0), egui::Sense::hover());
    let steps = 48;
    for i in 0..steps {
        let t = (i as f32 + 0.5) / steps as f32 * 2.0 - 1.0;
        let c = diverging(t);
        let srgb = |x: f32| (if x <= 0.0031308 { 12.92 * x } else { 1.055 * x.powf(1.0 / 2.4) - 0.055 } * 255.0) as u8;
        let x0 = rect.left() + rect.width() * i as f32 / steps as f32;
        let r = egui::Rect::from_min_max(
            egui::pos2(x0, rect.top()),
            egui::pos2(x0 + rect.width() / steps as f32 + 0.5, rect.bottom()),
        );
        ui.painter().rect_filled(r, 0.0, egui::Color32::from_rgb(srgb(c.x), srgb(c.y), srgb(c.z)));
    }
    let n = i32::from(isolines);
    for k in (-n..=n).filter(|_| n > 0) {
        let x = rect.center().x + rect.width() * 0.5 * k as f32 / (n + 1) as f32;
        let (width, top) = if k == 0 { (2.0, rect.top()) } else { (1.0, rect.center().y) };
        let stroke = egui::Stroke::new(width, egui::Color32::from_gray(20));
        ui.painter().line_segment([egui::pos2(x, top), egui::pos2(x, rect.bottom())], stroke);
    }
    ui.horizontal(|ui| {
        ui.label(RichText::new(short(-scale.half)).small());
        ui.add_space(60.0);
        ui.label(RichText::new("0").small());
        ui.add_space(60.0);
        ui.label(RichText::new(short(scale.half)).small());
    });
    let limit = if scheme == crate::Scheme::CatmullClark { "Catmull-Clark" } else { "Loop" };
    ui.label(
        RichText::new(format!("exact {limit} limit at each drawn vertex; beyond the range the colours saturate; grey: no curvature (at an extraordinary vertex itself)"))
            .small(),
    );
}

/// The adaptive display's checkbox: for the schemes with an exact limit
/// surface (Loop, Catmull-Clark).
pub(super) fn adaptive_row(ui: &mut egui::Ui, doc: &Doc, display: &mut Display) {
    let limit = matches!(doc.request.scheme, crate::Scheme::Loop | crate::Scheme::CatmullClark);
    let label = format!("Adaptive: the limit within {} px", crate::app::adaptive::PIXELS);
    let why = "draw the exact limit surface tessellated for the view: fine near the eye, coarse far away, re-tessellated when the view or the cage changes";
    let box_ = ui.add_enabled(limit || display.adaptive, egui::Checkbox::new(&mut display.adaptive, label));
    box_.on_hover_text(why).on_disabled_hover_text("Loop and Catmull-Clark have a limit surface to draw");
}
