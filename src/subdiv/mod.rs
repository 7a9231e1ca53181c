//! Subdivision: the shared 1-to-4 [`split`] plus one file of rules per scheme.
//!
//! A level = `split` (new V, O, C, valences; edge numbering) + edge points for
//! every edge + vertex points (Loop, Jarek) or a copy (interpolating schemes).
//! Every rule reads the old level only; output arrays are allocated once per
//! level with their exact sizes (`V' = V + E`, `F' = 4F`); the work is spread
//! over rayon's threads in chunks.

pub mod attributes;
pub mod butterfly;
pub mod features;
pub mod jarek;
pub mod limit;
pub mod loop_;
pub mod midpoint;
pub mod modified_butterfly;
pub mod packed;
pub mod rules;
pub mod stencil;

pub use crate::mesh::{BoundaryInterpolation, Creasing};
use crate::mesh::{CornerTable, Mesh, split};
use crate::{Error, Result};
use glam::Vec3;
use rules::{Level, Rules};
use std::borrow::Cow;
use std::time::Instant;

pub use loop_::LoopBeta;

/// A subdivision scheme.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Scheme {
    /// Linear: edge midpoints, nothing moves.
    Midpoint,
    /// Loop (approximating, C2 except at extraordinary vertices).
    #[default]
    Loop,
    /// Classic 8-point butterfly (interpolating).
    Butterfly,
    /// Zorin's modified butterfly (interpolating, C1 everywhere).
    ModifiedButterfly,
    /// Rossignac's Jarek scheme (approximating).
    Jarek,
}

impl Scheme {
    /// All schemes, in menu order.
    pub const ALL: [Scheme; 5] =
        [Scheme::Midpoint, Scheme::Loop, Scheme::Butterfly, Scheme::ModifiedButterfly, Scheme::Jarek];
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Midpoint => "midpoint",
            Scheme::Loop => "loop",
            Scheme::Butterfly => "butterfly",
            Scheme::ModifiedButterfly => "modified-butterfly",
            Scheme::Jarek => "jarek",
        }
    }
    /// Whether old vertices keep their positions.
    pub fn is_interpolating(self) -> bool {
        !matches!(self, Scheme::Loop | Scheme::Jarek)
    }
}

impl std::fmt::Display for Scheme {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Scheme {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "midpoint" | "linear" => Ok(Scheme::Midpoint),
            "loop" => Ok(Scheme::Loop),
            "butterfly" => Ok(Scheme::Butterfly),
            "modified-butterfly" | "modified_butterfly" | "mbutterfly" | "zorin" => Ok(Scheme::ModifiedButterfly),
            "jarek" => Ok(Scheme::Jarek),
            _ => Err(format!(
                "unknown scheme '{s}' (expected one of: midpoint, loop, butterfly, modified-butterfly, jarek)"
            )),
        }
    }
}

/// Options of a subdivision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Loop's vertex weights.
    pub loop_beta: LoopBeta,
    /// Modified-butterfly tension `w` (0 = Zorin's default).
    pub tension: f32,
    /// Refuse a level whose predicted memory exceeds this many bytes
    /// (`None`: 80% of the memory available when the call starts).
    pub max_memory: Option<u64>,
    /// How semi-sharp creases decay from level to level.
    pub creasing: Creasing,
    /// Whether boundary vertices with one face are corners.
    pub boundary: BoundaryInterpolation,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            loop_beta: LoopBeta::Loop,
            tension: 0.0,
            max_memory: None,
            creasing: Creasing::Uniform,
            boundary: BoundaryInterpolation::EdgeOnly,
        }
    }
}

/// Time spent per phase, in milliseconds, summed over levels.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stats {
    /// The whole split: edge numbering plus the new V, O, C and valence
    /// tables (the split and the O update are one pass).
    pub split_ms: f64,
    /// Part of `split_ms`: numbering the edges (owner corners, edge ids).
    pub numbering_ms: f64,
    /// Edge (odd) points.
    pub edge_ms: f64,
    /// Vertex (even) points or their copy.
    pub vertex_ms: f64,
    /// The whole call.
    pub total_ms: f64,
    /// Faces after each level.
    pub faces_per_level: Vec<usize>,
}

impl Stats {
    /// The stats of two calls run one after the other (the second
    /// continuing from the first's result).
    pub fn then(mut self, later: Stats) -> Stats {
        self.split_ms += later.split_ms;
        self.numbering_ms += later.numbering_ms;
        self.edge_ms += later.edge_ms;
        self.vertex_ms += later.vertex_ms;
        self.total_ms += later.total_ms;
        self.faces_per_level.extend(later.faces_per_level);
        self
    }
}

/// Predicted peak bytes of refining a mesh with `nt` triangles, `nv`
/// vertices and `ne` edges once (new tables, positions and scratch, plus the
/// old level still alive).
pub fn predict_level_bytes(nt: u64, nv: u64, ne: u64) -> u64 {
    let new_corners = 12 * nt;
    let new_verts = nv + ne;
    let new = new_corners * 8 + new_verts * (8 + 12);
    let scratch = 3 * nt * 4 + ne * 4;
    let old = 3 * nt * 8 + nv * 20;
    new + scratch + old
}

/// Bytes this process can still be given: 80% of the machine's
/// `MemAvailable`, and no more than half the process's address-space limit
/// (`ulimit -v`) where one is set; `None` when neither is known.
pub fn default_memory_limit() -> Option<u64> {
    let available = || -> Option<u64> {
        let s = std::fs::read_to_string("/proc/meminfo").ok()?;
        let line = s.lines().find(|l| l.starts_with("MemAvailable:"))?;
        let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kb * 1024 / 5 * 4)
    };
    match (available(), address_space_limit().map(|l| l / 2)) {
        (Some(a), Some(l)) => Some(a.min(l)),
        (a, l) => a.or(l),
    }
}

/// The process's address-space limit (`RLIMIT_AS`), when one is set.
fn address_space_limit() -> Option<u64> {
    #[cfg(unix)]
    {
        let mut r = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
        // SAFETY: getrlimit writes the limit into the struct we own and
        // reads nothing else of ours.
        let ok = unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut r) } == 0;
        (ok && r.rlim_cur != libc::RLIM_INFINITY).then_some(r.rlim_cur as u64)
    }
    #[cfg(not(unix))]
    None
}

/// Checks that refining `ct` once more (to level `level`) fits in `limit`
/// bytes and in 32-bit corner ids.
///
/// # Errors
/// [`Error::TooLarge`] with the predicted size.
pub fn check_level_fits(ct: &CornerTable, level: u32, limit: Option<u64>) -> Result<()> {
    check_levels_fit(ct, level.saturating_sub(1), 1, limit)
}

/// Checks, before any work, that refining `ct` (already at level `done`)
/// `more` more times fits in `limit` bytes and in 32-bit ids at every level.
/// Counts are predicted exactly: `F' = 4F`, `E' = 2E + 3F`, `V' = V + E`.
///
/// # Errors
/// [`Error::TooLarge`] naming the first level that does not fit.
pub fn check_levels_fit(ct: &CornerTable, done: u32, more: u32, limit: Option<u64>) -> Result<()> {
    let mut nt = ct.num_triangles() as u64;
    let mut nv = ct.num_vertices() as u64;
    let mut ne = (3 * nt + ct.num_border_edges() as u64) / 2;
    let limit_bytes = limit.unwrap_or(u64::MAX);
    for level in done + 1..=done + more {
        let bytes = predict_level_bytes(nt, nv, ne);
        let faces = 4 * nt;
        if 12 * nt >= u64::from(u32::MAX) || nv + ne >= u64::from(u32::MAX) || bytes > limit_bytes {
            let limit = limit_bytes.min(bytes.min(u64::MAX / 2));
            return Err(Error::TooLarge { level, faces, bytes, limit });
        }
        (nt, nv, ne) = (4 * nt, nv + ne, 2 * ne + 3 * nt);
    }
    Ok(())
}

/// Predicted triangle count after `levels` more levels.
pub fn predict_faces(ct: &CornerTable, levels: u32) -> u64 {
    (ct.num_triangles() as u64).saturating_mul(4u64.saturating_pow(levels))
}

pub(crate) fn ms(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1000.0
}

/// Runs `f` with the rules of `scheme` (static dispatch: every scheme's loops
/// are compiled separately and fully inlined).
pub(crate) fn with_rules<T>(scheme: Scheme, opts: &Options, f: impl RulesFn<T>) -> T {
    match scheme {
        Scheme::Midpoint => f.call(&midpoint::Midpoint),
        Scheme::Loop => f.call(&loop_::Loop::new(opts.loop_beta)),
        Scheme::Butterfly => f.call(&butterfly::Butterfly),
        Scheme::ModifiedButterfly => f.call(&modified_butterfly::ModifiedButterfly::new(opts.tension)),
        Scheme::Jarek => f.call(&jarek::Jarek),
    }
}

/// A generic callback over a [`Rules`] type (closures cannot be generic).
pub(crate) trait RulesFn<T> {
    fn call<R: Rules>(self, r: &R) -> T;
}

/// One level: split plus the scheme's points. `boundary` holds the input
/// level's vertex boundary flags when the previous level produced them;
/// the new level's are made only when another level follows (`last` false).
struct OneLevel<'a> {
    ct: Cow<'a, CornerTable>,
    positions: Cow<'a, [Vec3]>,
    boundary: Option<Vec<bool>>,
    last: bool,
    creasing: Creasing,
    stats: &'a mut Stats,
}

impl RulesFn<(Mesh, Option<Vec<bool>>)> for OneLevel<'_> {
    fn call<R: Rules>(self, r: &R) -> (Mesh, Option<Vec<bool>>) {
        let old: &CornerTable = &self.ct;
        let boundary = self.boundary.unwrap_or_else(|| rules::boundary_flags(old));
        let t0 = Instant::now();
        let ((ct, edges, next_boundary), (number_ms, _)) =
            split::split_with_boundary(old, (!self.last).then_some(&boundary[..]), self.creasing);
        self.stats.split_ms += ms(t0.elapsed());
        self.stats.numbering_ms += number_ms;
        let features = features::Features::of(old, self.creasing);
        let split::EdgeNumbering { owners, ids } = edges;
        let mut positions: Vec<Vec3> = crate::mem::zeroed(ct.num_vertices());
        let (vpart, epart) = positions.split_at_mut(old.num_vertices());
        let (vms, ems) = match features {
            None => r.apply(&Level::with_boundary(old, boundary), &owners, &self.positions, vpart, epart),
            Some(f) => features::apply(r, f, self.ct, self.positions, boundary, &owners, &ids, vpart, epart),
        };
        self.stats.vertex_ms += vms;
        self.stats.edge_ms += ems;
        (Mesh { ct, positions }, next_boundary)
    }
}

/// Refines `mesh` `levels` times with `scheme`.
///
/// # Errors
/// [`Error::TooLarge`] when a level would exceed the memory limit (checked
/// before it is allocated) or 32-bit corner ids.
pub fn subdivide(mesh: &Mesh, scheme: Scheme, levels: u32, opts: &Options) -> Result<(Mesh, Stats)> {
    subdivide_with_progress(mesh, scheme, levels, opts, |_, _| true)
}

/// [`subdivide`] calling `progress(level_done, levels)` after each level; if
/// it returns `false` the work stops and `Ok` holds the last finished level.
///
/// # Errors
/// See [`subdivide`].
pub fn subdivide_with_progress(
    mesh: &Mesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    mut progress: impl FnMut(u32, u32) -> bool,
) -> Result<(Mesh, Stats)> {
    let t0 = Instant::now();
    let limit = opts.max_memory.or_else(default_memory_limit);
    let mut stats = Stats::default();
    check_levels_fit(&mesh.ct, 0, levels, limit)?;
    let mut cur: Option<Mesh> = None;
    let mut boundary: Option<Vec<bool>> = None;
    let mut base = Some(features::with_boundary_corners(&mesh.ct, opts.boundary));
    for level in 1..=levels {
        // each level after the first owns (and may cut, see features::apply)
        // the one before it
        let (ct, positions) = match cur.take() {
            Some(m) => (Cow::Owned(m.ct), Cow::Owned(m.positions)),
            None => (base.take().unwrap_or(Cow::Borrowed(&mesh.ct)), Cow::Borrowed(&mesh.positions[..])),
        };
        let last = level == levels;
        let one =
            OneLevel { ct, positions, boundary: boundary.take(), last, creasing: opts.creasing, stats: &mut stats };
        let (next, next_boundary) = with_rules(scheme, opts, one);
        boundary = next_boundary;
        stats.faces_per_level.push(next.ct.num_triangles());
        cur = Some(next);
        if !progress(level, levels) {
            break;
        }
    }
    stats.total_ms = ms(t0.elapsed());
    Ok((cur.unwrap_or_else(|| mesh.clone()), stats))
}
