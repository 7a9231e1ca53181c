//! Loop subdivision (C. Loop, "Smooth Subdivision Surfaces Based on
//! Triangles", MS thesis, Utah 1987) with the boundary rules of Hoppe et al.,
//! "Piecewise Smooth Surface Reconstruction", SIGGRAPH 1994 (as in OpenSubdiv
//! `sdc/loopScheme.h`). docs/schemes.md §3.
//!
//! ```text
//!            c                     interior edge (a, b), wings c, d:
//!          /   \                     e = 3/8 (a + b) + 1/8 (c + d)
//!        a ----- b                 border edge: e = 1/2 (a + b)
//!          \   /
//!            d
//! interior vertex, valence n, neighbours p_i:
//!     v' = (1 - n beta) v + beta sum p_i
//!     Loop:   beta(n) = (1/n) (5/8 - (3/8 + 1/4 cos(2 pi / n))^2)   (default)
//!     Warren: beta(n) = 3/(8n) for n > 3, 3/16 for n = 3
//!     (both 1/16 at n = 6, 3/16 at n = 3)
//! boundary vertex, boundary neighbours q1, q2 (found from the two border
//! EDGES of its fan, never from "boundary neighbours" in general):
//!     v' = 3/4 v + 1/8 (q1 + q2)
//! ```
//! The boundary curve is therefore the cubic B-spline of the boundary polygon,
//! independent of the interior. A manifold vertex has exactly two border edges,
//! so the "corner" rule for 3+ border edges (v' = v) cannot arise after
//! validation; valence-2 boundary corners use the smooth boundary rule
//! (OpenSubdiv's `EDGE_ONLY` mode).

use super::{Coord, Level, Rules, Sink, ring_sums_map};
use crate::mesh::{n, p};

/// Which beta the vertex rule uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LoopBeta {
    /// Loop's original beta (OpenSubdiv, OpenMesh, VTK, CGAL).
    #[default]
    Loop,
    /// Warren's simplification (libigl, Open3D).
    Warren,
}

impl LoopBeta {
    /// Its name (`loop`, `warren`), as [`std::str::FromStr`] reads it.
    pub fn name(self) -> &'static str {
        match self {
            LoopBeta::Loop => "loop",
            LoopBeta::Warren => "warren",
        }
    }

    /// Beta for an interior vertex of valence `k`.
    pub fn beta(self, k: u32) -> f64 {
        let kf = f64::from(k.max(1));
        match self {
            LoopBeta::Loop => {
                let c = 3.0 / 8.0 + 0.25 * (2.0 * std::f64::consts::PI / kf).cos();
                (5.0 / 8.0 - c * c) / kf
            }
            LoopBeta::Warren => {
                if k == 3 {
                    3.0 / 16.0
                } else {
                    3.0 / (8.0 * kf)
                }
            }
        }
    }
}

impl std::str::FromStr for LoopBeta {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "loop" => Ok(LoopBeta::Loop),
            "warren" => Ok(LoopBeta::Warren),
            _ => Err(format!("unknown beta '{s}' (expected loop or warren)")),
        }
    }
}

/// Loop rules with a precomputed table of the vertex rule's weights.
pub(crate) struct Loop {
    /// `(1 - k beta, beta)` by valence `k`, in f64.
    weights: Vec<(f64, f64)>,
    kind: LoopBeta,
}

impl Loop {
    /// Loop rules with the given beta.
    pub(crate) fn new(kind: LoopBeta) -> Self {
        Loop { weights: (0..64).map(|k| Self::weights_of(kind, k)).collect(), kind }
    }
    fn weights_of(kind: LoopBeta, k: u32) -> (f64, f64) {
        let beta = kind.beta(k);
        (1.0 - f64::from(k) * beta, beta)
    }
    /// The interior vertex rule's `(centre, neighbour)` weights at valence `k`.
    #[inline(always)]
    fn weights(&self, k: u32) -> (f64, f64) {
        self.weights.get(k as usize).copied().unwrap_or_else(|| Self::weights_of(self.kind, k))
    }
}

impl Rules for Loop {
    const MOVES_VERTICES: bool = true;
    #[inline(always)]
    fn edge<S: Sink>(&self, ct: &Level, c: u32, s: &mut S) {
        let (a, b) = (ct.vtx(n(c)), ct.vtx(p(c)));
        match ct.o(c) {
            None => {
                s.add(a, 0.5);
                s.add(b, 0.5);
            }
            Some(x) => {
                s.add(a, 0.375);
                s.add(b, 0.375);
                s.add(ct.vtx(c), 0.125);
                s.add(ct.vtx(x), 0.125);
            }
        }
    }
    #[inline(always)]
    fn vertex<S: Sink>(&self, ct: &Level, v: u32, s: &mut S) {
        if let Some((q1, q2)) = ct.boundary_neighbours(v) {
            s.add(v, 0.75);
            s.add(q1, 0.125);
            s.add(q2, 0.125);
        } else {
            let (centre, beta) = self.weights(ct.valences()[v as usize]);
            s.add(v, centre);
            for c in ct.fan(v) {
                s.add(ct.vtx(n(c)), beta);
            }
        }
    }

    /// The crease vertex rule (Hoppe et al. 1994): `3/4 v + 1/8 (a + b)`.
    #[inline]
    fn crease_vertex<S: Sink>(&self, v: u32, a: u32, b: u32, s: &mut S) {
        s.add(v, 0.75);
        s.add(a, 0.125);
        s.add(b, 0.125);
    }

    /// Direct evaluation: vertex points from the lane-interleaved ring sums
    /// (`(1 - k beta) v + beta S`, boundary `3/4 v + 1/8 S`), edge points from
    /// the emitted stencils.
    fn vertex_points<P: Coord>(&self, lv: &Level, pos: &[P], vpart: &mut [P], scratch: &mut [P]) {
        ring_sums_map(lv, pos, vpart, scratch, |v, sum| {
            if lv.boundary[v] {
                pos[v].times(0.75) + sum.times(0.125)
            } else {
                // the weights rounded to the points' precision, as a sink rounds them
                let (centre, beta) = self.weights(lv.valences()[v]);
                pos[v].times(centre) + sum.times(beta)
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn beta_table_matches_schemes_md() {
        assert!((LoopBeta::Loop.beta(3) - 3.0 / 16.0).abs() < 1e-12);
        assert!((LoopBeta::Loop.beta(4) - 31.0 / 256.0).abs() < 1e-12);
        assert!((LoopBeta::Loop.beta(6) - 1.0 / 16.0).abs() < 1e-12);
        assert!((LoopBeta::Loop.beta(5) - 0.084093).abs() < 1e-6);
        assert!((LoopBeta::Warren.beta(3) - 3.0 / 16.0).abs() < 1e-12);
        assert!((LoopBeta::Warren.beta(6) - 1.0 / 16.0).abs() < 1e-12);
        assert!((LoopBeta::Warren.beta(4) - 3.0 / 32.0).abs() < 1e-12);
    }
}
