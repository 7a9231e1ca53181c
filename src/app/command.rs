//! Commands: everything that changes the viewer, as values. The panel
//! returns them, the workers' results arrive as them, and
//! [`Viewer::apply`] is the one place that carries them out (the pattern of
//! egui's demo app, `wrap_app.rs`: UI code never mutates the world).

use super::Viewer;
use super::display::Display;
use super::doc::{MAX_LEVEL, Problem, Request};
use super::jobs::Finished;
use super::model::Curve;
use crate::Error;
use crate::anim::tweak::Tweak;
use crate::render::export::{ExportStyle, ExportTarget};
use glam::{Vec2, Vec3};
use std::path::PathBuf;

/// One change to the viewer.
#[must_use = "a command does nothing until `Viewer::apply` carries it out"]
pub(crate) enum Command {
    /// Back to the built-in tetrahedron.
    OpenBuiltin,
    /// Open a model or curve file (repaired when repair-on-open is set).
    Open(PathBuf),
    /// Open a model given as bytes (a file picked or dropped on the page, a
    /// fetched URL), `name`'s extension choosing the format.
    #[cfg_attr(not(target_arch = "wasm32"), allow(dead_code, reason = "the page's way in; tested on the desktop"))]
    OpenBytes {
        /// The file's name.
        name: String,
        /// Its content.
        bytes: std::sync::Arc<[u8]>,
    },
    /// Open a model with repair (after it failed without).
    RepairAndOpen(super::jobs::Input),
    /// Repair every file opened from now on.
    SetRepairOnOpen(bool),
    /// New segment count or construction parameter of the shown curve.
    EditCurve(Curve),
    /// Back from the curve to the mesh.
    CloseCurve,
    /// Subdivide as asked (scheme, level, options).
    Subdivide(Request),
    /// Set the modified butterfly's tension without subdividing yet (while its slider is dragged).
    SetTension(f32),
    /// One level more (refused with the reason past the memory limit).
    LevelUp,
    /// One level less.
    LevelDown,
    /// New display options.
    SetDisplay(Display),
    /// Taubin-smooth the control mesh this many steps.
    Smooth(u32),
    /// Back to the control mesh as loaded.
    Revert,
    /// Pick the control-mesh edge under a ray (clears the pick when it misses).
    Pick {
        /// Ray origin (world).
        origin: Vec3,
        /// Unit ray direction.
        dir: Vec3,
    },
    /// Pick the point of the surface under a ray (clears it when it misses).
    PickSurface(super::probe::Ray),
    /// Forget the picked point.
    ClearSurfacePick,
    /// Set the sharpness of the control edge opposite `corner` (0 smooth,
    /// 10 infinitely sharp).
    SetSharpness {
        /// A corner facing the edge.
        corner: u32,
        /// Its new sharpness.
        sharpness: f32,
    },
    /// Make every control edge sharper than this dihedral angle (degrees)
    /// infinitely sharp, on top of the file's own tags.
    AutoCrease(f32),
    /// Make every control edge and vertex smooth.
    ClearCreases,
    /// Save the control mesh (OBJ or .ct by extension, with its tags).
    SaveControl(PathBuf),
    /// Flip the picked edge.
    FlipPicked,
    /// Split the picked edge at its midpoint.
    SplitPicked,
    /// Punch a hole at the face of the picked edge (its polygon, for a
    /// file of polygons), or fill it if it is one.
    ToggleHolePicked,
    /// Play or pause (starting the animation mode when it is off).
    TogglePlay,
    /// Pause and step this many frames.
    Step(i64),
    /// Leave the animation mode.
    StopAnimation,
    /// New path refinement (rebuilds a running animation).
    SetPathRefinement {
        /// Refinement count n.
        refine: u32,
        /// Tweak.
        tweak: Tweak,
    },
    /// Loop the playback or not.
    SetLooping(bool),
    /// Evaluate animation frames on the GPU (where it computes) or the CPU.
    SetGpuEval(bool),
    /// Playback rate.
    SetFps(f32),
    /// Jump to a frame.
    SetFrame(usize),
    /// Export the animation.
    Export(ExportTarget, ExportStyle),
    /// Cancel a running export.
    CancelExport,
    /// Hide the error.
    DismissError,
    /// Hide the notice.
    DismissNotice,
    /// Orbit the camera by a mouse motion in pixels.
    Orbit(Vec2),
    /// Pan the camera by a mouse motion in pixels, in a viewport `height` pixels tall.
    Pan {
        /// Motion in pixels.
        delta: Vec2,
        /// Viewport height in pixels.
        height: f32,
    },
    /// Zoom about the cursor.
    Zoom {
        /// Distance factor (< 1 zooms in).
        factor: f32,
        /// Cursor in the viewport's NDC.
        cursor: Vec2,
        /// The viewport's aspect.
        aspect: f32,
    },
    /// Orthographic or perspective projection.
    SetOrthographic(bool),
    /// Frame what is shown.
    Fit,
    /// Reset the camera direction and frame what is shown.
    ResetCamera,
    /// Save a screenshot of the next frame.
    Screenshot,
    /// How screenshots are taken (scale, transparency).
    SetShot(crate::render::Shot),
    /// A worker finished.
    Finished(Box<Finished>),
    /// What the GPU mirror found uploading the last frame.
    Gpu(Box<GpuReport>),
    /// The Inspect mode: on or off, its sub-mode, a pick, a step.
    Inspect(super::inspect::Action),
    /// Editing the cage: selection, grab, sharpness, undo, saving.
    Edit(super::edit::EditAction),
    /// The answer to closing or opening with unsaved changes.
    Answer(super::edit::Answer),
    /// The animation's keys: insert, set, delete, save.
    Key(super::keys::KeyAction),
}

/// What the GPU mirror's sync found that the document should know: the
/// mirror never writes the document; the window applies this as a command.
#[derive(Debug, Default)]
pub(crate) struct GpuReport {
    /// Whether a mesh was uploaded.
    pub(crate) uploaded: bool,
    /// Whether the adapter has compute passes.
    pub(crate) compute: bool,
    /// The plan whose compute passes are built, if any.
    pub(crate) gpu_ready: Option<u64>,
    /// Whether a new animation frame was shown.
    pub(crate) frame: bool,
    /// Whether that frame was evaluated on the GPU.
    pub(crate) on_gpu: bool,
    /// The GPU cannot evaluate the current plan (why): the CPU will.
    pub(crate) gpu_unavailable: Option<String>,
    /// Upload or evaluation errors.
    pub(crate) errors: Vec<crate::Error>,
}

impl Viewer {
    /// Carries out one command. A new control mesh that is not an edit (a
    /// new model, or reverting the edits) is framed.
    pub(crate) fn apply(&mut self, command: Command) {
        let control = self.doc.model.control.version();
        let (doc, view) = (&mut self.doc, &mut self.view);
        match command {
            Command::OpenBuiltin => doc.open_builtin(),
            Command::Open(path) => doc.open_asking(path.into()),
            Command::OpenBytes { name, bytes } => {
                doc.open_asking(super::jobs::Input { path: name.into(), bytes: Some(bytes) })
            }
            Command::RepairAndOpen(input) => doc.repair_and_open(input),
            Command::SetRepairOnOpen(on) => doc.repair_on_open = on,
            Command::EditCurve(curve) => doc.model.curve.set(Some(curve)),
            Command::CloseCurve => {
                doc.model.curve.set(None);
                view.reset = true;
            }
            Command::Subdivide(mut request) => {
                // a scheme picked in the panel refines every prim with it
                request.by_file &= request.scheme == doc.request.scheme;
                doc.request = request;
                doc.request_subdivision();
            }
            Command::SetTension(w) => doc.request.opts.tension = w,
            Command::LevelUp => self.level_up(),
            Command::LevelDown => self.level_down(),
            Command::SetDisplay(display) => {
                let reshade = doc.display.reshades_result(&display);
                doc.display = display;
                if reshade {
                    doc.reshade();
                }
            }
            Command::Smooth(steps) => doc.smooth(steps),
            Command::Revert => doc.revert(),
            Command::Pick { origin, dir } => {
                let picked = crate::mesh::pick::pick_edge(&doc.model.control.mesh, origin, dir);
                doc.model.picked.set(picked);
                if let (Some(c), true) = (picked, doc.display.click_creases) {
                    doc.toggle_crease(c);
                }
            }
            Command::PickSurface(ray) => doc.pick_surface(ray),
            Command::ClearSurfacePick => doc.model.probe = None,
            Command::SetSharpness { corner, sharpness } => doc.set_sharpness(corner, sharpness),
            Command::AutoCrease(degrees) => doc.auto_crease(degrees),
            Command::ClearCreases => doc.set_control_tags(&crate::mesh::Tags::default()),
            Command::SaveControl(path) => doc.save_control(&path),
            Command::FlipPicked => doc.flip_picked(),
            Command::SplitPicked => doc.split_picked(),
            Command::ToggleHolePicked => doc.toggle_hole_picked(),
            Command::TogglePlay => self.toggle_play(),
            Command::Step(frames) => self.step(frames),
            Command::StopAnimation => {
                doc.stop_animation();
                // the control mesh is shown unanimated again, framed like a new one
                view.fit |= doc.model.original.is_none();
            }
            Command::SetPathRefinement { refine, tweak } => {
                (doc.anim.refine, doc.anim.tweak) = (refine, tweak);
                if doc.anim.active {
                    doc.request_animation();
                }
            }
            Command::SetLooping(on) => self.with_clock(|c| c.looping = on),
            Command::SetGpuEval(on) => doc.anim.gpu_eval = on,
            Command::Gpu(report) => doc.take_gpu_report(*report),
            Command::SetFps(fps) => self.with_clock(|c| c.fps = fps),
            Command::SetFrame(f) => self.with_clock(|c| c.set_frame(f)),
            Command::Export(target, style) => doc.export(target, style),
            Command::CancelExport => doc.jobs.cancel_export(),
            Command::DismissError => doc.status.error = None,
            Command::DismissNotice => doc.status.notice = None,
            Command::Finished(finished) => self.finished(*finished),
            Command::Inspect(action) => doc.inspect(action),
            Command::Edit(action) => doc.edit(action),
            Command::Answer(answer) => self.answer(answer),
            Command::Key(action) => doc.key(action),
            camera => self.apply_camera(camera),
        }
        if self.doc.model.control.version() != control && self.doc.model.original.is_none() {
            self.view.fit = true;
        }
    }

    fn apply_camera(&mut self, command: Command) {
        let view = &mut self.view;
        match command {
            Command::Orbit(delta) => view.camera.orbit(delta),
            Command::Pan { delta, height } => view.camera.pan(delta, height),
            Command::Zoom { factor, cursor, aspect } => view.camera.zoom_to(factor, cursor, aspect),
            Command::SetOrthographic(on) => view.camera.orthographic = on,
            Command::Fit => view.fit = true,
            Command::ResetCamera => view.reset = true,
            Command::Screenshot => view.screenshot = true,
            Command::SetShot(shot) => view.shot = shot,
            _ => unreachable!("Viewer::apply handles every other command"),
        }
    }

    /// Goes on with what waited for the answer about unsaved changes.
    fn answer(&mut self, answer: super::edit::Answer) {
        let Some(pending) = self.doc.edit.pending.take() else { return };
        if !self.doc.answer(answer) {
            return;
        }
        match pending {
            super::edit::Pending::Close => self.view.quit = true,
            super::edit::Pending::Open(path) => self.doc.open(path),
        }
    }

    fn finished(&mut self, finished: Finished) {
        let had_curve = self.doc.model.curve.is_some();
        self.doc.adopt_finished(finished);
        if !had_curve && self.doc.model.curve.is_some() {
            self.view.fit_curve = true;
        }
    }

    fn level_up(&mut self) {
        let doc = &mut self.doc;
        if doc.request.level < doc.max_level() {
            doc.request.level += 1;
            doc.request_subdivision();
        } else {
            let why = doc
                .level_refusal(doc.request.level + 1)
                .unwrap_or_else(|| Error::Usage(format!("level {MAX_LEVEL} is the highest offered")));
            doc.fail(Problem::Other(why));
        }
    }

    fn level_down(&mut self) {
        if self.doc.request.level > 0 {
            self.doc.request.level -= 1;
            self.doc.request_subdivision();
        }
    }

    fn toggle_play(&mut self) {
        let anim = &mut self.doc.anim;
        match &mut anim.playback {
            Some(p) => p.clock.playing = !p.clock.playing,
            None if !anim.active => self.doc.request_animation(),
            None => {}
        }
    }

    fn step(&mut self, frames: i64) {
        let anim = &mut self.doc.anim;
        match &mut anim.playback {
            Some(p) => {
                p.clock.playing = false;
                p.clock.step(frames);
            }
            None if !anim.active => self.doc.request_animation(),
            None => {}
        }
    }

    fn with_clock(&mut self, f: impl FnOnce(&mut crate::anim::player::Clock)) {
        if let Some(p) = &mut self.doc.anim.playback {
            f(&mut p.clock);
        }
    }
}
