//! Exact evaluation of the Loop and Catmull-Clark limit surfaces at any
//! parameter point: position, first and second derivatives, unit normal,
//! mean, Gaussian and principal curvatures and directions
//! (docs/evaluation.md). Catmull-Clark points are ptex faces with `(u, v)`
//! in the unit square, evaluated by local subdivision (`catmark.rs`); the
//! rest of these notes are Loop's.
//!
//! A point is `(f, u, v)`: control triangle `f` and the barycentric point
//! `(1 - u - v) c0 + u c1 + v c2` of its corners in the order the file lists
//! them. The method (Stam, "Evaluation of Loop Subdivision Surfaces", 1998,
//! with his eigen decomposition replaced by an exact power table):
//!
//! 1. `level1.rs`: one Loop step in f64 isolates the extraordinary vertices,
//!    so each child face has at most one;
//! 2. a child face whose three vertices have valence 6 is a regular patch,
//!    the quartic box spline of 12 points (`patch.rs`);
//! 3. a child face with one extraordinary vertex is subdivided towards it
//!    `m` times, `m = floor(-log2(u + v))` in its corner's coordinates,
//!    through the power table of its valence (`extraordinary.rs`): at most
//!    11 matrix-vector products however close the point is; the point then
//!    lies on one of three regular patches;
//! 4. at the extraordinary vertex itself: its limit position and the
//!    normal of its tangent masks (the derivatives there are 0 or infinite
//!    and the curvature undefined: those fields are NaN).
//!
//! That path serves the faces whose three control vertices are interior
//! and carry no sharp feature (no sharp incident edge, no sharp vertex).
//! A face touching a boundary, a crease of any sharpness or a sharp vertex
//! is evaluated by local subdivision with the library's own rules until
//! the point lies on a regular patch (a box spline, with phantom points
//! beyond a border or an infinitely sharp crease) or next to a smooth
//! extraordinary vertex (`local.rs`). Only a face touching an interior
//! vertex of valence 2 (two triangles back to back) is refused, with an
//! error naming it. Schemes other than Loop and Catmull-Clark are refused
//! by name.

pub(crate) mod catmark;
pub(crate) mod catmark_limit;
pub(crate) mod color;
mod extraordinary;
mod group;
mod level1;
mod local;
mod patch;
mod points;
mod sector;
mod vertices;

pub use points::{Domain, EDGE_SLACK, parse_points_in};

pub use vertices::{poly_vertex_params, vertex_samples};

use crate::mesh::{Mesh, n, p};
use crate::subdiv::{Options, Scheme};
use crate::{Error, Result};
use extraordinary::Extraordinary;
use glam::DVec3;
use group::Grouped;
use level1::{BLOCK, Level1, REGULAR, Template};
use patch::{BoxSpline, Jet, Poly};
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

/// An affine map of parameters `(s, t) = J (u, v) + b`.
#[derive(Clone, Copy, Debug)]
struct Affine {
    j: [[f64; 2]; 2],
    b: [f64; 2],
}

impl Affine {
    const IDENTITY: Affine = Affine { j: [[1.0, 0.0], [0.0, 1.0]], b: [0.0, 0.0] };
    fn apply(&self, (u, v): (f64, f64)) -> (f64, f64) {
        (self.j[0][0] * u + self.j[0][1] * v + self.b[0], self.j[1][0] * u + self.j[1][1] * v + self.b[1])
    }
    /// `self` after `first`: the linear parts only (derivatives need no more).
    fn after(&self, first: &Affine) -> [[f64; 2]; 2] {
        let (a, b) = (&self.j, &first.j);
        let m = |i: usize, k: usize| a[i][0] * b[0][k] + a[i][1] * b[1][k];
        [[m(0, 0), m(0, 1)], [m(1, 0), m(1, 1)]]
    }
}

/// The four children of a triangle (`level1` module docs): child `k` and
/// the map from the parent's `(u, v)` to the child's.
fn child_of((u, v): (f64, f64), corner: bool) -> (usize, Affine) {
    let a = |j, b| Affine { j, b };
    if corner && u + v <= 0.5 {
        (0, a([[2.0, 0.0], [0.0, 2.0]], [0.0, 0.0]))
    } else if u >= 0.5 {
        (1, a([[2.0, 0.0], [0.0, 2.0]], [-1.0, 0.0]))
    } else if v >= 0.5 {
        (2, a([[2.0, 0.0], [0.0, 2.0]], [0.0, -1.0]))
    } else {
        (3, a([[2.0, 2.0], [-2.0, 0.0]], [-1.0, 1.0]))
    }
}

/// The map that makes corner `i` of a triangle its corner 0 (the corners
/// rotated to `(c_i, c_{i+1}, c_{i+2})`).
fn rotation(i: usize) -> Affine {
    match i {
        1 => Affine { j: [[0.0, 1.0], [-1.0, -1.0]], b: [0.0, 1.0] },
        2 => Affine { j: [[-1.0, -1.0], [1.0, 0.0]], b: [1.0, 0.0] },
        _ => Affine::IDENTITY,
    }
}

/// Supports up to this size live on the stack (valence 18).
const STACK_POINTS: usize = 24;

/// Evaluates the Loop limit surface of one control mesh at any point.
pub struct Evaluator {
    level1: Level1,
    /// How each control face is evaluated.
    path: Vec<Path>,
    /// Catmull-Clark: the control polygons (every other field is empty).
    poly: Option<Box<catmark::Poly>>,
    /// The control mesh for the faces of [`Path::Local`] (`None` if none).
    base: Option<local::Base<'static>>,
    spline: BoxSpline,
    /// The tables of each extraordinary valence present, by valence.
    valences: Vec<Option<Extraordinary>>,
    faces: usize,
}

/// How a control face is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Path {
    /// Its level-1 children and the power tables.
    Smooth,
    /// Local subdivision (a boundary or sharp feature at a corner).
    Local,
    /// Not at all (an interior vertex of valence 2 at a corner).
    Refused,
}

/// The path of each control face, from what its corners carry.
fn face_paths(mesh: &Mesh) -> Vec<Path> {
    let ct = &mesh.ct;
    let mut at = vec![Path::Smooth; ct.num_vertices()];
    for c in 0..ct.num_corners() as u32 {
        if ct.edge_sharpness(c) > 0.0 {
            at[ct.vtx(n(c)) as usize] = Path::Local;
            at[ct.vtx(p(c)) as usize] = Path::Local;
        }
    }
    if let Some(sharp) = ct.sharpness() {
        for &(v, s) in sharp.sharp_vertices() {
            if s > 0.0 {
                at[v as usize] = at[v as usize].max(Path::Local);
            }
        }
    }
    for (v, path) in at.iter_mut().enumerate() {
        if refused_vertex(ct, v as u32) {
            *path = Path::Refused;
        }
    }
    (0..ct.num_triangles())
        .map(|f| (0..3).map(|i| at[ct.vtx(3 * f as u32 + i) as usize]).max().unwrap_or(Path::Smooth))
        .collect()
}

/// An interior vertex of valence 2 (two triangles back to back) has no
/// smooth limit patch.
fn refused_vertex(ct: &crate::mesh::CornerTable, v: u32) -> bool {
    ct.valence(v) < 3 && !ct.is_boundary_vertex(v)
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

/// `(u, v)` if face `f` (of `faces`) and the point are good, scaled onto
/// the edge when `u + v` is a hair over 1.
fn check_point(faces: usize, f: usize, u: f64, v: f64) -> Result<(f64, f64)> {
    if f >= faces {
        return Err(Error::Usage(format!("face {f} out of range (the mesh has {faces} faces)")));
    }
    if !in_triangle(u, v) {
        return Err(Error::Usage(format!("({u}, {v}) is not in the triangle (u, v >= 0, u + v <= 1)")));
    }
    Ok(onto_triangle(u, v))
}

/// `u, v >= 0`, `u + v <= 1` with [`EDGE_SLACK`] (false for NaN).
#[inline]
fn in_triangle(u: f64, v: f64) -> bool {
    u >= 0.0 && v >= 0.0 && u + v <= 1.0 + EDGE_SLACK
}

/// A point [`in_triangle`] scaled onto the edge when `u + v` is a hair
/// over 1.
#[inline]
fn onto_triangle(u: f64, v: f64) -> (f64, f64) {
    let s = u + v;
    if s > 1.0 { (u / s, v / s) } else { (u, v) }
}

/// `u` and `v` in `[0, 1]` with [`EDGE_SLACK`] (false for NaN).
#[inline]
fn in_square(u: f64, v: f64) -> bool {
    let unit = 0.0..=1.0 + EDGE_SLACK;
    unit.contains(&u) && unit.contains(&v)
}

/// [`check_point`] for a ptex face's unit square.
fn check_square(faces: usize, f: usize, u: f64, v: f64) -> Result<(f64, f64)> {
    if f >= faces {
        return Err(Error::Usage(format!("ptex face {f} out of range (the mesh has {faces})")));
    }
    if !in_square(u, v) {
        return Err(Error::Usage(format!("({u}, {v}) is not in the unit square")));
    }
    Ok((u.min(1.0), v.min(1.0)))
}

fn valence_two(f: usize) -> Error {
    Error::Usage(format!(
        "face {f} touches an interior vertex of valence 2 (two triangles back to back), which has no limit patch"
    ))
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
pub fn evaluate_one(mesh: &Mesh, scheme: Scheme, opts: &Options, (f, u, v): (usize, f64, f64)) -> Result<Sample> {
    check_scheme(scheme)?;
    if scheme == Scheme::CatmullClark {
        return Evaluator::new(mesh, scheme, opts)?.eval(f, u, v);
    }
    let ct = &mesh.ct;
    let (u, v) = check_point(ct.num_triangles(), f, u, v)?;
    let corners = [0, 1, 2].map(|i| ct.vtx(3 * f as u32 + i));
    if corners.iter().any(|&x| refused_vertex(ct, x)) {
        return Err(valence_two(f));
    }
    let spline = BoxSpline::derive();
    let mut valences: Vec<Option<Extraordinary>> = Vec::new();
    for x in corners {
        add_table(&mut valences, ct.valence(x), ct.is_boundary_vertex(x), opts, &spline);
    }
    let pos: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    let base = local::Base::borrowed(mesh, &pos, opts);
    let tables = local::Tables { spline: &spline, valences: &valences };
    Ok(local::eval(&base, &tables, f as u32, (u, v), true))
}

/// The power table of an interior extraordinary valence `k`, once.
fn add_table(valences: &mut Vec<Option<Extraordinary>>, k: u32, boundary: bool, opts: &Options, spline: &BoxSpline) {
    if k != 6 && k >= 3 && !boundary {
        if valences.len() <= k as usize {
            valences.resize(k as usize + 1, None);
        }
        valences[k as usize].get_or_insert_with(|| Extraordinary::new(k, opts.loop_beta, spline));
    }
}

impl Evaluator {
    /// Prepares `mesh` for evaluation under `scheme` and `opts` (only
    /// [`Scheme::Loop`] has an exact evaluation here; `opts.loop_beta`
    /// chooses its weights).
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
        if scheme == Scheme::CatmullClark {
            let poly = crate::mesh::poly::PolyMesh::from_mesh(mesh);
            return Ok(Evaluator::of_poly(catmark::Poly::new(&poly, control.to_vec(), opts)));
        }
        let path = face_paths(mesh);
        let mut level1 = Level1::new(mesh, control, opts.loop_beta)?;
        level1.learn_templates(|f| path[f] == Path::Smooth);
        let base = path.contains(&Path::Local).then(|| local::Base::new(mesh, control, opts));
        let spline = BoxSpline::derive();
        let mut valences: Vec<Option<Extraordinary>> = Vec::new();
        // every smooth extraordinary vertex of any level is a control vertex
        // of the same valence (an edge vertex inside has valence 6)
        for v in 0..mesh.ct.num_vertices() as u32 {
            add_table(&mut valences, mesh.ct.valence(v), mesh.ct.is_boundary_vertex(v), opts, &spline);
        }
        Ok(Evaluator { level1, path, poly: None, base, spline, valences, faces: mesh.ct.num_triangles() })
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
        Ok(Evaluator::of_poly(catmark::Poly::new(mesh, pos, opts)))
    }

    /// The evaluator of Catmull-Clark's polygons `poly`.
    fn of_poly(poly: catmark::Poly) -> Evaluator {
        let faces = poly.num_faces();
        Evaluator {
            level1: Level1::default(),
            path: vec![Path::Local; faces],
            poly: Some(Box::new(poly)),
            base: None,
            spline: BoxSpline::derive(),
            valences: Vec::new(),
            faces,
        }
    }

    /// The number of control faces (Loop: triangles; Catmull-Clark: ptex
    /// faces).
    pub fn num_faces(&self) -> usize {
        self.faces
    }

    /// Where the points of this evaluator live.
    pub fn domain(&self) -> Domain {
        if self.poly.is_some() { Domain::Ptex(self.faces) } else { Domain::Triangles(self.faces) }
    }

    /// Whether control face `f` can be evaluated (every face but those
    /// touching an interior vertex of valence 2).
    pub fn accepts(&self, f: usize) -> bool {
        self.path.get(f).is_some_and(|&x| x != Path::Refused)
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
        let (u, v) = self.check(f, u, v)?;
        Ok(self.eval_checked(f, u, v, second))
    }

    /// `(u, v)` if face `f` and the point are good, scaled onto the edge when
    /// `u + v` is a hair over 1.
    fn check(&self, f: usize, u: f64, v: f64) -> Result<(f64, f64)> {
        if self.fits(f, u, v) {
            return Ok(self.onto_domain(u, v));
        }
        // why it does not fit: the domain's own check, else the face
        let domain =
            if self.poly.is_some() { check_square(self.faces, f, u, v) } else { check_point(self.faces, f, u, v) };
        Err(domain.err().unwrap_or_else(|| valence_two(f)))
    }

    /// Whether [`Evaluator::check`] passes the point (without making its
    /// error).
    #[inline]
    fn fits(&self, f: usize, u: f64, v: f64) -> bool {
        if self.poly.is_some() {
            return f < self.faces && in_square(u, v);
        }
        f < self.faces && in_triangle(u, v) && self.path[f] != Path::Refused
    }

    /// A point that [`Evaluator::fits`] as [`Evaluator::check`] passes it on.
    #[inline]
    fn onto_domain(&self, u: f64, v: f64) -> (f64, f64) {
        if self.poly.is_some() { (u.min(1.0), v.min(1.0)) } else { onto_triangle(u, v) }
    }

    /// A point [`Evaluator::check`] passed.
    fn eval_checked(&self, f: usize, u: f64, v: f64, second: bool) -> Sample {
        self.eval_cached(f, u, v, second, None)
    }

    /// [`Evaluator::eval_checked`], taking the level-1 face's polynomial or
    /// support from `cache` when it holds it (and leaving it there).
    #[inline]
    fn eval_cached<'a>(&'a self, f: usize, u: f64, v: f64, second: bool, cache: Option<&mut ChildCache<'a>>) -> Sample {
        if let Some(poly) = &self.poly {
            return poly.eval(f, (u, v), second);
        }
        if let (Path::Local, Some(base)) = (self.path[f], &self.base) {
            let tables = local::Tables { spline: &self.spline, valences: &self.valences };
            return local::eval(base, &tables, f as u32, (u, v), second);
        }
        let (k, map) = child_of((u, v), true);
        let face = 4 * f as u32 + k as u32;
        let st = map.apply((u, v));
        let mut one;
        let child = match cache {
            Some(cache) => cache.get(self, f, k),
            None => {
                one = Child::EMPTY;
                self.fill(face, &mut one);
                &one
            }
        };
        if child.corner == REGULAR {
            let jet = child.poly.jet(st.0, st.1, second);
            return finish(&jet, DVec3::ZERO, 1.0, map.j, 1.0, second);
        }
        self.near_corner(child, st, map, second)
    }

    /// [`Evaluator::eval_cached`] on a level-1 face `child` with an
    /// extraordinary corner, at its `st` (`map` from the control face's).
    #[inline(never)]
    fn near_corner(&self, child: &Child, st: (f64, f64), map: Affine, second: bool) -> Sample {
        let support = child.support();
        let len = support.len();
        let mut stack = [DVec3::ZERO; 2 * STACK_POINTS];
        let mut heap = Vec::new();
        let buf: &mut [DVec3] = if 2 * len <= stack.len() {
            &mut stack
        } else {
            heap.resize(2 * len, DVec3::ZERO);
            &mut heap
        };
        let (pts, tmp) = buf.split_at_mut(len);
        pts.copy_from_slice(support);
        let table = self.valences[len - 6].as_ref().unwrap_or_else(|| unreachable!("tables of every valence"));
        near_vertex(table, (pts, &mut tmp[..len]), st, (rotation(child.corner.into()), map), second)
    }

    /// Makes `c` level-1 face `g`'s: its support (read through its control
    /// face's block template where there is one, walked on level 1
    /// otherwise), and its polynomial when it is regular.
    fn fill(&self, g: u32, c: &mut Child) {
        let mut ids = [0u32; BLOCK];
        let block = self.level1.block(g / 4, &mut ids);
        if let Some(t) = block.and_then(|(key, _)| self.level1.template(key)) {
            let at = |i: usize| self.level1.point(ids[i]);
            return self.fill_from(g, c, at, &t.children[(g % 4) as usize]);
        }
        let (corner, len) = self.level1.shape(g);
        (c.g, c.corner, c.len) = (g, corner, len);
        if len > STACK_POINTS {
            c.big.resize(len, DVec3::ZERO);
            self.level1.support(g, corner, &mut c.big);
        } else {
            self.level1.support(g, corner, &mut c.small[..len]);
        }
        self.fit(c);
    }

    /// [`Evaluator::fill`] with the support read through the template
    /// entry `(corner, places)` of `g`'s control face, `at(i)` the point
    /// at place `i` of the face's block.
    #[inline]
    fn fill_from(&self, g: u32, c: &mut Child, at: impl Fn(usize) -> DVec3, (corner, places): &(u8, Vec<u8>)) {
        (c.g, c.corner, c.len) = (g, *corner, places.len());
        // a template exists only for valences below TEMPLATE_VALENCE, so
        // the support fits `small`
        for (o, &i) in c.small.iter_mut().zip(places) {
            *o = at(usize::from(i));
        }
        self.fit(c);
    }

    /// The polynomial of `c` when it is regular.
    fn fit(&self, c: &mut Child) {
        if c.corner == REGULAR {
            c.poly = patch::coefficients(&self.spline.basis, &c.small[..12]);
        }
    }
}

/// What the points of one level-1 face share: its support (walk order
/// from its extraordinary corner) and, when it is regular, its box spline.
struct Child {
    /// The level-1 face (`u32::MAX`: none yet).
    g: u32,
    corner: u8,
    len: usize,
    small: [DVec3; STACK_POINTS],
    /// The support when it is longer than `small`.
    big: Vec<DVec3>,
    poly: Poly,
}

impl Child {
    const EMPTY: Child = Child {
        g: u32::MAX,
        corner: REGULAR,
        len: 0,
        small: [DVec3::ZERO; STACK_POINTS],
        big: Vec::new(),
        poly: Poly([DVec3::ZERO; 15]),
    };

    fn support(&self) -> &[DVec3] {
        if self.len > STACK_POINTS { &self.big } else { &self.small[..self.len] }
    }
}

/// The control face met last and its level-1 faces, one slot per child
/// position: consecutive points of one control face share them.
struct ChildCache<'a> {
    /// The control face whose block `block` holds (`usize::MAX`: none).
    face: usize,
    /// The template of that block, if it has one.
    template: Option<&'a Template>,
    block: [DVec3; BLOCK],
    slots: [Child; 4],
}

impl<'a> ChildCache<'a> {
    fn new() -> ChildCache<'a> {
        ChildCache {
            face: usize::MAX,
            template: None,
            block: [DVec3::ZERO; BLOCK],
            slots: [Child::EMPTY, Child::EMPTY, Child::EMPTY, Child::EMPTY],
        }
    }

    /// Child `k` of control face `f`, made unless its slot holds it: read
    /// from `f`'s block through its template where it has one (the block
    /// gathered once per face), walked on level 1 otherwise.
    #[inline]
    fn get(&mut self, ev: &'a Evaluator, f: usize, k: usize) -> &Child {
        let g = 4 * f as u32 + k as u32;
        if self.slots[k].g == g {
            return &self.slots[k];
        }
        if self.face != f {
            self.face = f;
            let mut ids = [0u32; BLOCK];
            self.template = ev.level1.block(f as u32, &mut ids).and_then(|(key, len)| {
                let template = ev.level1.template(key)?;
                for (p, &v) in self.block.iter_mut().zip(&ids[..len]) {
                    *p = ev.level1.point(v);
                }
                Some(template)
            });
        }
        match self.template {
            Some(t) => ev.fill_from(g, &mut self.slots[k], |i| self.block[i], &t.children[k]),
            None => ev.fill(g, &mut self.slots[k]),
        }
        &self.slots[k]
    }
}

/// A point `st` of a level-1 face with an extraordinary corner: `pts` its
/// support (and scratch as long), the rotation making that corner the first
/// and the map from the control face to the level-1 face.
fn near_vertex(
    table: &Extraordinary,
    (pts, tmp): (&mut [DVec3], &mut [DVec3]),
    st: (f64, f64),
    (rot, first): (Affine, Affine),
    second: bool,
) -> Sample {
    let (u, v) = rot.apply(st);
    let j = rot.after(&first);
    let limit: DVec3 = pts.iter().zip(&table.limit).map(|(&p, &w)| p * w).sum();
    if u + v <= 0.0 {
        return at_vertex(pts, table, limit);
    }
    let m = level_of(u + v);
    let (u, v) = (scale2(u, m), scale2(v, m));
    pts.iter_mut().for_each(|p| *p -= limit);
    table.power(m as u32, pts, tmp);
    let (child, map) = child_of((u, v), false);
    let (s, t) = map.apply((u, v));
    let jet = patch::jet(&table.picks[child - 1], pts, s, t, second);
    let c = table.lambda.powi(m);
    let jj = Affine { j, b: [0.0; 2] };
    finish(&jet, limit, c, map.after(&jj), 2f64.powi(m), second)
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
        let Grouped { sorted, rank } = self.by_face(points)?;
        let done: Vec<T> = sorted
            .par_iter()
            .with_min_len(256)
            .map_init(ChildCache::new, |cache, &(f, (u, v))| keep(&self.eval_cached(f, u, v, second, Some(cache))))
            .collect();
        Ok(rank.par_iter().map(|r| done[r.load(Ordering::Relaxed)]).collect())
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

    /// The points checked (the first bad one refused, naming it) and
    /// grouped by face (`group.rs`).
    fn by_face(&self, points: &[(usize, f64, f64)]) -> Result<Grouped> {
        let fits = |&(f, u, v): &(usize, f64, f64)| self.fits(f, u, v);
        group::by_face(points, self.faces, fits, |u, v| self.onto_domain(u, v)).map_err(|i| {
            let (f, u, v) = points[i];
            let why = self.check(f, u, v).err().map(|e| e.to_string()).unwrap_or_default();
            Error::Usage(format!("point {}: {why}", i + 1))
        })
    }
}

/// `m` with `s 2^m` in `(1/2, 1]`, for `0 < s <= 1`.
fn level_of(s: f64) -> i32 {
    let mut m = (-s.log2()).floor().max(0.0) as i32;
    while scale2(s, m) <= 0.5 {
        m += 1;
    }
    while m > 0 && scale2(s, m) > 1.0 {
        m -= 1;
    }
    m
}

/// `x 2^m` without overflow of `2^m` (m up to 1100).
fn scale2(x: f64, m: i32) -> f64 {
    x * 2f64.powi(m / 2) * 2f64.powi(m - m / 2)
}

/// At the extraordinary vertex: its limit position and the normal of its
/// tangent masks.
fn at_vertex(pts: &[DVec3], table: &Extraordinary, limit: DVec3) -> Sample {
    let t = |mask: &[f64]| -> DVec3 { pts.iter().zip(mask).map(|(&p, &w)| p * w).sum() };
    let normal = t(&table.tangents[0]).cross(t(&table.tangents[1])).normalize();
    Sample { position: limit, normal, ..Sample::NAN }
}

/// The sample from the patch jet `jet` of the surface `base + c R`, where
/// the patch's `(s, t)` are `scale * J (u, v) + const`.
#[inline]
fn finish(jet: &Jet, base: DVec3, c: f64, j: [[f64; 2]; 2], scale: f64, second: bool) -> Sample {
    let normal = jet.ds.cross(jet.dt).normalize();
    // chain rule: P_u = c scale (R_s ds/du + R_t dt/du)
    let d1 = c * scale;
    let d2 = d1 * scale;
    let du = (jet.ds * j[0][0] + jet.dt * j[1][0]) * d1;
    let dv = (jet.ds * j[0][1] + jet.dt * j[1][1]) * d1;
    let mut out = Sample { position: base + jet.p * c, normal, du, dv, ..Sample::NAN };
    if second {
        let second_d = |a: usize, b: usize| {
            (jet.dss * (j[0][a] * j[0][b])
                + jet.dst * (j[0][a] * j[1][b] + j[1][a] * j[0][b])
                + jet.dtt * (j[1][a] * j[1][b]))
                * d2
        };
        (out.duu, out.duv, out.dvv) = (second_d(0, 0), second_d(0, 1), second_d(1, 1));
        curvature(jet, c, &mut out);
    }
    out
}

/// The curvatures of `out` (its normal set) from the fundamental forms of
/// the patch (any parameters) of the surface `base + c R`: those of `R`
/// divided by `c` (by `c^2` for the Gaussian). Sign: `k = -II / I`, so a
/// sphere with outward normals has `k = 1/R`.
fn curvature(jet: &Jet, c: f64, out: &mut Sample) {
    let normal = out.normal;
    let (e, f, g) = (jet.ds.dot(jet.ds), jet.ds.dot(jet.dt), jet.dt.dot(jet.dt));
    let (l, m, nn) = (-jet.dss.dot(normal), -jet.dst.dot(normal), -jet.dtt.dot(normal));
    let det = e * g - f * f;
    let gaussian = (l * nn - m * m) / det;
    let mean = (l * g - 2.0 * m * f + nn * e) / (2.0 * det);
    let disc = (mean * mean - gaussian).max(0.0).sqrt();
    let (k1, k2) = (mean + disc, mean - disc);
    // a principal direction a R_s + b R_t solves (II - k I) (a, b) = 0
    let dir = |k: f64| -> DVec3 {
        let (a11, a12, a22) = (l - k * e, m - k * f, nn - k * g);
        let (a, b) = if a11.abs() + a12.abs() >= a12.abs() + a22.abs() { (-a12, a11) } else { (a22, -a12) };
        let d = jet.ds * a + jet.dt * b;
        if d.length_squared() > 0.0 { d.normalize() } else { jet.ds.normalize() }
    };
    let dir1 = dir(k1);
    let dir2 = if disc > 0.0 { dir(k2) } else { normal.cross(dir1) };
    (out.mean, out.gaussian, out.k1, out.k2) = (mean / c, gaussian / (c * c), k1 / c, k2 / c);
    (out.dir1, out.dir2) = (dir1, dir2);
}

#[cfg(test)]
mod tests;
