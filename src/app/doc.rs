//! The viewer's document: the model, how it is displayed, the animation, the
//! worker jobs, the subdivision asked for, and the status line.
//!
//! The document changes only through [`super::command::Command`]s (the panel's
//! and the workers' alike) that [`super::Viewer::apply`] carries out by
//! calling the operations below. An error leaves the current model untouched
//! and is shown in the panel ([`Status`]).

use super::animation::Animation;
use super::display::Display;
use super::jobs::{AnimationJob, Finished, Jobs, Opened, Subdivided, SubdivisionJob};
use super::model::{Curve, Made, Model, Shown};
use crate::anim::paths::Paths;
use crate::mem::default_memory_limit;
use crate::mesh::edit::EditError;
use crate::mesh::options::ShapeOptions;
use crate::mesh::sharpness::{CreaseTag, INFINITE, Tags};
use crate::render::export::{ExportStyle, ExportTarget};
use crate::subdiv::ControlCounts;
use crate::{Error, Mesh, Options, Scheme, bundled};
use std::path::PathBuf;
use std::sync::Arc;

/// Highest level offered in the panel (further limited by memory).
pub(crate) const MAX_LEVEL: u32 = 10;

/// Name of the model built into the binary.
pub(crate) const BUILTIN_NAME: &str = "tetrahedron (built in)";
/// Where the built-in model's paths come from.
pub(crate) const BUILTIN_PATHS: &str = "bundled:tetrahedron.paths";

/// The subdivision asked for (the shown one may still be on its way).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Request {
    /// Scheme.
    pub(crate) scheme: Scheme,
    /// Level.
    pub(crate) level: u32,
    /// Scheme options (Loop beta, tension).
    pub(crate) opts: Options,
    /// Memory limit for levels.
    pub(crate) limit: Option<u64>,
    /// Whether each prim of the model is refined by the scheme and options
    /// its file states (a USD stage's `subdivisionScheme`, `none`
    /// included) rather than by `scheme`: set when a file states a scheme
    /// and none was pinned, cleared when the panel picks one.
    pub(crate) by_file: bool,
}

/// An error shown in the panel, by what the viewer was doing.
#[derive(Debug, thiserror::Error)]
pub(crate) enum Problem {
    /// Opening a file failed.
    #[error("could not open: {0}")]
    Open(Error),
    /// Building the animation failed.
    #[error("animation: {0}")]
    Animation(Error),
    /// Exporting the animation failed (or was cancelled).
    #[error("export: {0}")]
    Export(Error),
    /// A colouring failed (the displacement, a curvature's evaluation).
    #[error("colouring: {0}")]
    Coloring(Error),
    /// The picked edge cannot be flipped.
    #[error("flip: {0}")]
    Flip(EditError),
    /// Anything else (a refused level, a subdivision, the GPU, a screenshot).
    #[error(transparent)]
    Other(#[from] Error),
}

impl Problem {
    /// The error behind it (a refused flip is a usage error).
    pub(crate) fn into_error(self) -> Error {
        match self {
            Problem::Open(e) | Problem::Animation(e) | Problem::Export(e) | Problem::Coloring(e) => e,
            Problem::Other(e) => e,
            flip @ Problem::Flip(_) => Error::Usage(flip.to_string()),
        }
    }
}

/// What the panel reports besides the model.
#[derive(Debug, Default)]
pub(crate) struct Status {
    /// Last error, shown until dismissed.
    pub(crate) error: Option<Problem>,
    /// Last notice (export finished...).
    pub(crate) notice: Option<String>,
    /// The file whose opening failed last (offered for "Repair and open").
    pub(crate) failed: Option<super::jobs::Input>,
}

/// Everything the panel and the renderer read.
pub(crate) struct Doc {
    /// The control mesh, its subdivision and what is shown of them.
    pub(crate) model: Model,
    /// Display options.
    pub(crate) display: Display,
    /// The animation mode.
    pub(crate) anim: Animation,
    /// Worker threads.
    pub(crate) jobs: Jobs,
    /// The subdivision asked for.
    pub(crate) request: Request,
    /// Errors and notices.
    pub(crate) status: Status,
    /// Repair meshes when opening them (split non-manifold elements, orient, drop degenerate faces).
    pub(crate) repair_on_open: bool,
    /// The time code a stage's sampled points are read at (the command
    /// line's `--time`; `None`: where the stage opens).
    pub(crate) read_time: Option<f64>,
    /// The Inspect mode: picked corner, stencil, split.
    pub(crate) inspect: super::inspect::Inspect,
    /// The shape options the command line gave, which a file's option
    /// tags do not replace (see [`Doc::adopt_file_options`]).
    pub(crate) pinned: ShapeOptions,
    /// Editing the cage: selection, grab, history, saving, recovery.
    pub(crate) edit: super::edit::Edit,
}

/// The triangles of the polygon triangle `t` belongs to: `t` and those
/// across hidden diagonals (a fanned polygon's), transitively.
fn polygon_of(ct: &crate::CornerTable, t: u32) -> Vec<u32> {
    let hidden = |c: u32| ct.generations().is_some_and(|g| g.corner(c) == crate::mesh::Generations::HIDDEN);
    let mut face = vec![t];
    let mut k = 0;
    while k < face.len() {
        let f = face[k];
        for c in 3 * f..3 * f + 3 {
            if let Some(o) = ct.o(c).filter(|_| hidden(c))
                && !face.contains(&(o / 3))
            {
                face.push(o / 3);
            }
        }
        k += 1;
    }
    face
}

fn builtin_tetrahedron() -> (Mesh, Paths) {
    // Both are compiled in and parsed by bundled's unit test; a failure here
    // is a build error in disguise.
    bundled::tetrahedron().expect("the bundled tetrahedron and its paths are valid")
}

impl Default for Doc {
    fn default() -> Self {
        Doc::new()
    }
}

impl Doc {
    /// A document on the built-in tetrahedron.
    pub(crate) fn new() -> Doc {
        let (mesh, paths) = builtin_tetrahedron();
        Doc {
            model: Model::new(BUILTIN_NAME.into(), mesh),
            display: Display::default(),
            anim: Animation::new(paths, BUILTIN_PATHS.into()),
            jobs: Jobs::new(),
            request: Request {
                scheme: Scheme::Loop,
                level: 0,
                opts: Options::default(),
                limit: default_memory_limit(),
                by_file: false,
            },
            status: Status::default(),
            repair_on_open: false,
            read_time: None,
            inspect: Default::default(),
            pinned: ShapeOptions::default(),
            edit: Default::default(),
        }
    }

    /// A model's option tags: each one the file states becomes the asked
    /// subdivision's (the panel shows it) unless the command line pinned
    /// it; what the file leaves unsaid stays as it was.
    pub(crate) fn adopt_file_options(&mut self, file: ShapeOptions) {
        let o = file.overridden_by(self.pinned);
        // a scheme the file states, unless the command line pinned one
        self.request.by_file = file.scheme.is_some() && self.pinned.scheme.is_none();
        if let Some(s) = file.scheme.filter(|_| self.request.by_file).and_then(Scheme::of_file) {
            self.request.scheme = s;
        }
        self.request.opts = self.request.opts.with_file(o);
    }

    /// Whether any task is running.
    pub(crate) fn busy(&self) -> bool {
        self.jobs.busy()
    }

    /// Shows an error in the panel.
    pub(crate) fn fail(&mut self, problem: Problem) {
        self.status.error = Some(problem);
    }

    /// What the GPU mirror found: whether the adapter computes, for which
    /// plan its compute passes are built, whether the frame was evaluated
    /// there, and its errors (a plan it cannot take turns GPU evaluation
    /// off, with a notice).
    pub(crate) fn take_gpu_report(&mut self, r: super::command::GpuReport) {
        self.anim.gpu_compute = Some(r.compute);
        self.anim.gpu_ready = r.gpu_ready;
        if r.frame {
            self.anim.on_gpu = r.on_gpu;
        }
        if let Some(why) = r.gpu_unavailable {
            self.status.notice = Some(format!("GPU evaluation unavailable ({why}); evaluating on the CPU"));
            self.anim.gpu_eval = false;
        }
        if let Some(e) = r.errors.into_iter().last() {
            self.fail(Problem::Other(e));
        }
    }

    /// Faces of level `level` of the current control mesh with the chosen
    /// scheme: triangles, or the polygon schemes' quads.
    pub(crate) fn predicted_faces(&self, level: u32) -> u64 {
        ControlCounts::of_topology(&self.model.control.topo).faces_at(self.request.scheme, level)
    }

    /// Why `level` cannot be shown ([`Error::TooLarge`]), if it cannot.
    pub(crate) fn level_refusal(&self, level: u32) -> Option<Error> {
        let counts = ControlCounts::of_topology(&self.model.control.topo);
        counts.check(self.request.scheme, level, self.request.limit).err()
    }

    /// Highest level that fits in memory (at most [`MAX_LEVEL`]).
    pub(crate) fn max_level(&self) -> u32 {
        (0..=MAX_LEVEL).take_while(|&l| self.level_refusal(l).is_none()).last().unwrap_or(0)
    }

    /// Opens a model file on a worker thread (repairing it when
    /// [`Doc::repair_on_open`] is set).
    pub(crate) fn open(&mut self, input: super::jobs::Input) {
        self.jobs.load(input, self.repair_on_open, self.read_time);
    }

    /// Opens a file with repair, forgetting the failure that offered it.
    pub(crate) fn repair_and_open(&mut self, input: super::jobs::Input) {
        self.status.error = None;
        self.status.failed = None;
        self.jobs.load(input, true, self.read_time);
    }

    /// Makes `mesh` (read from `path`) the control mesh, at level 0 until
    /// the level asked for arrives.
    pub(crate) fn adopt(&mut self, path: PathBuf, mesh: Mesh, paths: Option<Paths>) {
        let mesh = Arc::new(mesh);
        let m = &mut self.model;
        m.name = match crate::bundled::from_arg(&path) {
            Some(bundled) => bundled.file_name.to_string(),
            None => path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned()),
        };
        m.control.set(Shown::new(mesh.clone()));
        m.raw = (*m.control).clone();
        m.attrs.refined = m.attrs.file.clone();
        m.original = None;
        m.precise = None;
        m.picked.set(None);
        m.probe = None;
        m.proxy = None;
        m.adaptive = Default::default();
        m.made = Made { opts: self.request.opts, scheme: m.made.scheme, ..Made::default() };
        match paths {
            Some(p) => {
                self.anim.paths = p;
                self.anim.paths_source = bundled::paths_for(&path).map(|p| p.describe()).unwrap_or_default();
            }
            None => self.anim.generate_paths(&mesh),
        }
        m.path = Some(path);
        self.edit.reset();
        self.anim.playback = None;
        self.reshade();
        // Keep the level when it fits; otherwise the largest that does, saying so.
        let fits = self.max_level();
        if self.request.level > fits {
            let why = self.level_refusal(self.request.level).map_or_else(String::new, |e| format!(" ({e})"));
            self.status.notice = Some(format!("level {} does not fit{why}: level {fits} shown", self.request.level));
            self.request.level = fits;
        }
        if self.request.level > 0 || self.anim.active {
            self.request_subdivision();
        }
    }

    /// Goes back to the built-in tetrahedron.
    pub(crate) fn open_builtin(&mut self) {
        let (mesh, paths) = builtin_tetrahedron();
        self.model.attrs.file = Default::default();
        self.jobs.cancel_load();
        self.adopt(PathBuf::from("tetrahedron.obj"), mesh, Some(paths));
        self.model.path = None;
        self.model.name = BUILTIN_NAME.into();
        self.anim.paths_source = BUILTIN_PATHS.into();
        self.look_for_recovery();
    }

    /// Requests the subdivision of [`Doc::request`] (superseding any running one).
    pub(crate) fn request_subdivision(&mut self) {
        if self.anim.active {
            self.request_animation();
        }
        if let Some(e) = self.level_refusal(self.request.level) {
            self.fail(e.into());
            self.request.level = self.model.made.level.min(self.max_level());
            self.jobs.cancel_subdivision();
            return;
        }
        let Request { scheme, level, opts, by_file, .. } = self.request;
        let (control, attrs) = ((*self.model.control).clone(), self.model.attrs.file.clone());
        self.jobs.subdivide(SubdivisionJob { control, attrs, scheme, level, opts, by_file });
    }

    /// What an animation of the current model and request is made of.
    pub(crate) fn animation_job(&self) -> AnimationJob {
        AnimationJob {
            mesh: self.model.control.mesh.clone(),
            paths: self.anim.paths.clone(),
            tweak: self.anim.tweak,
            refine: self.anim.refine,
            scheme: self.request.scheme,
            level: self.request.level,
            opts: self.request.opts,
        }
    }

    /// Starts the animation mode (building the plan on a worker thread).
    pub(crate) fn request_animation(&mut self) {
        self.anim.active = true;
        if let Some(e) = self.level_refusal(self.request.level) {
            self.jobs.cancel_animation();
            self.fail(e.into());
            return;
        }
        self.jobs.animate(self.animation_job());
    }

    /// Leaves the animation mode (the static result is shown again).
    pub(crate) fn stop_animation(&mut self) {
        self.anim.stop();
        self.jobs.cancel_animation();
    }

    /// Exports the animation on a worker thread with its own GPU device.
    pub(crate) fn export(&mut self, target: ExportTarget, style: ExportStyle) {
        self.jobs.export(self.animation_job(), target, style);
    }

    /// Rebuilds the shown result from the subdivision output and the display
    /// options (limit snapping, normals, colours).
    /// A curvature colouring on a scheme without one shows the result
    /// uncoloured, saying why on the status line (a notice, not an error).
    pub(crate) fn reshade(&mut self) {
        self.reshade_rows(None);
    }

    /// [`Doc::reshade`] after the subdivision output changed only at
    /// `rows` (see [`super::model::Model::reshade`]).
    pub(crate) fn reshade_rows(&mut self, rows: Option<Arc<[u32]>>) {
        if let Some(e) = self.model.reshade(&self.display, rows) {
            let curvature = matches!(self.display.coloring, super::display::Coloring::Curvature(_));
            match crate::subdiv::eval::color::check_scheme(self.model.made.scheme) {
                Err(refusal) if curvature => self.status.notice = Some(refusal.to_string()),
                _ => self.fail(Problem::Coloring(e)),
            }
        }
        // the drawn surface changed: the picked point is picked again
        self.repick();
    }
}

/// Edits of the control mesh.
impl Doc {
    /// Replaces the control mesh by an edited version (smoothing, edge
    /// operations), keeping the original for [`Doc::revert`], and
    /// re-subdivides; one step of the history, called `what`.
    pub(crate) fn replace_control(&mut self, what: &str, mesh: Mesh) {
        let before = self.model.control.mesh.clone();
        let after = Arc::new(mesh);
        self.install_control(after.clone());
        self.record(what, before, after);
        self.after_change();
    }

    /// Makes `mesh` the control mesh (an edit, or its undoing) and
    /// re-subdivides.
    pub(crate) fn install_control(&mut self, mesh: Arc<Mesh>) {
        let m = &mut self.model;
        if m.original.is_none() {
            m.original = Some(m.control.mesh.clone());
        }
        self.edit.topology += 1;
        // Edits that change the counts (edge splits) leave the file's attributes behind.
        let file = &mut m.attrs.file;
        if file.colors.as_ref().is_some_and(|c| c.len() != mesh.positions.len()) {
            file.colors = None;
        }
        if file.uv.as_ref().is_some_and(|u| u.len() != mesh.ct.v_table().len()) {
            file.uv = None;
        }
        m.attrs.refined = m.attrs.file.clone();
        if self.anim.paths.vertex_count() != mesh.positions.len() {
            self.anim.generate_paths(&mesh);
        }
        m.control.set(Shown::new(mesh));
        m.raw = (*m.control).clone();
        m.made.level = 0;
        m.proxy = None;
        m.picked.set(None);
        self.anim.playback = None;
        self.reshade();
        if self.request.level > 0 || self.anim.active {
            self.request_subdivision();
        }
    }

    /// Taubin lambda/mu smoothing of the control mesh.
    pub(crate) fn smooth(&mut self, steps: u32) {
        use crate::mesh::smooth::{TAUBIN_LAMBDA, TAUBIN_MU, taubin};
        let control = &self.model.control.mesh;
        let positions = taubin(control, steps, TAUBIN_LAMBDA, TAUBIN_MU);
        let ct = control.ct.clone();
        self.replace_control(&format!("smooth {steps} steps"), Mesh { ct, positions });
    }

    /// Back to the control mesh as loaded.
    pub(crate) fn revert(&mut self) {
        if let Some(m) = self.model.original.take() {
            self.replace_control("revert to the file", Arc::unwrap_or_clone(m));
            self.model.original = None;
        }
    }

    /// The control mesh with the sharpness `tags` give it (tags whose edge
    /// or vertex is gone are dropped), re-subdivided; the pick stays.
    pub(crate) fn set_control_tags(&mut self, tags: &crate::mesh::Tags) {
        let control = &self.model.control.mesh;
        let mut tags = tags.clone();
        tags.creases.retain(|t| control.ct.corner_opposite(t.v0, t.v1).is_some());
        tags.corners.retain(|t| (t.vertex as usize) < control.positions.len());
        let ct = match control.ct.clone().with_tags(&tags) {
            Ok(ct) => ct,
            Err(e) => return self.fail(Problem::Other(crate::Error::Invalid(e))),
        };
        let picked = *self.model.picked;
        let mesh = Mesh { ct, positions: control.positions.clone() };
        if let Some(mesh) = self.retag_surface(&tags, mesh) {
            self.replace_control("sharpness", mesh);
        }
        self.model.picked.set(picked);
    }

    /// The control mesh's tags with the edge opposite `c` at `sharpness`.
    pub(crate) fn set_sharpness(&mut self, c: u32, sharpness: f32) {
        let ct = &self.model.control.mesh.ct;
        if c as usize >= ct.num_corners() || ct.o(c).is_none() {
            return;
        }
        let (a, b) = (ct.vtx(crate::mesh::n(c)), ct.vtx(crate::mesh::p(c)));
        let mut tags = ct.sharpness().map(|s| s.to_tags(ct)).unwrap_or_default();
        tags.creases.retain(|t| (t.v0.min(t.v1), t.v0.max(t.v1)) != (a.min(b), a.max(b)));
        let sharpness = match crate::mesh::checked_sharpness(f64::from(sharpness)) {
            Ok(s) => s,
            Err(e) => return self.fail(Problem::Other(Error::Usage(format!("edge {a}-{b} has {e}")))),
        };
        tags.creases.push(CreaseTag { v0: a, v1: b, sharpness });
        self.set_control_tags(&tags);
    }

    /// Makes the edge opposite `c` infinitely sharp, or smooth if it was sharp.
    pub(crate) fn toggle_crease(&mut self, c: u32) {
        let ct = &self.model.control.mesh.ct;
        let sharp = ct.o(c).is_some() && ct.edge_sharpness(c) > 0.0;
        self.set_sharpness(c, if sharp { 0.0 } else { INFINITE });
    }

    /// The tags of the control mesh as loaded (before any edit) plus every
    /// edge sharper than `degrees` made infinitely sharp.
    pub(crate) fn auto_crease(&mut self, degrees: f32) {
        let m = &self.model;
        let loaded = m.original.as_deref().unwrap_or(&m.control.mesh);
        let file_tags = loaded.ct.sharpness().map(|s| s.to_tags(&loaded.ct)).unwrap_or_default();
        let control = &m.control.mesh;
        let auto =
            control.ct.clone().with_tags(&Tags::default()).map(|ct| ct.with_angle_creases(&control.positions, degrees));
        let mut tags = auto.ok().and_then(|ct| ct.sharpness().map(|s| s.to_tags(&ct))).unwrap_or_default();
        tags.creases.extend(file_tags.creases);
        tags.corners.extend(file_tags.corners);
        self.set_control_tags(&tags);
    }

    /// Writes the control mesh (its tags kept: OBJ `t crease`, .ct sections).
    pub(crate) fn save_control(&mut self, path: &std::path::Path) {
        match crate::io::save(path, &*self.model.control.mesh) {
            Ok(()) => self.status.notice = Some(format!("saved {}", path.display())),
            Err(e) => self.fail(Problem::Other(e)),
        }
    }

    /// Flips the picked edge of the control mesh.
    pub(crate) fn flip_picked(&mut self) {
        let Some(c) = *self.model.picked else { return };
        let mut m = (*self.model.control.mesh).clone();
        match crate::mesh::edit::flip_edge(&mut m.ct, c) {
            Ok(()) => self.replace_control("flip edge", m),
            Err(e) => self.fail(Problem::Flip(e)),
        }
    }

    /// Fills the hole beside the picked edge (a hole is not drawn, so the
    /// edge is picked on the face across it), or punches one at the face of
    /// the picked edge: every triangle of its polygon (joined across the
    /// hidden diagonals of a fanned polygon) stops being a hole, or becomes
    /// one. A hole's vertices keep shaping the rest, as OpenSubdiv's do.
    pub(crate) fn toggle_hole_picked(&mut self) {
        let Some(c) = *self.model.picked else { return };
        let ct = &self.model.control.mesh.ct;
        if c as usize >= ct.num_corners() {
            return;
        }
        let mut holes: Vec<u32> = ct.holes().to_vec();
        match self.model.hole_beside_pick() {
            Some(t) => {
                let face = polygon_of(ct, t);
                holes.retain(|t| !face.contains(t));
            }
            None => holes.extend(polygon_of(ct, c / 3)),
        }
        let mesh = &self.model.control.mesh;
        let picked = *self.model.picked;
        let after = Mesh { ct: mesh.ct.clone().with_holes(holes), positions: mesh.positions.clone() };
        self.replace_control("hole", after);
        self.model.picked.set(picked);
    }

    /// Splits the picked edge of the control mesh at its midpoint.
    pub(crate) fn split_picked(&mut self) {
        let Some(c) = *self.model.picked else { return };
        if c as usize >= self.model.control.mesh.ct.num_corners() {
            return;
        }
        let mut m = (*self.model.control.mesh).clone();
        crate::mesh::edit::split_edge(&mut m, c, 0.5);
        self.replace_control("split edge", m);
    }
}

/// Adopting what the workers send back.
impl Doc {
    /// Takes a finished task's result into the document.
    pub(crate) fn adopt_finished(&mut self, finished: Finished) {
        match finished {
            Finished::Loaded { input, result } => self.adopt_loaded(input, result),
            Finished::Curve(result) => self.adopt_curve(result),
            Finished::Subdivided(result) => match result {
                Ok(s) => self.adopt_subdivision(*s),
                Err(e) => {
                    self.fail(e.into());
                    self.request.level = self.model.made.level;
                }
            },
            Finished::Animated(_) if !self.anim.active => {}
            Finished::Animated(Ok(player)) => self.anim.adopt(player),
            Finished::Animated(Err(e)) => {
                self.fail(Problem::Animation(e));
                self.anim.active = false;
            }
            Finished::Exported(Ok((n, out))) => {
                self.status.notice = Some(format!("wrote {n} frames to {}", out.display()));
            }
            Finished::Exported(Err(e)) => self.fail(Problem::Export(e)),
            Finished::Inspected { shown, result } => self.adopt_inspected(shown, result),
            Finished::Tessellated(result) => self.adopt_tessellation(result),
        }
    }

    fn adopt_loaded(&mut self, input: super::jobs::Input, result: crate::Result<Opened>) {
        match result {
            Ok(o) => {
                self.status.failed = None;
                self.status.notice = o.report;
                self.adopt_file_options(o.attrs.options);
                self.model.attrs.file = o.attrs;
                self.adopt(o.path, o.mesh, o.paths);
                if let Some(n) = o.samples {
                    // the stage's own animation: its samples as they are
                    self.anim.paths_source = format!("the stage's {n} time samples");
                    self.anim.refine = 0;
                }
                self.model.precise = o.precise.map(|p| (self.model.control.mesh.clone(), Arc::new(p)));
                self.look_for_recovery();
            }
            Err(e) => {
                // Only a mesh-validity problem can be repaired; parse errors cannot.
                self.status.failed = matches!(e, Error::Mesh { .. }).then_some(input);
                self.fail(Problem::Open(e));
            }
        }
    }

    /// An inspector pick's answer: a stencil shows the cage it is drawn
    /// on; an error is the inspector's message, not the model's.
    fn adopt_inspected(&mut self, shown: Arc<Mesh>, result: crate::Result<super::inspect::Found>) {
        match result {
            Ok(found) => {
                self.display.control |= matches!(found, super::inspect::Found::Stencil(_));
                self.inspect.adopt(shown, found);
            }
            Err(e) => self.inspect.message = Some(e.to_string()),
        }
    }

    fn adopt_curve(&mut self, result: crate::Result<Curve>) {
        match result {
            Ok(curve) => {
                self.stop_animation();
                self.model.curve.set(Some(curve));
            }
            Err(e) => self.fail(Problem::Open(e)),
        }
    }

    fn adopt_subdivision(&mut self, s: Subdivided) {
        let m = &mut self.model;
        m.attrs.refined = s.attrs;
        m.raw = s.shown;
        m.proxy = s.proxy;
        let by_prim = s.by_prim;
        m.made = Made { level: s.level, scheme: s.scheme, opts: s.opts, stats: Some(s.stats), job_ms: s.ms, by_prim };
        self.adopt_refiner(s.refiner);
        self.reshade();
        self.edit_surface();
    }
}
