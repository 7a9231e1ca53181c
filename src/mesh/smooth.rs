//! Taubin lambda/mu smoothing (G. Taubin, "A Signal Processing Approach to
//! Fair Surface Design", SIGGRAPH 1995; docs/schemes.md §9) and, for comparison,
//! plain Laplacian smoothing.
//!
//! ```text
//! umbrella operator, uniform weights over the 1-ring:
//!     interior vertex i, neighbours j (valence k):  L(x_i) = (1/k) sum x_j - x_i
//!     boundary vertex i, boundary neighbours q1, q2: L(x_i) = 1/2 (x_q1 + x_q2) - x_i
//! one Taubin step = two simultaneous (Jacobi) passes:
//!     x <- x + lambda L(x),  then  x <- x + mu L(x),   lambda > 0, mu < -lambda
//! pass-band frequency k_PB = 1/lambda + 1/mu (> 0); lambda = 0.6307, mu = -0.6732
//! gives k_PB ~= 0.1 (the values quoted with Desbrun et al. 1999; see
//! [`TAUBIN_LAMBDA`], [`TAUBIN_MU`]).
//! ```
//! Boundary choice: boundary vertices are **smoothed along the boundary
//! only**, with the 1-D umbrella of their two boundary neighbours (found from
//! the border edges of their fan), with the same lambda/mu, so a boundary
//! curve is Taubin-smoothed as a polygon and does not shrink either; interior
//! vertices never pull the boundary inward. Both operators have weights that
//! sum to zero, so smoothing commutes with affine maps and keeps planes planar.

use super::Mesh;
use super::coord::Coord;
use glam::{DVec3, Vec3};
use rayon::prelude::*;

/// Taubin's lambda for a pass band of about 0.1 (docs/schemes.md §9).
pub const TAUBIN_LAMBDA: f32 = 0.6307;
/// Taubin's mu matching [`TAUBIN_LAMBDA`].
pub const TAUBIN_MU: f32 = -0.6732;

/// `steps` Taubin steps (each a lambda pass then a mu pass) on the positions
/// of `mesh`; returns the new positions (same ids). Use [`TAUBIN_LAMBDA`] and
/// [`TAUBIN_MU`] for the usual values; [`smooth_f64`] for f64 positions.
pub fn taubin(mesh: &Mesh, steps: u32, lambda: f32, mu: f32) -> Vec<Vec3> {
    // an f32 factor widened and rounded back as the pass takes it: the same f32
    passes(mesh, &mesh.positions, steps, f64::from(lambda), Some(f64::from(mu)))
}

/// `steps` passes of plain Laplacian smoothing `x <- x + lambda L(x)` with
/// the same umbrella and boundary handling as [`taubin`] (which shrinks a
/// closed surface; kept to show what Taubin's mu pass prevents).
pub fn laplacian(mesh: &Mesh, steps: u32, lambda: f32) -> Vec<Vec3> {
    passes(mesh, &mesh.positions, steps, f64::from(lambda), None)
}

/// [`taubin`] (with `mu`) or [`laplacian`] (without) of the f64 positions
/// `positions` (one per vertex of `mesh`, e.g. a file's own digits), all in
/// f64: the same passes, the caller's precision.
///
/// # Panics
/// If `positions` has not one point per vertex of `mesh` (a caller bug).
pub fn smooth_f64(mesh: &Mesh, positions: &[DVec3], steps: u32, lambda: f64, mu: Option<f64>) -> Vec<DVec3> {
    assert_eq!(positions.len(), mesh.ct.num_vertices(), "one position per vertex");
    passes(mesh, positions, steps, lambda, mu)
}

/// `steps` lambda passes, each followed by a mu pass when there is a mu.
fn passes<P: Coord>(mesh: &Mesh, positions: &[P], steps: u32, lambda: f64, mu: Option<f64>) -> Vec<P> {
    let mut x = positions.to_vec();
    let mut scratch = vec![P::ZERO; x.len()];
    for _ in 0..steps {
        umbrella_pass(mesh, &mut x, &mut scratch, lambda);
        if let Some(mu) = mu {
            umbrella_pass(mesh, &mut x, &mut scratch, mu);
        }
    }
    x
}

/// One simultaneous pass `x <- x + f L(x)`; `scratch` receives the old `x`.
fn umbrella_pass<P: Coord>(mesh: &Mesh, x: &mut [P], scratch: &mut [P], f: f64) {
    let ct = &mesh.ct;
    scratch.copy_from_slice(x);
    let old = &*scratch;
    x.par_iter_mut().enumerate().with_min_len(4096).for_each(|(v, xv)| {
        let v32 = v as u32;
        let avg = if let Some((a, b)) = ct.boundary_neighbours(v32) {
            (old[a as usize] + old[b as usize]).times(0.5)
        } else {
            let (mut s, mut k) = (P::ZERO, 0u32);
            for q in ct.ring(v32) {
                s += old[q as usize];
                k += 1;
            }
            s.over(f64::from(k.max(1)))
        };
        *xv = old[v] + (avg - old[v]).times(f);
    });
}
