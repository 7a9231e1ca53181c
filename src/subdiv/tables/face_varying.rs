//! Smooth texture coordinates for the polygon schemes (OpenSubdiv's
//! `FVAR_LINEAR_CORNERS_ONLY`): the UV charts refined as a mesh of their
//! own.
//!
//! The corners' texture coordinates, welded where a vertex's corners share
//! a value, are the vertices of a second polygon table over the same faces:
//! a seam (a vertex whose corners hold different values) is a border of
//! that table. Refining it with the scheme gives, inside a chart, exactly
//! the vertex rules; along a seam the boundary rules (`(a + 6 v + b) / 8`,
//! midpoints), as OpenSubdiv's face-varying boundaries; a value whose chart
//! has a single face at its vertex is an infinitely sharp corner where the
//! vertex has other faces (a chart corner on a seam) or where the boundary
//! option makes one-face vertices corners. The mesh's own sharpness goes
//! with it onto every edge that is not a seam and every value of a sharp
//! vertex. Both tables split their faces the same way (child face `c` of
//! corner `c`), so fine corner `c` of one is fine corner `c` of the other.

use crate::Result;
use crate::mesh::BoundaryInterpolation;
use crate::mesh::poly::{PolyMesh, PolyTable};
use crate::mesh::sharpness::Sharpness;
use crate::subdiv::{Options, Scheme, subdivide_poly};
use glam::{Vec2, Vec3};
use std::collections::HashMap;

/// Texture coordinates per corner of `pt` (one per polygon corner) after
/// `levels` levels of `scheme` on the UV charts; `None` where the charts do
/// not form a manifold table of their own (the caller then interpolates
/// linearly).
///
/// # Errors
/// A level that does not fit in memory.
pub fn smooth_uvs(
    pt: &PolyTable,
    uv: &[Vec2],
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<Option<Vec<Vec2>>> {
    let Some(charts) = charts(pt, uv) else { return Ok(None) };
    let opts = Options { boundary: BoundaryInterpolation::EdgeOnly, ..*opts };
    let (fine, _) = subdivide_poly(&charts, scheme, levels, &opts)?;
    let out = (0..fine.pt.num_corners() as u32).map(|c| fine.positions[fine.pt.vtx(c) as usize].truncate()).collect();
    Ok(Some(out))
}

/// The UV charts of `pt` as a polygon mesh (positions `(u, v, 0)`), with
/// the sharpness described in the module docs.
fn charts(pt: &PolyTable, uv: &[Vec2]) -> Option<PolyMesh> {
    if uv.len() != pt.num_corners() {
        return None;
    }
    let mut ids: HashMap<(u32, [u32; 2]), u32> = HashMap::with_capacity(pt.num_vertices());
    let mut vertex_of = Vec::new();
    let mut positions = Vec::new();
    let corners: Vec<u32> = (0..pt.num_corners() as u32)
        .map(|c| {
            let (v, t) = (pt.vtx(c), uv[c as usize]);
            *ids.entry((v, [t.x.to_bits(), t.y.to_bits()])).or_insert_with(|| {
                vertex_of.push(v);
                positions.push(Vec3::new(t.x, t.y, 0.0));
                positions.len() as u32 - 1
            })
        })
        .collect();
    let starts: Vec<u32> =
        (0..pt.num_faces() as u32).map(|f| pt.face_corners(f).start).chain([pt.num_corners() as u32]).collect();
    let (table, _, kept) = PolyTable::build(positions.len(), &starts, &corners, Some(&positions)).ok()?;
    if kept.is_some() || table.v_table() != corners.as_slice() {
        return None;
    }
    // values whose chart has one face at their vertex: corners, on the mesh
    // boundary too whatever the vertex boundary option (as OpenSubdiv)
    let corner_values: Vec<u32> = (0..positions.len() as u32).filter(|&u| table.fan(u).count() == 1).collect();
    let inherited = pt.sharpness().and_then(|s| {
        let edges = s.sharp_corners().iter().copied().filter(|&(c, _)| table.twin(c).is_some()).collect();
        let values = (0..positions.len() as u32)
            .map(|u| (u, s.vertex(vertex_of[u as usize])))
            .filter(|&(_, x)| x > 0.0)
            .collect();
        Sharpness::from_lists(edges, values)
    });
    let sharpness = Sharpness::with_corners(inherited, &corner_values);
    Some(PolyMesh { pt: table.with_sharpness(sharpness), positions })
}
