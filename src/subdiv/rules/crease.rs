//! The stencils of vertices and edges with sharp features: the scheme's
//! masks chosen and blended by the rule [`Features`] gives each element
//! (docs/sharp-features.md §5-6), and the 4-point curve rule along creases
//! of the interpolating schemes.

use super::features::{Features, Mask};
use super::{Level, Rules, Sink};
use crate::mesh::{CornerTable, n, p};

/// A sink that scales every weight.
pub(crate) struct Scaled<'s, S: Sink> {
    /// The sink weights go to.
    pub sink: &'s mut S,
    /// The factor.
    pub scale: f64,
}

impl<S: Sink> Sink for Scaled<'_, S> {
    #[inline(always)]
    fn add(&mut self, v: u32, w: f64) {
        self.sink.add(v, w * self.scale);
    }
}

/// What blending sharp and smooth masks needs of a scheme on its level:
/// the level's classified features and the scheme's four masks. The
/// triangle schemes give it through [`OnLevel`], Catmull-Clark and bilinear
/// through their polygon level.
pub(crate) trait Blend {
    /// The level's sharp features (`None`: none).
    fn features(&self) -> Option<&Features>;
    /// The smooth (or boundary) mask of vertex `v`.
    fn smooth_vertex<S: Sink>(&self, v: u32, s: &mut S);
    /// The curve mask of vertex `v` on a crease through `a` and `b`.
    fn crease_vertex<S: Sink>(&self, v: u32, a: u32, b: u32, s: &mut S);
    /// The smooth (or boundary) mask of the edge `c` names.
    fn smooth_edge<S: Sink>(&self, c: u32, s: &mut S);
    /// The crease mask of the edge `c` names.
    fn crease_edge<S: Sink>(&self, c: u32, s: &mut S);
}

/// A triangle scheme's rules on a level, as [`Blend`] asks for them.
pub(crate) struct OnLevel<'a, R> {
    /// The rules.
    pub r: &'a R,
    /// The level.
    pub lv: &'a Level<'a>,
}

impl<R: Rules> Blend for OnLevel<'_, R> {
    #[inline]
    fn features(&self) -> Option<&Features> {
        self.lv.features
    }
    #[inline]
    fn smooth_vertex<S: Sink>(&self, v: u32, s: &mut S) {
        self.r.vertex(self.lv, v, s);
    }
    #[inline]
    fn crease_vertex<S: Sink>(&self, v: u32, a: u32, b: u32, s: &mut S) {
        self.r.crease_vertex(v, a, b, s);
    }
    #[inline]
    fn smooth_edge<S: Sink>(&self, c: u32, s: &mut S) {
        self.r.edge(self.lv, c, s);
    }
    #[inline]
    fn crease_edge<S: Sink>(&self, c: u32, s: &mut S) {
        self.r.crease_edge(self.lv, c, s);
    }
}

/// Emits `scale` times the mask `m` of vertex `v`.
fn emit_mask<B: Blend, S: Sink>(b: &B, v: u32, m: Mask, scale: f64, s: &mut S) {
    let mut sc = Scaled { sink: s, scale };
    match m {
        Mask::Smooth => b.smooth_vertex(v, &mut sc),
        Mask::Crease(x, y) => b.crease_vertex(v, x, y, &mut sc),
        Mask::Corner => sc.add(v, 1.0),
    }
}

/// The stencil of vertex `v`'s new position with its feature, if any
/// (else the scheme's smooth rule).
#[inline]
pub(crate) fn vertex_stencil<B: Blend, S: Sink>(b: &B, v: u32, s: &mut S) {
    match b.features().and_then(|f| f.vertex(v)) {
        Some(f) if f.parent != Mask::Smooth => {
            if f.parent == f.child || f.weight >= 1.0 {
                emit_mask(b, v, f.parent, 1.0, s);
            } else {
                let w = f64::from(f.weight);
                emit_mask(b, v, f.parent, w, s);
                emit_mask(b, v, f.child, 1.0 - w, s);
            }
        }
        _ => b.smooth_vertex(v, s),
    }
}

/// The stencil of the new vertex on the edge owned by `c`, with its
/// feature, if any (else the scheme's smooth rule).
#[inline]
pub(crate) fn edge_stencil<B: Blend, S: Sink>(b: &B, c: u32, s: &mut S) {
    match b.features().and_then(|f| f.edge(c)) {
        // a crease at this level
        Some(w) if (w - 1.0).abs() < f32::EPSILON / 2.0 => b.crease_edge(c, s),
        // 0 < w < 1, or w > 1 (Chaikin, a child dart: features::edge_weight)
        Some(w) => {
            let w = f64::from(w);
            b.crease_edge(c, &mut Scaled { sink: s, scale: w });
            b.smooth_edge(c, &mut Scaled { sink: s, scale: 1.0 - w });
        }
        None => b.smooth_edge(c, s),
    }
}

/// The interpolating 4-point curve rule (Dyn, Levin, Gregory 1987) along the
/// crease through the edge owned by `c` (of the level `ct`, cut or not):
/// `-1/16 p0 + 9/16 p1 + 9/16 p2 - 1/16 p3`. Where the crease curve ends
/// (a dart or a corner) the missing point is replaced by the quadratic
/// through the other three (`3/8 p1 + 3/4 p2 - 1/8 p3`, the 4-point rule
/// with `p0 = 3 p1 - 3 p2 + p3`), and an edge ending at both ends is
/// split at its midpoint. Points along a crease therefore depend on the
/// crease polygon alone.
pub(crate) fn four_point_crease<S: Sink>(f: &Features, ct: &CornerTable, c: u32, s: &mut S) {
    let (p1, p2) = (f.original(ct.vtx(n(c))), f.original(ct.vtx(p(c))));
    match (f.crease_continues(ct, p1, p2), f.crease_continues(ct, p2, p1)) {
        (Some(p0), Some(p3)) => {
            s.add(p0, -1.0 / 16.0);
            s.add(p1, 9.0 / 16.0);
            s.add(p2, 9.0 / 16.0);
            s.add(p3, -1.0 / 16.0);
        }
        (None, Some(p3)) => {
            s.add(p1, 3.0 / 8.0);
            s.add(p2, 3.0 / 4.0);
            s.add(p3, -1.0 / 8.0);
        }
        (Some(p0), None) => {
            s.add(p0, -1.0 / 8.0);
            s.add(p1, 3.0 / 4.0);
            s.add(p2, 3.0 / 8.0);
        }
        (None, None) => {
            s.add(p1, 0.5);
            s.add(p2, 0.5);
        }
    }
}

/// A sink that maps the extra vertices of a cut table back to the vertices
/// they are copies of (for stencils recorded on a cut level).
pub(crate) struct Unsplit<'s, S: Sink> {
    /// The sink weights go to.
    pub sink: &'s mut S,
    /// The uncut table's vertex count.
    pub nv: u32,
    /// The cut's copies ([`crate::mesh::cut::Cut::copies`]).
    pub copies: &'s [u32],
}

impl<S: Sink> Sink for Unsplit<'_, S> {
    #[inline(always)]
    fn add(&mut self, v: u32, w: f64) {
        let v = if v < self.nv { v } else { self.copies[(v - self.nv) as usize] };
        self.sink.add(v, w);
    }
}
