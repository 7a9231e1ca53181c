//! The 3D area's mouse and keyboard: camera motion, picking, the keys of
//! [`super::HELP`].

use crate::app::command::Command;
use crate::app::display::Display;
use crate::app::probe::ray_at;
use crate::app::view::{View, cursor_ndc, viewport_aspect};
use egui::{Key, PointerButton, Sense};
use glam::Vec2;

/// Drags orbit or pan, the wheel zooms to the cursor, a double click fits, a
/// click picks a point of the surface (a control edge when edge picking is
/// on); then the keys.
pub(crate) fn scene_input(ui: &mut egui::Ui, rect: egui::Rect, view: &View, display: &mut Display) -> Vec<Command> {
    let mut out = Vec::new();
    let resp = ui.allocate_rect(rect, Sense::click_and_drag());
    let shift = ui.input(|i| i.modifiers.shift);
    let delta = Vec2::new(resp.drag_delta().x, resp.drag_delta().y);
    let aspect = viewport_aspect(rect, display.side_by_side);
    if resp.dragged_by(PointerButton::Primary) && !shift {
        out.push(Command::Orbit(delta));
    } else if resp.dragged_by(PointerButton::Secondary)
        || resp.dragged_by(PointerButton::Middle)
        || resp.dragged_by(PointerButton::Primary)
    {
        out.push(Command::Pan { delta, height: rect.height() });
    }
    if resp.double_clicked() {
        out.push(Command::Fit);
    } else if resp.clicked()
        && let Some(pos) = resp.interact_pointer_pos()
    {
        let ray = ray_at(&view.camera, rect, display.side_by_side, pos);
        out.push(if display.pick {
            Command::Pick { origin: ray.origin, dir: ray.dir }
        } else {
            Command::PickSurface(ray)
        });
    }
    if let Some(pos) = resp.hover_pos() {
        let (scroll, zoom) = ui.input(|i| (i.smooth_scroll_delta.y, i.zoom_delta()));
        let factor = (-scroll * 0.0025).exp() / zoom;
        if (factor - 1.0).abs() > 1e-4 {
            out.push(Command::Zoom { factor, cursor: cursor_ndc(rect, display.side_by_side, pos), aspect });
        }
    }
    if !ui.ctx().egui_wants_keyboard_input() {
        out.extend(keys(ui, view, display));
    }
    out
}

/// The keys: display toggles edit the draft `display`, the rest are commands.
fn keys(ui: &egui::Ui, view: &View, display: &mut Display) -> Vec<Command> {
    let pressed = |k: Key| ui.input(|i| i.key_pressed(k));
    let toggles: [(Key, &mut bool); 5] = [
        (Key::W, &mut display.wireframe),
        (Key::C, &mut display.control),
        (Key::N, &mut display.normals),
        (Key::B, &mut display.side_by_side),
        (Key::T, &mut display.turntable),
    ];
    for (k, on) in toggles {
        if pressed(k) {
            *on = !*on;
        }
    }
    if pressed(Key::S) {
        display.cycle_surface();
    }
    let commands = [
        (pressed(Key::O), Command::SetOrthographic(!view.camera.orthographic)),
        (pressed(Key::F), Command::Fit),
        (pressed(Key::R), Command::ResetCamera),
        (pressed(Key::P), Command::Screenshot),
        (pressed(Key::Space), Command::TogglePlay),
        (pressed(Key::ArrowRight), Command::Step(1)),
        (pressed(Key::ArrowLeft), Command::Step(-1)),
        (pressed(Key::Plus) || pressed(Key::Equals), Command::LevelUp),
        (pressed(Key::Minus), Command::LevelDown),
        (pressed(Key::Escape), Command::ClearSurfacePick),
    ];
    commands.into_iter().filter_map(|(on, c)| on.then_some(c)).collect()
}
