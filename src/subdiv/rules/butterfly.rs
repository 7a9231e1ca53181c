//! Classic 8-point butterfly (Dyn, Levin, Gregory, "A Butterfly Subdivision
//! Scheme for Surface Interpolation with Tension Control", ACM TOG 1990), the
//! rule of VTK, MeshLab and Rossignac's `bulge()` (docs/schemes.md §4.2).
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
//! substitution by the opposite wing (docs/schemes.md §4.5).

use super::{Accumulate, Coord, Level, Rules, Sink, four_point};
use crate::mesh::split::Owners;
use crate::mesh::{BORDER, CornerTable, n, p};

/// Classic butterfly rules.
pub(crate) struct Butterfly;

/// Emits `w` times the vertex across the edge opposite corner `x`; if that
/// edge is a border edge, `w` times the ghost `v(n(x)) + v(p(x)) - v(x)`
/// (the corner's own triangle reflected as a parallelogram).
#[inline(always)]
pub(crate) fn outer<S: Sink>(ct: &CornerTable, x: u32, w: f64, s: &mut S) {
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

/// [`eight_point`] evaluated directly when all four outer edges are interior
/// (`None` otherwise): the eight vertex ids are gathered first, without
/// branches, then summed in the same order as the emitted stencil (so the
/// result is bit-identical).
#[inline(always)]
pub(crate) fn eight_point_interior<P: Coord>(ct: &CornerTable, pos: &[P], c: u32, o: u32) -> Option<P> {
    let (v, o_table) = (ct.v_table(), ct.o_table());
    let (nc, pc, no, po) = (n(c), p(c), n(o), p(o));
    let x = [o_table[nc as usize], o_table[pc as usize], o_table[no as usize], o_table[po as usize]];
    if x.contains(&BORDER) {
        return None;
    }
    let ids = [nc, pc, c, o, x[0], x[1], x[2], x[3]].map(|k| v[k as usize] as usize);
    const W: [f64; 8] = [0.5, 0.5, 0.125, 0.125, -0.0625, -0.0625, -0.0625, -0.0625];
    let mut sum = P::ZERO;
    for (i, w) in ids.into_iter().zip(W) {
        sum += pos[i].times(w);
    }
    Some(sum)
}

impl Rules for Butterfly {
    /// Direct evaluation: interior edges with four interior outer edges (all
    /// but a thin band along the boundary) through `eight_point_interior`,
    /// the rest through the emitted stencils.
    fn edge_points<P: Coord>(&self, lv: &Level, owners: Owners, pos: &[P], _: &mut [P], epart: &mut [P]) {
        owners.par_pieces(epart, |qs, cs| {
            for (q, &c) in qs.iter_mut().zip(cs) {
                let o_raw = lv.o_table()[c as usize];
                *q = match (o_raw != BORDER).then(|| eight_point_interior(lv, pos, c, o_raw)).flatten() {
                    Some(e) => e,
                    None => {
                        let mut acc = Accumulate::new(pos);
                        self.edge(lv, c, &mut acc);
                        acc.sum
                    }
                };
            }
        });
    }

    const MOVES_VERTICES: bool = false;
    const CUT_AT_CREASES: bool = true;
    /// The 4-point curve along the crease (docs/sharp-features.md §6.2).
    #[inline]
    fn crease_edge<S: Sink>(&self, ct: &Level, c: u32, s: &mut S) {
        match ct.features {
            Some(f) => super::crease::four_point_crease(f, ct, c, s),
            None => self.edge(ct, c, s),
        }
    }
    #[inline(always)]
    fn edge<S: Sink>(&self, ct: &Level, c: u32, s: &mut S) {
        match ct.o(c) {
            None => four_point(ct, c, s),
            Some(o) => eight_point(ct, c, o, s),
        }
    }
}
