//! Reading a rendered texture back into an image: shared by offscreen
//! rendering (PNG, GIF frames) and the window's screenshot.
//!
//! A texture-to-buffer copy needs rows padded to wgpu's 256-byte alignment
//! ([`padded_bytes_per_row`]); [`Readback`] owns such a buffer for one size,
//! records the copy into an encoder, and after submission maps it and strips
//! the padding. Swapchain formats are often BGRA: [`Readback::read_rgba`]
//! swaps the channels for those and makes every pixel opaque.

use crate::{Error, Result};
use image::RgbaImage;

/// Row pitch of a texture-to-buffer copy: 4 bytes per pixel rounded up to
/// wgpu's 256-byte alignment.
pub(crate) fn padded_bytes_per_row(width: u32) -> u32 {
    (width * 4).div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT
}

/// A `width` x `height` texture of `format` that can be rendered into and
/// copied from (an offscreen image, a screenshot), with its view.
pub(crate) fn capture_texture(
    device: &wgpu::Device,
    label: &str,
    format: wgpu::TextureFormat,
    width: u32,
    height: u32,
) -> (wgpu::Texture, wgpu::TextureView) {
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    (texture, view)
}

/// A mappable buffer that receives one texture of a fixed size.
pub(crate) struct Readback {
    buffer: wgpu::Buffer,
    padded_row: u32,
    width: u32,
    height: u32,
}

impl Readback {
    /// A buffer for `width` x `height` RGBA8 (or BGRA8) pixels.
    pub(crate) fn new(device: &wgpu::Device, width: u32, height: u32) -> Readback {
        let padded_row = padded_bytes_per_row(width);
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: u64::from(padded_row) * u64::from(height),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Readback { buffer, padded_row, width, height }
    }

    /// Records the copy of `texture` (of this readback's size) into the buffer.
    pub(crate) fn copy_from(&self, encoder: &mut wgpu::CommandEncoder, texture: &wgpu::Texture) {
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &self.buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(self.padded_row),
                    rows_per_image: Some(self.height),
                },
            },
            texture.size(),
        );
    }

    /// Waits for the submitted copy and returns the pixels as stored.
    ///
    /// # Errors
    /// [`Error::Gpu`] when mapping fails.
    pub(crate) fn read(&self, device: &wgpu::Device) -> Result<RgbaImage> {
        read_rows(device, &self.buffer, self.padded_row, self.width, self.height)
    }

    /// Like [`Readback::read`], for a texture of `format`: BGRA pixels are
    /// swapped to RGBA and every pixel is made opaque.
    ///
    /// # Errors
    /// [`Error::Gpu`] when mapping fails.
    pub(crate) fn read_rgba(&self, device: &wgpu::Device, format: wgpu::TextureFormat) -> Result<RgbaImage> {
        let mut img = self.read(device)?;
        let bgra = matches!(format, wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb);
        for px in img.pixels_mut() {
            if bgra {
                px.0.swap(0, 2);
            }
            px.0[3] = 255;
        }
        Ok(img)
    }
}

/// Maps `buffer` and copies its `h` rows of `w` RGBA pixels into an image.
///
/// # Errors
/// [`Error::Gpu`] when mapping fails.
pub(crate) fn read_rows(
    device: &wgpu::Device,
    buffer: &wgpu::Buffer,
    padded: u32,
    w: u32,
    h: u32,
) -> Result<RgbaImage> {
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
    RgbaImage::from_raw(w, h, pixels)
        .ok_or_else(|| Error::Internal(format!("readback of {w}x{h} pixels has the wrong size")))
}

#[cfg(test)]
mod tests {
    use super::padded_bytes_per_row;

    #[test]
    fn rows_are_padded_to_256_bytes() {
        assert_eq!(padded_bytes_per_row(64), 256);
        assert_eq!(padded_bytes_per_row(65), 512);
        assert_eq!(padded_bytes_per_row(333), 1536);
    }
}
