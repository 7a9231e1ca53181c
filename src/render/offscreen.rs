//! Rendering without a window: into a texture, read back into an image.

use super::Look;
use super::camera::Camera;
use super::gpu::Gpu;
use super::scene::{GpuMesh, Renderer, Targets, ViewportDraw};
use crate::{Error, Mesh, Result};
use image::RgbaImage;

/// Format of offscreen images: sRGB, so the shader writes linear colour.
pub const OFFSCREEN_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;

/// An offscreen target of a fixed size with its own device.
pub struct Offscreen {
    /// The device.
    pub gpu: Gpu,
    /// The pipelines.
    pub renderer: Renderer,
    targets: Targets,
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    readback: wgpu::Buffer,
    padded_row: u32,
}

impl Offscreen {
    /// A `width` x `height` target on a new headless device.
    ///
    /// # Errors
    /// [`Error::Gpu`] without an adapter, [`Error::Usage`] for a size the
    /// device cannot hold.
    pub fn new(width: u32, height: u32) -> Result<Offscreen> {
        let gpu = Gpu::headless()?;
        let max = gpu.device.limits().max_texture_dimension_2d;
        if width == 0 || height == 0 || width > max || height > max {
            return Err(Error::Usage(format!("image size {width}x{height} is outside 1..={max} pixels per side")));
        }
        let samples = gpu.msaa_samples(OFFSCREEN_FORMAT);
        let renderer = Renderer::new(&gpu.device, OFFSCREEN_FORMAT, samples);
        let targets = Targets::new(&gpu.device, &renderer, width, height);
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("offscreen"),
            size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: OFFSCREEN_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&Default::default());
        let padded_row = padded_bytes_per_row(width);
        let readback = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: u64::from(padded_row) * u64::from(height),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Ok(Offscreen { gpu, renderer, targets, texture, view, readback, padded_row })
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
    pub fn render(&mut self, draws: &[ViewportDraw]) -> Result<RgbaImage> {
        let (w, h) = self.size();
        let device = &self.gpu.device;
        let mut encoder = device.create_command_encoder(&Default::default());
        self.renderer.encode(device, &self.gpu.queue, &mut encoder, &self.targets, &self.view, draws);
        encoder.copy_texture_to_buffer(
            self.texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &self.readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(self.padded_row),
                    rows_per_image: Some(h),
                },
            },
            self.texture.size(),
        );
        self.gpu.queue.submit([encoder.finish()]);
        read_rows(device, &self.readback, self.padded_row, w, h)
    }
}

/// Row pitch of a texture-to-buffer copy: 4 bytes per pixel rounded up to
/// wgpu's 256-byte alignment.
pub fn padded_bytes_per_row(width: u32) -> u32 {
    (width * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
}

/// Maps `buffer` and copies its `h` rows of `w` RGBA pixels into an image.
///
/// # Errors
/// [`Error::Gpu`] when mapping fails.
pub fn read_rows(device: &wgpu::Device, buffer: &wgpu::Buffer, padded: u32, w: u32, h: u32) -> Result<RgbaImage> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| Error::Gpu(format!("waiting for the GPU: {e}")))?;
    rx.recv().map_err(|e| Error::Gpu(format!("readback: {e}")))?.map_err(|e| Error::Gpu(format!("readback: {e}")))?;
    let mut pixels = Vec::with_capacity((w * h * 4) as usize);
    {
        let data = slice.get_mapped_range().map_err(|e| Error::Gpu(format!("readback: {e}")))?;
        for row in data.chunks_exact(padded as usize).take(h as usize) {
            pixels.extend_from_slice(&row[..(w * 4) as usize]);
        }
    }
    buffer.unmap();
    RgbaImage::from_raw(w, h, pixels).ok_or_else(|| Error::Gpu("readback size mismatch".into()))
}
