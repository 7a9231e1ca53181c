//! Picking a point of the surface: a click on the 3D area casts a ray
//! against what is drawn there ([`crate::subdiv::pick`]) and the panel
//! shows the control face, `(u, v)`, the exact limit and the nearest
//! control vertex. The ray is kept, so a new level or new points (a
//! smoothing, limit snapping) pick again along it.

use super::doc::Doc;
use super::view::{cursor_ndc, viewport_aspect};
use crate::render::Camera;
use crate::subdiv::pick::{Level, Pick, pick};
use glam::Vec3;

/// Which surface a click picks: the result, or the control mesh (the left
/// viewport side by side).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Target {
    /// The subdivision result as drawn.
    Result,
    /// The control mesh (level 0).
    Control,
}

/// A ray into the 3D area and what it picks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ray {
    /// Origin (world).
    pub(crate) origin: Vec3,
    /// Unit direction.
    pub(crate) dir: Vec3,
    /// The surface it is cast against.
    pub(crate) target: Target,
}

/// The picked point: the ray and what it found.
#[derive(Clone, Debug)]
pub(crate) struct Probe {
    /// The ray clicked.
    pub(crate) ray: Ray,
    /// What it hit.
    pub(crate) pick: Pick,
}

/// The ray under the point `pos` of the 3D area `rect` (points): in the
/// left or right viewport side by side (the left one shows the control
/// mesh).
pub(crate) fn ray_at(camera: &Camera, rect: egui::Rect, side_by_side: bool, pos: egui::Pos2) -> Ray {
    let aspect = viewport_aspect(rect, side_by_side);
    let (origin, dir) = camera.ray(cursor_ndc(rect, side_by_side, pos), aspect);
    let target = if side_by_side && pos.x < rect.center().x { Target::Control } else { Target::Result };
    Ray { origin, dir, target }
}

impl Doc {
    /// What `ray` hits, traced back to the control mesh; `None` when it
    /// misses, or when what is drawn is not a static surface (a curve, an
    /// animation frame).
    ///
    /// # Errors
    /// When the drawn level does not match what made it (a bug: the worker
    /// sets both together).
    pub(crate) fn cast(&self, ray: Ray) -> crate::Result<Option<Pick>> {
        let m = &self.model;
        if m.curve.is_some() || self.anim.active {
            return Ok(None);
        }
        let control = &*m.control.mesh;
        let (drawn, level) = match ray.target {
            Target::Control => (control, 0),
            Target::Result => (&*m.result.shown.mesh, m.made.level),
        };
        let level = Level { control, drawn, scheme: m.made.scheme, level, precise: m.precise_control() };
        pick(&level, &m.made.opts, ray.origin, ray.dir)
    }

    /// Picks the point under `ray` (a miss clears the pick).
    pub(crate) fn pick_surface(&mut self, ray: Ray) {
        if self.anim.active {
            self.status.notice = Some("picking the surface is off in the animation mode (stop it to pick)".into());
            return;
        }
        self.set_probe(ray);
    }

    /// Casts the kept ray again, after the drawn surface changed.
    pub(crate) fn repick(&mut self) {
        if let Some(ray) = self.model.probe.as_ref().map(|p| p.ray) {
            self.set_probe(ray);
        }
    }

    fn set_probe(&mut self, ray: Ray) {
        match self.cast(ray) {
            Ok(pick) => self.model.probe = pick.map(|pick| Probe { ray, pick }),
            Err(e) => {
                self.model.probe = None;
                self.fail(e.into());
            }
        }
    }
}
