//! What a refined mesh's vertices owe to its scheme, for the colourings:
//! the level that made each vertex and its distance from the control
//! surface, for triangle and polygon schemes alike (the mesh core's
//! [`crate::mesh::inspect`] knows only the 1-to-4 triangle split).

use super::sizes::ControlCounts;
use super::{Options, Scheme, subdivide};
use crate::mesh::inspect::{displacement_from_control, vertex_creation_level};
use crate::{Error, Mesh, Result};

/// Vertices after each of `0..=levels` levels of `scheme` on `control`.
pub(crate) fn vertices_per_level(control: &Mesh, scheme: Scheme, levels: u32) -> Vec<usize> {
    let c = ControlCounts::of(&control.ct);
    (0..=levels).map(|l| usize::try_from(c.vertices_at(scheme, l)).unwrap_or(usize::MAX)).collect()
}

/// The level that made each of the `nv` vertices of `levels` levels of
/// `scheme` on `control` (0: a control vertex; old vertices keep their ids).
pub fn creation_levels(control: &Mesh, scheme: Scheme, levels: u32, nv: usize) -> Vec<u8> {
    vertex_creation_level(&vertices_per_level(control, scheme, levels), nv)
}

/// Distance of each vertex of `fine` (`levels` levels of `scheme` on
/// `control`) from the point of the control surface it comes from: the
/// same vertex of the control refined by the scheme's linear counterpart
/// (midpoint for the triangle schemes, bilinear for the polygon ones),
/// which splits alike and numbers alike.
///
/// # Errors
/// [`Error::CountMismatch`] when `fine` is not `levels` levels of `control`.
pub fn displacement(control: &Mesh, fine: &Mesh, scheme: Scheme, levels: u32) -> Result<Vec<f32>> {
    if !scheme.is_polygonal() {
        return displacement_from_control(control, fine, levels);
    }
    let want = vertices_per_level(control, scheme, levels).last().copied().unwrap_or(0);
    if fine.positions.len() != want {
        return Err(Error::CountMismatch {
            what: format!("displacement: the fine mesh against {levels} levels of the control polygons"),
            unit: "vertices",
            expected: want,
            found: fine.positions.len(),
        });
    }
    let (flat, _) = subdivide(control, Scheme::Bilinear, levels, &Options::default())?;
    Ok(fine.positions.iter().zip(&flat.positions).map(|(a, b)| a.distance(*b)).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::poly::PolyMesh;
    use glam::Vec3;

    /// The counts are the refined mesh's; bilinear points lie on the control
    /// quads (displacement 0) and Catmull-Clark's move off them.
    #[test]
    fn polygon_levels_count_and_displace() {
        let positions: Vec<Vec3> =
            (0..8).map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, (i >> 2) as f32)).collect();
        let faces = [0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5];
        let starts: Vec<u32> = (0..=6).map(|f| 4 * f).collect();
        let cube = PolyMesh::from_faces(positions, &starts, &faces).unwrap().0.triangulated();
        for levels in 0..3 {
            let (cc, _) = subdivide(&cube, Scheme::CatmullClark, levels, &Options::default()).unwrap();
            assert_eq!(vertices_per_level(&cube, Scheme::CatmullClark, levels).last(), Some(&cc.positions.len()));
            let (flat, _) = subdivide(&cube, Scheme::Bilinear, levels, &Options::default()).unwrap();
            assert!(displacement(&cube, &flat, Scheme::Bilinear, levels).unwrap().iter().all(|&d| d < 1e-6));
            let d = displacement(&cube, &cc, Scheme::CatmullClark, levels).unwrap();
            assert_eq!(d.iter().any(|&x| x > 0.05), levels > 0, "level {levels}");
        }
        let (two, _) = subdivide(&cube, Scheme::CatmullClark, 2, &Options::default()).unwrap();
        assert!(displacement(&cube, &two, Scheme::CatmullClark, 1).is_err());
        let lv = creation_levels(&cube, Scheme::CatmullClark, 2, two.positions.len());
        assert_eq!((lv[0], lv[8], lv[two.positions.len() - 1]), (0, 1, 2));
    }
}
