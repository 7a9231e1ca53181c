//! The interface between a scheme and the machinery that applies it.
//!
//! A scheme only *emits* the stencil of each new point: pairs (old vertex id,
//! weight) through a [`Sink`]. The same emission code therefore serves the
//! one-shot subdivision (an [`Accumulate`] sink sums weighted positions, fully
//! inlined) and the stencil plan for animation (a recording sink stores the
//! weights once). All rules read the OLD level only.

use crate::mesh::{CornerTable, n, p};
use glam::Vec3;

/// Receives the weights of one stencil.
pub trait Sink {
    /// Adds `w` times old vertex `v`.
    fn add(&mut self, v: u32, w: f32);
}

/// Sums weighted old positions.
pub struct Accumulate<'a> {
    /// Old positions.
    pub pos: &'a [Vec3],
    /// The running sum.
    pub sum: Vec3,
}

impl<'a> Accumulate<'a> {
    /// A zero sum over `pos`.
    #[inline(always)]
    pub fn new(pos: &'a [Vec3]) -> Self {
        Accumulate { pos, sum: Vec3::ZERO }
    }
}

impl Sink for Accumulate<'_> {
    #[inline(always)]
    fn add(&mut self, v: u32, w: f32) {
        self.sum += self.pos[v as usize] * w;
    }
}

/// Records a stencil as (index, weight) pairs.
#[derive(Default)]
pub struct Record {
    /// Vertex ids.
    pub idx: Vec<u32>,
    /// Weights.
    pub w: Vec<f32>,
}

impl Sink for Record {
    #[inline]
    fn add(&mut self, v: u32, w: f32) {
        self.idx.push(v);
        self.w.push(w);
    }
}

/// The rules of one scheme: a stencil for every edge point and (for
/// approximating schemes) every vertex point.
pub trait Rules: Sync {
    /// Whether old vertices move (Loop, Jarek) or are copied (interpolating).
    const MOVES_VERTICES: bool;
    /// Stencil of the new vertex on the edge opposite owner corner `c`.
    fn edge<S: Sink>(&self, ct: &CornerTable, c: u32, s: &mut S);
    /// Stencil of old vertex `v`'s new position.
    #[inline(always)]
    fn vertex<S: Sink>(&self, _ct: &CornerTable, v: u32, s: &mut S) {
        s.add(v, 1.0);
    }
}

/// The 4-point curve rule along the boundary for the border edge opposite
/// owner corner `c` (Dyn, Levin, Gregory 1987; schemes.md 3.5a):
/// `e = 9/16 (p1 + p2) - 1/16 (p0 + p3)` with `p0, p1, p2, p3` consecutive
/// boundary vertices. Uses boundary vertices only, so the boundary curve is
/// the interpolating 4-point curve of the boundary polygon.
#[inline]
pub fn four_point<S: Sink>(ct: &CornerTable, c: u32, s: &mut S) {
    let (p1, p2) = (ct.vtx(n(c)), ct.vtx(p(c)));
    // the border edge runs p1 -> p2; p0 ends the fan of p1, p3 starts that of p2
    let p0 = ct.boundary_neighbours(p1).1;
    let p3 = ct.vtx(n(ct.vc[p2 as usize]));
    s.add(p0, -1.0 / 16.0);
    s.add(p1, 9.0 / 16.0);
    s.add(p2, 9.0 / 16.0);
    s.add(p3, -1.0 / 16.0);
}

/// Walks the `k` neighbours of interior vertex `v(x)` in swing order,
/// starting with `v(n(x))`.
#[inline]
pub fn ring_from(ct: &CornerTable, x: u32) -> impl Iterator<Item = u32> + '_ {
    let mut c = Some(x);
    std::iter::from_fn(move || {
        let cur = c?;
        c = ct.s(cur).filter(|&y| y != x);
        Some(ct.vtx(n(cur)))
    })
}
