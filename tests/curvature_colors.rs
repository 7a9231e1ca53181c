//! The curvature colours' default range shows the surface: on the bundled
//! critter (Loop and Catmull-Clark, level 3) most of the area is visibly
//! tinted, where the 2nd/98th-percentile clamp it replaced left the body
//! near white (issue 38, item 7).

use subdiv::eval::color;
use subdiv::eval::color::{CurvatureKind, HalfWidth, Scale};
use subdiv::{Mesh, Options, Scheme, bundled, subdivide};

/// The control mesh of a bundled model.
fn model(name: &str) -> Mesh {
    let path = std::path::PathBuf::from(format!("{}{name}", bundled::PREFIX));
    bundled::read(&path, &Default::default()).expect("a bundled model").mesh
}

/// The range the colours spanned before: the larger magnitude of the 2nd
/// and 98th percentiles of the values, each vertex counting once.
fn old_range(values: &[f64]) -> f64 {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    let at = |p: f64| v[((p / 100.0) * (v.len() - 1) as f64).round() as usize];
    at(2.0).abs().max(at(98.0).abs())
}

/// The share of the area (vertex areas of `fine`) whose colour is at least
/// a quarter of the way from white to the ends of the map over `range`.
fn tinted_share(values: &[f64], fine: &Mesh, range: f64) -> f64 {
    let areas = color::vertex_areas(&fine.ct, &fine.positions);
    let total: f64 = areas.iter().sum();
    let t = color::normalized(values, range);
    let tinted: f64 = t.iter().zip(&areas).filter(|(t, _)| t.abs() >= 0.25).map(|(_, a)| a).sum();
    tinted / total
}

#[test]
fn the_default_range_tints_most_of_the_critter() {
    let control = model("critter.obj");
    let opts = Options::default();
    for scheme in [Scheme::Loop, Scheme::CatmullClark] {
        let fine = subdivide(&control, scheme, 3, &opts).unwrap().0;
        for kind in [CurvatureKind::Mean, CurvatureKind::Gaussian, CurvatureKind::Min, CurvatureKind::Max] {
            let values = color::vertex_curvatures(&control, &fine, (scheme, 3, &opts), kind).unwrap();
            assert_eq!(values.len(), fine.positions.len());
            let auto = Scale::choose(None, &values, &fine.ct, &fine.positions);
            assert!(!auto.set && auto.half > 0.0);
            let (before, after) =
                (tinted_share(&values, &fine, old_range(&values)), tinted_share(&values, &fine, auto.half));
            eprintln!(
                "{scheme} L3 {}: range {:.3} -> {:.3}, tinted area {:.1}% -> {:.1}%",
                kind.name(),
                old_range(&values),
                auto.half,
                100.0 * before,
                100.0 * after
            );
            // the old clamp left most of the body near white; the default
            // tints more of it for every curvature, and most of it for the
            // mean and the larger principal curvature (Gaussian curvature,
            // a product of the two, has a longer tail: about 30%)
            assert!(after > before + 0.1, "{scheme} {}: {before} -> {after}", kind.name());
            if matches!(kind, CurvatureKind::Mean | CurvatureKind::Max) {
                assert!(before < 0.5, "{scheme} {}: the old range tinted {before}", kind.name());
                assert!(after >= 0.5, "{scheme} {}: the default range tints {after} of the area", kind.name());
            }
            // a range set by hand is used as it is
            let set = Scale::choose(Some(HalfWidth::new(7.5).unwrap()), &values, &fine.ct, &fine.positions);
            assert_eq!((set.half, set.set), (7.5, true));
        }
    }
}
