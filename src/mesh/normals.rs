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
