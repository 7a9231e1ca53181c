//! The Inspect section: on and off (`Q`), the sub-mode (Corners, Stencil,
//! Split) and what its pick shows: a corner's operators with buttons that
//! walk them, a stencil's rules and weights (Copy), a split's table of
//! child corner entries derived by formula beside the child table's.

use crate::app::command::Command;
use crate::app::doc::Doc;
use crate::app::inspect::split::SplitView;
use crate::app::inspect::{Action, Mode, PickedCorner};
use crate::render::inspect::weight_text;
use crate::subdiv::stencil::Stencil;
use egui::{Color32, RichText};

/// What a click does in each mode, and the keys.
fn hint(mode: Mode) -> &'static str {
    match mode {
        Mode::Corners => {
            "Click near a vertex inside a face: that corner. Keys n p o l r s u walk its operators \
             (in Corners mode only; N P O R S do not toggle their display options meanwhile). Esc leaves Inspect."
        }
        Mode::Stencil => {
            "Click near a vertex: its weights over the control vertices, drawn on the cage (discs sized by \
             |weight|, red positive, blue negative). Esc leaves Inspect."
        }
        Mode::Split => {
            "Click a face of level 1 or more: its parent one level down, the children, the new vertices' rules \
             and how each child corner's O (twin) entry follows from the parent's. Esc leaves Inspect."
        }
    }
}

/// The section.
pub(crate) fn inspect_section(ui: &mut egui::Ui, doc: &Doc) -> Vec<Command> {
    let mut out = Vec::new();
    let i = &doc.inspect;
    ui.horizontal_wrapped(|ui| {
        let mut on = i.on;
        if ui.checkbox(&mut on, "Inspect (Q)").changed() {
            out.push(Command::Inspect(Action::Toggle));
        }
        for m in Mode::ALL {
            if ui.selectable_label(i.mode == m, m.name()).clicked() {
                out.push(Command::Inspect(Action::SetMode(m)));
            }
        }
    });
    ui.label(RichText::new(hint(i.mode)).small().weak());
    if let Some(msg) = &i.message {
        ui.label(RichText::new(msg).color(Color32::from_rgb(240, 200, 90)));
    }
    if doc.jobs.busy.inspecting.is_some() {
        ui.label(RichText::new("working…").weak());
    }
    if !i.current(&doc.model.raw.mesh) {
        if i.shown.is_some() {
            ui.label(RichText::new("The level shown changed: click again.").small().weak());
        }
        return out;
    }
    match i.mode {
        Mode::Corners => {
            if let Some(c) = &i.corner {
                out.extend(corner_view(ui, c));
            }
        }
        Mode::Stencil => {
            if let Some(st) = &i.stencil {
                stencil_view(ui, st);
            }
        }
        Mode::Split => {
            if let Some(s) = &i.split {
                split_view(ui, s);
            }
        }
    }
    out
}

/// The key that walks an operator of either table.
fn key_of(name: &str) -> char {
    match name {
        "next" => 'n',
        "prev" => 'p',
        "twin" => 'o',
        "swing" => 's',
        _ => name.chars().next().unwrap_or('?'),
    }
}

/// The picked corner and its operators, each a button that walks to it.
fn corner_view(ui: &mut egui::Ui, c: &PickedCorner) -> Vec<Command> {
    use crate::app::inspect::Ops;
    let mut out = Vec::new();
    let head = match c.ops() {
        Some(Ops::Triangle(x)) => {
            format!("corner {} of triangle {} (vertex {}), triangle table", x.corner, x.triangle, x.vertex)
        }
        Some(Ops::Polygon(x)) => format!("corner {} of face {} (vertex {}), quad table", x.corner, x.face, x.vertex),
        None => return out,
    };
    ui.label(RichText::new(head).strong());
    egui::Grid::new("inspect-corner").num_columns(2).striped(true).show(ui, |ui| {
        for (name, target) in c.rows() {
            let walk = ui.add_enabled(target.is_some(), egui::Button::new(RichText::new(name).monospace()));
            if walk.on_hover_text(format!("walk to {name}(c) (key {})", key_of(name))).clicked() {
                out.push(Command::Inspect(Action::Walk(key_of(name))));
            }
            // the value in its arrow's colour
            let [r, g, b, _] = crate::render::inspect::op_color(name);
            let value = target.map_or_else(|| "border".into(), |t| t.to_string());
            ui.label(RichText::new(value).monospace().color(Color32::from_rgb(r, g, b)));
            ui.end_row();
        }
    });
    out
}

/// A stencil as plain text (what Copy puts on the clipboard).
pub(crate) fn stencil_text(st: &Stencil) -> String {
    let sum: f64 = st.weights.iter().map(|w| w.1).sum();
    let mut s = format!(
        "vertex {} of level {} of {}: {} control vertices, weights summing to {sum}\n",
        st.vertex,
        st.level,
        st.scheme,
        st.weights.len()
    );
    for (level, rule) in &st.rules {
        s += &format!("level {level}: {rule}\n");
    }
    for (j, w) in &st.weights {
        s += &format!("{j} {w} ({})\n", weight_text(*w));
    }
    s
}

/// The rules by level and the weights, with their sum, and Copy.
fn stencil_view(ui: &mut egui::Ui, st: &Stencil) {
    let sum: f64 = st.weights.iter().map(|w| w.1).sum();
    ui.label(RichText::new(format!("vertex {} of {} level {}", st.vertex, st.scheme, st.level)).strong());
    for (level, rule) in &st.rules {
        ui.label(format!("level {level}: {rule}"));
    }
    egui::Grid::new("inspect-stencil").num_columns(3).striped(true).show(ui, |ui| {
        ui.label(RichText::new("control vertex").weak());
        ui.label(RichText::new("weight").weak());
        ui.label("");
        ui.end_row();
        for &(j, w) in &st.weights {
            ui.label(RichText::new(j.to_string()).monospace());
            ui.label(RichText::new(weight_text(w)).monospace());
            ui.label(RichText::new(format!("{w:.6}")).monospace().weak());
            ui.end_row();
        }
        ui.label(RichText::new("sum").strong());
        ui.label(RichText::new(weight_text(sum)).monospace().strong());
        ui.label(RichText::new(format!("{sum:.6}")).monospace().weak());
        ui.end_row();
    });
    if ui.button("Copy").on_hover_text("the rules and the weights as plain text").clicked() {
        ui.ctx().copy_text(stencil_text(st));
    }
}

/// A split as plain text (what Copy puts on the clipboard).
pub(crate) fn split_text(s: &SplitView) -> String {
    let (child, parent) = s.face_words();
    let mut t = format!(
        "{child} {} of level {} is a child of {parent} {} of level {} (corners {:?}); children {:?}\n",
        s.picked,
        s.level,
        s.parent,
        s.level - 1,
        s.parent_corners,
        s.children
    );
    for (v, rule) in &s.new_vertices {
        t += &format!("new vertex {v}: {rule}\n");
    }
    for r in &s.rows {
        let id = |x: Option<u32>| x.map_or_else(|| "border".into(), |c| c.to_string());
        t += &format!("{}  {}  {}  = {}  table {}\n", r.corner, r.formula, r.worked, id(r.derived), id(r.table));
    }
    t
}

/// The parent, the children, the new vertices' rules and the table of
/// child corner entries.
fn split_view(ui: &mut egui::Ui, s: &SplitView) {
    let (child, parent) = s.face_words();
    let head =
        format!("{child} {} of level {}, a child of {parent} {} of level {}", s.picked, s.level, s.parent, s.level - 1);
    ui.label(RichText::new(head).strong());
    ui.label(format!("parent corners c: {:?}; children: {:?}", s.parent_corners, s.children));
    for (v, rule) in &s.new_vertices {
        ui.label(format!("new vertex {v}: {rule}"));
    }
    let entry = if child == "triangle" { "O'" } else { "T'" };
    ui.label(
        RichText::new(format!("{entry} of every child corner, by the split's formula and in the child table")).weak(),
    );
    if s.all_agree() {
        ui.label(RichText::new(format!("all {} entries agree", s.rows.len())).color(Color32::from_rgb(110, 210, 120)));
    }
    // two lines a child corner: the formula, then its numbers and the table's entry
    let id = |x: Option<u32>| x.map_or_else(|| "border".into(), |c| c.to_string());
    for (k, r) in s.rows.iter().enumerate() {
        if k % 4 == 0 {
            ui.separator();
            ui.label(RichText::new(format!("c = {}", s.parent_corners[k / 4])).strong());
        }
        ui.label(RichText::new(format!("{}: {}", r.corner, r.formula)).monospace());
        let (verdict, color) = if r.derived == r.table {
            ("agrees", Color32::from_rgb(110, 210, 120))
        } else {
            ("DIFFERS", Color32::from_rgb(240, 90, 80))
        };
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(format!("  {} = {}", r.worked, id(r.derived))).monospace().weak());
            ui.label(RichText::new(format!("table {} {verdict}", id(r.table))).monospace().color(color));
        });
    }
    if ui.button("Copy").on_hover_text("the split's facts and table as plain text").clicked() {
        ui.ctx().copy_text(split_text(s));
    }
}
