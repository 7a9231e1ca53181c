//! The tessellation's own checks: the stitching covers each patch once,
//! the output is watertight, and the measured distance is within the
//! tolerance (tests/tessellate.rs checks it against a dense refinement).

use super::grid::{self, Pt};
use super::*;
use glam::DMat4;
use std::collections::HashMap;

/// The rounds from nothing, the triangles kept with their corners' `(u, v)`
/// on their patch, and each triangle's control face.
fn run(
    mesh: &Mesh,
    control: &[DVec3],
    scheme: Scheme,
    opts: &Options,
    tolerance: Tolerance,
) -> Result<(Built, Vec<u32>, TessellationStats)> {
    let tolerance = tolerance.resolve(control)?;
    let ev = Evaluator::new_f64(mesh, control, scheme, opts)?;
    let first = Start::cold(&ev, mesh, scheme, &tolerance)?;
    let done = super::run(&ev, first, (opts, &tolerance), Instant::now())?;
    Ok((done.built, done.faces, done.stats))
}

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
        let out =
            tessellate(&mesh, &control, scheme, &Options::default(), Tolerance::Distance(t)).expect("tessellates");
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
        assert!(tessellate(&mesh, &control, Scheme::Loop, &Options::default(), Tolerance::Distance(t)).is_err());
        let view = ScreenTolerance { view_proj: DMat4::IDENTITY, width: 100.0, height: 100.0, pixels: t };
        assert!(tessellate(&mesh, &control, Scheme::Loop, &Options::default(), Tolerance::Screen(view)).is_err());
    }
    let flat = ScreenTolerance { view_proj: DMat4::ZERO, width: 100.0, height: 100.0, pixels: 0.5 };
    let e = tessellate(&mesh, &control, Scheme::Loop, &Options::default(), Tolerance::Screen(flat)).unwrap_err();
    assert!(e.to_string().contains("cannot be inverted"), "{e}");
    let small = Options { max_memory: Some(1 << 20), ..Options::default() };
    let e = tessellate(&mesh, &control, Scheme::Loop, &small, Tolerance::Distance(1e-9)).unwrap_err();
    assert!(e.to_string().contains("raise the tolerance"), "{e}");
}

/// At every vertex of the level-`levels` uniform refinement, the exact
/// limit there (the limit masks on that level, not the evaluator) and the
/// tessellation's flat triangle over the same `(u, v)` of the same control
/// face: an independent dense check. And the tessellation's triangles.
fn dense_pairs(mesh: &Mesh, scheme: Scheme, t: Tolerance, levels: u32) -> (Vec<(DVec3, DVec3)>, usize, Dense) {
    use crate::subdiv::eval::catmark_limit::limit_positions_f64;
    use crate::subdiv::eval::{poly_vertex_params, vertex_params};
    let opts = Options::default();
    let control: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    let (built, faces, stats) = run(mesh, &control, scheme, &opts, t).expect("tessellates");
    assert!(stats.met, "{scheme}: {stats:?}");
    let (limit, params, corners) = if scheme == Scheme::CatmullClark {
        let poly = PolyMesh::from_mesh(mesh);
        let (fine, pos) = crate::subdivide_f64(&poly, &control, scheme, levels, &opts).expect("refines");
        let table = fine.pt.triangulated();
        let params = poly_vertex_params(&poly.pt, &table, levels).expect("params");
        (limit_positions_f64(&fine, &pos, &opts).expect("limit"), params, table.v_table().to_vec())
    } else {
        let (fine, pos) = crate::subdivide_f64(mesh, &control, scheme, levels, &opts).expect("refines");
        let params = vertex_params(mesh.ct.num_triangles(), &fine.ct, levels).expect("params");
        let limit = crate::subdiv::rules::limit::loop_limit_positions_f64(&fine, &pos, opts.loop_beta);
        (limit, params, fine.ct.v_table().to_vec())
    };
    // each face's triangles, to find the one over a point
    let mut by_face: HashMap<u32, Vec<usize>> = HashMap::new();
    for (k, &f) in faces.iter().enumerate() {
        by_face.entry(f).or_default().push(k);
    }
    let mut pairs = Vec::with_capacity(limit.len());
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
        pairs.push((*x, found.expect("every point of the domain is covered")));
    }
    let dense = Dense::new(limit, corners.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect());
    (pairs, built.triangles.len(), dense)
}

/// The dense refinement's limit points and its triangles between them (a
/// surface within a small fraction of the tolerance of the limit), in cells
/// of about a triangle's size: the nearest of its points to a point.
struct Dense {
    points: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    cell: f64,
    cells: HashMap<[i64; 3], Vec<u32>>,
}

impl Dense {
    fn new(points: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Dense {
        let corner = |t: &[u32; 3], k: usize| points[t[k] as usize];
        let size = |t: &[u32; 3]| corner(t, 0).distance(corner(t, 1)).max(corner(t, 1).distance(corner(t, 2)));
        let cell = triangles.iter().map(size).sum::<f64>() / triangles.len() as f64;
        let key = |p: DVec3| (p / cell).floor().as_i64vec3().to_array();
        let mut cells: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
        for (i, t) in triangles.iter().enumerate() {
            let (lo, hi) = (0..3)
                .map(|k| corner(t, k))
                .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
            let (a, b) = (key(lo), key(hi));
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        cells.entry([x, y, z]).or_default().push(i as u32);
                    }
                }
            }
        }
        Dense { points, triangles, cell, cells }
    }

    /// The point of the dense surface nearest `q` among those within
    /// `reach` of it (`q` itself when none is).
    fn nearest(&self, q: DVec3, reach: f64) -> DVec3 {
        let k = (reach / self.cell).ceil() as i64 + 1;
        let c = (q / self.cell).floor().as_i64vec3();
        let mut best = (f64::INFINITY, q);
        for x in -k..=k {
            for y in -k..=k {
                for z in -k..=k {
                    for &t in self.cells.get(&[c.x + x, c.y + y, c.z + z]).into_iter().flatten() {
                        let [a, b, c] = self.triangles[t as usize].map(|i| self.points[i as usize]);
                        let p = closest_on_triangle(q, a, b, c);
                        if p.distance(q) < best.0 {
                            best = (p.distance(q), p);
                        }
                    }
                }
            }
        }
        best.1
    }
}

/// The point of triangle `abc` nearest `p` (Ericson, Real-Time Collision
/// Detection, 5.1.5).
fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

#[test]
fn the_tessellation_is_within_the_tolerance_of_a_dense_refinement() {
    let torus = crate::bundled::load(std::path::Path::new("bundled:torus.obj")).expect("bundled torus");
    let cube = crate::bundled::load(std::path::Path::new("bundled:cube.obj")).expect("bundled cube");
    for (mesh, scheme, t, levels) in [(&torus, Scheme::Loop, 2e-3, 5), (&cube, Scheme::CatmullClark, 2e-2, 6)] {
        let (pairs, triangles, dense) = dense_pairs(mesh, scheme, Tolerance::Distance(t), levels);
        // the flat point's distance from the limit at its own (u, v), or, where
        // that is over t (next to an extraordinary vertex, where the parameter
        // stretches), from the nearest point of the dense surface
        let distance = |&(x, q): &(DVec3, DVec3)| match x.distance(q) {
            d if d <= t => d,
            d => dense.nearest(q, d).distance(q),
        };
        let err = pairs.iter().map(distance).fold(0.0, f64::max);
        // (the dense surface's own flat triangles sag by about h^2 k / 8, with
        // h their size and k the curvature: below 1 % of t here)
        assert!(err <= t * 1.01, "{scheme}: {err} over {t} ({triangles} triangles)");
        // and not merely by being as fine as the dense level
        assert!(triangles < mesh.ct.num_triangles() << (2 * levels), "{scheme}: {triangles} triangles");
    }
}

#[test]
fn every_corner_is_the_limit_at_its_own_uv_with_its_normal() {
    let torus = crate::bundled::load(std::path::Path::new("bundled:torus.obj")).expect("bundled torus");
    let control: Vec<DVec3> = torus.positions.iter().map(|p| p.as_dvec3()).collect();
    let ev = Evaluator::new_f64(&torus, &control, Scheme::Loop, &Options::default()).expect("ev");
    let (built, faces, _) =
        run(&torus, &control, Scheme::Loop, &Options::default(), Tolerance::Distance(4.04e-4)).expect("runs");
    for (k, (_, t)) in built.triangles.iter().enumerate() {
        for p in t {
            let s = ev.eval(faces[k] as usize, p.uv.0, p.uv.1).expect("eval");
            let d = s.position.distance(built.positions[p.id as usize]);
            assert!(d < 1e-9, "triangle {k} of face {}: corner {} at {:?} is {d} away", faces[k], p.id, p.uv);
            let n = s.normal.distance(built.normals[p.id as usize]);
            assert!(n < 1e-9, "triangle {k}: corner {}'s normal is {n} off", p.id);
        }
    }
}

/// A perspective view of `width` x `height` pixels from `eye` towards the
/// origin (glam's right-handed projection, depth 0..1, as the viewer's).
fn view_from(eye: DVec3, width: f64, height: f64, pixels: f64) -> ScreenTolerance {
    let proj = glam::dcamera::rh::proj::directx::perspective(40f64.to_radians(), width / height, 0.05, 100.0);
    let view_proj = proj * glam::dcamera::rh::view::look_at_mat4(eye, DVec3::ZERO, DVec3::Y);
    ScreenTolerance { view_proj, width, height, pixels }
}

/// Pixel position of `p` in `view` (None behind the eye or off screen).
fn pixel(view: &ScreenTolerance, p: DVec3) -> Option<(f64, f64)> {
    let c = view.view_proj * p.extend(1.0);
    let (x, y) = (c.x / c.w, c.y / c.w);
    (c.w > 0.0 && x.abs() <= 1.0 && y.abs() <= 1.0).then_some((0.5 * view.width * x, 0.5 * view.height * y))
}

#[test]
fn a_screen_tolerance_keeps_the_dense_limit_within_its_pixels() {
    let torus = crate::bundled::load(std::path::Path::new("bundled:torus.obj")).expect("bundled torus");
    let cube = crate::bundled::load(std::path::Path::new("bundled:cube.obj")).expect("bundled cube");
    for (mesh, scheme, eye, levels) in [
        (&torus, Scheme::Loop, DVec3::new(0.4, 0.9, 1.6), 5),
        (&cube, Scheme::CatmullClark, DVec3::new(1.5, 1.2, 2.0), 6),
    ] {
        let view = view_from(eye, 240.0, 160.0, 0.5);
        let (pairs, triangles, dense) = dense_pairs(mesh, scheme, Tolerance::Screen(view), levels);
        let apart = |a: (f64, f64), b: (f64, f64)| ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
        let mut seen = 0;
        let mut worst: f64 = 0.0;
        for (x, q) in &pairs {
            if let (Some(a), Some(b)) = (pixel(&view, *x), pixel(&view, *q)) {
                seen += 1;
                // over half a pixel from the limit at its own (u, v): from the
                // nearest point of the dense surface
                let off = match apart(a, b) {
                    d if d <= 0.5 => d,
                    d => pixel(&view, dense.nearest(*q, x.distance(*q))).map_or(d, |n| apart(n, b)),
                };
                worst = worst.max(off);
            }
        }
        assert!(seen > pairs.len() / 4, "{scheme}: only {seen} of {} points in the view", pairs.len());
        assert!(worst <= 0.5 * 1.01, "{scheme}: {worst} pixels off ({triangles} triangles)");
    }
}

#[test]
fn a_nearer_view_is_finer_and_what_is_out_of_it_is_coarse() {
    let torus = crate::bundled::load(std::path::Path::new("bundled:torus.obj")).expect("bundled torus");
    let control: Vec<DVec3> = torus.positions.iter().map(|p| p.as_dvec3()).collect();
    let tris = |view: ScreenTolerance| {
        let out = tessellate(&torus, &control, Scheme::Loop, &Options::default(), Tolerance::Screen(view))
            .expect("tessellates");
        assert!(out.stats.met && out.stats.worst <= view.pixels, "{:?}", out.stats);
        assert!(is_watertight(&out.triangles), "cracks");
        out.triangles.len()
    };
    let near = tris(view_from(DVec3::new(0.0, 1.0, 2.0), 400.0, 300.0, 0.5));
    let far = tris(view_from(DVec3::new(0.0, 4.0, 8.0), 400.0, 300.0, 0.5));
    let coarser = tris(view_from(DVec3::new(0.0, 1.0, 2.0), 400.0, 300.0, 4.0));
    // (about as 1 / T: four times the distance or the pixels, a few times fewer)
    assert!(far < near / 2 && coarser < near / 4, "near {near}, far {far}, 4 pixels {coarser}");
    // looking away from it: every patch out of the view, each its control triangle
    let mut away = view_from(DVec3::new(0.0, 0.0, 5.0), 400.0, 300.0, 0.5);
    away.view_proj *= DMat4::from_translation(DVec3::new(0.0, 0.0, 10.0));
    assert_eq!(tris(away), torus.ct.num_triangles());
}

#[test]
fn a_fraction_of_the_diagonal_is_that_distance() {
    assert_eq!("1e-4x".parse::<Tolerance>().ok(), Some(Tolerance::Fraction(1e-4)));
    assert_eq!(" 2.5e-3 ".parse::<Tolerance>().ok(), Some(Tolerance::Distance(2.5e-3)));
    for bad in ["0", "-1x", "nan", "x", "1e-3y", ""] {
        let e = bad.parse::<Tolerance>().unwrap_err().to_string();
        assert!(e.contains("positive distance"), "{bad}: {e}");
    }
    let torus = crate::bundled::load(std::path::Path::new("bundled:torus.obj")).expect("bundled torus");
    let control: Vec<DVec3> = torus.positions.iter().map(|p| p.as_dvec3()).collect();
    let (lo, hi) = control.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &p| (l.min(p), h.max(p)));
    let go = |t| tessellate(&torus, &control, Scheme::Loop, &Options::default(), t).expect("tessellates");
    let (a, b) = (go(Tolerance::Fraction(2e-3)), go(Tolerance::Distance(2e-3 * lo.distance(hi))));
    assert_eq!((a.triangles, a.stats.tolerance), (b.triangles, b.stats.tolerance));
    assert!(tessellate(&torus, &control, Scheme::Loop, &Options::default(), Tolerance::Fraction(-1.0)).is_err());
}

#[test]
fn a_tessellator_makes_again_only_what_a_move_reaches() {
    let torus = crate::bundled::load(std::path::Path::new("bundled:torus.obj")).expect("bundled torus");
    let critter = crate::bundled::load(std::path::Path::new("bundled:critter.obj")).expect("bundled critter");
    // the critter's quads split in two: triangles' ptex faces, halved sides
    let triangles = Mesh::from_triangles(critter.positions.clone(), critter.ct.v_table()).expect("split");
    let opts = Options::default();
    for (mesh, scheme, fraction) in
        [(&torus, Scheme::Loop, 4e-4), (&critter, Scheme::CatmullClark, 1e-3), (&triangles, Scheme::CatmullClark, 3e-3)]
    {
        let control: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        // a distance: a fraction of the diagonal would move with the point
        let t = fraction * view::diagonal(&control);
        let mut tessellator = Tessellator::new();
        let first = tessellator.tessellate(mesh, &control, scheme, &opts, Tolerance::Distance(t)).expect("first");
        let same = tessellator.tessellate(mesh, &control, scheme, &opts, Tolerance::Distance(t)).expect("same");
        assert_eq!(same.stats.evaluations, 0, "{scheme}: nothing moved, nothing evaluated");
        assert_eq!((&same.triangles, &same.positions), (&first.triangles, &first.positions), "{scheme}");
        // one control point moved by a hundredth of the diagonal (a drag)
        let mut moved = control.clone();
        moved[3] += DVec3::splat(0.01 * view::diagonal(&control));
        let again = tessellator.tessellate(mesh, &moved, scheme, &opts, Tolerance::Distance(t)).expect("again");
        let fresh = tessellate(mesh, &moved, scheme, &opts, Tolerance::Distance(t)).expect("fresh");
        assert!(again.stats.met && again.stats.measured <= t, "{scheme}: {:?}", again.stats);
        assert!(is_watertight(&again.triangles), "{scheme}: cracks after the move");
        // every vertex on the new limit surface at its own (u, v): none of the
        // old surface stayed where the move reached
        let ev = Evaluator::new_f64(mesh, &moved, scheme, &opts).expect("ev");
        let at: Vec<(usize, f64, f64)> = again.params.iter().map(|&(f, u, v)| (f as usize, u, v)).collect();
        let limit = ev.eval_map(&at, false, |s| (s.position, s.normal)).expect("eval");
        let mut off = 0;
        for (k, (&(f, u, v), s)) in again.params.iter().zip(&limit).enumerate() {
            assert!(s.0.distance(again.positions[k]) < 1e-9, "{scheme}: vertex {k} on face {f} is off");
            assert!(s.1.distance(again.normals[k]) < 1e-9, "{scheme}: vertex {k}'s normal is off");
            off += usize::from(first.params.get(k) == Some(&(f, u, v)) && first.positions[k] != again.positions[k]);
        }
        // the move did move the surface, and the rest was not evaluated again
        assert!(off > 0, "{scheme}: no vertex moved");
        assert!(
            again.stats.evaluations * 4 < fresh.stats.evaluations,
            "{scheme}: {:?} vs {:?}",
            again.stats,
            fresh.stats
        );
        // another tolerance starts afresh
        if scheme != Scheme::Loop {
            continue;
        }
        let finer = tessellator.tessellate(mesh, &moved, scheme, &opts, Tolerance::Distance(t / 2.0)).expect("finer");
        let cold = tessellate(mesh, &moved, scheme, &opts, Tolerance::Distance(t / 2.0)).expect("cold");
        assert_eq!(finer.stats.evaluations, cold.stats.evaluations, "{scheme}");
    }
}
