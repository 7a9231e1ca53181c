//! Animation export: every frame rendered offscreen, written as one GIF or as
//! numbered PNGs. Used by `subdiv animate` and the viewer's Export button.

use super::offscreen::Offscreen;
use super::{Camera, GpuMesh, Look, save_png};
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

/// How the frames look.
#[derive(Clone, Copy, Debug)]
pub struct ExportStyle {
    /// Image width and height.
    pub size: (u32, u32),
    /// Faces, wireframe, control overlay.
    pub look: Look,
    /// Playback rate stored in the GIF.
    pub fps: f32,
}

impl Default for ExportStyle {
    fn default() -> Self {
        ExportStyle { size: (480, 480), look: Look::default(), fps: 30.0 }
    }
}

/// Bounds of the control polygon over every frame, so the camera frames the
/// whole motion.
pub fn motion_bounds(anim: &Animation) -> (Vec3, Vec3) {
    bounds_of((0..anim.frame_count()).flat_map(|f| anim.control(f)))
}

/// Bounds of the subdivided surface over every frame (evaluates them all).
pub fn surface_motion_bounds(anim: &mut Animation) -> (Vec3, Vec3) {
    (0..anim.frame_count())
        .map(|f| bounds_of(anim.evaluate(f).0))
        .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)))
        .unwrap_or_default()
}

/// Renders every frame of `anim` (whose control topology is `control`) and
/// writes them to `target`. `progress(done, total)` is called after each
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
    progress: impl FnMut(usize, usize) -> bool,
) -> Result<usize> {
    export_animation_painted(anim, control, target, style, None, progress)
}

/// [`export_animation`] with per-vertex `colors` (linear RGB, one per vertex
/// of the subdivided topology, the same every frame) shown on the surface.
///
/// # Errors
/// As [`export_animation`].
pub fn export_animation_painted(
    anim: &mut Animation,
    control: &Mesh,
    target: &ExportTarget,
    style: &ExportStyle,
    colors: Option<&[Vec3]>,
    mut progress: impl FnMut(usize, usize) -> bool,
) -> Result<usize> {
    let (w, h) = style.size;
    let mut off = Offscreen::new(w, h)?;
    // Frame the whole motion of what is drawn: the surface, and the control mesh when overlaid.
    let (mut lo, mut hi) = surface_motion_bounds(anim);
    if style.look.control {
        let (a, b) = motion_bounds(anim);
        (lo, hi) = (lo.min(a), hi.max(b));
    }
    let mut camera = Camera::framing(lo, hi, w as f32 / h as f32);
    camera.orthographic = false;
    let total = anim.frame_count();
    let (topo, pos, nrm) = anim.evaluate_with_topology(0);
    let mut fine = GpuMesh::new(&off.gpu.device, topo, pos, nrm)?;
    let look = Look { colors: colors.is_some(), ..style.look };
    if let Some(c) = colors {
        fine.set_colors(&off.gpu.device, c);
    }
    let mut coarse =
        GpuMesh::new(&off.gpu.device, &control.ct, anim.control(0), &vertex_normals(&control.ct, anim.control(0)))?;
    let mut render = |f: usize, off: &mut Offscreen| -> Result<image::RgbaImage> {
        let (pos, nrm) = anim.evaluate(f);
        fine.update(&off.gpu.queue, pos, nrm);
        let cpos = anim.control(f);
        coarse.update(&off.gpu.queue, cpos, &vertex_normals(&control.ct, cpos));
        off.render_one(camera, &fine, Some(&coarse), look)
    };
    let cancelled = || Error::cancelled("export");
    match target {
        ExportTarget::Frames(dir) => {
            std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
            for f in 0..total {
                let img = render(f, &mut off)?;
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
                    let img = render(f, &mut off)?;
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
