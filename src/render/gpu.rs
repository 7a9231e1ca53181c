//! Instance, adapter and device creation for the window and offscreen use.

use crate::{Error, Result};

/// A device and its queue, with the adapter they came from.
pub struct Gpu {
    /// The wgpu instance.
    pub instance: wgpu::Instance,
    /// The adapter chosen.
    pub adapter: wgpu::Adapter,
    /// The logical device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
}

impl Gpu {
    /// A device without any window (offscreen rendering, tests). Honours
    /// `WGPU_BACKEND` and the other wgpu environment variables.
    ///
    /// # Errors
    /// [`Error::Gpu`] when no adapter or device exists.
    pub(crate) fn headless() -> Result<Gpu> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = wgpu::Backends::all();
        let instance = wgpu::Instance::new(desc.with_env());
        #[cfg(not(target_arch = "wasm32"))]
        return pollster::block_on(Self::with_instance(instance, None));
        // a page cannot wait: its device comes with the window's surface
        #[cfg(target_arch = "wasm32")]
        {
            drop(instance);
            Err(Error::Gpu("offscreen rendering needs the desktop (subdiv render)".into()))
        }
    }

    /// Requests an adapter (compatible with `surface` when given) and a device.
    ///
    /// # Errors
    /// [`Error::Gpu`] when no adapter or device exists.
    pub(crate) async fn with_instance(
        instance: wgpu::Instance,
        surface: Option<&wgpu::Surface<'static>>,
    ) -> Result<Gpu> {
        let adapter = instance
            .request_adapter(&wgpu::RequestAdapterOptions {
                power_preference: wgpu::PowerPreference::HighPerformance,
                force_fallback_adapter: false,
                compatible_surface: surface,
                ..Default::default()
            })
            .await
            .map_err(|e| Error::Gpu(format!("no graphics adapter: {e}")))?;
        let (device, queue) = adapter
            .request_device(&wgpu::DeviceDescriptor {
                label: Some("subdiv"),
                // Everything the adapter offers: big meshes need big buffers.
                required_limits: adapter.limits(),
                ..Default::default()
            })
            .await
            .map_err(|e| Error::Gpu(format!("no graphics device: {e}")))?;
        Ok(Gpu { instance, adapter, device, queue })
    }

    /// `backend | name`, for logs and the stats panel.
    pub(crate) fn describe(&self) -> String {
        let info = self.adapter.get_info();
        format!("{:?} | {}", info.backend, info.name)
    }

    /// Whether the adapter is a software rasteriser (lavapipe, llvmpipe...).
    pub(crate) fn is_software(&self) -> bool {
        self.adapter.get_info().device_type == wgpu::DeviceType::Cpu
    }

    /// The sample count offscreen renders use: 1 on a software rasteriser,
    /// where 4x MSAA costs two to three times the frame and the FXAA pass
    /// smooths the edges instead, else [`Self::msaa_samples`]; `SUBDIV_MSAA`
    /// overrides both.
    pub(crate) fn default_samples(&self, format: wgpu::TextureFormat) -> u32 {
        if self.is_software() && std::env::var_os("SUBDIV_MSAA").is_none() { 1 } else { self.msaa_samples(format) }
    }

    /// Largest supported MSAA sample count (up to 4) usable with both `format`
    /// and the depth format. `SUBDIV_MSAA=1` (or 4) overrides.
    pub(crate) fn msaa_samples(&self, format: wgpu::TextureFormat) -> u32 {
        if let Some(n) = std::env::var("SUBDIV_MSAA").ok().and_then(|v| v.parse::<u32>().ok()) {
            return if n <= 1 { 1 } else { 4 };
        }
        let c = self.adapter.get_texture_format_features(format).flags;
        let d = self.adapter.get_texture_format_features(super::DEPTH_FORMAT).flags;
        [4, 2].into_iter().find(|&n| c.sample_count_supported(n) && d.sample_count_supported(n)).unwrap_or(1)
    }
}
