//! The refiner: a control mesh's topology refined once, any data served on
//! it many times (OpenSubdiv's `Far::TopologyRefiner` with its
//! `PrimvarRefiner` and stencil table in one object).
//!
//! [`Refiner::new`] refines the cage by the one-shot passes (it is what
//! [`crate::subdivide`] runs) and keeps every level: its table, with what
//! the rules need to record its stencils, and its points. The stencils are
//! recorded from those tables on first need, by the same rule code. From
//! then on:
//!
//! - any per-vertex data of any width is refined through the recorded rows,
//!   in f32 or f64 ([`Refiner::refine`], the f64 weights recorded in f64);
//! - moving control vertices ([`Refiner::move_vertices`]) re-evaluates only
//!   their support: at each level the rows that read a changed point of the
//!   level above, found through the transposed rows, then the normals of
//!   the changed finest points and of their neighbours. The result is
//!   bit-identical to evaluating every row again ([`Refiner::set_control`]);
//! - a sharpness change ([`Refiner::set_edge_sharpness`]) records the
//!   stencils again for the new tags and re-evaluates;
//! - every change is a step of a history ([`Refiner::undo`],
//!   [`Refiner::redo`]) that stores what changed, not the mesh.

mod attributes;
mod precise;
mod retag;
mod topology;

use super::tables::{LevelPlan, StencilPlan};
use super::{Levels, Options, Scheme, Stats};
use crate::mesh::sharpness::{CornerTag, CreaseTag, Tags, checked_sharpness};
use crate::{CornerTable, Error, Mesh, Result};
use glam::{DVec3, Vec3, Vec3A};
use rayon::prelude::*;
use retag::Patches;
use std::collections::HashMap;
use std::sync::OnceLock;
use topology::Topology;

/// For each point of a level, the rows of the next level that read it
/// (the level's stencil table transposed): CSR.
#[derive(Clone, Debug, Default)]
struct Readers {
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

    fn of_point(&self, j: u32) -> &[u32] {
        let (a, b) = (self.offsets[j as usize] as usize, self.offsets[j as usize + 1] as usize);
        &self.rows[a..b]
    }
}

/// Which points of each level an update touched: the lists, and a stamp
/// per point so that each is listed once.
#[derive(Clone, Debug, Default)]
struct Touched {
    lists: Vec<Vec<u32>>,
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
    fn begin(&mut self) {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamps.iter_mut().for_each(|s| s.fill(0));
            self.epoch = 1;
        }
        self.lists.iter_mut().for_each(Vec::clear);
    }

    /// Lists point `i` of level `l` unless it is listed already.
    fn mark(&mut self, l: usize, i: u32) {
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
struct EditTables {
    readers: Vec<Readers>,
    touched: Touched,
    /// The finest points whose position or normal the last evaluation
    /// made anew, each once (see [`Refiner::changed_rows`]); `None`: all.
    changed: Option<Vec<u32>>,
    /// Every level was evaluated by the rows since the last evaluation
    /// (the tables were just built): it changed every point.
    fresh: bool,
    /// The finest points the last evaluation made anew (see
    /// [`Refiner::last_changed`]).
    evaluated: Vec<u32>,
}

/// One change of a [`Refiner`]'s history.
#[derive(Clone, Debug)]
enum Step {
    /// Control vertices moved: their ids, positions before and after (and
    /// in f64, where the refiner keeps f64 points).
    Move { ids: Vec<u32>, before: Vec<Vec3>, after: Vec<Vec3>, precise: Option<Box<Moved64>> },
    /// The sharpness tags before and after.
    Tags { before: Tags, after: Tags },
}

/// A move's f64 control positions before and after.
type Moved64 = (Vec<DVec3>, Vec<DVec3>);

/// Undo and redo stacks.
#[derive(Clone, Debug, Default)]
struct History {
    done: Vec<Step>,
    undone: Vec<Step>,
}

/// A control mesh refined `levels` times with one scheme: every level's
/// table and points kept, its stencils recorded from them on first need,
/// any data refined on demand, edits applied where they reach. See the module's
/// documentation.
///
/// ```
/// use subdiv::{Mesh, Options, Refiner, Scheme};
/// use glam::Vec3;
/// let pos = vec![Vec3::new(1., 1., 1.), Vec3::new(1., -1., -1.), Vec3::new(-1., 1., -1.), Vec3::new(-1., -1., 1.)];
/// let mesh = Mesh::from_triangles(pos, &[0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2]).unwrap();
/// let mut r = Refiner::new(&mesh, Scheme::Loop, 2, &Options::default()).unwrap();
/// let changed = r.move_vertices(&[0], &[Vec3::new(2., 2., 2.)]).unwrap();
/// assert!(changed > 0 && changed < r.positions().len() + 1);
/// r.undo();
/// assert_eq!(r.control()[0], Vec3::new(1., 1., 1.));
/// ```
pub struct Refiner {
    /// The control topology with its current tags.
    cage: CornerTable,
    /// Every level's table, the finest, and the stencils made from them.
    topo: Topology,
    /// Points of every level: `[0]` the control points, last the finest.
    /// Each buffer is allocated once: edits write into it.
    points: Vec<Vec<Vec3>>,
    /// The same in f64, kept once asked for ([`Refiner::set_control_f64`]).
    precise: Option<Vec<Vec<DVec3>>>,
    /// The finest level's normals, made on first use and then kept up to
    /// date by every edit.
    normals: OnceLock<Vec<Vec3>>,
    /// The finest level's one-rings (CSR, a closed ring's first neighbour
    /// repeated at its end; `None` where a fan does not chain), made with
    /// the normals.
    rings: OnceLock<Option<(Vec<u32>, Vec<u32>)>>,
    /// The tables an edit walks (built on the first edit: a refiner that
    /// only serves data never pays for them).
    edit: Option<EditTables>,
    history: History,
    /// Rows recorded again after sharpness edits.
    patches: Patches,
    /// Whether the cage was a polygon table: attributes come and go per
    /// polygon corner.
    from_polygons: bool,
    /// The face-varying topology of the texture coordinates last served.
    face_varying: attributes::FaceVaryingCache,
    /// What the one-shot refinement took, phase by phase.
    stats: Stats,
}

impl Refiner {
    /// Refines `levels` levels of `scheme` on `cage`'s topology (its tags
    /// and holes included) at its positions, keeping every level.
    ///
    /// # Errors
    /// [`Error::TooLarge`] when a level would not fit in memory; a polygon
    /// scheme's refusal of the mesh.
    pub fn new<C: super::Cage>(cage: &C, scheme: Scheme, levels: u32, opts: &Options) -> Result<Refiner> {
        Self::with_progress(cage, (scheme, levels, opts), &mut |_, _| true)
    }

    /// [`Refiner::new`] calling `progress(level_done, levels)` after each
    /// level; if it returns `false` the refiner holds the levels done.
    ///
    /// # Errors
    /// As [`Refiner::new`].
    pub(crate) fn with_progress<C: super::Cage>(
        cage: &C,
        (scheme, levels, opts): (Scheme, u32, &Options),
        progress: &mut dyn FnMut(u32, u32) -> bool,
    ) -> Result<Refiner> {
        let (mesh, polygons) = cage.as_triangles(crate::subdiv::cage::sealed::Token::NEW);
        if polygons && !scheme.is_polygonal() {
            return Err(Error::Usage(format!("{scheme} subdivides triangles: fan the polygons first")));
        }
        let kept = cage.levels_kept(crate::subdiv::cage::sealed::Token::NEW, (scheme, levels, opts), progress)?;
        let mut r = Self::of_levels(mesh.into_owned().ct, kept, scheme, opts);
        r.from_polygons = polygons;
        Ok(r)
    }

    /// A refiner holding `levels` of `scheme` made on `cage`.
    fn of_levels(cage: CornerTable, mut levels: Levels, scheme: Scheme, opts: &Options) -> Refiner {
        let topo = Topology::of(&mut levels, scheme, opts);
        Refiner {
            cage,
            patches: Patches::sized(topo.levels()),
            topo,
            points: levels.points,
            precise: None,
            normals: OnceLock::new(),
            rings: OnceLock::new(),
            edit: None,
            history: History::default(),
            from_polygons: false,
            face_varying: Default::default(),
            stats: levels.stats,
        }
    }

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
            super::tables::plan::LevelTables::Triangles(t) => t.get(l as usize)?.0.clone(),
            super::tables::plan::LevelTables::Polygons(t) => t.get(l as usize)?.triangulated(),
        };
        Some(Mesh { ct, positions })
    }

    /// How many points each level has, the control level first.
    fn level_counts(&self) -> Vec<usize> {
        self.points.iter().map(Vec::len).collect()
    }

    /// The edit tables, built on first use (the stencils recorded then,
    /// and every level evaluated by them once: an edit re-evaluates rows,
    /// and a point then equals its row's sum bit for bit whatever moved).
    fn edit_tables(&mut self) -> &mut EditTables {
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

    /// The finest level's rings, made on first use.
    fn rings(&self) -> Option<&(Vec<u32>, Vec<u32>)> {
        self.rings
            .get_or_init(|| match &self.topo.fine_poly {
                Some(pt) => crate::mesh::normals::ring_lists(pt),
                None => crate::mesh::normals::ring_lists(self.topo.fine()),
            })
            .as_ref()
    }

    /// Every normal of the finest level.
    fn all_normals(&self) -> Vec<Vec3> {
        let pos = self.positions();
        match self.rings() {
            Some((offsets, ids)) => (0..pos.len())
                .into_par_iter()
                .with_min_len(4096)
                .map(|v| ring_normal(pos, v as u32, &ids[offsets[v] as usize..offsets[v + 1] as usize]))
                .collect(),
            None => crate::mesh::normals::vertex_normals(self.topo.fine(), pos),
        }
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

    /// The finest level's unit vertex normals (area-weighted over its
    /// faces; for a polygon scheme, over the polygons' rings of edge
    /// neighbours).
    pub fn normals(&self) -> &[Vec3] {
        self.normals.get_or_init(|| self.all_normals())
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

    /// New control positions, every level evaluated again (into the
    /// buffers already held) and every normal; the f64 points, where kept,
    /// from `control` widened.
    ///
    /// # Panics
    /// If `control` has not one point per control vertex (a caller bug).
    pub fn set_control(&mut self, control: &[Vec3]) {
        assert_eq!(control.len(), self.points[0].len(), "one position per control vertex");
        self.points[0].copy_from_slice(control);
        self.evaluate_all();
        if self.precise.is_some() {
            let wide: Vec<DVec3> = control.iter().map(|p| p.as_dvec3()).collect();
            self.evaluate_all_f64(Some(&wide));
        }
    }

    /// Every level evaluated by its rows from the control points, and
    /// every normal made so far.
    fn evaluate_all(&mut self) {
        let plan = self.topo.plan();
        for l in 0..plan.levels.len() {
            let (done, rest) = self.points.split_at_mut(l + 1);
            plan.apply_level(l, &done[l], &mut rest[0]);
            for (&r, row) in &self.patches.rows[l] {
                rest[0][r as usize] = sum_row(&row.idx, &row.w, &done[l]);
            }
        }
        if let Some(edit) = self.edit.as_mut() {
            edit.changed = None;
        }
        // every normal made so far, into the buffer already held
        let pos = self.points.last().map_or(&[][..], Vec::as_slice);
        let Some(normals) = self.normals.get_mut() else { return };
        match self.rings.get().and_then(Option::as_ref) {
            Some((offsets, ids)) => normals.par_iter_mut().enumerate().with_min_len(4096).for_each(|(v, n)| {
                *n = ring_normal(pos, v as u32, &ids[offsets[v] as usize..offsets[v + 1] as usize]);
            }),
            None => self.update_normals(&[]),
        }
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
    fn touch(&mut self, ids: &[u32], seeds: &[Vec<u32>]) {
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

    fn check_move(&self, ids: &[u32], to: usize) -> Result<()> {
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

    /// A move's step of the history (`after64`: its f64 positions, where
    /// the refiner keeps f64 points).
    fn push_move(&mut self, ids: &[u32], to: &[Vec3], after64: Option<Vec<DVec3>>) {
        let before = ids.iter().map(|&v| self.points[0][v as usize]).collect();
        let precise = self
            .precise
            .as_ref()
            .zip(after64)
            .map(|(levels, after)| Box::new((ids.iter().map(|&v| levels[0][v as usize]).collect(), after)));
        self.history.done.push(Step::Move { ids: ids.to_vec(), before, after: to.to_vec(), precise });
        self.history.undone.clear();
    }

    /// Sets control points (in f64 `to64`, else `to` widened, where f64
    /// points are kept) and re-evaluates their support (no history).
    fn place(&mut self, ids: &[u32], to: &[Vec3], to64: Option<&[DVec3]>) -> usize {
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
    fn evaluate_touched(&mut self) -> usize {
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

    /// The normals of the changed finest points and their neighbours;
    /// returns the points whose position or normal changed (`None`: every
    /// normal was made again, or none is made yet).
    fn update_normals_around(&mut self, changed: &[u32]) -> Option<Vec<u32>> {
        // none made yet: all of them made when first asked for
        self.normals.get()?;
        let Some((offsets, ids)) = self.rings.get().and_then(Option::as_ref) else {
            self.update_normals(&[]);
            return None;
        };
        let last = self.points.len() - 1;
        let t = &mut self.edit.as_mut()?.touched;
        t.begin();
        for &v in changed {
            t.mark(last, v);
            let (a, b) = (offsets[v as usize] as usize, offsets[v as usize + 1] as usize);
            for &w in &ids[a..b] {
                t.mark(last, w);
            }
        }
        let around = std::mem::take(&mut t.lists[last]);
        self.update_normals(&around);
        Some(around)
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

    /// The normals of the finest points `which` (all of them, without
    /// rings: the fan-averaged normals of the whole level).
    fn update_normals(&mut self, which: &[u32]) {
        if self.normals.get().is_none() {
            return;
        }
        let Some((offsets, ids)) = self.rings.get().and_then(Option::as_ref) else {
            let all = self.all_normals();
            self.normals = OnceLock::from(all);
            return;
        };
        let pos = self.points.last().map_or(&[][..], Vec::as_slice);
        let Some(normals) = self.normals.get_mut() else { return };
        let normal = |v: u32| ring_normal(pos, v, &ids[offsets[v as usize] as usize..offsets[v as usize + 1] as usize]);
        if which.len() > 4096 {
            let values: Vec<Vec3> = which.par_iter().map(|&v| normal(v)).collect();
            which.iter().zip(values).for_each(|(&v, n)| normals[v as usize] = n);
        } else {
            which.iter().for_each(|&v| normals[v as usize] = normal(v));
        }
    }

    /// The control mesh's tags now.
    pub fn tags(&self) -> Tags {
        self.cage.sharpness().map(|s| s.to_tags(&self.cage)).unwrap_or_default()
    }

    /// Sets the sharpness of the control edge `a`-`b` (0 smooth, 10 and
    /// above infinitely sharp), records the stencils again and
    /// re-evaluates. One step of the history.
    ///
    /// # Errors
    /// [`Error::Usage`] when `a`-`b` is not an edge of the cage, or for a
    /// sharpness that is not finite and at least 0
    /// ([`crate::mesh::checked_sharpness`]); nothing is changed then.
    pub fn set_edge_sharpness(&mut self, a: u32, b: u32, sharpness: f32) -> Result<()> {
        let s = checked_sharpness(f64::from(sharpness)).map_err(|e| Error::Usage(format!("edge {a}-{b} has {e}")))?;
        if self.cage.corner_opposite(a, b).is_none() && self.cage.corner_opposite(b, a).is_none() {
            return Err(Error::Usage(format!("{a}-{b} is not an edge of the control mesh")));
        }
        let mut tags = self.tags();
        tags.creases.retain(|t| (t.v0.min(t.v1), t.v0.max(t.v1)) != (a.min(b), a.max(b)));
        if s > 0.0 {
            tags.creases.push(CreaseTag { v0: a, v1: b, sharpness: s });
        }
        self.retag(tags)
    }

    /// Sets the sharpness of control vertex `v` (a corner; 0 smooth).
    ///
    /// # Errors
    /// [`Error::Usage`] when `v` is not a control vertex, or for a
    /// sharpness that is not finite and at least 0 (as
    /// [`Refiner::set_edge_sharpness`]); nothing is changed then.
    pub fn set_vertex_sharpness(&mut self, v: u32, sharpness: f32) -> Result<()> {
        let s = checked_sharpness(f64::from(sharpness)).map_err(|e| Error::Usage(format!("vertex {v} has {e}")))?;
        if v as usize >= self.points[0].len() {
            return Err(Error::Usage(format!("vertex {v} is not a control vertex")));
        }
        let mut tags = self.tags();
        tags.corners.retain(|t| t.vertex != v);
        if s > 0.0 {
            tags.corners.push(CornerTag { vertex: v, sharpness: s });
        }
        self.retag(tags)
    }

    /// Gives the cage `tags` (replacing its sharp edges and vertices);
    /// one step of the history, re-recorded where it reaches as
    /// [`Refiner::set_edge_sharpness`].
    ///
    /// # Errors
    /// A tag naming no edge or vertex of the cage.
    pub fn set_tags(&mut self, tags: &Tags) -> Result<()> {
        self.retag(tags.clone())
    }

    fn retag(&mut self, after: Tags) -> Result<()> {
        // a fanned polygon's diagonals are no edges of the surface
        let hidden = |a: u32, b: u32| {
            let c = self.cage.corner_opposite(a, b).or_else(|| self.cage.corner_opposite(b, a));
            c.is_some_and(|c| self.cage.edge_generation(c) == crate::mesh::Generations::HIDDEN)
        };
        if let Some(t) = after.creases.iter().find(|t| hidden(t.v0, t.v1)) {
            return Err(Error::Usage(format!("{}-{} is a diagonal of a polygon, not an edge", t.v0, t.v1)));
        }
        let before = self.tags();
        self.apply_tags(&after)?;
        self.history.done.push(Step::Tags { before, after });
        self.history.undone.clear();
        Ok(())
    }

    /// The cage with `tags`: the rows the change reaches recorded again
    /// ([`retag`]) and evaluated with what follows from them (or, where
    /// the tags decide holes, every level recorded again).
    fn apply_tags(&mut self, tags: &Tags) -> Result<()> {
        let cage = self.cage.clone().with_tags(tags).map_err(Error::Invalid)?;
        match self.retag_locally(tags)? {
            Some(redone) => {
                self.cage = cage;
                self.touch(&[], &redone);
                self.evaluate_touched();
            }
            None => self.rebuild(cage)?,
        }
        self.face_varying = Default::default();
        Ok(())
    }

    /// Every level refined anew on `cage` (the same faces, new tags), into
    /// the buffers already held: the points stay where they are (a view of
    /// them outlives the change), the f64 ones too, and the history.
    ///
    /// # Errors
    /// As [`Refiner::new`]; [`Error::Usage`] if the levels came out of
    /// other sizes (tags change no counts: a bug), nothing changed then.
    fn rebuild(&mut self, cage: CornerTable) -> Result<()> {
        let control = Mesh { ct: cage, positions: self.control().to_vec() };
        let mut fresh = Refiner::new(&control, self.scheme(), self.levels(), self.options())?;
        if fresh.level_counts() != self.level_counts() {
            return Err(Error::Usage("refined anew, the levels have other sizes (a bug)".into()));
        }
        for (old, new) in self.points.iter_mut().zip(&fresh.points) {
            old.copy_from_slice(new);
        }
        fresh.points = std::mem::take(&mut self.points);
        fresh.history = std::mem::take(&mut self.history);
        fresh.from_polygons = self.from_polygons;
        fresh.precise = self.precise.take();
        *self = fresh;
        // evaluated by the rows, as after every edit
        self.edit_tables();
        if self.precise.is_some() {
            self.evaluate_all_f64(None);
        }
        let n = self.positions().len() as u32;
        if let Some(edit) = self.edit.as_mut() {
            edit.evaluated = (0..n).collect();
            edit.changed = None;
        }
        Ok(())
    }

    /// Undoes the last step; whether there was one.
    pub fn undo(&mut self) -> bool {
        let Some(step) = self.history.done.pop() else { return false };
        self.redo_or_undo(&step, true);
        self.history.undone.push(step);
        true
    }

    /// Redoes the last undone step; whether there was one.
    pub fn redo(&mut self) -> bool {
        let Some(step) = self.history.undone.pop() else { return false };
        self.redo_or_undo(&step, false);
        self.history.done.push(step);
        true
    }

    fn redo_or_undo(&mut self, step: &Step, undo: bool) {
        match step {
            Step::Move { ids, before, after, precise } => {
                let to64 = precise.as_deref().map(|(b, a)| if undo { &b[..] } else { &a[..] });
                self.place(ids, if undo { before } else { after }, to64);
            }
            Step::Tags { before, after } => {
                // the tags were valid when the step was made on this cage
                if let Err(e) = self.apply_tags(if undo { before } else { after }) {
                    log::warn!("undo of a sharpness change: {e}");
                }
            }
        }
    }

    /// Steps that can be undone and redone.
    pub fn history_len(&self) -> (usize, usize) {
        (self.history.done.len(), self.history.undone.len())
    }

    /// Per-vertex data of `channels` values a control vertex (row-major:
    /// positions, colours, any user data) refined to the finest level, in
    /// the caller's precision: `f32` data with the f32 weights, `f64` data
    /// with the weights recorded in f64 (positions far from the origin keep
    /// their digits).
    ///
    /// # Errors
    /// [`Error::Usage`] when `data` is not `channels` values per control
    /// vertex.
    pub fn refine<T: Scalar>(&self, data: &[T], channels: usize) -> Result<Vec<T>> {
        T::refine_on(sealed::Token::NEW, self, data, channels)
    }

    /// [`Refiner::refine`] of f32 data.
    ///
    /// # Errors
    /// [`Error::Usage`] when `data` is not `channels` values per control
    /// vertex.
    fn refine_f32(&self, data: &[f32], channels: usize) -> Result<Vec<f32>> {
        self.check_width(data.len(), channels)?;
        let mut d = data.to_vec();
        for (level, patch) in self.topo.plan().levels.iter().zip(&self.patches.rows) {
            let mut out = refine_rows(level, &d, channels);
            patch_rows(&mut out, patch, &d, channels);
            d = out;
        }
        Ok(d)
    }

    /// [`Refiner::refine`] of f64 data, with the weights recorded in f64
    /// (on the tables kept, their tags as they now are).
    ///
    /// # Errors
    /// As [`Refiner::refine`].
    fn refine_f64(&self, data: &[f64], channels: usize) -> Result<Vec<f64>> {
        self.check_width(data.len(), channels)?;
        let mut d = data.to_vec();
        for (level, patch) in self.topo.plan_f64().iter().zip(&self.patches.rows_f64) {
            let mut out = refine_rows(level, &d, channels);
            patch_rows(&mut out, patch, &d, channels);
            d = out;
        }
        Ok(d)
    }

    fn check_width(&self, len: usize, channels: usize) -> Result<()> {
        let n = self.points[0].len();
        if channels == 0 || len != n * channels {
            return Err(Error::Usage(format!(
                "{len} values are not {channels} per control vertex (the cage has {n} vertices)"
            )));
        }
        Ok(())
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
fn sum_row(idx: &[u32], w: &[f32], input: &[Vec3]) -> Vec3 {
    let mut sum = Vec3A::ZERO;
    for (&j, &w) in idx.iter().zip(w) {
        sum += Vec3A::from(input[j as usize]) * w;
    }
    Vec3::from(sum)
}

/// The area-weighted unit normal of `v` from its ring (`Vec3::Z` where the
/// ring has no area).
fn ring_normal(pos: &[Vec3], v: u32, ring: &[u32]) -> Vec3 {
    let p = pos[v as usize];
    let n: Vec3 = ring.windows(2).map(|w| (pos[w[0] as usize] - p).cross(pos[w[1] as usize] - p)).sum();
    n.try_normalize().unwrap_or(Vec3::Z)
}

/// The rows a sharpness edit recorded again, over a level's rows applied
/// to `data` of `channels` values a point (`out`).
fn patch_rows<W: Copy, T>(out: &mut [T], patch: &HashMap<u32, retag::Row<W>>, data: &[T], channels: usize)
where
    T: Copy + Default + std::ops::AddAssign + std::ops::Mul<Output = T> + From<W>,
{
    for (&r, row) in patch {
        let o = &mut out[r as usize * channels..(r as usize + 1) * channels];
        o.fill(T::default());
        for (&j, &w) in row.idx.iter().zip(&row.w) {
            let src = &data[j as usize * channels..(j as usize + 1) * channels];
            o.iter_mut().zip(src).for_each(|(o, &s)| *o += s * T::from(w));
        }
    }
}

/// One level's rows applied to `data` of `channels` values a point.
fn refine_rows<W: crate::subdiv::rules::Weight, T>(level: &LevelPlan<W>, data: &[T], channels: usize) -> Vec<T>
where
    T: Copy + Send + Sync + Default + std::ops::AddAssign + std::ops::Mul<Output = T> + From<W>,
{
    let mut out = vec![T::default(); level.n_out() * channels];
    out.par_chunks_mut(channels).enumerate().with_min_len(1024).for_each(|(i, o)| match level.row(i) {
        Some((idx, w)) => {
            for (&j, &w) in idx.iter().zip(w) {
                let src = &data[j as usize * channels..(j as usize + 1) * channels];
                o.iter_mut().zip(src).for_each(|(o, &s)| *o += s * T::from(w));
            }
        }
        None => o.copy_from_slice(&data[i * channels..(i + 1) * channels]),
    });
    out
}

/// The refinement of data, out of reach of other crates: what [`Scalar`]
/// stands for, taking a [`sealed::Token`] only this crate makes.
pub(crate) mod sealed {
    use super::Refiner;
    use crate::Result;

    /// The argument of [`Refines::refine_on`]: only this crate makes one.
    pub struct Token(());

    impl Token {
        pub(crate) const NEW: Token = Token(());
    }

    /// Data refined by a refiner in this precision.
    pub trait Refines: Copy + Sized {
        /// `data` refined by `refiner` in this precision.
        ///
        /// # Errors
        /// As [`Refiner::refine`].
        fn refine_on(_: Token, refiner: &Refiner, data: &[Self], channels: usize) -> Result<Vec<Self>>;
    }

    impl Refines for f32 {
        fn refine_on(_: Token, refiner: &Refiner, data: &[f32], channels: usize) -> Result<Vec<f32>> {
            refiner.refine_f32(data, channels)
        }
    }

    impl Refines for f64 {
        fn refine_on(_: Token, refiner: &Refiner, data: &[f64], channels: usize) -> Result<Vec<f64>> {
            refiner.refine_f64(data, channels)
        }
    }
}

/// The scalar of the data [`Refiner::refine`] refines: `f32` or `f64`
/// (sealed).
#[allow(private_bounds)]
pub trait Scalar: sealed::Refines {}

impl Scalar for f32 {}
impl Scalar for f64 {}
