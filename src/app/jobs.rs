//! Worker threads: loading, subdividing, building an animation, exporting.
//!
//! Every long task runs on its own thread and reports one [`Finished`]
//! message through the channel that [`Jobs`] owns. Each kind of task but the
//! export has a ticket counter: a newer request supersedes an older one,
//! whose message is dropped by [`Jobs::poll`], and a superseded subdivision
//! stops after its current level and sends nothing. A running task shows in
//! its busy slot ([`Slots`]) until its message is polled. The document
//! adopts what [`Jobs::poll`] returns; nothing here touches the document.

use super::model::{Curve, Shown};
use crate::anim::paths::Paths;
use crate::anim::player::Animation;
use crate::anim::tweak::Tweak;
use crate::clock::Instant;
use crate::mesh::attributes::Attributes;
use crate::render::export::{ExportStyle, ExportTarget, export_animation};
use crate::subdiv::{ControlCounts, Stats};
use crate::{Mesh, Options, Result, Scheme, bundled};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Condvar, Mutex};
use std::time::Duration;

/// Largest proxy mesh (see [`super::model::Model::proxy`]).
pub(crate) const PROXY_FACES: u64 = 150_000;

/// A model to open: a file by its path (a bundled model by its name), or
/// bytes in memory named `path` (a file picked or dropped on the page, a
/// fetched URL), its extension choosing the format.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Input {
    /// The file, or the name of the bytes.
    pub(crate) path: PathBuf,
    /// The content, when it is not read from `path`.
    pub(crate) bytes: Option<Arc<[u8]>>,
}

impl From<PathBuf> for Input {
    fn from(path: PathBuf) -> Input {
        Input { path, bytes: None }
    }
}

impl Input {
    /// Reads the model through the one reading pipeline.
    fn read(&self, opts: &crate::io::ReadOptions) -> Result<crate::io::Loaded> {
        match &self.bytes {
            Some(bytes) => {
                let name = self.path.to_string_lossy();
                crate::io::read(crate::io::Source::Bytes { bytes, name: &name, folder: None }, opts)
            }
            None => bundled::read(&self.path, opts),
        }
    }
}

/// A running task shown in the panel.
#[derive(Clone)]
pub(crate) struct Busy {
    /// What is running.
    pub(crate) what: String,
    /// Units done (levels, frames).
    pub(crate) done: Arc<AtomicUsize>,
    /// Units in all.
    pub(crate) total: usize,
    /// Started at.
    pub(crate) since: Instant,
}

impl Busy {
    fn new(what: String, total: usize) -> Busy {
        Busy { what, done: Default::default(), total, since: Instant::now() }
    }
}

/// The busy slots, one per kind of task.
#[derive(Default)]
pub(crate) struct Slots {
    /// Running load.
    pub(crate) loading: Option<Busy>,
    /// Running subdivision.
    pub(crate) subdividing: Option<Busy>,
    /// Running animation build.
    pub(crate) building: Option<Busy>,
    /// Running export.
    pub(crate) exporting: Option<Busy>,
    /// Running inspector pick.
    pub(crate) inspecting: Option<Busy>,
    /// Running tessellation of the adaptive display.
    pub(crate) tessellating: Option<Busy>,
}

/// A loaded model.
pub(crate) struct Opened {
    /// The file.
    pub(crate) path: PathBuf,
    /// Its mesh.
    pub(crate) mesh: Mesh,
    /// The animation paths found for it (None: none, or for another vertex count).
    pub(crate) paths: Option<Paths>,
    /// What the repair did, when it did something.
    pub(crate) report: Option<String>,
    /// Its colours and texture coordinates.
    pub(crate) attrs: Attributes,
    /// Its points in f64 as the file wrote them (where the format keeps
    /// more digits than f32 and the mesh was not repaired).
    pub(crate) precise: Option<Vec<glam::DVec3>>,
    /// How many of a stage's time samples `paths` holds (its animation
    /// plays them).
    pub(crate) samples: Option<usize>,
}

/// A finished subdivision.
pub(crate) struct Subdivided {
    /// The output, with fan normals and topology.
    pub(crate) shown: Shown,
    /// A lower level of at most [`PROXY_FACES`] triangles, for big outputs.
    pub(crate) proxy: Option<Shown>,
    /// Phase times of both legs (proxy, then the rest).
    pub(crate) stats: Stats,
    /// Wall time of the job, ms.
    pub(crate) ms: f64,
    /// The control mesh's attributes refined to the output.
    pub(crate) attrs: Attributes,
    /// What was asked for.
    pub(crate) level: u32,
    /// The scheme used.
    pub(crate) scheme: Scheme,
    /// The options used.
    pub(crate) opts: Options,
    /// The refiner that made the output, and the control mesh it was
    /// built on (none at level 0).
    pub(crate) refiner: Option<(Arc<Mesh>, crate::Refiner)>,
    /// Whether the prims were refined apart and joined (see [`by_prim`]).
    pub(crate) by_prim: bool,
}

/// What a worker sends back.
pub(crate) enum Finished {
    /// A model file was read (or failed to).
    Loaded {
        /// The model asked for (offered for repair when it is invalid).
        input: Input,
        /// The model.
        result: Result<Opened>,
    },
    /// A `.bzc` curve was read.
    Curve(Result<Curve>),
    /// A subdivision finished.
    Subdivided(Result<Box<Subdivided>>),
    /// An animation plan was built.
    Animated(Result<Animation>),
    /// An export finished: frames written and where.
    Exported(Result<(usize, PathBuf)>),
    /// An inspector pick was answered, for the output it was made on.
    Inspected {
        /// That output.
        shown: Arc<Mesh>,
        /// What was found.
        result: Result<super::inspect::Found>,
    },
    /// A tessellation of the adaptive display finished.
    Tessellated(Result<Box<super::adaptive::Tessellated>>),
}

/// The inputs of a subdivision.
pub(crate) struct SubdivisionJob {
    /// The control mesh.
    pub(crate) control: Shown,
    /// Its attributes from the file.
    pub(crate) attrs: Attributes,
    /// Scheme.
    pub(crate) scheme: Scheme,
    /// Level.
    pub(crate) level: u32,
    /// Scheme options.
    pub(crate) opts: Options,
    /// Whether each prim goes by the scheme and options its file states
    /// (see [`super::doc::Request::by_file`]).
    pub(crate) by_file: bool,
}

/// The inputs of an animation plan (also what an export renders).
#[derive(Clone)]
pub(crate) struct AnimationJob {
    /// The control mesh.
    pub(crate) mesh: Arc<Mesh>,
    /// Its animation paths.
    pub(crate) paths: Paths,
    /// Path tweak.
    pub(crate) tweak: Tweak,
    /// Path refinement count.
    pub(crate) refine: u32,
    /// Scheme.
    pub(crate) scheme: Scheme,
    /// Level.
    pub(crate) level: u32,
    /// Scheme options.
    pub(crate) opts: Options,
}

impl AnimationJob {
    fn build(&self) -> Result<Animation> {
        Animation::new(&self.mesh, &self.paths, self.tweak, self.refine, self.scheme, self.level, &self.opts)
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Load,
    Subdivide,
    Animate,
    Export,
    Inspect,
    Tessellate,
}

struct Message {
    kind: Kind,
    ticket: u64,
    finished: Finished,
}

/// How many worker threads are alive, with a signal when one ends.
#[derive(Default)]
struct Workers {
    alive: Mutex<usize>,
    ended: Condvar,
    /// Tasks waiting for the next poll (the browser only: see [`Jobs::spawn`]).
    deferred: Mutex<Vec<Box<dyn FnOnce() + Send>>>,
}

/// Held by a worker thread; its drop (after the thread's message is sent)
/// counts the thread as ended.
struct WorkerGuard(Arc<Workers>);

impl Drop for WorkerGuard {
    fn drop(&mut self) {
        let mut alive = self.0.alive.lock().unwrap_or_else(|e| e.into_inner());
        *alive = alive.saturating_sub(1);
        self.0.ended.notify_all();
    }
}

/// The worker channel, the tickets and the busy slots.
pub(crate) struct Jobs {
    tx: Sender<Message>,
    rx: Receiver<Message>,
    load_ticket: Arc<AtomicU64>,
    subdivide_ticket: Arc<AtomicU64>,
    animate_ticket: Arc<AtomicU64>,
    inspect_ticket: Arc<AtomicU64>,
    tessellate_ticket: Arc<AtomicU64>,
    export_cancel: Arc<AtomicU64>,
    /// What is running.
    pub(crate) busy: Slots,
    workers: Arc<Workers>,
}

impl Default for Jobs {
    fn default() -> Self {
        Jobs::new()
    }
}

impl Jobs {
    /// No task running.
    pub(crate) fn new() -> Jobs {
        let (tx, rx) = channel();
        Jobs {
            tx,
            rx,
            load_ticket: Default::default(),
            subdivide_ticket: Default::default(),
            animate_ticket: Default::default(),
            inspect_ticket: Default::default(),
            tessellate_ticket: Default::default(),
            export_cancel: Default::default(),
            busy: Slots::default(),
            workers: Default::default(),
        }
    }

    /// Whether any task is running.
    pub(crate) fn busy(&self) -> bool {
        let b = &self.busy;
        b.loading.is_some()
            || b.subdividing.is_some()
            || b.building.is_some()
            || b.exporting.is_some()
            || b.inspecting.is_some()
            || b.tessellating.is_some()
    }

    fn ticket(&self, kind: Kind) -> Option<&Arc<AtomicU64>> {
        match kind {
            Kind::Load => Some(&self.load_ticket),
            Kind::Subdivide => Some(&self.subdivide_ticket),
            Kind::Animate => Some(&self.animate_ticket),
            Kind::Inspect => Some(&self.inspect_ticket),
            Kind::Tessellate => Some(&self.tessellate_ticket),
            Kind::Export => None,
        }
    }

    /// A new ticket of `kind`: every running task of that kind is superseded.
    fn next_ticket(&self, kind: Kind) -> u64 {
        self.ticket(kind).map_or(0, |t| t.fetch_add(1, Ordering::SeqCst) + 1)
    }

    fn slot(&mut self, kind: Kind) -> &mut Option<Busy> {
        match kind {
            Kind::Load => &mut self.busy.loading,
            Kind::Subdivide => &mut self.busy.subdividing,
            Kind::Animate => &mut self.busy.building,
            Kind::Export => &mut self.busy.exporting,
            Kind::Inspect => &mut self.busy.inspecting,
            Kind::Tessellate => &mut self.busy.tessellating,
        }
    }

    /// Runs `work` on a new thread; its result comes back as a message of
    /// `kind` with `ticket` (`None`: the work decided to send nothing).
    ///
    /// In the browser (no threads) the work waits for the next
    /// [`Jobs::poll`], which runs one such task per frame: the frame that
    /// asked has shown the task as busy by then.
    fn spawn(&self, kind: Kind, ticket: u64, work: impl FnOnce() -> Option<Finished> + Send + 'static) {
        *self.workers.alive.lock().unwrap_or_else(|e| e.into_inner()) += 1;
        let guard = WorkerGuard(self.workers.clone());
        let tx = self.tx.clone();
        let task = move || {
            let _guard = guard;
            if let Some(finished) = work() {
                // The receiver is gone only when the viewer is closing.
                let _ = tx.send(Message { kind, ticket, finished });
            }
        };
        #[cfg(not(target_arch = "wasm32"))]
        std::thread::spawn(task);
        #[cfg(target_arch = "wasm32")]
        self.workers.deferred.lock().unwrap_or_else(|e| e.into_inner()).push(Box::new(task));
    }

    /// Runs the oldest deferred task (the browser's stand-in for a worker
    /// thread); whether there was one.
    fn run_deferred(&self) -> bool {
        let next = {
            let mut queue = self.workers.deferred.lock().unwrap_or_else(|e| e.into_inner());
            (!queue.is_empty()).then(|| queue.remove(0))
        };
        next.map(|task| task()).is_some()
    }

    /// The messages of current tasks (superseded ones are dropped), each
    /// clearing its busy slot.
    pub(crate) fn poll(&mut self) -> Vec<Finished> {
        self.run_deferred();
        let mut out = Vec::new();
        while let Ok(m) = self.rx.try_recv() {
            if self.ticket(m.kind).is_some_and(|t| t.load(Ordering::SeqCst) != m.ticket) {
                continue;
            }
            *self.slot(m.kind) = None;
            out.push(m.finished);
        }
        out
    }

    /// Waits until no worker thread is alive (superseded ones included), at
    /// most `timeout`; whether they all ended. Their messages are then all
    /// in the channel, for [`Jobs::poll`].
    pub(crate) fn wait_for_workers(&self, timeout: Duration) -> bool {
        while self.run_deferred() {}
        // no threads: every task has run (and std's timed wait has no clock there)
        if cfg!(target_arch = "wasm32") {
            return true;
        }
        let alive = self.workers.alive.lock().unwrap_or_else(|e| e.into_inner());
        let (alive, _) =
            self.workers.ended.wait_timeout_while(alive, timeout, |n| *n > 0).unwrap_or_else(|e| e.into_inner());
        *alive == 0
    }

    /// Opens a model file (a `.bzc` curve, or a mesh, repaired or not; a
    /// stage's sampled points at `time`).
    pub(crate) fn load(&mut self, input: Input, repair: bool, time: Option<f64>) {
        let ticket = self.next_ticket(Kind::Load);
        self.busy.loading = Some(Busy::new(format!("loading {}", input.path.display()), 1));
        if input.bytes.is_none() && input.path.extension().is_some_and(|e| e.eq_ignore_ascii_case("bzc")) {
            self.spawn(Kind::Load, ticket, move || Some(Finished::Curve(load_curve(&input.path))));
        } else {
            self.spawn(Kind::Load, ticket, move || {
                let result = load_model(&input, repair, time);
                Some(Finished::Loaded { input, result })
            });
        }
    }

    /// Drops any running load (its model will not be adopted).
    pub(crate) fn cancel_load(&mut self) {
        self.next_ticket(Kind::Load);
        self.busy.loading = None;
    }

    /// Subdivides on a worker (superseding any running subdivision).
    pub(crate) fn subdivide(&mut self, job: SubdivisionJob) {
        let ticket = self.next_ticket(Kind::Subdivide);
        let busy = Busy::new(format!("{} level {}", job.scheme.name(), job.level), job.level as usize);
        let done = busy.done.clone();
        self.busy.subdividing = Some(busy);
        let latest = self.subdivide_ticket.clone();
        self.spawn(Kind::Subdivide, ticket, move || {
            let live = || latest.load(Ordering::SeqCst) == ticket;
            let result = run_subdivision(&job, &done, &live).map(Box::new);
            // A superseded run stopped early: its partial mesh is not the level asked for.
            live().then_some(Finished::Subdivided(result))
        });
    }

    /// Tessellates the limit for the adaptive display on a worker
    /// (superseding any running tessellation).
    pub(crate) fn tessellate(&mut self, job: super::adaptive::Job) {
        let ticket = self.next_ticket(Kind::Tessellate);
        self.busy.tessellating = Some(Busy::new("tessellating the limit for the view".into(), 1));
        self.spawn(Kind::Tessellate, ticket, move || Some(Finished::Tessellated(job.run().map(Box::new))));
    }

    /// Drops any running subdivision.
    pub(crate) fn cancel_subdivision(&mut self) {
        self.next_ticket(Kind::Subdivide);
        self.busy.subdividing = None;
    }

    /// Builds an animation plan on a worker (superseding any running build).
    pub(crate) fn animate(&mut self, job: AnimationJob) {
        let ticket = self.next_ticket(Kind::Animate);
        self.busy.building = Some(Busy::new(format!("animation plan, {} level {}", job.scheme.name(), job.level), 1));
        self.spawn(Kind::Animate, ticket, move || Some(Finished::Animated(job.build())));
    }

    /// Drops any running animation build.
    pub(crate) fn cancel_animation(&mut self) {
        self.next_ticket(Kind::Animate);
        self.busy.building = None;
    }

    /// Renders every frame of the animation to `target` on a worker with its
    /// own GPU device; does nothing while an export runs.
    pub(crate) fn export(&mut self, job: AnimationJob, target: ExportTarget, style: ExportStyle) {
        if self.busy.exporting.is_some() {
            return;
        }
        let frames = job.paths.keys_per_vertex << job.refine.min(20);
        let out = match &target {
            ExportTarget::Gif(p) | ExportTarget::Frames(p) => p.clone(),
        };
        let busy = Busy::new(format!("exporting {} frames to {}", frames, out.display()), frames);
        let done = busy.done.clone();
        self.busy.exporting = Some(busy);
        let cancel = self.export_cancel.clone();
        let cancel_at = cancel.load(Ordering::SeqCst);
        self.spawn(Kind::Export, 0, move || {
            let result = job.build().and_then(|mut anim| {
                export_animation(&mut anim, &job.mesh, &target, &style, None, |d, _| {
                    done.store(d, Ordering::Relaxed);
                    cancel.load(Ordering::SeqCst) == cancel_at
                })
                .map(|n| (n, out))
            });
            Some(Finished::Exported(result))
        });
    }

    /// Answers an inspector pick on a worker (superseding a running one).
    pub(crate) fn inspect(&mut self, job: super::inspect::InspectJob) {
        let ticket = self.next_ticket(Kind::Inspect);
        self.busy.inspecting = Some(Busy::new("inspecting".into(), 1));
        self.spawn(Kind::Inspect, ticket, move || {
            let result = job.run();
            Some(Finished::Inspected { shown: job.shown, result })
        });
    }

    /// Cancels a running export (it stops after its current frame).
    pub(crate) fn cancel_export(&mut self) {
        self.export_cancel.fetch_add(1, Ordering::SeqCst);
    }
}

/// A `.bzc` file as a curve with the default view of its construction.
fn load_curve(path: &std::path::Path) -> Result<Curve> {
    bundled::load_curve(path, &crate::io::Limits::default()).map(|control| Curve {
        name: path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default(),
        control,
        segments: 64,
        t: 0.5,
        construction: true,
    })
}

/// A model file (repaired when asked) with its attributes, textures
/// decoded, and matching paths; the repair report and the read's warnings
/// become the status notice.
pub(crate) fn load_model(input: &Input, repair: bool, time: Option<f64>) -> Result<Opened> {
    let path = input.path.as_path();
    let topology = if repair { crate::io::Topology::Repair } else { crate::io::Topology::Refuse };
    let opts = crate::io::ReadOptions { topology, textures: true, time, ..Default::default() };
    let loaded = input.read(&opts)?;
    let mut notes: Vec<String> = loaded.warnings;
    if loaded.notes.fanned > 0 {
        notes.insert(
            0,
            format!(
                "{} polygons: kept by Catmull-Clark and bilinear, fanned for the triangle schemes",
                loaded.notes.fanned
            ),
        );
    }
    if let Some(r) = loaded.notes.repair.filter(|r| !r.is_empty()) {
        notes.insert(0, format!("repaired: {r}"));
    }
    let mesh = loaded.mesh;
    let paths = match input.bytes.is_none().then(|| bundled::paths_for(path)).flatten() {
        Some(p) => {
            let paths = p.load(&opts.limits)?;
            // A .paths for another vertex count is ignored (a generated one is used).
            paths.check_model(&mesh, &p.describe()).ok().map(|_| paths)
        }
        None => None,
    };
    let (paths, samples) = match paths {
        Some(p) => (Some(p), None),
        None => match sampled_frames(input, &opts, &loaded.attributes, mesh.positions.len())? {
            Some(p) => {
                let n = p.keys_per_vertex;
                (Some(p), Some(n))
            }
            None => (None, None),
        },
    };
    let report = (!notes.is_empty()).then(|| notes.join("; "));
    let (attrs, precise) = (loaded.attributes, loaded.precise);
    Ok(Opened { path: path.to_path_buf(), mesh, paths, report, attrs, precise, samples })
}

/// Most time samples a stage's animation plays.
const MAX_SAMPLES: usize = 240;

/// A stage's time samples as animation keys (the stage read again at each
/// sample, at most [`MAX_SAMPLES`] spread over them), when its points are
/// sampled at two times or more and every read has `vertices` points.
fn sampled_frames(
    input: &Input,
    opts: &crate::io::ReadOptions,
    attrs: &Attributes,
    vertices: usize,
) -> Result<Option<Paths>> {
    let Some(times) = attrs.scene().map(|s| &s.times).filter(|t| t.len() > 1) else { return Ok(None) };
    let step = times.len().div_ceil(MAX_SAMPLES);
    let mut frames = Vec::new();
    for &t in times.iter().step_by(step) {
        let at = crate::io::ReadOptions { time: Some(t), attributes: false, textures: false, ..*opts };
        let frame = input.read(&at)?.mesh.positions;
        if frame.len() != vertices {
            return Ok(None);
        }
        frames.push(frame);
    }
    Ok(Paths::of_frames(&frames))
}

/// The subdivision of a model whose prims go by their file's schemes when
/// one scheme does not do for all: prims that state different options
/// (each set refined by its own, joined), or a model whose file says
/// `subdivisionScheme none` (its cage at every level). `None` otherwise:
/// one refiner then makes the level. No refiner comes back (an edit
/// subdivides again).
fn by_prim(job: &SubdivisionJob, t0: Instant) -> Result<Option<Subdivided>> {
    if !job.by_file {
        return Ok(None);
    }
    let mesh = &*job.control.mesh;
    let mut parts = crate::subdiv::parts_by_options(mesh, &job.attrs)?;
    if parts.is_empty() {
        if job.attrs.options.scheme != Some(crate::mesh::FileScheme::None) {
            return Ok(None);
        }
        parts.push((mesh.clone(), job.attrs.clone()));
    }
    let list: Vec<crate::Part> = parts
        .iter()
        .map(|(mesh, attrs)| crate::Part {
            mesh,
            attrs,
            scheme: attrs.options.scheme.map_or(Some(job.scheme), Scheme::of_file),
            levels: job.level,
            opts: job.opts.with_file(attrs.options),
        })
        .collect();
    // holes kept (not drawn): the level's faces are the parts' in order
    let (fine, attrs, stats) = crate::subdiv::subdivide_parts(&list, true)?;
    let (uv, materials) = crate::subdiv::tables::attributes::onto_fan(&fine.pt, attrs.uv, attrs.materials);
    let attrs = Attributes { uv, materials, ..attrs };
    let shown = Shown::new(Arc::new(fine.triangulated()));
    let ms = t0.elapsed().as_secs_f64() * 1e3;
    let (level, scheme, opts) = (job.level, job.scheme, job.opts);
    Ok(Some(Subdivided { shown, proxy: None, stats, ms, attrs, level, scheme, opts, refiner: None, by_prim: true }))
}

/// The highest level below `level` with at most [`PROXY_FACES`] triangles,
/// when `level` itself has more.
fn proxy_level(mesh: &Mesh, scheme: Scheme, level: u32) -> Option<u32> {
    let counts = ControlCounts::of(&mesh.ct);
    let drawn = |l: u32| counts.triangles_at(scheme, l);
    (drawn(level) > PROXY_FACES).then(|| (0..level).rev().find(|&l| drawn(l) <= PROXY_FACES)).flatten()
}

/// The subdivision of `job`: one refiner, which makes every level once and
/// serves the attributes on them; its proxy level, when the output is big,
/// is one of those levels. `done` counts the levels; `live` says whether
/// the job is still wanted (checked per level). The refiner goes with the
/// result, for the edit mode to take over.
fn run_subdivision(job: &SubdivisionJob, done: &AtomicUsize, live: &dyn Fn() -> bool) -> Result<Subdivided> {
    let t0 = Instant::now();
    if let Some(s) = by_prim(job, t0)? {
        return Ok(s);
    }
    let (control, scheme, level, opts) = (&job.control, job.scheme, job.level, job.opts);
    let mut progress = |l: u32, _| {
        done.store(l as usize, Ordering::Relaxed);
        live()
    };
    let r = crate::Refiner::with_progress(&*control.mesh, (scheme, level, &opts), &mut progress)?;
    let proxy = proxy_level(&control.mesh, scheme, level).and_then(|l| match l {
        0 => Some(control.clone()),
        l => r.level_mesh(l).map(|m| Shown::new(Arc::new(m))),
    });
    let attrs = r.attributes(&job.attrs).unwrap_or_default();
    let stats = r.stats().clone();
    let shown = if level == 0 { control.clone() } else { Shown::new(Arc::new(r.mesh())) };
    let refiner = (level > 0).then(|| (control.mesh.clone(), r));
    let ms = t0.elapsed().as_secs_f64() * 1e3;
    Ok(Subdivided { shown, proxy, stats, ms, attrs, level, scheme, opts, refiner, by_prim: false })
}
