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
use crate::subdiv::{Stats, check_levels_fit, default_memory_limit, predict_faces, subdivide_with_progress};
use crate::{Mesh, Options, Result, Scheme, io};
use glam::Vec3;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::time::Instant;

/// The tetrahedron compiled into the binary, so the viewer opens anywhere.
pub const TETRAHEDRON_OBJ: &str = include_str!("../../models/tetrahedron.obj");
/// Its animation paths.
pub const TETRAHEDRON_PATHS: &str = include_str!("../../paths/tetrahedron.paths");

/// Largest proxy mesh (see [`Doc::proxy`]).
pub const PROXY_FACES: u64 = 150_000;

/// Highest level offered in the panel (further limited by memory).
pub const MAX_LEVEL: u32 = 10;

/// A mesh with its normals and counts, ready to upload.
pub struct Shown {
    /// The mesh.
    pub mesh: Arc<Mesh>,
    /// Fan-averaged vertex normals.
    pub normals: Vec<Vec3>,
    /// V/E/F, genus, boundary loops...
    pub topo: Topology,
}

impl Shown {
    fn new(mesh: Arc<Mesh>) -> Shown {
        let normals = mesh.vertex_normals();
        let topo = topology(&mesh.ct);
        Shown { mesh, normals, topo }
    }
}

enum Done {
    Loaded { ticket: u64, result: Result<(PathBuf, Mesh, Option<Paths>, Option<String>)>, path: PathBuf },
    Subdivided { ticket: u64, result: Result<(Shown, Option<Shown>, Stats, f64)>, level: u32 },
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
    /// The subdivided mesh shown (the control mesh at level 0).
    pub result: Shown,
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
    // Both are compiled in and checked by the tests; a failure here is a build error in disguise.
    let (mesh, _) =
        io::obj::from_bytes(TETRAHEDRON_OBJ.as_bytes(), "tetrahedron.obj").expect("bundled tetrahedron is valid");
    let paths = Paths::parse(TETRAHEDRON_PATHS, "tetrahedron.paths").expect("bundled tetrahedron paths are valid");
    (mesh, paths)
}

/// The `.paths` that goes with `model`: `model.paths` beside it, or
/// `paths/<stem>.paths` of the bundled set.
pub fn paths_for(model: &Path) -> Option<PathBuf> {
    let beside = model.with_extension("paths");
    if beside.is_file() {
        return Some(beside);
    }
    let stem = model.file_stem()?;
    let bundled = Path::new(env!("CARGO_MANIFEST_DIR")).join("paths").join(stem).with_extension("paths");
    bundled.is_file().then_some(bundled)
}

impl Doc {
    /// A document on the built-in tetrahedron.
    pub fn new() -> Doc {
        let (mesh, paths) = builtin_tetrahedron();
        let (tx, rx) = channel();
        let mesh = Arc::new(mesh);
        Doc {
            name: "tetrahedron (built in)".into(),
            path: None,
            control: Shown::new(mesh.clone()),
            result: Shown::new(mesh),
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
            paths_source: "paths/tetrahedron.paths".into(),
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
        std::thread::spawn(move || {
            let loaded = if repair {
                io::load_repaired(&path).map(|(m, r)| {
                    let report = if r.is_empty() { None } else { Some(format!("repaired: {r}")) };
                    (m, report)
                })
            } else {
                io::load(&path).map(|m| (m, None))
            };
            let result = loaded.and_then(|(mesh, report)| {
                let paths = match paths_for(&path) {
                    Some(p) => {
                        let paths = Paths::load(&p)?;
                        // A .paths for another vertex count is ignored (a generated one is used).
                        paths.check_model(&mesh, &p.display().to_string()).ok().map(|_| paths)
                    }
                    None => None,
                };
                Ok((path.clone(), mesh, paths, report))
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
        std::thread::spawn(move || {
            let t0 = Instant::now();
            let result = subdivide_with_progress(&mesh, scheme, level, &opts, |l, _| {
                done.store(l as usize, Ordering::Relaxed);
                latest.load(Ordering::SeqCst) == ticket
            })
            .map(|(fine, stats)| {
                let ms = t0.elapsed().as_secs_f64() * 1e3;
                let big = fine.ct.num_triangles() as u64 > PROXY_FACES;
                let shown = if level == 0 { Shown::new(mesh.clone()) } else { Shown::new(Arc::new(fine)) };
                let proxy_level = (0..level).rev().find(|&l| predict_faces(&mesh.ct, l) <= PROXY_FACES);
                let proxy = match proxy_level {
                    Some(l) if big && latest.load(Ordering::SeqCst) == ticket => {
                        subdivide_with_progress(&mesh, scheme, l, &opts, |_, _| latest.load(Ordering::SeqCst) == ticket)
                            .ok()
                            .map(|(p, _)| Shown::new(Arc::new(p)))
                    }
                    _ => None,
                };
                (shown, proxy, stats, ms)
            });
            let _ = tx.send(Done::Subdivided { ticket, result, level });
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
                        Ok((path, mesh, paths, report)) => {
                            self.failed = None;
                            self.notice = report;
                            self.adopt(path, mesh, paths);
                        }
                        Err(e) => {
                            // Only a mesh-validity problem can be repaired; parse errors cannot.
                            self.failed = matches!(e, crate::Error::Mesh { .. }).then_some(path);
                            self.error = Some(format!("could not open: {e}"));
                        }
                    }
                }
                Done::Subdivided { ticket, result, level } => {
                    if ticket != self.sub_gen.load(Ordering::SeqCst) {
                        continue;
                    }
                    self.subdividing = None;
                    match result {
                        Ok((shown, proxy, stats, ms)) => {
                            self.result = shown;
                            self.proxy = proxy;
                            self.result_level = level;
                            self.result_scheme = self.scheme;
                            self.stats = Some(stats);
                            self.job_ms = ms;
                            self.result_changed = true;
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
        match paths {
            Some(p) => {
                self.paths = p;
                self.paths_source = paths_for(&path).map(|p| p.display().to_string()).unwrap_or_default();
            }
            None => {
                self.paths = Paths::generated(&mesh, 4);
                self.paths_source = "generated (small loops around each vertex)".into();
            }
        }
        self.path = Some(path);
        self.result = Shown::new(mesh);
        self.proxy = None;
        self.result_level = 0;
        self.stats = None;
        self.control_changed = true;
        self.result_changed = true;
        self.anim = None;
        // Keep the level when it fits; otherwise the largest that does.
        self.level = self.level.min(self.max_level());
        if self.level > 0 || self.animating {
            self.request_subdivision();
        }
    }

    /// Goes back to the built-in tetrahedron.
    pub fn open_builtin(&mut self) {
        let (mesh, paths) = builtin_tetrahedron();
        self.load_gen.fetch_add(1, Ordering::SeqCst);
        self.loading = None;
        self.adopt(PathBuf::from("tetrahedron.obj"), mesh, Some(paths));
        self.path = None;
        self.name = "tetrahedron (built in)".into();
        self.paths_source = "paths/tetrahedron.paths".into();
    }
}

impl Default for Doc {
    fn default() -> Self {
        Doc::new()
    }
}
