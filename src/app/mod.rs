//! The desktop viewer: winit window, wgpu surface, egui side panel.
//!
//! One frame: apply finished worker tasks ([`doc::Doc::poll`]), upload what
//! changed (only then), advance the animation (per frame only the stencil
//! plan and the normals are evaluated and copied into the existing vertex
//! buffers), run the panel, draw the 3D viewports into the surface and egui
//! over them. Nothing slow runs on this thread.

pub mod doc;
pub mod panel;

use crate::render::blit::Blit;
use crate::render::scene::{GpuMesh, Renderer, Targets, ViewportDraw};
use crate::render::{Gpu, Look, offscreen::padded_bytes_per_row, offscreen::read_rows};
use crate::{Error, Result, Scheme};
use doc::Doc;
use glam::Vec3;
use panel::UiState;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

/// What `subdiv view` (and `subdiv` with no arguments) was asked to show.
#[derive(Clone, Debug, Default)]
pub struct ViewOptions {
    /// Model to open (`None`: the bundled tetrahedron).
    pub model: Option<PathBuf>,
    /// Initial scheme.
    pub scheme: Scheme,
    /// Scheme options (Loop's or Warren's beta, tension, memory limit).
    pub opts: crate::Options,
    /// Initial level.
    pub level: u32,
    /// Start with the wireframe on.
    pub wireframe: bool,
    /// Render this many frames and exit (CI smoke test).
    pub frames: Option<u32>,
    /// Save the last frame here (with `frames`), or on P.
    pub screenshot: Option<PathBuf>,
    /// A `.paths` file for the animation.
    pub paths: Option<PathBuf>,
    /// Start playing the animation.
    pub play: bool,
    /// Start with the camera turning around the model.
    pub turntable: bool,
    /// Repair the model when opening it.
    pub repair: bool,
    /// Initial colouring.
    pub coloring: doc::Coloring,
}

/// Longest a `--frames` run may wait for its work before giving up.
const FRAMES_TIMEOUT: Duration = Duration::from_secs(300);

/// Opens the viewer window and runs until it is closed.
///
/// # Errors
/// When no window or GPU adapter can be created, or a `--frames` run fails.
pub fn run(opts: ViewOptions) -> Result<()> {
    // The model first: a bad file is reported as such even where no window can open.
    let mut app = App::new(opts)?;
    let event_loop = EventLoop::new().map_err(|e| {
        Error::Gpu(format!(
            "cannot open a window ({e}); without a display use `subdiv render` or `subdiv animate`, or run under xvfb-run"
        ))
    })?;
    event_loop.set_control_flow(ControlFlow::Wait);
    event_loop.run_app(&mut app).map_err(|e| Error::Gpu(format!("event loop: {e}")))?;
    match app.fatal.take() {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

struct Win {
    window: Arc<Window>,
    gpu: Gpu,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    renderer: Renderer,
    targets: Targets,
    egui_ctx: egui::Context,
    egui_state: egui_winit::State,
    egui_renderer: egui_wgpu::Renderer,
    control: Option<GpuMesh>,
    result: Option<GpuMesh>,
    proxy: Option<GpuMesh>,
    anim: Option<GpuMesh>,
    /// A Bezier curve: its polyline and its control polygon (with the construction highlighted).
    curve: Option<(GpuMesh, GpuMesh)>,
    repaint_after: Option<Duration>,
    blit: Blit,
    /// The 3D viewports rendered at the window's size, blitted every frame.
    scene: SceneTexture,
    /// What `scene` holds (None: must render).
    scene_key: Option<SceneKey>,
    /// Bumped on every mesh upload or animation update.
    version: u64,
    /// MSAA samples of the renderer's pipelines.
    samples: u32,
    /// The last GPU error (validation, out of memory): shown in the panel instead of a panic.
    gpu_error: Arc<std::sync::Mutex<Option<String>>>,
}

struct SceneTexture {
    view: wgpu::TextureView,
    group: wgpu::BindGroup,
}

impl SceneTexture {
    fn new(device: &wgpu::Device, blit: &Blit, format: wgpu::TextureFormat, w: u32, h: u32) -> SceneTexture {
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
struct SceneKey {
    camera: crate::render::Camera,
    look: Look,
    side_by_side: bool,
    rect: [f32; 4],
    size: (u32, u32),
    version: u64,
    proxy: bool,
}

/// Meshes above this many triangles are drawn through their proxy (a
/// lower level) while the camera moves, so orbiting stays fluid on a
/// software rasteriser; the full mesh returns as soon as the motion stops.
const PROXY_ABOVE: usize = 300_000;
/// How long after the last camera change the proxy is kept.
const SETTLE: Duration = Duration::from_millis(180);

struct App {
    opts: ViewOptions,
    doc: Doc,
    ui: UiState,
    win: Option<Win>,
    fatal: Option<Error>,
    frames_done: u32,
    /// Frame-to-frame times (ms) of the counted `--frames` frames.
    frame_log: Vec<f64>,
    last_camera: Option<crate::render::Camera>,
    last_motion: Instant,
    started: Instant,
    last_frame: Instant,
}

impl App {
    fn new(opts: ViewOptions) -> Result<App> {
        let mut doc = Doc::new();
        doc.scheme = opts.scheme;
        doc.opts = opts.opts;
        if let Some(limit) = opts.opts.max_memory {
            doc.limit = Some(limit);
        }
        doc.level = opts.level;
        if let Some(model) = opts.model.as_ref().filter(|m| m.extension().is_some_and(|e| e == "bzc")) {
            // Check the curve now so a bad file fails before any window; show it through the loader.
            crate::bundled::load_curve(model)?;
            doc.open(model.clone());
        } else if let Some(model) = &opts.model {
            // Load the first model synchronously so a bad file is a clear error before any window opens.
            let mesh = if opts.repair {
                let (mesh, report) = crate::bundled::load_repaired(model)?;
                if !report.is_empty() {
                    eprint!("{report}");
                    doc.notice = Some(format!("repaired: {report}"));
                }
                doc.repair_on_open = true;
                mesh
            } else if model.extension().is_none_or(|e| e.eq_ignore_ascii_case("obj")) {
                let (mesh, attrs) = crate::bundled::load_with_attributes(model)?;
                doc.file_attrs = attrs;
                mesh
            } else {
                crate::bundled::load(model)?
            };
            let paths = match &opts.paths {
                Some(p) => {
                    let paths = crate::anim::paths::Paths::load(p)?;
                    paths.check_model(&mesh, &p.display().to_string())?;
                    Some(paths)
                }
                None => doc::paths_for(model).and_then(|p| {
                    let paths = p.load().ok()?;
                    paths.check_model(&mesh, "").ok().map(|_| paths)
                }),
            };
            doc.adopt(model.clone(), mesh, paths);
        } else if let Some(p) = &opts.paths {
            let paths = crate::anim::paths::Paths::load(p)?;
            paths.check_model(&doc.control.mesh, &p.display().to_string())?;
            doc.paths = paths;
            doc.paths_source = p.display().to_string();
        }
        if let Some(reason) = doc.level_refusal(doc.level) {
            return Err(Error::Usage(reason));
        }
        doc.coloring = opts.coloring;
        doc.refresh_result();
        if doc.level > 0 {
            doc.request_subdivision();
        }
        if opts.play {
            doc.request_animation();
        }
        let mut ui = UiState::new(opts.wireframe);
        ui.turntable = opts.turntable;
        Ok(App {
            opts,
            doc,
            ui,
            win: None,
            fatal: None,
            frames_done: 0,
            frame_log: Vec::new(),
            last_camera: None,
            last_motion: Instant::now(),
            started: Instant::now(),
            last_frame: Instant::now(),
        })
    }

    fn create_window(&mut self, event_loop: &ActiveEventLoop) -> Result<Win> {
        let attrs = Window::default_attributes()
            .with_title("subdiv")
            .with_inner_size(winit::dpi::LogicalSize::new(1280.0, 800.0))
            .with_min_inner_size(winit::dpi::LogicalSize::new(320.0, 240.0));
        let window =
            Arc::new(event_loop.create_window(attrs).map_err(|e| Error::Gpu(format!("cannot open a window: {e}")))?);
        // wgpu 30: the instance needs the display connection, or GL cannot present.
        let desc =
            wgpu::InstanceDescriptor::new_with_display_handle(Box::new(event_loop.owned_display_handle())).with_env();
        let instance = wgpu::Instance::new(desc);
        let surface =
            instance.create_surface(window.clone()).map_err(|e| Error::Gpu(format!("cannot create a surface: {e}")))?;
        let gpu = pollster::block_on(Gpu::with_instance(instance, Some(&surface)))?;
        let caps = surface.get_capabilities(&gpu.adapter);
        let format = egui_wgpu::preferred_framebuffer_format(&caps.formats)
            .map_err(|e| Error::Gpu(format!("no usable surface format: {e}")))?;
        let size = window.inner_size();
        let mut config = surface
            .get_default_config(&gpu.adapter, size.width.max(1), size.height.max(1))
            .ok_or_else(|| Error::Gpu("the surface is not supported by the adapter".into()))?;
        config.format = format;
        config.present_mode = wgpu::PresentMode::AutoVsync;
        config.view_formats = vec![];
        surface.configure(&gpu.device, &config);
        let samples = gpu.msaa_samples(format);
        let gpu_error: Arc<std::sync::Mutex<Option<String>>> = Arc::default();
        let sink = gpu_error.clone();
        gpu.device.on_uncaptured_error(Arc::new(move |e| {
            if let Ok(mut slot) = sink.lock() {
                *slot = Some(e.to_string());
            }
        }));
        let egui_ctx = egui::Context::default();
        let egui_state = egui_winit::State::new(
            egui_ctx.clone(),
            egui::ViewportId::ROOT,
            &window,
            Some(window.scale_factor() as f32),
            None,
            Some(gpu.device.limits().max_texture_dimension_2d as usize),
        );
        let egui_renderer = egui_wgpu::Renderer::new(&gpu.device, format, egui_wgpu::RendererOptions::default());
        self.ui.adapter = gpu.describe();
        self.ui.msaa_available = samples > 1;
        // A software rasteriser pays per sample: start without MSAA there (the panel can turn it on).
        self.ui.msaa = samples > 1 && (!gpu.is_software() || std::env::var_os("SUBDIV_MSAA").is_some());
        let samples = if self.ui.msaa { samples } else { 1 };
        let renderer = Renderer::new(&gpu.device, format, samples);
        let targets = Targets::new(&gpu.device, &renderer, config.width, config.height);
        let blit = Blit::new(&gpu.device, format);
        let scene = SceneTexture::new(&gpu.device, &blit, format, config.width, config.height);
        Ok(Win {
            window,
            gpu,
            surface,
            config,
            renderer,
            targets,
            egui_ctx,
            egui_state,
            egui_renderer,
            control: None,
            result: None,
            proxy: None,
            anim: None,
            curve: None,
            repaint_after: None,
            blit,
            scene,
            scene_key: None,
            version: 0,
            samples,
            gpu_error,
        })
    }

    /// Uploads changed meshes and advances the animation.
    fn sync(&mut self, dt: f64) {
        let Some(win) = &mut self.win else { return };
        let (device, queue) = (&win.gpu.device, &win.gpu.queue);
        let doc = &mut self.doc;
        let t0 = Instant::now();
        let mut uploaded = false;
        let upload = |shown: &doc::Shown, error: &mut Option<String>| {
            GpuMesh::new(device, &shown.mesh.ct, &shown.mesh.positions, &shown.normals)
                .map_err(|e| *error = Some(e.to_string()))
                .ok()
        };
        if doc.control_changed {
            let fit = win.control.as_ref().is_none_or(|c| c.vertex_count() == 0) || doc.original.is_none();
            win.control = upload(&doc.control, &mut doc.error);
            doc.control_changed = false;
            // Edits (smoothing, flips) keep the view; a new model is framed.
            self.ui.fit |= fit;
            self.ui.highlighted = None;
            uploaded = true;
        }
        if self.ui.highlighted != doc.picked
            && let Some(c) = &mut win.control
        {
            let seg: Vec<Vec3> = doc
                .picked_edge()
                .map(|(a, b)| vec![doc.control.mesh.positions[a as usize], doc.control.mesh.positions[b as usize]])
                .unwrap_or_default();
            c.set_highlight(device, &seg);
            self.ui.highlighted = doc.picked;
            win.version += 1;
        }
        if doc.result_changed {
            let checker = doc.coloring == doc::Coloring::Checker;
            win.result =
                match doc.raw_attrs.uv.as_ref().filter(|u| checker && u.len() == doc.result.mesh.ct.v_table().len()) {
                    Some(uv) => {
                        let attr: Vec<Vec3> = uv.iter().map(|t| t.extend(0.0)).collect();
                        let r = &doc.result;
                        GpuMesh::unwelded(device, &r.mesh.ct, &r.mesh.positions, &r.normals, &attr)
                            .map_err(|e| doc.error = Some(e.to_string()))
                            .ok()
                    }
                    None => upload(&doc.result, &mut doc.error),
                };
            if let (Some(m), Some(colors), false) = (&mut win.result, &doc.result_colors, checker) {
                m.set_colors(device, colors);
            }
            win.proxy = doc.proxy.as_ref().and_then(|p| upload(p, &mut doc.error));
            doc.result_changed = false;
            uploaded = true;
        }
        if doc.curve_changed {
            let first = win.curve.is_none();
            win.curve = doc.curve.as_ref().map(|c| {
                let line = c.polyline();
                let pairs: Vec<u32> = (1..line.len() as u32).flat_map(|i| [i - 1, i]).collect();
                let poly: Vec<Vec3> = c.control.iter().map(|p| p.extend(0.0)).collect();
                let cpairs: Vec<u32> = (1..poly.len() as u32).flat_map(|i| [i - 1, i]).collect();
                let mut control = GpuMesh::lines(device, &poly, &cpairs);
                if c.construction {
                    let (mut segs, point) = c.construction_segments();
                    if let Some(q) = point {
                        let r = 0.01 * (poly.iter().fold(Vec3::ZERO, |a, p| a.max(p.abs()))).length().max(1e-6);
                        segs.extend([q - Vec3::X * r, q + Vec3::X * r, q - Vec3::Y * r, q + Vec3::Y * r]);
                    }
                    control.set_highlight(device, &segs);
                }
                (GpuMesh::lines(device, &line, &pairs), control)
            });
            if first && let Some(c) = &doc.curve {
                let points: Vec<Vec3> = c.control.iter().map(|p| p.extend(0.0)).collect();
                let (lo, hi) = crate::mesh::bounds_of(&points);
                self.ui.camera =
                    crate::render::Camera { yaw: 0.0, pitch: 0.0, orthographic: true, ..Default::default() };
                self.ui.camera.fit(lo, hi, 1.3);
            } else if win.curve.is_none() {
                self.ui.reset = true;
            }
            doc.curve_changed = false;
            win.version += 1;
        }
        let normal_length = 0.03 * self.ui.camera.radius;
        if let Some(a) = &mut doc.anim {
            let f = a.clock.tick(dt);
            if a.shown_frame != Some(f) {
                let fresh = a.shown_frame.is_none();
                let (topo, pos, nrm) = a.player.evaluate_with_topology(f);
                match &mut win.anim {
                    Some(m) if !fresh => m.update(queue, pos, nrm),
                    _ => win.anim = GpuMesh::new(device, topo, pos, nrm).ok(),
                }
                let cpos = a.player.control(f);
                if let Some(c) = &mut win.control {
                    let cn = crate::mesh::normals::vertex_normals(&doc.control.mesh.ct, cpos);
                    c.update(queue, cpos, &cn);
                }
                a.shown_frame = Some(f);
                win.version += 1;
            }
        } else if win.anim.is_some() {
            win.anim = None;
        }
        // Normal segments: built once per upload (a new GpuMesh has none), kept
        // current by GpuMesh::update while the animation plays.
        if self.ui.normals {
            if let Some(m) = win.result.as_mut().filter(|m| !m.has_normal_lines()) {
                m.set_normal_lines(device, &doc.result.mesh.positions, &doc.result.normals, normal_length);
                win.version += 1;
            }
            if let (Some(m), Some(a)) = (win.anim.as_mut(), doc.anim.as_mut())
                && !m.has_normal_lines()
            {
                let (pos, nrm) = a.player.evaluate(a.shown_frame.unwrap_or(0));
                m.set_normal_lines(device, pos, nrm, normal_length);
                win.version += 1;
            }
        } else {
            for m in [&mut win.result, &mut win.anim].into_iter().flatten() {
                if m.has_normal_lines() {
                    m.clear_normal_lines();
                    win.version += 1;
                }
            }
        }
        if uploaded {
            self.ui.upload_ms = t0.elapsed().as_secs_f64() * 1e3;
            win.version += 1;
        }
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        let raw_dt = (now - self.last_frame).as_secs_f64();
        let dt = raw_dt.min(0.25);
        self.last_frame = now;
        self.ui.frame_ms = if self.ui.frame_ms == 0.0 { dt * 1e3 } else { 0.9 * self.ui.frame_ms + 0.1 * dt * 1e3 };
        self.doc.poll();
        self.sync(dt);
        let Some(win) = &mut self.win else { return };
        if let Some(e) = win.gpu_error.lock().ok().and_then(|mut slot| slot.take()) {
            self.doc.error = Some(format!("graphics: {e}"));
        }
        let size = win.window.inner_size();
        if size.width == 0 || size.height == 0 {
            return; // minimised
        }
        let raw = win.egui_state.take_egui_input(&win.window);
        let (doc, ui_state) = (&mut self.doc, &mut self.ui);
        let out = win.egui_ctx.run_ui(raw, |ui| {
            panel::show(ui, doc, ui_state);
        });
        win.egui_state.handle_platform_output(&win.window, out.platform_output);
        win.repaint_after = out.viewport_output.get(&egui::ViewportId::ROOT).map(|v| v.repaint_delay);
        let ppp = out.pixels_per_point;
        let jobs = win.egui_ctx.tessellate(out.shapes, ppp);
        let mut delta = out.textures_delta;
        for (id, ds) in delta.set.drain() {
            for d in ds {
                win.egui_renderer.update_texture(&win.gpu.device, &win.gpu.queue, id, &d);
            }
        }

        // Camera fit/reset needs the 3D area's aspect.
        let rect = self.ui.scene_rect;
        let aspect = panel::viewport_aspect(rect, self.ui.side_by_side);
        if self.ui.reset {
            let ortho = self.ui.camera.orthographic;
            self.ui.camera = crate::render::Camera { orthographic: ortho, ..Default::default() };
            self.ui.fit = true;
            self.ui.reset = false;
        }
        if self.ui.fit && rect.is_positive() && self.doc.curve.is_none() {
            // Fit what is shown: the result (a Loop surface can be much smaller than its control mesh).
            let (lo, hi) = self.doc.result.mesh.bounds();
            self.ui.camera.fit(lo, hi, aspect);
            self.ui.fit = false;
        }

        let frame = match win.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f) | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                win.surface.configure(&win.gpu.device, &win.config);
                win.window.request_redraw();
                for id in delta.free.drain() {
                    win.egui_renderer.free_texture(&id);
                }
                return;
            }
            _ => {
                for id in delta.free.drain() {
                    win.egui_renderer.free_texture(&id);
                }
                return;
            }
        };
        let view = frame.texture.create_view(&Default::default());
        let want = if self.ui.msaa { win.gpu.msaa_samples(win.config.format) } else { 1 };
        if want != win.samples {
            win.renderer = Renderer::new(&win.gpu.device, win.config.format, want);
            win.targets = Targets::new(&win.gpu.device, &win.renderer, win.config.width, win.config.height);
            win.samples = want;
            win.scene_key = None;
        }
        let r = [rect.left() * ppp, rect.top() * ppp, rect.width() * ppp, rect.height() * ppp];
        if self.ui.turntable {
            self.ui.camera.yaw += (dt * 0.8) as f32;
        }
        if Some(self.ui.camera) != self.last_camera {
            self.last_camera = Some(self.ui.camera);
            self.last_motion = now;
        }
        let big = win.result.as_ref().is_some_and(|m| m.triangle_count() > PROXY_ABOVE);
        let use_proxy = !self.doc.animating && big && win.proxy.is_some() && now - self.last_motion < SETTLE;
        let result_mesh = if self.doc.animating {
            win.anim.as_ref().or(win.result.as_ref())
        } else if use_proxy {
            win.proxy.as_ref()
        } else {
            win.result.as_ref()
        };
        let look = Look {
            colors: self.doc.coloring != doc::Coloring::None,
            uv_checker: self.doc.coloring == doc::Coloring::Checker,
            ..self.ui.look()
        };
        let mut draws = Vec::with_capacity(2);
        if let Some((line, control)) = &win.curve {
            let look =
                Look { surface: crate::render::Surface::Hidden, wireframe: true, control: true, ..Look::default() };
            draws.push(ViewportDraw {
                rect: r,
                camera: self.ui.camera,
                mesh: Some(line),
                control: Some(control),
                look,
            });
        } else if self.ui.side_by_side {
            let half = r[2] / 2.0;
            let left = Look { wireframe: true, control: false, normals: false, ..look };
            draws.push(ViewportDraw {
                rect: [r[0], r[1], half, r[3]],
                camera: self.ui.camera,
                mesh: win.control.as_ref(),
                control: None,
                look: left,
            });
            draws.push(ViewportDraw {
                rect: [r[0] + half, r[1], r[2] - half, r[3]],
                camera: self.ui.camera,
                mesh: result_mesh,
                control: win.control.as_ref(),
                look,
            });
        } else {
            draws.push(ViewportDraw {
                rect: r,
                camera: self.ui.camera,
                mesh: result_mesh,
                control: win.control.as_ref(),
                look,
            });
        }
        let screen = egui_wgpu::ScreenDescriptor {
            size_in_pixels: [win.config.width, win.config.height],
            pixels_per_point: ppp,
        };
        let mut encoder = win.gpu.device.create_command_encoder(&Default::default());
        let user_cmds = win.egui_renderer.update_buffers(&win.gpu.device, &win.gpu.queue, &mut encoder, &jobs, &screen);

        // The 3D viewports are re-rendered only when something they show changed.
        let key = SceneKey {
            camera: self.ui.camera,
            look,
            side_by_side: self.ui.side_by_side,
            rect: r,
            size: (win.config.width, win.config.height),
            version: win.version,
            proxy: use_proxy,
        };
        if win.scene_key != Some(key) {
            let t = Instant::now();
            win.renderer.encode(&win.gpu.device, &win.gpu.queue, &mut encoder, &win.targets, &win.scene.view, &draws);
            win.scene_key = Some(key);
            self.ui.scene_renders += 1;
            self.ui.encode_ms = t.elapsed().as_secs_f64() * 1e3;
        }

        // The frames-mode exit and the P key both take a screenshot of this frame.
        let finishing = self.opts.frames.is_some_and(|n| {
            if !self.doc.busy() {
                self.frames_done += 1;
                self.frame_log.push(raw_dt * 1e3);
            }
            self.frames_done >= n
        });
        let shot_path = if finishing {
            self.opts.screenshot.clone()
        } else if std::mem::take(&mut self.ui.screenshot) {
            Some(self.opts.screenshot.clone().unwrap_or_else(|| {
                let secs = std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map(|d| d.as_secs())
                    .unwrap_or(0);
                PathBuf::from(format!("subdiv-{secs}.png"))
            }))
        } else {
            None
        };
        let shot = shot_path.as_ref().map(|_| {
            let tex = win.gpu.device.create_texture(&wgpu::TextureDescriptor {
                label: Some("screenshot"),
                size: wgpu::Extent3d { width: win.config.width, height: win.config.height, depth_or_array_layers: 1 },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: win.config.format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            });
            let v = tex.create_view(&Default::default());
            (tex, v)
        });
        let mut targets_views = vec![&view];
        if let Some((_, v)) = &shot {
            targets_views.push(v);
        }
        for target in targets_views {
            win.blit.draw(&mut encoder, &win.scene.group, target);
            let pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("egui"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: target,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations { load: wgpu::LoadOp::Load, store: wgpu::StoreOp::Store },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            win.egui_renderer.render(&mut pass.forget_lifetime(), &jobs, &screen);
        }
        let readback = shot.as_ref().map(|(tex, _)| {
            let padded = padded_bytes_per_row(win.config.width);
            let buf = win.gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("screenshot readback"),
                size: u64::from(padded) * u64::from(win.config.height),
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            encoder.copy_texture_to_buffer(
                tex.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: &buf,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(padded),
                        rows_per_image: Some(win.config.height),
                    },
                },
                tex.size(),
            );
            (buf, padded)
        });
        win.gpu.queue.submit(user_cmds.into_iter().chain([encoder.finish()]));
        win.window.pre_present_notify();
        win.gpu.queue.present(frame);
        for id in delta.free.drain() {
            win.egui_renderer.free_texture(&id);
        }
        if let (Some(path), Some((buf, padded))) = (shot_path, readback) {
            let saved =
                read_rows(&win.gpu.device, &buf, padded, win.config.width, win.config.height).and_then(|mut img| {
                    if matches!(
                        win.config.format,
                        wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb
                    ) {
                        for px in img.pixels_mut() {
                            px.0.swap(0, 2);
                        }
                    }
                    for px in img.pixels_mut() {
                        px.0[3] = 255;
                    }
                    crate::render::save_png(&img, &path)
                });
            match saved {
                Ok(()) => self.doc.notice = Some(format!("saved {}", path.display())),
                Err(e) => {
                    if finishing {
                        self.fatal = Some(e);
                    } else {
                        self.doc.error = Some(e.to_string());
                    }
                }
            }
        }
        if finishing {
            // Skip the first frames (uploads, pipeline warm-up) in the summary.
            let tail = &self.frame_log[self.frame_log.len() / 3..];
            if !tail.is_empty() {
                let mean = tail.iter().sum::<f64>() / tail.len() as f64;
                let max = tail.iter().fold(0.0f64, |a, &b| a.max(b));
                let tris = result_tris(&self.doc);
                let anim = match &self.doc.anim {
                    Some(a) => format!(
                        " anim_plan_ms={:.2} anim_normals_ms={:.2}",
                        a.player.last_timing.0.as_secs_f64() * 1e3,
                        a.player.last_timing.1.as_secs_f64() * 1e3
                    ),
                    None => String::new(),
                };
                println!(
                    "frames={} frame_ms_mean={mean:.1} frame_ms_max={max:.1} triangles={tris}{anim} scene_renders={} adapter=\"{}\"",
                    tail.len(),
                    self.ui.scene_renders,
                    self.ui.adapter
                );
            }
            if let Some(e) = self.doc.error.take().filter(|_| self.fatal.is_none()) {
                self.fatal = Some(Error::Usage(e));
            }
            event_loop.exit();
        } else if self.opts.frames.is_some() && self.started.elapsed() > FRAMES_TIMEOUT {
            self.fatal =
                Some(Error::Timeout { what: "--frames: the work".into(), seconds: FRAMES_TIMEOUT.as_secs_f64() });
            event_loop.exit();
        }
    }
}

fn result_tris(doc: &Doc) -> usize {
    match &doc.anim {
        Some(a) if doc.animating => a.player.topology().num_triangles(),
        _ => doc.result.mesh.ct.num_triangles(),
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.win.is_some() {
            return;
        }
        match self.create_window(event_loop) {
            Ok(win) => {
                win.window.request_redraw();
                self.win = Some(win);
            }
            Err(e) => {
                self.fatal = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(win) = &mut self.win else { return };
        let response = win.egui_state.on_window_event(&win.window, &event);
        if response.repaint {
            win.window.request_redraw();
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if size.width > 0 && size.height > 0 {
                    win.config.width = size.width;
                    win.config.height = size.height;
                    win.surface.configure(&win.gpu.device, &win.config);
                    win.targets = Targets::new(&win.gpu.device, &win.renderer, size.width, size.height);
                    win.scene =
                        SceneTexture::new(&win.gpu.device, &win.blit, win.config.format, size.width, size.height);
                    win.scene_key = None;
                }
                win.window.request_redraw();
            }
            WindowEvent::HoveredFile(_) => self.ui.hovering_file = true,
            WindowEvent::HoveredFileCancelled => self.ui.hovering_file = false,
            WindowEvent::DroppedFile(path) => {
                self.ui.hovering_file = false;
                self.doc.open(path);
                win.window.request_redraw();
            }
            WindowEvent::RedrawRequested => {
                self.redraw(event_loop);
                if let Some(win) = &self.win
                    && (self.opts.frames.is_some()
                        || self.doc.busy()
                        || self.doc.anim.as_ref().is_some_and(|a| a.clock.playing))
                {
                    win.window.request_redraw();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(win) = &self.win else { return };
        let settle_at = self.last_motion + SETTLE + Duration::from_millis(5);
        if win.scene_key.is_some_and(|k| k.proxy) {
            // The proxy is showing: come back for the full mesh once the camera has settled.
            if Instant::now() >= settle_at {
                win.window.request_redraw();
            } else {
                event_loop.set_control_flow(ControlFlow::WaitUntil(settle_at));
                return;
            }
        }
        if self.doc.busy() || self.ui.turntable || self.doc.anim.as_ref().is_some_and(|a| a.clock.playing) {
            // Poll the workers (and play) at the frame rate.
            win.window.request_redraw();
            event_loop.set_control_flow(ControlFlow::Wait);
        } else if let Some(d) = win.repaint_after {
            if d.is_zero() {
                win.window.request_redraw();
                event_loop.set_control_flow(ControlFlow::Wait);
            } else if d < Duration::from_secs(3600) {
                event_loop.set_control_flow(ControlFlow::WaitUntil(Instant::now() + d));
            } else {
                event_loop.set_control_flow(ControlFlow::Wait);
            }
        }
    }

    fn new_events(&mut self, _event_loop: &ActiveEventLoop, cause: winit::event::StartCause) {
        if let (winit::event::StartCause::ResumeTimeReached { .. }, Some(win)) = (cause, &self.win) {
            win.window.request_redraw();
        }
    }
}
