//! Vertex normals: the area-weighted average of the incident face normals
//! (schemes.md 4.4), computed per triangle and gathered per vertex in parallel.

use super::CornerTable;
use glam::Vec3;
use rayon::prelude::*;

/// Unnormalised face normals (cross product of two edges: length = 2 x area).
pub fn face_normals(ct: &CornerTable, pos: &[Vec3]) -> Vec<Vec3> {
    let mut out = vec![Vec3::ZERO; ct.num_triangles()];
    face_normals_into(ct, pos, &mut out);
    out
}

/// [`face_normals`] into a caller-owned buffer (no allocation per frame).
pub fn face_normals_into(ct: &CornerTable, pos: &[Vec3], out: &mut [Vec3]) {
    out.par_iter_mut().zip(ct.v_table().par_chunks_exact(3)).with_min_len(4096).for_each(|(f, tri)| {
        let a = pos[tri[0] as usize];
        *f = (pos[tri[1] as usize] - a).cross(pos[tri[2] as usize] - a);
    });
}

/// Area-weighted unit vertex normals: face normals gathered per vertex
/// through a [`VertexFaces`] list (sequential reads, faster than walking each
/// fan through O). A vertex whose faces all have zero area gets `Vec3::Z`.
/// For a fixed topology evaluated many times, keep the [`VertexFaces`].
pub fn vertex_normals(ct: &CornerTable, pos: &[Vec3]) -> Vec<Vec3> {
    let mut out = vec![Vec3::ZERO; ct.num_vertices()];
    VertexFaces::new(ct).normals_into(&face_normals(ct, pos), &mut out);
    out
}

/// The faces around every vertex as one compressed list (CSR): built once
/// for a fixed topology, it turns the per-frame normal gather into
/// sequential reads instead of a fan walk through the O table.
#[derive(Clone, Debug, Default)]
pub struct VertexFaces {
    /// `faces[offsets[v]..offsets[v + 1]]` are the triangles around `v`.
    offsets: Vec<u32>,
    faces: Vec<u32>,
}

impl VertexFaces {
    /// Counting sort of the corners by vertex (O(corners)).
    pub fn new(ct: &CornerTable) -> VertexFaces {
        let nv = ct.num_vertices();
        let mut offsets = vec![0u32; nv + 1];
        for &v in ct.v_table() {
            offsets[v as usize + 1] += 1;
        }
        for i in 0..nv {
            offsets[i + 1] += offsets[i];
        }
        let mut next = offsets.clone();
        let mut faces = vec![0u32; ct.v_table().len()];
        for (c, &v) in ct.v_table().iter().enumerate() {
            let slot = &mut next[v as usize];
            faces[*slot as usize] = (c / 3) as u32;
            *slot += 1;
        }
        VertexFaces { offsets, faces }
    }

    /// Area-weighted unit vertex normals from face normals `fnorm`.
    pub fn normals_into(&self, fnorm: &[Vec3], out: &mut [Vec3]) {
        out.par_iter_mut().enumerate().with_min_len(8192).for_each(|(v, nrm)| {
            let (a, b) = (self.offsets[v] as usize, self.offsets[v + 1] as usize);
            let s = self.faces[a..b].iter().fold(Vec3::ZERO, |s, &f| s + fnorm[f as usize]);
            *nrm = s.try_normalize().unwrap_or(Vec3::Z);
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gathered_normals_equal_fan_walks() {
        // the reference walks each vertex's fan through O
        for m in [crate::mesh::shapes::icosphere(3), crate::mesh::shapes::grid(5)] {
            let fnorm = face_normals(&m.ct, &m.positions);
            let got = vertex_normals(&m.ct, &m.positions);
            for (v, n) in got.iter().enumerate() {
                let s: Vec3 = m.ct.fan(v as u32).map(|c| fnorm[c as usize / 3]).sum();
                assert!((*n - s.normalize()).length() < 1e-5, "vertex {v}: {n} vs {s}");
            }
        }
    }
}
