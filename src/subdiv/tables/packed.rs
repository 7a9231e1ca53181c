//! A level's stencils packed for per-frame evaluation.
//!
//! The CSR form of [`super::rows::LevelPlan`] stores, per row, an offset,
//! and per entry an index and a weight: at Loop level 2 of the bunny that is
//! 23 MB read every frame for 6.7 MB of output. But the weights repeat: every
//! regular Loop edge point is `3/8, 3/8, 1/8, 1/8`, every vertex of valence
//! `k` has the same `(1 - k beta, beta, ..)`, and so on for every scheme. A
//! [`PackedLevel`] therefore stores each distinct weight vector once (a
//! *class*), one `u16` class id per row, and the indices; row offsets are
//! implied by the class lengths, with one start offset per chunk of
//! [`CHUNK`] rows so chunks evaluate in parallel. That halves the bytes read
//! per frame. The sums are taken in the same order with the same weights as
//! the CSR rows, so the results are bit-identical to them.

use super::rows::{LevelPlan, Point, copy_points};
use glam::Vec3A;
use rayon::prelude::*;
use std::collections::HashMap;

/// Rows per parallel chunk (one start offset each).
pub(crate) const CHUNK: usize = 2048;

/// Most distinct weight vectors a packed level holds (class ids are `u16`).
const MAX_CLASSES: usize = u16::MAX as usize;

/// One level's stencils as weight classes plus indices (see the module docs).
#[derive(Clone, Debug, Default)]
pub(crate) struct PackedLevel {
    n_in: usize,
    copy_vertices: bool,
    /// Class of every row.
    class: Vec<u16>,
    /// Class `c`'s weights are `class_weights[class_start[c]..class_start[c + 1]]`.
    class_start: Vec<u32>,
    class_weights: Vec<f32>,
    /// Source vertex ids, row after row.
    indices: Vec<u32>,
    /// Offset into `indices` of row `k * CHUNK`.
    chunk_start: Vec<u32>,
}

impl PackedLevel {
    /// Packs `lv`, or `None` when it has more distinct weight vectors than
    /// class ids, or is malformed (an index not below `n_in`, offsets out of
    /// order): then the CSR rows are evaluated instead.
    pub(crate) fn pack(lv: &LevelPlan) -> Option<PackedLevel> {
        let rows = lv.offsets.len().saturating_sub(1);
        let ordered = lv.offsets.first() == Some(&0)
            && lv.offsets.windows(2).all(|w| w[0] <= w[1])
            && lv.offsets.last().is_some_and(|&e| e as usize == lv.indices.len())
            && lv.weights.len() == lv.indices.len();
        if !ordered || lv.indices.par_iter().any(|&j| j as usize >= lv.n_in) {
            return None;
        }
        let mut ids: HashMap<&[u32], u16> = HashMap::new();
        // f32 weights keyed by their bits: classes are exact, never rounded
        let bits: &[u32] = bytemuck::cast_slice(&lv.weights);
        let (mut class, mut class_start, mut class_weights) = (Vec::with_capacity(rows), vec![0u32], Vec::new());
        for r in 0..rows {
            let (a, b) = (lv.offsets[r] as usize, lv.offsets[r + 1] as usize);
            let key = &bits[a..b];
            let next = ids.len();
            let id = *ids.entry(key).or_insert_with(|| {
                class_weights.extend_from_slice(&lv.weights[a..b]);
                class_start.push(class_weights.len() as u32);
                next.min(MAX_CLASSES) as u16
            });
            if ids.len() > MAX_CLASSES {
                return None;
            }
            class.push(id);
        }
        let chunk_start = (0..rows.div_ceil(CHUNK)).map(|k| lv.offsets[k * CHUNK]).collect();
        Some(PackedLevel {
            n_in: lv.n_in,
            copy_vertices: lv.copy_vertices,
            class,
            class_start,
            class_weights,
            indices: lv.indices.clone(),
            chunk_start,
        })
    }

    /// Applies this level: the same positions as [`LevelPlan::apply`].
    ///
    /// # Panics
    /// If `input` has fewer than `n_in` positions or `out` is not the size of
    /// the finer level (a caller bug, not input data).
    pub(crate) fn apply<I: Point, O: Point>(&self, input: &[I], out: &mut [O]) {
        assert!(input.len() >= self.n_in, "input has the coarser level's vertices");
        let rows = if self.copy_vertices {
            copy_points(&input[..self.n_in], &mut out[..self.n_in]);
            &mut out[self.n_in..]
        } else {
            out
        };
        assert_eq!(rows.len(), self.class.len(), "one output per row");
        let classes = Classes { start: &self.class_start, weights: &self.class_weights };
        rows.par_chunks_mut(CHUNK)
            .zip(self.class.par_chunks(CHUNK))
            .zip(&self.chunk_start)
            .for_each(|((out, class), &start)| rows_chunk(classes, &self.indices[start as usize..], class, input, out));
    }
}

/// The weight vectors of a level: class `c`'s are
/// `weights[start[c]..start[c + 1]]`.
#[derive(Clone, Copy)]
struct Classes<'a> {
    start: &'a [u32],
    weights: &'a [f32],
}

crate::cpu::multiversion! {
    /// One chunk of rows: row `k` has class `class[k]` and takes its
    /// indices from `indices` after those of the rows before it.
    fn rows_chunk<I: Point, O: Point>(classes: Classes, indices: &[u32], class: &[u16], input: &[I], out: &mut [O]) {
        let mut o = 0;
        for (q, &c) in out.iter_mut().zip(class) {
            let c = c as usize;
            let w = &classes.weights[classes.start[c] as usize..classes.start[c + 1] as usize];
            let idx = &indices[o..o + w.len()];
            *q = O::store(match w.len() {
                4 => fixed::<I, 4>(input, idx, w),
                7 => fixed::<I, 7>(input, idx, w),
                _ => gather(input, idx, w),
            });
            o += w.len();
        }
    }
}

/// [`gather`] of a row of `N` entries, unrolled.
#[inline(always)]
fn fixed<I: Point, const N: usize>(input: &[I], idx: &[u32], w: &[f32]) -> Vec3A {
    match (idx.first_chunk::<N>(), w.first_chunk::<N>()) {
        (Some(idx), Some(w)) => gather(input, idx, w),
        _ => gather(input, idx, w),
    }
}

/// One row's weighted sum: the products summed in the CSR row's order.
#[inline(always)]
fn gather<I: Point>(input: &[I], idx: &[u32], w: &[f32]) -> Vec3A {
    let mut sum = Vec3A::ZERO;
    for (&j, &w) in idx.iter().zip(w) {
        // SAFETY: `pack` copies the indices of a recorded level, every one a
        // vertex of the coarser level (below `n_in`; the fields are
        // private), and `apply` asserts `input.len() >= n_in`.
        sum += unsafe { *input.get_unchecked(j as usize) }.load() * w;
    }
    sum
}
