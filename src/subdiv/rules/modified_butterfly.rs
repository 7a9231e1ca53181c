//! Modified butterfly (Zorin, Schroeder, Sweldens, "Interpolating Subdivision
//! for Meshes with Arbitrary Topology", SIGGRAPH 1996; docs/schemes.md §4.3-4.5).
//! Old vertices never move. Valence counts EDGES.
//!
//! Regular interior edge (both ends interior, valence 6), tension `w`
//! (default 0, which is exactly the 8-point butterfly):
//! ```text
//!              c1 ------ b1 ------ c2
//!             /  \      /  \      /  \         a  (a1, a2)       1/2 - w
//!          d1 ---- a1 ========== a2 ---- d2    b  (b1, b2)       1/8 + 2w
//!             \  /      \  /      \  /         c  (c1 .. c4)    -1/16 - w
//!              c3 ------ b2 ------ c4          d  (d1, d2)       w
//! ```
//! One interior endpoint `v` of valence `k != 6` (extraordinary), neighbours
//! `e_0 .. e_{k-1}` around it with `e_0` the other endpoint:
//! ```text
//!   e = 3/4 v + sum_j s_j e_j
//!   k = 2: s = (3/8, -1/8)       (derived here, see `ev_weights`)
//!   k = 3: s = (5/12, -1/12, -1/12)
//!   k = 4: s = (3/8, 0, -1/8, 0)
//!   k >= 5: s_j = (1/4 + cos(2 pi j/k) + 1/2 cos(4 pi j/k)) / k
//! ```
//! Both endpoints extraordinary: the average of the two EV stencils.
//!
//! Boundary (our choice, docs/schemes.md §4.5):
//! * border edge: 4-point curve rule `9/16 (p1 + p2) - 1/16 (p0 + p3)`;
//! * interior edge with an extraordinary interior endpoint: its EV rule (as
//!   OpenMesh), averaged if both are;
//! * interior edge from a regular boundary vertex `b` (valence 4, i.e. 3
//!   faces) to a regular interior vertex `i` (naspert/MESH rule, reproduces
//!   quadratics):
//!   ```text
//!   b 3/8, i 5/8, boundary wing 1/16, interior wing 3/16,
//!   b's other boundary neighbour -1/16,
//!   i's neighbour across (i, boundary wing) -1/16,
//!   i's neighbour across (i, interior wing) -1/8
//!   ```
//! * anything else near the boundary: the 8-point rule with OpenMesh's
//!   parallelogram ghosts for missing outer vertices (linear precision).

use super::butterfly::{eight_point, eight_point_interior, outer};
use super::{Accumulate, Coord, Level, Rules, Sink, four_point};
use crate::mesh::split::Owners;
use crate::mesh::{BORDER, CornerTable, n, p};
use rayon::prelude::*;

/// Modified butterfly rules with tension `w` and precomputed EV weights.
pub(crate) struct ModifiedButterfly {
    w: f32,
    /// `ev[k]` = the `k` weights `s_j` for valence `k` (k < 64).
    ev: Vec<Vec<f64>>,
}

/// Zorin's extraordinary weights `s_j` for valence `k` (hard-coded tables for
/// k = 3 and 4; the cosine formula for k >= 5), and our rule for k = 2.
///
/// Valence 2 (derived here; no published table): an interior vertex of
/// valence 2 only occurs in a "pillow", two triangles glued back to back.
/// The cosine formula gives `s = (7/8, -1/8)` there, summing to 3/4 instead
/// of 1/4 (at k <= 2 the `cos(4 pi j/k)` term no longer sums to zero), so
/// the edge point would not be affine invariant (weights summing to 3/2).
/// We use the unique circulant with the eigenvalues Zorin's rule is built
/// on (docs/schemes.md §4.4): mode 0 = `s_0 + s_1` = 1/4 and mode 1 = `s_0 - s_1`
/// = 1/2, i.e. `s = (3/8, -1/8)`, the same values as the k = 4 table's
/// `s_0` and `s_2`; with the 3/4 on the vertex the stencil sums to one.
/// Valences 0 and 1 cannot occur at an interior vertex of a valid table
/// (`CornerTable` refuses degenerate faces); they get empty weights.
pub(crate) fn ev_weights(k: u32) -> Vec<f64> {
    match k {
        0 | 1 => Vec::new(),
        2 => vec![3.0 / 8.0, -1.0 / 8.0],
        3 => vec![5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0],
        4 => vec![3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0],
        _ => (0..k)
            .map(|j| {
                let t = 2.0 * std::f64::consts::PI * f64::from(j) / f64::from(k);
                (0.25 + t.cos() + 0.5 * (2.0 * t).cos()) / f64::from(k)
            })
            .collect(),
    }
}

impl ModifiedButterfly {
    /// Rules with tension `w` (0 = Zorin's default).
    pub(crate) fn new(w: f32) -> Self {
        ModifiedButterfly { w, ev: (0..64).map(ev_weights).collect() }
    }

    /// EV stencil around interior vertex `v(x)`, starting at neighbour `v(n(x))`,
    /// scaled by `scale`.
    #[inline]
    fn ev_rule<S: Sink>(&self, ct: &CornerTable, x: u32, scale: f64, s: &mut S) {
        let v = ct.vtx(x);
        let k = ct.valences()[v as usize];
        s.add(v, 0.75 * scale);
        let owned;
        let ws: &[f64] = match self.ev.get(k as usize) {
            Some(w) => w,
            None => {
                owned = ev_weights(k);
                &owned
            }
        };
        let mut c = x;
        for &wj in ws {
            s.add(ct.vtx(n(c)), wj * scale);
            match ct.s(c) {
                Some(y) => c = y,
                None => break,
            }
        }
    }

    /// The vertex `d` continuing the edge line beyond interior valence-6
    /// vertex `v(x)`, whose neighbour `v(n(x))` is the other endpoint.
    #[inline]
    fn beyond(ct: &CornerTable, x: u32) -> u32 {
        let mut c = x;
        for _ in 0..3 {
            c = ct.s(c).unwrap_or(c);
        }
        ct.vtx(n(c))
    }

    /// The naspert/MESH rule for the interior edge from regular boundary vertex
    /// `bv` to regular interior vertex `iv`. `bw`/`iw` are the boundary and the
    /// interior wing apexes; `xo` is the corner facing the edge `(bv, iw)` from
    /// the wing triangle, `xb`/`xi` the corners facing `(iv, bw)` / `(iv, iw)`.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn mesh_rule<S: Sink>(ct: &CornerTable, bv: u32, iv: u32, bw: u32, iw: u32, xo: u32, xb: u32, xi: u32, s: &mut S) {
        s.add(bv, 3.0 / 8.0);
        s.add(iv, 5.0 / 8.0);
        s.add(bw, 1.0 / 16.0);
        s.add(iw, 3.0 / 16.0);
        outer(ct, xo, -1.0 / 16.0, s);
        outer(ct, xb, -1.0 / 16.0, s);
        outer(ct, xi, -1.0 / 8.0, s);
    }
}

/// `class[v]` of a vertex that uses the regular rules (interior valence 6).
const REGULAR: u8 = 0;
/// `class[v]` of a boundary vertex.
const BOUNDARY: u8 = 1;
/// `class[v]` of an extraordinary vertex without tabulated weights (valence
/// 64 or more): left to [`Rules::edge`].
const SLOW: u8 = 2;
/// `class[v]` of an extraordinary vertex with a precomputed ring.
const RING: u8 = 3;

/// The one-ring of every extraordinary interior vertex, walked once per level
/// (an EV edge point then reads it instead of swinging around the vertex:
/// `k` dependent loads, each a likely cache miss, for every one of its `k`
/// edges). `class` holds one byte per vertex (small enough to stay in cache
/// while edge points are computed); the `i`-th [`RING`] vertex `evs[i]` has
/// its ring in `corners/verts[start[i]..start[i + 1]]`, in swing order from
/// `C[v]` (`verts[j] = v(n(corners[j]))`).
struct EvRings {
    class: Vec<u8>,
    evs: Vec<u32>,
    start: Vec<u32>,
    corners: Vec<u32>,
    verts: Vec<u32>,
}

impl EvRings {
    fn new(lv: &Level, tabulated: usize) -> Self {
        let nv = lv.num_vertices();
        let is_ev = |v: usize| !lv.boundary[v] && lv.valences()[v] != 6;
        let slow = |v: usize| is_ev(v) && lv.valences()[v] as usize >= tabulated;
        let class: Vec<u8> = (0..nv)
            .into_par_iter()
            .with_min_len(8192)
            .map(|v| {
                if lv.boundary[v] {
                    BOUNDARY
                } else if slow(v) {
                    SLOW
                } else if is_ev(v) {
                    RING
                } else {
                    REGULAR
                }
            })
            .collect();
        // extraordinary vertices are few (the input's, after level 1)
        let evs: Vec<u32> =
            (0..nv as u32).into_par_iter().with_min_len(8192).filter(|&v| class[v as usize] == RING).collect();
        let mut start = Vec::with_capacity(evs.len() + 1);
        let mut total = 0u32;
        for &v in &evs {
            start.push(total);
            total += lv.valences()[v as usize];
        }
        start.push(total);
        let mut corners = vec![0u32; total as usize];
        let mut verts = vec![0u32; total as usize];
        // carve the ring storage into one piece per vertex and fill them in parallel
        let mut pieces = Vec::with_capacity(evs.len());
        let (mut rc, mut rv) = (&mut corners[..], &mut verts[..]);
        for w in start.windows(2) {
            let k = (w[1] - w[0]) as usize;
            let (a, b) = std::mem::take(&mut rc).split_at_mut(k);
            let (x, y) = std::mem::take(&mut rv).split_at_mut(k);
            pieces.push((a, x));
            (rc, rv) = (b, y);
        }
        evs.par_iter().zip(pieces).with_min_len(256).for_each(|(&v, (cs, vs))| {
            let mut c = lv.c_table()[v as usize];
            for (cj, vj) in cs.iter_mut().zip(vs.iter_mut()) {
                *cj = c;
                *vj = lv.vtx(n(c));
                c = lv.s(c).unwrap_or(c);
            }
        });
        EvRings { class, evs, start, corners, verts }
    }
}

impl ModifiedButterfly {
    /// [`Self::ev_rule`] from the precomputed ring of extraordinary vertex
    /// `v`, starting at the neighbour across corner `x` (a corner of
    /// `v` in the triangle of the edge).
    #[inline(never)]
    fn ev_ring<P: Coord>(&self, r: &EvRings, v: u32, x: u32, scale: f64, acc: &mut Accumulate<P>) {
        let i = r.evs.binary_search(&v).expect("a RING vertex is listed");
        let (a, b) = (r.start[i] as usize, r.start[i + 1] as usize);
        let (cs, vs) = (&r.corners[a..b], &r.verts[a..b]);
        let k = cs.len();
        let j0 = cs.iter().position(|&c| c == x).unwrap_or(0);
        acc.add(v, 0.75 * scale);
        let ws = &self.ev[k];
        for (j, &wj) in ws.iter().enumerate() {
            let q = j0 + j;
            acc.add(vs[if q >= k { q - k } else { q }], wj * scale);
        }
    }
}

impl ModifiedButterfly {
    /// The point on the edge owned by `c`, [`Rules::edge_points`]'s body:
    /// regular interior edges (most of them) take the 8-point rule after
    /// one class load per endpoint; edges at extraordinary vertices read
    /// the rings walked once per level; everything else (boundary, tension)
    /// goes through [`Rules::edge`].
    fn edge_point<P: Coord>(&self, lv: &Level, rings: &EvRings, pos: &[P], c: u32) -> P {
        let mut acc = Accumulate::new(pos);
        let o_raw = lv.o_table()[c as usize];
        if o_raw == BORDER {
            self.edge_cold(lv, c, &mut acc);
            return acc.sum;
        }
        let (a1, a2) = (lv.vtx(n(c)), lv.vtx(p(c)));
        let (k1, k2) = (rings.class[a1 as usize], rings.class[a2 as usize]);
        if k1 == REGULAR && k2 == REGULAR && self.w == 0.0 {
            // both ends interior: every outer edge is interior too
            match eight_point_interior(lv, pos, c, o_raw) {
                Some(e) => acc.sum = e,
                None => eight_point(lv, c, o_raw, &mut acc),
            }
        } else if k1 == RING && k2 == RING {
            self.ev_ring(rings, a1, n(c), 0.5, &mut acc);
            self.ev_ring(rings, a2, n(o_raw), 0.5, &mut acc);
        } else if k1 == RING && k2 < SLOW {
            self.ev_ring(rings, a1, n(c), 1.0, &mut acc);
        } else if k2 == RING && k1 < SLOW {
            self.ev_ring(rings, a2, n(o_raw), 1.0, &mut acc);
        } else {
            self.edge_cold(lv, c, &mut acc);
        }
        acc.sum
    }

    /// [`Rules::edge`] out of line: the rare cases stay out of the hot loop.
    #[inline(never)]
    fn edge_cold<P: Coord>(&self, lv: &Level, c: u32, acc: &mut Accumulate<P>) {
        self.edge(lv, c, acc);
    }
}

impl Rules for ModifiedButterfly {
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

    /// Direct evaluation, the same stencils as [`Rules::edge`]: one
    /// `edge_point` per edge.
    fn edge_points<P: Coord>(&self, lv: &Level, owners: Owners, pos: &[P], _: &mut [P], epart: &mut [P]) {
        let rings = EvRings::new(lv, self.ev.len());
        owners.par_pieces(epart, |qs, cs| {
            for (q, &c) in qs.iter_mut().zip(cs) {
                *q = self.edge_point(lv, &rings, pos, c);
            }
        });
    }

    fn edge<S: Sink>(&self, ct: &Level, c: u32, s: &mut S) {
        let Some(o) = ct.o(c) else {
            return four_point(ct, c, s);
        };
        // triangle t(c) = (b1, a1, a2), triangle t(o) = (b2, a2, a1)
        let (a1, a2) = (ct.vtx(n(c)), ct.vtx(p(c)));
        let (bd1, bd2) = (ct.is_boundary_vertex(a1), ct.is_boundary_vertex(a2));
        let (k1, k2) = (ct.valences()[a1 as usize], ct.valences()[a2 as usize]);
        let ev1 = !bd1 && k1 != 6;
        let ev2 = !bd2 && k2 != 6;
        match (ev1, ev2) {
            (true, true) => {
                self.ev_rule(ct, n(c), 0.5, s);
                self.ev_rule(ct, n(o), 0.5, s);
            }
            (true, false) => self.ev_rule(ct, n(c), 1.0, s),
            (false, true) => self.ev_rule(ct, n(o), 1.0, s),
            (false, false) if !bd1 && !bd2 => {
                let w = f64::from(self.w);
                if w == 0.0 {
                    return eight_point(ct, c, o, s);
                }
                s.add(a1, 0.5 - w);
                s.add(a2, 0.5 - w);
                s.add(ct.vtx(c), 0.125 + 2.0 * w);
                s.add(ct.vtx(o), 0.125 + 2.0 * w);
                for x in [n(c), p(c), n(o), p(o)] {
                    outer(ct, x, -0.0625 - w, s);
                }
                s.add(Self::beyond(ct, n(c)), w);
                s.add(Self::beyond(ct, n(o)), w);
            }
            (false, false) => {
                let (b1, b2) = (ct.vtx(c), ct.vtx(o));
                // corners facing the outer edges: p(c) faces (b1,a1), n(c) faces (a2,b1),
                // n(o) faces (a1,b2), p(o) faces (b2,a2)
                if bd1 && !bd2 && k1 == 4 {
                    if ct.is_border(p(c)) {
                        // (a1,b1) is on the border: b1 is the boundary wing
                        Self::mesh_rule(ct, a1, a2, b1, b2, n(o), n(c), p(o), s);
                    } else {
                        Self::mesh_rule(ct, a1, a2, b2, b1, p(c), p(o), n(c), s);
                    }
                } else if bd2 && !bd1 && k2 == 4 {
                    if ct.is_border(n(c)) {
                        // (a2,b1) is on the border
                        Self::mesh_rule(ct, a2, a1, b1, b2, p(o), p(c), n(o), s);
                    } else {
                        Self::mesh_rule(ct, a2, a1, b2, b1, n(c), n(o), p(c), s);
                    }
                } else {
                    eight_point(ct, c, o, s);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn ev_weights_sum_to_quarter_and_match_tables() {
        for k in 2..40 {
            let s: f64 = ev_weights(k).iter().sum();
            assert!((s - 0.25).abs() < 1e-12, "k={k} sum={s}");
        }
        // the eigen-structure of docs/schemes.md §4.4: mode 1 of the circulant
        // (sum_j s_j cos(2 pi j / k)) is 1/2 for every valence, the k = 2
        // rule included
        for k in 2..40 {
            let m1: f64 = ev_weights(k)
                .iter()
                .enumerate()
                .map(|(j, s)| s * (std::f64::consts::TAU * j as f64 / f64::from(k)).cos())
                .sum();
            assert!((m1 - 0.5).abs() < 1e-12, "k={k} mode 1 = {m1}");
        }
        let w5 = ev_weights(5);
        assert!((w5[0] - 0.35).abs() < 1e-12 && (w5[1] - 0.030902).abs() < 1e-6);
        assert!((ev_weights(8)[2] + 1.0 / 32.0).abs() < 1e-12);
        assert!((ev_weights(7)[0] - 0.25).abs() < 1e-12);
    }
}
