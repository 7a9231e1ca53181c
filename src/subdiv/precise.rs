//! Double precision, the caller's choice (`--precision f64`, Python's
//! float64 arrays). Every scheme runs the one-shot passes of f32, written
//! once over the point type (`rules::Coord`: the rules emit their weights
//! in f64 and each precision rounds them as it takes them), on f64 points.
//! The topology is the one [`crate::subdivide`] makes (same vertex and face
//! ids), and an interpolating scheme's old vertices are copied, bit for
//! bit. [`plan_f64`] records the rows themselves with f64 weights, for a
//! caller that composes them into a subdivision matrix.

use super::tables::{LevelPlan, StencilPlan};
use super::{Options, Scheme};
use crate::mesh::poly::PolyMesh;
use crate::{Error, Mesh, Result};
use glam::DVec3;

/// `levels` levels of triangle `scheme` (or a polygon scheme on the
/// polygons the mesh stands for, as [`crate::subdivide`] takes them) of
/// `mesh`'s topology with the control positions `control` in f64: the
/// refined mesh (its `positions` the f64 ones rounded to f32, for drawing)
/// and the refined positions in f64.
///
/// # Errors
/// `control` not one position per vertex of `mesh`; a level that does not
/// fit in memory ([`Error::TooLarge`]).
pub(crate) fn subdivide_mesh_f64(
    mesh: &Mesh,
    control: &[DVec3],
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<(Mesh, Vec<DVec3>)> {
    check_count(control.len(), mesh.positions.len())?;
    let (ct, positions) = match scheme.is_polygonal() {
        // the polygons the mesh stands for, as subdivide takes them
        true => {
            let pt = crate::mesh::poly::PolyTable::from_corner_table(&mesh.ct);
            let mut kept = super::poly_kept((&pt, control), (scheme, levels, opts), &mut |_, _| true)?;
            let fine = kept.fine_poly.take().unwrap_or(pt);
            (fine.triangulated(), kept.points.pop().unwrap_or_default())
        }
        // the triangle schemes' one-shot passes, in f64
        false => {
            let none = None::<&fn(u32) -> u32>;
            match super::refine_levels(mesh, control, (scheme, levels, opts), none, |_, _| true)?.0 {
                super::refine::Refined::Table(ct, positions, ..) => (ct, positions),
                // refine_levels gives faces only when asked for them
                super::refine::Refined::Faces(_) => unreachable!("refine_levels made faces without being asked"),
            }
        }
    };
    let rounded = positions.iter().map(|p| p.as_vec3()).collect();
    Ok((Mesh { ct, positions: rounded }, positions))
}

/// [`subdivide_f64`] of a polygon mesh under a polygon scheme
/// (Catmull-Clark, bilinear): the refined polygons as
/// [`crate::subdivide_poly`] makes them, and their positions in f64.
///
/// # Errors
/// As [`subdivide_f64`]; a triangle scheme.
pub(crate) fn subdivide_poly_f64(
    mesh: &PolyMesh,
    control: &[DVec3],
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<(PolyMesh, Vec<DVec3>)> {
    if !scheme.is_polygonal() {
        return Err(Error::Usage(format!("{scheme} subdivides triangles: fan the polygons first")));
    }
    check_count(control.len(), mesh.positions.len())?;
    let (pt, positions) = match levels {
        // no level: the table as it came
        0 => (mesh.pt.clone(), control.to_vec()),
        _ => {
            let mut kept = super::poly_kept((&mesh.pt, control), (scheme, levels, opts), &mut |_, _| true)?;
            (kept.fine_poly.take().unwrap_or_default(), kept.points.pop().unwrap_or_default())
        }
    };
    let rounded = positions.iter().map(|p| p.as_vec3()).collect();
    Ok((PolyMesh { pt, positions: rounded }, positions))
}

fn check_count(got: usize, vertices: usize) -> Result<()> {
    if got == vertices {
        return Ok(());
    }
    Err(Error::Usage(format!("{got} double-precision positions for a mesh of {vertices} vertices")))
}

/// Every level of `scheme` on the topology `ct` recorded with f64
/// weights (rows coarse to fine, as [`StencilPlan::build`] records them in
/// f32), the finest triangles and, for a polygon scheme, the finest
/// polygons: what a caller composes into an exact subdivision matrix.
pub struct PlanF64 {
    /// The levels, coarse to fine.
    pub levels: Vec<LevelPlan<f64>>,
    /// The finest level's triangles.
    pub ct: crate::CornerTable,
    /// The finest level's polygons (polygon schemes).
    pub poly: Option<crate::mesh::poly::PolyTable>,
}

/// Records [`PlanF64`].
///
/// # Errors
/// A level that does not fit in memory ([`Error::TooLarge`]).
pub fn plan_f64(ct: &crate::CornerTable, scheme: Scheme, levels: u32, opts: &Options) -> Result<PlanF64> {
    let (levels, ct, poly) = StencilPlan::record::<f64>(ct, scheme, levels, opts)?;
    Ok(PlanF64 { levels, ct, poly })
}
