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
use crate::mesh::poly::PolyTable;
use crate::mesh::sharpness::{Sharpness, Tags};
use crate::mesh::{BoundaryInterpolation, Creasing};
use crate::subdiv::rules::Weight;
use crate::subdiv::tables::LevelPlan;
use crate::subdiv::tables::plan::LevelTables;
use crate::subdiv::{Options, Scheme};
use crate::{CornerTable, Result};
use std::collections::HashMap;

/// One recorded row.
#[derive(Clone, Debug, Default)]
pub(super) struct Row<W = f32> {
    pub(super) idx: Vec<u32>,
    pub(super) w: Vec<W>,
}

/// Rows recorded again after sharpness edits, per level, over the plan's;
/// and the readers they add (a point a new row reads that its old row did
/// not).
///
/// The same rows with f64 weights are recorded only while the f64 plan
/// exists (recorded later, it is recorded on the retagged tables): a
/// row's f64 patch, where there is one, is over the f64 plan's row. The
/// f32 rows are written into the f32 plan when it is asked for whole
/// ([`Refiner::plan`]); the f64 ones stay.
#[derive(Clone, Debug, Default)]
pub(super) struct Patches {
    pub(super) rows: Vec<HashMap<u32, Row>>,
    pub(super) rows_f64: Vec<HashMap<u32, Row<f64>>>,
    pub(super) readers: Vec<HashMap<u32, Vec<u32>>>,
}

impl Patches {
    pub(super) fn sized(levels: usize) -> Patches {
        Patches {
            rows: vec![HashMap::new(); levels],
            rows_f64: vec![HashMap::new(); levels],
            readers: vec![HashMap::new(); levels],
        }
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
    type Lists<'a> = (&'a [(u32, f32)], &'a [(u32, f32)]);
    fn lists(s: Option<&Sharpness>) -> Lists<'_> {
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
        let level = &self.topo.plan().levels[l];
        let first = if level.copy_vertices { level.n_in as u32 } else { 0 };
        let extra = &self.patches.readers[l];
        let readers = self.edit.as_ref().map_or(&[][..], |e| &e.readers[..]);
        let mut rows: Vec<u32> = points
            .iter()
            .flat_map(|&j| readers[l].of_point(j).iter().chain(extra.get(&j).into_iter().flatten()))
            .copied()
            .filter(|&r| r >= first)
            .collect();
        rows.sort_unstable();
        rows.dedup();
        rows
    }

    /// Takes `rows` (recorded anew, row `k` for new vertex `ids[k]`) over
    /// level `l`'s f64 rows.
    fn patch_f64(&mut self, l: usize, ids: &[u32], rows: &LevelPlan<f64>) {
        for (k, &r) in ids.iter().enumerate() {
            let (a, b) = (rows.offsets[k] as usize, rows.offsets[k + 1] as usize);
            let row = Row { idx: rows.indices[a..b].to_vec(), w: rows.weights[a..b].to_vec() };
            self.patches.rows_f64[l].insert(r, row);
        }
    }

    /// Takes `rows` (recorded anew, row `k` for new vertex `ids[k]`) over
    /// level `l`'s.
    fn patch(&mut self, l: usize, ids: &[u32], rows: &LevelPlan) {
        for (k, &r) in ids.iter().enumerate() {
            let (a, b) = (rows.offsets[k] as usize, rows.offsets[k + 1] as usize);
            let row = Row { idx: rows.indices[a..b].to_vec(), w: rows.weights[a..b].to_vec() };
            let old: &[u32] = match self.patches.rows[l].get(&r) {
                Some(p) => &p.idx,
                None => self.topo.plan().levels[l].row(r as usize).map_or(&[], |(i, _)| i),
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

    /// New `tags` on the same faces: every level's table takes the new
    /// sharpness, the rows it reaches are recorded again. Returns, per
    /// level, the rows recorded again, or `None` where the tags decide
    /// more than sharpness (boundary `None`: a border edge's tag decides
    /// which faces are holes), for a whole new recording.
    ///
    /// # Errors
    /// A tag naming no edge of the tables.
    pub(super) fn retag_locally(&mut self, tags: &Tags) -> Result<Option<Vec<Vec<u32>>>> {
        if self.topo.opts.boundary == BoundaryInterpolation::None {
            return Ok(None);
        }
        self.edit_tables();
        let mut tables = std::mem::replace(&mut self.topo.tables, LevelTables::Triangles(Vec::new()));
        let result = match &mut tables {
            LevelTables::Triangles(t) => self.retag_levels(t.iter_mut().map(|(t, o)| Level::Triangles(t, o)), tags),
            LevelTables::Polygons(t) => self.retag_levels(t.iter_mut().map(Level::Polygons), tags),
        };
        self.topo.tables = tables;
        let (redone, fine) = result?;
        self.topo.set_fine_sharpness(fine);
        Ok(Some(redone))
    }

    /// The levels retagged; the rows recorded again per level, and the
    /// finest level's new sharpness.
    fn retag_levels<'a>(
        &mut self,
        levels: impl Iterator<Item = Level<'a>>,
        tags: &Tags,
    ) -> Result<(Vec<Vec<u32>>, Option<Sharpness>)> {
        let mut sharpness = None;
        let mut redone = Vec::new();
        for (l, mut level) in levels.enumerate() {
            if l == 0 {
                sharpness = level.control_sharpness(tags, self.topo.opts.boundary)?;
            }
            let old = level.set_sharpness(sharpness);
            let near = level.changed_and_near(old.as_ref());
            let ids = self.readers_of(l, &near);
            let rows = level.record_rows(self.topo.scheme, &self.topo.opts, &ids);
            self.patch(l, &ids, &rows);
            if self.topo.has_plan_f64() {
                let rows = level.record_rows::<f64>(self.topo.scheme, &self.topo.opts, &ids);
                self.patch_f64(l, &ids, &rows);
            }
            redone.push(ids);
            sharpness = level.next_sharpness(self.topo.opts.creasing);
        }
        Ok((redone, sharpness))
    }
}

/// A kept level's table, of either kind.
enum Level<'a> {
    Triangles(&'a mut CornerTable, &'a [u32]),
    Polygons(&'a mut PolyTable),
}

impl Level<'_> {
    /// The control level's sharpness for `tags`, boundary corners added.
    fn control_sharpness(&self, tags: &Tags, boundary: BoundaryInterpolation) -> Result<Option<Sharpness>> {
        use crate::subdiv::rules::features::boundary_corners;
        let (s, corners) = match self {
            Level::Triangles(t, _) => (Sharpness::from_tags(&**t, tags), boundary_corners(&**t, boundary)),
            Level::Polygons(t) => (Sharpness::from_tags(&**t, tags), boundary_corners(&**t, boundary)),
        };
        let s = s.map_err(crate::Error::Invalid)?;
        Ok(if corners.is_empty() { s } else { Sharpness::with_corners(s, &corners) })
    }

    /// Gives the table `s`; returns the sharpness it had.
    fn set_sharpness(&mut self, s: Option<Sharpness>) -> Option<Sharpness> {
        match self {
            Level::Triangles(t, _) => {
                let old = t.sharpness().cloned();
                **t = std::mem::take(&mut **t).with_sharpness(s);
                old
            }
            Level::Polygons(t) => {
                let old = t.sharpness().cloned();
                **t = std::mem::take(&mut **t).with_sharpness(s);
                old
            }
        }
    }

    /// The vertices whose features changed from `old`, with their
    /// neighbours.
    fn changed_and_near(&self, old: Option<&Sharpness>) -> Vec<u32> {
        match self {
            Level::Triangles(t, _) => with_rings(&**t, &changed_vertices(&**t, old, t.sharpness())),
            Level::Polygons(t) => with_rings(&**t, &changed_vertices(&**t, old, t.sharpness())),
        }
    }

    /// The rows of new vertices `ids`, by the rules of the whole level.
    fn record_rows<W: Weight + std::ops::AddAssign>(
        &self,
        scheme: Scheme,
        opts: &Options,
        ids: &[u32],
    ) -> LevelPlan<W> {
        match self {
            Level::Triangles(t, owners) => crate::subdiv::tables::plan::record_rows_of(t, owners, (scheme, opts), ids),
            Level::Polygons(t) => crate::subdiv::tables::poly_plan::record_poly_level(t, scheme, opts, Some(ids)),
        }
    }

    /// The sharpness the split gives the next level.
    fn next_sharpness(&self, creasing: Creasing) -> Option<Sharpness> {
        match self {
            Level::Triangles(t, _) => t.sharpness().and_then(|s| s.split(t, creasing)),
            Level::Polygons(t) => crate::mesh::poly::split::split_sharpness_of(t, creasing),
        }
    }
}
