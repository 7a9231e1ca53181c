//! Split-and-tweak refinement of closed polygons (Rossignac's "Split & Tweak"
//! notes; Rossignac & Schaefer, "J-splines", CAD 2008; docs/schemes.md §8).
//!
//! For a closed polygon `P_0 .. P_{n-1}` (indices mod n), computed from the
//! OLD polygon before anything moves:
//! ```text
//! D_j = P_{j-1}/8 + P_{j+1}/8 - P_j/4      M_j = (P_j + P_{j+1})/2
//! B-spline:  Q_2j = P_j + D_j     Q_2j+1 = M_j                   masks [1,6,1]/8, [1,1]/2
//! 4-point:   Q_2j = P_j           Q_2j+1 = M_j - (D_j+D_j+1)/2   masks identity, [-1,9,9,-1]/16
//! Jarek:     Q_2j = P_j + D_j/2   Q_2j+1 = M_j - (D_j+D_j+1)/4   masks [1,14,1]/16, [-1,17,17,-1]/32
//! ```
//! Pitfall avoided: computing `D` on the already split polygon would turn the
//! B-spline tweak into `[1,14,1]/16`; here every `D_j` is computed first.

use glam::Vec3;

/// The tweak applied after each split.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Hash)]
pub enum Tweak {
    /// Uniform cubic B-spline (approximating, C2).
    BSpline,
    /// Dyn-Levin-Gregory 4-point (interpolating, C1).
    FourPoint,
    /// Jarek: the average of the two (J-spline with s = 1/2).
    #[default]
    Jarek,
}

impl Tweak {
    /// All tweaks, in menu order.
    pub const ALL: [Tweak; 3] = [Tweak::BSpline, Tweak::FourPoint, Tweak::Jarek];
    /// Command-line name.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Tweak::BSpline => "bspline",
            Tweak::FourPoint => "four-point",
            Tweak::Jarek => "jarek",
        }
    }
    /// (vertex displacement factor, edge displacement factor): `Q_2j = P_j + a D_j`,
    /// `Q_2j+1 = M_j - b (D_j + D_j+1)`.
    fn factors(self) -> (f32, f32) {
        match self {
            Tweak::BSpline => (1.0, 0.0),
            Tweak::FourPoint => (0.0, 0.5),
            Tweak::Jarek => (0.5, 0.25),
        }
    }
}

impl std::str::FromStr for Tweak {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "bspline" | "b-spline" | "cubic" => Ok(Tweak::BSpline),
            "four-point" | "4-point" | "fourpoint" | "4pt" => Ok(Tweak::FourPoint),
            "jarek" => Ok(Tweak::Jarek),
            _ => Err(format!("unknown tweak '{s}' (expected bspline, four-point or jarek)")),
        }
    }
}

/// One split-and-tweak step of a closed polygon: `n` points give `2n`.
pub(crate) fn refine_once(poly: &[Vec3], tweak: Tweak) -> Vec<Vec3> {
    let n = poly.len();
    if n == 0 {
        return Vec::new();
    }
    let (a, b) = tweak.factors();
    let d: Vec<Vec3> = (0..n).map(|j| poly[(j + n - 1) % n] / 8.0 + poly[(j + 1) % n] / 8.0 - poly[j] / 4.0).collect();
    let mut out = Vec::with_capacity(2 * n);
    for j in 0..n {
        let k = (j + 1) % n;
        out.push(poly[j] + d[j] * a);
        out.push((poly[j] + poly[k]) * 0.5 - (d[j] + d[k]) * b);
    }
    out
}

/// `levels` split-and-tweak steps: `n` points give `n * 2^levels`.
pub(crate) fn refine_closed(poly: &[Vec3], tweak: Tweak, levels: u32) -> Vec<Vec3> {
    let mut cur = poly.to_vec();
    for _ in 0..levels {
        cur = refine_once(&cur, tweak);
    }
    cur
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The masks: refine a unit impulse at index 4 of a 9-gon and read the weights.
    fn masks(t: Tweak) -> (Vec<f32>, Vec<f32>) {
        let mut p = vec![Vec3::ZERO; 9];
        p[4] = Vec3::X;
        let q = refine_once(&p, t);
        // vertex mask: weights of P_3, P_4, P_5 in Q_8 = new vertex at P_4
        let vertex = vec![refine_weight(&q, 2 * 5), q[8].x, refine_weight(&q, 2 * 3)];
        // edge mask of Q_{2j+1} for j = 2..5 w.r.t. P_4: Q_3 (j=1: P_4 is j+3?) ...
        let edge = vec![q[2 * 5 + 1].x, q[2 * 4 + 1].x, q[2 * 3 + 1].x, q[2 * 2 + 1].x];
        (vertex, edge)
    }
    fn refine_weight(q: &[Vec3], i: usize) -> f32 {
        q[i].x
    }

    #[test]
    fn masks_match_schemes_md() {
        let (v, e) = masks(Tweak::BSpline);
        assert_eq!(v, vec![1.0 / 8.0, 6.0 / 8.0, 1.0 / 8.0]);
        assert_eq!(e, vec![0.0, 0.5, 0.5, 0.0]);
        let (v, e) = masks(Tweak::FourPoint);
        assert_eq!(v, vec![0.0, 1.0, 0.0]);
        assert_eq!(e, vec![-1.0 / 16.0, 9.0 / 16.0, 9.0 / 16.0, -1.0 / 16.0]);
        let (v, e) = masks(Tweak::Jarek);
        assert_eq!(v, vec![1.0 / 16.0, 14.0 / 16.0, 1.0 / 16.0]);
        assert_eq!(e, vec![-1.0 / 32.0, 17.0 / 32.0, 17.0 / 32.0, -1.0 / 32.0]);
    }

    #[test]
    fn four_point_interpolates_the_keys() {
        let keys =
            [Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.2, 0.0), Vec3::new(1.3, 1.0, 0.5), Vec3::new(0.0, 1.0, 0.1)];
        let r = refine_closed(&keys, Tweak::FourPoint, 5);
        assert_eq!(r.len(), 4 * 32);
        for (j, k) in keys.iter().enumerate() {
            assert_eq!(r[32 * j], *k);
        }
        // the B-spline does not
        let b = refine_closed(&keys, Tweak::BSpline, 3);
        assert!(b[0].distance(keys[0]) > 0.05);
    }

    #[test]
    fn tweaks_use_the_old_polygon_only() {
        // a regular polygon stays centred and planar; a degenerate one stays put
        let same = [Vec3::ONE; 4];
        for t in Tweak::ALL {
            assert!(refine_closed(&same, t, 4).iter().all(|p| *p == Vec3::ONE));
        }
        // linear precision on a closed polygon is impossible, but the centroid is kept
        let sq =
            [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0), Vec3::new(-1.0, 0.0, 0.0), Vec3::new(0.0, -1.0, 0.0)];
        for t in Tweak::ALL {
            let r = refine_closed(&sq, t, 3);
            let c: Vec3 = r.iter().copied().sum::<Vec3>() / r.len() as f32;
            assert!(c.length() < 1e-6);
        }
    }
}
