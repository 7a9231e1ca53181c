//! Rossignac's "Jarek" scheme (docs/schemes.md §5): the surface analogue of the
//! Jarek split-and-tweak curve rule (vertex `V += D/2`, midpoint
//! `M -= (D_i + D_j)/4`, `D = 1/4 (avg - V)`).
//!
//! ```text
//! displacement  d_v = 1/8 (avg(1-ring of v) - v)
//! vertex        v'  = v + d_v = 7/8 v + 1/(8k) sum p_i          (valence k)
//! edge (a, b)   e   = (a + b)/2 - (d_a + d_b)/2
//! regular stencils: vertex 7/8 centre, 1/48 each neighbour;
//!   edge a, b 53/96; wings -1/48; the other 3 neighbours of a and of b -1/96
//! ```
//! Boundary variant (docs/schemes.md §5.2, our choice): a boundary vertex's
//! `d_v` uses its two BOUNDARY neighbours only, `d_v = 1/8 ((q1 + q2)/2 - v)`.
//! The boundary then follows the Jarek curve rule exactly: vertex
//! `[1, 14, 1]/16`, border edge `[-1, 17, 17, -1]/32`, independent of the
//! interior.

use super::crease;
use super::{Accumulate, Coord, Level, Rules, Sink, ring_sums_map};
use crate::mesh::split::Owners;
use crate::mesh::{n, p};
use rayon::prelude::*;

/// Jarek rules.
pub(crate) struct Jarek;

impl Jarek {
    /// Emits `scale * d_v`, `d_v` the displacement vertex `v` gets at this
    /// level: its smooth (or boundary) displacement, or on a sharp feature
    /// the feature's vertex stencil minus `v` (corner 0, crease
    /// `1/8 ((a + b)/2 - v)`, blends in transitions), so that the edge rule
    /// `e = (a + b)/2 - (d_a + d_b)/2` follows whatever rule each end gets.
    #[inline(always)]
    fn displacement<S: Sink>(ct: &Level, v: u32, scale: f64, s: &mut S) {
        if let Some(f) = ct.features
            && f.vertex(v).is_some()
        {
            s.add(v, -scale);
            crease::vertex_stencil(&crease::OnLevel { r: &Jarek, lv: ct }, v, &mut crease::Scaled { sink: s, scale });
            return;
        }
        Self::smooth_displacement(ct, v, scale, s);
    }

    /// `scale * d_v` with the smooth rule (the boundary rule on the border).
    #[inline(always)]
    fn smooth_displacement<S: Sink>(ct: &Level, v: u32, scale: f64, s: &mut S) {
        s.add(v, -scale / 8.0);
        if let Some((q1, q2)) = ct.boundary_neighbours(v) {
            s.add(q1, scale / 16.0);
            s.add(q2, scale / 16.0);
        } else {
            let w = scale / (8.0 * f64::from(ct.valences()[v as usize]));
            for c in ct.fan(v) {
                s.add(ct.vtx(n(c)), w);
            }
        }
    }
}

impl Rules for Jarek {
    const MOVES_VERTICES: bool = true;
    #[inline(always)]
    fn edge<S: Sink>(&self, ct: &Level, c: u32, s: &mut S) {
        let (a, b) = (ct.vtx(n(c)), ct.vtx(p(c)));
        s.add(a, 0.5);
        s.add(b, 0.5);
        Self::displacement(ct, a, -0.5, s);
        Self::displacement(ct, b, -0.5, s);
    }
    #[inline(always)]
    fn vertex<S: Sink>(&self, ct: &Level, v: u32, s: &mut S) {
        s.add(v, 1.0);
        Self::smooth_displacement(ct, v, 1.0, s);
    }
    /// The Jarek curve rule: `v + 1/8 ((a + b)/2 - v)`, i.e. `[1, 14, 1]/16`.
    #[inline]
    fn crease_vertex<S: Sink>(&self, v: u32, a: u32, b: u32, s: &mut S) {
        s.add(v, 14.0 / 16.0);
        s.add(a, 1.0 / 16.0);
        s.add(b, 1.0 / 16.0);
    }
    /// The same edge rule: along a crease both displacements are the curve's.
    #[inline]
    fn crease_edge<S: Sink>(&self, ct: &Level, c: u32, s: &mut S) {
        self.edge(ct, c, s);
    }

    /// Direct evaluation: every `d_v` once per level (from the ring sums),
    /// then `v' = v + d_v` and `e = (a + b)/2 - (d_a + d_b)/2`, instead of
    /// walking both endpoint rings again for every edge.
    fn vertex_points<P: Coord>(&self, lv: &Level, pos: &[P], vpart: &mut [P], scratch: &mut [P]) {
        // vpart holds d_v until edge_points has used it
        ring_sums_map(lv, pos, vpart, scratch, |v, sum| {
            let k = if lv.boundary[v] { 2.0 } else { f64::from(lv.valences()[v]) };
            (sum.over(k) - pos[v]).times(0.125)
        });
        if let Some(f) = lv.features {
            // a vertex on a sharp feature moves by its feature's rule
            for vf in f.vertices() {
                let v = vf.vertex as usize;
                let mut acc = Accumulate::new(pos);
                crease::vertex_stencil(&crease::OnLevel { r: self, lv }, vf.vertex, &mut acc);
                vpart[v] = acc.sum - pos[v];
            }
        }
    }

    /// The edge points from the displacements `d_v` that
    /// [`Rules::vertex_points`] left in `vpart`, then `v' = v + d_v`.
    fn edge_points<P: Coord>(&self, lv: &Level, owners: Owners, pos: &[P], vpart: &mut [P], epart: &mut [P]) {
        let d: &[P] = vpart;
        // chunks with a plain inner loop: the loop body is this function's
        // own code, so its inlining does not depend on where rustc places
        // rayon's per-item glue (a per-item closure cost 6% more
        // instructions after unrelated changes elsewhere in the crate)
        owners.par_pieces(epart, |qs, cs| {
            for (q, &c) in qs.iter_mut().zip(cs) {
                let (a, b) = (lv.vtx(n(c)) as usize, lv.vtx(p(c)) as usize);
                *q = (pos[a] + pos[b]).times(0.5) - (d[a] + d[b]).times(0.5);
            }
        });
        vpart.par_chunks_mut(8192).zip(pos.par_chunks(8192)).for_each(|(qs, xs)| {
            for (q, &x) in qs.iter_mut().zip(xs) {
                *q += x;
            }
        });
    }
}
