//! Attributes served by the refiner on the levels it recorded, without
//! refining the cage again:
//!
//! - **colours** (one per vertex) through the recorded rows, the scheme's
//!   own weights, then clamped to [0, 1] (the interpolating schemes'
//!   negative weights can overshoot);
//! - **texture coordinates**, smooth (Loop and Catmull-Clark, every
//!   `Options::uv` mode but `linear`): on their face-varying topology, the
//!   UV charts as a table of their own (OpenSubdiv's face-varying
//!   channel), recorded once and kept while the seams stay where they are;
//!   linear: per triangle corner by the 1-to-4 split's midpoints, per
//!   polygon corner bilinear in each face of the kept level tables;
//! - **materials**: each child face keeps its parent's.

use super::Refiner;
use crate::Result;
use crate::mesh::attributes::{Attributes, MaterialGroups, UvInterpolation, refine_corner_uvs, refine_face_ids};
use crate::mesh::poly::{PolyMesh, PolyTable};
use crate::mesh::{BoundaryInterpolation, Mesh};
use crate::subdiv::tables::attributes::{onto_fan, through_levels};
use crate::subdiv::tables::face_varying::{charts, triangles_as_polygons};
use crate::subdiv::tables::plan::LevelTables;
use crate::subdiv::{Options, Scheme};
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::sync::{Arc, Mutex};

/// The face-varying topology of the texture coordinates last served: the
/// chart table's corners (the UVs welded per vertex), its levels (a
/// refiner of the charts, the UVs its points), and the finest chart value
/// of every finest corner.
struct FaceVarying {
    corners: Vec<u32>,
    charts: Refiner,
    fine: Vec<u32>,
}

/// The refiner's face-varying topology, recorded on first use.
#[derive(Default)]
pub(super) struct FaceVaryingCache(Mutex<Option<Arc<FaceVarying>>>);

impl Refiner {
    /// The cage's attributes on the finest level, laid out as the cage's
    /// were: texture coordinates per triangle corner of
    /// [`Refiner::topology`] (per polygon corner of [`Refiner::polygons`]
    /// for a refiner built on a polygon table), colours per vertex, a
    /// material per face. Colours go through the recorded rows; texture
    /// coordinates through their own face-varying topology, recorded on
    /// the first call and reused while the seams stay where they are; see
    /// the module's documentation. An attribute whose count does not match
    /// the cage is dropped.
    ///
    /// # Errors
    /// A level of the texture coordinates' own topology that would not fit
    /// in memory.
    pub fn attributes(&self, attrs: &Attributes) -> Result<Attributes> {
        if self.levels() == 0 {
            return Ok(attrs.clone());
        }
        let colors = attrs.colors.as_ref().filter(|c| c.len() == self.control().len()).map(|c| self.colors(c));
        let (uv, materials) = match self.scheme().is_polygonal() {
            true => self.polygon_attributes(attrs)?,
            false => self.triangle_attributes(attrs)?,
        };
        Ok(Attributes { uv, colors, materials, options: attrs.options })
    }

    /// Colours through the levels' rows, clamped to [0, 1].
    fn colors(&self, colors: &[Vec3]) -> Vec<Vec3> {
        let flat: Vec<f32> = colors.iter().flat_map(|c| c.to_array()).collect();
        // one value per control vertex and channel: the width is the cage's
        let fine = self.refine_f32(&flat, 3).unwrap_or_default();
        fine.chunks_exact(3).map(|c| Vec3::from_slice(c).clamp(Vec3::ZERO, Vec3::ONE)).collect()
    }

    /// A triangle scheme's texture coordinates and materials.
    fn triangle_attributes(&self, attrs: &Attributes) -> Result<(Option<Vec<Vec2>>, Option<MaterialGroups>)> {
        let (cage, levels) = (&self.cage, self.levels());
        let uv = attrs.uv.as_ref().filter(|u| u.len() == cage.num_corners());
        let smooth = match uv {
            Some(uv) if self.scheme() == Scheme::Loop && self.options().uv != UvInterpolation::Linear => {
                self.smooth_uvs(&triangles_as_polygons(cage), uv)?
            }
            _ => None,
        };
        let uv = smooth.or_else(|| uv.map(|uv| refine_corner_uvs(uv, levels)));
        let materials = attrs
            .materials
            .as_ref()
            .filter(|m| m.face.len() == cage.num_triangles())
            .map(|m| MaterialGroups { face: refine_face_ids(&m.face, levels), ..m.clone() });
        Ok((uv, materials))
    }

    /// A polygon scheme's texture coordinates and materials: per polygon
    /// corner through the kept level tables, then onto the finest
    /// triangles (as [`PolyMesh::triangulated`] lays them out) unless the
    /// cage was polygons.
    fn polygon_attributes(&self, attrs: &Attributes) -> Result<(Option<Vec<Vec2>>, Option<MaterialGroups>)> {
        let on_polygons = match self.from_polygons {
            true => attrs.clone(),
            false => {
                let stand_in = Mesh { ct: self.cage.clone(), positions: vec![Vec3::ZERO; self.cage.num_vertices()] };
                PolyMesh::from_mesh_with_attributes(&stand_in, attrs).1
            }
        };
        let LevelTables::Polygons(tables) = &self.topo.tables else { return Ok((None, None)) };
        let control = PolyTable::from_corner_table(&self.cage);
        let uv = on_polygons.uv.filter(|u| u.len() == control.num_corners());
        let smooth = match &uv {
            Some(u) if self.scheme() == Scheme::CatmullClark && self.options().uv != UvInterpolation::Linear => {
                self.smooth_uvs(&control, u)?
            }
            _ => None,
        };
        let face = on_polygons.materials.as_ref().map(|m| m.face.clone()).filter(|f| f.len() == control.num_faces());
        let (uv, face) = through_levels(tables, uv, face, smooth.is_none());
        let uv = smooth.or(uv);
        let materials = on_polygons.materials.zip(face).map(|(m, face)| MaterialGroups { face, ..m });
        match self.polygons() {
            Some(fine) if !self.from_polygons => Ok(onto_fan(fine, uv, materials)),
            _ => Ok((uv, materials)),
        }
    }

    /// Texture coordinates per corner of `pt` (the cage's polygons or
    /// triangles) smooth on their charts, per finest corner; `None` where
    /// the charts do not form a manifold table of their own (the caller
    /// then interpolates linearly).
    fn smooth_uvs(&self, pt: &PolyTable, uv: &[Vec2]) -> Result<Option<Vec<Vec2>>> {
        let Some(charts) = charts(pt, uv, self.options()) else { return Ok(None) };
        let fv = self.face_varying(&charts)?;
        // the charts' refiner made its points from these very values, or
        // the new values go through its rows
        let values = match fv.charts.control() == &charts.positions[..] {
            true => fv.charts.positions().to_vec(),
            false => {
                let flat: Vec<f32> = charts.positions.iter().flat_map(|p| p.to_array()).collect();
                let fine = fv.charts.refine_f32(&flat, 3)?;
                fine.chunks_exact(3).map(Vec3::from_slice).collect()
            }
        };
        Ok(Some(fv.fine.par_iter().map(|&v| values[v as usize].truncate()).collect()))
    }

    /// The face-varying topology of `charts`: the one kept when its corners
    /// are those of the last, else recorded now (and kept).
    fn face_varying(&self, charts: &PolyMesh) -> Result<Arc<FaceVarying>> {
        let mut kept = self.face_varying.0.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(fv) = kept.as_ref().filter(|fv| fv.corners == charts.pt.v_table()) {
            return Ok(fv.clone());
        }
        // the charts' own borders are seams: boundaries, never corners by the option
        let opts = Options { boundary: BoundaryInterpolation::EdgeOnly, ..*self.options() };
        let refiner = Refiner::new(&charts.triangulated(), self.scheme(), self.levels(), &opts)?;
        let fine = match refiner.polygons() {
            Some(p) => p.v_table().to_vec(),
            None => refiner.topology().v_table().to_vec(),
        };
        let fv = Arc::new(FaceVarying { corners: charts.pt.v_table().to_vec(), charts: refiner, fine });
        *kept = Some(fv.clone());
        Ok(fv)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 x 3 grid of points in the plane, 8 triangles, and texture
    /// coordinates per corner equal to the points' x and y.
    fn grid() -> (Mesh, Vec<Vec2>) {
        let pos: Vec<Vec3> = (0..9).map(|i| Vec3::new((i % 3) as f32, (i / 3) as f32, 0.0)).collect();
        let mut tris = Vec::new();
        for (x, y) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let v = y * 3 + x;
            tris.extend([v, v + 1, v + 4, v, v + 4, v + 3]);
        }
        let mesh = Mesh::from_triangles(pos, &tris).unwrap();
        let uv = mesh.ct.v_table().iter().map(|&v| mesh.positions[v as usize].truncate()).collect();
        (mesh, uv)
    }

    #[test]
    fn texture_coordinates_with_the_same_seams_reuse_their_topology() {
        let (mesh, uv) = grid();
        // the grid's one-triangle corners stay put, on the surface and the chart
        let opts = Options { boundary: BoundaryInterpolation::EdgeAndCorner, ..Options::default() };
        let r = Refiner::new(&mesh, Scheme::Loop, 2, &opts).unwrap();
        let with = |uv: Vec<Vec2>| Attributes { uv: Some(uv), ..Default::default() };
        let first = r.attributes(&with(uv.clone())).unwrap().uv.unwrap();
        let kept = r.face_varying.0.lock().unwrap().clone().unwrap();
        // UVs equal to the positions' x and y on a flat chart: Loop reproduces them
        let fine = r.mesh();
        for (c, &v) in fine.ct.v_table().iter().enumerate() {
            assert!(first[c].distance(fine.positions[v as usize].truncate()) < 1e-5, "corner {c}");
        }
        let shift = Vec2::new(0.5, 0.25);
        let moved = r.attributes(&with(uv.iter().map(|&t| t + shift).collect())).unwrap().uv.unwrap();
        let again = r.face_varying.0.lock().unwrap().clone().unwrap();
        assert!(Arc::ptr_eq(&kept, &again), "the same seams: the same face-varying topology");
        assert!(first.iter().zip(&moved).all(|(a, b)| (*a + shift).distance(*b) < 1e-5));
        // a seam along x = 1 (the right half's chart moved away): a topology of its own
        let mut seamed = uv.clone();
        for t in seamed.chunks_exact_mut(3) {
            if t.iter().map(|u| u.x).sum::<f32>() > 3.0 {
                t.iter_mut().for_each(|u| *u += Vec2::new(5.0, 0.0));
            }
        }
        let split = r.attributes(&with(seamed)).unwrap().uv.unwrap();
        assert!(split.iter().any(|u| u.x > 4.0) && split.iter().any(|u| u.x < 2.0), "both charts refined");
        let other = r.face_varying.0.lock().unwrap().clone().unwrap();
        assert!(!Arc::ptr_eq(&kept, &other), "other seams: recorded again");
    }
}
