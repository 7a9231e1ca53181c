//! Attributes refined by a scheme: colours through the scheme's stencil
//! plan (see [`crate::mesh::attributes`] for the data and the linear UV rule).
//!
//! * **Colours** (one per vertex) use the scheme's own weights: they are
//!   refined by the same stencil plan as the positions (so a colour that is
//!   an affine function of position stays that function wherever the scheme
//!   reproduces it), then clamped to [0, 1] since the interpolating schemes'
//!   negative weights can overshoot.
//! * **Texture coordinates** are refined linearly inside each triangle,
//!   whatever the scheme ([`refine_corner_uvs`]).

use super::plan::{PlanScratch, StencilPlan};
use crate::mesh::CornerTable;
pub use crate::mesh::attributes::{Attributes, refine_corner_uvs, split_corner_uvs};
use crate::{Options, Result, Scheme};
use glam::Vec3;
use rayon::prelude::*;

/// Vertex colours after `levels` levels of `scheme` on `ct`, with the
/// scheme's weights (through a stencil plan), clamped to [0, 1].
///
/// # Errors
/// A level that does not fit in memory.
pub fn refine_colors(
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
/// See [`refine_colors`].
pub fn refine(ct: &CornerTable, attrs: &Attributes, scheme: Scheme, levels: u32, opts: &Options) -> Result<Attributes> {
    Ok(Attributes {
        uv: attrs.uv.as_ref().map(|uv| refine_corner_uvs(uv, levels)),
        colors: attrs.colors.as_ref().map(|c| refine_colors(ct, c, scheme, levels, opts)).transpose()?,
        materials: attrs.materials.as_ref().map(|m| crate::mesh::attributes::MaterialGroups {
            face: crate::mesh::attributes::refine_face_ids(&m.face, levels),
            ..m.clone()
        }),
    })
}
