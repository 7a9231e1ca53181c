//! Attributes refined by a scheme: colours through the scheme's stencil
//! plan (see [`crate::mesh::attributes`] for the data and the linear UV rule).
//!
//! * **Colours** (one per vertex) use the scheme's own weights: they are
//!   refined by the same stencil plan as the positions (so a colour that is
//!   an affine function of position stays that function wherever the scheme
//!   reproduces it), then clamped to [0, 1] since the interpolating schemes'
//!   negative weights can overshoot.
//! * **Texture coordinates** are refined by Catmull-Clark and Loop on their
//!   UV charts (`face_varying`: OpenSubdiv's face-varying
//!   interpolation, every mode of [`crate::Options::uv`] but `all`), per
//!   polygon corner for the polygon schemes; linearly in each face with
//!   `all` ([`split_poly_uvs`]) and by the other triangle schemes
//!   ([`refine_corner_uvs`]).
//! * **Materials**: each child face keeps its parent's.

use super::plan::{PlanScratch, StencilPlan};
use crate::mesh::CornerTable;
use crate::mesh::attributes::MaterialGroups;
pub(crate) use crate::mesh::attributes::{Attributes, refine_corner_uvs};
use crate::mesh::poly::PolyTable;
use crate::subdiv::UvInterpolation;
use crate::{Options, Result, Scheme};
use glam::{Vec2, Vec3};
use rayon::prelude::*;

/// Vertex colours after `levels` levels of `scheme` on `ct`, with the
/// scheme's weights (through a stencil plan), clamped to [0, 1].
///
/// # Errors
/// A level that does not fit in memory.
pub(crate) fn refine_colors(
    ct: &CornerTable,
    colors: &[Vec3],
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<Vec<Vec3>> {
    let plan = StencilPlan::build(ct, scheme, levels, opts)?;
    let mut out = Vec::new();
    plan.apply(colors, &mut PlanScratch::default(), &mut out);
    out.par_iter_mut().for_each(|c| *c = c.clamp(Vec3::ZERO, Vec3::ONE));
    Ok(out)
}

/// Both attributes after `levels` levels of `scheme` on `ct`.
///
/// # Errors
/// See `refine_colors`.
pub(crate) fn refine(
    ct: &CornerTable,
    attrs: &Attributes,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<Attributes> {
    if scheme.is_polygonal() {
        return refine_through_polygons(ct, attrs, scheme, levels, opts);
    }
    let smooth = match &attrs.uv {
        Some(uv) if scheme == Scheme::Loop && opts.uv != UvInterpolation::Linear && uv.len() == ct.num_corners() => {
            super::face_varying::smooth_triangle_uvs(ct, uv, levels, opts)?
        }
        _ => None,
    };
    Ok(Attributes {
        uv: smooth.or_else(|| attrs.uv.as_ref().map(|uv| refine_corner_uvs(uv, levels))),
        colors: attrs.colors.as_ref().map(|c| refine_colors(ct, c, scheme, levels, opts)).transpose()?,
        materials: attrs
            .materials
            .as_ref()
            .map(|m| MaterialGroups { face: crate::mesh::attributes::refine_face_ids(&m.face, levels), ..m.clone() }),
        options: attrs.options,
    })
}

/// [`refine`] of a polygon scheme on a triangle table: through the
/// polygons it stands for ([`refine_poly`]), then onto the triangles of the
/// result as [`crate::mesh::poly::PolyMesh::triangulated`] lays them out.
fn refine_through_polygons(
    ct: &CornerTable,
    attrs: &Attributes,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<Attributes> {
    use crate::mesh::poly::PolyMesh;
    let stand_in = crate::Mesh { ct: ct.clone(), positions: vec![Vec3::ZERO; ct.num_vertices()] };
    let (pm, pattrs) = PolyMesh::from_mesh_with_attributes(&stand_in, attrs);
    let (fine, pt) = refine_poly_levels(&pm, &pattrs, scheme, levels, opts)?;
    let (uv, materials) = onto_fan(&pt, fine.uv, fine.materials);
    Ok(Attributes { uv, colors: fine.colors, materials, options: fine.options })
}

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

/// The attributes of a polygon mesh (texture coordinates per polygon
/// corner, colours per vertex, a material per face) after `levels` levels
/// of the polygon scheme `scheme`: texture coordinates as `opts.uv` says
/// (smooth on the charts, `face_varying`, or bilinear in each face,
/// `split_poly_uvs`), colours with the scheme's own weights
/// (clamped to [0, 1]), each child face keeping its parent's material.
///
/// # Errors
/// A level that does not fit in memory; a triangle scheme.
pub(crate) fn refine_poly(
    mesh: &crate::mesh::poly::PolyMesh,
    attrs: &Attributes,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<Attributes> {
    refine_poly_levels(mesh, attrs, scheme, levels, opts).map(|(a, _)| a)
}

/// [`refine_poly`] and the finest polygons it split its way to.
fn refine_poly_levels(
    mesh: &crate::mesh::poly::PolyMesh,
    attrs: &Attributes,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<(Attributes, PolyTable)> {
    use crate::mesh::poly::{PolyMesh, split};
    let colors = match &attrs.colors {
        Some(c) if c.len() == mesh.positions.len() => {
            let painted = PolyMesh { pt: mesh.pt.clone(), positions: c.clone() };
            let (fine, _) = crate::subdiv::subdivide_poly(&painted, scheme, levels, opts)?;
            Some(fine.positions.into_iter().map(|c| c.clamp(Vec3::ZERO, Vec3::ONE)).collect())
        }
        _ => None,
    };
    let mut pt = mesh.pt.clone();
    let uv = attrs.uv.clone().filter(|u| u.len() == pt.num_corners());
    let smooth = match &uv {
        Some(u) if opts.uv != UvInterpolation::Linear && scheme == Scheme::CatmullClark => {
            super::face_varying::smooth_uvs(&pt, u, scheme, levels, opts)?
        }
        _ => None,
    };
    let linear = smooth.is_none();
    let face = attrs.materials.as_ref().map(|m| m.face.clone()).filter(|f| f.len() == pt.num_faces());
    // each level's table, split as it is handed over; pt ends the finest
    let tables = (0..levels).map(|_| {
        let next = split::split(&pt, opts.creasing).0;
        std::mem::replace(&mut pt, next)
    });
    let (uv, face) = through_levels(tables, uv, face, linear);
    let materials = attrs.materials.as_ref().zip(face).map(|(m, face)| MaterialGroups { face, ..m.clone() });
    Ok((Attributes { uv: smooth.or(uv), colors, materials, options: attrs.options }, pt))
}
