//! The adaptive display: the exact limit surface tessellated for the view
//! so that it is drawn within half a pixel of the limit at any zoom
//! ([`crate::tessellate`] with a [`ScreenTolerance`]: fine near the eye,
//! coarse far from it, one triangle per control face out of the view, no
//! cracks). A worker tessellates; the last tessellation stays drawn while
//! the camera moves or the cage is edited, and the next is asked for as soon
//! as the worker is free, for the view, cage and scheme of that frame. After
//! an edit in a still view the next is made from the last ([`Tessellator`]):
//! only the patches the moved points reach are evaluated again.

use super::doc::Doc;
use super::model::Shown;
use super::view::{View, viewport_aspect};
use crate::clock::Instant;
use crate::subdiv::eval::color::CurvatureKind;
use crate::{Mesh, Options, Result, Scheme, ScreenTolerance, TessellationStats, Tessellator, Tolerance};
use glam::DVec3;
use std::sync::Arc;

/// The largest distance on screen between the drawn surface and the limit.
pub(crate) const PIXELS: f64 = 0.5;

/// What a tessellation was made for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Key {
    /// The control mesh's version.
    control: u64,
    /// The scheme and its options.
    scheme: Scheme,
    opts: Options,
    /// The view and the pixels.
    view: ScreenTolerance,
    /// The curvature coloured, evaluated at every vertex with the points.
    curvature: Option<CurvatureKind>,
}

/// A tessellation of the limit for a view, ready to draw.
pub(crate) struct Tessellated {
    /// The triangles on the limit, with its exact normals.
    pub(crate) shown: Shown,
    /// Each triangle's control face and its corners' `(u, v)` there (what
    /// a pick on it is traced back with).
    pub(crate) faces: Vec<u32>,
    pub(crate) corners: Vec<[(f64, f64); 3]>,
    /// The scheme and options it was made with.
    pub(crate) scheme: Scheme,
    pub(crate) opts: Options,
    /// How it went.
    pub(crate) stats: TessellationStats,
    /// Wall time of the job, ms.
    pub(crate) ms: f64,
    /// What made it, kept for the next (taken back by the model).
    tessellator: Option<Tessellator>,
    /// The curvature asked for and its exact value at every vertex.
    pub(crate) curvature: Option<(CurvatureKind, Arc<Vec<f64>>)>,
}

/// The adaptive display's state in the model.
#[derive(Default)]
pub(crate) struct Adaptive {
    /// The tessellation drawn (the latest finished).
    pub(crate) drawn: Option<Arc<Tessellated>>,
    /// What the latest request was for (asked again only when it changes).
    asked: Option<Key>,
    /// The view of the frame before (see [`Adaptive::still`]).
    seen: Option<ScreenTolerance>,
    /// The last tessellation's state, for the next after an edit (only the
    /// patches an edit reaches are made again); `None` while a job holds it.
    tessellator: Option<Tessellator>,
}

impl Adaptive {
    /// Whether `view` is the view of the frame before (the camera is
    /// still), noting it for the next frame.
    pub(crate) fn still(&mut self, view: ScreenTolerance) -> bool {
        self.seen.replace(view) == Some(view)
    }
}

/// What a tessellation job needs.
pub(crate) struct Job {
    /// The control mesh and its points in f64 (the file's own digits
    /// where the model has them).
    mesh: Arc<Mesh>,
    control: Vec<DVec3>,
    key: Key,
    tessellator: Tessellator,
}

impl Job {
    /// Tessellates (on a worker thread).
    pub(crate) fn run(mut self) -> Result<Tessellated> {
        let start = Instant::now();
        let Key { scheme, opts, view, curvature, .. } = self.key;
        let out = self.tessellator.tessellate(&self.mesh, &self.control, scheme, &opts, Tolerance::Screen(view))?;
        let positions = out.positions.iter().map(|p| p.as_vec3()).collect();
        let corners: Vec<u32> = out.triangles.iter().flatten().copied().collect();
        let mesh = Mesh::from_triangles(positions, &corners).map_err(|e| crate::Error::Usage(e.to_string()))?;
        let mut shown = Shown::new(Arc::new(mesh));
        // the exact normals, not the triangles' average
        shown.normals = Arc::new(out.normals.iter().map(|n| n.as_vec3()).collect());
        let curvature = match curvature {
            Some(kind) => {
                let ev = crate::Evaluator::new_f64(&self.mesh, &self.control, scheme, &opts)?;
                let at: Vec<(usize, f64, f64)> = out.params.iter().map(|&(f, u, v)| (f as usize, u, v)).collect();
                Some((kind, Arc::new(ev.eval_map(&at, true, |s| kind.of(s))?)))
            }
            None => None,
        };
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let (faces, corners) = (out.faces, out.corners);
        let tessellator = Some(self.tessellator);
        Ok(Tessellated { shown, faces, corners, scheme, opts, stats: out.stats, ms, tessellator, curvature })
    }
}

/// The screen tolerance of the result's viewport (the right half side by
/// side) at `pixels_per_point`; `None` before the 3D area is laid out.
pub(crate) fn screen_tolerance(view: &View, side_by_side: bool, pixels_per_point: f32) -> Option<ScreenTolerance> {
    let rect = view.scene_rect;
    if !rect.is_positive() {
        return None;
    }
    let width = if side_by_side { rect.width() / 2.0 } else { rect.width() };
    let view_proj = view.camera.view_proj(viewport_aspect(rect, side_by_side)).as_dmat4();
    let (width, height) = (f64::from(width * pixels_per_point), f64::from(rect.height() * pixels_per_point));
    Some(ScreenTolerance { view_proj, width, height, pixels: PIXELS })
}

/// The adaptive display's requests and results.
impl Doc {
    /// Asks for a tessellation for `view` when the adaptive display is on,
    /// what it would be made for changed and no tessellation is running.
    pub(crate) fn request_tessellation(&mut self, view: ScreenTolerance) {
        let m = &self.model;
        if !self.display.adaptive || m.curve.is_some() || self.jobs.busy.tessellating.is_some() {
            return;
        }
        let (scheme, opts) = (self.request.scheme, self.request.opts);
        let curvature = match self.display.coloring {
            super::display::Coloring::Curvature(kind) => Some(kind),
            _ => None,
        };
        let key = Key { control: m.control.version(), scheme, opts, view, curvature };
        // the same, or only the curvature turned off (the drawn one has the geometry)
        if m.adaptive.asked.is_some_and(|a| a == key || (curvature.is_none() && Key { curvature, ..a } == key)) {
            return;
        }
        let mesh = m.control.mesh.clone();
        let control = m.control_f64();
        self.model.adaptive.asked = Some(key);
        let tessellator = self.model.adaptive.tessellator.take().unwrap_or_default();
        self.jobs.tessellate(Job { mesh, control, key, tessellator });
    }

    /// Takes a finished tessellation: drawn from now on; a refusal (a
    /// scheme without a limit, a view past the memory budget) is a notice
    /// and the uniform level is drawn.
    pub(crate) fn adopt_tessellation(&mut self, result: Result<Box<Tessellated>>) {
        match result {
            Ok(mut t) => {
                self.model.adaptive.tessellator = t.tessellator.take();
                self.model.adaptive.drawn = Some(Arc::from(t));
            }
            Err(e) => {
                self.model.adaptive.drawn = None;
                self.status.notice = Some(format!("adaptive display: {e}"));
            }
        }
        self.reshade();
    }

    /// What the adaptive display draws now: its latest tessellation while
    /// it is on.
    pub(crate) fn adaptive_shown(&self) -> Option<&Tessellated> {
        self.model.adaptive.drawn.as_deref().filter(|_| self.display.adaptive)
    }
}
