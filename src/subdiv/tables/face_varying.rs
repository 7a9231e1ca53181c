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

use crate::mesh::BoundaryInterpolation;
use crate::mesh::CornerTable;
use crate::mesh::attributes::weld_uvs;
use crate::mesh::poly::{PolyMesh, PolyTable};
use crate::mesh::sharpness::Sharpness;
use crate::subdiv::Options;
use glam::{Vec2, Vec3};

/// The triangles of `ct` as polygons of three corners (the same corners):
/// a table with hidden diagonals stands for polygons, not its triangles'.
pub(crate) fn triangles_as_polygons(ct: &CornerTable) -> PolyTable {
    let plain = CornerTable::from_parts(
        ct.v_table().to_vec(),
        ct.o_table().to_vec(),
        ct.c_table().to_vec(),
        ct.valences().to_vec(),
    )
    .with_sharpness(ct.sharpness().cloned());
    PolyTable::from_corner_table(&plain)
}

/// The UV charts of `pt` as a polygon mesh (positions `(u, v, 0)`), with
/// the sharpness described in the module docs.
pub(crate) fn charts(pt: &PolyTable, uv: &[Vec2], opts: &Options) -> Option<PolyMesh> {
    if uv.len() != pt.num_corners() {
        return None;
    }
    let (values, corners) = weld_uvs(pt.v_table(), uv);
    let mut vertex_of = vec![0u32; values.len()];
    for (c, &u) in corners.iter().enumerate() {
        vertex_of[u as usize] = pt.vtx(c as u32);
    }
    let positions: Vec<Vec3> = values.iter().map(|t| Vec3::new(t.x, t.y, 0.0)).collect();
    let starts: Vec<u32> =
        (0..pt.num_faces() as u32).map(|f| pt.face_corners(f).start).chain([pt.num_corners() as u32]).collect();
    let (table, _, kept) = PolyTable::build(positions.len(), &starts, &corners, Some(&positions)).ok()?;
    if kept.is_some() || table.v_table() != corners.as_slice() {
        return None;
    }
    let corner_values = fixed_values(pt, &table, &vertex_of, opts);
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

/// The values (vertices of the chart table `table`, `vertex_of` their mesh
/// vertices) that stay where they are as `opts.uv` says: OpenSubdiv's
/// sharpening of face-varying values (`vtr/fvarLevel.cpp`,
/// `completeTopologyFromFaceValues`), for a manifold mesh:
///
/// ```text
/// mismatch   a vertex with a seam (more than one value, or one value on
///            a chart border inside the mesh: a dart), or on the mesh
///            border with linear boundaries, or a one-face border vertex
///            when corners are sharp and the vertex boundary option does
///            not already make it a corner
/// all sharp  linear boundaries, an infinitely sharp vertex, three or more
///            values with corners-plus1/plus2, a dart with
///            corners-plus2/boundaries; with corners-plus1/plus2 and two
///            values: an infinitely sharp edge inside either span, or (plus2)
///            a span of one face
/// sharp      all sharp, an infinitely sharp edge inside the value's span,
///            or a span of one face unless the mode is none
/// ```
///
/// A vertex without a mismatch keeps the vertex's own rule: its values
/// follow the mesh's sharpness, which the chart table inherits, and a
/// one-face corner the vertex boundary option sharpens.
fn fixed_values(pt: &PolyTable, table: &PolyTable, vertex_of: &[u32], opts: &Options) -> Vec<u32> {
    use crate::mesh::attributes::UvInterpolation as U;
    let mode = opts.uv;
    let linear_boundaries = matches!(mode, U::Boundaries | U::Linear);
    let dependent = matches!(mode, U::CornersPlus1 | U::CornersPlus2);
    let plus2 = mode == U::CornersPlus2;
    let corners_sharp = mode != U::None;
    let sharpen_darts = plus2 || linear_boundaries;
    let geometric_corners = opts.boundary == BoundaryInterpolation::EdgeAndCorner;
    let inf = crate::mesh::sharpness::INFINITE;
    let mut values_of: Vec<Vec<u32>> = vec![Vec::new(); pt.num_vertices()];
    for (u, &v) in vertex_of.iter().enumerate() {
        values_of[v as usize].push(u as u32);
    }
    // the span of a value: its faces, and the infinitely sharp mesh edges inside it
    let size = |u: u32| table.fan(u).count();
    let sharp_inside = |u: u32| {
        table.fan(u).filter(|&x| table.twin(x).is_some() && pt.sharpness().is_some_and(|s| s.corner(x) >= inf)).count()
    };
    let mut out = Vec::new();
    for (v, values) in values_of.iter().enumerate() {
        let v = v as u32;
        let (boundary, faces) = (pt.is_boundary_vertex(v), pt.fan(v).count());
        let n = values.len();
        let seam = n > 1 || (n == 1 && table.is_boundary_vertex(values[0]) && !boundary);
        let v_inf = pt.sharpness().is_some_and(|s| s.vertex(v) >= inf) || (geometric_corners && boundary && faces == 1);
        let mismatch =
            seam || (boundary && linear_boundaries) || (boundary && faces == 1 && corners_sharp && !geometric_corners);
        if !mismatch {
            // the vertex's own rule: a corner the boundary option makes
            if v_inf {
                out.extend_from_slice(values);
            }
            continue;
        }
        let mut all = linear_boundaries || v_inf || (dependent && n > 2) || (sharpen_darts && n == 1 && !boundary);
        if !all && dependent && n == 2 {
            all = sharp_inside(values[0]) > 0 || sharp_inside(values[1]) > 0;
            all |= plus2 && (size(values[0]) == 1 || size(values[1]) == 1);
        }
        out.extend(values.iter().copied().filter(|&u| all || sharp_inside(u) > 0 || (size(u) == 1 && corners_sharp)));
    }
    out
}
