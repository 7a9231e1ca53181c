//! Building a polygon table from faces, validating them as
//! [`crate::CornerTable::build`] validates triangles: every corner's
//! half-edge (`V[c] -> V[next(c)]`) is bucketed by its start vertex with a
//! counting sort (no hashing), its twin is the one half-edge of its end
//! vertex's bucket that runs back; a second one the same way is an
//! inconsistent orientation, three or more faces on an edge a non-manifold
//! edge. One walk of every fan then finds non-manifold vertices and fills
//! `C[v]` and the valences.

use super::{Faces, PolyTable};
use crate::MeshError;
use crate::mesh::BORDER;
use glam::Vec3;

/// What [`PolyTable::build`] found besides errors.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PolyBuildReport {
    /// Vertices of the input that no face uses; they were dropped.
    pub unreferenced: usize,
}

impl PolyTable {
    /// Builds and validates a table for `nv` vertices and the faces
    /// `corners[face_starts[f]..face_starts[f + 1]]`. Vertices no face uses
    /// are dropped; the third value then maps new vertex ids to input ids.
    /// A table whose faces are all quads stores none (see [`PolyTable`]).
    ///
    /// # Errors
    /// [`MeshError`] naming the input face or vertex: no face, a face of
    /// fewer than 3 corners or using a vertex twice, an index out of range, a
    /// non-finite position, a non-manifold edge or vertex, an inconsistent
    /// orientation, or a mesh too large for 32-bit ids.
    pub fn build(
        nv: usize,
        face_starts: &[u32],
        corners: &[u32],
        positions: Option<&[Vec3]>,
    ) -> Result<(PolyTable, PolyBuildReport, Option<Vec<u32>>), MeshError> {
        let nf = face_starts.len().saturating_sub(1);
        let nc = corners.len();
        if nf == 0 {
            return Err(MeshError::Empty);
        }
        if nc >= (u32::MAX as usize) / 8 || nv >= u32::MAX as usize {
            return Err(MeshError::TooManyElements { what: format!("{nf} faces, {nc} corners, {nv} vertices") });
        }
        check_faces(face_starts, corners, nv)?;
        let (v, kept, found) = crate::mesh::build::compact(corners, nv, positions)?;
        let report = PolyBuildReport { unreferenced: found.unreferenced };
        let nvk = kept.as_ref().map_or(nv, Vec::len);
        let all_quads = face_starts.windows(2).all(|w| w[1] - w[0] == 4);
        let faces = (!all_quads).then(|| {
            let mut face = vec![0u32; nc];
            for (f, w) in face_starts.windows(2).enumerate() {
                face[w[0] as usize..w[1] as usize].fill(f as u32);
            }
            Faces { starts: face_starts.to_vec(), face }
        });
        let mut pt = PolyTable { faces, v, ..PolyTable::default() };
        let input_ids = |e| crate::mesh::build::input_ids(e, kept.as_deref());
        pt.t = twins(&pt, nvk).map_err(input_ids)?;
        pt.fill_fans(nvk).map_err(input_ids)?;
        Ok((pt, report, kept))
    }

    /// Fills `C` and the valences by walking every fan once.
    ///
    /// # Errors
    /// [`MeshError::NonManifoldVertex`] for a vertex whose corners form more
    /// than one fan.
    pub(super) fn fill_fans(&mut self, nv: usize) -> Result<(), MeshError> {
        // corners per vertex, and for each vertex a fan start: a corner
        // whose edge leaves along the border, else any corner
        let mut count = vec![0u32; nv];
        let mut start = vec![BORDER; nv];
        for (c, &x) in self.v.iter().enumerate() {
            let x = x as usize;
            count[x] += 1;
            if start[x] == BORDER || (self.t[c] == BORDER && self.t[start[x] as usize] != BORDER) {
                start[x] = c as u32;
            }
        }
        let mut valence = vec![0u32; nv];
        for x in 0..nv as u32 {
            let s = start[x as usize];
            let walked = self.fan_from(s).count() as u32;
            if walked != count[x as usize] {
                return Err(MeshError::NonManifoldVertex { vertex: x, fans: self.count_fans(x) });
            }
            valence[x as usize] = walked + u32::from(self.t[s as usize] == BORDER);
        }
        self.vc = start;
        self.valence = valence;
        Ok(())
    }

    /// The fans of vertex `x` (on the error path only: a scan of all corners).
    fn count_fans(&self, x: u32) -> usize {
        let mut left: Vec<u32> = (0..self.v.len() as u32).filter(|&c| self.v[c as usize] == x).collect();
        let mut fans = 0;
        while let Some(&c) = left.first() {
            // walk back to the fan's start, then the whole fan
            let mut s = c;
            while let Some(u) = self.twin(s).map(|t| self.next(t)).filter(|&u| u != c) {
                s = u;
            }
            let fan: Vec<u32> = self.fan_from(s).collect();
            left.retain(|y| !fan.contains(y));
            fans += 1;
        }
        fans
    }

    /// The corners from `start` on in swing order.
    fn fan_from(&self, start: u32) -> impl Iterator<Item = u32> + '_ {
        let mut next = Some(start);
        std::iter::from_fn(move || {
            let c = next?;
            next = self.swing(c).filter(|&x| x != start);
            Some(c)
        })
    }
}

/// Faces of at least 3 corners, indices in range, no vertex twice in a face.
fn check_faces(face_starts: &[u32], corners: &[u32], nv: usize) -> Result<(), MeshError> {
    let mut seen: Vec<u32> = Vec::new();
    for (f, w) in face_starts.windows(2).enumerate() {
        let (a, b) = (w[0] as usize, w[1] as usize);
        if b < a || b > corners.len() || b - a < 3 {
            return Err(MeshError::DegenerateFace { face: f, vertex: corners.get(a).copied().unwrap_or(0) });
        }
        seen.clear();
        for &i in &corners[a..b] {
            if i as usize >= nv {
                return Err(MeshError::IndexOutOfRange { face: f, index: i64::from(i), len: nv });
            }
            if seen.contains(&i) {
                return Err(MeshError::DegenerateFace { face: f, vertex: i });
            }
            seen.push(i);
        }
    }
    Ok(())
}

/// The twin of every corner (see the module docs).
fn twins(pt: &PolyTable, nv: usize) -> Result<Vec<u32>, MeshError> {
    let nc = pt.v.len();
    let mut start = vec![0u32; nv + 1];
    for &a in &pt.v {
        start[a as usize + 1] += 1;
    }
    for i in 0..nv {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    // each half-edge in the bucket of its start vertex, with its end
    let mut by_start = vec![(0u32, 0u32); nc];
    for c in 0..nc as u32 {
        let a = pt.v[c as usize] as usize;
        by_start[fill[a] as usize] = (c, pt.v[pt.next(c) as usize]);
        fill[a] += 1;
    }
    let bucket = |a: u32| &by_start[start[a as usize] as usize..start[a as usize + 1] as usize];
    let mut t = vec![BORDER; nc];
    for c in 0..nc as u32 {
        let (a, b) = (pt.v[c as usize], pt.v[pt.next(c) as usize]);
        let back: Vec<u32> = bucket(b).iter().filter(|&&(_, end)| end == a).map(|&(x, _)| x).collect();
        let same: Vec<u32> = bucket(a).iter().filter(|&&(x, end)| x != c && end == b).map(|&(x, _)| x).collect();
        if back.len() + same.len() + 1 > 2 {
            let mut faces: Vec<usize> =
                back.iter().chain(&same).chain(std::iter::once(&c)).map(|&x| pt.face(x) as usize).collect();
            faces.sort_unstable();
            let n = faces.len();
            faces.truncate(crate::error::MAX_EXAMPLES);
            return Err(MeshError::NonManifoldEdge { v0: a.min(b), v1: a.max(b), faces: n, examples: faces });
        }
        if let Some(&other) = same.first() {
            let (f0, f1) = (pt.face(c).min(pt.face(other)) as usize, pt.face(c).max(pt.face(other)) as usize);
            return Err(MeshError::InconsistentOrientation { v0: a, v1: b, f0, f1 });
        }
        if let Some(&x) = back.first() {
            t[c as usize] = x;
        }
    }
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2 x 1 grid of quads and a triangle on top: faces of 4, 4 and 3.
    fn mixed() -> (Vec<u32>, Vec<u32>) {
        // 3---4---5
        // |   |   |    6 above 4: triangle (3, 4, 6)? kept planar for ids
        // 0---1---2
        let starts = vec![0, 4, 8, 11];
        let corners = vec![0, 1, 4, 3, 1, 2, 5, 4, 3, 4, 6];
        (starts, corners)
    }

    #[test]
    fn twins_pair_each_edge_reversed_and_fans_are_whole() {
        let (starts, corners) = mixed();
        let (pt, rep, kept) = PolyTable::build(7, &starts, &corners, None).unwrap();
        assert_eq!((rep.unreferenced, kept), (0, None));
        assert_eq!((pt.num_faces(), pt.num_corners(), pt.num_vertices()), (3, 11, 7));
        for c in 0..pt.num_corners() as u32 {
            if let Some(x) = pt.twin(c) {
                assert_eq!(pt.twin(x), Some(c));
                assert_eq!((pt.vtx(x), pt.vtx(pt.next(x))), (pt.vtx(pt.next(c)), pt.vtx(c)));
            }
        }
        // the edge (1, 4) is shared by the two quads, (3, 4) by a quad and the triangle
        assert_eq!(pt.num_edges(), 9);
        assert_eq!(pt.valences()[4], 4);
        assert_eq!(pt.valences()[1], 3);
        for v in 0..7 {
            assert_eq!(pt.fan(v).count(), corners.iter().filter(|&&x| x == v).count(), "vertex {v}");
        }
        assert!(!pt.is_quads());
        let quads = PolyTable::build(6, &starts[..3], &corners[..8], None).unwrap().0;
        assert!(quads.is_quads() && quads.next(7) == 4 && quads.prev(4) == 7);
    }

    #[test]
    fn bad_polygons_are_refused_naming_the_face() {
        let (starts, corners) = mixed();
        let mut bad = corners.clone();
        bad[9] = 3; // the triangle uses vertex 3 twice
        assert!(matches!(PolyTable::build(7, &starts, &bad, None), Err(MeshError::DegenerateFace { face: 2, .. })));
        // the second quad reversed: edge (1, 4) twice the same way
        let flipped = vec![0, 1, 4, 3, 4, 5, 2, 1, 3, 4, 6];
        let e = PolyTable::build(7, &starts, &flipped, None).unwrap_err();
        assert!(matches!(e, MeshError::InconsistentOrientation { f0: 0, f1: 1, .. }), "{e}");
        // a third face on the edge (1, 4)
        let fin = [starts.clone(), vec![14]].concat();
        let fin_corners = [corners.clone(), vec![4, 1, 7]].concat();
        let e = PolyTable::build(8, &fin, &fin_corners, None).unwrap_err();
        assert!(matches!(e, MeshError::NonManifoldEdge { faces: 3, .. }), "{e}");
    }
}
