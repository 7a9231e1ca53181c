//! Curvature as colour: which curvature, its values at the vertices of a
//! level, the range the colours span and a diverging colour map (blue
//! negative, white zero, red positive).
//!
//! Which schemes: the exact limit surfaces, Loop's and Catmull-Clark's
//! ([`SCHEMES`], [`check_scheme`]: the one check `render` and the viewer
//! make). Bilinear is its own limit (flat faces, no curvature between
//! them), the interpolating schemes and Jarek have no closed-form limit to
//! evaluate.
//!
//! The range: symmetric about zero, `[-r, r]` (every curvature coloured
//! here is signed), `r` either set (`--range`, the panel's field) or, by
//! default, the [`PERCENTILE`]th percentile of `|value|` weighted by area
//! ([`auto_range`]): the magnitude the curvature stays below on 90% of the
//! surface. Each vertex stands for a third of the area of each triangle
//! around it (the barycentric vertex area, the simplest of the vertex areas
//! in Meyer, Desbrun, Schröder and Barr, "Discrete Differential-Geometry
//! Operators for Triangulated 2-Manifolds", 2003), so a finely meshed
//! region counts for its size, not for its number of vertices. Clamping a
//! colour map at a percentile and making it symmetric about zero are what
//! MeshLab's "Colorize by vertex Quality" offers ("Percentile Crop", "Zero
//! Symmetric").
//!
//! Why the 90th percentile by area and not the 2nd and 98th percentiles of
//! the values (this map's range before): the curvature grows without bound
//! towards an extraordinary vertex and is large at sharp tips, so the
//! extreme few percent of the values come from a few vertices and set a
//! range that leaves the body of a model near white. Measured on the
//! bundled critter's mean curvature (`tests/curvature_colors.rs`, the share
//! of the area with `|value| / r >= 0.25`, a visible tint): at Loop level 3
//! the old range was `r = 24.1` and tinted 3.5% of the area, the 95th
//! percentile by area gives `r = 4.9` and 47%, the 90th `r = 3.8` and 58%
//! (Catmull-Clark level 3: 22.5 and 4.1%, 5.1 and 47%, 3.8 and 58%). So the
//! 90th: most of the surface coloured, at most a tenth of it saturated at
//! the ends. Gaussian curvature, a product of two curvatures, has a longer
//! tail (29% tinted on the critter, 1.3% before); `--range` narrows it.

use super::Sample;
use crate::mesh::{CornerTable, Mesh};
use crate::subdiv::{Options, Scheme};
use crate::{Error, Result};
use glam::Vec3;

/// The default range: the 90th percentile of `|value|` by area
/// (`auto_range`, the module docs say why).
pub const PERCENTILE: f64 = 90.0;

/// The most isolines per side of zero over the curvature colours
/// (`--isolines`, the viewer's slider).
pub const MAX_ISOLINES: u8 = 50;

/// The schemes whose limit surface the curvature colours show: those with
/// an exact evaluation (`src/subdiv/eval/`).
pub const SCHEMES: [Scheme; 2] = [Scheme::Loop, Scheme::CatmullClark];

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
    pub(crate) fn of(self, s: &Sample) -> f64 {
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
    /// Its name in words (`mean curvature`, ...), for a colour bar.
    pub fn words(self) -> &'static str {
        match self {
            CurvatureKind::Mean => "mean curvature",
            CurvatureKind::Gaussian => "Gaussian curvature",
            CurvatureKind::Min => "min curvature",
            CurvatureKind::Max => "max curvature",
        }
    }
}

/// Whether the curvature colours exist for `scheme` ([`SCHEMES`]); the
/// refusal names the schemes that have them and why this one has none.
///
/// # Errors
/// [`Error::Usage`] for every scheme but Loop and Catmull-Clark.
pub fn check_scheme(scheme: Scheme) -> Result<()> {
    if SCHEMES.contains(&scheme) {
        return Ok(());
    }
    let why = match scheme {
        Scheme::Bilinear | Scheme::Midpoint => "its limit is the flat-faced level itself, with no curvature",
        Scheme::Jarek => "its limit has no exact evaluation here",
        _ => "an interpolating scheme's limit has no exact evaluation here",
    };
    let names: Vec<&str> = SCHEMES.iter().map(|s| s.name()).collect();
    Err(Error::Usage(format!(
        "curvature colours exist for {} (their exact limit surfaces), not for {scheme}: {why}",
        names.join(" and ")
    )))
}

/// The curvature `kind` of the exact limit at every vertex of `fine`, the
/// level `levels` of `scheme` over `control` (see
/// [`super::vertex_samples`]); NaN where it is not defined.
///
/// # Errors
/// A scheme without curvature colours ([`check_scheme`]), or the
/// evaluation's errors.
pub fn vertex_curvatures(
    control: &Mesh,
    fine: &Mesh,
    (scheme, levels, opts): (Scheme, u32, &Options),
    kind: CurvatureKind,
) -> Result<Vec<f64>> {
    check_scheme(scheme)?;
    let samples = super::vertex_samples(control, fine, scheme, levels, opts)?;
    Ok(samples.iter().map(|s| kind.of(s)).collect())
}

/// Blue (-1) through white (0) to red (+1), in linear RGB.
pub(crate) fn diverging(t: f32) -> Vec3 {
    let t = t.clamp(-1.0, 1.0);
    let white = Vec3::splat(0.92);
    let (blue, red) = (Vec3::new(0.05, 0.18, 0.75), Vec3::new(0.75, 0.06, 0.05));
    if t < 0.0 { white.lerp(blue, -t) } else { white.lerp(red, t) }
}

/// The area each vertex of `ct` stands for: a third of the area of every
/// triangle around it (the barycentric vertex area).
pub fn vertex_areas(ct: &CornerTable, positions: &[Vec3]) -> Vec<f64> {
    let mut out = vec![0.0; ct.num_vertices()];
    for t in 0..ct.num_triangles() as u32 {
        let v = [0, 1, 2].map(|i| ct.vtx(3 * t + i) as usize);
        let [a, b, c] = v.map(|i| positions[i].as_dvec3());
        let third = (b - a).cross(c - a).length() / 6.0;
        for i in v {
            out[i] += third;
        }
    }
    out
}

/// The `percentile`th percentile of `|value|` with each value weighted by
/// its `area` (the smallest `|value|` with at least `percentile`% of the
/// area at or below it); NaN and infinite values are skipped. Where the
/// areas are all zero every value weighs the same. 0 when no value is
/// finite.
pub(crate) fn area_percentile(values: &[f64], areas: &[f64], percentile: f64) -> f64 {
    let mut v: Vec<(f64, f64)> = values
        .iter()
        .zip(areas.iter().copied().chain(std::iter::repeat(0.0)))
        .filter(|(x, _)| x.is_finite())
        .map(|(x, a)| (x.abs(), if a.is_finite() { a.max(0.0) } else { 0.0 }))
        .collect();
    if v.is_empty() {
        return 0.0;
    }
    if v.iter().all(|&(_, a)| a == 0.0) {
        v.iter_mut().for_each(|x| x.1 = 1.0);
    }
    v.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = v.iter().map(|x| x.1).sum();
    let want = total * (percentile / 100.0).clamp(0.0, 1.0);
    let mut sum = 0.0;
    for &(x, a) in &v {
        sum += a;
        if sum >= want {
            return x;
        }
    }
    v[v.len() - 1].0
}

/// The default half-width of the curvature colours for `values` at the
/// vertices of the level `(ct, positions)`: the [`PERCENTILE`]th
/// percentile of `|value|` by area (module docs).
pub(crate) fn auto_range(values: &[f64], ct: &CornerTable, positions: &[Vec3]) -> f64 {
    area_percentile(values, &vertex_areas(ct, positions), PERCENTILE)
}

/// A half-width of the curvature colours set by hand (`--range`, the
/// panel's field): finite and positive, so equality is an equivalence.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct HalfWidth(f64);

// never NaN (HalfWidth::new refuses it): PartialEq is reflexive
impl Eq for HalfWidth {}

impl HalfWidth {
    /// `r` as a half-width.
    ///
    /// # Errors
    /// Zero, negative, NaN or infinite.
    pub fn new(r: f64) -> std::result::Result<HalfWidth, String> {
        if r.is_finite() && r > 0.0 {
            Ok(HalfWidth(r))
        } else {
            Err(format!("'{r}' is not a range: give the half-width of the curvature colours, a number above 0"))
        }
    }
    /// The half-width.
    pub(crate) fn get(self) -> f64 {
        self.0
    }
}

impl std::str::FromStr for HalfWidth {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<HalfWidth, String> {
        let bad = || format!("'{s}' is not a range: give the half-width of the curvature colours, a number above 0");
        let r: f64 = s.trim().parse().map_err(|_| bad())?;
        HalfWidth::new(r).map_err(|_| bad())
    }
}

impl std::fmt::Display for HalfWidth {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.0)
    }
}

/// The range the curvature colours span: `[-half, half]`, set by hand or
/// the default (`auto_range`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scale {
    /// The half-width.
    pub half: f64,
    /// Set by hand (else the default percentile).
    pub set: bool,
}

impl Scale {
    /// The range `set`, or the default for `values` on the level `(ct,
    /// positions)`.
    pub fn choose(set: Option<HalfWidth>, values: &[f64], ct: &CornerTable, positions: &[Vec3]) -> Scale {
        match set {
            Some(r) => Scale { half: r.get(), set: true },
            None => Scale { half: auto_range(values, ct, positions), set: false },
        }
    }
    /// What the range is and where it came from: `±3.40 (auto: 90% of the
    /// area)` or `±5.00 (set)`.
    pub fn describe(&self) -> String {
        let how = if self.set { "set".to_string() } else { format!("auto: {PERCENTILE}% of the area") };
        format!("±{} ({how})", short(self.half))
    }
}

/// `x` in three significant digits, without an exponent from 0.001 to
/// 99999 (`3.40`, `24.1`, `0.0123`), with one outside (`1.23e-5`).
pub(crate) fn short(x: f64) -> String {
    let a = x.abs();
    if !x.is_finite() || a == 0.0 {
        return format!("{x}");
    }
    if !(1e-3..1e5).contains(&a) {
        return format!("{x:.2e}");
    }
    let digits = (2 - a.log10().floor() as i32).max(0) as usize;
    format!("{x:.digits$}")
}

#[cfg(test)]
/// The colour of each value on the diverging map over `[-range, range]`;
/// NaN (not evaluated) is mid grey.
pub(crate) fn colors(values: &[f64], range: f64) -> Vec<Vec3> {
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
/// every value to 0, as `colors` paints it white.
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
        // |v| of equal weights: 0 .. 0.69 and one outlier; 95% of them at
        // or below 0.64
        let r = area_percentile(&v, &[], 95.0);
        assert!(r > 0.6 && r < 0.7, "{r}");
        let c = colors(&v, r);
        assert_eq!(c[v.len() - 1], Vec3::splat(0.45));
        let t = normalized(&v, r);
        assert!(t[v.len() - 1].is_nan() && t[v.len() - 2] > 1e6, "NaN kept, outliers not clamped");
        assert!((f64::from(t[0]) + 0.3 / r).abs() < 1e-6);
        assert_eq!(normalized(&[2.0], 0.0), [0.0]);
    }

    #[test]
    fn the_percentile_goes_by_area() {
        // a value on a large area and many on small ones: the large area decides
        let values = [1.0, -5.0, 5.0, 5.0, -5.0];
        let areas = [96.0, 1.0, 1.0, 1.0, 1.0];
        assert_eq!(area_percentile(&values, &areas, 95.0), 1.0);
        assert_eq!(area_percentile(&values, &areas, 97.0), 5.0);
        assert_eq!(area_percentile(&[f64::NAN], &[1.0], 95.0), 0.0);
        // a unit square of two triangles: the two corners on the diagonal
        // carry a third of both
        let p = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        let m = Mesh::from_triangles(p, &[0, 1, 2, 0, 2, 3]).unwrap();
        let a = vertex_areas(&m.ct, &m.positions);
        assert!((a[0] - 1.0 / 3.0).abs() < 1e-9 && (a[1] - 1.0 / 6.0).abs() < 1e-9, "{a:?}");
        assert!((a.iter().sum::<f64>() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn a_range_is_a_positive_number_and_says_where_it_came_from() {
        assert_eq!("2.5".parse::<HalfWidth>().unwrap().get(), 2.5);
        for bad in ["0", "-1", "NaN", "inf", "", "wide"] {
            let e = bad.parse::<HalfWidth>().unwrap_err();
            assert!(e.contains("above 0") && !e.contains('\n'), "{bad}: {e}");
        }
        assert_eq!(Scale { half: 5.0, set: true }.describe(), "±5.00 (set)");
        assert_eq!(Scale { half: 3.14259, set: false }.describe(), "±3.14 (auto: 90% of the area)");
        assert_eq!(
            (short(24.06), short(0.01234), short(-1.5e-5), short(123456.0)),
            ("24.1".to_string(), "0.0123".to_string(), "-1.50e-5".to_string(), "1.23e5".to_string())
        );
        let names = check_scheme(Scheme::Butterfly).unwrap_err().to_string();
        assert!(names.contains("loop and catmull-clark") && names.contains("butterfly"), "{names}");
        assert!(check_scheme(Scheme::CatmullClark).is_ok() && check_scheme(Scheme::Bilinear).is_err());
    }
}
