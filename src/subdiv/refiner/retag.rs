//! A sharpness edit re-recorded where it reaches: on every level's kept
//! table the new sharpness is carried down (the split's decay, sparse),
//! the vertices whose features changed are found by comparing the old and
//! new sharp lists, and only the rows that read those vertices or their
//! neighbours are recorded again, by the same rule code as the whole
//! level. The new rows override the plan's until it is asked for whole
//! ([`super::Refiner::plan`]), and the points they make are evaluated
//! again with everything downstream of them.

use super::Refiner;
use crate::mesh::edges::EdgeTable;
use crate::mesh::normals::Fans;
use crate::mesh::sharpness::Sharpness;
use crate::subdiv::tables::LevelPlan;
use crate::subdiv::tables::plan::LevelTables;
use crate::{CornerTable, Result};
use std::collections::HashMap;

/// One recorded row.
#[derive(Clone, Debug, Default)]
pub(super) struct Row {
    pub(super) idx: Vec<u32>,
    pub(super) w: Vec<f32>,
}

/// Rows recorded again after sharpness edits, per level, over the plan's;
/// and the readers they add (a point a new row reads that its old row did
/// not).
#[derive(Clone, Debug, Default)]
pub(super) struct Patches {
    pub(super) rows: Vec<HashMap<u32, Row>>,
    pub(super) readers: Vec<HashMap<u32, Vec<u32>>>,
}

impl Patches {
    pub(super) fn sized(levels: usize) -> Patches {
        Patches { rows: vec![HashMap::new(); levels], readers: vec![HashMap::new(); levels] }
    }
}

/// The vertices whose sharp features differ between `old` and `new` (the
/// ends of edges whose sharpness changed, the vertices whose own did).
fn changed_vertices<T: EdgeTable + ?Sized>(table: &T, old: Option<&Sharpness>, new: Option<&Sharpness>) -> Vec<u32> {
    fn diff(a: &[(u32, f32)], b: &[(u32, f32)]) -> Vec<u32> {
        let (ma, mb): (HashMap<u32, f32>, HashMap<u32, f32>) =
            (a.iter().copied().collect(), b.iter().copied().collect());
        let mut out: Vec<u32> = ma.iter().filter(|(k, v)| mb.get(k) != Some(v)).map(|(k, _)| *k).collect();
        out.extend(mb.keys().filter(|k| !ma.contains_key(k)));
        out
    }
    fn lists(s: Option<&Sharpness>) -> (&[(u32, f32)], &[(u32, f32)]) {
        s.map_or((&[], &[]), |s| (s.sharp_corners(), s.sharp_vertices()))
    }
    let ((oc, ov), (nc, nv)) = (lists(old), lists(new));
    let mut out: Vec<u32> = diff(oc, nc)
        .into_iter()
        .flat_map(|c| {
            let (a, b) = table.edge_ends(c);
            [a, b]
        })
        .chain(diff(ov, nv))
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// `vertices` and their neighbours.
fn with_rings<T: Fans + ?Sized>(table: &T, vertices: &[u32]) -> Vec<u32> {
    let mut out = vertices.to_vec();
    let mut pairs = Vec::new();
    for &v in vertices {
        table.fan_pairs(v, &mut pairs);
        out.extend(pairs.iter().flat_map(|&(a, b)| [a, b]));
    }
    out.sort_unstable();
    out.dedup();
    out
}

impl Refiner {
    /// The rows of level `l + 1` that read any of `points` of level `l`,
    /// sorted, without an interpolating level's copies.
    fn readers_of(&self, l: usize, points: &[u32]) -> Vec<u32> {
        let level = &self.plan.levels[l];
        let first = if level.copy_vertices { level.n_in as u32 } else { 0 };
        let extra = &self.patches.readers[l];
        let mut rows: Vec<u32> = points
            .iter()
            .flat_map(|&j| self.readers[l].of_point(j).iter().chain(extra.get(&j).into_iter().flatten()))
            .copied()
            .filter(|&r| r >= first)
            .collect();
        rows.sort_unstable();
        rows.dedup();
        rows
    }

    /// Takes `rows` (recorded anew, row `k` for new vertex `ids[k]`) over
    /// level `l`'s.
    fn patch(&mut self, l: usize, ids: &[u32], rows: &LevelPlan) {
        for (k, &r) in ids.iter().enumerate() {
            let (a, b) = (rows.offsets[k] as usize, rows.offsets[k + 1] as usize);
            let row = Row { idx: rows.indices[a..b].to_vec(), w: rows.weights[a..b].to_vec() };
            let old: &[u32] = match self.patches.rows[l].get(&r) {
                Some(p) => &p.idx,
                None => self.plan.levels[l].row(r as usize).map_or(&[], |(i, _)| i),
            };
            for &j in row.idx.iter().filter(|j| !old.contains(j)) {
                let list = self.patches.readers[l].entry(j).or_default();
                if !list.contains(&r) {
                    list.push(r);
                }
            }
            self.patches.rows[l].insert(r, row);
        }
    }

    /// The cage `cage` (new tags, same faces): every level's table takes
    /// the new sharpness, the rows it reaches are recorded again and
    /// evaluated with what follows from them. Returns, per level, the rows
    /// recorded again.
    pub(super) fn retag_locally(&mut self, cage: &CornerTable) -> Result<Vec<Vec<u32>>> {
        let mut tables = std::mem::replace(&mut self.tables, LevelTables::Triangles(Vec::new()));
        let result = match &mut tables {
            LevelTables::Triangles(t) => self.retag_triangles(cage, t),
            LevelTables::Polygons(t) => self.retag_polygons(cage, t),
        };
        self.tables = tables;
        result
    }

    fn retag_triangles(&mut self, cage: &CornerTable, t: &mut [(CornerTable, Vec<u32>)]) -> Result<Vec<Vec<u32>>> {
        use crate::subdiv::rules::features::with_boundary_corners;
        let mut sharpness = with_boundary_corners(cage, self.opts.boundary).sharpness().cloned();
        let mut redone = Vec::with_capacity(t.len());
        for (l, (table, owners)) in t.iter_mut().enumerate() {
            let old = table.sharpness().cloned();
            *table = std::mem::take(table).with_sharpness(sharpness);
            let changed = changed_vertices(table, old.as_ref(), table.sharpness());
            let ids = self.readers_of(l, &with_rings(table, &changed));
            let rows = crate::subdiv::tables::plan::record_rows_of(table, owners, (self.scheme, &self.opts), &ids);
            self.patch(l, &ids, &rows);
            redone.push(ids);
            sharpness = table.sharpness().and_then(|s| s.split(table, self.opts.creasing));
        }
        Ok(redone)
    }

    fn retag_polygons(
        &mut self,
        cage: &CornerTable,
        t: &mut [crate::mesh::poly::PolyTable],
    ) -> Result<Vec<Vec<u32>>> {
        use crate::mesh::poly::PolyTable;
        use crate::subdiv::refine::poly::with_boundary_corners;
        let control = PolyTable::from_corner_table(cage);
        let first = with_boundary_corners(&control, self.opts.boundary).unwrap_or(control);
        let mut sharpness = first.sharpness().cloned();
        let mut redone = Vec::with_capacity(t.len());
        for (l, table) in t.iter_mut().enumerate() {
            let old = table.sharpness().cloned();
            *table = std::mem::take(table).with_sharpness(sharpness);
            let changed = changed_vertices(table, old.as_ref(), table.sharpness());
            let ids = self.readers_of(l, &with_rings(table, &changed));
            let rows = crate::subdiv::tables::poly_plan::record_poly_level(table, self.scheme, &self.opts, Some(&ids));
            self.patch(l, &ids, &rows);
            redone.push(ids);
            sharpness = crate::mesh::poly::split::split_sharpness_of(table, self.opts.creasing);
        }
        Ok(redone)
    }
}
