//! Classic 8-point butterfly (Dyn, Levin, Gregory, "A Butterfly Subdivision
//! Scheme for Surface Interpolation with Tension Control", ACM TOG 1990), the
//! rule of VTK, MeshLab and Rossignac's `bulge()` (schemes.md 3.2).
//!
//! ```text
//!         c1 ------ b1 ------ c2
//!           \      /  \      /          e = 1/2 (a1 + a2)
//!            a1 ========== a2              + 1/8 (b1 + b2)
//!           /      \  /      \             - 1/16 (c1 + c2 + c3 + c4)
//!         c3 ------ b2 ------ c4
//! ```
//! Old vertices never move. Border edges use the 4-point curve rule
//! `9/16 (p1 + p2) - 1/16 (p0 + p3)`. An interior edge whose outer vertex `c`
//! is missing (its wing's outer edge is a border edge) uses OpenMesh's
//! parallelogram ghost `c = x + y - z` (the wing apex translated by the edge
//! vector), which keeps the stencil linear and linear-precise, unlike VTK's
//! substitution by the opposite wing (schemes.md 3.5).

use super::rules::{Level, Rules, Sink, four_point};
use crate::mesh::{CornerTable, n, p};

/// Classic butterfly rules.
pub struct Butterfly;

/// Emits `w` times the vertex across the edge opposite corner `x`; if that
/// edge is a border edge, `w` times the ghost `v(n(x)) + v(p(x)) - v(x)`
/// (the corner's own triangle reflected as a parallelogram).
#[inline(always)]
pub(crate) fn outer<S: Sink>(ct: &CornerTable, x: u32, w: f32, s: &mut S) {
    match ct.o(x) {
        Some(y) => s.add(ct.vtx(y), w),
        None => {
            s.add(ct.vtx(n(x)), w);
            s.add(ct.vtx(p(x)), w);
            s.add(ct.vtx(x), -w);
        }
    }
}

/// The 8-point butterfly stencil for the interior edge opposite owner `c`
/// (with opposite `o`), weights `(a, b, c) = (1/2, 1/8, -1/16)`.
#[inline(always)]
pub(crate) fn eight_point<S: Sink>(ct: &CornerTable, c: u32, o: u32, s: &mut S) {
    s.add(ct.vtx(n(c)), 0.5);
    s.add(ct.vtx(p(c)), 0.5);
    s.add(ct.vtx(c), 0.125);
    s.add(ct.vtx(o), 0.125);
    for x in [n(c), p(c), n(o), p(o)] {
        outer(ct, x, -0.0625, s);
    }
}

impl Rules for Butterfly {
    const MOVES_VERTICES: bool = false;
    #[inline(always)]
    fn edge<S: Sink>(&self, ct: &Level, c: u32, s: &mut S) {
        match ct.o(c) {
            None => four_point(ct, c, s),
            Some(o) => eight_point(ct, c, o, s),
        }
    }
}
