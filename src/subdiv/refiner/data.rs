//! Data refined by a [`Refiner`] through its recorded rows: any per-vertex
//! data of any width, in f32 (the f32 weights) or f64 (the weights
//! recorded in f64), with the rows sharpness edits recorded again over
//! each level's; and the sealed [`Scalar`] trait naming the two precisions.

use super::Refiner;
use super::retag;
use crate::subdiv::tables::LevelPlan;
use crate::{Error, Result};
use rayon::prelude::*;
use std::collections::HashMap;

impl Refiner {
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
    pub(super) fn refine_f32(&self, data: &[f32], channels: usize) -> Result<Vec<f32>> {
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
