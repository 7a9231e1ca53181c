//! The GPU copies of the document's meshes, kept current by comparing the
//! versions of the document's artefacts with those uploaded last.
//!
//! Per frame, [`GpuScene::sync`] re-uploads only an artefact whose version
//! changed (control mesh, picked edge, result and proxy, curve): where every
//! version since the one it holds changed only some rows of the mesh (a
//! drag in the edit mode, [`super::model::Versioned::rows_since`]), it
//! writes those rows into the buffers it has, else it makes them anew. It
//! uploads the document's current animation frame (evaluated by the
//! document on the CPU and copied into the existing vertex buffers, or
//! evaluated here by the compute passes), and keeps the normal segments
//! built or dropped as the display asks. It only reads the document: what
//! the document should know (errors, whether the GPU evaluates) comes back
//! as a [`GpuReport`]. [`GpuScene::version`] changes whenever anything drawn
//! changed, so the window can cache the 3D image.

use super::command::GpuReport;
use super::doc::Doc;
use super::model::{Curve, Shown};
use crate::Result;
use crate::io::bezier::{curve_polyline, de_casteljau_construction};
use crate::mesh::attributes::MaterialGroups;
use crate::render::GpuMesh;
use crate::render::gpu_anim::{AnimatedMesh, supports_compute};
use crate::render::textures::MaterialDraw;
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
    /// The result's buffers have one vertex per vertex of the level (not
    /// per corner, as for textures): rows can be written into them.
    welded: bool,
}

/// The meshes as drawn.
#[derive(Default)]
pub(crate) struct GpuScene {
    /// The control mesh (positions animated while the animation plays).
    pub(crate) control: Option<GpuMesh>,
    /// The shown result.
    pub(crate) result: Option<GpuMesh>,
    /// The result's proxy.
    pub(crate) proxy: Option<GpuMesh>,
    /// The animated result, with its compute passes once built (GPU
    /// evaluation: the same type the animation export evaluates with).
    pub(crate) anim: Option<AnimatedMesh>,
    /// The plan whose compute passes were built into `anim`, or tried (a
    /// plan that does not fit the device is not retried).
    gpu_tried: Option<u64>,
    /// A Bezier curve: its polyline and its control polygon (with the construction highlighted).
    pub(crate) curve: Option<(GpuMesh, GpuMesh)>,
    seen: Seen,
    /// Changes whenever anything drawn changed.
    pub(crate) version: u64,
    /// Bytes sent to the GPU for the document's meshes so far (buffers
    /// made or written; the animation's frames not counted).
    pub(crate) uploaded_bytes: u64,
}

fn upload(device: &wgpu::Device, shown: &Shown) -> Result<GpuMesh> {
    GpuMesh::new(device, &shown.mesh.ct, &shown.mesh.positions, &shown.normals)
}

/// Rows at most this far apart are written as one range: each write has a
/// cost of its own, and the rows between go again as they are.
const ROW_GAP: usize = 32;

/// Sorted rows as ranges, those at most [`ROW_GAP`] apart joined.
fn row_ranges(rows: &[u32]) -> Vec<std::ops::Range<usize>> {
    let mut out: Vec<std::ops::Range<usize>> = Vec::new();
    for r in rows.iter().map(|&r| r as usize) {
        match out.last_mut() {
            Some(last) if r <= last.end + ROW_GAP => last.end = last.end.max(r + 1),
            _ => out.push(r..r + 1),
        }
    }
    out
}

/// Writes the rows of `shown` changed since the upload into `mesh`'s
/// buffers, when `rows` says which (and the mesh holds a vertex per row);
/// the bytes written, or `None` when it must be made whole.
fn write_rows(queue: &wgpu::Queue, mesh: Option<&mut GpuMesh>, shown: &Shown, rows: Option<Vec<u32>>) -> Option<u64> {
    let (mesh, rows) = (mesh?, rows?);
    let (positions, normals) = (&shown.mesh.positions, &shown.normals);
    (mesh.vertex_count() == positions.len() && normals.len() == positions.len())
        .then(|| mesh.write_ranges(queue, (positions, normals), &row_ranges(&rows)))
}

/// The material groups of the shown result, when the colouring is
/// `Material` and the model has groups for each of its triangles.
fn shown_materials(doc: &Doc) -> Option<&MaterialGroups> {
    let groups = doc.model.attrs.refined.materials.as_ref()?;
    let nt = doc.model.result.shown.mesh.ct.num_triangles();
    (doc.display.coloring == super::display::Coloring::Material && groups.face.len() == nt).then_some(groups)
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
    /// Uploads what changed in `doc` (which it only reads), the animation's
    /// current frame included, and says what the document should know.
    pub(crate) fn sync(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        doc: &Doc,
        normal_length: f32,
    ) -> GpuReport {
        let mut report = GpuReport { compute: supports_compute(device), ..Default::default() };
        report.uploaded =
            self.sync_control((device, queue), doc, &mut report) | self.sync_result((device, queue), doc, &mut report);
        self.sync_highlight(device, doc);
        self.sync_curve(device, doc);
        self.sync_animation(device, queue, doc, &mut report);
        self.sync_normal_lines(device, doc, normal_length);
        if report.uploaded {
            self.version += 1;
        }
        report.gpu_ready = self.gpu_tried.filter(|_| self.anim.as_ref().is_some_and(AnimatedMesh::gpu_ready));
        report
    }

    /// The control mesh: the rows an edit moved written into its buffers,
    /// or made whole.
    fn sync_control(&mut self, gpu: (&wgpu::Device, &wgpu::Queue), doc: &Doc, report: &mut GpuReport) -> bool {
        let control = &doc.model.control;
        let unanimated = self.seen.control_animated && doc.anim.playback.is_none();
        if control.version() == self.seen.control && !unanimated {
            return false;
        }
        let rows = control.rows_since(self.seen.control).filter(|_| !self.seen.control_animated);
        if let Some(bytes) = write_rows(gpu.1, self.control.as_mut(), control, rows) {
            self.uploaded_bytes += bytes;
        } else {
            self.control = upload(gpu.0, control).map_err(|e| report.errors.push(e)).ok();
            self.uploaded_bytes += self.control.as_ref().map_or(0, GpuMesh::byte_size);
        }
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

    /// The result and its proxy: the rows an edit moved written into the
    /// result's buffers (an edit leaves no proxy), or both made whole.
    fn sync_result(&mut self, gpu: (&wgpu::Device, &wgpu::Queue), doc: &Doc, report: &mut GpuReport) -> bool {
        let result = &doc.model.result;
        if result.version() == self.seen.result {
            return false;
        }
        let rows = result.rows_since(self.seen.result).filter(|_| self.seen.welded && doc.model.proxy.is_none());
        if let Some(bytes) = write_rows(gpu.1, self.result.as_mut(), &result.shown, rows) {
            self.uploaded_bytes += bytes;
            self.proxy = None;
            self.seen.result = result.version();
            return true;
        }
        let (device, queue) = gpu;
        let r = &result.shown;
        let checker = doc.display.coloring == super::display::Coloring::Checker;
        let refined = &doc.model.attrs.refined;
        let corner_uv = refined.uv.as_deref().filter(|u| u.len() == r.mesh.ct.v_table().len());
        let mesh = match (shown_materials(doc), corner_uv) {
            (Some(groups), uv) => {
                // the model's textures stay on the GPU from one level to the next
                let reuse = self.result.as_ref().and_then(GpuMesh::materials);
                let materials = MaterialDraw { groups, uv, reuse };
                GpuMesh::textured(device, queue, &r.mesh.ct, &r.mesh.positions, &r.normals, materials)
            }
            (None, Some(uv)) if checker => {
                let attr: Vec<Vec3> = uv.iter().map(|t| t.extend(0.0)).collect();
                GpuMesh::unwelded(device, &r.mesh.ct, &r.mesh.positions, &r.normals, &attr)
            }
            _ => upload(device, r),
        };
        self.seen.welded = shown_materials(doc).is_none() && !(checker && corner_uv.is_some());
        self.result = mesh.map_err(|e| report.errors.push(e)).ok();
        let materials = self.result.as_ref().is_some_and(|m| m.materials().is_some());
        if let (Some(m), false, false) = (&mut self.result, checker, materials) {
            if let Some(values) = &result.values {
                m.set_values(device, values);
            } else if let Some(colors) = &result.colors {
                m.set_colors(device, colors);
            }
        }
        self.proxy = doc.model.proxy.as_ref().and_then(|p| upload(device, p).map_err(|e| report.errors.push(e)).ok());
        let made = [&self.result, &self.proxy].into_iter().flatten();
        self.uploaded_bytes += made.map(GpuMesh::byte_size).sum::<u64>();
        self.seen.result = result.version();
        true
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

    /// The document's current animation frame into the animated mesh
    /// (rebuilt for a new plan, updated in place otherwise) and the control
    /// mesh's buffers: the CPU's evaluation uploaded, or the GPU's compute
    /// passes run on the frame's control points.
    fn sync_animation(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, doc: &Doc, report: &mut GpuReport) {
        let (Some(p), Some(shown)) = (&doc.anim.playback, doc.anim.shown) else {
            self.seen.frame = None;
            if self.anim.take().is_some() {
                self.version += 1;
            }
            return;
        };
        let (id, f) = (shown.id, shown.frame);
        if self.seen.frame == Some((id, f)) || id != p.id {
            return;
        }
        let fresh = self.seen.frame.is_none_or(|(seen, _)| seen != id);
        report.frame = true;
        if shown.on_cpu {
            let (pos, nrm) = p.player.evaluated();
            match &mut self.anim {
                Some(m) if !fresh => m.upload(queue, pos, nrm),
                _ => {
                    self.anim = AnimatedMesh::new(device, p.player.topology(), pos, nrm).ok();
                    self.gpu_tried = None;
                }
            }
        } else if let Some(m) = self.anim.as_ref().filter(|m| m.gpu_ready()) {
            match m.evaluate(device, queue, p.player.control(f)) {
                Ok(()) => report.on_gpu = true,
                Err(e) => report.errors.push(e),
            }
        }
        // the compute passes for this plan, once its mesh is up (a plan the
        // GPU cannot take is said once, and the CPU evaluates it)
        if report.compute
            && doc.anim.gpu_eval
            && self.gpu_tried != Some(id)
            && let Some(m) = &mut self.anim
        {
            if let Err(e) = m.start_gpu(device, p.player.plan()) {
                log::warn!("GPU evaluation unavailable, evaluating on the CPU: {e}");
                report.gpu_unavailable = Some(e.to_string());
            }
            self.gpu_tried = Some(id);
        }
        let cpos = p.player.control(f);
        if let Some(c) = &mut self.control {
            let cn = crate::mesh::normals::vertex_normals(&doc.model.control.mesh.ct, cpos);
            c.update(queue, cpos, &cn);
            self.seen.control_animated = true;
        }
        self.seen.frame = Some((id, f));
        self.version += 1;
    }

    /// Normal segments: built once per upload (a new mesh has none), kept
    /// current by [`GpuMesh::update`] while the animation plays.
    fn sync_normal_lines(&mut self, device: &wgpu::Device, doc: &Doc, length: f32) {
        if !doc.display.normals {
            for m in [self.result.as_mut(), self.anim.as_mut().map(AnimatedMesh::mesh_mut)].into_iter().flatten() {
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
            self.uploaded_bytes += (r.mesh.positions.len() * 24) as u64;
            self.version += 1;
        }
        // with normals shown every frame is evaluated on the CPU
        if let (Some(m), Some(p)) = (self.anim.as_mut().map(AnimatedMesh::mesh_mut), doc.anim.playback.as_ref())
            && !m.has_normal_lines()
            && doc.anim.shown.is_some_and(|s| s.on_cpu)
        {
            let (pos, nrm) = p.player.evaluated();
            m.set_normal_lines(device, pos, nrm, length);
            self.version += 1;
        }
    }
}
