//! The interface between a scheme and the machinery that applies it.
//!
//! A scheme only *emits* the stencil of each new point: pairs (old vertex id,
//! weight) through a [`Sink`]. The same emission code therefore serves the
//! one-shot subdivision (an [`Accumulate`] sink sums weighted positions, fully
//! inlined) and the stencil plan for animation (a recording sink stores the
//! weights once). All rules read the OLD level only.
//!
//! This is the rules layer of subdivision (OpenSubdiv's `sdc`): masks only,
//! no tables and no timing. One file per scheme, [`features`] for which
//! rule a sharp vertex or edge gets, [`crease`] for the stencils that
//! follow from it, [`limit`] for limit positions and normals. The
//! refinement that applies them level by level is
//! [`crate::subdiv::refine`]; the tables that record them,
//! [`crate::subdiv::tables`].

pub(crate) mod butterfly;
pub(crate) mod catmull_clark;
pub(crate) mod crease;
pub(crate) mod features;
pub(crate) mod jarek;
pub(crate) mod limit;
pub(crate) mod loop_;
pub(crate) mod midpoint;
pub(crate) mod modified_butterfly;

use crate::mesh::split::Owners;
use crate::mesh::{BORDER, CornerTable, n, p};
use features::Features;
use glam::Vec3;
use rayon::prelude::*;
use std::borrow::Cow;

/// One level's topology plus per-vertex facts that rules ask for often. It
/// dereferences to the [`CornerTable`], so rules call the table's operators
/// directly; [`Level::is_boundary_vertex`] answers from a flag array (one
/// load) instead of `O[p(C[v])]` (two dependent loads).
pub(crate) struct Level<'a> {
    /// The table (for [`Rules::CUT_AT_CREASES`] schemes on a level with
    /// creases: the table cut open along them).
    pub ct: &'a CornerTable,
    /// `boundary[v]`: is vertex `v` on the boundary?
    pub boundary: Vec<bool>,
    /// The level's sharp features, classified (`None`: no sharpness).
    pub features: Option<&'a Features>,
}

impl<'a> Level<'a> {
    /// Precomputes the per-vertex flags of `ct` (parallel, O(V)).
    pub(crate) fn new(ct: &'a CornerTable) -> Self {
        Self::with_boundary(ct, boundary_flags(ct))
    }
    /// A level whose boundary flags are known.
    pub(crate) fn with_boundary(ct: &'a CornerTable, boundary: Vec<bool>) -> Self {
        Level { ct, boundary, features: None }
    }
    /// This level with its sharp features.
    pub(crate) fn with_features(mut self, features: Option<&'a Features>) -> Self {
        self.features = features;
        self
    }
    /// Is vertex `v` on the boundary?
    #[inline(always)]
    pub(crate) fn is_boundary_vertex(&self, v: u32) -> bool {
        self.boundary[v as usize]
    }
}

/// `boundary[v]`: is vertex `v` of `ct` on the boundary (parallel, O(V)).
pub(crate) fn boundary_flags(ct: &CornerTable) -> Vec<bool> {
    ct.c_table().par_iter().with_min_len(8192).map(|&c| ct.o_table()[p(c) as usize] == BORDER).collect()
}

impl std::ops::Deref for Level<'_> {
    type Target = CornerTable;
    #[inline(always)]
    fn deref(&self) -> &CornerTable {
        self.ct
    }
}

/// Receives the weights of one stencil.
pub(crate) trait Sink {
    /// Adds `w` times old vertex `v`. Rules compute their weights in f64;
    /// a sink of single-precision values rounds each weight to f32 as it
    /// takes it (so a fast pass that rounds the same weights alike gives
    /// the same sums), a double-precision one keeps it.
    fn add(&mut self, v: u32, w: f64);
}

pub(crate) use crate::mesh::coord::Coord;

/// Sums weighted old positions.
pub(crate) struct Accumulate<'a, P = Vec3> {
    /// Old positions.
    pub pos: &'a [P],
    /// The running sum.
    pub sum: P,
}

impl<'a, P: Coord> Accumulate<'a, P> {
    /// A zero sum over `pos`.
    #[inline(always)]
    pub(crate) fn new(pos: &'a [P]) -> Self {
        Accumulate { pos, sum: P::ZERO }
    }
}

impl<P: Coord> Sink for Accumulate<'_, P> {
    #[inline(always)]
    fn add(&mut self, v: u32, w: f64) {
        self.sum += self.pos[v as usize].times(w);
    }
}

/// Records a stencil as (index, weight) pairs, the weights rounded to f32
/// (the stencil plans' precision) or kept in f64 (`Record<f64>`).
pub(crate) struct Record<W = f32> {
    /// Vertex ids.
    pub idx: Vec<u32>,
    /// Weights.
    pub w: Vec<W>,
}

impl<W> Default for Record<W> {
    fn default() -> Self {
        Record { idx: Vec::new(), w: Vec::new() }
    }
}

/// A weight type a [`Record`] stores.
pub trait Weight: Copy + Send + Sync + 'static {
    /// `w` in this type (rounded for f32).
    fn of(w: f64) -> Self;
    /// This weight in f64.
    fn wide(self) -> f64;
}

impl Weight for f32 {
    #[inline(always)]
    fn of(w: f64) -> f32 {
        w as f32
    }
    #[inline(always)]
    fn wide(self) -> f64 {
        f64::from(self)
    }
}

impl Weight for f64 {
    #[inline(always)]
    fn of(w: f64) -> f64 {
        w
    }
    #[inline(always)]
    fn wide(self) -> f64 {
        self
    }
}

impl<W: Weight> Sink for Record<W> {
    #[inline]
    fn add(&mut self, v: u32, w: f64) {
        self.idx.push(v);
        self.w.push(W::of(w));
    }
}

/// The rules of one scheme: a stencil for every edge point and (for
/// approximating schemes) every vertex point, smooth and along creases
/// (how the two are chosen and blended is [`super::features`]).
pub(crate) trait Rules: Sync {
    /// Whether old vertices move (Loop, Jarek) or are copied (interpolating).
    const MOVES_VERTICES: bool;
    /// Whether the smooth stencils reach across edges, so that on a level
    /// with creases they must see the level cut open along them (the
    /// butterfly family; docs/sharp-features.md §6.2).
    const CUT_AT_CREASES: bool = false;
    /// Smooth stencil of the new vertex on the edge opposite owner corner
    /// `c` (the scheme's boundary rule where `c` is a border corner).
    fn edge<S: Sink>(&self, ct: &Level, c: u32, s: &mut S);
    /// Smooth stencil of old vertex `v`'s new position (the boundary rule
    /// for a boundary vertex).
    #[inline(always)]
    fn vertex<S: Sink>(&self, _ct: &Level, v: u32, s: &mut S) {
        s.add(v, 1.0);
    }
    /// The curve rule of the edge owned by `c` along a crease (the default:
    /// its midpoint). `c` names the same edge in the cut and uncut tables;
    /// read the crease from `ct.features`.
    #[inline]
    fn crease_edge<S: Sink>(&self, ct: &Level, c: u32, s: &mut S) {
        let original = |v: u32| ct.features.map_or(v, |f| f.original(v));
        s.add(original(ct.vtx(n(c))), 0.5);
        s.add(original(ct.vtx(p(c))), 0.5);
    }
    /// The curve rule of vertex `v` on a crease through its neighbours `a`
    /// and `b` (the default: `v` stays).
    #[inline]
    fn crease_vertex<S: Sink>(&self, v: u32, _a: u32, _b: u32, s: &mut S) {
        s.add(v, 1.0);
    }
    /// The old vertices' new positions over a whole level with the smooth
    /// (and boundary) rules, into `vpart`. The default sums each emitted
    /// stencil (or copies, when vertices do not move); a scheme may
    /// override it with a faster equivalent (the stencil-plan tests check
    /// the two agree).
    ///
    /// `scratch` is memory the pass may use as it likes (the level's edge
    /// part, which [`Rules::edge_points`] writes afterwards).
    fn vertex_points<P: Coord>(&self, lv: &Level, pos: &[P], vpart: &mut [P], scratch: &mut [P]) {
        let _ = scratch;
        if Self::MOVES_VERTICES {
            vpart.par_iter_mut().enumerate().with_min_len(2048).for_each(|(v, q)| {
                let mut acc = Accumulate::new(pos);
                self.vertex(lv, v as u32, &mut acc);
                *q = acc.sum;
            });
        } else {
            vpart.par_iter_mut().zip(pos.par_iter()).with_min_len(8192).for_each(|(q, &x)| *q = x);
        }
    }
    /// One point per edge, in `owners` order, with the smooth (and
    /// boundary) rules, into `epart`. It runs after
    /// [`Rules::vertex_points`] of the same level, with `vpart` as that
    /// left it: a scheme whose edge rule needs an intermediate of the
    /// vertex pass (Jarek's displacements) may leave it there and finish
    /// the vertex points here. The default sums each emitted stencil.
    fn edge_points<P: Coord>(&self, lv: &Level, owners: Owners, pos: &[P], vpart: &mut [P], epart: &mut [P]) {
        let _ = vpart;
        stencil_edge_points(self, lv, owners, pos, epart);
    }
}

/// Every edge point through the emitted stencils.
///
/// The owners come in increasing order, so `V`, `O` and the owner's own
/// corners are read almost in sequence; the vertex across the edge,
/// `V[O[c]]`, is not, and at the last levels the stencil waits for its
/// cache miss. It is prefetched 32 edges before it is needed, so
/// that the misses of many edges overlap: bunny Loop level 3, the edge
/// points of all levels on one thread, warm (`examples/phases`), 21-22 ms
/// without against 13.3-13.9 with (8 edges ahead gave 15-16, 24 to 96 the
/// same as 32; prefetching the four positions as well made it slower).
pub(crate) fn stencil_edge_points<R: Rules + ?Sized, P: Coord>(
    r: &R,
    lv: &Level,
    owners: Owners,
    pos: &[P],
    out: &mut [P],
) {
    let (vt, ot) = (lv.v_table(), lv.o_table());
    owners.par_pieces(out, |out, own| {
        for (i, (q, &c)) in out.iter_mut().zip(own).enumerate() {
            if let Some(&ahead) = own.get(i + AHEAD) {
                // a border corner's O is BORDER, out of bounds: no prefetch
                crate::cpu::prefetch(vt, ot[ahead as usize] as usize);
            }
            let mut acc = Accumulate::new(pos);
            r.edge(lv, c, &mut acc);
            *q = acc.sum;
        }
    });
}

/// How many edges ahead [`stencil_edge_points`] prefetches.
const AHEAD: usize = 32;

/// [`ring_sums`], then `out[v] = f(v, sum)`, in the same pass that adds the
/// per-thread accumulators and fixes boundary vertices (one pass over the
/// vertices instead of three). The accumulators of the threads after the
/// first are taken from `scratch` as far as it holds them (its contents are
/// overwritten), so that a level's edge part, written afterwards, serves as
/// memory already faulted in; the rest are allocated.
pub(crate) fn ring_sums_map<P: Coord>(
    lv: &Level,
    pos: &[P],
    out: &mut [P],
    scratch: &mut [P],
    f: impl Fn(usize, P) -> P + Sync,
) {
    let (vt, nc) = (lv.ct.v_table(), lv.ct.num_corners());
    // a part takes at least 2^20 corners: below that its accumulator's
    // fresh pages and the merge cost more than it saves (fandisk's level 3,
    // 620 k corners scattered: 3.0-3.6 ms on two threads, 1.5-2.0 on one)
    let threads = crate::mesh::scatter_count(nc, 1 << 20);
    let per = nc.div_ceil(threads).div_ceil(3) * 3;
    let scatter = |acc: &mut [P], k: usize| {
        for tri in vt[(k * per).min(nc)..((k + 1) * per).min(nc)].chunks_exact(3) {
            let (a, b, c) = (tri[0] as usize, tri[1] as usize, tri[2] as usize);
            let (pa, pb, pc) = (pos[a], pos[b], pos[c]);
            acc[a] += pb;
            acc[b] += pc;
            acc[c] += pa;
        }
    };
    let extra = &scatter_parts(out, threads, scratch, scatter);
    out.par_iter_mut().enumerate().with_min_len(8192).for_each(|(v, q)| {
        let mut sum = *q;
        for e in extra {
            sum += e[v];
        }
        if lv.boundary[v]
            && let Some((a, b)) = lv.boundary_neighbours(v as u32)
        {
            sum = pos[a as usize] + pos[b as usize];
        }
        *q = f(v, sum);
    });
}

/// Runs a scatter pass in `parts` parts, in parallel: `scatter(acc, k)` sums
/// part `k` into `acc`. Part 0 sums into `out` itself; each later part into
/// an accumulator of `out.len()` points, taken from `scratch` as far as it
/// holds them (memory a level has already faulted in and writes only later,
/// such as its edge part: at bunny Loop level 3 on two threads 6.7 MB of
/// fresh pages fewer), the rest allocated. Every accumulator, `out` too, is
/// cleared by the thread that then fills it. Returns the later parts'
/// accumulators, in order, for the caller to add per point.
pub(crate) fn scatter_parts<'s, P: Coord>(
    out: &mut [P],
    parts: usize,
    scratch: &'s mut [P],
    scatter: impl Fn(&mut [P], usize) + Sync,
) -> Vec<Cow<'s, [P]>> {
    let (n, later) = (out.len(), parts.saturating_sub(1));
    let from_scratch = scratch.len().checked_div(n).map_or(0, |k| k.min(later));
    let mut borrowed: Vec<&'s mut [P]> = scratch.chunks_exact_mut(n.max(1)).take(from_scratch).collect();
    let mut owned: Vec<Vec<P>> = (from_scratch..later).map(|_| crate::mem::zeroed(n)).collect();
    let scatter = &scatter;
    rayon::scope(|sc| {
        sc.spawn(move |_| {
            out.fill(P::ZERO);
            scatter(out, 0);
        });
        for (k, acc) in borrowed.iter_mut().enumerate() {
            sc.spawn(move |_| {
                acc.fill(P::ZERO);
                scatter(acc, k + 1);
            });
        }
        // fresh zero pages: nothing to clear
        for (k, acc) in owned.iter_mut().enumerate() {
            sc.spawn(move |_| scatter(acc, from_scratch + k + 1));
        }
    });
    let borrowed = borrowed.into_iter().map(|a| -> Cow<'s, [P]> { Cow::Borrowed(a) });
    borrowed.chain(owned.into_iter().map(Cow::Owned)).collect()
}

/// The 4-point curve rule along the boundary for the border edge opposite
/// owner corner `c` (Dyn, Levin, Gregory 1987; docs/schemes.md §4.5 (a)):
/// `e = 9/16 (p1 + p2) - 1/16 (p0 + p3)` with `p0, p1, p2, p3` consecutive
/// boundary vertices. Uses boundary vertices only, so the boundary curve is
/// the interpolating 4-point curve of the boundary polygon.
#[inline]
pub(crate) fn four_point<S: Sink>(ct: &CornerTable, c: u32, s: &mut S) {
    let (p1, p2) = (ct.vtx(n(c)), ct.vtx(p(c)));
    // the border edge runs p1 -> p2; p0 ends the fan of p1, p3 starts that
    // of p2 (both ends of a border edge are boundary vertices, so the
    // fallback to p1 itself is never taken)
    let p0 = ct.boundary_neighbours(p1).map_or(p1, |(_, last)| last);
    let p3 = ct.vtx(n(ct.corner_of(p2)));
    s.add(p0, -1.0 / 16.0);
    s.add(p1, 9.0 / 16.0);
    s.add(p2, 9.0 / 16.0);
    s.add(p3, -1.0 / 16.0);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;

    /// The ring sums are the same whether a thread's accumulator comes from
    /// `scratch`, is allocated, or both (scratch too small for all), and
    /// whatever was in `scratch`; to 1e-6 of one thread's (the partial sums
    /// are added in another order).
    #[test]
    fn ring_sums_take_accumulators_from_scratch_or_allocate_them() {
        // 3.9 M corners: three threads get 2^20 corners or more each
        let m = shapes::icosphere(8);
        let lv = Level::new(&m.ct);
        let nv = m.positions.len();
        let sums = |threads: usize, scratch_len: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut out = vec![Vec3::NAN; nv];
            let mut scratch = vec![Vec3::splat(7.0); scratch_len];
            pool.install(|| ring_sums_map(&lv, &m.positions, &mut out, &mut scratch, |_, s| s));
            out
        };
        let one = sums(1, 0);
        for (threads, scratch_len) in [(3, 0), (3, nv), (3, 2 * nv + 5), (2, 3 * nv)] {
            let many = sums(threads, scratch_len);
            let worst = one.iter().zip(&many).map(|(a, b)| (*a - *b).abs().max_element()).fold(0.0, f32::max);
            assert!(worst <= 1e-6, "{threads} threads, scratch {scratch_len}: off by {worst}");
        }
        // every neighbour counted once: the sum of a valence-6 vertex's ring
        // over 6 is a point near the unit sphere
        let v = (0..nv).find(|&v| m.ct.valences()[v] == 6).unwrap();
        assert!(((one[v] / 6.0).length() - 1.0).abs() < 1e-3);
    }
}
