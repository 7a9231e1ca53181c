//! The full update of a [`Refiner`]: every row of every level evaluated
//! again from the control points ([`Refiner::set_control`]), then every
//! normal made so far.

use super::Refiner;
use super::edit::sum_row;
use glam::{DVec3, Vec3};

impl Refiner {
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
    pub(super) fn evaluate_all(&mut self) {
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
        self.remake_normals();
    }
}
