//! The window's surface and its configuration in one owning type, after
//! wgpu's examples (`examples/features/src/framework.rs`, `SurfaceWrapper`):
//! the frame loop asks for a frame and gets one or nothing; configuring,
//! resizing (never to zero) and recovering a lost or outdated surface happen
//! here.

use crate::render::Gpu;
use crate::{Error, Result};

/// A configured surface.
pub(crate) struct SurfaceWrapper {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
}

/// What [`SurfaceWrapper::acquire`] got.
pub(crate) enum Acquired {
    /// A frame to draw into and present.
    Frame(wgpu::SurfaceTexture),
    /// The surface was lost or outdated and is reconfigured: draw again.
    Retry,
    /// No frame now (timeout, occluded); wait for the next redraw.
    Skip,
}

impl SurfaceWrapper {
    /// Configures `surface` for `gpu` at `width` x `height`: a non-sRGB
    /// format as egui wants (the scene shader encodes sRGB itself), vsync.
    ///
    /// # Errors
    /// [`Error::Gpu`] when the adapter offers no usable format or configuration.
    pub(crate) fn new(surface: wgpu::Surface<'static>, gpu: &Gpu, width: u32, height: u32) -> Result<SurfaceWrapper> {
        let caps = surface.get_capabilities(&gpu.adapter);
        let format = egui_wgpu::preferred_framebuffer_format(&caps.formats)
            .map_err(|e| Error::Gpu(format!("no usable surface format: {e}")))?;
        let mut config = surface
            .get_default_config(&gpu.adapter, width.max(1), height.max(1))
            .ok_or_else(|| Error::Gpu("the surface is not supported by the adapter".into()))?;
        config.format = format;
        config.present_mode = wgpu::PresentMode::AutoVsync;
        config.view_formats = vec![];
        surface.configure(&gpu.device, &config);
        Ok(SurfaceWrapper { surface, config })
    }

    /// The colour format of its frames.
    pub(crate) fn format(&self) -> wgpu::TextureFormat {
        self.config.format
    }

    /// Its size in pixels.
    pub(crate) fn size(&self) -> (u32, u32) {
        (self.config.width, self.config.height)
    }

    /// Reconfigures for a new window size; a zero size (minimised) is
    /// ignored. Whether the size changed.
    pub(crate) fn resize(&mut self, device: &wgpu::Device, width: u32, height: u32) -> bool {
        if width == 0 || height == 0 {
            return false;
        }
        self.config.width = width;
        self.config.height = height;
        self.surface.configure(device, &self.config);
        true
    }

    /// The next frame, reconfiguring a lost or outdated surface.
    pub(crate) fn acquire(&mut self, device: &wgpu::Device) -> Acquired {
        match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f) | wgpu::CurrentSurfaceTexture::Suboptimal(f) => Acquired::Frame(f),
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                self.surface.configure(device, &self.config);
                Acquired::Retry
            }
            _ => Acquired::Skip,
        }
    }
}
