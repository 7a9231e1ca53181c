//! Rendering without a window: into a texture, read back into an image.

use super::Look;
use super::camera::Camera;
use super::gpu::Gpu;
use super::readback::{Readback, capture_texture};
use super::scene::{GpuMesh, Renderer, Targets, ViewportDraw};
use crate::{Error, Mesh, Result};
use image::RgbaImage;

/// Format of offscreen images: sRGB, so the shader writes linear colour.
pub(crate) const OFFSCREEN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// An offscreen target of a fixed size with its own device.
pub struct Offscreen {
    /// The device.
    pub gpu: Gpu,
    /// The pipelines.
    pub renderer: Renderer,
    targets: Targets,
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    readback: Readback,
}

impl Offscreen {
    /// A `width` x `height` target on a new headless device.
    ///
    /// # Errors
    /// [`Error::Gpu`] without an adapter, [`Error::Usage`] for a size the
    /// device cannot hold.
    pub fn new(width: u32, height: u32) -> Result<Offscreen> {
        Self::build(width, height, None)
    }

    /// [`Offscreen::new`] with `samples` MSAA samples: 1 for none (the FXAA
    /// pass smooths the edges instead), more for the most the adapter
    /// supports up to 4 (`Gpu::msaa_samples`, 1 where it supports none);
    /// [`Renderer::samples`] says what it got.
    ///
    /// # Errors
    /// As [`Offscreen::new`].
    pub fn with_samples(width: u32, height: u32, samples: u32) -> Result<Offscreen> {
        Self::build(width, height, Some(samples))
    }

    fn build(width: u32, height: u32, samples: Option<u32>) -> Result<Offscreen> {
        let gpu = Gpu::headless()?;
        let max = gpu.device.limits().max_texture_dimension_2d;
        if width == 0 || height == 0 || width > max || height > max {
            return Err(Error::Usage(format!("image size {width}x{height} is outside 1..={max} pixels per side")));
        }
        let samples = match samples {
            None => gpu.default_samples(OFFSCREEN_FORMAT),
            Some(n) if n <= 1 => 1,
            Some(_) => gpu.msaa_samples(OFFSCREEN_FORMAT),
        };
        let renderer = Renderer::new(&gpu.device, OFFSCREEN_FORMAT, samples);
        let targets = Targets::new(&gpu.device, &renderer, width, height);
        let (texture, view) = capture_texture(&gpu.device, "offscreen", OFFSCREEN_FORMAT, width, height);
        let readback = Readback::new(&gpu.device, width, height);
        Ok(Offscreen { gpu, renderer, targets, texture, view, readback })
    }

    /// Takes the next images as `shot` says: its scale widens the lines
    /// (the target keeps its size; make it `shot.size(...)`), its
    /// transparency clears the background to alpha 0.
    pub fn set_shot(&mut self, shot: super::Shot) {
        self.renderer.pixel_scale = shot.scale.max(1) as f32;
        self.renderer.transparent = shot.transparent;
    }

    /// Image size.
    pub fn size(&self) -> (u32, u32) {
        self.targets.size
    }

    /// Uploads a mesh (with fan-averaged vertex normals) to this device.
    ///
    /// # Errors
    /// [`Error::Gpu`] when the mesh exceeds the device's buffer limit.
    pub fn upload(&self, mesh: &Mesh) -> Result<GpuMesh> {
        GpuMesh::new(&self.gpu.device, &mesh.ct, &mesh.positions, &mesh.vertex_normals())
    }

    /// Renders one full-size viewport.
    ///
    /// # Errors
    /// [`Error::Gpu`] when the readback fails.
    pub fn render_one(
        &mut self,
        camera: Camera,
        mesh: &GpuMesh,
        control: Option<&GpuMesh>,
        look: Look,
    ) -> Result<RgbaImage> {
        let (w, h) = self.size();
        let draw = ViewportDraw { rect: [0.0, 0.0, w as f32, h as f32], camera, mesh: Some(mesh), control, look };
        self.render(&[draw])
    }

    /// Renders the viewports and reads the image back.
    ///
    /// # Errors
    /// [`Error::Gpu`] when the readback fails.
    pub(crate) fn render(&mut self, draws: &[ViewportDraw]) -> Result<RgbaImage> {
        let device = &self.gpu.device;
        let mut encoder = device.create_command_encoder(&Default::default());
        self.renderer.encode(device, &self.gpu.queue, &mut encoder, &self.targets, &self.view, draws);
        self.readback.copy_from(&mut encoder, &self.texture);
        self.gpu.queue.submit([encoder.finish()]);
        self.readback.read(device)
    }
}

/// Renders `draws` (rectangles in pixels of a `size` image) on an existing
/// device into a new offscreen target taken as `shot` says, and reads it
/// back: the window's screenshots, at any multiple of its size, without
/// touching its own targets.
///
/// # Errors
/// [`Error::Usage`] for a size the device cannot hold, [`Error::Gpu`] when
/// the readback fails.
pub fn shoot(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    samples: u32,
    size: (u32, u32),
    shot: super::Shot,
    draws: &[ViewportDraw],
) -> Result<RgbaImage> {
    let (w, h) = size;
    let max = device.limits().max_texture_dimension_2d;
    if w == 0 || h == 0 || w > max || h > max {
        return Err(Error::Usage(format!("screenshot size {w}x{h} is outside 1..={max} pixels per side")));
    }
    let mut renderer = Renderer::new(device, OFFSCREEN_FORMAT, samples);
    renderer.pixel_scale = shot.scale.max(1) as f32;
    renderer.transparent = shot.transparent;
    let targets = Targets::new(device, &renderer, w, h);
    let (texture, view) = capture_texture(device, "screenshot", OFFSCREEN_FORMAT, w, h);
    let readback = Readback::new(device, w, h);
    let mut encoder = device.create_command_encoder(&Default::default());
    renderer.encode(device, queue, &mut encoder, &targets, &view, draws);
    readback.copy_from(&mut encoder, &texture);
    queue.submit([encoder.finish()]);
    readback.read(device)
}
