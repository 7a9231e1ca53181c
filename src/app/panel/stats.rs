//! The statistics section, the error and the notice.

use super::sep;
use crate::app::command::Command;
use crate::app::doc::Doc;
use crate::app::view::View;
use egui::{Color32, RichText};

/// Counts of the control mesh and the result, phase times, frame times;
/// the error and the notice with their dismiss buttons.
pub(crate) fn stats_section(ui: &mut egui::Ui, doc: &Doc, view: &View) -> Vec<Command> {
    let m = &doc.model;
    let (c, t) = (&m.control.topo, &m.result.shown.topo);
    egui::Grid::new("stats").num_columns(3).striped(true).show(ui, |ui| {
        ui.label("");
        ui.label("control");
        match doc.adaptive_shown() {
            Some(_) => ui.label("adaptive"),
            None => ui.label(format!("level {}", m.made.level)),
        };
        ui.end_row();
        // a polygon mesh counts its polygons and their edges, not the
        // triangles and diagonals it is drawn with
        for (name, a, b) in [
            ("vertices", c.vertices, t.vertices),
            ("edges", c.edges - c.diagonals, t.edges - t.diagonals),
            ("faces", c.faces - c.diagonals, t.faces - t.diagonals),
            ("boundary loops", c.boundary_loops, t.boundary_loops),
            ("components", c.components, t.components),
        ] {
            ui.label(name);
            ui.label(sep(a as u64));
            ui.label(sep(b as u64));
            ui.end_row();
        }
        ui.label("genus");
        ui.label(c.genus.to_string());
        ui.label(t.genus.to_string());
        ui.end_row();
    });
    if let Some(s) = &m.made.stats {
        ui.label(format!(
            "{} ×{}: {:.1} ms (split+O {:.1}, edge points {:.1}, vertex points {:.1}); job {:.1} ms",
            m.made.scheme.name(),
            m.made.level,
            s.total_ms,
            s.split_ms,
            s.edge_ms,
            s.vertex_ms,
            m.made.job_ms
        ));
    }
    if let Some(a) = doc.adaptive_shown() {
        let s = &a.stats;
        ui.label(format!(
            "adaptive: {} triangles within {} px of the limit (largest measured {:.2} px), {} rounds, job {:.0} ms",
            sep(a.shown.topo.faces as u64),
            crate::app::adaptive::PIXELS,
            s.worst,
            s.rounds,
            a.ms
        ));
    }
    if let Some(p) = &doc.anim.playback {
        // the figures `subdiv animate --stats` prints
        ui.label(format!(
            "animation: plan_ms {:.1}, frame_ms {:.2} (median; positions and normals)",
            p.player.plan_ms(),
            p.player.frame_ms().unwrap_or(0.0)
        ));
    }
    let st = &view.stats;
    ui.label(format!(
        "frame {:.1} ms ({:.0} fps), last upload {:.1} ms, {}",
        st.frame_ms,
        1000.0 / st.frame_ms.max(0.01),
        st.upload_ms,
        crate::error::human_bytes(st.upload_bytes)
    ));
    ui.label(RichText::new(format!("{} · 3D renders {}", st.adapter, st.scene_renders)).small().weak());
    status_lines(ui, doc)
}

fn status_lines(ui: &mut egui::Ui, doc: &Doc) -> Vec<Command> {
    let mut out = Vec::new();
    if let Some(e) = &doc.status.error {
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(e.to_string()).color(Color32::from_rgb(255, 110, 90)));
            if ui.small_button("dismiss").clicked() {
                out.push(Command::DismissError);
            }
        });
    }
    if let Some(n) = &doc.status.notice {
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(n).color(Color32::from_rgb(120, 220, 130)));
            if ui.small_button("ok").clicked() {
                out.push(Command::DismissNotice);
            }
        });
    }
    out
}
