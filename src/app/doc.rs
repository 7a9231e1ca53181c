//! The viewer's document: the control mesh, its subdivision, the animation,
//! and the worker threads that compute them so the window never waits.
//!
//! Every long task (loading, subdividing, building an animation, exporting)
//! runs on its own thread and reports through a channel. Each kind of task
//! has a generation counter: a newer request supersedes an older one, whose
//! result is dropped, and a superseded subdivision stops after its current
//! level. An error leaves the current model untouched and is shown in the
//! panel.

use crate::anim::paths::Paths;
use crate::anim::player::{Animation, Clock};
use crate::anim::tweak::Tweak;
use crate::mesh::topology::{Topology, topology};
use crate::render::export::{ExportStyle, ExportTarget, export_animation};
use crate::subdiv::attributes::Attributes;
use crate::subdiv::{Stats, check_levels_fit, default_memory_limit, predict_faces, subdivide_with_progress};
use crate::{Mesh, Options, Result, Scheme, bundled};
use glam::Vec3;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::time::Instant;

/// Which normals shade the result.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum NormalMode {
    /// Area-weighted average of the face normals around each vertex.
    #[default]
    FanAverage,
    /// Exact normals of the Loop limit surface (tangent masks).
    LoopLimit,
    /// Butterfly tangent masks.
    Butterfly,
}

impl NormalMode {
    /// All modes, in menu order.
    pub const ALL: [NormalMode; 3] = [NormalMode::FanAverage, NormalMode::LoopLimit, NormalMode::Butterfly];
    /// Menu label.
    pub fn name(self) -> &'static str {
        match self {
            NormalMode::FanAverage => "fan-averaged",
            NormalMode::LoopLimit => "Loop limit",
            NormalMode::Butterfly => "butterfly masks",
        }
    }
}

/// Per-vertex colouring of the result.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Coloring {
    /// The material colour.
    #[default]
    None,
    /// The level that created each vertex ("shells").
    Shells,
    /// Distance from the control mesh's surface.
    Displacement,
    /// The colours of the file (`v x y z r g b`), refined with the scheme's weights.
    File,
    /// A checker texture through the file's texture coordinates (`vt`).
    Checker,
}

impl Coloring {
    /// All modes, in menu order.
    pub const ALL: [Coloring; 5] =
        [Coloring::None, Coloring::Shells, Coloring::Displacement, Coloring::File, Coloring::Checker];
    /// Menu label.
    pub fn name(self) -> &'static str {
        match self {
            Coloring::None => "none",
            Coloring::Shells => "level shells",
            Coloring::Displacement => "displacement from control",
            Coloring::File => "colours of the file",
            Coloring::Checker => "texture (checker through vt)",
        }
    }
}

impl std::str::FromStr for Coloring {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "" | "none" => Ok(Coloring::None),
            "shells" | "levels" => Ok(Coloring::Shells),
            "displacement" => Ok(Coloring::Displacement),
            "file" | "colors" | "colours" => Ok(Coloring::File),
            "checker" | "uv" | "texture" => Ok(Coloring::Checker),
            _ => Err(format!("unknown colouring '{s}' (none, shells, displacement, file, checker)")),
        }
    }
}

/// Largest proxy mesh (see [`Doc::proxy`]).
pub const PROXY_FACES: u64 = 150_000;

/// Highest level offered in the panel (further limited by memory).
pub const MAX_LEVEL: u32 = 10;

/// A mesh with its normals and counts, ready to upload. Cloning shares the
/// arrays.
#[derive(Clone)]
pub struct Shown {
    /// The mesh.
    pub mesh: Arc<Mesh>,
    /// Unit vertex normals (fan-averaged unless a display option chose others).
    pub normals: Arc<Vec<Vec3>>,
    /// V/E/F, genus, boundary loops...
    pub topo: Topology,
}

impl Shown {
    /// Computes the fan-averaged normals and the topology (worker threads do this).
    fn new(mesh: Arc<Mesh>) -> Shown {
        let normals = Arc::new(mesh.vertex_normals());
        let topo = topology(&mesh.ct);
        Shown { mesh, normals, topo }
    }
}

/// A planar Bezier curve opened from a `.bzc` file.
#[derive(Clone, Debug)]
pub struct Curve {
    /// File name.
    pub name: String,
    /// Control points.
    pub control: Vec<glam::Vec2>,
    /// Polyline segments drawn.
    pub segments: usize,
    /// Parameter of the de Casteljau construction shown.
    pub t: f32,
    /// Show the construction at `t`.
    pub construction: bool,
}

impl Curve {
    /// The evaluated polyline (de Casteljau at `segments + 1` parameters), in the z = 0 plane.
    pub fn polyline(&self) -> Vec<Vec3> {
        crate::io::bezier::curve_polyline(&self.control, self.segments).iter().map(|p| p.extend(0.0)).collect()
    }
    /// The intermediate polygons of de Casteljau at `t`, as segments, ending with the curve point.
    pub fn construction_segments(&self) -> (Vec<Vec3>, Option<Vec3>) {
        let mut level: Vec<glam::Vec2> = self.control.clone();
        let mut segs = Vec::new();
        while level.len() > 1 {
            level = crate::io::bezier::de_casteljau_step(&level, self.t);
            for w in level.windows(2) {
                segs.push(w[0].extend(0.0));
                segs.push(w[1].extend(0.0));
            }
        }
        (segs, level.first().map(|p| p.extend(0.0)))
    }
}

/// A finished subdivision: the result, its proxy, phase times, job time and
/// the refined attributes.
type Subdivided = (Shown, Option<Shown>, Stats, f64, Attributes);

/// A loaded model: its path, mesh, matching paths, repair report and attributes.
type Opened = (PathBuf, Mesh, Option<Paths>, Option<String>, Attributes);

enum Done {
    Loaded { ticket: u64, result: Result<Opened>, path: PathBuf },
    LoadedCurve { ticket: u64, result: Result<Curve> },
    Subdivided { ticket: u64, result: Result<Subdivided>, level: u32 },
    Animated { ticket: u64, result: Result<Animation> },
    Exported { result: Result<(usize, PathBuf)> },
}

/// A running task shown in the panel.
#[derive(Clone)]
pub struct Busy {
    /// What is running.
    pub what: String,
    /// Units done (levels, frames).
    pub done: Arc<AtomicUsize>,
    /// Units in all.
    pub total: usize,
    /// Started at.
    pub since: Instant,
}

/// The animation state of the document.
pub struct Anim {
    /// Evaluator (stencil plan and refined paths).
    pub player: Animation,
    /// Frame clock.
    pub clock: Clock,
    /// Frame last evaluated (None: needs evaluation).
    pub shown_frame: Option<usize>,
}

/// Everything the panel and the renderer read.
pub struct Doc {
    /// Display name of the model.
    pub name: String,
    /// File it came from (None: built in).
    pub path: Option<PathBuf>,
    /// The control mesh.
    pub control: Shown,
    /// The subdivided mesh shown (the control mesh at level 0), after the
    /// display options (limit snapping, normal mode) are applied to `raw`.
    pub result: Shown,
    /// The subdivision output itself, with fan normals and topology from the worker.
    pub raw: Shown,
    /// Shading normals.
    pub normal_mode: NormalMode,
    /// Show the Loop limit positions instead of the level's points.
    pub snap_limit: bool,
    /// Per-vertex colouring.
    pub coloring: Coloring,
    /// Vertex colours and corner texture coordinates of the control mesh, from its file.
    pub file_attrs: Attributes,
    /// `file_attrs` refined to `raw`.
    pub raw_attrs: Attributes,
    /// Colours for `result` (with `coloring`), linear RGB.
    pub result_colors: Option<Vec<Vec3>>,
    /// Largest value behind the colours (levels, or a distance), for the legend.
    pub color_max: f32,
    /// The control mesh as loaded, before smoothing or edge edits.
    pub original: Option<Arc<Mesh>>,
    /// A picked control-mesh corner: the edge opposite it is selected.
    pub picked: Option<u32>,
    /// A Bezier curve shown instead of the mesh.
    pub curve: Option<Curve>,
    /// Set when `curve` changed (upload).
    pub curve_changed: bool,
    /// A lower level of the same subdivision (at most [`PROXY_FACES`]
    /// triangles), drawn instead of a big `result` while the camera moves.
    pub proxy: Option<Shown>,
    /// Level of `result`.
    pub result_level: u32,
    /// Scheme of `result`.
    pub result_scheme: Scheme,
    /// Phase times of the last subdivision.
    pub stats: Option<Stats>,
    /// Wall time of the last subdivision job, ms.
    pub job_ms: f64,
    /// Requested scheme.
    pub scheme: Scheme,
    /// Requested level.
    pub level: u32,
    /// Scheme options (Loop beta, tension).
    pub opts: Options,
    /// Memory limit for levels.
    pub limit: Option<u64>,
    /// Animation paths for the control mesh (file or generated).
    pub paths: Paths,
    /// Where the paths came from.
    pub paths_source: String,
    /// Path refinement count n (K * 2^n frames).
    pub refine: u32,
    /// Path tweak.
    pub tweak: Tweak,
    /// The animation when active.
    pub anim: Option<Anim>,
    /// Whether the animation mode is on (it may still be building).
    pub animating: bool,
    /// Last error, shown until dismissed.
    pub error: Option<String>,
    /// Last notice (export finished...).
    pub notice: Option<String>,
    /// Repair meshes when opening them (split non-manifold elements, orient, drop degenerate faces).
    pub repair_on_open: bool,
    /// The file whose opening failed last (offered for "Repair and open").
    pub failed: Option<PathBuf>,
    /// Set when `control` changed (upload, refit the camera).
    pub control_changed: bool,
    /// Set when `result` changed (upload).
    pub result_changed: bool,
    load_gen: Arc<AtomicU64>,
    sub_gen: Arc<AtomicU64>,
    anim_gen: Arc<AtomicU64>,
    tx: Sender<Done>,
    rx: Receiver<Done>,
    /// Running load.
    pub loading: Option<Busy>,
    /// Running subdivision.
    pub subdividing: Option<Busy>,
    /// Running animation build.
    pub building: Option<Busy>,
    /// Running export.
    pub exporting: Option<Busy>,
    export_cancel: Arc<AtomicU64>,
}

fn builtin_tetrahedron() -> (Mesh, Paths) {
    // Both are compiled in and parsed by bundled's unit test; a failure here
    // is a build error in disguise.
    bundled::tetrahedron().expect("the bundled tetrahedron and its paths are valid")
}

pub use crate::bundled::paths_for;

impl Doc {
    /// A document on the built-in tetrahedron.
    pub fn new() -> Doc {
        let (mesh, paths) = builtin_tetrahedron();
        let (tx, rx) = channel();
        let shown = Shown::new(Arc::new(mesh));
        Doc {
            name: "tetrahedron (built in)".into(),
            path: None,
            control: shown.clone(),
            result: shown.clone(),
            raw: shown,
            normal_mode: NormalMode::default(),
            snap_limit: false,
            coloring: Coloring::default(),
            file_attrs: Attributes::default(),
            raw_attrs: Attributes::default(),
            result_colors: None,
            color_max: 0.0,
            original: None,
            picked: None,
            curve: None,
            curve_changed: false,
            proxy: None,
            result_level: 0,
            result_scheme: Scheme::Loop,
            stats: None,
            job_ms: 0.0,
            scheme: Scheme::Loop,
            level: 0,
            opts: Options::default(),
            limit: default_memory_limit(),
            paths,
            paths_source: "bundled:tetrahedron.paths".into(),
            refine: 5,
            tweak: Tweak::Jarek,
            anim: None,
            animating: false,
            error: None,
            notice: None,
            repair_on_open: false,
            failed: None,
            control_changed: true,
            result_changed: true,
            load_gen: Default::default(),
            sub_gen: Default::default(),
            anim_gen: Default::default(),
            tx,
            rx,
            loading: None,
            subdividing: None,
            building: None,
            exporting: None,
            export_cancel: Default::default(),
        }
    }

    /// Whether any task is running.
    pub fn busy(&self) -> bool {
        self.loading.is_some() || self.subdividing.is_some() || self.building.is_some() || self.exporting.is_some()
    }

    /// Triangles of level `level` of the current control mesh.
    pub fn predicted_faces(&self, level: u32) -> u64 {
        predict_faces(&self.control.mesh.ct, level)
    }

    /// Why `level` cannot be shown (memory), if it cannot.
    pub fn level_refusal(&self, level: u32) -> Option<String> {
        check_levels_fit(&self.control.mesh.ct, 0, level, self.limit).err().map(|e| e.to_string())
    }

    /// Highest level that fits in memory (at most [`MAX_LEVEL`]).
    pub fn max_level(&self) -> u32 {
        (0..=MAX_LEVEL).take_while(|&l| self.level_refusal(l).is_none()).last().unwrap_or(0)
    }

    /// Opens a model file on a worker thread (repairing it when
    /// [`Doc::repair_on_open`] is set).
    pub fn open(&mut self, path: PathBuf) {
        self.open_with(path, self.repair_on_open);
    }

    /// Opens a model file on a worker thread, repairing it or not.
    pub fn open_with(&mut self, path: PathBuf, repair: bool) {
        let ticket = self.load_gen.fetch_add(1, Ordering::SeqCst) + 1;
        let tx = self.tx.clone();
        self.loading = Some(Busy {
            what: format!("loading {}", path.display()),
            done: Default::default(),
            total: 1,
            since: Instant::now(),
        });
        if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("bzc")) {
            std::thread::spawn(move || {
                let result = crate::bundled::load_curve(&path).map(|control| Curve {
                    name: path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default(),
                    control,
                    segments: 64,
                    t: 0.5,
                    construction: true,
                });
                let _ = tx.send(Done::LoadedCurve { ticket, result });
            });
            return;
        }
        std::thread::spawn(move || {
            let loaded = if repair {
                bundled::load_repaired(&path).map(|(m, r)| {
                    let report = if r.is_empty() { None } else { Some(format!("repaired: {r}")) };
                    (m, report, Attributes::default())
                })
            } else {
                let is_obj = path.extension().is_none_or(|e| e.eq_ignore_ascii_case("obj"));
                if is_obj {
                    bundled::load_with_attributes(&path).map(|(m, a)| (m, None, a))
                } else {
                    bundled::load(&path).map(|m| (m, None, Attributes::default()))
                }
            };
            let result = loaded.and_then(|(mesh, report, attrs)| {
                let paths = match paths_for(&path) {
                    Some(p) => {
                        let paths = p.load()?;
                        // A .paths for another vertex count is ignored (a generated one is used).
                        paths.check_model(&mesh, &p.describe()).ok().map(|_| paths)
                    }
                    None => None,
                };
                Ok((path.clone(), mesh, paths, report, attrs))
            });
            let _ = tx.send(Done::Loaded { ticket, result, path });
        });
    }

    /// Requests the current scheme and level (superseding any running request).
    pub fn request_subdivision(&mut self) {
        let ticket = self.sub_gen.fetch_add(1, Ordering::SeqCst) + 1;
        if self.animating {
            self.request_animation();
        }
        if let Some(reason) = self.level_refusal(self.level) {
            self.error = Some(reason);
            self.level = self.result_level.min(self.max_level());
            self.subdividing = None;
            return;
        }
        let (mesh, scheme, level, opts) = (self.control.mesh.clone(), self.scheme, self.level, self.opts);
        let done = Arc::new(AtomicUsize::new(0));
        self.subdividing = Some(Busy {
            what: format!("{} level {level}", scheme.name()),
            done: done.clone(),
            total: level as usize,
            since: Instant::now(),
        });
        let (tx, latest) = (self.tx.clone(), self.sub_gen.clone());
        let (file_attrs, control) = (self.file_attrs.clone(), self.control.clone());
        // A big result gets a proxy: the highest lower level of at most PROXY_FACES
        // triangles, on the way to the result (not computed twice).
        let proxy_level = (predict_faces(&mesh.ct, level) > PROXY_FACES)
            .then(|| (0..level).rev().find(|&l| predict_faces(&mesh.ct, l) <= PROXY_FACES))
            .flatten();
        std::thread::spawn(move || {
            let t0 = Instant::now();
            let live = || latest.load(Ordering::SeqCst) == ticket;
            let run = |from: &Mesh, first: u32, levels: u32| {
                subdivide_with_progress(from, scheme, levels, &opts, |l, _| {
                    done.store((first + l) as usize, Ordering::Relaxed);
                    live()
                })
            };
            let result = (|| {
                let (proxy, first_stats) = match proxy_level {
                    Some(0) => (Some(control.clone()), Stats::default()),
                    Some(l) => {
                        let (p, s) = run(&mesh, 0, l)?;
                        (Some(Shown::new(Arc::new(p))), s)
                    }
                    None => (None, Stats::default()),
                };
                let (from, first) = match &proxy {
                    Some(p) => (p.mesh.clone(), proxy_level.unwrap_or(0)),
                    None => (mesh.clone(), 0),
                };
                let (fine, stats) = run(&from, first, level - first)?;
                let stats = first_stats.then(stats);
                let shown = if level == 0 { control } else { Shown::new(Arc::new(fine)) };
                let ms = t0.elapsed().as_secs_f64() * 1e3;
                let attrs =
                    crate::subdiv::attributes::refine(&mesh.ct, &file_attrs, scheme, level, &opts).unwrap_or_default();
                Ok((shown, proxy, stats, ms, attrs))
            })();
            // A superseded run stopped early: its partial mesh is not the level asked for.
            if live() {
                let _ = tx.send(Done::Subdivided { ticket, result, level });
            }
        });
    }

    /// Starts the animation mode (building the plan on a worker thread).
    pub fn request_animation(&mut self) {
        self.animating = true;
        let ticket = self.anim_gen.fetch_add(1, Ordering::SeqCst) + 1;
        if let Some(reason) = self.level_refusal(self.level) {
            self.error = Some(reason);
            return;
        }
        let (mesh, paths, tweak, refine, scheme, level, opts) = (
            self.control.mesh.clone(),
            self.paths.clone(),
            self.tweak,
            self.refine,
            self.scheme,
            self.level,
            self.opts,
        );
        self.building = Some(Busy {
            what: format!("animation plan, {} level {level}", scheme.name()),
            done: Default::default(),
            total: 1,
            since: Instant::now(),
        });
        let tx = self.tx.clone();
        std::thread::spawn(move || {
            let result = Animation::new(&mesh, &paths, tweak, refine, scheme, level, &opts);
            let _ = tx.send(Done::Animated { ticket, result });
        });
    }

    /// Leaves the animation mode (the static result is shown again).
    pub fn stop_animation(&mut self) {
        self.animating = false;
        self.anim = None;
        self.building = None;
        self.anim_gen.fetch_add(1, Ordering::SeqCst);
        self.result_changed = true;
        self.control_changed = true;
    }

    /// Exports the animation on a worker thread with its own GPU device.
    pub fn export(&mut self, target: ExportTarget, style: ExportStyle) {
        if self.exporting.is_some() {
            return;
        }
        let (mesh, paths, tweak, refine, scheme, level, opts) = (
            self.control.mesh.clone(),
            self.paths.clone(),
            self.tweak,
            self.refine,
            self.scheme,
            self.level,
            self.opts,
        );
        let frames = self.paths.keys_per_vertex << refine.min(20);
        let done = Arc::new(AtomicUsize::new(0));
        let out = match &target {
            ExportTarget::Gif(p) | ExportTarget::Frames(p) => p.clone(),
        };
        self.exporting = Some(Busy {
            what: format!("exporting {} frames to {}", frames, out.display()),
            done: done.clone(),
            total: frames,
            since: Instant::now(),
        });
        let cancel_gen = self.export_cancel.load(Ordering::SeqCst);
        let (tx, cancel) = (self.tx.clone(), self.export_cancel.clone());
        std::thread::spawn(move || {
            let result = Animation::new(&mesh, &paths, tweak, refine, scheme, level, &opts).and_then(|mut anim| {
                export_animation(&mut anim, &mesh, &target, &style, |d, _| {
                    done.store(d, Ordering::Relaxed);
                    cancel.load(Ordering::SeqCst) == cancel_gen
                })
                .map(|n| (n, out))
            });
            let _ = tx.send(Done::Exported { result });
        });
    }

    /// Cancels a running export.
    pub fn cancel_export(&mut self) {
        self.export_cancel.fetch_add(1, Ordering::SeqCst);
    }

    /// Applies finished tasks; returns whether anything changed.
    pub fn poll(&mut self) -> bool {
        let mut changed = false;
        while let Ok(done) = self.rx.try_recv() {
            changed = true;
            match done {
                Done::Loaded { ticket, result, path } => {
                    if ticket != self.load_gen.load(Ordering::SeqCst) {
                        continue;
                    }
                    self.loading = None;
                    match result {
                        Ok((path, mesh, paths, report, attrs)) => {
                            self.failed = None;
                            self.notice = report;
                            self.file_attrs = attrs;
                            self.adopt(path, mesh, paths);
                        }
                        Err(e) => {
                            // Only a mesh-validity problem can be repaired; parse errors cannot.
                            self.failed = matches!(e, crate::Error::Mesh { .. }).then_some(path);
                            self.error = Some(format!("could not open: {e}"));
                        }
                    }
                }
                Done::LoadedCurve { ticket, result } => {
                    if ticket != self.load_gen.load(Ordering::SeqCst) {
                        continue;
                    }
                    self.loading = None;
                    match result {
                        Ok(curve) => {
                            self.stop_animation();
                            self.curve = Some(curve);
                            self.curve_changed = true;
                        }
                        Err(e) => self.error = Some(format!("could not open: {e}")),
                    }
                }
                Done::Subdivided { ticket, result, level } => {
                    if ticket != self.sub_gen.load(Ordering::SeqCst) {
                        continue;
                    }
                    self.subdividing = None;
                    match result {
                        Ok((shown, proxy, stats, ms, attrs)) => {
                            self.raw_attrs = attrs;
                            self.raw = shown.clone();
                            self.result = shown;
                            self.proxy = proxy;
                            self.result_level = level;
                            self.result_scheme = self.scheme;
                            self.stats = Some(stats);
                            self.job_ms = ms;
                            self.refresh_result();
                        }
                        Err(e) => {
                            self.error = Some(e.to_string());
                            self.level = self.result_level;
                        }
                    }
                }
                Done::Animated { ticket, result } => {
                    if ticket != self.anim_gen.load(Ordering::SeqCst) || !self.animating {
                        continue;
                    }
                    self.building = None;
                    match result {
                        Ok(player) => {
                            let mut clock = Clock::new(player.frame_count());
                            if let Some(old) = &self.anim {
                                clock.playing = old.clock.playing;
                                clock.fps = old.clock.fps;
                                clock.looping = old.clock.looping;
                                clock.set_frame(old.clock.frame() * player.frame_count() / old.clock.frames().max(1));
                            } else {
                                clock.playing = true;
                            }
                            self.anim = Some(Anim { player, clock, shown_frame: None });
                        }
                        Err(e) => {
                            self.error = Some(format!("animation: {e}"));
                            self.animating = false;
                        }
                    }
                }
                Done::Exported { result } => {
                    self.exporting = None;
                    match result {
                        Ok((n, out)) => self.notice = Some(format!("wrote {n} frames to {}", out.display())),
                        Err(e) => self.error = Some(format!("export: {e}")),
                    }
                }
            }
        }
        changed
    }

    /// Makes `mesh` (read from `path`) the control mesh.
    pub fn adopt(&mut self, path: PathBuf, mesh: Mesh, paths: Option<Paths>) {
        let mesh = Arc::new(mesh);
        self.name =
            path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| path.display().to_string());
        self.control = Shown::new(mesh.clone());
        self.raw = self.control.clone();
        self.raw_attrs = self.file_attrs.clone();
        match paths {
            Some(p) => {
                self.paths = p;
                self.paths_source = paths_for(&path).map(|p| p.describe()).unwrap_or_default();
            }
            None => {
                self.paths = Paths::generated(&mesh, 4);
                self.paths_source = "generated (small loops around each vertex)".into();
            }
        }
        self.path = Some(path);
        self.original = None;
        self.picked = None;
        self.proxy = None;
        self.result_level = 0;
        self.stats = None;
        self.control_changed = true;
        self.result_changed = true;
        self.anim = None;
        self.refresh_result();
        // Keep the level when it fits; otherwise the largest that does.
        self.level = self.level.min(self.max_level());
        if self.level > 0 || self.animating {
            self.request_subdivision();
        }
    }

    /// Goes back to the built-in tetrahedron.
    pub fn open_builtin(&mut self) {
        let (mesh, paths) = builtin_tetrahedron();
        self.file_attrs = Attributes::default();
        self.load_gen.fetch_add(1, Ordering::SeqCst);
        self.loading = None;
        self.adopt(PathBuf::from("tetrahedron.obj"), mesh, Some(paths));
        self.path = None;
        self.name = "tetrahedron (built in)".into();
        self.paths_source = "bundled:tetrahedron.paths".into();
    }
}

impl Doc {
    /// Rebuilds the shown result from the subdivision output and the display
    /// options (limit snapping, normals, colours), and marks it for upload.
    pub fn refresh_result(&mut self) {
        use crate::mesh::inspect::{
            colormap, displacement_from_control, vertex_counts_per_level, vertex_creation_level,
        };
        use crate::subdiv::limit::{butterfly_normals, loop_limit_normals, loop_limit_positions_with};
        let raw = &self.raw;
        let mesh = if self.snap_limit {
            Arc::new(Mesh {
                ct: raw.mesh.ct.clone(),
                positions: loop_limit_positions_with(&raw.mesh, self.opts.loop_beta),
            })
        } else {
            raw.mesh.clone()
        };
        let normals = match self.normal_mode {
            // the worker's fan normals, unless the points moved to the limit
            NormalMode::FanAverage if !self.snap_limit => raw.normals.clone(),
            NormalMode::FanAverage => Arc::new(mesh.vertex_normals()),
            NormalMode::LoopLimit => Arc::new(loop_limit_normals(&mesh)),
            NormalMode::Butterfly => Arc::new(butterfly_normals(&mesh)),
        };
        let nv = mesh.positions.len();
        let level = self.result_level;
        let ramp = |t: &[f32]| t.iter().map(|&t| Vec3::from(colormap(t))).collect::<Vec<_>>();
        let (colors, max) = match self.coloring {
            Coloring::None | Coloring::Checker => (None, 0.0),
            Coloring::Shells => {
                let counts = vertex_counts_per_level(&self.control.mesh.ct, level);
                let lv = vertex_creation_level(&counts, nv);
                let t: Vec<f32> = lv.iter().map(|&l| f32::from(l) / level.max(1) as f32).collect();
                (Some(ramp(&t)), level as f32)
            }
            Coloring::File => (self.raw_attrs.colors.clone().filter(|c| c.len() == nv), 1.0),
            Coloring::Displacement => match displacement_from_control(&self.control.mesh, &mesh, level) {
                Ok(d) => {
                    let max = d.iter().fold(0.0f32, |a, &b| a.max(b));
                    let t: Vec<f32> = d.iter().map(|&x| if max > 0.0 { x / max } else { 0.0 }).collect();
                    (Some(ramp(&t)), max)
                }
                Err(e) => {
                    self.error = Some(format!("displacement: {e}"));
                    (None, 0.0)
                }
            },
        };
        self.result_colors = colors;
        self.color_max = max;
        // snapping moves points, not connectivity: the topology is the raw one
        self.result = Shown { mesh, normals, topo: raw.topo.clone() };
        self.result_changed = true;
    }

    /// Replaces the control mesh by an edited version (smoothing, edge
    /// operations), keeping the original for [`Doc::revert`], and
    /// re-subdivides.
    pub fn replace_control(&mut self, mesh: Mesh) {
        if self.original.is_none() {
            self.original = Some(self.control.mesh.clone());
        }
        let mesh = Arc::new(mesh);
        // Edits that change the counts (edge splits) leave the file's attributes behind.
        if self.file_attrs.colors.as_ref().is_some_and(|c| c.len() != mesh.positions.len()) {
            self.file_attrs.colors = None;
        }
        if self.file_attrs.uv.as_ref().is_some_and(|u| u.len() != mesh.ct.v_table().len()) {
            self.file_attrs.uv = None;
        }
        self.raw_attrs = self.file_attrs.clone();
        if self.paths.vertex_count() != mesh.positions.len() {
            self.paths = Paths::generated(&mesh, 4);
            self.paths_source = "generated (small loops around each vertex)".into();
        }
        self.control = Shown::new(mesh);
        self.raw = self.control.clone();
        self.result_level = 0;
        self.proxy = None;
        self.anim = None;
        self.picked = None;
        self.control_changed = true;
        self.refresh_result();
        if self.level > 0 || self.animating {
            self.request_subdivision();
        }
    }

    /// Taubin lambda/mu smoothing of the control mesh.
    pub fn smooth(&mut self, steps: u32) {
        use crate::mesh::smooth::{TAUBIN_LAMBDA, TAUBIN_MU, taubin};
        let positions = taubin(&self.control.mesh, steps, TAUBIN_LAMBDA, TAUBIN_MU);
        let ct = self.control.mesh.ct.clone();
        self.replace_control(Mesh { ct, positions });
    }

    /// Back to the control mesh as loaded.
    pub fn revert(&mut self) {
        if let Some(m) = self.original.take() {
            let m = Arc::unwrap_or_clone(m);
            self.replace_control(m);
            self.original = None;
        }
    }

    /// Flips the picked edge of the control mesh.
    pub fn flip_picked(&mut self) {
        let Some(c) = self.picked else { return };
        let mut m = (*self.control.mesh).clone();
        match crate::mesh::edit::flip_edge(&mut m.ct, c) {
            Ok(()) => self.replace_control(m),
            Err(e) => self.error = Some(format!("flip: {e}")),
        }
    }

    /// Splits the picked edge of the control mesh at its midpoint.
    pub fn split_picked(&mut self) {
        let Some(c) = self.picked else { return };
        if c as usize >= self.control.mesh.ct.num_corners() {
            return;
        }
        let mut m = (*self.control.mesh).clone();
        crate::mesh::edit::split_edge(&mut m, c, 0.5);
        self.replace_control(m);
    }

    /// The vertex ids of the picked edge.
    pub fn picked_edge(&self) -> Option<(u32, u32)> {
        let c = self.picked?;
        let ct = &self.control.mesh.ct;
        ((c as usize) < ct.num_corners())
            .then(|| (ct.v_table()[crate::mesh::n(c) as usize], ct.v_table()[crate::mesh::p(c) as usize]))
    }
}

/// The corner of `mesh` whose opposite edge is nearest to where the ray
/// `origin + t * dir` first hits the surface (brute force over the
/// triangles, Moller-Trumbore), or `None` when the ray misses.
pub fn pick_edge(mesh: &Mesh, origin: Vec3, dir: Vec3) -> Option<u32> {
    let mut best: Option<(f32, u32, Vec3)> = None;
    for (t, tri) in mesh.ct.v_table().chunks_exact(3).enumerate() {
        let [a, b, c] = [tri[0], tri[1], tri[2]].map(|i| mesh.positions[i as usize]);
        let (e1, e2) = (b - a, c - a);
        let pv = dir.cross(e2);
        let det = e1.dot(pv);
        if det.abs() < 1e-12 {
            continue;
        }
        let inv = 1.0 / det;
        let tv = origin - a;
        let u = tv.dot(pv) * inv;
        let qv = tv.cross(e1);
        let v = dir.dot(qv) * inv;
        let dist = e2.dot(qv) * inv;
        if u < 0.0 || v < 0.0 || u + v > 1.0 || dist <= 0.0 {
            continue;
        }
        if best.is_none_or(|(d, _, _)| dist < d) {
            best = Some((dist, t as u32, origin + dir * dist));
        }
    }
    let (_, t, hit) = best?;
    let seg = |p: Vec3, q: Vec3| {
        let d = q - p;
        let s = ((hit - p).dot(d) / d.length_squared().max(1e-30)).clamp(0.0, 1.0);
        (p + d * s).distance(hit)
    };
    (0..3u32)
        .map(|k| {
            let c = 3 * t + k;
            let (p, q) = (mesh.ct.v_table()[crate::mesh::n(c) as usize], mesh.ct.v_table()[crate::mesh::p(c) as usize]);
            (seg(mesh.positions[p as usize], mesh.positions[q as usize]), c)
        })
        .min_by(|x, y| x.0.total_cmp(&y.0))
        .map(|(_, c)| c)
}

impl Default for Doc {
    fn default() -> Self {
        Doc::new()
    }
}
