//! The 1-to-4 split of a corner table, shared by every scheme. It knows no
//! weights: it only builds the new V, O, C and valence tables and numbers the
//! edges (docs/schemes.md §7.4-7.7).
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
//! Edge generations (see [`super::Generations`]: the generation of the edge
//! opposite each corner) follow from this layout, for the new level `j`:
//! the six corners facing the three interior edges of a split triangle (`c`
//! and `A(c)`) get `j`, and a corner facing half of an old edge inherits
//! that edge's generation: `g'[n(A(c))] = g[n(c)]`, `g'[p(A(c))] = g[p(c)]`.
//! So the split stores none: it records its triangle count, and the
//! generations are read back through these formulas when asked for.
//!
//! `C'` and valences propagate too: an old vertex keeps its valence and
//! `C'[v] = A(C[v])`; an edge vertex has valence 6 (interior) or 4 (border)
//! and `C' = c` (interior) or `p(A(p(c)))` (border, the first corner of its fan).

use super::{BORDER, CornerTable, Creasing, Mesh, VertexId, n, owns_edge, p};
use rayon::prelude::*;

/// Corners per parallel work item: big enough to amortise scheduling, small
/// enough to balance two to sixteen threads.
pub(crate) const CHUNK: usize = 1 << 14;

/// The edge numbering of a table: `owners[e]` is the corner owning edge `e`;
/// [`EdgeIds`] gives the id of the edge opposite any corner.
pub struct EdgeNumbering {
    /// Owner corner of every edge, in edge-id order.
    pub owners: Vec<u32>,
    /// The id of the edge opposite each corner.
    pub ids: EdgeIds,
}

/// The id of the edge opposite every corner, without an array of them: an
/// edge's id is the number of owner corners before its owner (edges are
/// numbered in owner order), so one bit per corner (is it an owner?) and
/// the count of owners before each 64-corner word answer it with one
/// popcount. At bunny level 3 that is 0.6 MB, which stays in the cache,
/// against a 13 MB array of ids that the numbering pass wrote at random
/// (`w[O[c]]`, a cache miss each) and the writing pass read back.
#[derive(Clone, Debug, Default)]
pub struct EdgeIds {
    /// Bit `c % 64` of word `c / 64`: corner `c` owns its edge.
    owns: Vec<u64>,
    /// Owner corners before word `k`.
    before: Vec<u32>,
}

impl EdgeIds {
    /// The owner bits of the table whose O table is `o_table`, in parallel.
    pub(crate) fn new(o_table: &[u32]) -> EdgeIds {
        let owns: Vec<u64> = o_table
            .par_chunks(64)
            .with_min_len(CHUNK / 64)
            .enumerate()
            .map(|(k, ch)| owner_bits(64 * k as u32, ch))
            .collect();
        let mut before = Vec::with_capacity(owns.len() + 1);
        let mut sum = 0u32;
        before.push(0);
        for w in &owns {
            sum += w.count_ones();
            before.push(sum);
        }
        EdgeIds { owns, before }
    }

    /// Number of edges.
    pub(crate) fn count(&self) -> u32 {
        self.before.last().copied().unwrap_or(0)
    }

    /// Owner corners before corner `c` (`c` up to the corner count).
    #[inline(always)]
    pub(crate) fn rank(&self, c: u32) -> u32 {
        let (k, i) = ((c / 64) as usize, c % 64);
        let below = self.owns.get(k).map_or(0, |w| (w & ((1u64 << i) - 1)).count_ones());
        self.before[k] + below
    }

    /// The id of the edge opposite corner `c`, whose O entry is `x`.
    #[inline(always)]
    pub(crate) fn edge(&self, c: u32, x: u32) -> u32 {
        if owns_edge(c, x) { self.rank(c) } else { self.rank(x) }
    }

    /// [`EdgeIds::edge`] for a pass that visits corners in increasing order
    /// from some corner `s` on, `next` starting at `rank(s)`: an owner's id
    /// is `next`, counted up as the owners pass, so only the other corners
    /// pay a rank (a popcount).
    #[inline(always)]
    pub(crate) fn edge_in_order(&self, c: u32, x: u32, next: &mut u32) -> u32 {
        if owns_edge(c, x) {
            *next += 1;
            *next - 1
        } else {
            self.rank(x)
        }
    }
}

/// Bit `i`: corner `base + i` owns its edge, for the (at most 64) O entries
/// `ch` of corners `base ..`. A whole word is made a byte per corner, in a
/// loop the compiler vectorises, and packed eight bytes at a time with one
/// multiplication (byte `j` of a word of 0s and 1s lands on bit `56 + j`):
/// at bunny level 2, 3.3 M corners, 0.7 ms on one thread against 1.7 for
/// a shift and an or per corner.
#[inline]
fn owner_bits(base: u32, ch: &[u32]) -> u64 {
    let Ok(ch) = <&[u32; 64]>::try_from(ch) else {
        return ch.iter().enumerate().fold(0, |bits, (i, &x)| bits | (u64::from(owns_edge(base + i as u32, x)) << i));
    };
    let mut owns = [0u8; 64];
    for (i, (b, &x)) in owns.iter_mut().zip(ch).enumerate() {
        *b = u8::from(owns_edge(base + i as u32, x));
    }
    let (eights, _) = owns.as_chunks::<8>();
    eights
        .iter()
        .enumerate()
        .fold(0, |bits, (j, e)| bits | ((u64::from_le_bytes(*e).wrapping_mul(0x0102_0408_1020_4080) >> 56) << (8 * j)))
}

impl EdgeIds {
    /// `out` (one element per edge) cut into one piece per [`CHUNK`] of
    /// corners: the pieces of the edges those corners own, in order.
    fn carve<'a, T>(&self, mut out: &'a mut [T]) -> Vec<&'a mut [T]> {
        const WORDS: usize = CHUNK / 64;
        let chunks = self.owns.len().div_ceil(WORDS);
        let mut pieces = Vec::with_capacity(chunks);
        for k in 0..chunks {
            let (first, end) = (self.before[k * WORDS], self.before[((k + 1) * WORDS).min(self.owns.len())]);
            let (a, b) = std::mem::take(&mut out).split_at_mut((end - first) as usize);
            pieces.push(a);
            out = b;
        }
        pieces
    }

    /// Calls `f` with every owner corner among corners `CHUNK k ..`, in
    /// order, read off their bits (a loop per owner, without a branch per
    /// corner on whether it owns its edge).
    fn for_each_owner(&self, k: usize, mut f: impl FnMut(u32)) {
        const WORDS: usize = CHUNK / 64;
        let words = &self.owns[k * WORDS..((k + 1) * WORDS).min(self.owns.len())];
        for (i, &w) in words.iter().enumerate() {
            let base = 64 * (k * WORDS + i) as u32;
            let mut bits = w;
            while bits != 0 {
                f(base + bits.trailing_zeros());
                bits &= bits - 1;
            }
        }
    }
}

/// The owner corners of a table's edges, in edge-id order: a list (what
/// [`number_edges`] makes), or read off the owner bits piece by piece, for
/// a level that made no list (the last level of a subdivision that keeps
/// only its faces: at bunny level 3 the list is 6.7 MB written, faulted in
/// and read once).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Owners<'a> {
    /// `list[e]` owns edge `e`.
    List(&'a [u32]),
    /// The owner bits: the `e`-th owner corner owns edge `e`.
    Bits(&'a EdgeIds),
}

impl Owners<'_> {
    /// Number of edges.
    pub(crate) fn len(&self) -> usize {
        match self {
            Owners::List(list) => list.len(),
            Owners::Bits(ids) => ids.count() as usize,
        }
    }

    #[cfg(test)]
    /// Whether there are no edges.
    pub(crate) fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Calls `each(out, owners)` in parallel on consecutive pieces of `out`
    /// (one element per edge) and of the owners: `out[i]` is the element of
    /// the edge that `owners[i]` owns. A piece has at most 16,384 owners.
    ///
    /// # Panics
    /// If `out` does not have one element per edge.
    pub(crate) fn par_pieces<T: Send>(&self, out: &mut [T], each: impl Fn(&mut [T], &[u32]) + Sync) {
        assert_eq!(out.len(), self.len(), "one element per edge");
        match *self {
            Owners::List(list) => {
                out.par_chunks_mut(CHUNK / 4).zip(list.par_chunks(CHUNK / 4)).for_each(|(o, c)| each(o, c));
            }
            Owners::Bits(ids) => ids.carve(out).into_par_iter().enumerate().for_each(|(k, piece)| {
                let mut list = Vec::with_capacity(piece.len());
                ids.for_each_owner(k, |c| list.push(c));
                each(piece, &list);
            }),
        }
    }
}

/// A raw pointer that may be shared between threads which write disjoint
/// elements.
#[derive(Clone, Copy)]
struct SharedMut(*mut u32);
// SAFETY: used only for writes to elements that exactly one thread writes
// (see number_edges_with and NewVertexTables), and read only after the
// parallel loop has joined.
unsafe impl Send for SharedMut {}
unsafe impl Sync for SharedMut {}

/// [`SharedMut`] for flags.
#[derive(Clone, Copy)]
struct SharedBool(*mut bool);
// SAFETY: as for SharedMut: each element is written by one thread.
unsafe impl Send for SharedBool {}
unsafe impl Sync for SharedBool {}

impl SharedBool {
    #[inline(always)]
    fn get(self) -> *mut bool {
        self.0
    }
}

impl SharedMut {
    /// The pointer (a method, so closures capture the whole Sync wrapper).
    #[inline(always)]
    fn get(self) -> *mut u32 {
        self.0
    }
}

/// Numbers the edges of `ct` in O(n), in parallel: the owner bits and
/// their counts first (`EdgeIds`), then every chunk lists its owners from
/// its first id on.
pub fn number_edges(ct: &CornerTable) -> EdgeNumbering {
    number_edges_with(ct.o_table(), EdgeIds::new(ct.o_table()), |_, _, _| {})
}

/// [`number_edges`] of the table whose O (or polygon twin) table is
/// `o_table`, from its owner bits `ids`, calling `each(id, owner,
/// opposite)` for every edge, in parallel, while the numbering pass has the
/// three at hand (the split fills the new vertices' `C` and valence this
/// way, without another pass). `opposite` is the raw O entry of the owner:
/// a corner, or [`BORDER`].
pub(crate) fn number_edges_with(o_table: &[u32], ids: EdgeIds, each: impl Fn(u32, u32, u32) + Sync) -> EdgeNumbering {
    let mut owners: Vec<u32> = crate::mem::zeroed(ids.count() as usize);
    let slices = ids.carve(&mut owners);
    slices.into_par_iter().enumerate().for_each(|(k, own)| {
        let first = ids.rank((k * CHUNK) as u32);
        let mut e = 0usize;
        ids.for_each_owner(k, |c| {
            own[e] = c;
            each(first + e as u32, c, o_table[c as usize]);
            e += 1;
        });
    });
    EdgeNumbering { owners, ids }
}

/// Splits every triangle into four. Returns the new table and the edge
/// numbering of the old one (edge `e` became vertex `old.num_vertices() + e`).
///
/// # Panics
/// If the new table's corner or vertex ids would not fit below [`BORDER`]
/// (more than about 358 million old triangles). [`crate::subdivide`] and the
/// stencil plan refuse such levels beforehand with [`crate::Error::TooLarge`].
pub fn split(old: &CornerTable) -> (CornerTable, EdgeNumbering) {
    split_timed(old).0
}

/// [`split`], the sharpness decaying by `creasing`.
pub(crate) fn split_with(old: &CornerTable, creasing: Creasing) -> (CornerTable, EdgeNumbering) {
    let ((ct, edges, _), _) = split_with_boundary(old, None, creasing);
    (ct, edges)
}

/// [`split`], also returning the milliseconds spent numbering edges and
/// writing the new tables.
///
/// Written for memory bandwidth: every output array is written exactly once,
/// in streams, by straight-line code per old triangle (no per-corner loop,
/// no bounds checks inside the loop, no division but one `x % 3` per
/// opposite corner); the new vertices' `C` and valence are written by the
/// numbering pass, which has each edge's owner and opposite at hand.
pub(crate) fn split_timed(old: &CornerTable) -> ((CornerTable, EdgeNumbering), (f64, f64)) {
    let ((ct, edges, _), times) = split_with_boundary(old, None, Creasing::Uniform);
    ((ct, edges), times)
}

/// The new table, the old table's edge numbering and (when asked for) the new
/// vertices' boundary flags.
pub(crate) type SplitLevel = (CornerTable, EdgeNumbering, Option<Vec<bool>>);

/// `A(c)`: the first corner of the corner triangle of `v(c)` in a split of a
/// table with `nt` triangles (docs/schemes.md §7.4).
#[inline(always)]
fn corner_triangle(nt: usize, c: u32) -> u32 {
    (3 * nt * (c as usize % 3 + 1) + 3 * (c as usize / 3)) as u32
}

/// [`split_timed`]; given the old vertices' boundary flags, also returns the
/// new ones (an old vertex keeps its flag, an edge vertex is on the boundary
/// iff its edge is a border edge), written by the numbering pass, so that
/// the next level need not find them by chasing `O[p(C[v])]`.
///
/// Two passes: the numbering pass ([`number_edges_and_vertices`]: edge ids,
/// and the new vertices' `C`, valence and boundary flag) and the writing
/// passes ([`write_v`] and [`write_o`], side by side: the new V and O, one
/// old triangle at a time; then [`carry_old_vertices`]: the old vertices'
/// `C` and valence).
pub(crate) fn split_with_boundary(
    old: &CornerTable,
    old_boundary: Option<&[bool]>,
    creasing: Creasing,
) -> (SplitLevel, (f64, f64)) {
    // the new table's ids (corners up to 12 F, vertices up to V + E <= 2 * 3 F
    // as every vertex has a corner) must stay below BORDER, or its O would
    // wrap and lose the invariant that the next split's raw writes rely on
    let nc = old.num_corners() as u64;
    assert!(
        4 * nc < u64::from(BORDER),
        "split: {nc} corners are too many for 32-bit ids after a split (subdivide refuses this level)"
    );
    let t0 = crate::clock::Instant::now();
    let NewVertexTables { edges, mut vc, mut valence, boundary } = number_edges_and_vertices(old, old_boundary);
    let t1 = crate::clock::Instant::now();
    let (v2, o2) = rayon::join(|| write_v(old, &edges.ids, &|j| j), || write_o(old));
    carry_old_vertices(old, &mut vc, &mut valence);
    let times = (ms(t1 - t0), ms(t1.elapsed()));
    // sharp features are sparse: carried from the old table's, beside O
    let sharpness = old.sharpness().and_then(|s| s.split(old, creasing));
    let generations = old.generations().cloned().unwrap_or_default().after_split(old.num_triangles());
    let ct = CornerTable::from_parts(v2, o2, vc, valence)
        .with_sharpness(sharpness)
        .with_holes(old.split_holes())
        .with_generations(Some(generations));
    ((ct, edges, boundary), times)
}

/// The new V table of a split and the old table's edge ids, and nothing
/// else: no O, C, valence, sharpness or generations, and no list of the
/// edges' owners ([`Owners::Bits`] reads them off the ids). For the last
/// level of a subdivision whose caller needs only its faces (writing a
/// file): at bunny level 3 that leaves out 77 MB of the 157 the level
/// wrote. The V table is the one [`split`] makes.
///
/// # Panics
/// As [`split`].
///
/// Every vertex id goes through `id` as it is written, so that a caller
/// wanting other ids (wider, or renumbered) gets them in the one pass that
/// writes the table, without a `u32` table to convert afterwards.
pub(crate) fn split_faces<I: VertexId, M: Fn(u32) -> I + Sync>(old: &CornerTable, id: &M) -> (Vec<I>, EdgeIds) {
    let nc = old.num_corners() as u64;
    assert!(4 * nc < u64::from(BORDER), "split: {nc} corners are too many for 32-bit ids after a split");
    let ids = EdgeIds::new(old.o_table());
    let v2 = write_v(old, &ids, id);
    (v2, ids)
}

/// What the numbering pass of a split produces: the old table's edge
/// numbering and the new table's per-vertex arrays.
struct NewVertexTables {
    edges: EdgeNumbering,
    vc: Vec<u32>,
    valence: Vec<u32>,
    boundary: Option<Vec<bool>>,
}

/// The numbering pass of a split: numbers the old edges and fills the new
/// vertices' part of the `C` and valence tables (and all boundary flags when
/// the old ones are given; an old vertex keeps its flag): edge vertex
/// `V + e` has valence 6 and `C' = c` (interior edge, owner `c`) or valence
/// 4 and `C' = p(A(p(c)))`, the first corner of its fan (border). The old
/// vertices' part is [`carry_old_vertices`].
fn number_edges_and_vertices(old: &CornerTable, old_boundary: Option<&[bool]>) -> NewVertexTables {
    let (nt, nvu) = (old.num_triangles(), old.num_vertices());
    let ids = EdgeIds::new(old.o_table());
    let ne = ids.count() as usize;
    let mut vc: Vec<u32> = crate::mem::zeroed(nvu + ne);
    let mut valence: Vec<u32> = crate::mem::zeroed(nvu + ne);
    let mut boundary: Option<Vec<bool>> = old_boundary.map(|b| {
        let mut nb = crate::mem::zeroed::<bool>(nvu + ne);
        nb[..nvu].copy_from_slice(b);
        nb
    });
    let edges = {
        let vcp = SharedMut(vc[nvu..].as_mut_ptr());
        let valp = SharedMut(valence[nvu..].as_mut_ptr());
        let bp = boundary.as_mut().map(|b| SharedBool(b[nvu..].as_mut_ptr()));
        number_edges_with(old.o_table(), ids, |id, c, x| {
            if let Some(bp) = bp {
                // SAFETY: as for C and valence below.
                unsafe { *bp.get().add(id as usize) = x == BORDER };
            }
            let (d, k) = if x == BORDER { (p(corner_triangle(nt, p(c))), 4) } else { (c, 6) };
            // SAFETY: the three tails have `ne` elements; `id < ne` (an id
            // is the number of owner corners before its owner, `ne` the
            // number of owners: EdgeIds::rank) and every id is written once
            // (each edge has one owner).
            unsafe {
                *vcp.get().add(id as usize) = d;
                *valp.get().add(id as usize) = k;
            }
        })
    };
    NewVertexTables { edges, vc, valence, boundary }
}

/// The old vertices' part of the new `C` and valence tables: an old vertex
/// keeps its valence and its `C` moves to its corner triangle, `C'[v] = A(C[v])`.
fn carry_old_vertices(old: &CornerTable, vc: &mut [u32], valence: &mut [u32]) {
    let (nt, nvu) = (old.num_triangles(), old.num_vertices());
    vc[..nvu].par_iter_mut().zip(old.c_table().par_iter()).with_min_len(CHUNK).for_each(|(d, &c)| {
        *d = corner_triangle(nt, c);
    });
    valence[..nvu].copy_from_slice(old.valences());
}

/// The new V table of a split, written in four streams (the central
/// triangles and the three corner triangles), one old triangle at a time,
/// from the old V and O and the edge ids `ids` of the numbering pass, each
/// vertex id `j` written as `id(j)`. The corners are visited in order within
/// a chunk ([`EdgeIds::edge_in_order`], from the chunk's first rank).
fn write_v<I: VertexId, M: Fn(u32) -> I + Sync>(old: &CornerTable, ids: &EdgeIds, id: &M) -> Vec<I> {
    let nc = old.num_corners();
    let nv = old.num_vertices() as u32;
    let mut v2: Vec<I> = crate::mem::zeroed(4 * nc);
    let old_v3: &[[u32; 3]] = bytemuck::cast_slice(old.v_table());
    let old_o3: &[[u32; 3]] = bytemuck::cast_slice(old.o_table());
    let init = |t: usize| ids.rank(3 * t as u32);
    for_each_split_triangle_with(&mut v2, nc, init, |next, t, [b0, b1, b2, b3]| {
        let c0 = 3 * t as u32;
        let (vv, x) = (old_v3[t], old_o3[t]);
        let ws = std::array::from_fn(|k| nv + ids.edge_in_order(c0 + k as u32, x[k], next));
        let (ws, vv) = (ws.map(id), vv.map(id));
        // central triangle: the three edge vertices
        *b0 = ws;
        // corner triangle k: (V[c], W[p(c)], W[n(c)]) for c = c0 + k
        *b1 = [vv[0], ws[2], ws[1]];
        *b2 = [vv[1], ws[0], ws[2]];
        *b3 = [vv[2], ws[1], ws[0]];
    });
    v2
}

/// The new O table of a split, in four streams like [`write_v`], from the
/// old O alone (the formulas of the module docs).
fn write_o(old: &CornerTable) -> Vec<u32> {
    let nc = old.num_corners();
    // p(A(n(x))) and n(A(p(x))) for a corner x = 3u + j of the old table are
    // x + DN[j] and x + DP[j] (wrapping): A(n(x)) = 3nt((j+1)%3 + 1) + 3u.
    let nt3 = nc as u32;
    let dn: [u32; 3] = std::array::from_fn(|j| (nt3 * ((j as u32 + 1) % 3 + 1) + 2).wrapping_sub(j as u32));
    let dp: [u32; 3] = std::array::from_fn(|j| (nt3 * ((j as u32 + 2) % 3 + 1) + 1).wrapping_sub(j as u32));
    let across_n = |x: u32| if x == BORDER { BORDER } else { x.wrapping_add(dn[(x % 3) as usize]) };
    let across_p = |x: u32| if x == BORDER { BORDER } else { x.wrapping_add(dp[(x % 3) as usize]) };
    let mut o2: Vec<u32> = crate::mem::zeroed(4 * nc);
    let old_o3: &[[u32; 3]] = bytemuck::cast_slice(old.o_table());
    for_each_split_triangle(&mut o2, nc, |t, [q0, q1, q2, q3]| {
        let c0 = 3 * t as u32;
        let x = old_o3[t];
        // O'[c] = A(c) for the central corners
        *q0 = [nt3 + c0, 2 * nt3 + c0, 3 * nt3 + c0];
        // corner triangle k: (c, p(A(n(O[n(c)]))), n(A(p(O[p(c)]))))
        let (an, ap) = (x.map(across_n), x.map(across_p));
        *q1 = [c0, an[1], ap[2]];
        *q2 = [c0 + 1, an[2], ap[0]];
        *q3 = [c0 + 2, an[0], ap[1]];
    });
    o2
}

/// Calls `each(t, [central, corner 1, corner 2, corner 3])` for every old
/// triangle `t` of a split of `nc` old corners, in parallel chunks, with the
/// four triangles of the new table `table` (`4 nc` entries) that `t`
/// becomes: the four streams of the layout in the module docs.
fn for_each_split_triangle<T: Send>(table: &mut [T], nc: usize, each: impl Fn(usize, [&mut [T; 3]; 4]) + Sync) {
    for_each_split_triangle_with(table, nc, |_| (), |_, t, four| each(t, four));
}

/// [`for_each_split_triangle`] with a state per parallel chunk, made by
/// `init(t)` for its first old triangle `t` and passed to `each` for every
/// triangle of the chunk, in order.
fn for_each_split_triangle_with<T: Send, S>(
    table: &mut [T],
    nc: usize,
    init: impl Fn(usize) -> S + Sync,
    each: impl Fn(&mut S, usize, [&mut [T; 3]; 4]) + Sync,
) {
    fn tri<T>(s: &mut [T]) -> &mut [[T; 3]] {
        let (triples, rest) = s.as_chunks_mut::<3>();
        debug_assert!(rest.is_empty(), "a table of whole triangles");
        triples
    }
    let (s0, rest) = table.split_at_mut(nc);
    let (s1, rest) = rest.split_at_mut(nc);
    let (s2, s3) = rest.split_at_mut(nc);
    let g = CHUNK / 3;
    tri(s0)
        .par_chunks_mut(g)
        .zip(tri(s1).par_chunks_mut(g))
        .zip(tri(s2).par_chunks_mut(g))
        .zip(tri(s3).par_chunks_mut(g))
        .enumerate()
        .for_each(|(k, (((s0, s1), s2), s3))| {
            let len = s0.len();
            let (s1, s2, s3) = (&mut s1[..len], &mut s2[..len], &mut s3[..len]);
            let mut state = init(k * g);
            for (i, (((a, b), c), d)) in
                s0.iter_mut().zip(s1.iter_mut()).zip(s2.iter_mut()).zip(s3.iter_mut()).enumerate()
            {
                each(&mut state, k * g + i, [a, b, c, d]);
            }
        });
}

/// The edge generations after a split at generation `level`, from those of
/// the old corners `og` (module docs): four streams, the central triangles'
/// and the three corner triangles', one old triangle at a time, like
/// [`write_v`]. For [`Generations::corners`]; the split itself only
/// records its triangle count.
pub(crate) fn split_generations(og: &[u8], level: u8) -> Vec<u8> {
    let nc = og.len();
    let mut corner: Vec<u8> = vec![level; 4 * nc];
    // the central corners (the first nc) face interior edges: already `level`
    let (g1, rest) = corner[nc..].split_at_mut(nc);
    let (g2, g3) = rest.split_at_mut(nc);
    // whole triangles per chunk
    let g = 3 * (CHUNK / 3);
    og.par_chunks(g).zip(g1.par_chunks_mut(g)).zip(g2.par_chunks_mut(g)).zip(g3.par_chunks_mut(g)).for_each(
        |(((og, g1), g2), g3)| {
            let old3: &[[u8; 3]] = bytemuck::cast_slice(og);
            fn tri(s: &mut [u8]) -> &mut [[u8; 3]] {
                bytemuck::cast_slice_mut(s)
            }
            let (g1, g2, g3) = (tri(g1), tri(g2), tri(g3));
            for (t, x) in old3.iter().enumerate() {
                // corner triangle k of c = 3t + k: (A, n(A), p(A)) face
                // (interior, half of the edge opposite n(c), half of p(c)'s)
                g1[t] = [level, x[1], x[2]];
                g2[t] = [level, x[2], x[0]];
                g3[t] = [level, x[0], x[1]];
            }
        },
    );
    corner
}

/// One split with every new vertex at the midpoint of its edge: linear
/// subdivision, the points lying on the old triangles (the `midpoint`
/// scheme gives the same points; the tests check it). For shapes and for
/// measuring a scheme's displacement from the control surface, which need
/// no scheme.
pub fn split_linear(mesh: &Mesh) -> Mesh {
    let (ct, edges) = split(&mesh.ct);
    let old = &mesh.ct;
    let pos = &mesh.positions;
    let mut positions = Vec::with_capacity(ct.num_vertices());
    positions.extend_from_slice(pos);
    positions.par_extend(edges.owners.par_iter().map(|&c| {
        let (a, b) = (old.vtx(n(c)), old.vtx(p(c)));
        (pos[a as usize] + pos[b as usize]) * 0.5
    }));
    Mesh { ct, positions }
}

/// [`split_linear`] `levels` times.
pub fn refine_linear(mesh: &Mesh, levels: u32) -> Mesh {
    let mut cur = mesh.clone();
    for _ in 0..levels {
        cur = split_linear(&cur);
    }
    cur
}

fn ms(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1000.0
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::mesh::shapes;

    /// The id of the edge opposite every corner of the table whose O (or
    /// twin) table is `o`, numbered by hand: owners in corner order.
    pub(crate) fn numbered_by_hand(o: &[u32]) -> Vec<u32> {
        let mut w = vec![u32::MAX; o.len()];
        let mut next = 0u32;
        for (c, &x) in o.iter().enumerate() {
            if owns_edge(c as u32, x) {
                w[c] = next;
                if x != BORDER {
                    w[x as usize] = next;
                }
                next += 1;
            }
        }
        w
    }

    #[test]
    fn edge_ids_from_owner_bits_equal_a_numbering_by_hand() {
        // closed and open meshes, several 64-corner words and a partial last one
        for m in [shapes::icosphere(3), shapes::grid(9), shapes::icosphere(0)] {
            let o = m.ct.o_table();
            let w = numbered_by_hand(o);
            let next = w.iter().filter(|&&e| e != u32::MAX).max().map_or(0, |&e| e + 1);
            let ids = EdgeIds::new(o);
            assert_eq!(ids.count(), next);
            assert_eq!(next as usize, m.ct.num_edges());
            for (c, &x) in o.iter().enumerate() {
                assert_eq!(ids.edge(c as u32, x), w[c], "corner {c}");
            }
            let numbering = number_edges(&m.ct);
            for (e, &c) in numbering.owners.iter().enumerate() {
                assert_eq!(w[c as usize], e as u32, "owner of edge {e}");
            }
        }
    }

    /// The owners read off the bits, piece by piece, are the listed ones in
    /// the same order, and every piece of `out` is the part of the edges its
    /// owners own: over several chunks, a partial last word and chunk,
    /// closed and open meshes, and with no edges at all.
    #[test]
    fn owners_from_bits_are_the_listed_owners_piece_by_piece() {
        let meshes = [shapes::icosphere(5), shapes::grid(110), shapes::icosphere(0)];
        assert!(!meshes[1].ct.num_corners().is_multiple_of(64) && meshes[1].ct.num_corners() > 4 * CHUNK);
        for m in meshes {
            let listed = number_edges(&m.ct);
            let bits = EdgeIds::new(m.ct.o_table());
            for owners in [Owners::List(&listed.owners), Owners::Bits(&bits)] {
                assert_eq!(owners.len(), listed.owners.len());
                // each element learns its owner; pieces must line up with it
                let mut out = vec![u32::MAX; owners.len()];
                let pieces = std::sync::atomic::AtomicUsize::new(0);
                owners.par_pieces(&mut out, |o, cs| {
                    assert_eq!(o.len(), cs.len());
                    assert!(cs.len() <= CHUNK);
                    o.copy_from_slice(cs);
                    pieces.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                });
                assert_eq!(out, listed.owners, "{owners:?}");
                assert!(listed.owners.len() < CHUNK || pieces.into_inner() > 1, "several pieces");
            }
        }
        let none = EdgeIds::new(&[]);
        let mut out: Vec<u32> = Vec::new();
        Owners::Bits(&none).par_pieces(&mut out, |_, cs| assert!(cs.is_empty()));
        assert!(Owners::Bits(&none).is_empty());
    }

    /// The split's edge vertices (written with ids counted as the owners
    /// pass, from each parallel chunk's first rank) are the hand-numbered
    /// edges, over several chunks, closed and open, in the full split and
    /// the faces-only one.
    #[test]
    fn split_names_every_edge_vertex_by_its_hand_numbered_edge() {
        for m in [shapes::icosphere(5), shapes::grid(110)] {
            let (ct, o) = (&m.ct, m.ct.o_table());
            assert!(ct.num_corners() > 3 * CHUNK, "several chunks");
            let (nt, nv) = (ct.num_triangles(), ct.num_vertices() as u32);
            let w = numbered_by_hand(o);
            let (full, _) = split(ct);
            let (faces, _) = split_faces(ct, &|j| j);
            assert_eq!(full.v_table(), &faces[..]);
            let v2 = full.v_table();
            for c in 0..ct.num_corners() as u32 {
                let a = corner_triangle(nt, c) as usize;
                assert_eq!(v2[c as usize], nv + w[c as usize], "central corner {c}");
                assert_eq!(v2[a], ct.vtx(c), "corner triangle of {c}");
                assert_eq!(v2[a + 1], nv + w[p(c) as usize], "corner triangle of {c}, after");
                assert_eq!(v2[a + 2], nv + w[n(c) as usize], "corner triangle of {c}, before");
            }
        }
    }
}
