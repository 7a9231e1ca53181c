//! Exact evaluation of the Loop and Catmull-Clark limit surfaces at any
//! parameter point: position, first and second derivatives, unit normal,
//! mean, Gaussian and principal curvatures and directions
//! (docs/evaluation.md). [`Evaluator`] checks the points and groups them
//! by face; each scheme's evaluator, behind it, evaluates them: Loop's
//! (`loop_surface.rs`: control triangles, barycentric `(u, v)`, by power
//! tables near extraordinary vertices and local subdivision near sharp
//! features) and Catmull-Clark's (`catmark.rs`: ptex faces, `(u, v)` in
//! the unit square, by local subdivision). Both end each point in
//! `finish.rs`. Schemes other than Loop and Catmull-Clark are refused by
//! name.

pub(crate) mod catmark;
pub(crate) mod catmark_limit;
pub(crate) mod color;
mod extraordinary;
mod finish;
mod group;
mod level1;
mod local;
mod loop_surface;
mod patch;
mod points;
mod sector;
mod vertices;

pub use points::{Domain, EDGE_SLACK, parse_points_in};

#[cfg(test)]
pub(crate) use vertices::vertex_params;
pub use vertices::{poly_vertex_params, vertex_samples};

use crate::mesh::Mesh;
use crate::subdiv::{Options, Scheme};
use crate::{Error, Result};
use glam::DVec3;
use group::Grouped;
use loop_surface::LoopSurface;
use rayon::prelude::*;
use std::sync::atomic::Ordering;

/// The limit surface at one parameter point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Limit position.
    pub position: DVec3,
    /// Unit normal, on the side the face's winding makes its front.
    pub normal: DVec3,
    /// First derivatives with respect to `u` and `v`.
    pub du: DVec3,
    /// See `du`.
    pub dv: DVec3,
    /// Second derivatives `d2/du2`, `d2/dudv`, `d2/dv2`.
    pub duu: DVec3,
    /// See `duu`.
    pub duv: DVec3,
    /// See `duu`.
    pub dvv: DVec3,
    /// Mean curvature, positive where the surface bends away from its
    /// normal (a sphere with outward normals: `1/R`).
    pub mean: f64,
    /// Gaussian curvature (`1/R^2` on a sphere).
    pub gaussian: f64,
    /// Principal curvatures, `k1 >= k2` (same sign convention as `mean`).
    pub k1: f64,
    /// See `k1`.
    pub k2: f64,
    /// Unit principal directions of `k1` and `k2` (tangent to the surface).
    pub dir1: DVec3,
    /// See `dir1`.
    pub dir2: DVec3,
}

impl Default for Sample {
    /// [`Sample::NAN`].
    fn default() -> Self {
        Sample::NAN
    }
}

impl Sample {
    /// Position, unit normal, mean and Gaussian curvature: a line of
    /// `subdiv eval --curvature` (without it, the first six).
    pub(crate) fn row(&self) -> [f64; 8] {
        let (p, n) = (self.position, self.normal);
        [p.x, p.y, p.z, n.x, n.y, n.z, self.mean, self.gaussian]
    }

    /// Every field NaN.
    pub const NAN: Sample = Sample {
        position: DVec3::NAN,
        normal: DVec3::NAN,
        du: DVec3::NAN,
        dv: DVec3::NAN,
        duu: DVec3::NAN,
        duv: DVec3::NAN,
        dvv: DVec3::NAN,
        mean: f64::NAN,
        gaussian: f64::NAN,
        k1: f64::NAN,
        k2: f64::NAN,
        dir1: DVec3::NAN,
        dir2: DVec3::NAN,
    };
}

/// Evaluates the Loop or Catmull-Clark limit surface of one control mesh at
/// any point (Loop: control triangles; Catmull-Clark: ptex faces).
pub struct Evaluator {
    surface: Surface,
}

/// The scheme's evaluator behind an [`Evaluator`].
enum Surface {
    /// Loop: control triangles.
    Loop(Box<LoopSurface>),
    /// Catmull-Clark: the control polygons, points on their ptex faces.
    CatmullClark(Box<catmark::Poly>),
}

/// What [`Evaluator`] asks of a scheme's evaluator: the check of a point
/// on its domain and the evaluation of checked points.
trait Limit: Sync {
    /// The number of control faces.
    fn faces(&self) -> usize;

    /// Whether control face `f` can be evaluated.
    fn accepts(&self, f: usize) -> bool;

    /// Whether [`Limit::check`] passes the point (without making its
    /// error).
    fn fits(&self, f: usize, u: f64, v: f64) -> bool;

    /// A point that [`Limit::fits`] as [`Limit::check`] passes it on.
    fn onto_domain(&self, u: f64, v: f64) -> (f64, f64);

    /// `(u, v)` if face `f` and the point are good, scaled onto the edge when
    /// `u + v` is a hair over 1.
    fn check(&self, f: usize, u: f64, v: f64) -> Result<(f64, f64)>;

    /// A point [`Limit::check`] passed.
    fn eval_checked(&self, f: usize, uv: (f64, f64), second: bool) -> Sample;

    /// The points `sorted` (grouped by face, each passed by
    /// [`Limit::check`]) in parallel, each sample mapped by `keep`, in the
    /// order of `sorted` (by default each point on its own; a scheme may
    /// share work between consecutive points of a face).
    fn eval_sorted<T: Send>(
        &self,
        sorted: &[(usize, (f64, f64))],
        second: bool,
        keep: impl Fn(&Sample) -> T + Sync,
    ) -> Vec<T> {
        in_parallel(sorted, || (), |_, f, uv| keep(&self.eval_checked(f, uv, second)))
    }
}

/// `eval` of each point of `sorted` in parallel, in order, each thread
/// keeping a state made by `init` from one of its points to the next (what
/// consecutive points of a face share).
fn in_parallel<C, T: Send>(
    sorted: &[(usize, (f64, f64))],
    init: impl Fn() -> C + Sync + Send,
    eval: impl Fn(&mut C, usize, (f64, f64)) -> T + Sync + Send,
) -> Vec<T> {
    sorted.par_iter().with_min_len(256).map_init(init, |state, &(f, uv)| eval(state, f, uv)).collect()
}

/// Refuses a scheme without an exact evaluation, naming it.
fn check_scheme(scheme: Scheme) -> Result<()> {
    if matches!(scheme, Scheme::Loop | Scheme::CatmullClark) {
        return Ok(());
    }
    let why = if scheme.is_interpolating() {
        "an interpolating scheme has no closed-form limit to evaluate"
    } else {
        "exact evaluation exists for Loop and Catmull-Clark"
    };
    Err(Error::Usage(format!("cannot evaluate the {scheme} limit surface: {why}")))
}

/// The limit of `mesh` at one point `(f, u, v)`, preparing only what that
/// face needs (Loop: the tables of its corners' valences, no level 1 of the
/// whole mesh; Catmull-Clark: a copy of the control polygons): for one
/// query on a large mesh, such as a pick. Every face goes
/// the way [`Evaluator`] takes the faces at a sharp feature (local
/// subdivision), so the result equals [`Evaluator::eval`]'s to rounding
/// (the rules' weights are single precision).
///
/// # Errors
/// As [`Evaluator::new`] and [`Evaluator::eval`].
pub fn evaluate_one(mesh: &Mesh, scheme: Scheme, opts: &Options, at: (usize, f64, f64)) -> Result<Sample> {
    let pos: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    evaluate_one_f64(mesh, &pos, scheme, opts, at)
}

/// [`evaluate_one`] from the f64 control points `control` (one per vertex
/// of `mesh`; `mesh.positions` are not read).
///
/// # Errors
/// As [`evaluate_one`]; `control` not one position per vertex.
pub(crate) fn evaluate_one_f64(
    mesh: &Mesh,
    control: &[DVec3],
    scheme: Scheme,
    opts: &Options,
    (f, u, v): (usize, f64, f64),
) -> Result<Sample> {
    check_scheme(scheme)?;
    if scheme == Scheme::CatmullClark || control.len() != mesh.positions.len() {
        return Evaluator::new_f64(mesh, control, scheme, opts)?.eval(f, u, v);
    }
    loop_surface::evaluate_one(mesh, control, opts, (f, u, v))
}

impl Evaluator {
    /// Prepares `mesh` for evaluation under `scheme` and `opts`
    /// ([`Scheme::Loop`], `opts.loop_beta` choosing its weights, or
    /// [`Scheme::CatmullClark`] on the polygons the mesh stands for).
    ///
    /// # Errors
    /// [`Error::Usage`] naming a scheme without an exact evaluation.
    pub fn new(mesh: &Mesh, scheme: Scheme, opts: &Options) -> Result<Evaluator> {
        let pos: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        Evaluator::new_f64(mesh, &pos, scheme, opts)
    }

    /// [`Evaluator::new`] with the control positions in f64 (`control`, one
    /// per vertex of `mesh`; `mesh.positions` are not read): double
    /// precision from the caller's own digits, where `new` starts from f32.
    ///
    /// # Errors
    /// As [`Evaluator::new`]; `control` not one position per vertex.
    pub fn new_f64(mesh: &Mesh, control: &[DVec3], scheme: Scheme, opts: &Options) -> Result<Evaluator> {
        check_scheme(scheme)?;
        if control.len() != mesh.positions.len() {
            let n = mesh.positions.len();
            return Err(Error::Usage(format!("{} control positions for a mesh of {n} vertices", control.len())));
        }
        let surface = if scheme == Scheme::CatmullClark {
            let poly = crate::mesh::poly::PolyMesh::from_mesh(mesh);
            Surface::CatmullClark(Box::new(catmark::Poly::new(&poly, control.to_vec(), opts)))
        } else {
            Surface::Loop(Box::new(LoopSurface::new(mesh, control, opts)?))
        };
        Ok(Evaluator { surface })
    }

    /// [`Evaluator::new`] for a polygon mesh: Catmull-Clark, points on its
    /// ptex faces ([`catmark::ptex_faces`]).
    ///
    /// # Errors
    /// [`Error::Usage`] naming a scheme other than Catmull-Clark.
    pub(crate) fn new_poly(mesh: &crate::mesh::poly::PolyMesh, scheme: Scheme, opts: &Options) -> Result<Evaluator> {
        check_scheme(scheme)?;
        if scheme != Scheme::CatmullClark {
            return Err(Error::Usage(format!("the {scheme} limit surface is evaluated on triangles, not polygons")));
        }
        let pos = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let poly = catmark::Poly::new(mesh, pos, opts);
        Ok(Evaluator { surface: Surface::CatmullClark(Box::new(poly)) })
    }

    /// The number of control faces (Loop: triangles; Catmull-Clark: ptex
    /// faces).
    pub fn num_faces(&self) -> usize {
        match &self.surface {
            Surface::Loop(s) => s.faces(),
            Surface::CatmullClark(s) => s.faces(),
        }
    }

    /// Where the points of this evaluator live.
    pub fn domain(&self) -> Domain {
        match &self.surface {
            Surface::Loop(s) => Domain::Triangles(s.faces()),
            Surface::CatmullClark(s) => Domain::Ptex(s.faces()),
        }
    }

    /// Whether control face `f` can be evaluated (every face but those
    /// touching an interior vertex of valence 2).
    pub fn accepts(&self, f: usize) -> bool {
        match &self.surface {
            Surface::Loop(s) => s.accepts(f),
            Surface::CatmullClark(s) => s.accepts(f),
        }
    }

    /// The limit surface at `(f, u, v)`: everything [`Sample`] holds.
    ///
    /// # Errors
    /// [`Error::Usage`] for a face out of range or refused, or a parameter
    /// outside the triangle (`u, v >= 0`, `u + v <= 1 + 1e-6`, finite).
    pub fn eval(&self, f: usize, u: f64, v: f64) -> Result<Sample> {
        self.eval_with(f, u, v, true)
    }

    /// [`Evaluator::eval`] without the second derivatives and curvatures
    /// (NaN in the sample): position, normal and first derivatives, at
    /// about half the cost.
    ///
    /// # Errors
    /// As [`Evaluator::eval`].
    pub fn eval_first(&self, f: usize, u: f64, v: f64) -> Result<Sample> {
        self.eval_with(f, u, v, false)
    }

    fn eval_with(&self, f: usize, u: f64, v: f64, second: bool) -> Result<Sample> {
        match &self.surface {
            Surface::Loop(s) => eval_one(&**s, (f, u, v), second),
            Surface::CatmullClark(s) => eval_one(&**s, (f, u, v), second),
        }
    }
}

/// The point `(f, u, v)` of `surface`, checked first.
fn eval_one(surface: &impl Limit, (f, u, v): (usize, f64, f64), second: bool) -> Result<Sample> {
    let uv = surface.check(f, u, v)?;
    Ok(surface.eval_checked(f, uv, second))
}

impl Evaluator {
    /// Every point of `points`, in parallel, with the second derivatives and
    /// curvatures when `second`. The points are checked first: the first
    /// bad one is refused, naming it, before any is evaluated.
    ///
    /// # Errors
    /// As [`Evaluator::eval`], naming the point's index.
    pub fn eval_all(&self, points: &[(usize, f64, f64)], second: bool) -> Result<Vec<Sample>> {
        self.eval_map(points, second, |s| *s)
    }

    /// [`Evaluator::eval_all`] kept small: each sample mapped by `keep` (say
    /// to the position and normal) as soon as it is made. The points are
    /// evaluated grouped by face (a counting sort), so that the points of
    /// one level-1 face share its support and, when it is regular, its
    /// polynomial (made once, not per point), and the kept values are put
    /// back in the order of `points`.
    ///
    /// # Errors
    /// As [`Evaluator::eval_all`].
    pub fn eval_map<T: Copy + Send + Sync>(
        &self,
        points: &[(usize, f64, f64)],
        second: bool,
        keep: impl Fn(&Sample) -> T + Sync,
    ) -> Result<Vec<T>> {
        match &self.surface {
            Surface::Loop(s) => map_grouped(&**s, points, second, keep),
            Surface::CatmullClark(s) => map_grouped(&**s, points, second, keep),
        }
    }

    /// The first `N` columns of `Sample::row` at every point (six:
    /// position and normal; eight: with the curvatures, when `second`), as
    /// [`Evaluator::eval_map`] keeps them: the rows `subdiv eval` writes.
    ///
    /// # Errors
    /// As [`Evaluator::eval_all`].
    pub fn eval_rows<const N: usize>(&self, points: &[(usize, f64, f64)], second: bool) -> Result<Vec<[f64; N]>> {
        const { assert!(N <= 8, "a row has eight columns") };
        self.eval_map(points, second, |s| {
            let row = s.row();
            std::array::from_fn(|k| row[k])
        })
    }
}

/// [`Evaluator::eval_map`] on `surface`: the points checked and grouped by
/// face, evaluated, and the kept values put back in the order of `points`.
fn map_grouped<T: Copy + Send + Sync>(
    surface: &impl Limit,
    points: &[(usize, f64, f64)],
    second: bool,
    keep: impl Fn(&Sample) -> T + Sync,
) -> Result<Vec<T>> {
    let Grouped { sorted, rank } = by_face(surface, points)?;
    let done: Vec<T> = surface.eval_sorted(&sorted, second, keep);
    Ok(rank.par_iter().map(|r| done[r.load(Ordering::Relaxed)]).collect())
}

/// The points checked (the first bad one refused, naming it) and
/// grouped by face (`group.rs`).
fn by_face(surface: &impl Limit, points: &[(usize, f64, f64)]) -> Result<Grouped> {
    let fits = |&(f, u, v): &(usize, f64, f64)| surface.fits(f, u, v);
    group::by_face(points, surface.faces(), fits, |u, v| surface.onto_domain(u, v)).map_err(|i| {
        let (f, u, v) = points[i];
        let why = surface.check(f, u, v).err().map(|e| e.to_string()).unwrap_or_default();
        Error::Usage(format!("point {}: {why}", i + 1))
    })
}

#[cfg(test)]
mod tests;
