//! Loop's evaluator: control triangle `f` and the barycentric point
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
//! error naming it.

use super::extraordinary::Extraordinary;
use super::finish::{Affine, finish};
use super::level1::{BLOCK, Level1, REGULAR, Template};
use super::patch::{self, BoxSpline, Poly};
use super::points::EDGE_SLACK;
use super::{Limit, Sample, local};
use crate::mesh::{Mesh, n, p};
use crate::subdiv::Options;
use crate::{Error, Result};
use glam::DVec3;

/// The four children of a triangle (`level1` module docs): child `k` and
/// the map from the parent's `(u, v)` to the child's.
pub(super) fn child_of((u, v): (f64, f64), corner: bool) -> (usize, Affine) {
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
pub(super) fn rotation(i: usize) -> Affine {
    match i {
        1 => Affine { j: [[0.0, 1.0], [-1.0, -1.0]], b: [0.0, 1.0] },
        2 => Affine { j: [[-1.0, -1.0], [1.0, 0.0]], b: [1.0, 0.0] },
        _ => Affine::IDENTITY,
    }
}

/// Supports up to this size live on the stack (valence 18).
const STACK_POINTS: usize = 24;

/// Evaluates the Loop limit surface of one control mesh at any point.
pub(super) struct LoopSurface {
    level1: Level1,
    /// How each control face is evaluated.
    path: Vec<Path>,
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

fn valence_two(f: usize) -> Error {
    Error::Usage(format!(
        "face {f} touches an interior vertex of valence 2 (two triangles back to back), which has no limit patch"
    ))
}

/// [`super::evaluate_one`] for Loop: the tables of face `f`'s corners'
/// valences and the control mesh borrowed, no level 1 of the whole mesh.
///
/// # Errors
/// As [`super::evaluate_one`].
pub(super) fn evaluate_one(mesh: &Mesh, pos: &[DVec3], opts: &Options, (f, u, v): (usize, f64, f64)) -> Result<Sample> {
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
    let base = local::Base::borrowed(mesh, pos, opts);
    let tables = local::Tables { spline: &spline, valences: &valences };
    Ok(local::eval(&base, &tables, f as u32, (u, v), true, &mut local::LoopMemo::default()))
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

impl LoopSurface {
    /// Prepares `mesh` with the control positions `control` (f64, one per
    /// vertex, checked by the caller); `opts.loop_beta` chooses the weights.
    ///
    /// # Errors
    /// As [`Level1::new`].
    pub(super) fn new(mesh: &Mesh, control: &[DVec3], opts: &Options) -> Result<LoopSurface> {
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
        Ok(LoopSurface { level1, path, base, spline, valences, faces: mesh.ct.num_triangles() })
    }

    /// [`Limit::eval_checked`], taking the level-1 face's polynomial or
    /// support from `cache` when it holds it (and leaving it there).
    #[inline]
    fn eval_cached<'a>(&'a self, f: usize, u: f64, v: f64, second: bool, cache: Option<&mut ChildCache<'a>>) -> Sample {
        if let (Path::Local, Some(base)) = (self.path[f], &self.base) {
            let tables = local::Tables { spline: &self.spline, valences: &self.valences };
            let (mut one, memo) = (local::LoopMemo::default(), cache.map(|c| &mut c.local));
            return local::eval(base, &tables, f as u32, (u, v), second, memo.unwrap_or(&mut one));
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

    /// [`LoopSurface::eval_cached`] on a level-1 face `child` with an
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

    /// [`LoopSurface::fill`] with the support read through the template
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

impl Limit for LoopSurface {
    fn faces(&self) -> usize {
        self.faces
    }

    /// Whether control face `f` can be evaluated (every face but those
    /// touching an interior vertex of valence 2).
    fn accepts(&self, f: usize) -> bool {
        self.path.get(f).is_some_and(|&x| x != Path::Refused)
    }

    #[inline]
    fn fits(&self, f: usize, u: f64, v: f64) -> bool {
        f < self.faces && in_triangle(u, v) && self.path[f] != Path::Refused
    }

    #[inline]
    fn onto_domain(&self, u: f64, v: f64) -> (f64, f64) {
        onto_triangle(u, v)
    }

    fn check(&self, f: usize, u: f64, v: f64) -> Result<(f64, f64)> {
        if self.fits(f, u, v) {
            return Ok(self.onto_domain(u, v));
        }
        // why it does not fit: the triangle's own check, else the face
        Err(check_point(self.faces, f, u, v).err().unwrap_or_else(|| valence_two(f)))
    }

    fn eval_checked(&self, f: usize, (u, v): (f64, f64), second: bool) -> Sample {
        self.eval_cached(f, u, v, second, None)
    }

    /// Each thread keeps a [`ChildCache`]: consecutive points of one
    /// level-1 face share its support and polynomial.
    fn eval_sorted<T: Send>(
        &self,
        sorted: &[(usize, (f64, f64))],
        second: bool,
        keep: impl Fn(&Sample) -> T + Sync,
    ) -> Vec<T> {
        super::in_parallel(sorted, ChildCache::new, |cache, f, (u, v)| {
            keep(&self.eval_cached(f, u, v, second, Some(cache)))
        })
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
    /// The local subdivision of the last face of [`Path::Local`].
    local: local::LoopMemo,
}

impl<'a> ChildCache<'a> {
    fn new() -> ChildCache<'a> {
        ChildCache {
            face: usize::MAX,
            template: None,
            block: [DVec3::ZERO; BLOCK],
            slots: [Child::EMPTY, Child::EMPTY, Child::EMPTY, Child::EMPTY],
            local: local::LoopMemo::default(),
        }
    }

    /// Child `k` of control face `f`, made unless its slot holds it: read
    /// from `f`'s block through its template where it has one (the block
    /// gathered once per face), walked on level 1 otherwise.
    #[inline]
    fn get(&mut self, ev: &'a LoopSurface, f: usize, k: usize) -> &Child {
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
pub(super) fn near_vertex(
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

/// `m` with `s 2^m` in `(1/2, 1]`, for `0 < s <= 1`.
pub(super) fn level_of(s: f64) -> i32 {
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
pub(super) fn scale2(x: f64, m: i32) -> f64 {
    x * 2f64.powi(m / 2) * 2f64.powi(m - m / 2)
}

/// At the extraordinary vertex: its limit position and the normal of its
/// tangent masks.
fn at_vertex(pts: &[DVec3], table: &Extraordinary, limit: DVec3) -> Sample {
    let t = |mask: &[f64]| -> DVec3 { pts.iter().zip(mask).map(|(&p, &w)| p * w).sum() };
    let normal = t(&table.tangents[0]).cross(t(&table.tangents[1])).normalize();
    Sample { position: limit, normal, ..Sample::NAN }
}
