//! The tessellation's own checks: the stitching covers each patch once,
//! the output is watertight, and the measured distance is within the
//! tolerance (tests/tessellate.rs checks it against a dense refinement).

use super::grid::{self, Pt};
use super::*;
use std::collections::HashMap;

/// The signed area of a triangle in `(u, v)`.
fn area([a, b, c]: &[Pt; 3]) -> f64 {
    0.5 * ((b.uv.0 - a.uv.0) * (c.uv.1 - a.uv.1) - (c.uv.0 - a.uv.0) * (b.uv.1 - a.uv.1))
}

/// A side of `k + 1` points at the given fractions, ids from `first`.
fn side(quad: bool, s: usize, fractions: &[f64], first: u32) -> Vec<Pt> {
    let corners: &[(f64, f64)] = if quad { &grid::CORNERS_QUAD } else { &grid::CORNERS_TRI };
    let (a, b) = (corners[s], corners[(s + 1) % corners.len()]);
    fractions
        .iter()
        .enumerate()
        .map(|(k, &t)| Pt { id: first + k as u32, uv: (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)) })
        .collect()
}

#[test]
fn every_patch_is_covered_once_with_positive_triangles() {
    let sides_of =
        [vec![0.0, 1.0], vec![0.0, 0.3, 0.35, 1.0], vec![0.0, 0.25, 0.5, 0.75, 1.0], vec![0.0, 0.1, 0.2, 0.9, 1.0]];
    for quad in [false, true] {
        let (k, whole) = if quad { (4, 1.0) } else { (3, 0.5) };
        for n in 1..9 {
            for pick in 0..4 {
                let sides: Vec<Vec<Pt>> =
                    (0..k).map(|s| side(quad, s, &sides_of[(pick + s) % 4], 100 * s as u32)).collect();
                let mut out = Vec::new();
                grid::triangulate(quad, (n, false), &sides, 1000, &mut out);
                let total: f64 = out.iter().map(area).sum();
                assert!((total - whole).abs() < 1e-12, "quad {quad} n {n} sides {pick}: area {total}");
                assert!(
                    out.iter().all(|t| area(t) > 1e-9),
                    "quad {quad} n {n} sides {pick}: a flat or inverted triangle"
                );
            }
        }
    }
}

#[test]
fn uniform_sides_give_the_regular_grid() {
    for (quad, k) in [(false, 3), (true, 4)] {
        let n = 5;
        let f: Vec<f64> = (0..=n).map(|i| f64::from(i) / f64::from(n)).collect();
        let sides: Vec<Vec<Pt>> = (0..k).map(|s| side(quad, s, &f, 100 * s as u32)).collect();
        let mut out = Vec::new();
        grid::triangulate(quad, (n, true), &sides, 1000, &mut out);
        assert_eq!(out.len() as u32, n * n * if quad { 2 } else { 1 });
    }
}

/// Every directed edge of `t` once and its reverse once: a closed surface.
fn is_watertight(t: &[[u32; 3]]) -> bool {
    let mut seen: HashMap<(u32, u32), u32> = HashMap::new();
    for tri in t {
        for i in 0..3 {
            *seen.entry((tri[i], tri[(i + 1) % 3])).or_default() += 1;
        }
    }
    seen.iter().all(|(&(a, b), &k)| k == 1 && seen.get(&(b, a)) == Some(&1))
}

#[test]
fn a_closed_cage_gives_a_watertight_mesh_within_the_tolerance() {
    let mesh = crate::bundled::load(std::path::Path::new("bundled:torus.obj")).expect("bundled torus");
    let control: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    for (scheme, t) in [(Scheme::Loop, 4e-3), (Scheme::CatmullClark, 2e-2), (Scheme::Loop, 1e-3)] {
        let out = tessellate(&mesh, &control, scheme, &Options::default(), t).expect("tessellates");
        assert!(out.stats.met && out.stats.measured <= t, "{scheme} {t}: {:?}", out.stats);
        assert!(is_watertight(&out.triangles), "{scheme} {t}: cracks");
        assert_eq!(out.params.len(), out.positions.len());
    }
}

#[test]
fn a_bad_tolerance_is_refused() {
    let mesh = crate::bundled::load(std::path::Path::new("bundled:tetrahedron.obj")).expect("bundled");
    let control: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    for t in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(tessellate(&mesh, &control, Scheme::Loop, &Options::default(), t).is_err());
    }
    let small = Options { max_memory: Some(1 << 20), ..Options::default() };
    let e = tessellate(&mesh, &control, Scheme::Loop, &small, 1e-9).unwrap_err();
    assert!(e.to_string().contains("raise the tolerance"), "{e}");
}

/// The largest distance, at every vertex of the level-`levels` uniform
/// refinement, between the exact limit there (the limit masks on that
/// level, not the evaluator) and the tessellation's flat triangle over the
/// same `(u, v)` of the same control face: an independent dense check.
fn dense_error(mesh: &Mesh, scheme: Scheme, t: f64, levels: u32) -> (f64, usize) {
    use crate::subdiv::eval::catmark_limit::limit_positions_f64;
    use crate::subdiv::eval::{poly_vertex_params, vertex_params};
    let opts = Options::default();
    let control: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    let (built, faces, stats) = run(mesh, &control, scheme, &opts, t).expect("tessellates");
    assert!(stats.met, "{scheme}: {stats:?}");
    let (limit, params) = if scheme == Scheme::CatmullClark {
        let poly = PolyMesh::from_mesh(mesh);
        let (fine, pos) = crate::subdivide_f64(&poly, &control, scheme, levels, &opts).expect("refines");
        let params = poly_vertex_params(&poly.pt, &fine.pt.triangulated(), levels).expect("params");
        (limit_positions_f64(&fine, &pos, &opts).expect("limit"), params)
    } else {
        let (fine, pos) = crate::subdivide_f64(mesh, &control, scheme, levels, &opts).expect("refines");
        let params = vertex_params(mesh.ct.num_triangles(), &fine.ct, levels).expect("params");
        (crate::subdiv::rules::limit::loop_limit_positions_f64(&fine, &pos, opts.loop_beta), params)
    };
    // each face's triangles, to find the one over a point
    let mut by_face: HashMap<u32, Vec<usize>> = HashMap::new();
    for (k, &f) in faces.iter().enumerate() {
        by_face.entry(f).or_default().push(k);
    }
    let mut worst: f64 = 0.0;
    for (x, &(f, u, v)) in limit.iter().zip(&params) {
        let found = by_face[&(f as u32)].iter().find_map(|&k| {
            let [a, b, c] = built.triangles[k].1;
            let d = (b.uv.0 - a.uv.0) * (c.uv.1 - a.uv.1) - (c.uv.0 - a.uv.0) * (b.uv.1 - a.uv.1);
            let l1 = ((u - a.uv.0) * (c.uv.1 - a.uv.1) - (c.uv.0 - a.uv.0) * (v - a.uv.1)) / d;
            let l2 = ((b.uv.0 - a.uv.0) * (v - a.uv.1) - (u - a.uv.0) * (b.uv.1 - a.uv.1)) / d;
            let inside = l1 >= -1e-12 && l2 >= -1e-12 && l1 + l2 <= 1.0 + 1e-12;
            let p = |q: Pt| built.positions[q.id as usize];
            inside.then(|| p(a) * (1.0 - l1 - l2) + p(b) * l1 + p(c) * l2)
        });
        worst = worst.max(found.expect("every point of the domain is covered").distance(*x));
    }
    (worst, built.triangles.len())
}

#[test]
fn the_tessellation_is_within_the_tolerance_of_a_dense_refinement() {
    let torus = crate::bundled::load(std::path::Path::new("bundled:torus.obj")).expect("bundled torus");
    let cube = crate::bundled::load(std::path::Path::new("bundled:cube.obj")).expect("bundled cube");
    for (mesh, scheme, t, levels) in [(&torus, Scheme::Loop, 2e-3, 5), (&cube, Scheme::CatmullClark, 2e-2, 5)] {
        let (err, triangles) = dense_error(mesh, scheme, t, levels);
        assert!(err <= t * (1.0 + 1e-9), "{scheme}: {err} over {t} ({triangles} triangles)");
        // and not merely by being as fine as the dense level
        assert!(triangles < mesh.ct.num_triangles() << (2 * levels), "{scheme}: {triangles} triangles");
    }
}

#[test]
fn every_corner_is_the_limit_at_its_own_uv() {
    let torus = crate::bundled::load(std::path::Path::new("bundled:torus.obj")).expect("bundled torus");
    let control: Vec<DVec3> = torus.positions.iter().map(|p| p.as_dvec3()).collect();
    let ev = Evaluator::new_f64(&torus, &control, Scheme::Loop, &Options::default()).expect("ev");
    let (built, faces, _) = run(&torus, &control, Scheme::Loop, &Options::default(), 4.04e-4).expect("runs");
    for (k, (_, t)) in built.triangles.iter().enumerate() {
        for p in t {
            let s = ev.eval(faces[k] as usize, p.uv.0, p.uv.1).expect("eval");
            let d = s.position.distance(built.positions[p.id as usize]);
            assert!(d < 1e-9, "triangle {k} of face {}: corner {} at {:?} is {d} away", faces[k], p.id, p.uv);
        }
    }
}
