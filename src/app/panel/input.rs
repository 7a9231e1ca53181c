//! The 3D area's mouse and keyboard: camera motion, picking, the keys of
//! [`super::HELP`]. While Inspect is on a click picks for it, `Esc` leaves
//! it, and in its Corners mode the letters `n p o l r s u` walk the picked
//! corner instead of their usual toggles.

use super::PanelState;
use crate::app::command::Command;
use crate::app::display::Display;
use crate::app::doc::Doc;
use crate::app::inspect::{Action, Inspect, Mode};
use crate::app::probe::ray_at;
use crate::app::view::{View, cursor_ndc, viewport_aspect};
use egui::{Key, PointerButton, Sense};
use glam::Vec2;

/// Drags orbit or pan, the wheel zooms to the cursor, a double click fits, a
/// click picks a point of the surface (a control edge when edge picking is
/// on, the inspector's corner, vertex or face while Inspect is on); then
/// the keys.
pub(crate) fn scene_input(
    ui: &mut egui::Ui,
    rect: egui::Rect,
    (doc, view): (&Doc, &View),
    display: &mut Display,
    panel: &mut PanelState,
) -> Vec<Command> {
    let mut out = Vec::new();
    let inspect = &doc.inspect;
    let resp = ui.allocate_rect(rect, Sense::click_and_drag());
    if super::edit::edit_input(ui, (rect, &resp), (doc, view), panel, &mut out) {
        return out;
    }
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
        out.push(if inspect.on {
            Command::Inspect(Action::Pick(ray))
        } else if display.pick {
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
        out.extend(inspect_keys(ui, inspect));
        let walking = inspect.on && inspect.mode == Mode::Corners;
        out.extend(keys(ui, view, display, walking).into_iter().filter(|c| {
            // Esc leaves Inspect rather than clearing the picked point
            !(inspect.on && matches!(c, Command::ClearSurfacePick))
        }));
    }
    out
}

/// The operator keys of the Corners mode.
const WALK: [(Key, char); 7] =
    [(Key::N, 'n'), (Key::P, 'p'), (Key::O, 'o'), (Key::L, 'l'), (Key::R, 'r'), (Key::S, 's'), (Key::U, 'u')];

/// `Q` toggles Inspect; while it is on `Esc` leaves it and, in its Corners
/// mode, `n p o l r s u` walk the picked corner.
fn inspect_keys(ui: &egui::Ui, inspect: &Inspect) -> Vec<Command> {
    let pressed = |k: Key| ui.input(|i| i.key_pressed(k));
    let mut out = Vec::new();
    if pressed(Key::Q) {
        out.push(Command::Inspect(Action::Toggle));
    }
    if inspect.on && pressed(Key::Escape) {
        out.push(Command::Inspect(Action::Leave));
    }
    if inspect.on && inspect.mode == Mode::Corners {
        out.extend(WALK.iter().filter(|(k, _)| pressed(*k)).map(|&(_, c)| Command::Inspect(Action::Walk(c))));
    }
    out
}

/// The keys: display toggles edit the draft `display`, the rest are
/// commands; with `walking` (Inspect's Corners mode) the operator letters
/// are left to [`inspect_keys`].
fn keys(ui: &egui::Ui, view: &View, display: &mut Display, walking: bool) -> Vec<Command> {
    // Ctrl and Alt chords are the edit mode's (Ctrl+S saves, Alt+A selects
    // none), told by the modifiers each key was pressed with
    let plain = |k: Key| {
        ui.input(|i| {
            i.events.iter().any(|e| {
                matches!(e, egui::Event::Key { key, pressed: true, modifiers, .. }
                    if *key == k && !modifiers.command && !modifiers.alt)
            })
        })
    };
    let pressed = |k: Key| plain(k) && !(walking && WALK.iter().any(|w| w.0 == k));
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
        (pressed(Key::I), Command::Key(crate::app::keys::KeyAction::Insert)),
        (pressed(Key::ArrowRight), Command::Step(1)),
        (pressed(Key::ArrowLeft), Command::Step(-1)),
        (pressed(Key::Plus) || pressed(Key::Equals), Command::LevelUp),
        (pressed(Key::Minus), Command::LevelDown),
        (pressed(Key::Escape), Command::ClearSurfacePick),
    ];
    commands.into_iter().filter_map(|(on, c)| on.then_some(c)).collect()
}
