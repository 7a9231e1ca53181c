//! Curvature as colour: which curvature, its values at sampled points and
//! a diverging colour map (blue negative, white zero, red positive) over a
//! range clamped at percentiles, so a few extreme values (near an
//! extraordinary vertex, where Loop's curvature is unbounded) do not wash
//! out the rest.

use super::Sample;
use glam::Vec3;

/// The default clamp of [`symmetric_range`]: the 2nd and 98th percentiles.
pub const PERCENTILE: f64 = 2.0;

/// The most isolines per side of zero over the curvature colours
/// (`--isolines`, the viewer's slider).
pub const MAX_ISOLINES: u8 = 50;

/// A curvature to colour by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CurvatureKind {
    /// Mean curvature `H` (positive where the surface bends away from its normal).
    Mean,
    /// Gaussian curvature `K`.
    Gaussian,
    /// The smaller principal curvature `k2`.
    Min,
    /// The larger principal curvature `k1`.
    Max,
}

impl CurvatureKind {
    /// The value of this curvature in a sample.
    pub fn of(self, s: &Sample) -> f64 {
        match self {
            CurvatureKind::Mean => s.mean,
            CurvatureKind::Gaussian => s.gaussian,
            CurvatureKind::Min => s.k2,
            CurvatureKind::Max => s.k1,
        }
    }
    /// Its name in the CLI (`mean-curvature`, ...).
    pub fn name(self) -> &'static str {
        match self {
            CurvatureKind::Mean => "mean-curvature",
            CurvatureKind::Gaussian => "gaussian-curvature",
            CurvatureKind::Min => "min-curvature",
            CurvatureKind::Max => "max-curvature",
        }
    }
}

/// Blue (-1) through white (0) to red (+1), in linear RGB.
pub fn diverging(t: f32) -> Vec3 {
    let t = t.clamp(-1.0, 1.0);
    let white = Vec3::splat(0.92);
    let (blue, red) = (Vec3::new(0.05, 0.18, 0.75), Vec3::new(0.75, 0.06, 0.05));
    if t < 0.0 { white.lerp(blue, -t) } else { white.lerp(red, t) }
}

/// The symmetric range `[-r, r]` holding the values between the
/// `percentile`th and the `(100 - percentile)`th percentile (NaN skipped).
pub fn symmetric_range(values: &[f64], percentile: f64) -> f64 {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    let at = |p: f64| v[((p / 100.0) * (v.len() - 1) as f64).round() as usize];
    at(percentile).abs().max(at(100.0 - percentile).abs())
}

/// The colour of each value on the diverging map over `[-range, range]`;
/// NaN (not evaluated) is mid grey.
pub fn colors(values: &[f64], range: f64) -> Vec<Vec3> {
    values
        .iter()
        .map(|&x| {
            if x.is_nan() {
                Vec3::splat(0.45)
            } else if range > 0.0 {
                diverging((x / range) as f32)
            } else {
                diverging(0.0)
            }
        })
        .collect()
}

/// Each value over `range` (the half-width of the map, so `[-1, 1]` spans
/// it; values beyond it stay beyond), for a renderer that colours per pixel
/// and draws isolines; NaN (not evaluated) stays NaN. A zero range maps
/// every value to 0, as [`colors`] paints it white.
pub fn normalized(values: &[f64], range: f64) -> Vec<f32> {
    values
        .iter()
        .map(|&x| {
            if x.is_nan() {
                f32::NAN
            } else if range > 0.0 {
                (x / range) as f32
            } else {
                0.0
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_map_diverges_from_white_and_the_range_ignores_outliers() {
        assert!(diverging(-1.0).z > 0.5 && diverging(-1.0).x < 0.2);
        assert!(diverging(1.0).x > 0.5 && diverging(1.0).z < 0.2);
        assert!((diverging(0.0) - Vec3::splat(0.92)).length() < 1e-6);
        let mut v: Vec<f64> = (0..100).map(|i| f64::from(i) / 100.0 - 0.3).collect();
        v.push(1e9);
        v.push(f64::NAN);
        let r = symmetric_range(&v, 2.0);
        assert!(r > 0.6 && r < 0.7, "{r}");
        let c = colors(&v, r);
        assert_eq!(c[v.len() - 1], Vec3::splat(0.45));
        let t = normalized(&v, r);
        assert!(t[v.len() - 1].is_nan() && t[v.len() - 2] > 1e6, "NaN kept, outliers not clamped");
        assert!((f64::from(t[0]) + 0.3 / r).abs() < 1e-6);
        assert_eq!(normalized(&[2.0], 0.0), [0.0]);
    }
}
