//! The vocabulary every part of subdivision shares: the [`Scheme`], the
//! [`Options`] of a subdivision and the [`Stats`] it reports. Kept apart
//! from the facade (`subdiv/mod.rs`) so that the rules and the refinement
//! import these, not the entry points built on them.

use super::rules::catmull_clark::TriangleSubdivision;
use super::rules::loop_::LoopBeta;
use super::rules::{Rules, butterfly, jarek, loop_, midpoint, modified_butterfly};
use crate::mesh::attributes::UvInterpolation;
use crate::mesh::{BoundaryInterpolation, Creasing};

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
    /// The scheme a file states (USD's `subdivisionScheme`); `None` for
    /// `none`: the cage is the surface, not subdivided.
    pub fn of_file(f: crate::mesh::FileScheme) -> Option<Scheme> {
        match f {
            crate::mesh::FileScheme::CatmullClark => Some(Scheme::CatmullClark),
            crate::mesh::FileScheme::Loop => Some(Scheme::Loop),
            crate::mesh::FileScheme::Bilinear => Some(Scheme::Bilinear),
            crate::mesh::FileScheme::None => None,
        }
    }

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

impl Options {
    /// These options with the ones a file states (its `t` tags, a USD
    /// prim's attributes) in their place, where it states them.
    pub fn with_file(self, file: crate::mesh::ShapeOptions) -> Options {
        Options {
            boundary: file.boundary.unwrap_or(self.boundary),
            uv: file.fvar.unwrap_or(self.uv),
            triangles: file.triangles.unwrap_or(self.triangles),
            creasing: file.creasing.unwrap_or(self.creasing),
            ..self
        }
    }
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
    /// Whether the large arrays were given 2 MiB pages (the page policy:
    /// by default while the host gives them cheaply, then 4 KiB pages);
    /// `None` in a record not made by a refinement.
    pub huge_pages: Option<bool>,
}

impl Stats {
    /// Closes the record of a call begun at `t0`.
    pub(crate) fn finish(&mut self, t0: crate::clock::Instant) {
        self.total_ms = ms(t0.elapsed());
        self.huge_pages = Some(crate::mem::huge_pages());
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
