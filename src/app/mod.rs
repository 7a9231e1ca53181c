//! The desktop viewer: winit window, wgpu surface, egui side panel.
//!
//! The state, split by what changes together (egui's demo app pattern):
//! ```text
//! Viewer (viewer.rs)            the viewer without a window; what the tests drive
//! ├── doc: Doc (doc.rs)         the document
//! │   ├── model (model.rs)        control mesh, subdivision output, shown result, proxy,
//! │   │                           attributes, picked edge, picked point (probe.rs),
//! │   │                           curve; versions per artefact
//! │   ├── display (display.rs)    surface, wireframe, overlays, normals, colouring
//! │   ├── anim (animation.rs)     paths, the built plan, the playback clock
//! │   ├── jobs (jobs.rs)          worker channel, tickets, busy slots, cancellation
//! │   └── request, status         the subdivision asked for; errors and notices
//! ├── view: View (view.rs)      camera, pending fits, frame statistics
//! └── panel: PanelState         the panel's text fields and file browser
//! ```
//! The panel (`panel/`) reads all of it and returns `Command`s; workers'
//! results arrive as `Command::Finished`; `Viewer::apply` (command.rs)
//! is the one place that changes the document.
//!
//! One frame (`App::redraw`): adopt finished worker tasks, upload what
//! changed by version and advance the animation (gpu_scene.rs: per frame only
//! the stencil plan and the normals are evaluated and copied into the
//! existing vertex buffers), run the panel, acquire the surface frame
//! (surface.rs), draw the 3D viewports into a cached texture when they
//! changed, blit it and draw egui over it, present, save a screenshot
//! (window.rs). Nothing slow runs on this thread.

pub(crate) mod adaptive;
pub(crate) mod animation;
pub(crate) mod command;
pub(crate) mod display;
pub(crate) mod doc;
pub(crate) mod edit;
mod gpu_scene;
pub(crate) mod inspect;
pub(crate) mod jobs;
pub(crate) mod keys;
pub(crate) mod model;
#[cfg(target_arch = "wasm32")]
pub mod page;
#[cfg(any(target_arch = "wasm32", test))]
pub(crate) mod page_query;
pub(crate) mod panel;
pub(crate) mod probe;
pub(crate) mod recovery;
pub(crate) mod surface;
pub(crate) mod view;
pub(crate) mod viewer;
mod window;

#[cfg(test)]
mod adaptive_tests;
#[cfg(test)]
mod edit_tests;
#[cfg(test)]
mod inspect_tests;
#[cfg(test)]
mod stage_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod upload_tests;

pub(crate) use command::Command;
pub(crate) use viewer::Viewer;

use crate::clock::Instant;
use crate::render::Camera;
use crate::{Error, Result, Scheme};
use display::Display;
use std::path::PathBuf;
use std::time::Duration;
use window::Win;
use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::window::WindowId;

/// What `subdiv view` (and `subdiv` with no arguments) was asked to show.
#[derive(Clone, Debug, Default)]
pub struct ViewOptions {
    /// Model to open (`None`: the bundled tetrahedron).
    pub model: Option<PathBuf>,
    /// Initial scheme.
    pub scheme: Scheme,
    /// Scheme options (Loop's or Warren's beta, tension, memory limit).
    pub opts: crate::Options,
    /// Which of `opts`' shape options (boundary, face-varying, triangles,
    /// creasing) the command line gave: a file's option tags do not
    /// replace those.
    pub flags: crate::mesh::options::ShapeOptions,
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
    /// The time code a USD stage's sampled points are read at (`None`:
    /// where the stage opens).
    pub time: Option<f64>,
    /// Initial colouring; `None` is auto (see [`crate::render::Coloring::initial`]).
    pub coloring: Option<crate::render::Coloring>,
    /// Start with this many isolines per side of zero over a curvature
    /// colouring (`None`: off).
    pub isolines: Option<u8>,
    /// The half-width of the curvature colours' range (`None`: the default
    /// percentile, see `crate::subdiv::eval::color`).
    pub range: Option<crate::subdiv::eval::color::HalfWidth>,
    /// Tag the edges sharper than this dihedral angle (degrees) on opening.
    pub crease_angle: Option<f32>,
    /// Start with the control mesh (the cage) shown.
    pub control: bool,
    /// Start with the adaptive display (the limit within half a pixel).
    pub adaptive: bool,
}

impl ViewOptions {
    /// What `subdiv` with no arguments shows a new user: the bundled
    /// tetrahedron at level 3 with the butterfly scheme (the original
    /// assignment's), under its translucent cage. Interpolating, so the
    /// surface passes through the cage's corners and the levels visibly
    /// round it off; four faces make the cage easy to read.
    pub fn first_launch() -> ViewOptions {
        ViewOptions { scheme: Scheme::Butterfly, level: 3, control: true, ..ViewOptions::default() }
    }
}

/// Longest a `--frames` run may wait for its work before giving up.
const FRAMES_TIMEOUT: Duration = Duration::from_secs(300);

/// How long after the last camera change the proxy is kept.
const SETTLE: Duration = Duration::from_millis(180);

/// Opens the viewer window and runs until it is closed.
///
/// # Errors
/// When no window or GPU adapter can be created, or a `--frames` run fails.
#[cfg(not(target_arch = "wasm32"))]
pub fn run(opts: ViewOptions) -> Result<()> {
    // The model first: a bad file is reported as such even where no window can open.
    let mut app = App::new(opts)?;
    let event_loop = winit::event_loop::EventLoop::new().map_err(|e| {
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

/// Opens the model of the command line through the same command as any
/// other ([`Command::Open`]), waiting for its worker, so that a bad file is
/// a clear error before any window opens; then the `--paths` given.
fn open_initial(viewer: &mut Viewer, opts: &ViewOptions) -> Result<()> {
    if let Some(model) = &opts.model {
        viewer.apply(Command::SetRepairOnOpen(opts.repair));
        viewer.doc.read_time = opts.time;
        viewer.apply(Command::Open(model.clone()));
        // a read is bounded by its budget: it ends
        while viewer.doc.jobs.busy.loading.is_some() {
            viewer.doc.jobs.wait_for_workers(Duration::from_secs(1));
            viewer.poll();
        }
        if let Some(doc::Problem::Open(e)) = viewer.doc.status.error.take() {
            return Err(e);
        }
        if let Some(notice) = &viewer.doc.status.notice {
            log::warn!("{notice}");
        }
    }
    if let Some(p) = &opts.paths {
        let doc = &mut viewer.doc;
        let paths = crate::anim::paths::Paths::load(p, &crate::io::Limits::default())?;
        paths.check_model(&doc.model.control.mesh, &p.display().to_string())?;
        doc.anim.paths = paths;
        doc.anim.paths_source = p.display().to_string();
    }
    Ok(())
}

/// A `--frames N` run: counts frames, times them, says when to finish.
struct FramesRun {
    frames: Option<u32>,
    screenshot: Option<PathBuf>,
    done: u32,
    /// Frame-to-frame times (ms) of the counted frames.
    log: Vec<f64>,
    started: Instant,
}

impl FramesRun {
    /// Counts a frame unless the workers are still busy; whether the run
    /// ends with this frame.
    fn count(&mut self, raw_dt: f64, busy: bool) -> bool {
        self.frames.is_some_and(|n| {
            if !busy {
                self.done += 1;
                self.log.push(raw_dt * 1e3);
            }
            self.done >= n
        })
    }

    /// Where this frame's screenshot goes: the run's last frame, or P
    /// (`asked`) to the `--screenshot` file or a timestamped one.
    fn shot_path(&self, finishing: bool, asked: bool) -> Option<PathBuf> {
        if finishing {
            self.screenshot.clone()
        } else if asked {
            Some(self.screenshot.clone().unwrap_or_else(|| {
                let secs = std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map(|d| d.as_secs())
                    .unwrap_or(0);
                PathBuf::from(format!("subdiv-{secs}.png"))
            }))
        } else {
            None
        }
    }

    /// The `frames=... frame_ms_mean=...` line, without the first frames
    /// (uploads, pipeline warm-up).
    fn summary(&self, viewer: &Viewer) -> Option<String> {
        let tail = &self.log[self.log.len() / 3..];
        if tail.is_empty() {
            return None;
        }
        let mean = tail.iter().sum::<f64>() / tail.len() as f64;
        let max = tail.iter().fold(0.0f64, |a, &b| a.max(b));
        let doc = &viewer.doc;
        let (tris, anim) = match &doc.anim.playback {
            Some(p) => {
                let (plan, normals) = p.player.last_timing;
                let timing = format!(
                    " anim_plan_ms={:.2} anim_normals_ms={:.2} plan_ms={:.1} anim_frame_ms={:.2}",
                    plan.as_secs_f64() * 1e3,
                    normals.as_secs_f64() * 1e3,
                    p.player.plan_ms(),
                    p.player.frame_ms().unwrap_or(0.0)
                );
                let tris = if doc.anim.active { p.player.topology().num_triangles() } else { result_tris(doc) };
                (tris, timing)
            }
            None => (result_tris(doc), String::new()),
        };
        let stats = &viewer.view.stats;
        Some(format!(
            "frames={} frame_ms_mean={mean:.1} frame_ms_max={max:.1} triangles={tris}{anim} scene_renders={} adapter=\"{}\"",
            tail.len(),
            stats.scene_renders,
            stats.adapter
        ))
    }
}

fn result_tris(doc: &doc::Doc) -> usize {
    doc.model.result.shown.mesh.ct.num_triangles()
}

/// When the camera last moved, so that a big result is drawn through its
/// proxy while it moves.
struct Motion {
    last_camera: Option<Camera>,
    last_motion: Instant,
}

impl Motion {
    /// Notes the camera of this frame; whether it moved within [`SETTLE`].
    fn moving(&mut self, camera: Camera, now: Instant) -> bool {
        if Some(camera) != self.last_camera {
            self.last_camera = Some(camera);
            self.last_motion = now;
        }
        now - self.last_motion < SETTLE
    }
}

struct App {
    viewer: Viewer,
    win: Option<Win>,
    fatal: Option<Error>,
    run: FramesRun,
    motion: Motion,
    last_frame: Instant,
}

impl App {
    fn new(opts: ViewOptions) -> Result<App> {
        let mut viewer = Viewer::new();
        let doc = &mut viewer.doc;
        doc.request.scheme = opts.scheme;
        doc.request.opts = opts.opts;
        doc.pinned = opts.flags;
        if let Some(limit) = opts.opts.max_memory {
            doc.request.limit = Some(limit);
        }
        doc.request.level = opts.level;
        open_initial(&mut viewer, &opts)?;
        let doc = &mut viewer.doc;
        if let Some(deg) = opts.crease_angle {
            doc.auto_crease(deg);
            viewer.panel.crease_angle = deg;
        }
        let doc = &mut viewer.doc;
        if let Some(e) = doc.level_refusal(doc.request.level) {
            return Err(e);
        }
        // a model with MTL materials opens showing them unless a colouring was asked for
        let coloring = crate::render::Coloring::initial(opts.coloring, doc.model.attrs.file.materials.is_some());
        doc.display = Display {
            turntable: opts.turntable,
            coloring,
            control: opts.control,
            adaptive: opts.adaptive,
            ..Display::new(opts.wireframe)
        };
        if let Some(count) = opts.isolines {
            doc.display.isolines = display::Isolines { on: true, count };
        }
        doc.display.range = opts.range;
        doc.reshade();
        if doc.request.level > 0 {
            doc.request_subdivision();
        }
        if opts.play {
            doc.request_animation();
        }
        let now = Instant::now();
        Ok(App {
            viewer,
            win: None,
            fatal: None,
            run: FramesRun { frames: opts.frames, screenshot: opts.screenshot, done: 0, log: Vec::new(), started: now },
            motion: Motion { last_camera: None, last_motion: now },
            last_frame: now,
        })
    }

    /// Time since the last frame: as measured, and capped for the animation clock.
    fn tick(&mut self) -> (f64, f64) {
        let now = Instant::now();
        let raw_dt = (now - self.last_frame).as_secs_f64();
        let dt = raw_dt.min(0.25);
        self.last_frame = now;
        let stats = &mut self.viewer.view.stats;
        stats.frame_ms = if stats.frame_ms == 0.0 { dt * 1e3 } else { 0.9 * stats.frame_ms + 0.1 * dt * 1e3 };
        (raw_dt, dt)
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let (raw_dt, dt) = self.tick();
        self.viewer.poll();
        self.viewer.advance(dt);
        let Some(win) = &mut self.win else { return };
        win.sync(&mut self.viewer);
        if win.is_minimised() {
            return;
        }
        let egui = win.run_egui(&mut self.viewer);
        let Some(frame) = win.acquire() else {
            win.end_egui(egui);
            return;
        };
        let target = frame.texture.create_view(&Default::default());
        let viewer = &mut self.viewer;
        win.ensure_samples(viewer.doc.display.msaa, viewer.doc.display.fxaa);
        if viewer.doc.display.turntable {
            viewer.view.camera.yaw += (dt * 0.8) as f32;
        }
        let moving = self.motion.moving(viewer.view.camera, Instant::now());
        let use_proxy = !viewer.doc.anim.active && !viewer.doc.display.adaptive && win.has_big_result() && moving;
        let (mut encoder, user) = win.begin_frame(&egui);
        let t = Instant::now();
        if win.draw_scene(&mut encoder, viewer, egui.pixels_per_point(), use_proxy) {
            viewer.view.stats.scene_renders += 1;
            viewer.view.stats.encode_ms = t.elapsed().as_secs_f64() * 1e3;
        }
        // The frames-mode exit captures this frame, panel and all; the P key
        // renders the 3D area offscreen, as View::shot says (scale, transparency).
        let finishing = self.run.count(raw_dt, viewer.doc.busy());
        let asked = std::mem::take(&mut viewer.view.screenshot);
        // a page cannot wait for the GPU's readback, nor write a file
        #[cfg(target_arch = "wasm32")]
        let asked = asked && {
            viewer.doc.status.notice = Some("screenshots need the desktop viewer (or `subdiv render`)".into());
            false
        };
        let shot = self.run.shot_path(finishing, asked);
        let capture = shot.as_ref().filter(|_| finishing).map(|_| win.capture());
        let ppp = egui.pixels_per_point();
        win.composite(&mut encoder, &target, capture.as_ref(), &egui);
        win.present(encoder, user, frame);
        win.end_egui(egui);
        if let Some(path) = shot {
            let img = match &capture {
                Some(c) => win.read_capture(c),
                None => win.scene_shot(viewer, ppp, viewer.view.shot),
            };
            let saved = img.and_then(|img| crate::render::save_png(&img, &path));
            match saved {
                Ok(()) => viewer.doc.status.notice = Some(format!("saved {}", path.display())),
                Err(e) if finishing => self.fatal = Some(e),
                Err(e) => viewer.doc.fail(e.into()),
            }
        }
        win.show_title(&viewer.doc);
        if viewer.view.quit {
            event_loop.exit();
        }
        self.end_of_frame(event_loop, finishing);
    }

    /// Ends a `--frames` run after its last frame (printing the frame times,
    /// failing on a shown error), or when it waited too long.
    fn end_of_frame(&mut self, event_loop: &ActiveEventLoop, finishing: bool) {
        if finishing {
            if let Some(line) = self.run.summary(&self.viewer) {
                println!("{line}");
            }
            if let Some(p) = self.viewer.doc.status.error.take().filter(|_| self.fatal.is_none()) {
                self.fatal = Some(p.into_error());
            }
            event_loop.exit();
        } else if self.run.frames.is_some() && self.run.started.elapsed() > FRAMES_TIMEOUT {
            self.fatal =
                Some(Error::Timeout { what: "--frames: the work".into(), seconds: FRAMES_TIMEOUT.as_secs_f64() });
            event_loop.exit();
        }
    }

    /// Whether frames must keep coming (a run, a worker to poll, playback).
    fn animating(&self) -> bool {
        self.run.frames.is_some() || self.viewer.doc.busy() || self.viewer.doc.anim.playing()
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.win.is_some() {
            return;
        }
        // the page opens its window itself (page.rs: its device comes later)
        #[cfg(target_arch = "wasm32")]
        let _ = event_loop;
        #[cfg(not(target_arch = "wasm32"))]
        match Win::create(event_loop, &mut self.viewer) {
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
        // egui asks a repaint of every redraw it sees; the redraw under way
        // is that repaint (asking another, the browser draws forever)
        if win.egui_event(&event) && !matches!(event, WindowEvent::RedrawRequested) {
            win.window.request_redraw();
        }
        let view = &mut self.viewer.view;
        match event {
            WindowEvent::CloseRequested if self.viewer.doc.edit.history.dirty() => {
                self.viewer.doc.edit.pending = Some(edit::Pending::Close);
                win.window.request_redraw();
            }
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                win.resize(size.width, size.height);
                win.window.request_redraw();
            }
            WindowEvent::HoveredFile(_) => view.hovering_file = true,
            WindowEvent::HoveredFileCancelled => view.hovering_file = false,
            WindowEvent::DroppedFile(path) => {
                view.hovering_file = false;
                win.window.request_redraw();
                self.viewer.apply(Command::Open(path));
            }
            WindowEvent::RedrawRequested => {
                self.redraw(event_loop);
                if let Some(win) = &self.win
                    && self.animating()
                {
                    win.window.request_redraw();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(win) = &self.win else { return };
        let settle_at = self.motion.last_motion + SETTLE + Duration::from_millis(5);
        if win.scene_key.is_some_and(|k| k.proxy) {
            // The proxy is showing: come back for the full mesh once the camera has settled.
            if Instant::now() >= settle_at {
                win.window.request_redraw();
            } else {
                event_loop.set_control_flow(ControlFlow::WaitUntil(settle_at));
                return;
            }
        }
        let doc = &self.viewer.doc;
        if doc.busy() || doc.display.turntable || doc.anim.playing() {
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
