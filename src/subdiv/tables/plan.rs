//! Stencil plans for fixed topology (docs/schemes.md §7.8; OpenSubdiv's
//! `far::StencilTable`, libigl's subdivision matrix `S`).
//!
//! When only the control positions change (animation), the topology, the O
//! table and every weight are the same each frame. A [`StencilPlan`] records,
//! once, each level's stencils as a flat CSR table (`offsets`, `indices`,
//! `weights`; one row per new vertex) from the very same rule code that the
//! one-shot subdivision runs, then [`StencilPlan::apply`] only gathers
//! weighted sums level by level. Applying level by level keeps the tables
//! small: a composed control-to-final matrix would have L-ring support.

use super::packed::PackedLevel;
use super::rows::{LevelPlan, Point};
use crate::Result;
use crate::mesh::order::Relabel;
use crate::mesh::split;
use crate::mesh::{CornerTable, Creasing};
use crate::subdiv::refine::build::{Table, tables};
use crate::subdiv::rules::crease::{OnLevel, Unsplit, edge_stencil, vertex_stencil};
use crate::subdiv::rules::features::Features;
use crate::subdiv::rules::{Level, Record, Rules, Weight};
use crate::subdiv::{Options, RulesFn, Scheme, with_rules};
use glam::{Vec3, Vec3A};
use rayon::prelude::*;

/// A recorded multi-level subdivision of one topology.
#[derive(Clone, Debug)]
pub struct StencilPlan {
    /// The scheme recorded.
    pub scheme: Scheme,
    /// Per-level stencils, coarse to fine.
    pub levels: Vec<LevelPlan>,
    /// Topology of the finest level.
    pub ct: CornerTable,
    /// `levels` packed for [`StencilPlan::apply`] (built with them; `None`
    /// where a level has too many distinct weight vectors to pack).
    packed: Vec<Option<PackedLevel>>,
    /// The renumbering of the control mesh the levels were recorded in
    /// ([`StencilPlan::build_local`]); `None`: the control mesh's own order.
    order: Option<Relabel>,
    /// A polygon scheme's finest level as polygons (`ct` is their
    /// triangles).
    poly: Option<Box<crate::mesh::poly::PolyTable>>,
}

/// Recorded levels, the finest topology, and its polygons for a polygon
/// scheme.
/// Recorded levels (weights `W`), the finest triangles and, for a polygon
/// scheme, the finest polygons.
pub(crate) type Recorded<W = f32> = (Vec<LevelPlan<W>>, CornerTable, Option<crate::mesh::poly::PolyTable>);

/// The table every level of a refinement was made from (its boundary
/// corners applied, its sharpness that level's), with the owner corners of
/// its edges for the triangle schemes: what a level's rows are recorded on.
#[derive(Clone, Debug)]
pub(crate) enum LevelTables {
    /// The triangle schemes' levels.
    Triangles(Vec<(CornerTable, Vec<u32>)>),
    /// The polygon schemes'.
    Polygons(Vec<crate::mesh::poly::PolyTable>),
}

/// Reusable buffers for [`StencilPlan::apply`]: the intermediate levels,
/// 16 bytes a point (see [`Point`]).
#[derive(Default)]
pub struct PlanScratch {
    a: Vec<Vec3A>,
    b: Vec<Vec3A>,
}

impl PlanScratch {
    /// Buffers sized for `plan`'s intermediate levels up front, so that no
    /// evaluation allocates.
    pub fn for_plan(plan: &StencilPlan) -> PlanScratch {
        // every level but the last passes through a and b
        let (_, rest) = plan.levels.split_last().unwrap_or((&LevelPlan::default(), &[]));
        let n = rest.iter().map(LevelPlan::n_out).max().unwrap_or(0);
        PlanScratch { a: vec![Vec3A::ZERO; n], b: vec![Vec3A::ZERO; n] }
    }
}

struct RecordLevel<'a, W> {
    /// The level, copied only where it is cut open along its creases.
    ct: std::borrow::Cow<'a, CornerTable>,
    owners: &'a [u32],
    creasing: Creasing,
    weight: std::marker::PhantomData<W>,
    /// Record only the rows of these new vertices, in this order (none of
    /// them an old vertex an interpolating scheme copies): the stencils of
    /// a few vertices without the whole level.
    only: Option<&'a [u32]>,
}

/// The CSR table of `rows` rows, row `i` recorded by `f` (in parallel, in
/// pieces, concatenated in order).
pub(super) fn record_rows<W: Weight>(
    rows: usize,
    f: impl Fn(usize, &mut Record<W>) + Sync,
) -> (Vec<u32>, Vec<u32>, Vec<W>) {
    const ROWS: usize = 4096;
    let parts: Vec<(Vec<u32>, Record<W>)> = (0..rows.div_ceil(ROWS))
        .into_par_iter()
        .map(|k| {
            let mut rec = Record::default();
            let mut ends = Vec::with_capacity(ROWS);
            for i in k * ROWS..((k + 1) * ROWS).min(rows) {
                f(i, &mut rec);
                ends.push(rec.idx.len() as u32);
            }
            (ends, rec)
        })
        .collect();
    let total: usize = parts.iter().map(|(_, r)| r.idx.len()).sum();
    let mut offsets = Vec::with_capacity(rows + 1);
    offsets.push(0u32);
    let mut indices = Vec::with_capacity(total);
    let mut weights = Vec::with_capacity(total);
    for (ends, rec) in parts {
        let base = indices.len() as u32;
        offsets.extend(ends.iter().map(|e| e + base));
        indices.extend_from_slice(&rec.idx);
        weights.extend_from_slice(&rec.w);
    }
    (offsets, indices, weights)
}

impl<W: Weight> RulesFn<LevelPlan<W>> for RecordLevel<'_, W> {
    fn call<R: Rules>(self, r: &R) -> LevelPlan<W> {
        let mut table = self.ct;
        let nv = table.num_vertices();
        let ne = self.owners.len();
        let mut f = Features::of(&*table, self.creasing);
        // schemes whose stencils reach across edges see a creased level cut
        // open along its creases; the cut's extra vertices map back to theirs
        if let Some(f) = f.as_mut().filter(|_| R::CUT_AT_CREASES) {
            let corners = f.cut_corners(&table);
            f.set_cut(table.to_mut().cut_in_place(&corners));
        }
        let lv = Level::new(&table).with_features(f.as_ref());
        let copies: &[u32] = f.as_ref().map_or(&[], |f| f.copies());
        let (on, owners) = (OnLevel { r, lv: &lv }, self.owners);
        let row = |i: usize, rec: &mut Record<W>| {
            let mut s = Unsplit { sink: rec, nv: nv as u32, copies };
            if R::MOVES_VERTICES && i < nv {
                vertex_stencil(&on, i as u32, &mut s);
            } else {
                let e = if R::MOVES_VERTICES { i - nv } else { i };
                edge_stencil(&on, owners[e], &mut s);
            }
        };
        let (offsets, indices, weights) = match self.only {
            // row i is new vertex i (moving schemes) or edge point i
            Some(ids) => {
                let first = if R::MOVES_VERTICES { 0 } else { nv };
                record_rows(ids.len(), |k, rec| row(ids[k] as usize - first, rec))
            }
            None => record_rows(if R::MOVES_VERTICES { nv + ne } else { ne }, row),
        };
        LevelPlan { n_in: nv, copy_vertices: !R::MOVES_VERTICES, offsets, indices, weights }
    }
}

/// One level of triangle `scheme` recorded on `ct` as it is (its boundary
/// corners already applied, [`with_boundary_corners`]), and the split table
/// it makes: the local subdivision of exact evaluation runs the very rules
/// the one-shot subdivision runs.
pub(crate) fn record_one_level(ct: &CornerTable, scheme: Scheme, opts: &Options) -> (LevelPlan, CornerTable) {
    let (next, edges) = split::split_with(ct, opts.creasing);
    (record_level(ct, &edges.owners, scheme, opts), next)
}

/// The rows of one level of triangle `scheme` on `ct` (its boundary
/// corners already applied), `owners` the owner corners of its edges in
/// the split's order, weights of type `W`.
/// Every level's rows with weights `W`, recorded on the level tables (as
/// the builder made them, their tags as they now are): the one recording
/// of a plan, for [`StencilPlan::build`] and the refiner alike.
pub(crate) fn record_levels<W: Weight + std::ops::AddAssign>(
    tables: &LevelTables,
    scheme: Scheme,
    opts: &Options,
) -> Vec<LevelPlan<W>> {
    match tables {
        LevelTables::Triangles(t) => t.iter().map(|(ct, owners)| record_level::<W>(ct, owners, scheme, opts)).collect(),
        LevelTables::Polygons(t) => {
            t.iter().map(|pt| super::poly_plan::record_poly_level::<W>(pt, scheme, opts, None)).collect()
        }
    }
}

/// One level of a [`LevelTables`], borrowed: its table (and its edges'
/// owner corners, for the triangle schemes).
#[derive(Clone, Copy)]
pub(crate) enum LevelTable<'a> {
    Triangles(&'a CornerTable, &'a [u32]),
    Polygons(&'a crate::mesh::poly::PolyTable),
}

impl LevelTables {
    /// Levels held.
    pub(crate) fn len(&self) -> usize {
        match self {
            LevelTables::Triangles(t) => t.len(),
            LevelTables::Polygons(t) => t.len(),
        }
    }

    /// Level `i`.
    pub(crate) fn level(&self, i: usize) -> Option<LevelTable<'_>> {
        match self {
            LevelTables::Triangles(t) => t.get(i).map(|(ct, o)| LevelTable::Triangles(ct, o)),
            LevelTables::Polygons(t) => t.get(i).map(LevelTable::Polygons),
        }
    }
}

pub(crate) fn record_level<W: Weight>(
    ct: &CornerTable,
    owners: &[u32],
    scheme: Scheme,
    opts: &Options,
) -> LevelPlan<W> {
    let weight = std::marker::PhantomData;
    let ct = std::borrow::Cow::Borrowed(ct);
    let record = RecordLevel { ct, owners, creasing: opts.creasing, weight, only: None };
    with_rules(scheme, opts, record)
}

/// The rows of the new vertices `ids` alone of one level of triangle
/// `scheme` on `ct` (as [`record_level`]), row `k` that of `ids[k]`; an
/// interpolating scheme's copied old vertices must not be among them.
pub(crate) fn record_rows_of<W: Weight>(
    ct: &CornerTable,
    owners: &[u32],
    (scheme, opts): (Scheme, &Options),
    ids: &[u32],
) -> LevelPlan<W> {
    let weight = std::marker::PhantomData;
    let ct = std::borrow::Cow::Borrowed(ct);
    let record = RecordLevel { ct, owners, creasing: opts.creasing, weight, only: Some(ids) };
    with_rules(scheme, opts, record)
}

/// A finest level's new sharpness `s`, on its polygons (when a polygon
/// scheme's) and on their triangles alike, edge by edge (each where held).
pub(crate) fn with_fine_sharpness(
    ct: Option<&mut CornerTable>,
    poly: Option<&mut crate::mesh::poly::PolyTable>,
    s: Option<crate::mesh::Sharpness>,
) {
    match (ct, poly) {
        (ct, Some(poly)) => {
            let tags = s.as_ref().map(|s| s.to_tags(&*poly)).unwrap_or_default();
            *poly = std::mem::take(poly).with_sharpness(s);
            if let Some(ct) = ct {
                let on_triangles = crate::mesh::Sharpness::from_tags(&*ct, &tags).ok().flatten();
                *ct = std::mem::take(ct).with_sharpness(on_triangles);
            }
        }
        (Some(ct), None) => *ct = std::mem::take(ct).with_sharpness(s),
        (None, None) => {}
    }
}

impl StencilPlan {
    /// Records `levels` levels of `scheme` on topology `ct`.
    ///
    /// # Errors
    /// [`crate::Error::TooLarge`] when a level would not fit in memory.
    pub fn build(ct: &CornerTable, scheme: Scheme, levels: u32, opts: &Options) -> Result<Self> {
        let (plans, fine, poly) = Self::record(ct, scheme, levels, opts)?;
        Ok(Self::packed(scheme, plans, (fine, poly), None))
    }

    /// The levels recorded on `ct` with weights `W`, and the finest
    /// topology.
    pub(crate) fn record<W: Weight + std::ops::AddAssign>(
        ct: &CornerTable,
        scheme: Scheme,
        levels: u32,
        opts: &Options,
    ) -> Result<Recorded<W>> {
        let how = (scheme, levels, opts);
        if scheme.is_polygonal() {
            // the polygons the table stands for (its hidden diagonals joined)
            let (kept, poly) = tables(&crate::mesh::poly::PolyTable::from_corner_table(ct), how)?;
            let plans = record_levels(&Table::into_tables(kept), scheme, opts);
            return Ok((plans, poly.triangulated(), Some(poly)));
        }
        let (kept, fine) = tables(ct, how)?;
        Ok((record_levels(&Table::into_tables(kept), scheme, opts), fine, None))
    }

    /// A plan of levels recorded elsewhere (the refiner's), packed.
    pub(crate) fn from_recorded(scheme: Scheme, (levels, ct, poly): Recorded) -> Self {
        Self::packed(scheme, levels, (ct, poly), None)
    }

    /// The finest level's sharpness after an edit of the tags (on its
    /// polygons and their triangles alike, edge by edge).
    pub(crate) fn set_fine_sharpness(&mut self, s: Option<crate::mesh::Sharpness>) {
        with_fine_sharpness(Some(&mut self.ct), self.poly.as_deref_mut(), s);
    }

    /// Level `i`'s rows replaced (a sharpness edit's): applied unpacked
    /// from now on (bit-identical, a little slower).
    pub(crate) fn level_mut(&mut self, i: usize) -> &mut LevelPlan {
        self.packed[i] = None;
        &mut self.levels[i]
    }

    /// A plan of recorded levels, packed for evaluation.
    fn packed(
        scheme: Scheme,
        levels: Vec<LevelPlan>,
        (ct, poly): (CornerTable, Option<crate::mesh::poly::PolyTable>),
        order: Option<Relabel>,
    ) -> Self {
        let packed = levels.par_iter().map(PackedLevel::pack).collect();
        StencilPlan { scheme, levels, ct, packed, order, poly: poly.map(Box::new) }
    }

    /// [`StencilPlan::build`] for speed of evaluation: the levels are
    /// recorded on the control table renumbered in a locality order
    /// (`Relabel::breadth_first`), so that each row's inputs lie near
    /// each other at every level; the first level reads the control
    /// positions in their own order, so [`StencilPlan::apply`] takes the
    /// same input. The finest topology [`StencilPlan::ct`] and the output
    /// are then those of `ct.relabelled(order)` ([`StencilPlan::order`]):
    /// the same surface as [`StencilPlan::build`]'s with other face and
    /// vertex ids. The bunny at Loop level 2: fastest frame 4.4-4.8 -> 3.6-3.9
    /// ms (docs/performance.md).
    ///
    /// # Errors
    /// As [`StencilPlan::build`].
    pub fn build_local(ct: &CornerTable, scheme: Scheme, levels: u32, opts: &Options) -> Result<Self> {
        if levels == 0 {
            return Self::build(ct, scheme, levels, opts);
        }
        let order = Relabel::breadth_first(ct);
        let (mut plans, fine, poly) = Self::record(&ct.relabelled(&order), scheme, levels, opts)?;
        plans[0] = std::mem::take(&mut plans[0]).reading_through(&order.old_vertices());
        Ok(Self::packed(scheme, plans, (fine, poly), Some(order)))
    }

    /// The renumbering of the control table whose subdivision this plan's
    /// levels and [`StencilPlan::ct`] are ([`StencilPlan::build_local`]);
    /// `None` when they are the control table's own.
    pub fn order(&self) -> Option<&Relabel> {
        self.order.as_ref()
    }

    /// The finest level's polygons, for a polygon scheme's plan (its
    /// [`StencilPlan::ct`] is their triangles): what the normals' rings of
    /// edge neighbours are built from.
    pub(crate) fn polygons(&self) -> Option<&crate::mesh::poly::PolyTable> {
        self.poly.as_deref()
    }

    /// Number of control vertices the plan expects.
    pub(crate) fn n_control(&self) -> usize {
        self.levels.first().map_or(self.ct.num_vertices(), |l| l.n_in)
    }

    /// Evaluates the finest positions for new control positions into `out`
    /// (resized to the finest vertex count). Allocates only on first use.
    ///
    /// # Panics
    /// If `control.len() != self.n_control()` (a caller bug, not input data).
    pub fn apply(&self, control: &[Vec3], scratch: &mut PlanScratch, out: &mut Vec<Vec3>) {
        assert_eq!(control.len(), self.n_control(), "control vertex count does not match the plan");
        out.resize(self.ct.num_vertices(), Vec3::ZERO);
        let Some((_, rest)) = self.levels.split_last() else {
            out.copy_from_slice(control);
            return;
        };
        let PlanScratch { a, b } = scratch;
        for (i, lvl) in rest.iter().enumerate() {
            if i == 0 {
                a.resize(lvl.n_out(), Vec3A::ZERO);
                self.apply_level(i, control, a);
            } else {
                b.resize(lvl.n_out(), Vec3A::ZERO);
                self.apply_level(i, a, b);
                std::mem::swap(a, b);
            }
        }
        if rest.is_empty() {
            self.apply_level(0, control, out);
        } else {
            self.apply_level(rest.len(), a, out);
        }
    }

    /// Level `i`, packed where it could be packed (bit-identical either way).
    pub(crate) fn apply_level<I: Point, O: Point>(&self, i: usize, input: &[I], out: &mut [O]) {
        match &self.packed[i] {
            Some(p) => p.apply(input, out),
            None => self.levels[i].apply(input, out),
        }
    }
}
