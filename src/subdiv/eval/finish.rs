//! From a patch's jet to a [`Sample`]: the affine maps between a face's
//! parameters and its patches', the chain rule through them and the
//! curvatures. Every path of both schemes ends here (`loop_surface.rs`,
//! `local.rs`, `catmark.rs`).

use super::Sample;
use super::patch::Jet;
use glam::DVec3;

/// An affine map of parameters `(s, t) = J (u, v) + b`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Affine {
    pub(super) j: [[f64; 2]; 2],
    pub(super) b: [f64; 2],
}

impl Affine {
    pub(super) const IDENTITY: Affine = Affine { j: [[1.0, 0.0], [0.0, 1.0]], b: [0.0, 0.0] };
    pub(super) fn apply(&self, (u, v): (f64, f64)) -> (f64, f64) {
        (self.j[0][0] * u + self.j[0][1] * v + self.b[0], self.j[1][0] * u + self.j[1][1] * v + self.b[1])
    }
    /// `self` after `first`: the linear parts only (derivatives need no more).
    pub(super) fn after(&self, first: &Affine) -> [[f64; 2]; 2] {
        let (a, b) = (&self.j, &first.j);
        let m = |i: usize, k: usize| a[i][0] * b[0][k] + a[i][1] * b[1][k];
        [[m(0, 0), m(0, 1)], [m(1, 0), m(1, 1)]]
    }
}

/// The sample from the patch jet `jet` of the surface `base + c R`, where
/// the patch's `(s, t)` are `scale * J (u, v) + const`.
#[inline]
pub(super) fn finish(jet: &Jet, base: DVec3, c: f64, j: [[f64; 2]; 2], scale: f64, second: bool) -> Sample {
    let normal = jet.ds.cross(jet.dt).normalize();
    // chain rule: P_u = c scale (R_s ds/du + R_t dt/du)
    let d1 = c * scale;
    let d2 = d1 * scale;
    let du = (jet.ds * j[0][0] + jet.dt * j[1][0]) * d1;
    let dv = (jet.ds * j[0][1] + jet.dt * j[1][1]) * d1;
    let mut out = Sample { position: base + jet.p * c, normal, du, dv, ..Sample::NAN };
    if second {
        let second_d = |a: usize, b: usize| {
            (jet.dss * (j[0][a] * j[0][b])
                + jet.dst * (j[0][a] * j[1][b] + j[1][a] * j[0][b])
                + jet.dtt * (j[1][a] * j[1][b]))
                * d2
        };
        (out.duu, out.duv, out.dvv) = (second_d(0, 0), second_d(0, 1), second_d(1, 1));
        curvature(jet, c, &mut out);
    }
    out
}

/// The curvatures of `out` (its normal set) from the fundamental forms of
/// the patch (any parameters) of the surface `base + c R`: those of `R`
/// divided by `c` (by `c^2` for the Gaussian). Sign: `k = -II / I`, so a
/// sphere with outward normals has `k = 1/R`.
fn curvature(jet: &Jet, c: f64, out: &mut Sample) {
    let normal = out.normal;
    let (e, f, g) = (jet.ds.dot(jet.ds), jet.ds.dot(jet.dt), jet.dt.dot(jet.dt));
    let (l, m, nn) = (-jet.dss.dot(normal), -jet.dst.dot(normal), -jet.dtt.dot(normal));
    let det = e * g - f * f;
    let gaussian = (l * nn - m * m) / det;
    let mean = (l * g - 2.0 * m * f + nn * e) / (2.0 * det);
    let disc = (mean * mean - gaussian).max(0.0).sqrt();
    let (k1, k2) = (mean + disc, mean - disc);
    // a principal direction a R_s + b R_t solves (II - k I) (a, b) = 0
    let dir = |k: f64| -> DVec3 {
        let (a11, a12, a22) = (l - k * e, m - k * f, nn - k * g);
        let (a, b) = if a11.abs() + a12.abs() >= a12.abs() + a22.abs() { (-a12, a11) } else { (a22, -a12) };
        let d = jet.ds * a + jet.dt * b;
        if d.length_squared() > 0.0 { d.normalize() } else { jet.ds.normalize() }
    };
    let dir1 = dir(k1);
    let dir2 = if disc > 0.0 { dir(k2) } else { normal.cross(dir1) };
    (out.mean, out.gaussian, out.k1, out.k2) = (mean / c, gaussian / (c * c), k1 / c, k2 / c);
    (out.dir1, out.dir2) = (dir1, dir2);
}
