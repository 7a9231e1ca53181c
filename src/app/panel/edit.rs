//! Editing the cage, as Blender's edit mode: `E` on or off; a click
//! selects a control vertex (Shift adds or removes, a click away from
//! every handle picks the edge under it), `A` all, `Alt+A` none, Ctrl+drag
//! a box; dragging a selected handle moves the selection in the view
//! plane; `G` grabs (`X` `Y` `Z` hold it to an axis, a typed number moves
//! exactly that far, Return or a click confirms, Esc or a right click
//! cancels, the wheel scales the proportional radius); `Shift+E` then a
//! number sets the sharpness of the picked edge or of the selected
//! vertices. Undo, redo and saving (`Ctrl+Z`, `Ctrl+Shift+Z` or `Ctrl+Y`,
//! `Ctrl+S`, `Ctrl+Shift+S`) work in any mode.

use super::PanelState;
use crate::app::command::Command;
use crate::app::doc::Doc;
use crate::app::edit::{Answer, Axis, EditAction, Pending};
use crate::app::view::{View, cursor_ndc, viewport_aspect};
use egui::{Color32, Event, Key, Pos2, Rect};
use glam::{Vec2, Vec3};

/// Handles drawn at most (a denser cage shows the selected ones only).
const MAX_HANDLES: usize = 20_000;

/// How near a click must be to a handle, points.
const HANDLE_REACH: f32 = 10.0;

/// The viewport the cage is edited in: the left one side by side.
fn cage_viewport(rect: Rect, side_by_side: bool) -> Rect {
    let mut vp = rect;
    if side_by_side {
        vp.set_width(rect.width() / 2.0);
    }
    vp
}

/// Where the control vertices fall on the screen: `None` behind the eye,
/// or on the far side of the cage (its normal facing away), as Blender
/// hides what the surface hides.
pub(crate) fn handle_positions(doc: &Doc, view: &View, rect: Rect) -> Vec<Option<Pos2>> {
    let side = doc.display.side_by_side;
    let (vp, aspect) = (cage_viewport(rect, side), viewport_aspect(rect, side));
    let vp_m = view.camera.view_proj(aspect);
    let (eye, forward, ortho) = (view.camera.eye(), view.camera.forward(), view.camera.orthographic);
    let control = &doc.model.control;
    let normals = control.normals.iter().copied().chain(std::iter::repeat(Vec3::ZERO));
    control
        .mesh
        .positions
        .iter()
        .zip(normals)
        .map(|(&p, n)| {
            let ndc = vp_m.project_point3(p);
            let toward = if ortho { -forward } else { eye - p };
            ((0.0..=1.0).contains(&ndc.z) && ndc.is_finite() && toward.dot(n) >= 0.0).then(|| to_screen(vp, ndc))
        })
        .collect()
}

/// A point of the viewport `vp` from its NDC.
fn to_screen(vp: Rect, ndc: Vec3) -> Pos2 {
    egui::pos2(vp.left() + (ndc.x + 1.0) * 0.5 * vp.width(), vp.top() + (1.0 - ndc.y) * 0.5 * vp.height())
}

/// The control vertex whose handle is nearest `at`, within reach.
fn nearest_handle(handles: &[Option<Pos2>], at: Pos2) -> Option<u32> {
    handles
        .iter()
        .enumerate()
        .filter_map(|(i, h)| h.map(|h| (i as u32, h.distance(at))))
        .filter(|&(_, d)| d <= HANDLE_REACH)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

/// The world offset of the cursor moved from `anchor` to `now` (NDC), at
/// the depth of `centroid`.
fn view_plane_offset(view: &View, aspect: f32, centroid: Vec3, anchor: Vec2, now: Vec2) -> Vec3 {
    let m = view.camera.view_proj(aspect);
    let z = m.project_point3(centroid).z;
    let inv = m.inverse();
    inv.project_point3(now.extend(z)) - inv.project_point3(anchor.extend(z))
}

/// The edit mode's mouse and keys over the 3D area; whether it took the
/// pointer (then the camera does not move).
pub(crate) fn edit_input(
    ui: &egui::Ui,
    (rect, resp): (Rect, &egui::Response),
    (doc, view): (&Doc, &View),
    panel: &mut PanelState,
    out: &mut Vec<Command>,
) -> bool {
    out.extend(history_keys(ui));
    if !resp.dragged() {
        panel.dragging_handle = false;
    }
    let side = doc.display.side_by_side;
    let cursor = ui.input(|i| i.pointer.hover_pos()).map(|p| cursor_ndc(rect, side, p));
    if !doc.edit.on {
        // E turns it on; what follows in the same frame is the mode's
        let events = ui.input(|i| i.events.clone());
        let e =
            |ev: &Event| matches!(ev, Event::Key { key: Key::E, pressed: true, modifiers, .. } if modifiers.is_none());
        if let Some(k) = events.iter().position(e) {
            out.push(Command::Edit(EditAction::Toggle));
            mode_keys(&events[k + 1..], cursor, panel, out);
        }
        return false;
    }
    let aspect = viewport_aspect(rect, side);
    let pointer = ui.input(|i| i.pointer.hover_pos());
    if let Some(g) = &doc.edit.grab {
        grab_input(ui, resp, (g, view, aspect), (pointer, rect, side), out);
        return true;
    }
    if sharpness_typing(ui, panel, out) {
        return true;
    }
    let handles = handle_positions(doc, view, rect);
    let shift = ui.input(|i| i.modifiers.shift);
    let ctrl = ui.input(|i| i.modifiers.command);
    if resp.drag_started_by(egui::PointerButton::Primary)
        && let Some(at) = resp.interact_pointer_pos()
    {
        if ctrl {
            panel.box_start = Some(at);
        } else if nearest_handle(&handles, at).is_some_and(|v| doc.edit.selected.binary_search(&v).is_ok()) {
            panel.dragging_handle = true;
            out.push(Command::Edit(EditAction::Grab { anchor: cursor_ndc(rect, side, at) }));
        }
    }
    if let Some(start) = panel.box_start {
        box_select(ui, resp, (start, &handles, shift), panel, out);
        return true;
    }
    if resp.clicked()
        && let Some(at) = resp.interact_pointer_pos()
    {
        match nearest_handle(&handles, at) {
            Some(v) => out.push(Command::Edit(EditAction::Select { ids: vec![v], add: shift })),
            None => {
                if !shift {
                    out.push(Command::Edit(EditAction::Select { ids: Vec::new(), add: false }));
                }
                let ray = crate::app::probe::ray_at(&view.camera, rect, side, at);
                out.push(Command::Pick { origin: ray.origin, dir: ray.dir });
            }
        }
        return true;
    }
    mode_keys(&ui.input(|i| i.events.clone()), cursor, panel, out);
    panel.dragging_handle
}

/// Ctrl+Z, Ctrl+Shift+Z or Ctrl+Y, Ctrl+S, Ctrl+Shift+S (each key with
/// the modifiers it was pressed with: a quick chord is over by the end of
/// the frame).
fn history_keys(ui: &egui::Ui) -> Vec<Command> {
    let events = ui.input(|i| i.events.clone());
    let chord = |e: &Event| match e {
        Event::Key { key, pressed: true, modifiers, .. } if modifiers.command => Some((*key, modifiers.shift)),
        _ => None,
    };
    events
        .iter()
        .filter_map(chord)
        .filter_map(|(key, shift)| match key {
            Key::Z if shift => Some(EditAction::Redo),
            Key::Z => Some(EditAction::Undo),
            Key::Y => Some(EditAction::Redo),
            Key::S if shift => Some(EditAction::AskPath),
            Key::S => Some(EditAction::Save),
            _ => None,
        })
        .map(Command::Edit)
        .collect()
}

/// E, G, A, Alt+A, Shift+E in the edit mode (not grabbing). The keys
/// typed after G or Shift+E in the same frame (a fast typist, a script)
/// are theirs, in the order they came.
fn mode_keys(events: &[Event], cursor: Option<Vec2>, panel: &mut PanelState, out: &mut Vec<Command>) {
    for (k, e) in events.iter().enumerate() {
        let Event::Key { key, pressed: true, modifiers, .. } = e else { continue };
        if modifiers.command {
            continue;
        }
        match key {
            Key::E if modifiers.shift => {
                panel.sharpness_text = Some(String::new());
                return sharpness_keys(&events[k + 1..], panel, out);
            }
            Key::E => out.push(Command::Edit(EditAction::Toggle)),
            Key::G => {
                out.push(Command::Edit(EditAction::Grab { anchor: cursor.unwrap_or(Vec2::ZERO) }));
                out.extend(grab_keys(&events[k + 1..], "").into_iter().map(Command::Edit));
                return;
            }
            Key::A if modifiers.alt => out.push(Command::Edit(EditAction::Select { ids: Vec::new(), add: false })),
            Key::A => out.push(Command::Edit(EditAction::SelectAll)),
            _ => {}
        }
    }
}

/// A grab's keys in the order they came: X Y Z hold it to an axis,
/// digits, a point and a minus type a distance (Backspace takes one
/// back), Return confirms, Esc cancels.
fn grab_keys(events: &[Event], typed: &str) -> Vec<EditAction> {
    let mut out = Vec::new();
    let mut t = typed.to_string();
    for e in events {
        match e {
            Event::Key { key, pressed: true, .. } => match key {
                Key::X => out.push(EditAction::Constrain(Axis::X)),
                Key::Y => out.push(EditAction::Constrain(Axis::Y)),
                Key::Z => out.push(EditAction::Constrain(Axis::Z)),
                Key::Backspace => {
                    t.pop();
                    out.push(EditAction::Typed(t.clone()));
                }
                Key::Enter => return [out, vec![EditAction::Confirm]].concat(),
                Key::Escape => return [out, vec![EditAction::Cancel]].concat(),
                _ => {}
            },
            Event::Text(s) if s.chars().any(number_char) => {
                t.extend(s.chars().filter(|&c| number_char(c)));
                out.push(EditAction::Typed(t.clone()));
            }
            _ => {}
        }
    }
    out
}

fn number_char(c: char) -> bool {
    c.is_ascii_digit() || c == '.' || c == '-'
}

/// Shift+E's number from `events`: typed, Return sets it, Esc drops it.
fn sharpness_keys(events: &[Event], panel: &mut PanelState, out: &mut Vec<Command>) {
    for e in events {
        let Some(t) = panel.sharpness_text.as_mut() else { return };
        match e {
            Event::Text(s) => t.extend(s.chars().filter(|&c| number_char(c))),
            Event::Key { key: Key::Backspace, pressed: true, .. } => _ = t.pop(),
            Event::Key { key: Key::Enter, pressed: true, .. } => {
                if let Ok(s) = t.parse::<f32>() {
                    out.push(Command::Edit(EditAction::Sharpness(s)));
                }
                panel.sharpness_text = None;
            }
            Event::Key { key: Key::Escape, pressed: true, .. } => panel.sharpness_text = None,
            _ => {}
        }
    }
}

/// During a grab: the mouse moves it, X Y Z hold it, numbers are typed,
/// Return or a click confirms, Esc or a right click cancels, the wheel
/// scales the radius.
fn grab_input(
    ui: &egui::Ui,
    resp: &egui::Response,
    (g, view, aspect): (&crate::app::edit::Grab, &View, f32),
    (pointer, rect, side): (Option<Pos2>, Rect, bool),
    out: &mut Vec<Command>,
) {
    if let Some(p) = pointer {
        let offset = view_plane_offset(view, aspect, g.centroid, g.anchor, cursor_ndc(rect, side, p));
        if offset != g.mouse {
            out.push(Command::Edit(EditAction::GrabTo(offset)));
        }
    }
    let keys = grab_keys(&ui.input(|i| i.events.clone()), &g.typed);
    let ended = keys.iter().any(|a| matches!(a, EditAction::Confirm | EditAction::Cancel));
    out.extend(keys.into_iter().map(Command::Edit));
    if ended {
        return;
    }
    let scroll = ui.input(|i| i.smooth_scroll_delta.y);
    if scroll.abs() > 0.5 {
        out.push(Command::Edit(EditAction::ScaleRadius((scroll * 0.005).exp())));
    }
    let released = resp.drag_stopped_by(egui::PointerButton::Primary);
    if resp.clicked() || released {
        out.push(Command::Edit(EditAction::Confirm));
    } else if resp.secondary_clicked() {
        out.push(Command::Edit(EditAction::Cancel));
    }
}

/// While Shift+E's number is typed, the frame's keys are its.
fn sharpness_typing(ui: &egui::Ui, panel: &mut PanelState, out: &mut Vec<Command>) -> bool {
    if panel.sharpness_text.is_none() {
        return false;
    }
    sharpness_keys(&ui.input(|i| i.events.clone()), panel, out);
    true
}

/// Ctrl+drag: the box follows the mouse; on release its handles are
/// selected (Shift adds).
fn box_select(
    ui: &egui::Ui,
    resp: &egui::Response,
    (start, handles, shift): (Pos2, &[Option<Pos2>], bool),
    panel: &mut PanelState,
    out: &mut Vec<Command>,
) {
    let Some(now) = ui.input(|i| i.pointer.hover_pos()) else { return };
    let r = Rect::from_two_pos(start, now);
    ui.painter().rect_stroke(r, 0.0, egui::Stroke::new(1.0, Color32::WHITE), egui::StrokeKind::Middle);
    if resp.drag_stopped() || !ui.input(|i| i.pointer.primary_down()) {
        panel.box_start = None;
        let ids = handles.iter().enumerate().filter(|(_, h)| h.is_some_and(|h| r.contains(h))).map(|(i, _)| i as u32);
        out.push(Command::Edit(EditAction::Select { ids: ids.collect(), add: shift }));
    }
}

/// The handles of the control vertices (selected ones orange), the
/// proportional radius around a grab, and what is being typed.
pub(crate) fn handles(ui: &egui::Ui, rect: Rect, doc: &Doc, view: &View, panel: &PanelState) {
    if !doc.edit.on {
        return;
    }
    let painter = ui.painter_at(rect);
    let all = handle_positions(doc, view, rect);
    let sel = &doc.edit.selected;
    let dark = egui::Stroke::new(1.0, Color32::from_black_alpha(200));
    if all.len() <= MAX_HANDLES {
        for h in all.iter().flatten() {
            painter.circle(*h, 3.0, Color32::from_gray(230), dark);
        }
    }
    paths(&painter, rect, doc, view);
    // the selection shows through: it is what a grab moves
    let sel_at = handle_points(doc, view, rect, sel);
    for h in sel_at {
        painter.circle(h, 4.5, Color32::from_rgb(255, 150, 30), dark);
    }
    let font = egui::FontId::proportional(15.0);
    let at = rect.left_bottom() + egui::vec2(12.0, -14.0);
    let accent = Color32::from_rgb(255, 200, 40);
    if let Some(g) = &doc.edit.grab {
        let d = g.offset();
        let axis = g.axis.map_or(String::new(), |a| format!(" along {a:?}"));
        let typed = if g.typed.is_empty() { String::new() } else { format!(" [{}]", g.typed) };
        let text = format!("Grab{axis}{typed}: D {:.4} {:.4} {:.4}  (Return confirms, Esc cancels)", d.x, d.y, d.z);
        painter.text(at, egui::Align2::LEFT_BOTTOM, text, font, accent);
        if doc.edit.proportional {
            radius_ring(&painter, rect, doc, view, g.centroid + d);
        }
    } else if let Some(t) = &panel.sharpness_text {
        let text = format!("Sharpness: {t}_  (Return sets, Esc cancels)");
        painter.text(at, egui::Align2::LEFT_BOTTOM, text, font, accent);
    }
}

/// Paths shown at most (one per selected vertex).
const MAX_PATHS: usize = 64;

/// The refined split-and-tweak paths of the selected vertices through
/// their keys (small squares), while an animation is built.
fn paths(painter: &egui::Painter, rect: Rect, doc: &Doc, view: &View) {
    let Some(p) = &doc.anim.playback else { return };
    let side = doc.display.side_by_side;
    let (vp, aspect) = (cage_viewport(rect, side), viewport_aspect(rect, side));
    let m = view.camera.view_proj(aspect);
    let screen = |q: Vec3| Some(m.project_point3(q)).filter(|n| (0.0..=1.0).contains(&n.z)).map(|n| to_screen(vp, n));
    let frames = p.player.frame_count();
    let line = egui::Stroke::new(1.5, Color32::from_rgb(120, 200, 255));
    for &v in doc.edit.selected.iter().take(MAX_PATHS) {
        let v = v as usize;
        let points: Vec<Pos2> =
            (0..=frames).filter_map(|f| p.player.control(f).get(v).copied().and_then(screen)).collect();
        painter.add(egui::Shape::line(points, line));
        if v < doc.anim.paths.vertex_count() {
            for q in doc.anim.paths.polygon(v).iter().filter_map(|&q| screen(q)) {
                painter.rect_filled(
                    Rect::from_center_size(q, egui::vec2(6.0, 6.0)),
                    1.0,
                    Color32::from_rgb(120, 200, 255),
                );
            }
        }
    }
}

/// Where the vertices `ids` fall on the screen, hidden or not.
fn handle_points(doc: &Doc, view: &View, rect: Rect, ids: &[u32]) -> Vec<Pos2> {
    let side = doc.display.side_by_side;
    let (vp, aspect) = (cage_viewport(rect, side), viewport_aspect(rect, side));
    let m = view.camera.view_proj(aspect);
    let pos = &doc.model.control.mesh.positions;
    ids.iter()
        .filter_map(|&v| pos.get(v as usize))
        .map(|&p| m.project_point3(p))
        .filter(|n| (0.0..=1.0).contains(&n.z) && n.is_finite())
        .map(|n| to_screen(vp, n))
        .collect()
}

/// The proportional radius as a circle around `centre`.
fn radius_ring(painter: &egui::Painter, rect: Rect, doc: &Doc, view: &View, centre: Vec3) {
    let side = doc.display.side_by_side;
    let (vp, aspect) = (cage_viewport(rect, side), viewport_aspect(rect, side));
    let m = view.camera.view_proj(aspect);
    let (right, _) = view.camera.right_up();
    let screen = |p: Vec3| {
        let n = m.project_point3(p);
        to_screen(vp, n)
    };
    let (c, e) = (screen(centre), screen(centre + right * doc.edit.radius));
    painter.circle_stroke(c, c.distance(e), egui::Stroke::new(1.5, Color32::from_white_alpha(160)));
}

/// The panel's Edit section: the mode, the selection, proportional
/// editing, sharpness, the history, saving.
pub(crate) fn edit_section(ui: &mut egui::Ui, doc: &Doc, panel: &mut PanelState) -> Vec<Command> {
    let mut out = Vec::new();
    let e = &doc.edit;
    let mut on = e.on;
    if ui.checkbox(&mut on, "Edit the cage (E)").changed() {
        out.push(Command::Edit(EditAction::Toggle));
    }
    ui.label(format!("{} of {} vertices selected", e.selected.len(), doc.model.control.mesh.positions.len()));
    let mut prop = e.proportional;
    ui.horizontal(|ui| {
        if ui.checkbox(&mut prop, "Proportional").changed() {
            out.push(Command::Edit(EditAction::SetProportional(prop)));
        }
        let mut r = e.radius;
        if ui.add(egui::DragValue::new(&mut r).speed(0.01).prefix("radius ")).changed() && r > 0.0 {
            out.push(Command::Edit(EditAction::ScaleRadius(r / e.radius)));
        }
    });
    ui.horizontal(|ui| {
        ui.add(egui::DragValue::new(&mut panel.sharpness).range(0.0..=10.0).speed(0.05));
        if ui.button("Set sharpness (Shift+E)").clicked() {
            out.push(Command::Edit(EditAction::Sharpness(panel.sharpness)));
        }
    });
    out.extend(history_list(ui, doc));
    out.extend(save_row(ui, doc, panel));
    out
}

/// Undo, redo and the steps, the undone ones greyed.
fn history_list(ui: &mut egui::Ui, doc: &Doc) -> Vec<Command> {
    let mut out = Vec::new();
    let h = &doc.edit.history;
    ui.horizontal(|ui| {
        if ui.add_enabled(!h.done.is_empty(), egui::Button::new("Undo (Ctrl+Z)")).clicked() {
            out.push(Command::Edit(EditAction::Undo));
        }
        if ui.add_enabled(!h.undone.is_empty(), egui::Button::new("Redo (Ctrl+Shift+Z)")).clicked() {
            out.push(Command::Edit(EditAction::Redo));
        }
    });
    egui::ScrollArea::vertical().max_height(120.0).id_salt("history").show(ui, |ui| {
        ui.label(egui::RichText::new("opened").weak());
        for (_, step) in &h.done {
            ui.label(step.label());
        }
        for (_, step) in h.undone.iter().rev() {
            ui.label(egui::RichText::new(step.label()).weak().italics());
        }
    });
    out
}

/// Save, Save As and its path.
fn save_row(ui: &mut egui::Ui, doc: &Doc, panel: &mut PanelState) -> Vec<Command> {
    let mut out = Vec::new();
    ui.horizontal(|ui| {
        let label = if doc.edit.history.dirty() { "Save (Ctrl+S) — unsaved changes" } else { "Save (Ctrl+S)" };
        if ui.button(label).clicked() {
            out.push(Command::Edit(EditAction::Save));
        }
    });
    if doc.edit.ask_path || panel.save_as_open {
        ui.horizontal(|ui| {
            ui.label("Save as");
            let r = ui.text_edit_singleline(&mut panel.save_path);
            let enter = r.lost_focus() && ui.input(|i| i.key_pressed(Key::Enter));
            if ui.button("Save").clicked() || enter {
                out.push(Command::Edit(EditAction::SaveAs(panel.save_path.clone().into())));
                panel.save_as_open = false;
            }
        });
    }
    out
}

/// The questions: recover a crashed session's edits, or what to do with
/// unsaved changes before closing or opening another model.
pub(crate) fn dialogs(ctx: &egui::Context, doc: &Doc) -> Vec<Command> {
    let mut out = Vec::new();
    if doc.edit.offer {
        egui::Window::new("Unsaved edits found").collapsible(false).resizable(false).show(ctx, |ui| {
            ui.label(format!("{} has edits from a session that did not end. Recover them?", doc.model.name));
            ui.horizontal(|ui| {
                if ui.button("Recover (Return)").clicked() || ctx.input(|i| i.key_pressed(Key::Enter)) {
                    out.push(Command::Edit(EditAction::Recover));
                }
                if ui.button("Discard (Esc)").clicked() || ctx.input(|i| i.key_pressed(Key::Escape)) {
                    out.push(Command::Edit(EditAction::DiscardRecovery));
                }
            });
        });
    }
    if let Some(p) = &doc.edit.pending {
        let what = match p {
            Pending::Close => "closing".to_string(),
            Pending::Open(input) => format!("opening {}", input.path.display()),
        };
        egui::Window::new("Unsaved changes").collapsible(false).resizable(false).show(ctx, |ui| {
            ui.label(format!("{} has unsaved changes. Save them before {what}?", doc.model.name));
            ui.horizontal(|ui| {
                for (label, a) in [("Save", Answer::Save), ("Discard", Answer::Discard), ("Cancel", Answer::Cancel)] {
                    if ui.button(label).clicked() {
                        out.push(Command::Answer(a));
                    }
                }
            });
        });
    }
    out
}
