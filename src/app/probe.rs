//! Picking a point of the surface: a click on the 3D area casts a ray
//! against what is drawn there ([`crate::subdiv::pick`]) and the panel
//! shows the control face, `(u, v)`, the exact limit and the nearest
//! control vertex. The ray is kept, so a new level or new points (a
//! smoothing, limit snapping) pick again along it.

use super::doc::Doc;
use super::view::{cursor_ndc, viewport_aspect};
use crate::render::Camera;
use crate::subdiv::pick::{Level, Pick, Tessellated, pick, pick_tessellated};
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
    /// The prim hit, when the model is a stage's prims.
    pub(crate) prim: Option<String>,
    /// Whether it was traced on the cage (prims refined apart).
    pub(crate) on_cage: bool,
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
        if self.traced_on_cage(ray) {
            return self.cast_on_cage(ray);
        }
        if let Some(t) = self.adaptive_shown().filter(|_| ray.target == Target::Result) {
            // the adaptive display: traced back through the tessellation's own faces
            let drawn = Tessellated { mesh: &t.shown.mesh, faces: &t.faces, corners: &t.corners };
            let how = (t.scheme, &t.opts);
            // the points the tessellation was made from (the file's digits where unmoved)
            let points = m.control_f64();
            return Ok(pick_tessellated((control, Some(&points)), how, &drawn, (ray.origin, ray.dir)));
        }
        let (drawn, level) = match ray.target {
            Target::Control => (control, 0),
            Target::Result => (&*m.result.shown.mesh, m.made.level),
        };
        let level = Level { control, drawn, scheme: m.made.scheme, level, precise: m.precise_control() };
        pick(&level, &m.made.opts, ray.origin, ray.dir)
    }

    /// Whether a pick is traced on the cage: when the drawn level is a
    /// stage's prims refined apart (no one refinement of the cage to
    /// trace it back through).
    fn traced_on_cage(&self, ray: Ray) -> bool {
        ray.target == Target::Result && self.model.made.by_prim
    }

    /// A pick on the cage, with the scheme and options of the prim hit:
    /// its control face, `(u, v)` and the exact limit of that prim's
    /// surface there.
    fn cast_on_cage(&self, ray: Ray) -> crate::Result<Option<Pick>> {
        let m = &self.model;
        let control = &*m.control.mesh;
        let Some(hit) = crate::mesh::pick::nearest_hit(control, ray.origin, ray.dir) else { return Ok(None) };
        let options = prim_of(&m.attrs.file, hit.triangle).map_or(m.attrs.file.options, |p| p.options);
        let scheme = options.scheme.map_or(Some(m.made.scheme), crate::Scheme::of_file).unwrap_or(m.made.scheme);
        let level = Level { control, drawn: control, scheme, level: 0, precise: m.precise_control() };
        pick(&level, &m.made.opts.with_file(options), ray.origin, ray.dir)
    }

    /// The path of the prim a pick hit: the group of its drawn triangle.
    fn prim_hit(&self, ray: Ray, pick: &Pick) -> Option<String> {
        let m = &self.model;
        let attrs = match ray.target == Target::Control || self.traced_on_cage(ray) || m.made.level == 0 {
            true => &m.attrs.file,
            false => &m.attrs.refined,
        };
        prim_of(attrs, pick.triangle).map(|p| p.path.clone())
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
            Ok(pick) => {
                let on_cage = self.traced_on_cage(ray);
                self.model.probe = pick.map(|pick| Probe { ray, prim: self.prim_hit(ray, &pick), pick, on_cage });
            }
            Err(e) => {
                self.model.probe = None;
                self.fail(e.into());
            }
        }
    }
}

/// The prim of triangle `t` by its material group, when `attrs` hold a scene.
fn prim_of(attrs: &crate::mesh::Attributes, t: u32) -> Option<&crate::mesh::Prim> {
    let m = attrs.materials.as_ref()?;
    m.scene.as_deref()?.prim_of_group(*m.face.get(t as usize)?)
}
