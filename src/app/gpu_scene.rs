//! The GPU copies of the document's meshes, kept current by comparing the
//! versions of the document's artefacts with those uploaded last.
//!
//! Per frame, [`GpuScene::sync`] re-uploads only an artefact whose version
//! changed (control mesh, picked edge, result and proxy, curve), advances the
//! animation (per frame only the stencil plan and the normals are evaluated
//! and copied into the existing vertex buffers), and keeps the normal
//! segments built or dropped as the display asks. [`GpuScene::version`]
//! changes whenever anything drawn changed, so the window can cache the 3D
//! image.

use super::doc::{Doc, Problem};
use super::model::{Curve, Shown};
use crate::Result;
use crate::io::bezier::{curve_polyline, de_casteljau_construction};
use crate::render::GpuMesh;
use crate::render::gpu_anim::{GpuAnimator, supports_compute};
use glam::{Vec2, Vec3};

/// What was uploaded last: the document versions, the animation frame.
#[derive(Default)]
struct Seen {
    control: u64,
    result: u64,
    picked: u64,
    curve: u64,
    /// The plan id and frame on the animated mesh.
    frame: Option<(u64, usize)>,
    /// The control mesh's buffers hold animated positions.
    control_animated: bool,
}

/// The meshes as drawn.
#[derive(Default)]
pub struct GpuScene {
    /// The control mesh (positions animated while the animation plays).
    pub control: Option<GpuMesh>,
    /// The shown result.
    pub result: Option<GpuMesh>,
    /// The result's proxy.
    pub proxy: Option<GpuMesh>,
    /// The animated result.
    pub anim: Option<GpuMesh>,
    /// The compute passes writing `anim` (GPU evaluation), with its plan id
    /// (`None` inside: the plan does not fit the device; not retried).
    animator: Option<(u64, Option<GpuAnimator>)>,
    /// A Bezier curve: its polyline and its control polygon (with the construction highlighted).
    pub curve: Option<(GpuMesh, GpuMesh)>,
    seen: Seen,
    /// Changes whenever anything drawn changed.
    pub version: u64,
}

fn upload(device: &wgpu::Device, shown: &Shown) -> Result<GpuMesh> {
    GpuMesh::new(device, &shown.mesh.ct, &shown.mesh.positions, &shown.normals)
}

fn lift(points: &[Vec2]) -> Vec<Vec3> {
    points.iter().map(|p| p.extend(0.0)).collect()
}

/// Index pairs joining consecutive points of a polyline of `n` points.
fn polyline_pairs(n: usize) -> Vec<u32> {
    (1..n as u32).flat_map(|i| [i - 1, i]).collect()
}

/// A curve's polyline, and its control polygon with the de Casteljau
/// construction (and a small cross at the curve point) highlighted.
fn curve_meshes(device: &wgpu::Device, c: &Curve) -> (GpuMesh, GpuMesh) {
    let line = lift(&curve_polyline(&c.control, c.segments));
    let poly = lift(&c.control);
    let mut control = GpuMesh::lines(device, &poly, &polyline_pairs(poly.len()));
    if c.construction {
        let (segs, point) = de_casteljau_construction(&c.control, c.t);
        let mut segs = lift(&segs);
        if let Some(q) = point.map(|p| p.extend(0.0)) {
            let r = 0.01 * (poly.iter().fold(Vec3::ZERO, |a, p| a.max(p.abs()))).length().max(1e-6);
            segs.extend([q - Vec3::X * r, q + Vec3::X * r, q - Vec3::Y * r, q + Vec3::Y * r]);
        }
        control.set_highlight(device, &segs);
    }
    (GpuMesh::lines(device, &line, &polyline_pairs(line.len())), control)
}

impl GpuScene {
    /// Uploads what changed and advances the animation by `dt` seconds;
    /// whether a mesh was uploaded. Upload errors are shown in the panel.
    pub fn sync(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        doc: &mut Doc,
        dt: f64,
        normal_length: f32,
    ) -> bool {
        let uploaded = self.sync_control(device, doc) | self.sync_result(device, doc);
        self.sync_highlight(device, doc);
        self.sync_curve(device, doc);
        self.sync_animation(device, queue, doc, dt);
        self.sync_normal_lines(device, doc, normal_length);
        if uploaded {
            self.version += 1;
        }
        uploaded
    }

    fn sync_control(&mut self, device: &wgpu::Device, doc: &mut Doc) -> bool {
        let control = &doc.model.control;
        let unanimated = self.seen.control_animated && doc.anim.playback.is_none();
        if control.version() == self.seen.control && !unanimated {
            return false;
        }
        self.control = upload(device, control).map_err(|e| doc.status.error = Some(e.into())).ok();
        self.seen.control = control.version();
        self.seen.control_animated = false;
        self.seen.picked = 0; // the new buffers have no highlight
        true
    }

    fn sync_highlight(&mut self, device: &wgpu::Device, doc: &Doc) {
        let picked = &doc.model.picked;
        if picked.version() == self.seen.picked {
            return;
        }
        if let Some(c) = &mut self.control {
            let at = |v: u32| doc.model.control.mesh.positions[v as usize];
            let seg: Vec<Vec3> = doc.model.picked_edge().map(|(a, b)| vec![at(a), at(b)]).unwrap_or_default();
            c.set_highlight(device, &seg);
            self.version += 1;
        }
        self.seen.picked = picked.version();
    }

    fn sync_result(&mut self, device: &wgpu::Device, doc: &mut Doc) -> bool {
        let result = &doc.model.result;
        if result.version() == self.seen.result {
            return false;
        }
        let r = &result.shown;
        let checker = doc.display.coloring == super::display::Coloring::Checker;
        let refined = &doc.model.attrs.refined;
        let corner_uv = refined.uv.as_deref().filter(|u| u.len() == r.mesh.ct.v_table().len());
        let mesh = match (self.corner_attribute(doc, corner_uv), corner_uv) {
            (Some(attr), _) => GpuMesh::unwelded(device, &r.mesh.ct, &r.mesh.positions, &r.normals, &attr),
            (None, Some(uv)) if checker => {
                let attr: Vec<Vec3> = uv.iter().map(|t| t.extend(0.0)).collect();
                GpuMesh::unwelded(device, &r.mesh.ct, &r.mesh.positions, &r.normals, &attr)
            }
            _ => upload(device, r),
        };
        let mut errors = Vec::new();
        self.result = mesh.map_err(|e| errors.push(e)).ok();
        if let (Some(m), Some(colors), false) = (&mut self.result, &result.colors, checker) {
            m.set_colors(device, colors);
        }
        self.proxy = doc.model.proxy.as_ref().and_then(|p| upload(device, p).map_err(|e| errors.push(e)).ok());
        self.seen.result = result.version();
        if let Some(e) = errors.pop() {
            doc.fail(Problem::Other(e));
        }
        true
    }

    /// The per-corner material colours of the shown result, when the
    /// colouring is `Material` and the model has material groups.
    fn corner_attribute(&mut self, doc: &Doc, uv: Option<&[Vec2]>) -> Option<Vec<Vec3>> {
        let groups = doc.model.attrs.refined.materials.as_ref()?;
        let nt = doc.model.result.shown.mesh.ct.num_triangles();
        if doc.display.coloring != super::display::Coloring::Material || groups.face.len() != nt {
            return None;
        }
        Some(crate::render::materials::corner_colors(groups, uv))
    }

    fn sync_curve(&mut self, device: &wgpu::Device, doc: &Doc) {
        let curve = &doc.model.curve;
        if curve.version() == self.seen.curve {
            return;
        }
        self.curve = curve.as_ref().map(|c| curve_meshes(device, c));
        self.seen.curve = curve.version();
        self.version += 1;
    }

    /// Advances the clock; a new frame is evaluated into the animated mesh
    /// (rebuilt for a new plan, updated in place otherwise) and the control
    /// mesh's buffers.
    fn sync_animation(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, doc: &mut Doc, dt: f64) {
        let Some(p) = &mut doc.anim.playback else {
            self.seen.frame = None;
            if self.anim.take().is_some() {
                self.version += 1;
            }
            return;
        };
        let f = p.clock.tick(dt);
        if self.seen.frame == Some((p.id, f)) {
            return;
        }
        let fresh = self.seen.frame.is_none_or(|(id, _)| id != p.id);
        let compute = *doc.anim.gpu_compute.get_or_insert_with(|| supports_compute(device));
        // normal segments are kept current by CPU updates only
        let on_gpu = compute && doc.anim.gpu_eval && !doc.display.normals && !fresh && self.anim.is_some();
        if on_gpu && self.animator.as_ref().is_none_or(|(id, _)| *id != p.id) {
            let built = self.anim.as_ref().map(|m| GpuAnimator::new(device, p.player.plan(), m));
            // a plan the GPU cannot take is said, and the CPU evaluates it
            let built = match built {
                Some(Err(e)) => {
                    log::warn!("GPU evaluation unavailable, evaluating on the CPU: {e}");
                    doc.status.notice = Some(format!("GPU evaluation unavailable ({e}); evaluating on the CPU"));
                    doc.anim.gpu_eval = false;
                    None
                }
                b => b.and_then(Result::ok),
            };
            self.animator = Some((p.id, built));
        }
        doc.anim.on_gpu = false;
        match (&self.animator, on_gpu && doc.anim.gpu_eval) {
            (Some((_, Some(a))), true) => match a.update(device, queue, p.player.control(f)) {
                Ok(()) => doc.anim.on_gpu = true,
                Err(e) => doc.status.error = Some(e.into()),
            },
            _ => {
                let (topo, pos, nrm) = p.player.evaluate_with_topology(f);
                match &mut self.anim {
                    Some(m) if !fresh => m.update(queue, pos, nrm),
                    _ => {
                        self.anim = GpuMesh::new(device, topo, pos, nrm).ok();
                        self.animator = None;
                    }
                }
            }
        }
        let cpos = p.player.control(f);
        if let Some(c) = &mut self.control {
            let cn = crate::mesh::normals::vertex_normals(&doc.model.control.mesh.ct, cpos);
            c.update(queue, cpos, &cn);
            self.seen.control_animated = true;
        }
        self.seen.frame = Some((p.id, f));
        self.version += 1;
    }

    /// Normal segments: built once per upload (a new mesh has none), kept
    /// current by [`GpuMesh::update`] while the animation plays.
    fn sync_normal_lines(&mut self, device: &wgpu::Device, doc: &mut Doc, length: f32) {
        if !doc.display.normals {
            for m in [&mut self.result, &mut self.anim].into_iter().flatten() {
                if m.has_normal_lines() {
                    m.clear_normal_lines();
                    self.version += 1;
                }
            }
            return;
        }
        if let Some(m) = self.result.as_mut().filter(|m| !m.has_normal_lines()) {
            let r = &doc.model.result.shown;
            m.set_normal_lines(device, &r.mesh.positions, &r.normals, length);
            self.version += 1;
        }
        if let (Some(m), Some(p)) = (self.anim.as_mut(), doc.anim.playback.as_mut())
            && !m.has_normal_lines()
        {
            let (pos, nrm) = p.player.evaluate(self.seen.frame.map_or(0, |(_, f)| f));
            m.set_normal_lines(device, pos, nrm, length);
            self.version += 1;
        }
    }
}
