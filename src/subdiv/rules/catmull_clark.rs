//! Catmull-Clark and bilinear subdivision on a polygon table
//! (docs/schemes.md §12; E. Catmull, J. Clark, "Recursively generated
//! B-spline surfaces on arbitrary topological meshes", 1978; OpenSubdiv 3.5
//! `sdc/catmarkScheme.h` and `sdc/bilinearScheme.h`).
//!
//! Masks, in terms of the old level (`FP(f)`: a face point, itself the
//! average of the face's `k` vertices, so every stencil below expands into
//! old vertices only):
//!
//! ```text
//! face point       FP(f) = 1/k sum of the face's vertices
//! edge point       (v0 + v1 + FP(f0) + FP(f1)) / 4       smooth, interior
//!                  (v0 + v1) / 2                          border, crease
//! vertex point     (n-2)/n v + 1/n^2 sum e_j + 1/n^2 sum FP(f_j)
//!                                  smooth interior, valence n, e_j the
//!                                  other ends of its edges, f_j its faces
//!                  (a + 6 v + b) / 8                      border, crease
//!                  v                                      corner
//! ```
//!
//! Faces of any size take the same rules at the control level, as
//! OpenSubdiv's default triangle rule (`TRI_SUB_CATMARK`) does; from level
//! 1 on every face is a quad. Sharp features (semi-sharp edges and
//! vertices, uniform or Chaikin decay, transitions blended with OpenSubdiv's
//! fractional weight) go through the same classification as Loop's
//! ([`super::features`], [`super::crease`]).
//!
//! Bilinear: face points as above, edge points the midpoints, vertices
//! stay; sharpness changes nothing (as OpenSubdiv's `SCHEME_BILINEAR`).

use super::Sink;
use super::crease::Blend;
use super::features::Features;
pub(crate) use crate::mesh::options::TriangleSubdivision;
use crate::mesh::poly::PolyTable;

/// One polygon level as the masks see it.
pub(crate) struct PolyLevel<'a> {
    /// The table.
    pub pt: &'a PolyTable,
    /// Its sharp features, classified (`None`: no sharpness).
    pub features: Option<&'a Features>,
}

impl PolyLevel<'_> {
    /// The two border neighbours of boundary vertex `v` (the other ends of
    /// the edges leaving along the border from its first corner and
    /// entering its last one).
    #[inline]
    pub(crate) fn border_neighbours(&self, v: u32) -> (u32, u32) {
        let pt = self.pt;
        let first = pt.corner_of(v);
        let last = pt.fan(v).last().unwrap_or(first);
        (pt.vtx(pt.next(first)), pt.vtx(pt.prev(last)))
    }
}

/// Emits `scale` times face `f`'s point (the average of its vertices).
#[inline]
pub(crate) fn face_point<S: Sink>(pt: &PolyTable, f: u32, scale: f64, s: &mut S) {
    let r = pt.face_corners(f);
    let w = scale / f64::from(r.end - r.start);
    for c in r {
        s.add(pt.vtx(c), w);
    }
}

/// The masks of one polygon scheme (see the module docs).
pub(crate) trait PolyRules: Sync {
    /// Whether old vertices move and edge points see the faces (false:
    /// bilinear).
    const SMOOTH: bool;
    /// The scheme's smooth (and border) mask of the point of the edge `c`
    /// names.
    fn edge<S: Sink>(&self, lv: &PolyLevel, c: u32, s: &mut S);
    /// The scheme's smooth (and border) mask of vertex `v`'s new position.
    fn vertex<S: Sink>(&self, lv: &PolyLevel, v: u32, s: &mut S);
    /// Whether interior edges of triangles take OpenSubdiv's smooth
    /// triangle rule ([`TriangleSubdivision::Smooth`]).
    fn smooth_triangles(&self) -> bool {
        false
    }
}

/// Catmull-Clark's masks, with OpenSubdiv's smooth triangle rule when
/// asked (`TRI_SUB_SMOOTH`: below).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct CatmullClark {
    /// The edge rule of OpenSubdiv's `TRI_SUB_SMOOTH` on the edges of
    /// triangles.
    pub smooth_triangles: bool,
}

impl CatmullClark {
    /// The rules `opts` ask for.
    pub(crate) fn new(opts: &crate::subdiv::scheme::Options) -> CatmullClark {
        CatmullClark { smooth_triangles: opts.triangles == TriangleSubdivision::Smooth }
    }
}

/// The weight of a face point in the smooth triangle rule, by the face's
/// corner count (OpenSubdiv's `CATMARK_SMOOTH_TRI_EDGE_WEIGHT`).
fn smooth_triangle_weight(corners: u32) -> f64 {
    if corners == 3 { 0.47 } else { 0.25 }
}

/// The `(end, face point)` weights of the smooth triangle rule on an edge
/// between faces of `k0` and `k1` corners, `None` when neither is a
/// triangle (the ordinary rule).
pub(crate) fn smooth_triangle_edge(k0: u32, k1: u32) -> Option<(f64, f64)> {
    if k0 != 3 && k1 != 3 {
        return None;
    }
    let f = 0.5 * (smooth_triangle_weight(k0) + smooth_triangle_weight(k1));
    Some((0.5 * (1.0 - 2.0 * f), f))
}

/// Bilinear masks.
pub(crate) struct Bilinear;

impl PolyRules for CatmullClark {
    const SMOOTH: bool = true;
    fn smooth_triangles(&self) -> bool {
        self.smooth_triangles
    }
    #[inline]
    fn edge<S: Sink>(&self, lv: &PolyLevel, c: u32, s: &mut S) {
        let pt = lv.pt;
        let (a, b) = (pt.vtx(c), pt.vtx(pt.next(c)));
        match pt.twin(c) {
            None => {
                s.add(a, 0.5);
                s.add(b, 0.5);
            }
            Some(t) => {
                let (f0, f1) = (pt.face(c), pt.face(t));
                let (we, wf) = self
                    .smooth_triangles
                    .then(|| smooth_triangle_edge(pt.face_size(f0), pt.face_size(f1)))
                    .flatten()
                    .unwrap_or((0.25, 0.25));
                s.add(a, we);
                s.add(b, we);
                face_point(pt, f0, wf, s);
                face_point(pt, f1, wf, s);
            }
        }
    }
    #[inline]
    fn vertex<S: Sink>(&self, lv: &PolyLevel, v: u32, s: &mut S) {
        let pt = lv.pt;
        if pt.is_boundary_vertex(v) {
            let (a, b) = lv.border_neighbours(v);
            crease_vertex(v, a, b, s);
            return;
        }
        let n = f64::from(pt.valences()[v as usize]);
        let w = 1.0 / (n * n);
        s.add(v, (n - 2.0) / n);
        for c in pt.fan(v) {
            s.add(pt.vtx(pt.next(c)), w);
            face_point(pt, pt.face(c), w, s);
        }
    }
}

impl PolyRules for Bilinear {
    const SMOOTH: bool = false;
    #[inline]
    fn edge<S: Sink>(&self, lv: &PolyLevel, c: u32, s: &mut S) {
        s.add(lv.pt.vtx(c), 0.5);
        s.add(lv.pt.vtx(lv.pt.next(c)), 0.5);
    }
    #[inline]
    fn vertex<S: Sink>(&self, _: &PolyLevel, v: u32, s: &mut S) {
        s.add(v, 1.0);
    }
}

/// The crease (and border) vertex mask: `(a + 6 v + b) / 8`.
#[inline]
pub(crate) fn crease_vertex<S: Sink>(v: u32, a: u32, b: u32, s: &mut S) {
    s.add(a, 0.125);
    s.add(v, 0.75);
    s.add(b, 0.125);
}

/// A polygon scheme's masks on a level, as [`Blend`] asks for them.
pub(crate) struct PolyOn<'a, R> {
    /// The masks.
    pub r: &'a R,
    /// The level.
    pub lv: &'a PolyLevel<'a>,
}

impl<R: PolyRules> Blend for PolyOn<'_, R> {
    #[inline]
    fn features(&self) -> Option<&Features> {
        if R::SMOOTH { self.lv.features } else { None }
    }
    #[inline]
    fn smooth_vertex<S: Sink>(&self, v: u32, s: &mut S) {
        self.r.vertex(self.lv, v, s);
    }
    #[inline]
    fn crease_vertex<S: Sink>(&self, v: u32, a: u32, b: u32, s: &mut S) {
        crease_vertex(v, a, b, s);
    }
    #[inline]
    fn smooth_edge<S: Sink>(&self, c: u32, s: &mut S) {
        self.r.edge(self.lv, c, s);
    }
    #[inline]
    fn crease_edge<S: Sink>(&self, c: u32, s: &mut S) {
        let pt = self.lv.pt;
        s.add(pt.vtx(c), 0.5);
        s.add(pt.vtx(pt.next(c)), 0.5);
    }
}
