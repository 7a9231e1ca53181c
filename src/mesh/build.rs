//! Building the O table from a triangle list in expected O(n), and validating
//! the input (docs/schemes.md §7.3).
//!
//! Method: every corner `c` owns the directed half-edge `v(n(c)) -> v(p(c))`
//! opposite it. Half-edges are bucketed by their start vertex with a counting
//! sort (O(n), no hashing); the opposite of `c` is the unique corner whose
//! half-edge runs the other way, found by scanning the (valence-sized) bucket
//! of `v(p(c))` (in parallel; an error is the first in corner order, as a
//! serial scan would find it). A second half-edge in the same direction means inconsistent
//! orientation; three or more faces on an edge mean a non-manifold edge. A
//! final pass walks every fan once to find non-manifold vertices and to fill
//! `C[v]` and the valences.

use super::{BORDER, CornerTable, n, p};
use crate::MeshError;
use glam::Vec3;

/// What [`CornerTable::build`] found besides errors.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BuildReport {
    /// Vertices of the input that no triangle uses; they were dropped.
    pub unreferenced: usize,
    /// The first few dropped vertex ids (input numbering).
    pub unreferenced_examples: Vec<u32>,
}

impl CornerTable {
    /// Builds and validates a corner table for `nv` vertices and the flat
    /// triangle list `tris`. Vertices no triangle uses are dropped; the third
    /// return value then maps new vertex ids to input ids.
    ///
    /// When `positions` is given, every used position must be finite.
    ///
    /// # Errors
    /// [`MeshError`] naming the input face or vertex ids: empty mesh, index out
    /// of range, degenerate face, non-finite position, non-manifold edge,
    /// inconsistent orientation, non-manifold vertex, or a mesh too large for
    /// 32-bit corner ids.
    pub fn build(
        nv: usize,
        tris: &[u32],
        positions: Option<&[Vec3]>,
    ) -> Result<(CornerTable, BuildReport, Option<Vec<u32>>), MeshError> {
        let nc = tris.len() - tris.len() % 3;
        if nc == 0 {
            return Err(MeshError::Empty);
        }
        if nc >= (u32::MAX as usize) / 4 || nv >= u32::MAX as usize {
            return Err(MeshError::TooManyElements { what: format!("{} triangles, {nv} vertices", nc / 3) });
        }
        let tris = &tris[..nc];
        // range and degeneracy
        for (f, tri) in tris.chunks_exact(3).enumerate() {
            for &i in tri {
                if i as usize >= nv {
                    return Err(MeshError::IndexOutOfRange { face: f, index: i as i64, len: nv });
                }
            }
            if tri[0] == tri[1] || tri[0] == tri[2] {
                return Err(MeshError::DegenerateFace { face: f, vertex: tri[0] });
            }
            if tri[1] == tri[2] {
                return Err(MeshError::DegenerateFace { face: f, vertex: tri[1] });
            }
        }
        let (v, kept, report) = compact(tris, nv, positions)?;
        let nvk = kept.as_ref().map_or(nv, Vec::len);
        let o_table = build_o(&v, nvk).map_err(|e| input_ids(e, kept.as_deref()))?;
        // build_o pairs every corner with the one corner of the reversed
        // half-edge or refuses the mesh, and V was checked above: the checks
        // of from_vo would find nothing
        let ct = CornerTable::with_fans(v, o_table, nvk).map_err(|e| input_ids(e, kept.as_deref()))?;
        Ok((ct, report, kept))
    }

    /// Completes a table from V and a valid O: checks both, fills `C[v]` and
    /// the valences, and checks that every vertex has exactly one fan. This
    /// is where the invariants listed on [`CornerTable`] are established for
    /// every table read or built ([`CornerTable::build`] ends here too).
    ///
    /// # Errors
    /// [`MeshError::BadOppositeTable`] naming the first corner whose O entry
    /// is out of range, paired with itself, not paired back, or not facing
    /// the same edge reversed (or when V and O differ in length);
    /// [`MeshError::IndexOutOfRange`] for a vertex id `>= nv`;
    /// [`MeshError::DegenerateFace`] for a triangle using a vertex twice;
    /// [`MeshError::NonManifoldVertex`]; [`MeshError::UnusedVertex`] for a
    /// vertex id no corner uses; [`MeshError::TooManyElements`] past 32-bit
    /// corner ids (of the table four times as large that a split makes).
    pub fn from_vo(v: Vec<u32>, o: Vec<u32>, nv: usize) -> Result<CornerTable, MeshError> {
        check_v(&v, nv)?;
        check_o(&v, &o)?;
        Self::with_fans(v, o, nv)
    }

    /// [`CornerTable::from_vo`] for a V and O that have passed its checks,
    /// or were made to pass them ([`CornerTable::build`] checks V itself and
    /// makes O by pairing each half-edge with its one reversed twin): walks
    /// every fan to fill C and the valences, and checks that every vertex
    /// has exactly one fan.
    pub(crate) fn with_fans(v: Vec<u32>, o: Vec<u32>, nv: usize) -> Result<CornerTable, MeshError> {
        let mut ct = CornerTable {
            v,
            o,
            vc: vec![BORDER; nv],
            valence: vec![0u32; nv],
            sharpness: None,
            holes: None,
            generations: None,
        };
        let mut visited = vec![false; ct.v.len()];
        for c0 in 0..ct.v.len() as u32 {
            if visited[c0 as usize] {
                continue;
            }
            let (start, count, closed) = walk_fan(&ct, c0, &mut visited);
            let vert = ct.v[c0 as usize];
            if ct.vc[vert as usize] != BORDER {
                let fans = count_fans(&ct, vert);
                return Err(MeshError::NonManifoldVertex { vertex: vert, fans });
            }
            ct.vc[vert as usize] = start;
            ct.valence[vert as usize] = count + u32::from(!closed);
        }
        if let Some(missing) = ct.vc.iter().position(|&x| x == BORDER) {
            return Err(MeshError::UnusedVertex { vertex: missing as u32 });
        }
        Ok(ct)
    }
}

/// V of a table for `nv` vertices: whole triangles within 32-bit corner ids
/// (with room for a split), vertex ids in range, no vertex twice in a triangle.
fn check_v(v: &[u32], nv: usize) -> Result<(), MeshError> {
    if v.len() >= (u32::MAX as usize) / 4 || nv >= u32::MAX as usize {
        return Err(MeshError::TooManyElements { what: format!("{} corners, {nv} vertices", v.len()) });
    }
    for (face, tri) in v.chunks(3).enumerate() {
        if let Some(&i) = tri.iter().find(|&&i| i as usize >= nv) {
            return Err(MeshError::IndexOutOfRange { face, index: i64::from(i), len: nv });
        }
        if let [a, b, c] = *tri
            && (a == b || a == c || b == c)
        {
            return Err(MeshError::DegenerateFace { face, vertex: if a == b || a == c { a } else { b } });
        }
    }
    Ok(())
}

/// O must be an involution without fixed points that pairs each corner with
/// the corner facing the same edge in the opposite direction.
fn check_o(v: &[u32], o: &[u32]) -> Result<(), MeshError> {
    let nc = v.len();
    if o.len() != nc || !nc.is_multiple_of(3) {
        return Err(MeshError::BadOppositeTable { corner: 0, msg: "V and O have different lengths".into() });
    }
    first_error(nc, |c| {
        let x = o[c as usize];
        if x == BORDER {
            return Ok(());
        }
        let bad = |msg: &str| Err(MeshError::BadOppositeTable { corner: c as usize, msg: msg.into() });
        if x as usize >= nc || x == c {
            return bad("opposite corner out of range");
        }
        if o[x as usize] != c {
            return bad("o(o(c)) != c");
        }
        if v[n(x) as usize] != v[p(c) as usize] || v[p(x) as usize] != v[n(c) as usize] {
            return bad("the opposite corner does not face the same edge in the opposite direction");
        }
        Ok(())
    })
}

/// Walks the fan of corner `c0` (in a table whose O is checked), marking
/// its corners visited: `(first corner, corners, closed)`. The first corner
/// is `c0` for a closed fan and the one after the border otherwise.
fn walk_fan(ct: &CornerTable, c0: u32, visited: &mut [bool]) -> (u32, u32, bool) {
    // unswing to the start of the fan (or all the way round)
    let mut start = c0;
    let mut closed = false;
    while let Some(x) = ct.u(start) {
        if x == c0 {
            closed = true;
            break;
        }
        start = x;
    }
    if closed {
        start = c0;
    }
    let mut count = 0u32;
    let mut c = start;
    // a checked O pairs corners of one vertex, so the swing stays in this
    // fan and ends at the border or back at the start
    while !visited[c as usize] {
        visited[c as usize] = true;
        count += 1;
        match ct.s(c) {
            Some(x) if x != start => c = x,
            _ => break,
        }
    }
    (start, count, closed)
}

/// Number of separate fans at vertex `vert` (only called on the error path).
fn count_fans(ct: &CornerTable, vert: u32) -> usize {
    let corners: Vec<u32> = (0..ct.v.len() as u32).filter(|&c| ct.v[c as usize] == vert).collect();
    let mut seen = vec![false; corners.len()];
    let mut fans = 0;
    for i in 0..corners.len() {
        if seen[i] {
            continue;
        }
        fans += 1;
        let mut stack = vec![corners[i]];
        while let Some(c) = stack.pop() {
            let Some(k) = corners.iter().position(|&x| x == c) else {
                continue;
            };
            if seen[k] {
                continue;
            }
            seen[k] = true;
            stack.extend(ct.s(c));
            stack.extend(ct.u(c));
        }
    }
    fans
}

/// Corners per parallel work item of the checks and of [`build_o`].
const CHUNK: usize = 1 << 14;

/// The first error of `check(c)` over all corners `c < nc`, in corner order
/// (the same one a serial loop would stop at), checked in parallel.
fn first_error(nc: usize, check: impl Fn(u32) -> Result<(), MeshError> + Sync) -> Result<(), MeshError> {
    use rayon::prelude::*;
    let first = (0..nc.div_ceil(CHUNK))
        .into_par_iter()
        .filter_map(|k| (k * CHUNK..((k + 1) * CHUNK).min(nc)).find_map(|c| check(c as u32).err()))
        .find_first(|_| true);
    first.map_or(Ok(()), Err)
}

/// Builds O from V with a counting sort of half-edges by start vertex.
/// What both tables' builds do first: the corners renumbered without the
/// vertices no face uses, the kept vertices' input ids (when any was
/// dropped), and the report of the dropped ones; every used position must
/// be finite.
///
/// # Errors
/// [`MeshError::NonFinite`] naming the first used vertex (input id) whose
/// position is not finite.
#[allow(clippy::type_complexity, reason = "the three results of one pass")]
pub(super) fn compact(
    corners: &[u32],
    nv: usize,
    positions: Option<&[Vec3]>,
) -> Result<(Vec<u32>, Option<Vec<u32>>, BuildReport), MeshError> {
    let mut new_id = vec![BORDER; nv];
    for &i in corners {
        new_id[i as usize] = 0;
    }
    let mut kept = Vec::new();
    let mut report = BuildReport::default();
    for (i, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = kept.len() as u32;
            kept.push(i as u32);
        } else {
            report.unreferenced += 1;
            if report.unreferenced_examples.len() < 10 {
                report.unreferenced_examples.push(i as u32);
            }
        }
    }
    if let Some(pos) = positions
        && let Some(&k) = kept.iter().find(|&&k| !pos[k as usize].is_finite())
    {
        return Err(MeshError::NonFinite { vertex: k as usize });
    }
    if report.unreferenced == 0 {
        return Ok((corners.to_vec(), None, report));
    }
    Ok((corners.iter().map(|&i| new_id[i as usize]).collect(), Some(kept), report))
}

/// `e` with the compacted vertex ids it names turned back into the input's
/// (`kept` maps one to the other; `None` when nothing was dropped).
pub(super) fn input_ids(e: MeshError, kept: Option<&[u32]>) -> MeshError {
    let orig = |x: u32| kept.map_or(x, |k| k[x as usize]);
    match e {
        MeshError::NonManifoldEdge { v0, v1, faces, examples } => {
            MeshError::NonManifoldEdge { v0: orig(v0), v1: orig(v1), faces, examples }
        }
        MeshError::InconsistentOrientation { v0, v1, f0, f1 } => {
            MeshError::InconsistentOrientation { v0: orig(v0), v1: orig(v1), f0, f1 }
        }
        MeshError::NonManifoldVertex { vertex, fans } => MeshError::NonManifoldVertex { vertex: orig(vertex), fans },
        other => other,
    }
}

fn build_o(v: &[u32], nv: usize) -> Result<Vec<u32>, MeshError> {
    use rayon::prelude::*;
    let nc = v.len();
    // bucket corners by the start vertex of the half-edge opposite them,
    // each with the half-edge's end, so that a scan reads one bucket only
    let mut start = vec![0u32; nv + 1];
    for c in 0..nc as u32 {
        start[v[n(c) as usize] as usize + 1] += 1;
    }
    for i in 0..nv {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut by_start = vec![(0u32, 0u32); nc];
    for c in 0..nc as u32 {
        let a = v[n(c) as usize] as usize;
        by_start[fill[a] as usize] = (c, v[p(c) as usize]);
        fill[a] += 1;
    }
    drop(fill);
    let bucket = |a: u32| &by_start[start[a as usize] as usize..start[a as usize + 1] as usize];
    // the twin of c, or why there is none (the checks of the module docs)
    let twin_of = |c: u32| -> Result<u32, MeshError> {
        let (a, b) = (v[n(c) as usize], v[p(c) as usize]);
        let mut twin = BORDER;
        let mut opp = 0usize;
        for &(x, end) in bucket(b) {
            if end == a {
                opp += 1;
                twin = x;
            }
        }
        let same = bucket(a).iter().filter(|&&(x, end)| x != c && end == b).count();
        if same + opp + 1 > 2 {
            let mut faces: Vec<usize> = bucket(a)
                .iter()
                .filter(|&&(_, end)| end == b)
                .chain(bucket(b).iter().filter(|&&(_, end)| end == a))
                .map(|&(x, _)| x as usize / 3)
                .collect();
            faces.sort_unstable();
            let n = faces.len();
            faces.truncate(crate::error::MAX_EXAMPLES);
            return Err(MeshError::NonManifoldEdge { v0: a.min(b), v1: a.max(b), faces: n, examples: faces });
        }
        if same == 1 {
            let other = bucket(a).iter().find(|&&(x, end)| x != c && end == b).map_or(c, |&(x, _)| x);
            let (f0, f1) = ((c / 3).min(other / 3) as usize, (c / 3).max(other / 3) as usize);
            return Err(MeshError::InconsistentOrientation { v0: a, v1: b, f0, f1 });
        }
        Ok(twin)
    };
    let mut o = vec![BORDER; nc];
    // in parallel; the error reported is the first in corner order, as a
    // serial loop would find it
    let first = o
        .par_chunks_mut(CHUNK)
        .enumerate()
        .filter_map(|(k, och)| {
            for (i, slot) in och.iter_mut().enumerate() {
                match twin_of((k * CHUNK + i) as u32) {
                    Ok(t) => *slot = t,
                    Err(e) => return Some(e),
                }
            }
            None
        })
        .find_first(|_| true);
    match first {
        Some(e) => Err(e),
        None => Ok(o),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tet() -> Vec<u32> {
        vec![0, 2, 1, 0, 3, 2, 0, 1, 3, 1, 2, 3]
    }

    #[test]
    fn tetrahedron_is_closed_valence_3() {
        let (ct, rep, kept) = CornerTable::build(4, &tet(), None).unwrap();
        assert!(kept.is_none());
        assert_eq!(rep.unreferenced, 0);
        assert!(ct.o.iter().all(|&x| x != BORDER));
        assert_eq!(ct.valence, vec![3; 4]);
        for c in 0..12u32 {
            let x = ct.o(c).unwrap();
            assert_eq!(ct.o(x), Some(c));
            assert_eq!(ct.vtx(n(x)), ct.vtx(p(c)));
            assert_eq!(ct.vtx(ct.s(c).unwrap()), ct.vtx(c));
            assert_eq!(ct.u(ct.s(c).unwrap()), Some(c));
        }
        // an interior vertex has no boundary neighbours (this used to loop
        // forever, swinging round the closed fan)
        for v in 0..4 {
            assert_eq!(ct.boundary_neighbours(v), None);
        }
    }

    #[test]
    fn errors_are_typed() {
        assert_eq!(CornerTable::build(3, &[], None).unwrap_err(), MeshError::Empty);
        assert!(matches!(
            CornerTable::build(3, &[0, 1, 5], None).unwrap_err(),
            MeshError::IndexOutOfRange { face: 0, index: 5, len: 3 }
        ));
        assert!(matches!(
            CornerTable::build(3, &[0, 1, 1], None).unwrap_err(),
            MeshError::DegenerateFace { face: 0, .. }
        ));
        // fin: three triangles on edge (0,1)
        let fin = [0, 1, 2, 1, 0, 3, 0, 1, 4];
        assert!(matches!(
            CornerTable::build(5, &fin, None).unwrap_err(),
            MeshError::NonManifoldEdge { v0: 0, v1: 1, faces: 3, .. }
        ));
        // two faces with the same orientation on an edge
        let flip = [0, 1, 2, 0, 1, 3];
        assert!(matches!(CornerTable::build(4, &flip, None).unwrap_err(), MeshError::InconsistentOrientation { .. }));
        // bowtie: two triangles sharing vertex 2 only
        let bow = [0, 1, 2, 2, 3, 4];
        assert_eq!(CornerTable::build(5, &bow, None).unwrap_err(), MeshError::NonManifoldVertex { vertex: 2, fans: 2 });
        let nan = [Vec3::ZERO, Vec3::X, Vec3::new(f32::NAN, 0.0, 0.0)];
        assert_eq!(CornerTable::build(3, &[0, 1, 2], Some(&nan)).unwrap_err(), MeshError::NonFinite { vertex: 2 });
    }

    #[test]
    fn from_vo_refuses_every_broken_invariant() {
        let bad_o = |v: Vec<u32>, o: Vec<u32>, nv: usize| match CornerTable::from_vo(v, o, nv) {
            Err(MeshError::BadOppositeTable { corner, .. }) => corner,
            other => panic!("expected a bad opposite table, got {other:?}"),
        };
        // the square (0,1,2), (0,2,3): its diagonal is faced by corners 1 and 5
        let sq = vec![0, 1, 2, 0, 2, 3];
        let good = vec![BORDER, 5, BORDER, BORDER, BORDER, 1];
        assert!(CornerTable::from_vo(sq.clone(), good, 4).is_ok());
        assert_eq!(bad_o(sq.clone(), vec![BORDER, 6, BORDER, BORDER, BORDER, 1], 4), 1, "out of range");
        assert_eq!(bad_o(sq.clone(), vec![BORDER, 1, BORDER, BORDER, BORDER, BORDER], 4), 1, "paired with itself");
        assert_eq!(bad_o(sq.clone(), vec![BORDER, 5, BORDER, BORDER, BORDER, BORDER], 4), 1, "asymmetric");
        assert_eq!(bad_o(sq.clone(), vec![BORDER, 4, BORDER, BORDER, 1, BORDER], 4), 1, "not the same edge");
        assert_eq!(bad_o(sq.clone(), vec![BORDER; 5], 4), 0, "lengths differ");
        // a vertex id past the vertex count, a vertex no corner uses
        assert_eq!(
            CornerTable::from_vo(vec![0, 1, 5], vec![BORDER; 3], 3).unwrap_err(),
            MeshError::IndexOutOfRange { face: 0, index: 5, len: 3 }
        );
        assert_eq!(
            CornerTable::from_vo(vec![0, 1, 2], vec![BORDER; 3], 4).unwrap_err(),
            MeshError::UnusedVertex { vertex: 3 }
        );
        // a triangle using a vertex twice, with its two corners of that vertex
        // paired: a consistent involution, but an interior vertex of valence 1
        assert_eq!(
            CornerTable::from_vo(vec![0, 1, 1], vec![BORDER, 2, 1], 2).unwrap_err(),
            MeshError::DegenerateFace { face: 0, vertex: 1 }
        );
    }

    #[test]
    fn unreferenced_vertices_are_dropped() {
        let (ct, rep, kept) = CornerTable::build(6, &[0, 2, 4], None).unwrap();
        assert_eq!(rep.unreferenced, 3);
        assert_eq!(kept.unwrap(), vec![0, 2, 4]);
        assert_eq!(ct.v, vec![0, 1, 2]);
        assert_eq!(ct.valence, vec![2, 2, 2]);
    }

    #[test]
    fn boundary_fan_starts_at_border() {
        // a square split in two: 0-1-2, 0-2-3
        let (ct, _, _) = CornerTable::build(4, &[0, 1, 2, 0, 2, 3], None).unwrap();
        assert_eq!(ct.valence, vec![3, 2, 3, 2]);
        for v in 0..4 {
            assert!(ct.is_boundary_vertex(v));
            assert_eq!(ct.u(ct.vc[v as usize]), None);
            assert_eq!(ct.fan(v).count() as u32 + 1, ct.valence[v as usize]);
        }
        assert_eq!(ct.ring(0).collect::<Vec<_>>(), vec![1, 2, 3]);
        assert_eq!(ct.boundary_neighbours(0), Some((1, 3)));
    }
}
