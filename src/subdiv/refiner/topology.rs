//! The refined topology a [`super::Refiner`] keeps: every level's table as
//! the one-shot refinement made it, and the stencils recorded from those
//! tables on first need (a refiner that only serves the levels it made
//! never records them).

use crate::CornerTable;
use crate::mesh::Sharpness;
use crate::mesh::poly::PolyTable;
use crate::subdiv::tables::plan::{LevelTables, record_levels, with_fine_sharpness};
use crate::subdiv::tables::{LevelPlan, StencilPlan};
use crate::subdiv::{Levels, Options, Scheme};
use std::sync::OnceLock;

/// Every level's table and the finest, and the stencils made from them.
pub(super) struct Topology {
    pub(super) scheme: Scheme,
    pub(super) opts: Options,
    /// The table each level was made from (sharpness edits re-record on
    /// them).
    pub(super) tables: LevelTables,
    /// The finest triangles (a polygon scheme's fanned from its polygons on
    /// first use).
    fine: OnceLock<CornerTable>,
    /// A polygon scheme's finest polygons.
    pub(super) fine_poly: Option<PolyTable>,
    /// The levels' rows in f32, recorded on first use.
    plan: OnceLock<StencilPlan>,
    /// The levels' rows with f64 weights, recorded on first use.
    plan_f64: OnceLock<Vec<LevelPlan<f64>>>,
}

impl Topology {
    /// The topology of `levels` (its points taken by the caller).
    pub(super) fn of(levels: &mut Levels, scheme: Scheme, opts: &Options) -> Topology {
        let tables = std::mem::replace(&mut levels.tables, LevelTables::Triangles(Vec::new()));
        Topology {
            scheme,
            opts: *opts,
            tables,
            fine: levels.fine.take().map_or_else(OnceLock::new, OnceLock::from),
            fine_poly: levels.fine_poly.take(),
            plan: OnceLock::new(),
            plan_f64: OnceLock::new(),
        }
    }

    /// Levels refined.
    pub(super) fn levels(&self) -> usize {
        self.tables.len()
    }

    /// The finest triangles.
    pub(super) fn fine(&self) -> &CornerTable {
        self.fine.get_or_init(|| self.fine_poly.as_ref().map(PolyTable::triangulated).unwrap_or_default())
    }

    /// The f32 stencils, recorded on first use.
    pub(super) fn plan(&self) -> &StencilPlan {
        self.plan.get_or_init(|| {
            let levels = self.record::<f32>();
            StencilPlan::from_recorded(self.scheme, (levels, self.fine().clone(), self.fine_poly.clone()))
        })
    }

    /// [`Topology::plan`], to write rows into.
    pub(super) fn plan_mut(&mut self) -> &mut StencilPlan {
        self.plan();
        self.plan.get_mut().expect("recorded just above")
    }

    /// The stencils with f64 weights, recorded on first use.
    pub(super) fn plan_f64(&self) -> &[LevelPlan<f64>] {
        self.plan_f64.get_or_init(|| self.record::<f64>())
    }

    /// Every level's rows with weights `W`, recorded on the tables kept
    /// (their tags as they now are): the topology is not refined again.
    fn record<W: crate::subdiv::rules::Weight + std::ops::AddAssign>(&self) -> Vec<LevelPlan<W>> {
        record_levels(&self.tables, self.scheme, &self.opts)
    }

    /// Whether the f64 rows are recorded (a sharpness edit then records
    /// the rows it reaches in f64 too, over them).
    pub(super) fn has_plan_f64(&self) -> bool {
        self.plan_f64.get().is_some()
    }

    /// The finest level's sharpness after an edit of the tags, wherever
    /// the finest level is held (the rows the edit reaches are recorded
    /// again over both plans' by the caller).
    pub(super) fn set_fine_sharpness(&mut self, s: Option<Sharpness>) {
        with_fine_sharpness(self.fine.get_mut(), self.fine_poly.as_mut(), s.clone());
        if let Some(plan) = self.plan.get_mut() {
            plan.set_fine_sharpness(s);
        }
    }
}
