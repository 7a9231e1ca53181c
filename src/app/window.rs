//! The window and everything it owns on the GPU: the surface, the renderer
//! and its targets, the egui layer, the GPU copies of the meshes, the cached
//! 3D image. The steps of a frame are methods here; [`super::App`] runs them
//! in order.

use super::Viewer;
use super::command::Command;
use super::gpu_scene::GpuScene;
use super::surface::SurfaceWrapper;
use crate::clock::Instant;
use crate::render::blit::Blit;
use crate::render::gpu_anim::AnimatedMesh;
use crate::render::readback::{Readback, capture_texture};
use crate::render::scene::{GpuMesh, Renderer, Targets, ViewportDraw};
use crate::render::{Camera, Gpu, Look, Surface};
use crate::{Error, Result};
use std::sync::{Arc, Mutex};
use std::time::Duration;
#[cfg(not(target_arch = "wasm32"))]
use winit::event_loop::ActiveEventLoop;
use winit::window::Window;

/// Meshes above this many triangles are drawn through their proxy (a
/// lower level) while the camera moves, so orbiting stays fluid on a
/// software rasteriser; the full mesh returns as soon as the motion stops.
pub(crate) const PROXY_ABOVE: usize = 300_000;

/// The 3D viewports rendered at the window's size, blitted every frame.
struct SceneTexture {
    view: wgpu::TextureView,
    group: wgpu::BindGroup,
}

impl SceneTexture {
    fn new(device: &wgpu::Device, blit: &Blit, format: wgpu::TextureFormat, (w, h): (u32, u32)) -> SceneTexture {
        let tex = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("scene"),
            size: wgpu::Extent3d { width: w.max(1), height: h.max(1), depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let view = tex.create_view(&Default::default());
        let group = blit.bind(device, &view);
        SceneTexture { view, group }
    }
}

/// Everything the 3D image depends on; equal keys mean the cached scene is current.
#[derive(Clone, Copy, PartialEq)]
pub(crate) struct SceneKey {
    camera: Camera,
    look: Look,
    side_by_side: bool,
    rect: [f32; 4],
    size: (u32, u32),
    version: u64,
    /// The proxy is drawn instead of the result.
    pub(crate) proxy: bool,
}

/// egui's context, its winit input state and its wgpu renderer.
struct EguiLayer {
    ctx: egui::Context,
    state: egui_winit::State,
    renderer: egui_wgpu::Renderer,
}

/// One frame of egui, tessellated, with the textures to free after it.
pub(crate) struct EguiFrame {
    jobs: Vec<egui::ClippedPrimitive>,
    screen: egui_wgpu::ScreenDescriptor,
    free: Vec<egui::TextureId>,
}

impl EguiFrame {
    /// Physical pixels per egui point.
    pub(crate) fn pixels_per_point(&self) -> f32 {
        self.screen.pixels_per_point
    }
}

/// A texture the frame is also drawn into, to be read back (a screenshot).
pub(crate) struct Capture {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    readback: Readback,
}

/// The window and its GPU state.
pub(crate) struct Win {
    /// The winit window.
    pub(crate) window: Arc<Window>,
    gpu: Gpu,
    surface: SurfaceWrapper,
    renderer: Renderer,
    targets: Targets,
    egui: EguiLayer,
    /// The GPU copies of the document's meshes.
    pub(crate) scene: GpuScene,
    blit: Blit,
    scene_texture: SceneTexture,
    /// What `scene_texture` holds (None: must render).
    pub(crate) scene_key: Option<SceneKey>,
    /// MSAA samples of the renderer's pipelines.
    samples: u32,
    /// The last GPU error (validation, out of memory): shown in the panel instead of a panic.
    gpu_error: Arc<Mutex<Option<String>>>,
    /// When egui wants the next frame.
    pub(crate) repaint_after: Option<Duration>,
    /// The title shown.
    title: String,
}

/// The window's title: the model, `*` before it while it has unsaved
/// changes.
pub(crate) fn title(doc: &super::doc::Doc) -> String {
    let star = if doc.edit.history.dirty() { "*" } else { "" };
    format!("{star}{} — subdiv", doc.model.name)
}

/// The window's first size in points: 1280 x 800, or within 90% of the
/// monitor's `(width, height)` in points where that is smaller, keeping
/// the aspect (a 1024 x 768 screen gets 921 x 576, never a window that
/// runs off it).
#[cfg(not(target_arch = "wasm32"))]
pub(crate) fn initial_size(monitor: Option<(f64, f64)>) -> (f64, f64) {
    let (w, h) = (1280.0, 800.0);
    let Some((mw, mh)) = monitor.filter(|&(mw, mh)| mw > 0.0 && mh > 0.0) else { return (w, h) };
    let k = (0.9 * mw / w).min(0.9 * mh / h).min(1.0);
    ((w * k).round().max(320.0), (h * k).round().max(240.0))
}

#[cfg(not(target_arch = "wasm32"))]
fn open_window(event_loop: &ActiveEventLoop) -> Result<Arc<Window>> {
    let monitor = event_loop.primary_monitor().or_else(|| event_loop.available_monitors().next()).map(|m| {
        let (size, scale) = (m.size(), m.scale_factor().max(0.1));
        (f64::from(size.width) / scale, f64::from(size.height) / scale)
    });
    let (w, h) = initial_size(monitor);
    let attrs = Window::default_attributes()
        .with_title("subdiv")
        .with_inner_size(winit::dpi::LogicalSize::new(w, h))
        .with_min_inner_size(winit::dpi::LogicalSize::new(320.0, 240.0));
    let window = event_loop.create_window(attrs).map_err(|e| Error::Gpu(format!("cannot open a window: {e}")))?;
    Ok(Arc::new(window))
}

/// The device and a surface on `window`.
#[cfg(not(target_arch = "wasm32"))]
fn connect(event_loop: &ActiveEventLoop, window: &Arc<Window>) -> Result<(Gpu, SurfaceWrapper)> {
    // wgpu 30: the instance needs the display connection, or GL cannot present.
    let desc =
        wgpu::InstanceDescriptor::new_with_display_handle(Box::new(event_loop.owned_display_handle())).with_env();
    let instance = wgpu::Instance::new(desc);
    let surface =
        instance.create_surface(window.clone()).map_err(|e| Error::Gpu(format!("cannot create a surface: {e}")))?;
    let gpu = pollster::block_on(Gpu::with_instance(instance, Some(&surface)))?;
    let size = window.inner_size();
    let surface = SurfaceWrapper::new(surface, &gpu, size.width, size.height)?;
    Ok((gpu, surface))
}

/// Uncaptured GPU errors land in the returned slot instead of panicking.
fn catch_gpu_errors(device: &wgpu::Device) -> Arc<Mutex<Option<String>>> {
    let slot: Arc<Mutex<Option<String>>> = Arc::default();
    let sink = slot.clone();
    device.on_uncaptured_error(Arc::new(move |e| {
        if let Ok(mut s) = sink.lock() {
            *s = Some(e.to_string());
        }
    }));
    slot
}

impl EguiLayer {
    fn new(window: &Window, gpu: &Gpu, format: wgpu::TextureFormat) -> EguiLayer {
        let ctx = egui::Context::default();
        let state = egui_winit::State::new(
            ctx.clone(),
            egui::ViewportId::ROOT,
            window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        let renderer = egui_wgpu::Renderer::new(&gpu.device, format, egui_wgpu::RendererOptions::default());
        EguiLayer { ctx, state, renderer }
    }
}

impl Win {
    /// Opens the window and sets up the GPU; reports the adapter and chooses
    /// the initial MSAA in `viewer`.
    #[cfg(not(target_arch = "wasm32"))]
    pub(crate) fn create(event_loop: &ActiveEventLoop, viewer: &mut Viewer) -> Result<Win> {
        let window = open_window(event_loop)?;
        let (gpu, surface) = connect(event_loop, &window)?;
        Win::from_parts(window, gpu, surface, viewer)
    }

    /// The window's GPU state on `gpu` and the configured `surface`.
    pub(crate) fn from_parts(
        window: Arc<Window>,
        gpu: Gpu,
        surface: SurfaceWrapper,
        viewer: &mut Viewer,
    ) -> Result<Win> {
        let format = surface.format();
        let gpu_error = catch_gpu_errors(&gpu.device);
        let egui = EguiLayer::new(&window, &gpu, format);
        let available = gpu.msaa_samples(format);
        viewer.view.stats.adapter = gpu.describe();
        viewer.view.stats.msaa_available = available > 1;
        // A software rasteriser pays per sample: start without MSAA there (the panel can turn it on).
        let msaa = available > 1 && (!gpu.is_software() || std::env::var_os("SUBDIV_MSAA").is_some());
        viewer.doc.display.msaa = msaa;
        let samples = if msaa { available } else { 1 };
        let renderer = Renderer::new(&gpu.device, format, samples);
        let (w, h) = surface.size();
        let targets = Targets::new(&gpu.device, &renderer, w, h);
        let blit = Blit::new(&gpu.device, format);
        let scene_texture = SceneTexture::new(&gpu.device, &blit, format, (w, h));
        Ok(Win {
            window,
            gpu,
            surface,
            renderer,
            targets,
            egui,
            scene: GpuScene::default(),
            blit,
            scene_texture,
            scene_key: None,
            samples,
            gpu_error,
            repaint_after: None,
            title: String::new(),
        })
    }

    /// Passes a window event to egui; whether egui wants a repaint.
    pub(crate) fn egui_event(&mut self, event: &winit::event::WindowEvent) -> bool {
        self.egui.state.on_window_event(&self.window, event).repaint
    }

    /// Follows a new window size (the surface and every size-bound target).
    pub(crate) fn resize(&mut self, width: u32, height: u32) {
        if self.surface.resize(&self.gpu.device, width, height) {
            let device = &self.gpu.device;
            self.targets = Targets::new(device, &self.renderer, width, height);
            self.scene_texture = SceneTexture::new(device, &self.blit, self.surface.format(), (width, height));
            self.scene_key = None;
        }
    }

    /// Uploads what changed, advances the animation, reports GPU errors.
    pub(crate) fn sync(&mut self, viewer: &mut Viewer) {
        let (t0, sent) = (Instant::now(), self.scene.uploaded_bytes);
        let normal_length = 0.03 * viewer.view.camera.radius;
        let mut report = self.scene.sync(&self.gpu.device, &self.gpu.queue, &viewer.doc, normal_length);
        if report.uploaded {
            viewer.view.stats.upload_ms = t0.elapsed().as_secs_f64() * 1e3;
            viewer.view.stats.upload_bytes = self.scene.uploaded_bytes - sent;
        }
        if let Some(e) = self.gpu_error.lock().ok().and_then(|mut slot| slot.take()) {
            report.errors.push(Error::Gpu(e));
        }
        viewer.apply(Command::Gpu(Box::new(report)));
    }

    /// Shows the document's title when it changed.
    pub(crate) fn show_title(&mut self, doc: &super::doc::Doc) {
        let t = title(doc);
        if t != self.title {
            self.window.set_title(&t);
            self.title = t;
        }
    }

    /// Whether the window has an area to draw into.
    pub(crate) fn is_minimised(&self) -> bool {
        let size = self.window.inner_size();
        size.width == 0 || size.height == 0
    }

    /// Runs the panel (its commands are applied) and tessellates it; egui's
    /// new textures are uploaded.
    pub(crate) fn run_egui(&mut self, viewer: &mut Viewer) -> EguiFrame {
        let raw = self.egui.state.take_egui_input(&self.window);
        let out = self.egui.ctx.run_ui(raw, |ui| {
            viewer.ui(ui);
        });
        self.egui.state.handle_platform_output(&self.window, out.platform_output);
        self.repaint_after = out.viewport_output.get(&egui::ViewportId::ROOT).map(|v| v.repaint_delay);
        let ppp = out.pixels_per_point;
        let jobs = self.egui.ctx.tessellate(out.shapes, ppp);
        let mut delta = out.textures_delta;
        for (id, ds) in delta.set.drain() {
            for d in ds {
                self.egui.renderer.update_texture(&self.gpu.device, &self.gpu.queue, id, &d);
            }
        }
        let (w, h) = self.surface.size();
        let screen = egui_wgpu::ScreenDescriptor { size_in_pixels: [w, h], pixels_per_point: ppp };
        EguiFrame { jobs, screen, free: delta.free.drain().collect() }
    }

    /// Frees the textures egui no longer uses (after the frame, drawn or not).
    pub(crate) fn end_egui(&mut self, frame: EguiFrame) {
        for id in &frame.free {
            self.egui.renderer.free_texture(id);
        }
    }

    /// The next surface frame; `None` when there is none now (a lost
    /// surface is reconfigured and a redraw requested).
    pub(crate) fn acquire(&mut self) -> Option<wgpu::SurfaceTexture> {
        match self.surface.acquire(&self.gpu.device) {
            super::surface::Acquired::Frame(f) => Some(f),
            super::surface::Acquired::Retry => {
                self.window.request_redraw();
                None
            }
            super::surface::Acquired::Skip => None,
        }
    }

    /// Rebuilds the pipelines when the MSAA option changed; turns the FXAA
    /// pass on or off.
    pub(crate) fn ensure_samples(&mut self, msaa: bool, fxaa: bool) {
        if self.renderer.fxaa != fxaa {
            self.renderer.fxaa = fxaa;
            self.scene_key = None;
        }
        let format = self.surface.format();
        let want = if msaa { self.gpu.msaa_samples(format) } else { 1 };
        if want != self.samples {
            self.renderer = Renderer::new(&self.gpu.device, format, want);
            self.renderer.fxaa = fxaa;
            let (w, h) = self.surface.size();
            self.targets = Targets::new(&self.gpu.device, &self.renderer, w, h);
            self.samples = want;
            self.scene_key = None;
        }
    }

    /// A command encoder with egui's buffers updated; the extra command
    /// buffers egui asked for come along.
    pub(crate) fn begin_frame(&mut self, egui: &EguiFrame) -> (wgpu::CommandEncoder, Vec<wgpu::CommandBuffer>) {
        let (device, queue) = (&self.gpu.device, &self.gpu.queue);
        let mut encoder = device.create_command_encoder(&Default::default());
        let user = self.egui.renderer.update_buffers(device, queue, &mut encoder, &egui.jobs, &egui.screen);
        (encoder, user)
    }

    /// Re-renders the 3D viewports into the cached texture when something
    /// they show changed; whether it did.
    pub(crate) fn draw_scene(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        viewer: &Viewer,
        ppp: f32,
        use_proxy: bool,
    ) -> bool {
        let rect = viewer.view.scene_rect;
        let r = [rect.left() * ppp, rect.top() * ppp, rect.width() * ppp, rect.height() * ppp];
        let display = &viewer.doc.display;
        let look = display.look();
        let key = SceneKey {
            camera: viewer.view.camera,
            look,
            side_by_side: display.side_by_side,
            rect: r,
            size: self.surface.size(),
            version: self.scene.version,
            proxy: use_proxy,
        };
        if self.scene_key == Some(key) {
            return false;
        }
        let s = &self.scene;
        let result = if viewer.doc.anim.active {
            s.anim.as_ref().map(AnimatedMesh::mesh).or(s.result.as_ref())
        } else if use_proxy {
            s.proxy.as_ref()
        } else {
            s.result.as_ref()
        };
        let draws = viewport_draws(s, result, viewer.view.camera, look, display.side_by_side, r);
        self.renderer.encode(
            &self.gpu.device,
            &self.gpu.queue,
            encoder,
            &self.targets,
            &self.scene_texture.view,
            &draws,
        );
        self.scene_key = Some(key);
        true
    }

    /// The 3D area alone (no panel), rendered offscreen at `shot.scale`
    /// times its size in pixels (`ppp` pixels per point), lines as wide
    /// relative to it, on a transparent background if asked: what P and the
    /// panel's button save.
    ///
    /// # Errors
    /// [`Error::Usage`] for a size the device cannot hold; readback errors.
    pub(crate) fn scene_shot(&self, viewer: &Viewer, ppp: f32, shot: crate::render::Shot) -> Result<image::RgbaImage> {
        let rect = viewer.view.scene_rect;
        let px = |v: f32| (v * ppp).round().max(1.0) as u32;
        let (w, h) = shot.size(px(rect.width()), px(rect.height()));
        let s = &self.scene;
        let result = if viewer.doc.anim.active {
            s.anim.as_ref().map(AnimatedMesh::mesh).or(s.result.as_ref())
        } else {
            s.result.as_ref()
        };
        let display = &viewer.doc.display;
        let r = [0.0, 0.0, w as f32, h as f32];
        let draws = viewport_draws(s, result, viewer.view.camera, display.look(), display.side_by_side, r);
        let samples = self.gpu.default_samples(crate::render::offscreen::OFFSCREEN_FORMAT);
        crate::render::offscreen::shoot(&self.gpu.device, &self.gpu.queue, samples, (w, h), shot, &draws)
    }

    /// Whether the result is big enough to be drawn through its proxy while the camera moves.
    pub(crate) fn has_big_result(&self) -> bool {
        self.scene.proxy.is_some() && self.scene.result.as_ref().is_some_and(|m| m.triangle_count() > PROXY_ABOVE)
    }

    /// A texture of the frame's size and format to read the frame back from.
    pub(crate) fn capture(&self) -> Capture {
        let (w, h) = self.surface.size();
        let (texture, view) = capture_texture(&self.gpu.device, "screenshot", self.surface.format(), w, h);
        Capture { texture, view, readback: Readback::new(&self.gpu.device, w, h) }
    }

    /// The cached 3D image, then egui over it, into `target` and into the
    /// capture when there is one (whose copy to its buffer is recorded too).
    pub(crate) fn composite(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        capture: Option<&Capture>,
        egui: &EguiFrame,
    ) {
        for view in std::iter::once(target).chain(capture.map(|c| &c.view)) {
            self.blit.draw(encoder, &self.scene_texture.group, view);
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            self.egui.renderer.render(&mut pass.forget_lifetime(), &egui.jobs, &egui.screen);
        }
        if let Some(c) = capture {
            c.readback.copy_from(encoder, &c.texture);
        }
    }

    /// Submits the frame's commands and presents it.
    pub(crate) fn present(
        &self,
        encoder: wgpu::CommandEncoder,
        user: Vec<wgpu::CommandBuffer>,
        frame: wgpu::SurfaceTexture,
    ) {
        self.gpu.queue.submit(user.into_iter().chain([encoder.finish()]));
        self.window.pre_present_notify();
        self.gpu.queue.present(frame);
    }

    /// The captured frame as an RGBA image (after [`Win::present`]).
    ///
    /// # Errors
    /// [`Error::Gpu`] when the readback fails.
    pub(crate) fn read_capture(&self, capture: &Capture) -> Result<image::RgbaImage> {
        capture.readback.read_rgba(&self.gpu.device, self.surface.format())
    }
}

/// The viewports of the 3D area `r` (pixels): a curve alone; or the control
/// mesh (wireframe) beside the result; or the result alone.
fn viewport_draws<'a>(
    s: &'a GpuScene,
    result: Option<&'a GpuMesh>,
    camera: Camera,
    look: Look,
    side_by_side: bool,
    r: [f32; 4],
) -> Vec<ViewportDraw<'a>> {
    if let Some((line, control)) = &s.curve {
        let look = Look { surface: Surface::Hidden, wireframe: true, control: true, ..Look::default() };
        return vec![ViewportDraw { rect: r, camera, mesh: Some(line), control: Some(control), look }];
    }
    if !side_by_side {
        return vec![ViewportDraw { rect: r, camera, mesh: result, control: s.control.as_ref(), look }];
    }
    let half = r[2] / 2.0;
    let left = Look { wireframe: true, control: false, normals: false, ..look };
    vec![
        ViewportDraw { rect: [r[0], r[1], half, r[3]], camera, mesh: s.control.as_ref(), control: None, look: left },
        ViewportDraw {
            rect: [r[0] + half, r[1], r[2] - half, r[3]],
            camera,
            mesh: result,
            control: s.control.as_ref(),
            look,
        },
    ]
}
