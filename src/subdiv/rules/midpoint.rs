//! Midpoint (linear) 1-to-4 subdivision.
//!
//! ```text
//! odd (edge) point:   e = 1/2 a + 1/2 b          a ---- e ---- b
//! even (vertex):      v' = v
//! ```
//! The surface does not change; it is the "split" half of split-and-tweak and
//! a cheap level-of-detail baseline (docs/schemes.md §2). Note that OpenMesh's
//! `MidpointT` is a different operation (vertex truncation).

use super::{Level, Rules, Sink};
use crate::mesh::{n, p};

/// Midpoint rules.
pub(crate) struct Midpoint;

impl Rules for Midpoint {
    const MOVES_VERTICES: bool = false;
    #[inline(always)]
    fn edge<S: Sink>(&self, ct: &Level, c: u32, s: &mut S) {
        s.add(ct.vtx(n(c)), 0.5);
        s.add(ct.vtx(p(c)), 0.5);
    }
}
