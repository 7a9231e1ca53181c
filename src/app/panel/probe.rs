//! The picked point: the control face and `(u, v)` under the click, the
//! exact limit there (or why not), the nearest control vertex; Copy puts
//! the same as plain text on the clipboard.

use crate::app::command::Command;
use crate::app::doc::Doc;
use crate::app::probe::Target;
use crate::subdiv::pick::{ControlFace, Limit, Pick};
use egui::RichText;
use glam::{DVec3, Vec3};

/// The picked point's facts, Copy and Clear; a hint when nothing is picked.
pub(crate) fn probe_section(ui: &mut egui::Ui, doc: &Doc) -> Vec<Command> {
    let mut out = Vec::new();
    let Some(probe) = &doc.model.probe else {
        let hint = if doc.display.pick {
            "Edge picking is on (Surface and tools): a click picks a control edge."
        } else {
            "Click the surface to pick a point: its control face, (u, v), exact limit and nearest control vertex."
        };
        ui.label(RichText::new(hint).small().weak());
        return out;
    };
    let p = &probe.pick;
    egui::Grid::new("probe").num_columns(2).striped(true).show(ui, |ui| {
        let prim = probe.prim.iter().map(|path| ("Prim", path.clone()));
        for (name, value) in prim.chain(rows(p, probe.ray.target, doc.adaptive_shown().is_some())) {
            ui.label(name);
            ui.label(RichText::new(value).monospace());
            ui.end_row();
        }
    });
    if probe.on_cage {
        ui.label("traced on the cage: the prims were refined apart, each by its own scheme");
    }
    if let Limit::Unavailable(why) = &p.limit {
        ui.label(format!("limit evaluation: not available for {why}"));
    }
    ui.horizontal(|ui| {
        if ui.button("Copy").on_hover_text("these facts as plain text").clicked() {
            ui.ctx().copy_text(p.to_string());
        }
        if ui.button("Clear (Esc)").clicked() {
            out.push(Command::ClearSurfacePick);
        }
    });
    out
}

/// The label and value of each fact shown.
fn rows(p: &Pick, target: Target, adaptive: bool) -> Vec<(&'static str, String)> {
    let v3 = |v: Vec3| format!("{:.5} {:.5} {:.5}", v.x, v.y, v.z);
    let d3 = |v: DVec3| format!("{:.5} {:.5} {:.5}", v.x, v.y, v.z);
    let surface = match target {
        Target::Result if adaptive => format!("{} limit, adaptive", p.scheme),
        Target::Result => format!("{} level {}", p.scheme, p.level),
        Target::Control => "control mesh".into(),
    };
    let mut rows = vec![("Surface", surface), ("Hit (drawn)", v3(p.point))];
    match p.face {
        ControlFace::Triangle { face, u, v } => {
            rows.push(("Control face", face.to_string()));
            rows.push(("u, v", format!("{u:.6} {v:.6}")));
        }
        ControlFace::Polygon { face, size, corner, ptex } => {
            rows.push(("Control face", format!("polygon {face} ({size} corners)")));
            rows.push(("Nearest corner", corner.to_string()));
            if let Some((p, u, v)) = ptex {
                rows.push(("Ptex face, u, v", format!("{p}  {u:.6} {v:.6}")));
            }
        }
    }
    let cv = &p.vertex;
    let boundary = if cv.boundary { ", boundary" } else { "" };
    rows.push(("Nearest vertex", format!("{} (valence {}{boundary})", cv.id, cv.valence)));
    if let Limit::Exact(s) = &p.limit {
        rows.push(("Limit position", d3(s.position)));
        rows.push(("Limit normal", d3(s.normal)));
        rows.push(("Mean H, Gauss K", format!("{:.4e} {:.4e}", s.mean, s.gaussian)));
        rows.push(("k1, k2", format!("{:.4e} {:.4e}", s.k1, s.k2)));
    }
    rows
}
