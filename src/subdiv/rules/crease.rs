//! The stencils of vertices and edges with sharp features: the scheme's
//! masks chosen and blended by the rule [`Features`] gives each element
//! (docs/sharp-features.md §5-6), and the 4-point curve rule along creases
//! of the interpolating schemes.

use super::features::{Features, Mask};
use super::{Level, Rules, Sink};
use crate::mesh::{CornerTable, n, p};

/// A sink that scales every weight.
pub struct Scaled<'s, S: Sink> {
    /// The sink weights go to.
    pub sink: &'s mut S,
    /// The factor.
    pub scale: f32,
}

impl<S: Sink> Sink for Scaled<'_, S> {
    #[inline(always)]
    fn add(&mut self, v: u32, w: f32) {
        self.sink.add(v, w * self.scale);
    }
}

/// Emits `scale` times the mask `m` of vertex `v`.
fn emit_mask<R: Rules, S: Sink>(r: &R, lv: &Level, v: u32, m: Mask, scale: f32, s: &mut S) {
    let mut sc = Scaled { sink: s, scale };
    match m {
        Mask::Smooth => r.vertex(lv, v, &mut sc),
        Mask::Crease(a, b) => r.crease_vertex(v, a, b, &mut sc),
        Mask::Corner => sc.add(v, 1.0),
    }
}

/// The stencil of vertex `v`'s new position with its feature, if any
/// (else the scheme's smooth rule).
#[inline]
pub fn vertex_stencil<R: Rules, S: Sink>(r: &R, lv: &Level, v: u32, s: &mut S) {
    match lv.features.and_then(|f| f.vertex(v)) {
        Some(f) if f.parent != Mask::Smooth => {
            if f.parent == f.child || f.weight >= 1.0 {
                emit_mask(r, lv, v, f.parent, 1.0, s);
            } else {
                emit_mask(r, lv, v, f.parent, f.weight, s);
                emit_mask(r, lv, v, f.child, 1.0 - f.weight, s);
            }
        }
        _ => r.vertex(lv, v, s),
    }
}

/// The stencil of the new vertex on the edge owned by `c`, with its
/// feature, if any (else the scheme's smooth rule).
#[inline]
pub fn edge_stencil<R: Rules, S: Sink>(r: &R, lv: &Level, c: u32, s: &mut S) {
    match lv.features.and_then(|f| f.edge(c)) {
        Some(w) if w >= 1.0 => r.crease_edge(lv, c, s),
        Some(w) => {
            r.crease_edge(lv, c, &mut Scaled { sink: s, scale: w });
            r.edge(lv, c, &mut Scaled { sink: s, scale: 1.0 - w });
        }
        None => r.edge(lv, c, s),
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
pub fn four_point_crease<S: Sink>(f: &Features, ct: &CornerTable, c: u32, s: &mut S) {
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
pub struct Unsplit<'s, S: Sink> {
    /// The sink weights go to.
    pub sink: &'s mut S,
    /// The uncut table's vertex count.
    pub nv: u32,
    /// The cut's copies ([`crate::mesh::cut::Cut::copies`]).
    pub copies: &'s [u32],
}

impl<S: Sink> Sink for Unsplit<'_, S> {
    #[inline(always)]
    fn add(&mut self, v: u32, w: f32) {
        let v = if v < self.nv { v } else { self.copies[(v - self.nv) as usize] };
        self.sink.add(v, w);
    }
}
