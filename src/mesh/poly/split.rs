//! The quad split of a polygon table, shared by Catmull-Clark and bilinear
//! subdivision: every corner becomes one quad, the new twins are written by
//! formula from the old ones (no rebuild), edges are numbered without
//! hashing (docs/schemes.md §12.2).
//!
//! Old corner `c` at vertex `v = V[c]`, in face `f`, whose edge leaves to
//! `V[next(c)]` (edge id `e(c)`) and whose entering edge is `e(prev(c))`,
//! becomes the quad `c` of corners `4c .. 4c + 3`:
//!
//! ```text
//! V'[4c]     = v                  (its vertex point)
//! V'[4c + 1] = nv + e(c)          (the point of the edge leaving c)
//! V'[4c + 2] = nv + ne + f        (the face point)
//! V'[4c + 3] = nv + e(prev(c))    (the point of the edge entering c)
//!
//! T'[4c]     = 4 next(T[c]) + 3   (BORDER on a border edge)
//! T'[4c + 1] = 4 next(c) + 2
//! T'[4c + 2] = 4 prev(c) + 1
//! T'[4c + 3] = 4 T[prev(c)]       (BORDER on a border edge)
//! ```
//!
//! The half of an old edge that a child corner names keeps the edge's
//! sharpness, decayed (`4c` the half at `V[c]`, `4 next(c) + 3` the half at
//! `V[next(c)]`); the inner edges are smooth. New `C`: an old vertex keeps
//! its fan's first child `4 C[v]`; an edge point `4c + 1` of its owner
//! (`4 next(c) + 3`, the first of its fan, on a border edge); a face point
//! `4 first(f) + 2`. Valences: unchanged, 4 (3 on the border), the face's
//! size.

use super::PolyTable;
use crate::mesh::split::{CHUNK, EdgeIds, EdgeNumbering, number_edges_with};
use crate::mesh::{BORDER, Creasing, VertexId};
use rayon::prelude::*;

/// Splits every face of `old` into quads (see the module docs), the
/// sharpness decaying by `creasing`. Returns the new table and the old
/// table's edge numbering (edge `e` became vertex `nv + e`, face `f` vertex
/// `nv + ne + f`).
///
/// # Panics
/// If the new table's ids would not fit below [`BORDER`] (the subdivision
/// refuses such levels beforehand).
pub(crate) fn split(old: &PolyTable, creasing: Creasing) -> (PolyTable, EdgeNumbering) {
    let nc = old.num_corners();
    assert!(4 * nc as u64 + 4 < u64::from(BORDER), "quad split: {nc} corners are too many for 32-bit ids");
    let ids = EdgeIds::new(&old.t);
    let edges = number_edges_with(&old.t, ids, |_, _, _| {});
    let (nv, ne) = (old.num_vertices() as u32, edges.ids.count());
    let (v, t) = rayon::join(|| write_v(old, (&edges.ids, nv, ne), &|j| j), || write_t(old));
    let (vc, valence) = write_c_and_valence(old, &edges.owners);
    let sharpness = old.sharpness().and_then(|s| split_sharpness(s, old, creasing));
    let pt = PolyTable {
        faces: None,
        v,
        t,
        vc,
        valence,
        sharpness: sharpness.map(Box::new),
        holes: None,
        level: old.level + 1,
    };
    // the children of face f are the quads of its corners
    let holes = old.holes().iter().flat_map(|&f| old.face_corners(f)).collect();
    let pt = pt.with_holes(holes);
    (pt, edges)
}

/// The new V table of the quad split and the old table's edge ids, and
/// nothing else: no twins, C, valences or sharpness, and no list of the
/// edges' owners ([`crate::mesh::split::Owners::Bits`] reads them off the
/// ids). For the last level of a subdivision whose caller needs only its
/// faces (writing a file): at level 3 of 70 k quads that leaves out 117 of
/// the 229 MB the level wrote. The V table is the one [`split`] makes.
///
/// Every vertex id goes through `id` as it is written (see
/// [`crate::mesh::split`]'s `split_faces`).
///
/// # Panics
/// As [`split`].
pub(crate) fn split_faces<I: VertexId, M: Fn(u32) -> I + Sync>(old: &PolyTable, id: &M) -> (Vec<I>, EdgeIds) {
    let nc = old.num_corners();
    assert!(4 * nc as u64 + 4 < u64::from(BORDER), "quad split: {nc} corners are too many for 32-bit ids");
    let ids = EdgeIds::new(&old.t);
    let (nv, ne) = (old.num_vertices() as u32, ids.count());
    (write_v(old, (&ids, nv, ne), id), ids)
}

/// The new C and valences (see the module docs): old vertices, then edge
/// points in owner order, then face points, each range written in parallel
/// straight into its place.
fn write_c_and_valence(old: &PolyTable, owners: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let (nv, ne, nf) = (old.num_vertices(), owners.len(), old.num_faces());
    let mut vc: Vec<u32> = crate::mem::zeroed(nv + ne + nf);
    let mut valence: Vec<u32> = crate::mem::zeroed(nv + ne + nf);
    let (vc_old, rest) = vc.split_at_mut(nv);
    let (vc_edge, vc_face) = rest.split_at_mut(ne);
    let (val_old, rest) = valence.split_at_mut(nv);
    let (val_edge, val_face) = rest.split_at_mut(ne);
    vc_old.par_iter_mut().zip(old.vc.par_iter()).with_min_len(CHUNK).for_each(|(x, &c)| *x = 4 * c);
    val_old.par_iter_mut().zip(old.valence.par_iter()).with_min_len(CHUNK).for_each(|(x, &k)| *x = k);
    vc_edge.par_iter_mut().zip(val_edge.par_iter_mut()).zip(owners.par_iter()).with_min_len(CHUNK).for_each(
        |((x, k), &c)| {
            (*x, *k) = if old.t[c as usize] == BORDER { (4 * old.next(c) + 3, 3) } else { (4 * c + 1, 4) };
        },
    );
    vc_face.par_iter_mut().zip(val_face.par_iter_mut()).enumerate().with_min_len(CHUNK).for_each(|(f, (x, k))| {
        let r = old.face_corners(f as u32);
        (*x, *k) = (4 * r.start + 2, r.end - r.start);
    });
    (vc, valence)
}

/// The new V table (see the module docs), one old corner (four new
/// corners) at a time, in parallel; an all-quad table a face (sixteen new
/// corners) at a time, its four edge ids ranked once, each serving the
/// corner it leaves and the one it enters. `ids` numbers the old table's
/// `ne` edges, `nv` its vertices; every vertex id `j` is written as `id(j)`.
fn write_v<I: VertexId, M: Fn(u32) -> I + Sync>(
    old: &PolyTable,
    (ids, nv, ne): (&EdgeIds, u32, u32),
    id: &M,
) -> Vec<I> {
    let mut v: Vec<I> = crate::mem::zeroed(4 * old.num_corners());
    if old.is_quads() {
        const FACES: usize = CHUNK / 4;
        v.par_chunks_mut(16 * FACES).enumerate().for_each(|(k, vch)| {
            // the corners come in order, from the chunk's first on
            let mut next = ids.rank((4 * k * FACES) as u32);
            for (i, vf) in vch.chunks_exact_mut(16).enumerate() {
                let f = (k * FACES + i) as u32;
                let c0 = 4 * f;
                let e: [I; 4] = std::array::from_fn(|j| {
                    let c = c0 + j as u32;
                    id(nv + ids.edge_in_order(c, old.t[c as usize], &mut next))
                });
                let fp = id(nv + ne + f);
                for j in 0..4 {
                    let q = [id(old.v[(c0 + j as u32) as usize]), e[j], fp, e[(j + 3) % 4]];
                    vf[4 * j..4 * j + 4].copy_from_slice(&q);
                }
            }
        });
        return v;
    }
    let edge = |c: u32| ids.edge(c, old.t[c as usize]);
    v.par_chunks_mut(4 * CHUNK).enumerate().for_each(|(k, vch)| {
        let base = (k * CHUNK) as u32;
        for (i, vq) in vch.chunks_exact_mut(4).enumerate() {
            let c = base + i as u32;
            let q = [old.v[c as usize], nv + edge(c), nv + ne + old.face(c), nv + edge(old.prev(c))];
            vq.copy_from_slice(&q.map(id));
        }
    });
    v
}

/// The new twin table T (see the module docs), from the old twins alone,
/// one old corner (four new corners) at a time, in parallel; next and
/// previous are arithmetic in an all-quad table.
fn write_t(old: &PolyTable) -> Vec<u32> {
    let mut t: Vec<u32> = crate::mem::zeroed(4 * old.num_corners());
    let quads = old.is_quads();
    t.par_chunks_mut(4 * CHUNK).enumerate().for_each(|(k, tch)| {
        let base = (k * CHUNK) as u32;
        for (i, tq) in tch.chunks_exact_mut(4).enumerate() {
            let c = base + i as u32;
            let (next, prev) =
                if quads { ((c & !3) | ((c + 1) & 3), (c & !3) | ((c + 3) & 3)) } else { (old.next(c), old.prev(c)) };
            let (tc, tp) = (old.t[c as usize], old.t[prev as usize]);
            let next_of_twin = |x: u32| if quads { (x & !3) | ((x + 1) & 3) } else { old.next(x) };
            tq[0] = if tc == BORDER { BORDER } else { 4 * next_of_twin(tc) + 3 };
            tq[1] = 4 * next + 2;
            tq[2] = 4 * prev + 1;
            tq[3] = if tp == BORDER { BORDER } else { 4 * tp };
        }
    });
    t
}

/// The sharpness after the split (see the module docs), or `None` when
/// every value decayed to smooth.
fn split_sharpness(
    s: &crate::mesh::sharpness::Sharpness,
    old: &PolyTable,
    creasing: Creasing,
) -> Option<crate::mesh::sharpness::Sharpness> {
    let decay = s.edge_decay(old, creasing);
    let mut corners = Vec::with_capacity(2 * s.sharp_corners().len());
    for &(c, x) in s.sharp_corners() {
        let next = old.next(c);
        corners.push((4 * c, decay.at(x, old.v[c as usize])));
        corners.push((4 * next + 3, decay.at(x, old.v[next as usize])));
    }
    let vertices = s.sharp_vertices().iter().map(|&(v, x)| (v, crate::mesh::sharpness::decrement(x))).collect();
    crate::mesh::sharpness::Sharpness::from_lists(corners, vertices)
}

/// The sharpness the split of `old` gives its children (what [`split`]
/// carries), without splitting: a sharpness edit's new tags carried down
/// the levels of a refiner.
pub(crate) fn split_sharpness_of(old: &PolyTable, creasing: Creasing) -> Option<crate::mesh::sharpness::Sharpness> {
    old.sharpness().and_then(|s| split_sharpness(s, old, creasing))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::edges::EdgeTable;

    /// Every table the split makes equals the table built from its faces
    /// (twins, fans, valences), whatever the face sizes, closed or open.
    fn assert_equals_rebuild(pt: &PolyTable) {
        let nf = pt.num_faces() as u32;
        let mut starts = vec![0u32];
        let mut corners = Vec::new();
        for f in 0..nf {
            corners.extend(pt.face_corners(f).map(|c| pt.vtx(c)));
            starts.push(corners.len() as u32);
        }
        let (rebuilt, rep, kept) = PolyTable::build(pt.num_vertices(), &starts, &corners, None).unwrap();
        assert_eq!((rep.unreferenced, kept), (0, None));
        assert_eq!(rebuilt.t, pt.t, "twins");
        assert_eq!(rebuilt.valence, pt.valence, "valences");
        for x in 0..pt.num_vertices() as u32 {
            let c = pt.corner_of(x);
            assert_eq!(pt.vtx(c), x);
            assert_eq!(pt.is_boundary_vertex(x), rebuilt.is_boundary_vertex(x), "vertex {x}");
            if pt.is_boundary_vertex(x) {
                assert_eq!(pt.twin_entry(c), BORDER, "C of boundary vertex {x} starts its fan");
            }
        }
    }

    /// A triangular prism whose bottom quad and front side carry an extra
    /// vertex (6, between 0 and 1): faces of 3, 4 and 5 corners; `open`
    /// leaves out the side x = 0, so that the mesh has a border.
    fn prism_faces(open: bool) -> (Vec<u32>, Vec<u32>) {
        let mut faces: Vec<Vec<u32>> = vec![vec![2, 1, 6, 0], vec![3, 4, 5], vec![0, 6, 1, 4, 3], vec![1, 2, 5, 4]];
        if !open {
            faces.push(vec![2, 0, 3, 5]);
        }
        let mut starts = vec![0u32];
        let mut corners = Vec::new();
        for f in faces {
            corners.extend(f);
            starts.push(corners.len() as u32);
        }
        (starts, corners)
    }

    #[test]
    fn twins_carried_through_four_splits_equal_a_rebuild() {
        for open in [false, true] {
            let (starts, corners) = prism_faces(open);
            let (mut pt, _, _) = PolyTable::build(7, &starts, &corners, None).unwrap();
            assert_equals_rebuild(&pt);
            for level in 1..=4 {
                let (e, f, v) = (pt.num_edges(), pt.num_faces(), pt.num_vertices());
                let h = pt.num_corners();
                let (next, numbering) = split(&pt, Creasing::Uniform);
                assert_eq!(numbering.owners.len(), e);
                assert_eq!(next.num_vertices(), v + e + f, "level {level}");
                assert_eq!((next.num_faces(), next.num_edges()), (h, 2 * e + h), "level {level}");
                assert!(next.is_quads());
                assert_equals_rebuild(&next);
                pt = next;
            }
        }
    }

    #[test]
    fn edge_generations_follow_the_splits() {
        let (starts, corners) = prism_faces(true);
        let (pt, _, _) = PolyTable::build(7, &starts, &corners, None).unwrap();
        let (one, _) = split(&pt, Creasing::Uniform);
        let (two, _) = split(&one, Creasing::Uniform);
        for c in 0..two.num_corners() as u32 {
            let g = two.edge_generation(c);
            // a control-edge half joins two vertices that are old vertices
            // or edge points of control edges; check against the level-1
            // parent directly: children 4x+1, 4x+2 are new (2)
            match c % 4 {
                1 | 2 => assert_eq!(g, 2),
                0 => assert_eq!(g, one.edge_generation(c / 4)),
                _ => assert_eq!(g, one.edge_generation(one.prev(c / 4))),
            }
            // both corners of an interior edge agree
            if let Some(x) = two.twin(c) {
                assert_eq!(two.edge_generation(x), g);
            }
            let (a, b) = two.edge_ends(c);
            assert!(a != b);
        }
    }

    /// The quad split's edge vertices (ids counted as the owners pass, from
    /// each parallel chunk's first rank) are the hand-numbered edges, over
    /// several chunks of an open grid of quads.
    #[test]
    fn quad_split_names_every_edge_vertex_by_its_hand_numbered_edge() {
        let n = 120u32;
        let id = |i: u32, j: u32| j * (n + 1) + i;
        let mut corners = Vec::new();
        for j in 0..n {
            for i in 0..n {
                corners.extend([id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        let starts: Vec<u32> = (0..=n * n).map(|f| 4 * f).collect();
        let (pt, _, _) = PolyTable::build(((n + 1) * (n + 1)) as usize, &starts, &corners, None).unwrap();
        assert!(pt.is_quads() && pt.num_corners() > 3 * CHUNK, "the all-quad path, several chunks");
        let w = crate::mesh::split::tests::numbered_by_hand(&pt.t);
        let (nv, ne) = (pt.num_vertices() as u32, pt.num_edges() as u32);
        let (v, ids) = split_faces(&pt, &|j| j);
        assert_eq!(ids.count(), ne);
        for c in 0..pt.num_corners() as u32 {
            let q = &v[4 * c as usize..4 * c as usize + 4];
            let expected = [pt.vtx(c), nv + w[c as usize], nv + ne + pt.face(c), nv + w[pt.prev(c) as usize]];
            assert_eq!(q, expected, "quad of corner {c}");
        }
        let (full, _) = split(&pt, Creasing::Uniform);
        assert_eq!(full.v, v, "the full split's V");
    }
}
