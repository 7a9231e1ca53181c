//! Picking the subdivision surface: a ray cast against the drawn level,
//! traced back to the control mesh, with the exact limit surface there.
//!
//! ```text
//! ray --(mesh::pick::nearest_hit)--> drawn triangle t, barycentric (b1, b2)
//!     --(mesh::lineage: the split's numbering, level by level)--> control face
//!     f and the (u, v) of t's corners in f --> (u, v) of the hit in f
//!     --(eval::Evaluator on f's neighbourhood, or eval::evaluate_one at a
//!        border or sharp feature; Loop only)--> limit position, normal, curvatures
//! ```
//! A point `(f, u, v)` is the evaluator's: control triangle `f` in the
//! file's face order (polygons fanned for the triangle schemes) and the
//! point `(1 - u - v) c0 + u c1 + v c2` of its corners in the order the file
//! lists them. The polygon schemes (Catmull-Clark, bilinear) name the
//! control polygon and its corner nearest the hit (whose quarter of the
//! polygon, its level-1 quad, holds the hit).
//! Where the evaluator has nothing exact (another scheme, a face at an
//! interior vertex of valence 2), [`Limit::Unavailable`] says why.

use super::eval::{Evaluator, Sample, evaluate_one_f64};
use super::{Options, Scheme};
use crate::mesh::lineage::{QUAD_CORNERS, barycentric, quad_parent, quad_point, triangle_origin};
use crate::mesh::pick::{Hit, nearest_hit};
use crate::mesh::poly::PolyTable;
use crate::mesh::{CornerTable, Mesh, n, p};
use crate::{Error, Result};
use glam::{DVec3, Vec3};
use std::borrow::Cow;

/// A drawn level of a subdivision: what a ray is cast against.
#[derive(Clone, Copy)]
pub struct Level<'a> {
    /// The control mesh (polygons fanned, as read).
    pub control: &'a Mesh,
    /// The level drawn: the subdivision of `control` by `scheme` (its
    /// points may be moved, say to their limit, its triangles not).
    pub drawn: &'a Mesh,
    /// The scheme that made `drawn`.
    pub scheme: Scheme,
    /// Its level (0: `drawn` has `control`'s triangles).
    pub level: u32,
    /// `control`'s points in f64 (say the file's own digits), one per
    /// vertex: the limit at a pick is evaluated from them. `None` (or
    /// another count): from `control`'s f32 points, widened.
    pub precise: Option<&'a [DVec3]>,
}

/// The control face a pick lies in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ControlFace {
    /// A control triangle and the barycentric point of the hit in it.
    Triangle {
        /// The triangle (0-based, the file's face order, polygons fanned).
        face: u32,
        /// Weight of corner 1.
        u: f64,
        /// Weight of corner 2.
        v: f64,
    },
    /// A control polygon (the polygon schemes).
    Polygon {
        /// The polygon (0-based, the file's face order).
        face: u32,
        /// Its number of corners.
        size: u32,
        /// The corner (0-based in the polygon's order) nearest the hit:
        /// whose quarter of the face (its level-1 quad) holds it, or,
        /// drawn unrefined, nearest in space.
        corner: u32,
        /// The hit as the Catmull-Clark evaluator's point: the ptex face
        /// ([`super::eval::catmark::ptex_faces`]) and `(u, v)` in its unit
        /// square; `None` on a polygon other than a quad drawn unrefined.
        ptex: Option<(u32, f64, f64)>,
    },
}

/// The control vertex nearest a pick.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlVertex {
    /// Its id.
    pub id: u32,
    /// Its number of edges.
    pub valence: u32,
    /// Whether it is on the boundary.
    pub boundary: bool,
    /// Its control position.
    pub position: Vec3,
}

/// The exact limit surface at a pick, or why there is none.
#[derive(Clone, Debug, PartialEq)]
pub enum Limit {
    /// Position, normal, derivatives and curvatures.
    Exact(Box<Sample>),
    /// Why the limit is not evaluated there.
    Unavailable(String),
}

/// Where a ray meets a subdivision surface.
#[derive(Clone, Debug, PartialEq)]
pub struct Pick {
    /// The hit on the drawn level.
    pub point: Vec3,
    /// The ray parameter of the hit (the distance for a unit direction).
    pub distance: f32,
    /// The drawn triangle hit.
    pub triangle: u32,
    /// The level drawn.
    pub level: u32,
    /// The scheme.
    pub scheme: Scheme,
    /// The control face and the point in it.
    pub face: ControlFace,
    /// The control vertex of that face nearest the hit: in its parameters
    /// for a triangle (the corner of largest weight), the corner of the
    /// quarter holding the hit for a refined polygon, the corner nearest in
    /// space for a polygon drawn unrefined.
    pub vertex: ControlVertex,
    /// The exact limit surface there.
    pub limit: Limit,
}

/// The first point where the ray `origin + t dir` (`dir` unit) meets the
/// drawn level, traced back to the control mesh, with the exact limit
/// there (Loop) or why not; `None` when the ray misses.
///
/// # Errors
/// [`Error::Usage`] when `drawn` is not `level` levels of `control` under
/// `scheme` (its triangle count says so).
pub fn pick(level: &Level, opts: &Options, origin: Vec3, dir: Vec3) -> Result<Option<Pick>> {
    let Some(hit) = nearest_hit(level.drawn, origin, dir) else {
        return Ok(None);
    };
    let (face, vertex) = trace(level, &hit)?;
    let limit = limit_at((level.control, level.precise), level.scheme, opts, &face);
    let (point, distance, triangle) = (hit.point, hit.t, hit.triangle);
    Ok(Some(Pick { point, distance, triangle, level: level.level, scheme: level.scheme, face, vertex, limit }))
}

/// A tessellation of the limit drawn instead of a level (the viewer's
/// adaptive display): its triangles, each with its control face (Loop: the
/// control triangle; Catmull-Clark: the ptex face) and its corners' `(u, v)`
/// there ([`super::Tessellation::corners`]).
pub(crate) struct Tessellated<'a> {
    pub(crate) mesh: &'a Mesh,
    pub(crate) faces: &'a [u32],
    pub(crate) corners: &'a [[(f64, f64); 3]],
}

/// [`pick`] on a tessellation of the limit of `control` under `scheme`
/// (Loop or Catmull-Clark): the hit's `(u, v)` interpolated from its
/// triangle's corners, on their control face; `None` when the ray misses
/// (or the tessellation is of another cage).
pub(crate) fn pick_tessellated(
    control: (&Mesh, Option<&[DVec3]>),
    (scheme, opts): (Scheme, &Options),
    drawn: &Tessellated,
    (origin, dir): (Vec3, Vec3),
) -> Option<Pick> {
    let hit = nearest_hit(drawn.mesh, origin, dir)?;
    let k = hit.triangle as usize;
    let (f, c) = (*drawn.faces.get(k)?, drawn.corners.get(k)?);
    let (b1, b2) = (f64::from(hit.uv.0), f64::from(hit.uv.1));
    let w = [1.0 - b1 - b2, b1, b2];
    let (u, v) = (0..3).fold((0.0, 0.0), |(u, v), i| (u + w[i] * c[i].0, v + w[i] * c[i].1));
    let ct = &control.0.ct;
    let (face, id, valence) = if scheme == Scheme::CatmullClark {
        let pt = PolyTable::from_corner_table(ct);
        let (polygon, corner) = *super::eval::catmark::ptex_faces(&pt).get(f as usize)?;
        let r = pt.face_corners(polygon);
        // a quad's nearest corner is the quarter of its square holding the
        // hit; an n-gon's ptex face is its corner's quarter
        let corner = match (corner == super::eval::catmark::QUAD, u >= 0.5, v >= 0.5) {
            (false, _, _) => corner,
            (true, false, false) => 0,
            (true, true, false) => 1,
            (true, true, true) => 2,
            (true, false, true) => 3,
        };
        let id = pt.vtx(r.start + corner);
        let size = r.end - r.start;
        (ControlFace::Polygon { face: polygon, size, corner, ptex: Some((f, u, v)) }, id, pt.valences()[id as usize])
    } else {
        let weights = [1.0 - u - v, u, v];
        let nearest = (0..3).max_by(|&a, &b| weights[a].total_cmp(&weights[b])).unwrap_or(0);
        let id = *ct.v_table().get(3 * f as usize + nearest)?;
        (ControlFace::Triangle { face: f, u, v }, id, ct.valence(id))
    };
    let position = *control.0.positions.get(id as usize)?;
    let vertex = ControlVertex { id, valence, boundary: ct.is_boundary_vertex(id), position };
    let limit = limit_at(control, scheme, opts, &face);
    let (point, distance, triangle) = (hit.point, hit.t, hit.triangle);
    Some(Pick { point, distance, triangle, level: 0, scheme, face, vertex, limit })
}

/// The control face and vertex of a hit on the drawn level.
///
/// # Errors
/// As [`pick`].
pub(crate) fn trace(level: &Level, hit: &Hit) -> Result<(ControlFace, ControlVertex)> {
    let ct = &level.control.ct;
    let nt = ct.num_triangles();
    let mismatch = || {
        Error::Usage(format!(
            "{} drawn triangles are not level {} of {} control triangles under {}",
            level.drawn.ct.num_triangles(),
            level.level,
            nt,
            level.scheme
        ))
    };
    let vertex = |id: u32| ControlVertex {
        id,
        valence: ct.valence(id),
        boundary: ct.is_boundary_vertex(id),
        position: level.control.positions[id as usize],
    };
    let (b1, b2) = (f64::from(hit.uv.0), f64::from(hit.uv.1));
    if level.scheme.is_polygonal() && level.level > 0 {
        let pt = PolyTable::from_corner_table(ct);
        let quads = (pt.num_corners() as u64) << (2 * (level.level - 1));
        if level.drawn.ct.num_triangles() as u64 != 2 * quads {
            return Err(mismatch());
        }
        let (c, uv) = quad_point(hit.triangle, level.level, b1, b2);
        let f = pt.face(c);
        let (first, size) = (pt.face_corners(f).start, pt.face_size(f));
        // the polygons' valence: a fanned face's diagonals are no edges
        let v = ControlVertex { valence: pt.valences()[pt.vtx(c) as usize], ..vertex(pt.vtx(c)) };
        let ptex = ptex_point(&pt, f, c - first, uv);
        return Ok((ControlFace::Polygon { face: f, size, corner: c - first, ptex: Some(ptex) }, v));
    }
    let (f, corners) = triangle_origin(hit.triangle, nt, level.level)
        .filter(|_| level.drawn.ct.num_triangles() as u64 == (nt as u64) << (2 * level.level))
        .ok_or_else(mismatch)?;
    let [u, v] = barycentric(&corners, b1, b2);
    let weights = [1.0 - u - v, u, v];
    let k = (0..3).max_by(|&a, &b| weights[a].total_cmp(&weights[b])).unwrap_or(0);
    let nearest = vertex(ct.vtx(3 * f + k as u32));
    if level.scheme.is_polygonal() {
        // level 0 of a polygon scheme: the fanned triangle's polygon, and
        // its corner nearest the hit
        let pt = PolyTable::from_corner_table(ct);
        let polygon = polygon_of(&pt, ct, f).ok_or_else(mismatch)?;
        let r = pt.face_corners(polygon);
        let dist = |c: u32| level.control.positions[pt.vtx(c) as usize].distance_squared(hit.point);
        let c = r.clone().min_by(|&a, &b| dist(a).total_cmp(&dist(b))).unwrap_or(r.start);
        let v = ControlVertex { valence: pt.valences()[pt.vtx(c) as usize], ..vertex(pt.vtx(c)) };
        // a quad drawn unrefined: the fan triangle's corners are quad corners
        let size = r.end - r.start;
        let quad_corner =
            |k: u32| (0..4).find(|&i| pt.vtx(r.start + i) == ct.vtx(3 * f + k)).map(|i| QUAD_CORNERS[i as usize]);
        let ptex = match (size, quad_corner(0), quad_corner(1), quad_corner(2)) {
            (4, Some(a), Some(b), Some(c)) => {
                let [u, v] = barycentric(&[a, b, c], b1, b2);
                Some((ptex_point(&pt, polygon, 0, [0.0, 0.0]).0, u, v))
            }
            _ => None,
        };
        return Ok((ControlFace::Polygon { face: polygon, size, corner: c - r.start, ptex }, v));
    }
    Ok((ControlFace::Triangle { face: f, u, v }, nearest))
}

/// The ptex face and `(u, v)` of the point `uv` of the level-1 quad of
/// corner `k` of polygon `f`: a quad's quarter maps back to the quad's
/// square; an n-gon's ptex face is that level-1 quad itself.
fn ptex_point(pt: &PolyTable, f: u32, k: u32, uv: [f64; 2]) -> (u32, f64, f64) {
    let before: u32 = (0..f).map(|g| if pt.face_size(g) == 4 { 1 } else { pt.face_size(g) }).sum();
    if pt.face_size(f) == 4 {
        let [u, v] = quad_parent(k, uv);
        (before, u, v)
    } else {
        (before + k, uv[0], uv[1])
    }
}

/// The polygon of `pt` holding the three vertices of triangle `f` of `ct`
/// (a polygon's fan triangles use its corners only).
fn polygon_of(pt: &PolyTable, ct: &CornerTable, f: u32) -> Option<u32> {
    let tri = [ct.vtx(3 * f), ct.vtx(3 * f + 1), ct.vtx(3 * f + 2)];
    (0..pt.num_faces() as u32).find(|&g| {
        let r = pt.face_corners(g);
        let verts = &pt.v_table()[r.start as usize..r.end as usize];
        tri.iter().all(|x| verts.contains(x))
    })
}

/// The exact limit of `control` under `scheme` at a pick's face, or why
/// there is none (the scheme, or what the face touches): from the f64
/// points `precise` when given (one per vertex), else from the f32 ones.
pub(crate) fn limit_at(
    (control, precise): (&Mesh, Option<&[DVec3]>),
    scheme: Scheme,
    opts: &Options,
    face: &ControlFace,
) -> Limit {
    let why = |s: String| Limit::Unavailable(s);
    let exact = |r: Result<Sample>| r.map_or_else(|e| why(e.to_string()), |s| Limit::Exact(Box::new(s)));
    let precise = precise.filter(|p| p.len() == control.positions.len());
    let points = || -> Cow<'_, [DVec3]> {
        precise.map_or_else(|| Cow::Owned(control.positions.iter().map(|p| p.as_dvec3()).collect()), Cow::Borrowed)
    };
    let (face, u, v) = match (scheme, *face) {
        (Scheme::Loop, ControlFace::Triangle { face, u, v }) => (face, u, v),
        (Scheme::CatmullClark, ControlFace::Polygon { ptex: Some((p, u, v)), .. }) => {
            return exact(evaluate_one_f64(control, &points(), scheme, opts, (p as usize, u, v)));
        }
        (Scheme::CatmullClark, _) => return why(format!("{scheme}: a polygon drawn unrefined (subdivide once)")),
        (s, _) if s.is_interpolating() => {
            return why(format!("{scheme}: an interpolating scheme has no closed-form limit"));
        }
        _ => return why(format!("{scheme}: exact evaluation exists for Loop and Catmull-Clark")),
    };
    let sample = match local_mesh(control, face).filter(|_| !touches_feature(&control.ct, face)) {
        // the face's own neighbourhood: the same limit at a cost that does not grow with the mesh
        Some((local, ids)) => {
            let at: Vec<DVec3> = match precise {
                Some(p) => ids.iter().map(|&i| p[i as usize]).collect(),
                None => local.positions.iter().map(|p| p.as_dvec3()).collect(),
            };
            Evaluator::new_f64(&local, &at, scheme, opts).and_then(|ev| ev.eval(0, u, v))
        }
        // a border or sharp feature: local subdivision from this face alone
        None => evaluate_one_f64(control, &points(), scheme, opts, (face as usize, u, v)),
    };
    exact(sample)
}

/// Control triangle `f` with every triangle at one of its vertices, as a
/// mesh of its own with `f` first (same corner order): all the limit over
/// `f` depends on. After one Loop step, the support of `f`'s children is
/// the vertex points of `f`'s own vertices (their whole fans are here) and
/// the edge points of edges at them (both their triangles are here);
/// nothing past that, so an evaluator of this small mesh gives `f`'s limit
/// without preparing the whole control mesh (1.8 s for a million
/// triangles). `None` when the piece is not a valid mesh by itself (a ring
/// vertex whose faces here fall in two fans): then the whole mesh is used.
pub fn neighbourhood(control: &Mesh, f: u32) -> Option<Mesh> {
    local_mesh(control, f).map(|(mesh, _)| mesh)
}

/// [`neighbourhood`], with the control vertex each of its vertices is.
fn local_mesh(control: &Mesh, f: u32) -> Option<(Mesh, Vec<u32>)> {
    let ct = &control.ct;
    let mut faces = vec![f];
    for k in 0..3 {
        for c in ct.fan(ct.vtx(3 * f + k)) {
            let t = c / 3;
            if !faces.contains(&t) {
                faces.push(t);
            }
        }
    }
    let mut ids: Vec<u32> = Vec::with_capacity(3 * faces.len());
    let mut positions = Vec::new();
    let mut tris = Vec::with_capacity(3 * faces.len());
    for &t in &faces {
        for k in 0..3 {
            let v = ct.vtx(3 * t + k);
            let local = ids.iter().position(|&x| x == v).unwrap_or_else(|| {
                ids.push(v);
                positions.push(control.positions[v as usize]);
                ids.len() - 1
            });
            tris.push(local as u32);
        }
    }
    Mesh::from_triangles(positions, &tris).ok().map(|mesh| (mesh, ids))
}

/// Whether a vertex of control triangle `f` is on the boundary, at a sharp
/// edge or sharp itself: its limit depends on more than [`neighbourhood`]
/// keeps (the sharpness, the rings beyond a border), and
/// `evaluate_one` evaluates it from the whole mesh without preparing it.
fn touches_feature(ct: &CornerTable, f: u32) -> bool {
    let sharp_vertex =
        |v: u32| ct.sharpness().is_some_and(|s| s.sharp_vertices().iter().any(|&(x, s)| x == v && s > 0.0));
    (0..3).any(|k| {
        let v = ct.vtx(3 * f + k);
        ct.is_boundary_vertex(v)
            || sharp_vertex(v)
            || ct.fan(v).any(|c| ct.edge_sharpness(n(c)) > 0.0 || ct.edge_sharpness(p(c)) > 0.0)
    })
}

impl std::fmt::Display for Pick {
    /// A plain-text block, one fact a line (what the viewer's Copy gives).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v3 = |p: Vec3| format!("{:.6} {:.6} {:.6}", p.x, p.y, p.z);
        writeln!(f, "surface: {} level {}, drawn triangle {}", self.scheme, self.level, self.triangle)?;
        writeln!(f, "hit on the drawn surface: {}", v3(self.point))?;
        match self.face {
            ControlFace::Triangle { face, u, v } => writeln!(f, "control face: {face}  u v: {u:.6} {v:.6}")?,
            ControlFace::Polygon { face, size, corner, ptex } => {
                writeln!(f, "control face: polygon {face} ({size} corners), nearest its corner {corner}")?;
                if let Some((p, u, v)) = ptex {
                    writeln!(f, "ptex face: {p}  u v: {u:.6} {v:.6}")?;
                }
            }
        }
        let cv = &self.vertex;
        let boundary = if cv.boundary { ", on the boundary" } else { "" };
        writeln!(f, "nearest control vertex: {} (valence {}{boundary}) at {}", cv.id, cv.valence, v3(cv.position))?;
        match &self.limit {
            Limit::Unavailable(why) => writeln!(f, "limit evaluation: not available for {why}"),
            Limit::Exact(s) => {
                let d3 = |p: glam::DVec3| format!("{:.9} {:.9} {:.9}", p.x, p.y, p.z);
                writeln!(f, "limit position: {}", d3(s.position))?;
                writeln!(f, "limit normal: {}", d3(s.normal))?;
                writeln!(f, "mean curvature H: {:.6e}  Gaussian K: {:.6e}", s.mean, s.gaussian)?;
                writeln!(f, "principal k1: {:.6e}  k2: {:.6e}", s.k1, s.k2)?;
                writeln!(f, "directions d1: {}  d2: {}", d3(s.dir1), d3(s.dir2))
            }
        }
    }
}
