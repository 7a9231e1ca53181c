//! Local edits of a [`Refiner`]: moves of control vertices
//! ([`Refiner::move_vertices`]) and a vertex's support
//! ([`Refiner::support`]). A move marks, level by level, the rows that read
//! a changed point of the level above (through each level's transposed
//! rows, [`Readers`]), evaluates only those rows, then the normals around
//! the changed finest points; the tables an edit walks are built on the
//! first edit.

use super::Refiner;
use super::precise;
use crate::subdiv::tables::LevelPlan;
use crate::{Error, Result};
use glam::{DVec3, Vec3, Vec3A};
use rayon::prelude::*;

/// For each point of a level, the rows of the next level that read it
/// (the level's stencil table transposed): CSR.
#[derive(Clone, Debug, Default)]
pub(super) struct Readers {
    offsets: Vec<u32>,
    rows: Vec<u32>,
}

impl Readers {
    fn of(level: &LevelPlan) -> Readers {
        let n_in = level.n_in;
        let base = if level.copy_vertices { n_in } else { 0 };
        let mut count = vec![0u32; n_in + 1];
        if level.copy_vertices {
            count[..n_in].iter_mut().for_each(|c| *c += 1);
        }
        for &j in &level.indices {
            count[j as usize] += 1;
        }
        let mut offsets = Vec::with_capacity(n_in + 1);
        let mut acc = 0u32;
        for c in &count[..n_in] {
            offsets.push(acc);
            acc += c;
        }
        offsets.push(acc);
        let mut fill = offsets.clone();
        let mut rows = vec![0u32; acc as usize];
        if level.copy_vertices {
            for j in 0..n_in {
                rows[fill[j] as usize] = j as u32;
                fill[j] += 1;
            }
        }
        for r in 0..level.offsets.len() - 1 {
            let (a, b) = (level.offsets[r] as usize, level.offsets[r + 1] as usize);
            for &j in &level.indices[a..b] {
                rows[fill[j as usize] as usize] = (base + r) as u32;
                fill[j as usize] += 1;
            }
        }
        Readers { offsets, rows }
    }

    pub(super) fn of_point(&self, j: u32) -> &[u32] {
        let (a, b) = (self.offsets[j as usize] as usize, self.offsets[j as usize + 1] as usize);
        &self.rows[a..b]
    }
}

/// Which points of each level an update touched: the lists, and a stamp
/// per point so that each is listed once.
#[derive(Clone, Debug, Default)]
pub(super) struct Touched {
    pub(super) lists: Vec<Vec<u32>>,
    stamps: Vec<Vec<u32>>,
    epoch: u32,
}

impl Touched {
    fn sized(counts: &[usize]) -> Touched {
        Touched {
            lists: vec![Vec::new(); counts.len()],
            stamps: counts.iter().map(|&n| vec![0; n]).collect(),
            epoch: 0,
        }
    }

    /// A new update: every stamp older than it.
    pub(super) fn begin(&mut self) {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamps.iter_mut().for_each(|s| s.fill(0));
            self.epoch = 1;
        }
        self.lists.iter_mut().for_each(Vec::clear);
    }

    /// Lists point `i` of level `l` unless it is listed already.
    pub(super) fn mark(&mut self, l: usize, i: u32) {
        let s = &mut self.stamps[l][i as usize];
        if *s != self.epoch {
            *s = self.epoch;
            self.lists[l].push(i);
        }
    }
}

/// What a local edit walks: each level's readers, and the points touched;
/// the finest points the last edit evaluated.
#[derive(Clone, Debug, Default)]
pub(super) struct EditTables {
    pub(super) readers: Vec<Readers>,
    pub(super) touched: Touched,
    /// The finest points whose position or normal the last evaluation
    /// made anew, each once (see [`Refiner::changed_rows`]); `None`: all.
    pub(super) changed: Option<Vec<u32>>,
    /// Every level was evaluated by the rows since the last evaluation
    /// (the tables were just built): it changed every point.
    pub(super) fresh: bool,
    /// The finest points the last evaluation made anew (see
    /// [`Refiner::last_changed`]).
    pub(super) evaluated: Vec<u32>,
}

impl Refiner {
    /// The edit tables, built on first use (the stencils recorded then,
    /// and every level evaluated by them once: an edit re-evaluates rows,
    /// and a point then equals its row's sum bit for bit whatever moved).
    pub(super) fn edit_tables(&mut self) -> &mut EditTables {
        if self.edit.is_none() {
            self.evaluate_all();
            let readers = self.topo.plan().levels.par_iter().map(Readers::of).collect();
            let touched = Touched::sized(&self.level_counts());
            self.edit = Some(EditTables { readers, touched, changed: None, fresh: true, evaluated: Vec::new() });
        }
        self.edit.get_or_insert_with(EditTables::default)
    }

    /// Builds now what the first edit would build (the stencils, the
    /// tables an edit walks, every level evaluated by the rows), so that
    /// the first move or sharpness change costs what later ones do: an
    /// editor calls it when it opens. A refiner that only serves data
    /// never needs it.
    pub fn prepare_edits(&mut self) {
        self.edit_tables();
    }

    /// The finest points that control vertex `v` influences (its support),
    /// in increasing order; empty for an id out of range.
    pub fn support(&mut self, v: u32) -> Vec<u32> {
        if v as usize >= self.points[0].len() {
            return Vec::new();
        }
        self.touch(&[v], &[]);
        let mut rows = self.edit_tables().touched.lists.last().cloned().unwrap_or_default();
        rows.sort_unstable();
        rows
    }

    /// Marks the control points `ids`, the rows `seeds[l]` of level
    /// `l + 1` and, level by level, the rows that read a marked point.
    pub(super) fn touch(&mut self, ids: &[u32], seeds: &[Vec<u32>]) {
        self.edit_tables();
        let Some(EditTables { readers, touched: t, .. }) = self.edit.as_mut() else { return };
        t.begin();
        for &v in ids {
            t.mark(0, v);
        }
        for (l, readers) in readers.iter().enumerate() {
            for &r in seeds.get(l).into_iter().flatten() {
                t.mark(l + 1, r);
            }
            let extra = &self.patches.readers[l];
            let list = std::mem::take(&mut t.lists[l]);
            for &j in &list {
                for &r in readers.of_point(j).iter().chain(extra.get(&j).into_iter().flatten()) {
                    t.mark(l + 1, r);
                }
            }
            t.lists[l] = list;
        }
    }

    /// [`Refiner::move_vertices`] without a step of the history (a drag's
    /// intermediate positions; the caller keeps its own history).
    ///
    /// # Errors
    /// As [`Refiner::move_vertices`].
    pub(crate) fn set_vertices(&mut self, ids: &[u32], to: &[Vec3]) -> Result<usize> {
        self.check_move(ids, to.len())?;
        Ok(self.place(ids, to, None))
    }

    pub(super) fn check_move(&self, ids: &[u32], to: usize) -> Result<()> {
        let n = self.points[0].len();
        if ids.len() != to {
            return Err(Error::Usage(format!("{} vertex ids but {to} positions", ids.len())));
        }
        if let Some(bad) = ids.iter().find(|&&v| v as usize >= n) {
            return Err(Error::Usage(format!("vertex {bad} is not a control vertex (the cage has {n})")));
        }
        Ok(())
    }

    /// Moves control vertices `ids` to `to` and re-evaluates what they
    /// reach: the rows of each level that read a changed point, and the
    /// normals around the changed finest points. One step of the history.
    /// Returns how many finest points changed.
    ///
    /// The first edit (a move, [`Refiner::support`] or a sharpness change)
    /// records the stencils and evaluates every level by them once: the
    /// points [`Refiner::new`] made by the one-shot passes may differ from
    /// the rows' sums in the last bit, and from then on every edit, undo
    /// and redo equals evaluating every row ([`Refiner::set_control`]) bit
    /// for bit.
    ///
    /// # Errors
    /// [`Error::Usage`] when the lists differ in length or an id is out of
    /// range (nothing is changed then).
    pub fn move_vertices(&mut self, ids: &[u32], to: &[Vec3]) -> Result<usize> {
        self.check_move(ids, to.len())?;
        let wide = self.precise.as_ref().map(|_| to.iter().map(|p| p.as_dvec3()).collect::<Vec<_>>());
        self.push_move(ids, to, wide);
        Ok(self.place(ids, to, None))
    }

    /// Sets control points (in f64 `to64`, else `to` widened, where f64
    /// points are kept) and re-evaluates their support (no history).
    pub(super) fn place(&mut self, ids: &[u32], to: &[Vec3], to64: Option<&[DVec3]>) -> usize {
        for (&v, &p) in ids.iter().zip(to) {
            self.points[0][v as usize] = p;
        }
        if let Some(levels) = self.precise.as_mut() {
            for (k, &v) in ids.iter().enumerate() {
                levels[0][v as usize] = to64.map_or_else(|| to[k].as_dvec3(), |t| t[k]);
            }
        }
        self.touch(ids, &[]);
        self.evaluate_touched()
    }

    /// Evaluates the marked rows level by level, then the normals around
    /// the marked finest points; returns how many finest points changed.
    pub(super) fn evaluate_touched(&mut self) -> usize {
        let Some(edit) = self.edit.as_mut() else { return 0 };
        let plan = self.topo.plan();
        for l in 0..plan.levels.len() {
            let (done, rest) = self.points.split_at_mut(l + 1);
            let (input, out) = (&done[l], &mut rest[0]);
            let (level, patch) = (&plan.levels[l], &self.patches.rows[l]);
            let rows = &edit.touched.lists[l + 1];
            let value = |r: u32| match patch.get(&r) {
                Some(row) => sum_row(&row.idx, &row.w, input),
                None => row_value(level, r, input),
            };
            if rows.len() > 4096 {
                let values: Vec<Vec3> = rows.par_iter().map(|&r| value(r)).collect();
                rows.iter().zip(values).for_each(|(&r, p)| out[r as usize] = p);
            } else {
                rows.iter().for_each(|&r| out[r as usize] = value(r));
            }
        }
        if let Some(levels) = self.precise.as_mut() {
            let f64_rows = (self.topo.plan_f64(), &self.patches.rows_f64[..]);
            precise::evaluate_rows(f64_rows, &edit.touched.lists, levels);
        }
        let last = plan.levels.len();
        let changed = std::mem::take(&mut edit.touched.lists[last]);
        let around = self.update_normals_around(&changed);
        let count = changed.len();
        if let Some(edit) = self.edit.as_mut() {
            let fresh = std::mem::take(&mut edit.fresh);
            edit.changed = around.filter(|_| !fresh);
            edit.evaluated.clone_from(&changed);
            edit.touched.lists[last] = changed;
        }
        count
    }

    /// The finest points the last edit (a move, a sharpness change, an
    /// undo or redo) evaluated again: those that changed, and perhaps a
    /// few whose values came out the same. Every point after a sharpness
    /// change that refined anew (boundary `None`).
    pub fn last_changed(&self) -> &[u32] {
        self.edit.as_ref().map_or(&[], |e| &e.evaluated)
    }

    /// The finest points whose position or normal the last change (a
    /// move, an undo or redo, a sharpness change recorded locally) made
    /// anew, each once, in no order: what a copy of the finest level and
    /// its normals must take again (the viewer's GPU buffers). `None` when
    /// it may have changed them all: before the normals are made
    /// ([`Refiner::normals`]), at the first edit (which evaluates every
    /// level by the rows), after [`Refiner::set_control`] or a sharpness
    /// change that refined anew.
    pub(crate) fn changed_rows(&self) -> Option<&[u32]> {
        self.edit.as_ref()?.changed.as_deref()
    }
}

/// Row `r` of `level` evaluated on `input`, summed in the order and width
/// of [`LevelPlan::apply`] (so bit-identical to it).
fn row_value(level: &LevelPlan, r: u32, input: &[Vec3]) -> Vec3 {
    match level.row(r as usize) {
        Some((idx, w)) => sum_row(idx, w, input),
        None => input[r as usize],
    }
}

/// A row's weighted sum, as [`LevelPlan::apply`] sums.
pub(super) fn sum_row(idx: &[u32], w: &[f32], input: &[Vec3]) -> Vec3 {
    let mut sum = Vec3A::ZERO;
    for (&j, &w) in idx.iter().zip(w) {
        sum += Vec3A::from(input[j as usize]) * w;
    }
    Vec3::from(sum)
}
