//! Texture coordinates and materials through the polygon levels a
//! [`crate::Refiner`] keeps (see [`crate::mesh::attributes`] for the data
//! and the linear UV rule): texture coordinates per polygon corner,
//! bilinear in each face ([`split_poly_uvs`]; the smooth modes refine the
//! UV charts instead, `face_varying`), each child face keeping its parent's
//! material, then onto the fanned triangles of the finest level
//! ([`onto_fan`]). The refiner's colours go through its rows.

use crate::mesh::attributes::MaterialGroups;
use crate::mesh::poly::PolyTable;
use glam::Vec2;
use rayon::prelude::*;

/// Per-polygon-corner texture coordinates and per-face materials of the
/// finest polygons `fine` onto their fanned triangles, as
/// [`crate::mesh::poly::PolyMesh::triangulated`] lays them out.
pub(crate) fn onto_fan(
    fine: &PolyTable,
    uv: Option<Vec<Vec2>>,
    materials: Option<MaterialGroups>,
) -> (Option<Vec<Vec2>>, Option<MaterialGroups>) {
    let fan = fine.fan_corners();
    (
        uv.map(|u| fan.iter().map(|&c| u[c as usize]).collect()),
        materials.map(|m| MaterialGroups {
            face: fan.chunks_exact(3).map(|t| m.face[fine.face(t[0]) as usize]).collect(),
            ..m
        }),
    )
}

/// Texture coordinates per polygon corner (bilinear in each face, only when
/// `linear`) and face ids (child face `c` is old corner `c`: it keeps its
/// face's) through the polygon levels `tables`, coarse to fine, each the
/// table a level splits.
pub(crate) fn through_levels<T: std::borrow::Borrow<PolyTable>>(
    tables: impl IntoIterator<Item = T>,
    mut uv: Option<Vec<Vec2>>,
    mut face: Option<Vec<u32>>,
    linear: bool,
) -> (Option<Vec<Vec2>>, Option<Vec<u32>>) {
    for pt in tables {
        let pt = pt.borrow();
        uv = uv.filter(|_| linear).map(|u| split_poly_uvs(pt, &u));
        face = face.map(|f| (0..pt.num_corners() as u32).map(|c| f[pt.face(c) as usize]).collect());
    }
    (uv, face)
}

/// Texture coordinates per polygon corner after one quad split of `pt`,
/// bilinear inside each face (OpenSubdiv's `FVAR_LINEAR_ALL`): child quad
/// `c` gets `uv(c)`, the midpoints of the edges leaving and entering `c`,
/// and the face's centroid, so seams stay where they are.
fn split_poly_uvs(pt: &PolyTable, uv: &[Vec2]) -> Vec<Vec2> {
    let centroid: Vec<Vec2> = (0..pt.num_faces() as u32)
        .into_par_iter()
        .map(|f| {
            let r = pt.face_corners(f);
            let k = (r.end - r.start) as f32;
            r.map(|c| uv[c as usize]).sum::<Vec2>() / k
        })
        .collect();
    let mut out = vec![Vec2::ZERO; 4 * uv.len()];
    out.par_chunks_mut(4).enumerate().for_each(|(c, q)| {
        let c = c as u32;
        let (a, next, prev) = (uv[c as usize], uv[pt.next(c) as usize], uv[pt.prev(c) as usize]);
        q[0] = a;
        q[1] = (a + next) * 0.5;
        q[2] = centroid[pt.face(c) as usize];
        q[3] = (prev + a) * 0.5;
    });
    out
}
