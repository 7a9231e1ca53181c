//! What a [`Refiner`] keeps and hands out: the scheme, levels and options
//! it was made with, every level's points and tables (a level as a mesh,
//! the finest topology and polygons), the control mesh as it now is, what
//! building took, and the stencil plan of the levels as they now are.

use super::Refiner;
use crate::subdiv::tables::StencilPlan;
use crate::subdiv::tables::plan::LevelTables;
use crate::subdiv::{Options, Scheme, Stats};
use crate::{CornerTable, Mesh};
use glam::Vec3;

impl Refiner {
    /// What building the levels took, phase by phase, as
    /// [`crate::subdivide`] reports it (the stencils, recorded on first
    /// need, are not in it).
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Level `l` as a mesh (the finest: [`Refiner::mesh`]; a polygon
    /// scheme's fanned), if refined.
    pub(crate) fn level_mesh(&self, l: u32) -> Option<Mesh> {
        let positions = self.points.get(l as usize)?.clone();
        if l as usize + 1 == self.points.len() {
            return Some(Mesh { ct: self.topology().clone(), positions });
        }
        let ct = match &self.topo.tables {
            LevelTables::Triangles(t) => t.get(l as usize)?.0.clone(),
            LevelTables::Polygons(t) => t.get(l as usize)?.triangulated(),
        };
        Some(Mesh { ct, positions })
    }

    /// How many points each level has, the control level first.
    pub(super) fn level_counts(&self) -> Vec<usize> {
        self.points.iter().map(Vec::len).collect()
    }

    /// The scheme.
    pub fn scheme(&self) -> Scheme {
        self.topo.scheme
    }

    /// Levels refined.
    pub fn levels(&self) -> u32 {
        self.topo.levels() as u32
    }

    /// The options the levels were refined with.
    pub fn options(&self) -> &Options {
        &self.topo.opts
    }

    /// The control mesh as it now is (moved points, current tags).
    pub fn cage(&self) -> Mesh {
        Mesh { ct: self.cage.clone(), positions: self.control().to_vec() }
    }

    /// The control points.
    pub fn control(&self) -> &[Vec3] {
        &self.points[0]
    }

    /// The finest level's points. They stay in one buffer for the
    /// refiner's life (every edit, undo, redo and sharpness change writes
    /// into it, never moves it), so a view of them stays valid as long as
    /// the refiner.
    pub fn positions(&self) -> &[Vec3] {
        self.points.last().map_or(&[], Vec::as_slice)
    }

    /// The points of level `level` (0: the control points), if refined.
    pub fn level_positions(&self, level: u32) -> Option<&[Vec3]> {
        self.points.get(level as usize).map(Vec::as_slice)
    }

    /// The finest level's triangles (a polygon scheme's quads as two
    /// triangles each, see [`Refiner::polygons`]).
    pub fn topology(&self) -> &CornerTable {
        self.topo.fine()
    }

    /// A polygon scheme's finest polygons.
    pub fn polygons(&self) -> Option<&crate::mesh::poly::PolyTable> {
        self.topo.fine_poly.as_ref()
    }

    /// The finest level as a mesh.
    pub fn mesh(&self) -> Mesh {
        Mesh { ct: self.topology().clone(), positions: self.positions().to_vec() }
    }

    /// The stencil plan of the levels as they now are (for the GPU or an
    /// animation; recorded now if not yet): rows recorded again after
    /// sharpness edits are written into it first.
    pub fn plan(&mut self) -> &StencilPlan {
        let plan = self.topo.plan_mut();
        for l in 0..plan.levels.len() {
            if self.patches.rows[l].is_empty() {
                continue;
            }
            let rows = std::mem::take(&mut self.patches.rows[l]);
            let level = plan.level_mut(l);
            let first = if level.copy_vertices { level.n_in } else { 0 };
            let (mut offsets, mut indices, mut weights) = (vec![0u32], Vec::new(), Vec::new());
            for i in 0..level.offsets.len() - 1 {
                let (idx, w) = match rows.get(&((first + i) as u32)) {
                    Some(r) => (&r.idx[..], &r.w[..]),
                    None => level.row(first + i).unwrap_or((&[], &[])),
                };
                indices.extend_from_slice(idx);
                weights.extend_from_slice(w);
                offsets.push(indices.len() as u32);
            }
            (level.offsets, level.indices, level.weights) = (offsets, indices, weights);
        }
        self.topo.plan()
    }
}
