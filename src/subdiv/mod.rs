//! Subdivision: the shared 1-to-4 split plus one file of rules per scheme,
//! in three layers as OpenSubdiv's `sdc`, `vtr` and `far`:
//!
//! - [`rules`]: the schemes' masks (what weights make a new point), sharp
//!   features' rules, limit masks; no tables, no timing;
//! - [`refine`]: one level after another, the split
//!   ([`crate::mesh::split`], which knows no scheme) and the rules applied
//!   to the new points, with the time of each phase;
//! - [`tables`]: the stencil plans that record the rules once for a
//!   topology and re-apply them to new control points (animation,
//!   attributes), and their packed form.
//!
//! A level = `split` (new V, O, C, valences; edge numbering) + edge points for
//! every edge + vertex points (Loop, Jarek) or a copy (interpolating schemes).
//! Every rule reads the old level only; output arrays are allocated once per
//! level with their exact sizes (`V' = V + E`, `F' = 4F`); the work is spread
//! over rayon's threads in chunks.

mod cage;
pub(crate) mod eval;
pub(crate) mod inspect;
pub(crate) mod pick;
mod precise;
pub(crate) mod refine;
mod refiner;
pub(crate) mod rules;
pub(crate) mod sizes;
pub(crate) mod stencil;
pub(crate) mod tables;

use crate::Result;
pub(crate) use crate::mem::default_memory_limit;
pub(crate) use crate::mesh::attributes::UvInterpolation;
use crate::mesh::poly::PolyMesh;
pub(crate) use crate::mesh::{BoundaryInterpolation, Creasing};
use crate::mesh::{Faces, Mesh, VertexId};
pub(crate) use refine::check_levels_fit;
use refine::{OneLevel, Refined};
use rules::{Rules, butterfly, catmull_clark, features, jarek, loop_, midpoint, modified_butterfly};
use std::borrow::Cow;
use std::time::Instant;

pub use cage::{Cage, subdivide, subdivide_f64, subdivide_faces};
pub(crate) use catmull_clark::TriangleSubdivision;
pub use loop_::LoopBeta;
pub use precise::{PlanF64, plan_f64};
pub use refiner::{Refiner, Scalar};
pub(crate) use sizes::ControlCounts;

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
    /// Catmull-Clark on polygons (approximating; quads from level 1 on).
    CatmullClark,
    /// Bilinear on polygons: every face split into quads at its edge
    /// midpoints and centroid, nothing moves.
    Bilinear,
}

impl Scheme {
    /// All schemes, in menu order.
    pub const ALL: [Scheme; 7] = [
        Scheme::Midpoint,
        Scheme::Loop,
        Scheme::Butterfly,
        Scheme::ModifiedButterfly,
        Scheme::Jarek,
        Scheme::CatmullClark,
        Scheme::Bilinear,
    ];
    /// The schemes of triangles (polygons are fanned for them).
    pub const TRIANGLE: [Scheme; 5] =
        [Scheme::Midpoint, Scheme::Loop, Scheme::Butterfly, Scheme::ModifiedButterfly, Scheme::Jarek];
    /// The schemes of polygons (they take faces of any size and make quads).
    pub const POLYGON: [Scheme; 2] = [Scheme::CatmullClark, Scheme::Bilinear];
    /// Whether the scheme works on polygons (Catmull-Clark, bilinear).
    pub fn is_polygonal(self) -> bool {
        matches!(self, Scheme::CatmullClark | Scheme::Bilinear)
    }
    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Scheme::Midpoint => "midpoint",
            Scheme::Loop => "loop",
            Scheme::Butterfly => "butterfly",
            Scheme::ModifiedButterfly => "modified-butterfly",
            Scheme::Jarek => "jarek",
            Scheme::CatmullClark => "catmull-clark",
            Scheme::Bilinear => "bilinear",
        }
    }
    /// Whether old vertices keep their positions.
    pub fn is_interpolating(self) -> bool {
        !matches!(self, Scheme::Loop | Scheme::Jarek | Scheme::CatmullClark)
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
            "catmull-clark" | "catmull_clark" | "catmark" | "cc" => Ok(Scheme::CatmullClark),
            "bilinear" => Ok(Scheme::Bilinear),
            _ => Err(format!(
                "unknown scheme '{s}' (expected one of: midpoint, loop, butterfly, modified-butterfly, jarek, catmull-clark, bilinear)"
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
    /// How the polygon schemes refine texture coordinates.
    pub uv: UvInterpolation,
    /// How Catmull-Clark refines triangles.
    pub triangles: TriangleSubdivision,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            loop_beta: LoopBeta::Loop,
            tension: 0.0,
            max_memory: None,
            creasing: Creasing::Uniform,
            boundary: BoundaryInterpolation::EdgeOnly,
            uv: UvInterpolation::Smooth,
            triangles: TriangleSubdivision::Catmark,
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
    pub(crate) fn then(mut self, later: Stats) -> Stats {
        self.split_ms += later.split_ms;
        self.numbering_ms += later.numbering_ms;
        self.edge_ms += later.edge_ms;
        self.vertex_ms += later.vertex_ms;
        self.total_ms += later.total_ms;
        self.faces_per_level.extend(later.faces_per_level);
        self
    }
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
        // the polygon schemes have no triangle rules: their callers go
        // through subdivide_poly; this arm is never reached by them
        Scheme::CatmullClark | Scheme::Bilinear => f.call(&midpoint::Midpoint),
    }
}

/// A generic callback over a [`Rules`] type (closures cannot be generic).
pub(crate) trait RulesFn<T> {
    fn call<R: Rules>(self, r: &R) -> T;
}

/// Refines `mesh` `levels` times with `scheme`.
///
/// # Errors
/// [`crate::Error::TooLarge`] when a level would exceed the memory limit (checked
/// before it is allocated) or 32-bit corner ids.
pub(crate) fn subdivide_mesh(mesh: &Mesh, scheme: Scheme, levels: u32, opts: &Options) -> Result<(Mesh, Stats)> {
    subdivide_with_progress(mesh, scheme, levels, opts, |_, _| true)
}

/// [`subdivide`] calling `progress(level_done, levels)` after each level; if
/// it returns `false` the work stops and `Ok` holds the last finished level.
///
/// # Errors
/// See [`subdivide`].
pub(crate) fn subdivide_with_progress(
    mesh: &Mesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    progress: impl FnMut(u32, u32) -> bool,
) -> Result<(Mesh, Stats)> {
    if scheme.is_polygonal() {
        // the polygons the mesh stands for (its hidden diagonals joined)
        let poly = PolyMesh::from_mesh(mesh);
        let (fine, stats) = subdivide_poly_with_progress(&poly, scheme, levels, opts, progress)?;
        return Ok((fine.triangulated(), stats));
    }
    // every level with its table: no faces-only last level, so no id map
    let (fine, stats) = refine_levels(mesh, scheme, levels, opts, None::<&fn(u32) -> u32>, progress)?;
    match fine {
        Refined::Table(m, _) => Ok((m, stats)),
        // refine_levels gives faces only when asked for them
        Refined::Faces(_) => unreachable!("refine_levels made faces without being asked"),
    }
}

/// [`subdivide_faces`] with every vertex id `j` of the faces written as
/// `id(j)`, in the pass that writes them: for a caller that wants other ids
/// (wider integers, its own numbering) without converting a `u32` table
/// afterwards, which at bunny level 3 would be 53 MB written, read and
/// freed. The positions are those of [`subdivide_faces`], in its order.
///
/// # Errors
/// As [`subdivide`].
pub(crate) fn subdivide_mesh_faces_as<I: VertexId>(
    mesh: &Mesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    id: impl Fn(u32) -> I + Sync,
) -> Result<(Faces<I>, Stats)> {
    if scheme.is_polygonal() {
        let (fine, stats) = subdivide(mesh, scheme, levels, opts)?;
        return Ok((Faces::of_mapped(&fine, id), stats));
    }
    let (fine, stats) = refine_levels(mesh, scheme, levels, opts, Some(&id), |_, _| true)?;
    Ok(match fine {
        Refined::Table(m, _) => Faces::of_mapped(&m, id),
        Refined::Faces(t) => t,
    })
    .map(|t| (t, stats))
}

/// The levels of a triangle scheme, the last one as faces only, its ids
/// through `faces_only`, when that is given (and the last level reached:
/// `progress` may stop the work earlier, after a level with its table).
fn refine_levels<I: VertexId, M: Fn(u32) -> I + Sync>(
    mesh: &Mesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    faces_only: Option<&M>,
    mut progress: impl FnMut(u32, u32) -> bool,
) -> Result<(Refined<I>, Stats)> {
    let t0 = Instant::now();
    let limit = opts.max_memory.or_else(default_memory_limit);
    let mut stats = Stats::default();
    check_levels_fit(&mesh.ct, 0, levels, limit)?;
    let mut cur: Option<Mesh> = None;
    let mut boundary: Option<Vec<bool>> = None;
    let mut base = Some(features::with_boundary_corners(&mesh.ct, opts.boundary));
    for level in 1..=levels {
        // each level after the first owns (and may cut, see refine::with_features)
        // the one before it
        let (ct, positions) = match cur.take() {
            Some(m) => (Cow::Owned(m.ct), Cow::Owned(m.positions)),
            None => (base.take().unwrap_or(Cow::Borrowed(&mesh.ct)), Cow::Borrowed(&mesh.positions[..])),
        };
        let last = level == levels;
        let (boundary_in, creasing) = (boundary.take(), opts.creasing);
        let one = OneLevel {
            ct,
            positions,
            boundary: boundary_in,
            last,
            faces_only: faces_only.filter(|_| last),
            creasing,
            stats: &mut stats,
        };
        match with_rules(scheme, opts, one) {
            Refined::Table(next, next_boundary) => {
                boundary = next_boundary;
                stats.faces_per_level.push(next.ct.num_triangles());
                cur = Some(next);
            }
            Refined::Faces(t) => {
                stats.faces_per_level.push(t.num_faces());
                stats.total_ms = ms(t0.elapsed());
                return Ok((Refined::Faces(t), stats));
            }
        }
        if !progress(level, levels) {
            break;
        }
    }
    stats.total_ms = ms(t0.elapsed());
    Ok((Refined::Table(cur.unwrap_or_else(|| mesh.clone()), None), stats))
}

/// Refines the polygon mesh `mesh` `levels` times with a polygon scheme
/// (Catmull-Clark or bilinear; a triangle scheme is an error: fan the
/// mesh and use [`subdivide`]).
///
/// # Errors
/// [`crate::Error::TooLarge`] when a level would exceed the memory limit or
/// 32-bit ids; [`crate::Error::Usage`] for a triangle scheme.
pub(crate) fn subdivide_poly(
    mesh: &PolyMesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<(PolyMesh, Stats)> {
    subdivide_poly_with_progress(mesh, scheme, levels, opts, |_, _| true)
}

/// [`subdivide_poly`] calling `progress(level_done, levels)` after each
/// level; if it returns `false` the work stops and `Ok` holds the last
/// finished level.
///
/// # Errors
/// See [`subdivide_poly`].
pub(crate) fn subdivide_poly_with_progress(
    mesh: &PolyMesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    mut progress: impl FnMut(u32, u32) -> bool,
) -> Result<(PolyMesh, Stats)> {
    if !scheme.is_polygonal() {
        return Err(crate::Error::Usage(format!("{scheme} subdivides triangles: fan the polygons first")));
    }
    let t0 = Instant::now();
    let limit = opts.max_memory.or_else(default_memory_limit);
    refine::poly::check_levels_fit(&mesh.pt, 0, levels, limit)?;
    let mut stats = Stats::default();
    let base = refine::poly::with_boundary_corners(&mesh.pt, opts.boundary)
        .map(|pt| PolyMesh { pt, positions: mesh.positions.clone() });
    let mut cur: Option<PolyMesh> = None;
    for level in 1..=levels {
        let from = cur.as_ref().or(base.as_ref()).unwrap_or(mesh);
        let next = match scheme {
            Scheme::Bilinear => refine::poly::level(&catmull_clark::Bilinear, from, opts.creasing, &mut stats),
            _ => refine::poly::level(&catmull_clark::CatmullClark::new(opts), from, opts.creasing, &mut stats),
        };
        stats.faces_per_level.push(next.pt.num_faces());
        cur = Some(next);
        if !progress(level, levels) {
            break;
        }
    }
    stats.total_ms = ms(t0.elapsed());
    Ok((cur.or(base).unwrap_or_else(|| mesh.clone()), stats))
}

/// [`subdivide_poly_faces`] with every vertex id `j` of the quads written
/// as `id(j)`, in the pass that writes them (see [`subdivide_faces_as`]).
///
/// # Errors
/// As [`subdivide_poly_faces`].
pub(crate) fn subdivide_poly_faces_as<I: VertexId>(
    mesh: &PolyMesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    id: impl Fn(u32) -> I + Sync,
) -> Result<(Faces<I>, Stats)> {
    if levels == 0 {
        return Err(crate::Error::Usage("faces alone come from at least one level (quads after it)".into()));
    }
    let limit = opts.max_memory.or_else(default_memory_limit);
    refine::poly::check_levels_fit(&mesh.pt, 0, levels, limit)?;
    // the levels before the last (none: the control mesh, its boundary's
    // corners tagged as subdivide_poly tags them), then the last one
    let (before, mut stats) = subdivide_poly(mesh, scheme, levels - 1, opts)?;
    let t0 = Instant::now();
    let fine = match scheme {
        Scheme::Bilinear => {
            refine::poly::level_faces(&catmull_clark::Bilinear, &before, (opts.creasing, &id), &mut stats)
        }
        _ => {
            let r = catmull_clark::CatmullClark::new(opts);
            refine::poly::level_faces(&r, &before, (opts.creasing, &id), &mut stats)
        }
    };
    stats.faces_per_level.push(fine.num_faces());
    stats.total_ms += ms(t0.elapsed());
    Ok((fine, stats))
}
