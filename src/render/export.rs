//! Animation export: every frame rendered offscreen, written as one GIF or as
//! numbered PNGs. Used by `subdiv animate` and the viewer's Export button.
//! The frames are evaluated on the CPU and uploaded, or by the compute
//! passes in the drawn buffers ([`Evaluation`]; through [`AnimatedMesh`],
//! as in the viewer): the same images either way, to rounding.

use super::gpu_anim::AnimatedMesh;
use super::offscreen::Offscreen;
use super::{Camera, Gpu, GpuMesh, Look, save_png};
use crate::anim::player::Animation;
use crate::mesh::bounds_of;
use crate::mesh::normals::vertex_normals;
use crate::{Error, Mesh, Result};
use glam::Vec3;
use std::path::{Path, PathBuf};

/// Where the frames go.
#[derive(Clone, Debug)]
pub enum ExportTarget {
    /// One looping animated GIF.
    Gif(PathBuf),
    /// `frame_0000.png`, `frame_0001.png`, ... in a directory (created if missing).
    Frames(PathBuf),
}

/// Where an export's frames are evaluated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Evaluation {
    /// On the CPU ([`Animation::evaluate`]), each frame uploaded.
    #[default]
    Cpu,
    /// By the compute passes (`AnimatedMesh`), drawn from the buffers they
    /// write: no frame is evaluated on the CPU.
    Gpu,
}

/// How the frames look.
#[derive(Clone, Copy, Debug)]
pub struct ExportStyle {
    /// Image width and height.
    pub size: (u32, u32),
    /// Faces, wireframe, control overlay.
    pub look: Look,
    /// Playback rate stored in the GIF.
    pub fps: f32,
    /// Where the frames are evaluated.
    pub eval: Evaluation,
}

impl Default for ExportStyle {
    fn default() -> Self {
        ExportStyle { size: (480, 480), look: Look::default(), fps: 30.0, eval: Evaluation::Cpu }
    }
}

/// Bounds of the control polygon over every frame, so the camera frames the
/// whole motion.
pub fn motion_bounds(anim: &Animation) -> (Vec3, Vec3) {
    bounds_of((0..anim.frame_count()).flat_map(|f| anim.control(f)))
}

/// Bounds of the subdivided surface over every frame (evaluates them all).
pub(crate) fn surface_motion_bounds(anim: &mut Animation) -> (Vec3, Vec3) {
    (0..anim.frame_count())
        .map(|f| bounds_of(anim.evaluate(f).0))
        .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
        .unwrap_or_default()
}

/// Bounds of the subdivided surface over every frame, each evaluated by
/// `animated`'s compute passes on `gpu` and read back (no frame is
/// evaluated on the CPU).
///
/// # Errors
/// As [`AnimatedMesh::evaluate`] and [`AnimatedMesh::positions`].
pub(crate) fn gpu_surface_motion_bounds(animated: &AnimatedMesh, gpu: &Gpu, anim: &Animation) -> Result<(Vec3, Vec3)> {
    let mut bounds: Option<(Vec3, Vec3)> = None;
    for f in 0..anim.frame_count() {
        animated.evaluate(&gpu.device, &gpu.queue, anim.control(f))?;
        let (lo, hi) = bounds_of(animated.positions(&gpu.device, &gpu.queue)?.iter());
        bounds = Some(bounds.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi))));
    }
    Ok(bounds.unwrap_or_default())
}

/// The device, meshes and camera of one export; renders its frames.
struct FrameRenderer<'a> {
    off: Offscreen,
    anim: &'a mut Animation,
    control: &'a Mesh,
    /// The surface: evaluated on the CPU and uploaded, or on the GPU in place.
    fine: AnimatedMesh,
    /// The control mesh (drawn when the look overlays it).
    coarse: GpuMesh,
    camera: Camera,
    look: Look,
}

impl<'a> FrameRenderer<'a> {
    fn new(
        anim: &'a mut Animation,
        control: &'a Mesh,
        style: &ExportStyle,
        colors: Option<&[Vec3]>,
    ) -> Result<FrameRenderer<'a>> {
        let (w, h) = style.size;
        let off = Offscreen::new(w, h)?;
        // frame the whole motion of what is drawn: the surface, and the control mesh when overlaid
        let (mut fine, (mut lo, mut hi)) = match style.eval {
            Evaluation::Gpu => {
                let fine = AnimatedMesh::on_gpu(&off.gpu, anim.plan(), anim.control(0))?;
                let bounds = gpu_surface_motion_bounds(&fine, &off.gpu, anim)?;
                (fine, bounds)
            }
            Evaluation::Cpu => {
                let bounds = surface_motion_bounds(anim);
                let (topo, pos, nrm) = anim.evaluate_with_topology(0);
                (AnimatedMesh::new(&off.gpu.device, topo, pos, nrm)?, bounds)
            }
        };
        if style.look.control {
            let (a, b) = motion_bounds(anim);
            (lo, hi) = (lo.min(a), hi.max(b));
        }
        let mut camera = Camera::framing(lo, hi, w as f32 / h as f32);
        camera.orthographic = false;
        if let Some(c) = colors {
            fine.mesh_mut().set_colors(&off.gpu.device, c);
        }
        let c0 = anim.control(0);
        let coarse = GpuMesh::new(&off.gpu.device, &control.ct, c0, &vertex_normals(&control.ct, c0))?;
        let look = Look { colors: colors.is_some(), ..style.look };
        Ok(FrameRenderer { off, anim, control, fine, coarse, camera, look })
    }

    /// Frame `f`, evaluated where the export asked and drawn.
    fn render(&mut self, f: usize) -> Result<image::RgbaImage> {
        let gpu = &self.off.gpu;
        if self.fine.gpu_ready() {
            self.fine.evaluate(&gpu.device, &gpu.queue, self.anim.control(f))?;
        } else {
            let (pos, nrm) = self.anim.evaluate(f);
            self.fine.upload(&gpu.queue, pos, nrm);
        }
        let cpos = self.anim.control(f);
        self.coarse.update(&gpu.queue, cpos, &vertex_normals(&self.control.ct, cpos));
        self.off.render_one(self.camera, self.fine.mesh(), Some(&self.coarse), self.look)
    }
}

/// Renders every frame of `anim` (whose control topology is `control`) and
/// writes them to `target`, evaluated where `style.eval` says, with
/// per-vertex `colors` (linear RGB, one per vertex of the subdivided
/// topology, the same every frame) on the surface where given.
/// `progress(done, total)` is called after each
/// frame; returning `false` cancels (nothing is left behind for a GIF).
/// Returns the number of frames written.
///
/// # Errors
/// GPU, I/O and encoding errors; [`Error::Cancelled`] when cancelled.
pub fn export_animation(
    anim: &mut Animation,
    control: &Mesh,
    target: &ExportTarget,
    style: &ExportStyle,
    colors: Option<&[Vec3]>,
    mut progress: impl FnMut(usize, usize) -> bool,
) -> Result<usize> {
    let total = anim.frame_count();
    let mut frames = FrameRenderer::new(anim, control, style, colors)?;
    let cancelled = || Error::cancelled("export");
    match target {
        ExportTarget::Frames(dir) => {
            std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
            for f in 0..total {
                let img = frames.render(f)?;
                save_png(&img, &frame_path(dir, f, total))?;
                if !progress(f + 1, total) {
                    return Err(cancelled());
                }
            }
        }
        ExportTarget::Gif(path) => {
            let delay = image::Delay::from_numer_denom_ms(1000, style.fps.clamp(1.0, 100.0).round() as u32);
            crate::io::atomic_write(path, |wr| {
                let gif_err = |e: image::ImageError| Error::encode(path, "GIF", e);
                let mut enc = image::codecs::gif::GifEncoder::new_with_speed(wr, 10);
                enc.set_repeat(image::codecs::gif::Repeat::Infinite).map_err(gif_err)?;
                for f in 0..total {
                    let img = frames.render(f)?;
                    enc.encode_frame(image::Frame::from_parts(img, 0, 0, delay)).map_err(gif_err)?;
                    if !progress(f + 1, total) {
                        return Err(cancelled());
                    }
                }
                Ok(())
            })?;
        }
    }
    Ok(total)
}

/// `dir/frame_0007.png`, zero-padded to the width of the frame count.
pub fn frame_path(dir: &Path, f: usize, total: usize) -> PathBuf {
    let width = total.saturating_sub(1).max(1).to_string().len().max(4);
    dir.join(format!("frame_{f:0width$}.png"))
}
