//! Double precision kept beside the f32 points: a refiner asked for f64
//! points ([`Refiner::set_control_f64`]) holds every level's points in f64
//! too, and every edit evaluates the rows it reaches in both precisions:
//! the same touched rows, their f64 weights recorded by the same rule code
//! as [`Refiner::refine`]'s (and again, where a sharpness edit reaches,
//! beside the f32 rows). The f64 points therefore equal refining the f64
//! control points whole ([`Refiner::refine`]) bit for bit, after any edits.

use super::Refiner;
use super::retag::Row;
use crate::subdiv::tables::LevelPlan;
use crate::{Error, Result};
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use std::collections::HashMap;

impl Refiner {
    /// Keeps every level's points in f64 from now on, from the control
    /// points `control`: every level evaluated with the rows' f64 weights
    /// (recorded now if not yet), and from then on every edit evaluates
    /// the rows it reaches in f64 as well ([`Refiner::positions_f64`]).
    /// The f32 control points become `control` rounded. Calling it again
    /// sets new f64 control points (into the buffers held).
    ///
    /// # Errors
    /// [`Error::Usage`] when `control` has not one point per control
    /// vertex, or a coordinate that is not finite in f32 (nothing changed).
    pub fn set_control_f64(&mut self, control: &[DVec3]) -> Result<()> {
        let n = self.points[0].len();
        if control.len() != n {
            return Err(Error::Usage(format!("{} f64 control points for {n} control vertices", control.len())));
        }
        check_points(control)?;
        let rounded: Vec<Vec3> = control.iter().map(|p| p.as_vec3()).collect();
        self.edit_tables();
        if rounded != self.points[0] {
            self.points[0].copy_from_slice(&rounded);
            self.evaluate_all();
        }
        self.evaluate_all_f64(Some(control));
        Ok(())
    }

    /// The finest level's points in f64, where kept
    /// ([`Refiner::set_control_f64`]); in one buffer for the refiner's life,
    /// as [`Refiner::positions`].
    pub fn positions_f64(&self) -> Option<&[DVec3]> {
        self.precise.as_ref().and_then(|l| l.last()).map(Vec::as_slice)
    }

    /// The f64 control points, where kept.
    pub fn control_f64(&self) -> Option<&[DVec3]> {
        self.precise.as_ref().and_then(|l| l.first()).map(Vec::as_slice)
    }

    /// [`Refiner::move_vertices`] to f64 positions: the f64 points (kept
    /// from now on, if not yet, from the f32 control points widened) take
    /// `to` as given, the f32 ones `to` rounded. One step of the history.
    ///
    /// # Errors
    /// As [`Refiner::move_vertices`]; a coordinate not finite in f32.
    pub fn move_vertices_f64(&mut self, ids: &[u32], to: &[DVec3]) -> Result<usize> {
        self.check_move(ids, to.len())?;
        check_points(to)?;
        if self.precise.is_none() {
            let wide: Vec<DVec3> = self.points[0].iter().map(|p| p.as_dvec3()).collect();
            self.set_control_f64(&wide)?;
        }
        let rounded: Vec<Vec3> = to.iter().map(|p| p.as_vec3()).collect();
        self.push_move(ids, &rounded, Some(to.to_vec()));
        Ok(self.place(ids, &rounded, Some(to)))
    }

    /// Every level in f64 from the f64 control points (`control`, else
    /// those held), into the buffers held (made now on first use).
    pub(super) fn evaluate_all_f64(&mut self, control: Option<&[DVec3]>) {
        let mut levels = self
            .precise
            .take()
            .unwrap_or_else(|| self.points.iter().map(|p| crate::mem::zeroed::<DVec3>(p.len())).collect());
        if let Some(c) = control {
            levels[0].copy_from_slice(c);
        }
        for (l, (level, patch)) in self.topo.plan_f64().iter().zip(&self.patches.rows_f64).enumerate() {
            let (done, rest) = levels.split_at_mut(l + 1);
            let input = &done[l];
            rest[0].par_iter_mut().enumerate().with_min_len(1024).for_each(|(r, o)| {
                *o = row_value(level, patch, r as u32, input);
            });
        }
        self.precise = Some(levels);
    }
}

/// Refuses points that are not finite in f32 (the refiner's own points
/// are their rounding).
fn check_points(points: &[DVec3]) -> Result<()> {
    let bad = |p: &DVec3| !p.is_finite() || p.abs().max_element() > f64::from(f32::MAX);
    match points.iter().position(bad) {
        Some(i) => Err(Error::Usage(format!("point {i} has a coordinate that is not finite in single precision"))),
        None => Ok(()),
    }
}

/// Row `r` of a level in f64: a sharpness edit's (in `patch`), else the
/// plan's, else (an interpolating level's old vertex) the copy; summed as
/// [`Refiner::refine`] sums, so bit-identical to it.
fn row_value(level: &LevelPlan<f64>, patch: &HashMap<u32, Row<f64>>, r: u32, input: &[DVec3]) -> DVec3 {
    let (idx, w) = match patch.get(&r) {
        Some(row) => (&row.idx[..], &row.w[..]),
        None => match level.row(r as usize) {
            Some(row) => row,
            None => return input[r as usize],
        },
    };
    let mut sum = DVec3::ZERO;
    for (&j, &w) in idx.iter().zip(w) {
        sum += input[j as usize] * w;
    }
    sum
}

/// Every level's f64 rows, and the rows sharpness edits recorded over them.
pub(super) type Rows64<'a> = (&'a [LevelPlan<f64>], &'a [HashMap<u32, Row<f64>>]);

/// The rows `touched[l + 1]` of every level `l + 1` evaluated in f64 from
/// level `l` (an edit's rows, as the f32 ones).
pub(super) fn evaluate_rows((plan, patches): Rows64<'_>, touched: &[Vec<u32>], levels: &mut [Vec<DVec3>]) {
    for (l, (level, patch)) in plan.iter().zip(patches).enumerate() {
        let (done, rest) = levels.split_at_mut(l + 1);
        let (input, out) = (&done[l], &mut rest[0]);
        let rows = &touched[l + 1];
        if rows.len() > 4096 {
            let values: Vec<DVec3> = rows.par_iter().map(|&r| row_value(level, patch, r, input)).collect();
            rows.iter().zip(values).for_each(|(&r, p)| out[r as usize] = p);
        } else {
            rows.iter().for_each(|&r| out[r as usize] = row_value(level, patch, r, input));
        }
    }
}
