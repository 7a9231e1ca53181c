//! One level's stencils as a CSR table of rows (one row per new vertex:
//! source ids and weights), and the points the kernels read and write.
//! The plan ([`super::StencilPlan`]) is a list of these; the packed form
//! ([`super::packed`]) is built from them.

use crate::subdiv::rules::Weight;
use glam::{Vec3, Vec3A};
use rayon::prelude::*;

/// A point the level kernels read and write: [`Vec3`] (12 bytes, what
/// callers hand in and get back) or [`Vec3A`] (16 bytes, one SSE register:
/// the intermediate levels, where a weighted sum is one multiply and one add
/// per entry instead of three each). The lanes compute the same IEEE
/// products and sums either way, so the results are bit-identical.
pub trait Point: Copy + Send + Sync {
    /// The point in a register.
    fn load(self) -> Vec3A;
    /// Back from a register.
    fn store(v: Vec3A) -> Self;
}

impl Point for Vec3 {
    #[inline(always)]
    fn load(self) -> Vec3A {
        Vec3A::from(self)
    }
    #[inline(always)]
    fn store(v: Vec3A) -> Self {
        Vec3::from(v)
    }
}

impl Point for Vec3A {
    #[inline(always)]
    fn load(self) -> Vec3A {
        self
    }
    #[inline(always)]
    fn store(v: Vec3A) -> Self {
        v
    }
}

/// One level's stencils, their weights in f32 (the plans that animate) or
/// f64 (exact stencils).
#[derive(Clone, Debug, Default)]
pub struct LevelPlan<W = f32> {
    /// Vertices of the coarser level.
    pub n_in: usize,
    /// Old vertices are copied unchanged (interpolating schemes): their rows
    /// are omitted and `offsets` covers only the edge points.
    pub copy_vertices: bool,
    /// Row `i` spans `indices[offsets[i]..offsets[i+1]]`.
    pub offsets: Vec<u32>,
    /// Source vertex ids.
    pub indices: Vec<u32>,
    /// Weights.
    pub weights: Vec<W>,
}

impl<W: Weight> LevelPlan<W> {
    /// This level reading its input through `old`: input `j` of the rows
    /// becomes input `old[j]`. The copied old vertices of an interpolating
    /// level become rows of one entry (weight 1), since the copy is now a
    /// gather. For a level recorded on a relabelled table and fed the
    /// table's vertices in their old order.
    pub(crate) fn reading_through(self, old: &[u32]) -> LevelPlan<W> {
        let map = |j: &u32| old[*j as usize];
        if !self.copy_vertices {
            return LevelPlan { indices: self.indices.iter().map(map).collect(), ..self };
        }
        let n = self.n_in as u32;
        let offsets = (0..n).chain(self.offsets.iter().map(|&x| x + n)).collect();
        let indices = old[..self.n_in].iter().copied().chain(self.indices.iter().map(map)).collect();
        let weights = std::iter::repeat_n(W::of(1.0), self.n_in).chain(self.weights.iter().copied()).collect();
        LevelPlan { n_in: self.n_in, copy_vertices: false, offsets, indices, weights }
    }

    /// Vertices of the finer level.
    pub fn n_out(&self) -> usize {
        self.offsets.len() - 1 + if self.copy_vertices { self.n_in } else { 0 }
    }

    /// The row of new vertex `i`: its sources and weights (a copied old
    /// vertex of an interpolating level: itself with weight 1, returned as
    /// `None`).
    pub(crate) fn row(&self, i: usize) -> Option<(&[u32], &[W])> {
        let r = if self.copy_vertices { i.checked_sub(self.n_in)? } else { i };
        let (a, b) = (*self.offsets.get(r)? as usize, *self.offsets.get(r + 1)? as usize);
        Some((&self.indices[a..b], &self.weights[a..b]))
    }
}

impl LevelPlan {
    /// Applies this level: `out` gets `n_out()` positions.
    pub fn apply<I: Point, O: Point>(&self, input: &[I], out: &mut [O]) {
        let rows = if self.copy_vertices {
            copy_points(&input[..self.n_in], &mut out[..self.n_in]);
            &mut out[self.n_in..]
        } else {
            out
        };
        rows.par_iter_mut().enumerate().with_min_len(4096).for_each(|(i, q)| {
            let (a, b) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
            let mut sum = Vec3A::ZERO;
            for (&j, &w) in self.indices[a..b].iter().zip(&self.weights[a..b]) {
                sum += input[j as usize].load() * w;
            }
            *q = O::store(sum);
        });
    }
}

/// Copies points from one layout to the other (the old vertices of an
/// interpolating level).
pub(crate) fn copy_points<I: Point, O: Point>(input: &[I], out: &mut [O]) {
    out.par_iter_mut().zip(input).with_min_len(1 << 14).for_each(|(o, &i)| *o = O::store(i.load()));
}
