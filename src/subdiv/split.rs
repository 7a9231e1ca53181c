//! The 1-to-4 split of a corner table, shared by every scheme. It knows no
//! weights: it only builds the new V, O, C and valence tables and numbers the
//! edges (schemes.md 7.4 and 7.5).
//!
//! Layout (`nt` old triangles; corner `c` of triangle `t = c/3`, `k = c%3`):
//! * the central triangle `t` keeps corner ids: `V'[c] = W[c]`, where `W[c]`
//!   is the new vertex on the edge opposite `c`;
//! * the corner triangle of `v(c)` starts at `A(c) = 3nt(k+1) + 3t`:
//!   `V'[A] = V[c]`, `V'[n(A)] = W[p(c)]`, `V'[p(A)] = W[n(c)]`.
//!
//! New opposites, computed directly (no rebuild):
//! ```text
//! O'[c]       = A(c)            O'[A(c)] = c
//! O'[n(A(c))] = BORDER if b(n(c)) else p(A(n(O[n(c)])))
//! O'[p(A(c))] = BORDER if b(p(c)) else n(A(p(O[p(c)])))
//! ```
//! Edges are numbered without hashing: corner `c` owns the edge opposite it
//! when `O[c]` is the border or `c < O[c]`; owners are counted per chunk, a
//! prefix sum gives each chunk its first edge id. New vertex ids: old vertices
//! keep theirs, edge `e` becomes vertex `V + e`.
//!
//! `C'` and valences propagate too: an old vertex keeps its valence and
//! `C'[v] = A(C[v])`; an edge vertex has valence 6 (interior) or 4 (border)
//! and `C' = c` (interior) or `p(A(p(c)))` (border, the first corner of its fan).

use crate::mesh::{BORDER, CornerTable, n, p};
use rayon::prelude::*;

/// Corners per parallel work item: big enough to amortise scheduling, small
/// enough to balance two to sixteen threads.
pub(crate) const CHUNK: usize = 1 << 14;

/// The edge numbering of a table: `owners[e]` is the corner owning edge `e`,
/// `w[c]` is the id of the edge opposite corner `c` (for both of its corners).
pub struct EdgeNumbering {
    /// Owner corner of every edge, in edge-id order.
    pub owners: Vec<u32>,
    /// Edge id of the edge opposite each corner.
    pub w: Vec<u32>,
}

#[inline(always)]
fn is_owner(c: u32, x: u32) -> bool {
    x == BORDER || c < x
}

/// A raw pointer that may be shared between threads which write disjoint
/// elements.
#[derive(Clone, Copy)]
struct SharedMut(*mut u32);
// SAFETY: used only for writes to elements that exactly one thread writes
// (see number_edges), and read only after the parallel loop has joined.
unsafe impl Send for SharedMut {}
unsafe impl Sync for SharedMut {}

impl SharedMut {
    /// The pointer (a method, so closures capture the whole Sync wrapper).
    #[inline(always)]
    fn get(self) -> *mut u32 {
        self.0
    }
}

/// Numbers the edges of `ct` in O(n), in parallel: owners are counted per
/// chunk, a prefix sum gives each chunk its first id, then each owner writes
/// its id to itself and to its opposite corner, so that later passes read
/// `w` sequentially instead of chasing `O`.
pub fn number_edges(ct: &CornerTable) -> EdgeNumbering {
    let o = &ct.o;
    let counts: Vec<u32> = o
        .par_chunks(CHUNK)
        .enumerate()
        .map(|(k, ch)| {
            let base = (k * CHUNK) as u32;
            ch.iter().enumerate().filter(|&(i, &x)| is_owner(base + i as u32, x)).count() as u32
        })
        .collect();
    let ne: u32 = counts.iter().sum();
    let mut owners: Vec<u32> = crate::mem::zeroed(ne as usize);
    let mut w: Vec<u32> = crate::mem::zeroed(o.len());
    // carve `owners` into one slice per chunk
    let mut slices = Vec::with_capacity(counts.len());
    let mut rest: &mut [u32] = &mut owners;
    let mut first = 0u32;
    for &cnt in &counts {
        let (a, b) = rest.split_at_mut(cnt as usize);
        slices.push((first, a));
        first += cnt;
        rest = b;
    }
    let wp = SharedMut(w.as_mut_ptr());
    let nc = o.len();
    o.par_chunks(CHUNK).zip(slices).enumerate().for_each(|(k, (och, (first, own)))| {
        let base = (k * CHUNK) as u32;
        let mut e = 0usize;
        for (i, &x) in och.iter().enumerate() {
            let c = base + i as u32;
            if is_owner(c, x) {
                let id = first + e as u32;
                own[e] = c;
                e += 1;
                // SAFETY: c < nc; x < nc for a valid table (checked at build);
                // every corner is written once: by itself if it owns its edge,
                // otherwise by its opposite (the owner). O is an involution, so
                // no two threads write the same element.
                unsafe {
                    debug_assert!((c as usize) < nc);
                    *wp.get().add(c as usize) = id;
                    if x != BORDER {
                        debug_assert!((x as usize) < nc);
                        *wp.get().add(x as usize) = id;
                    }
                }
            }
        }
    });
    EdgeNumbering { owners, w }
}

/// Splits every triangle into four. Returns the new table and the edge
/// numbering of the old one (edge `e` became vertex `old.num_vertices() + e`).
pub fn split(old: &CornerTable) -> (CornerTable, EdgeNumbering) {
    split_timed(old).0
}

/// [`split`], also returning the milliseconds spent numbering edges and
/// writing the new tables.
pub fn split_timed(old: &CornerTable) -> ((CornerTable, EdgeNumbering), (f64, f64)) {
    let t0 = std::time::Instant::now();
    let edges = number_edges(old);
    let t1 = std::time::Instant::now();
    let nt = old.num_triangles();
    let nv = old.num_vertices() as u32;
    let nc = 3 * nt;
    let (ov, oo) = (&old.v, &old.o);
    let ew = &edges.w;
    let a = |c: u32| (3 * nt * (c as usize % 3 + 1) + 3 * (c as usize / 3)) as u32;

    let mut v2: Vec<u32> = crate::mem::zeroed(4 * nc);
    let mut o2: Vec<u32> = crate::mem::zeroed(4 * nc);
    {
        let (b0, rest) = v2.split_at_mut(nc);
        let (b1, rest) = rest.split_at_mut(nc);
        let (b2, b3) = rest.split_at_mut(nc);
        let (q0, rest) = o2.split_at_mut(nc);
        let (q1, rest) = rest.split_at_mut(nc);
        let (q2, q3) = rest.split_at_mut(nc);
        let g = CHUNK / 3 * 3;
        b0.par_chunks_mut(g)
            .zip(b1.par_chunks_mut(g))
            .zip(b2.par_chunks_mut(g))
            .zip(b3.par_chunks_mut(g))
            .zip(q0.par_chunks_mut(g))
            .zip(q1.par_chunks_mut(g))
            .zip(q2.par_chunks_mut(g))
            .zip(q3.par_chunks_mut(g))
            .enumerate()
            .for_each(|(k, (((((((b0, b1), b2), b3), q0), q1), q2), q3))| {
                let base = (k * g) as u32;
                let mut bv = [b1, b2, b3];
                let mut bo = [q1, q2, q3];
                for i in (0..b0.len()).step_by(3) {
                    let c0 = base + i as u32;
                    let j = c0 as usize;
                    let ws = [nv + ew[j], nv + ew[j + 1], nv + ew[j + 2]];
                    b0[i..i + 3].copy_from_slice(&ws);
                    for kk in 0..3u32 {
                        let c = c0 + kk;
                        let (cn, cp) = (n(c), p(c));
                        // central corner c faces the corner triangle's corner A(c)
                        q0[i + kk as usize] = a(c);
                        let bvk = &mut bv[kk as usize];
                        bvk[i] = ov[c as usize];
                        bvk[i + 1] = ws[(cp - c0) as usize];
                        bvk[i + 2] = ws[(cn - c0) as usize];
                        let bok = &mut bo[kk as usize];
                        bok[i] = c;
                        let x = oo[cn as usize];
                        bok[i + 1] = if x == BORDER { BORDER } else { p(a(n(x))) };
                        let y = oo[cp as usize];
                        bok[i + 2] = if y == BORDER { BORDER } else { n(a(p(y))) };
                    }
                }
            });
    }
    let ne = edges.owners.len();
    let nvu = nv as usize;
    let mut vc: Vec<u32> = crate::mem::zeroed(nvu + ne);
    let mut valence: Vec<u32> = crate::mem::zeroed(nvu + ne);
    {
        let (vc_old, vc_new) = vc.split_at_mut(nvu);
        let (val_old, val_new) = valence.split_at_mut(nvu);
        vc_old.par_iter_mut().zip(old.vc.par_iter()).with_min_len(CHUNK).for_each(|(d, &c)| *d = a(c));
        val_old.par_iter_mut().zip(old.valence.par_iter()).with_min_len(CHUNK).for_each(|(d, &k)| *d = k);
        vc_new.par_iter_mut().zip(val_new.par_iter_mut()).zip(edges.owners.par_iter()).with_min_len(CHUNK).for_each(
            |((d, k), &c)| {
                if oo[c as usize] == BORDER {
                    *d = p(a(p(c)));
                    *k = 4;
                } else {
                    *d = c;
                    *k = 6;
                }
            },
        );
    }
    let times = (super::ms(t1 - t0), super::ms(t1.elapsed()));
    ((CornerTable { v: v2, o: o2, vc, valence }, edges), times)
}
