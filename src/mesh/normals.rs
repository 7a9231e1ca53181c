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
    out.par_iter_mut().zip(ct.v.par_chunks_exact(3)).with_min_len(4096).for_each(|(f, tri)| {
        let a = pos[tri[0] as usize];
        *f = (pos[tri[1] as usize] - a).cross(pos[tri[2] as usize] - a);
    });
}

/// Area-weighted unit vertex normals, walking each vertex's fan.
/// A vertex whose faces all have zero area gets `Vec3::Z`.
pub fn vertex_normals(ct: &CornerTable, pos: &[Vec3]) -> Vec<Vec3> {
    let mut fnorm = vec![Vec3::ZERO; ct.num_triangles()];
    let mut out = vec![Vec3::ZERO; ct.num_vertices()];
    vertex_normals_into(ct, pos, &mut fnorm, &mut out);
    out
}

/// [`vertex_normals`] with caller-owned scratch (`fnorm`, one per triangle)
/// and output (one per vertex), for per-frame use.
pub fn vertex_normals_into(ct: &CornerTable, pos: &[Vec3], fnorm: &mut [Vec3], out: &mut [Vec3]) {
    face_normals_into(ct, pos, fnorm);
    let fnorm = &*fnorm;
    out.par_iter_mut().enumerate().with_min_len(4096).for_each(|(v, nrm)| {
        let mut s = Vec3::ZERO;
        for c in ct.fan(v as u32) {
            s += fnorm[c as usize / 3];
        }
        *nrm = s.try_normalize().unwrap_or(Vec3::Z);
    });
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
        for &v in &ct.v {
            offsets[v as usize + 1] += 1;
        }
        for i in 0..nv {
            offsets[i + 1] += offsets[i];
        }
        let mut next = offsets.clone();
        let mut faces = vec![0u32; ct.v.len()];
        for (c, &v) in ct.v.iter().enumerate() {
            let slot = &mut next[v as usize];
            faces[*slot as usize] = (c / 3) as u32;
            *slot += 1;
        }
        VertexFaces { offsets, faces }
    }

    /// Area-weighted unit vertex normals from face normals `fnorm` (as
    /// [`vertex_normals_into`], summed in the same fan-independent way: the
    /// result is identical up to floating-point summation order).
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
    fn csr_normals_equal_fan_normals() {
        let m = crate::mesh::shapes::icosphere(3);
        let mut fnorm = vec![Vec3::ZERO; m.ct.num_triangles()];
        let mut fan = vec![Vec3::ZERO; m.positions.len()];
        vertex_normals_into(&m.ct, &m.positions, &mut fnorm, &mut fan);
        let mut csr = vec![Vec3::ZERO; m.positions.len()];
        VertexFaces::new(&m.ct).normals_into(&fnorm, &mut csr);
        for (a, b) in fan.iter().zip(&csr) {
            assert!((*a - *b).length() < 1e-5, "{a} {b}");
        }
    }
}
