//! Exact Loop limit evaluation (`subdiv::eval`) against independent
//! truths: the limit positions of subdivided vertices at dyadic parameters
//! (subdivision and limit masks, not the evaluator), OpenSubdiv's regular
//! patches (tests/fixtures/loop_eval), finite differences of positions for
//! the derivatives, continuity across patch edges, and the curvature of a
//! sphere and a torus.

mod common;
use common::*;
use glam::{DVec3, Vec3};
use subdiv::Evaluator;
use subdiv::eval::Sample;
use subdiv::eval::loop_limit_positions_with;
use subdiv::{LoopBeta, Mesh, Options, Scheme, subdivide};

/// A closed bipyramid: two apexes of valence `n` around an `n`-gon of
/// valence-4 vertices, moved off their symmetric places.
fn bipyramid(n: u32, seed: u64) -> Mesh {
    let mut rng = Rng(seed);
    let mut pos = vec![Vec3::Z, -Vec3::Z];
    for i in 0..n {
        let a = i as f32 * std::f32::consts::TAU / n as f32;
        pos.push(Vec3::new(a.cos(), a.sin(), 0.0) + rng.vec3() * 0.1);
    }
    let mut tris = Vec::new();
    for i in 0..n {
        let (a, b) = (2 + i, 2 + (i + 1) % n);
        tris.extend([0, a, b, 1, b, a]);
    }
    Mesh::from_triangles(pos, &tris).unwrap()
}

/// Closed meshes with extraordinary vertices of valence 3, 4, 5, 7, 8 and 12.
fn closed_meshes() -> Vec<(String, Mesh)> {
    let mut out = vec![("tetrahedron".to_string(), bundled("tetrahedron.obj")), ("icosahedron".into(), icosahedron())];
    for n in [3, 5, 7, 8, 12] {
        out.push((format!("bipyramid {n}"), bipyramid(n, 0x9e3779b97f4a7c15 ^ u64::from(n))));
    }
    out.push(("cube".into(), bundled("cube.obj")));
    out
}

fn opts(beta: LoopBeta) -> Options {
    Options { loop_beta: beta, ..Options::default() }
}

/// The vertex of level `k` at the dyadic point `(u, v)` of control face `f`,
/// following the split's layout (src/mesh/split.rs): the central child
/// keeps the parent's corner ids with the vertex on the opposite edge, the
/// corner child of corner `c` starts at `3 nt (c % 3 + 1) + 3 t`.
fn vertex_at(levels: &[Mesh], f: u32, u: f64, v: f64) -> u32 {
    let (mut t, mut w) = (f, [1.0 - u - v, u, v]);
    for lv in &levels[..levels.len() - 1] {
        let nt = lv.ct.num_triangles() as u32;
        let i = (0..3).max_by(|&a, &b| w[a].total_cmp(&w[b])).unwrap();
        if w[i] >= 0.5 {
            let b = [2.0 * w[(i + 1) % 3], 2.0 * w[(i + 2) % 3]];
            t += nt * (i as u32 + 1);
            w = [1.0 - b[0] - b[1], b[0], b[1]];
        } else {
            w = [1.0 - 2.0 * w[0], 1.0 - 2.0 * w[1], 1.0 - 2.0 * w[2]];
        }
    }
    let i = (0..3).find(|&i| (w[i] - 1.0).abs() < 1e-9).expect("a dyadic point ends on a vertex");
    levels[levels.len() - 1].ct.vtx(3 * t + i as u32)
}

/// `mesh` with the crease tags `(v0, v1, sharpness)` and corner tags
/// `(vertex, sharpness)`.
fn tagged(mut mesh: Mesh, creases: &[(u32, u32, f32)], corners: &[(u32, f32)]) -> Mesh {
    use subdiv::mesh::{CornerTag, CreaseTag, Tags};
    let tags = Tags {
        creases: creases.iter().map(|&(v0, v1, sharpness)| CreaseTag { v0, v1, sharpness }).collect(),
        corners: corners.iter().map(|&(vertex, sharpness)| CornerTag { vertex, sharpness }).collect(),
    };
    mesh.ct = mesh.ct.clone().with_tags(&tags).unwrap();
    mesh
}

/// `mesh` without the faces touching vertex `v`, moved a little.
fn with_hole(mesh: &Mesh, v: u32, seed: u64) -> Mesh {
    let mut rng = Rng(seed);
    let tris: Vec<u32> = mesh.ct.v_table().chunks_exact(3).filter(|t| !t.contains(&v)).flatten().copied().collect();
    let pos = mesh.positions.iter().map(|&p| p + rng.vec3() * 0.05).collect();
    Mesh::from_triangles(pos, &tris).unwrap()
}

/// Meshes with borders, creases of every kind and sharp vertices, and the
/// options to subdivide them with. No dart is infinitely sharp: the limit
/// mask the truth uses there is OpenSubdiv's smooth one, which is not the
/// limit of the dart's rules.
fn featured_meshes() -> Vec<(String, Mesh, Options)> {
    let d = Options::default;
    let equator = |n: u32, s: f32| -> Vec<(u32, u32, f32)> { (0..n).map(|i| (2 + i, 2 + (i + 1) % n, s)).collect() };
    let chaikin = Options { creasing: subdiv::mesh::Creasing::Chaikin, ..d() };
    let corners = Options { boundary: subdiv::mesh::BoundaryInterpolation::EdgeAndCorner, ..d() };
    let mut bumpy = flat_grid(5);
    let mut rng = Rng(11);
    bumpy.positions.iter_mut().for_each(|p| p.z += rng.next_f32() * 0.3);
    let steps: Vec<(u32, u32, f32)> =
        equator(6, 0.0).iter().zip([0.5, 1.5, 2.3, 3.0, 1.0, 0.7]).map(|(e, s)| (e.0, e.1, s)).collect();
    vec![
        ("hemisphere".into(), hemisphere(), d()),
        (
            "icosphere with a hole".into(),
            with_hole(&icosphere(2), 0, 5),
            Options { loop_beta: LoopBeta::Warren, ..d() },
        ),
        ("open bipyramid".into(), with_hole(&bipyramid(5, 9), 0, 6), d()),
        ("bumpy grid".into(), bumpy.clone(), d()),
        ("bumpy grid, corners".into(), bumpy, corners),
        ("infinite crease".into(), tagged(bipyramid(6, 1), &equator(6, 10.0), &[]), d()),
        ("crease and corner".into(), tagged(bipyramid(7, 2), &equator(7, 10.0), &[(0, 10.0), (1, 2.5)]), d()),
        ("semi-sharp".into(), tagged(bipyramid(5, 3), &equator(5, 1.5), &[(0, 0.8)]), d()),
        ("semi-sharp steps".into(), tagged(bipyramid(6, 4), &steps, &[]), d()),
        ("semi-sharp, Chaikin".into(), tagged(bipyramid(6, 4), &steps, &[]), chaikin),
    ]
}

/// The worst distance, relative to the size, between the evaluator and the
/// limit masks of the level-4 refinement at every dyadic point of levels 0
/// to 4 of every face (a level-k vertex keeps its id at level 4, where
/// every semi-sharp feature of sharpness <= 4 has decayed, so the masks
/// are the limit).
fn dyadic_worst(mesh: &Mesh, opts: &Options) -> f64 {
    let ev = Evaluator::new(mesh, Scheme::Loop, opts).unwrap();
    let mut levels = vec![mesh.clone()];
    for _ in 0..4 {
        levels.push(subdivide(levels.last().unwrap(), Scheme::Loop, 1, opts).unwrap().0);
    }
    let limits = loop_limit_positions_with(&levels[4], opts.loop_beta);
    let size = f64::from(scale(mesh));
    let mut worst = 0.0f64;
    for k in 0..=4usize {
        let d = f64::from(1u32 << k);
        for f in 0..mesh.ct.num_triangles() as u32 {
            for i in 0..=(1u32 << k) {
                for j in 0..=(1u32 << k) - i {
                    let (u, v) = (f64::from(i) / d, f64::from(j) / d);
                    let want = limits[vertex_at(&levels[..=k], f, u, v) as usize].as_dvec3();
                    let got = ev.eval(f as usize, u, v).unwrap().position;
                    worst = worst.max((got - want).length() / size);
                }
            }
        }
    }
    worst
}

#[test]
fn dyadic_points_near_borders_creases_and_corners_are_the_limits() {
    for (name, mesh, opts) in featured_meshes() {
        let worst = dyadic_worst(&mesh, &opts);
        // the reference is computed in f32
        assert!(worst < 2e-6, "{name}: worst relative distance {worst:e}");
    }
}

#[test]
fn dyadic_points_are_the_limits_of_subdivided_vertices() {
    for beta in [LoopBeta::Loop, LoopBeta::Warren] {
        for (name, mesh) in closed_meshes() {
            let worst = dyadic_worst(&mesh, &opts(beta));
            // the reference is computed in f32
            assert!(worst < 2e-6, "{name} ({beta:?}): worst relative distance {worst:e}");
        }
    }
}

fn scale(m: &Mesh) -> f32 {
    let (lo, hi) = m.bounds();
    (hi - lo).length()
}

/// Random interior parameter points of every face.
fn random_points(mesh: &Mesh, per_face: usize, seed: u64) -> Vec<(usize, f64, f64)> {
    let mut rng = Rng(seed);
    let mut out = Vec::new();
    for f in 0..mesh.ct.num_triangles() {
        for _ in 0..per_face {
            let (mut a, mut b) = (f64::from(rng.next_f32()) * 0.5 + 0.5, f64::from(rng.next_f32()) * 0.5 + 0.5);
            if a + b > 1.0 {
                (a, b) = (1.0 - a, 1.0 - b);
            }
            // inside, away from the corners and edges: u, v >= 0.02, u + v <= 0.98
            out.push((f, 0.02 + 0.94 * a, 0.02 + 0.94 * b));
        }
    }
    out
}

/// The derivatives of `ev` at `points` against central differences of
/// positions (first) and of first derivatives (second); the normal is
/// `du x dv` normalised.
fn check_derivatives(ev: &Evaluator, points: &[(usize, f64, f64)], size: f64, name: &str) {
    let h = 1e-5;
    for &(f, u, v) in points {
        let s = ev.eval(f, u, v).unwrap();
        let at = |a: f64, b: f64| ev.eval(f, a, b).unwrap();
        let (pu, mu, pv, mv) = (at(u + h, v), at(u - h, v), at(u, v + h), at(u, v - h));
        let du = (pu.position - mu.position) / (2.0 * h);
        let dv = (pv.position - mv.position) / (2.0 * h);
        let duu = (pu.du - mu.du) / (2.0 * h);
        let duv = (pv.du - mv.du) / (2.0 * h);
        let dvv = (pv.dv - mv.dv) / (2.0 * h);
        let close = |a: DVec3, b: DVec3, tol: f64| (a - b).length() <= tol * (size + b.length());
        assert!(close(s.du, du, 1e-6) && close(s.dv, dv, 1e-6), "{name} face {f} ({u}, {v}): first derivatives");
        assert!(
            close(s.duu, duu, 1e-4) && close(s.duv, duv, 1e-4) && close(s.dvv, dvv, 1e-4),
            "{name} face {f} ({u}, {v}): second derivatives {:?} against {duu:?}",
            s.duu
        );
        let n = s.du.cross(s.dv).normalize();
        assert!(n.dot(s.normal) > 1.0 - 1e-12);
    }
}

#[test]
fn derivatives_match_finite_differences() {
    for (name, mesh) in closed_meshes() {
        let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
        check_derivatives(&ev, &random_points(&mesh, 6, 11), f64::from(scale(&mesh)), &name);
    }
}

/// The point `t` of the way along edge (a, b) in a face whose corners are
/// `corners`, as that face's `(u, v)`.
fn on_edge(corners: [u32; 3], a: u32, b: u32, t: f64) -> (f64, f64) {
    let mut w = [0.0; 3];
    for (i, &c) in corners.iter().enumerate() {
        if c == a {
            w[i] = 1.0 - t;
        }
        if c == b {
            w[i] = t;
        }
    }
    (w[1], w[2])
}

/// Both faces of every interior edge of `mesh` at three points of the edge:
/// `check(c, x, y)` with `c` a corner facing the edge and the two samples.
fn across_edges(mesh: &Mesh, ev: &Evaluator, mut check: impl FnMut(u32, &Sample, &Sample)) {
    let ct = &mesh.ct;
    let corners = |f: u32| [ct.vtx(3 * f), ct.vtx(3 * f + 1), ct.vtx(3 * f + 2)];
    for c in 0..ct.num_corners() as u32 {
        let Some(o) = ct.o(c) else { continue };
        let (f, g) = (c / 3, o / 3);
        let (a, b) = (ct.vtx(subdiv::mesh::n(c)), ct.vtx(subdiv::mesh::p(c)));
        for t in [0.13, 0.5, 0.77] {
            let (uf, vf) = on_edge(corners(f), a, b, t);
            let (ug, vg) = on_edge(corners(g), a, b, t);
            check(c, &ev.eval(f as usize, uf, vf).unwrap(), &ev.eval(g as usize, ug, vg).unwrap());
        }
    }
}

#[test]
fn patches_meet_with_one_tangent_plane_and_one_curvature() {
    for (name, mesh) in closed_meshes() {
        let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
        across_edges(&mesh, &ev, |c, x, y| {
            assert!((x.position - y.position).length() < 1e-12, "{name}: edge of corner {c}");
            assert!(x.normal.dot(y.normal) > 1.0 - 1e-12, "{name}: normals across the edge of corner {c}");
            // Loop is C2 away from extraordinary vertices: so is the curvature
            assert!((x.mean - y.mean).abs() < 1e-6 * (1.0 + x.mean.abs()), "{name}: H {} {}", x.mean, y.mean);
        });
    }
}

/// Mean |H R - 1| and |K R^2 - 1| over random points of an icosphere of
/// radius `r`, R each point's distance from the centre.
fn sphere_deviation(levels: u32, r: f32) -> (f64, f64) {
    let mut mesh = icosphere(levels);
    mesh.positions.iter_mut().for_each(|p| *p *= r);
    let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
    let (mut dev, mut count) = ((0.0, 0.0), 0.0);
    for (f, u, v) in random_points(&mesh, 2, 5) {
        let s: Sample = ev.eval(f, u, v).unwrap();
        let radius = s.position.length();
        let (h, k) = (s.mean * radius - 1.0, s.gaussian * radius * radius - 1.0);
        assert!(h.abs() < 0.25 && k.abs() < 0.5, "H R = {}, K R^2 = {}", 1.0 + h, 1.0 + k);
        assert!(s.k1 >= s.k2 && s.k2 > 0.0);
        assert!(s.normal.dot(s.position.normalize()) > 0.999, "the normal points outward");
        assert!(s.dir1.dot(s.normal).abs() < 1e-9 && s.dir2.dot(s.normal).abs() < 1e-9);
        dev = (dev.0 + h.abs(), dev.1 + k.abs());
        count += 1.0;
    }
    (dev.0 / count, dev.1 / count)
}

#[test]
fn a_sphere_like_mesh_has_curvature_one_over_its_radius() {
    // a Loop surface is not a sphere: the curvature ripples around the
    // valence-5 vertices and along the icosahedron's edges (where the
    // icosphere's sampling has kinks), by a few percent on average, and
    // comes closer on a finer control mesh
    let coarse = sphere_deviation(3, 2.5);
    let fine = sphere_deviation(4, 2.5);
    println!("mean deviations: icosphere 3 {coarse:?}, icosphere 4 {fine:?}");
    assert!(fine.0 < 0.02 && fine.1 < 0.04, "{fine:?}");
    assert!(fine.0 < coarse.0 && fine.1 < coarse.1, "{coarse:?} then {fine:?}");
}

#[test]
fn a_torus_is_elliptic_outside_and_hyperbolic_inside() {
    let mesh = bundled("torus.obj");
    let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
    // the torus's axis and radii from its vertices
    let (lo, hi) = mesh.bounds();
    let centre = ((lo + hi) * 0.5).as_dvec3();
    let ext = (hi - lo).as_dvec3();
    let axis = if ext.x <= ext.y && ext.x <= ext.z {
        DVec3::X
    } else if ext.y <= ext.z {
        DVec3::Y
    } else {
        DVec3::Z
    };
    let (outer, tube) = ((ext.max_element()) / 2.0, ext.min_element() / 2.0);
    let big_r = outer - tube;
    let (mut pos, mut neg) = (0, 0);
    for (f, u, v) in random_points(&mesh, 1, 3) {
        let s = ev.eval(f, u, v).unwrap();
        let d = s.position - centre;
        let from_axis = (d - axis * d.dot(axis)).length();
        if from_axis > big_r + 0.5 * tube {
            assert!(s.gaussian > 0.0, "outside, at {from_axis}: K = {}", s.gaussian);
            pos += 1;
        } else if from_axis < big_r - 0.5 * tube {
            assert!(s.gaussian < 0.0, "inside, at {from_axis}: K = {}", s.gaussian);
            neg += 1;
        }
        assert!(s.mean > 0.0 || from_axis < big_r, "H > 0 on the outer half");
    }
    assert!(pos > 50 && neg > 50, "{pos} outside, {neg} inside");
}

#[test]
fn other_schemes_faces_and_parameters_are_refused_by_name() {
    let mesh = icosahedron();
    for s in [Scheme::Butterfly, Scheme::ModifiedButterfly, Scheme::Jarek, Scheme::Midpoint] {
        let e = Evaluator::new(&mesh, s, &Options::default()).err().expect("refused");
        assert!(e.to_string().contains(s.name()), "{e}");
    }
    let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
    assert!(ev.eval(20, 0.1, 0.1).unwrap_err().to_string().contains("face 20"));
    for (u, v) in [(-0.1, 0.2), (0.7, 0.5), (f64::NAN, 0.1), (0.1, f64::INFINITY)] {
        assert!(ev.eval(0, u, v).is_err(), "({u}, {v})");
    }
    // u + v a hair over 1 is on the edge
    assert!(ev.eval(0, 0.5, 0.5 + 1e-9).is_ok());
    // borders are evaluated; only an interior vertex of valence 2 is refused
    let open = hemisphere();
    let ev = Evaluator::new(&open, Scheme::Loop, &Options::default()).unwrap();
    assert!((0..open.ct.num_triangles()).all(|f| ev.accepts(f)));
    // (the pillow's level 1 is not even a manifold table)
    if let Ok(ev) = Evaluator::new(&pillow(), Scheme::Loop, &Options::default()) {
        assert!(!ev.accepts(0));
        assert!(ev.eval(0, 0.2, 0.2).unwrap_err().to_string().contains("valence 2"));
    }
}

#[test]
fn the_extraordinary_vertex_itself_has_its_limit_and_normal() {
    let mesh = bipyramid(7, 3);
    let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
    let limits = loop_limit_positions_with(&mesh, LoopBeta::Loop);
    let normals = subdiv::eval::loop_limit_normals(&mesh);
    let ct = &mesh.ct;
    for f in 0..ct.num_triangles() as u32 {
        for (i, (u, v)) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].into_iter().enumerate() {
            let s = ev.eval(f as usize, u, v).unwrap();
            let vert = ct.vtx(3 * f + i as u32) as usize;
            assert!((s.position - limits[vert].as_dvec3()).length() < 1e-6);
            assert!(s.normal.dot(normals[vert].as_dvec3()) > 1.0 - 1e-6);
            // approaching the vertex, the normal tends to it
            let near = ev.eval(f as usize, 1e-9 + u * (1.0 - 3e-9), 1e-9 + v * (1.0 - 3e-9)).unwrap();
            assert!(near.normal.dot(s.normal) > 1.0 - 1e-4);
        }
    }
}

/// The numbers of a fixture's lines that are not comments.
fn rows(path: &std::path::Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect()
}

#[test]
fn regular_patches_equal_opensubdivs() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/loop_eval");
    for (case, mesh_path) in [
        ("torus", model_path("torus.obj")),
        ("torus_sheared", dir.join("torus_sheared.obj")),
        ("icosphere", dir.join("icosphere.obj")),
        // an open grid: the border faces are OpenSubdiv's regular boundary patches
        ("open_grid", dir.join("open_grid.obj")),
    ] {
        let (mesh, _) = load_with_attributes(&mesh_path);
        let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
        let points = rows(&dir.join(format!("{case}.points.txt")));
        let want = rows(&dir.join(format!("{case}.osd.txt")));
        assert_eq!(points.len(), want.len());
        assert!(points.len() >= 200);
        let size = f64::from(scale(&mesh));
        let mut worst = 0.0f64;
        for (pt, w) in points.iter().zip(&want) {
            let s = ev.eval(pt[0] as usize, pt[1], pt[2]).unwrap();
            let v = |i: usize| DVec3::new(w[3 * i], w[3 * i + 1], w[3 * i + 2]);
            for (i, got) in [s.position, s.du, s.dv, s.duu, s.duv, s.dvv].into_iter().enumerate() {
                // our control points are the file's numbers rounded to f32,
                // OpenSubdiv's the numbers in f64: 1e-7 of the size apart
                let tol = 2e-7 * (size + v(i).length());
                worst = worst.max((got - v(i)).length() / (size + v(i).length()));
                assert!((got - v(i)).length() <= tol, "{case} {pt:?} column {i}: {got:?} against {:?}", v(i));
            }
        }
        println!("{case}: worst relative difference {worst:e}");
    }
}

#[test]
fn every_refined_vertex_gets_the_limit_of_its_own_position() {
    // the exact limit at each vertex's parameter equals the limit mask
    // applied to that vertex of the refinement
    let mesh = bipyramid(5, 17);
    for levels in 0..=3 {
        let fine = subdivide(&mesh, Scheme::Loop, levels, &Options::default()).unwrap().0;
        let samples = subdiv::eval::vertex_samples(&mesh, &fine, Scheme::Loop, levels, &Options::default()).unwrap();
        let limits = loop_limit_positions_with(&fine, LoopBeta::Loop);
        for (s, l) in samples.iter().zip(&limits) {
            assert!((s.position - l.as_dvec3()).length() < 1e-5, "level {levels}");
        }
    }
}

#[test]
fn featured_faces_have_their_derivatives_and_meet_their_neighbours() {
    for (name, mesh, opts) in featured_meshes() {
        let ev = Evaluator::new(&mesh, Scheme::Loop, &opts).unwrap();
        let size = f64::from(scale(&mesh));
        check_derivatives(&ev, &random_points(&mesh, 2, 17), size, &name);
        across_edges(&mesh, &ev, |c, x, y| {
            assert!((x.position - y.position).length() < 1e-9 * size, "{name}: edge of corner {c}");
            // a crease that never decays is a fold; every other edge is smooth in the limit
            if mesh.ct.edge_sharpness(c) < subdiv::mesh::INFINITE {
                assert!(x.normal.dot(y.normal) > 1.0 - 1e-9, "{name}: normals across the edge of corner {c}");
            }
        });
    }
}

#[test]
fn one_point_at_a_time_equals_the_prepared_evaluator() {
    let mut meshes: Vec<(String, Mesh, Options)> = featured_meshes();
    meshes.extend(closed_meshes().into_iter().map(|(n, m)| (n, m, Options::default())));
    for (name, mesh, opts) in meshes {
        let ev = Evaluator::new(&mesh, Scheme::Loop, &opts).unwrap();
        let size = f64::from(scale(&mesh));
        for (f, u, v) in random_points(&mesh, 1, 23).into_iter().chain([(0, 0.0, 0.0), (0, 0.5, 0.5)]) {
            let (a, b) =
                (ev.eval(f, u, v).unwrap(), subdiv::eval::evaluate_one(&mesh, Scheme::Loop, &opts, (f, u, v)).unwrap());
            // the prepared evaluator's smooth faces use double-precision weights, the local path the rules' single ones
            assert!((a.position - b.position).length() < 1e-7 * size, "{name} face {f} ({u}, {v})");
            assert!(a.normal.dot(b.normal) > 1.0 - 1e-9, "{name} face {f} ({u}, {v})");
        }
    }
}

#[test]
fn grouped_evaluation_equals_one_point_at_a_time() {
    // eval_map groups the points by face and shares each level-1 face's
    // support and polynomial between them; eval builds them per point. An
    // icosphere (valences 5 and 6) and the bundled critter (fanned quads:
    // valences 3 to 9, smooth and local faces), many points per face, in
    // random order, a few right at a corner
    let critter = subdiv::bundled::load(std::path::Path::new("bundled:critter.obj")).unwrap();
    for mesh in [icosphere(2), critter] {
        let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
        let faces: Vec<usize> = (0..ev.num_faces()).filter(|&f| ev.accepts(f)).collect();
        let mut rng = Rng(0x9e3779b97f4a7c15);
        let mut next = || rng.unit();
        let points: Vec<(usize, f64, f64)> = (0..10 * faces.len())
            .map(|_| {
                let f = faces[(next() * faces.len() as f64) as usize % faces.len()];
                let (u, v) = (next(), next());
                if u < 0.01 {
                    (f, 0.0, 0.0)
                } else if u + v > 1.0 {
                    (f, 1.0 - u, 1.0 - v)
                } else {
                    (f, u, v)
                }
            })
            .collect();
        let bits = |a: DVec3| a.to_array().map(f64::to_bits);
        for second in [false, true] {
            let grouped = ev.eval_all(&points, second).unwrap();
            for (i, (&(f, u, v), g)) in points.iter().zip(&grouped).enumerate() {
                let one = if second { ev.eval(f, u, v) } else { ev.eval_first(f, u, v) }.unwrap();
                let at = || format!("point {i} {:?}", points[i]);
                assert_eq!((bits(g.position), bits(g.normal)), (bits(one.position), bits(one.normal)), "{}", at());
                assert_eq!((bits(g.du), bits(g.dv)), (bits(one.du), bits(one.dv)), "{}", at());
                assert_eq!(g.mean.to_bits(), one.mean.to_bits(), "{}", at());
            }
        }
    }
}

/// The faces of a perturbed level-2 icosphere above `z = -0.35`: an open
/// cap whose border has vertices of one to five faces.
fn icosphere_cap(seed: u64) -> Mesh {
    let s = icosphere(2);
    let mut rng = Rng(seed);
    let pos: Vec<Vec3> = s.positions.iter().map(|&p| p + (rng.vec3() - Vec3::splat(0.5)) * 0.2).collect();
    let tris: Vec<u32> =
        s.ct.v_table()
            .chunks_exact(3)
            .filter(|t| t.iter().all(|&v| pos[v as usize].z > -0.35))
            .flatten()
            .copied()
            .collect();
    Mesh::from_triangles(pos, &tris).unwrap()
}

/// Whether the limit surface has one tangent plane at vertex `v` seen
/// from its faces: not at an infinitely sharp vertex (a cone), a dart or
/// a corner of three or more infinitely sharp edges, nor at a border
/// vertex of more than six faces (the rules are not C1 there).
fn has_tangent_plane(mesh: &Mesh, v: u32) -> bool {
    let ct = &mesh.ct;
    let infinite = subdiv::mesh::INFINITE;
    let sharp_vertex = ct.sharpness().is_some_and(|s| s.vertex(v) >= infinite);
    let fan: Vec<u32> = ct.fan(v).collect();
    let sharp_edges = fan.iter().filter(|&&c| ct.edge_sharpness(subdiv::mesh::p(c)) >= infinite).count()
        + usize::from(ct.is_boundary_vertex(v));
    !sharp_vertex && (sharp_edges == 0 || sharp_edges == 2) && !(ct.is_boundary_vertex(v) && fan.len() > 6)
}

#[test]
fn every_corner_of_an_open_or_creased_mesh_has_a_finite_limit_normal() {
    let mut meshes = featured_meshes();
    for seed in 1..4 {
        meshes.push((format!("icosphere cap {seed}"), icosphere_cap(seed), Options::default()));
    }
    for (name, mesh, opts) in meshes {
        let ev = Evaluator::new(&mesh, Scheme::Loop, &opts).unwrap();
        let size = f64::from(scale(&mesh));
        for f in 0..mesh.ct.num_triangles() {
            for (i, (u, v)) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)].into_iter().enumerate() {
                let s = ev.eval(f, u, v).unwrap();
                assert!(s.position.is_finite() && s.normal.is_finite(), "{name} face {f} corner {i}: {s:?}");
                assert!((s.normal.length() - 1.0).abs() < 1e-12, "{name} face {f} corner {i}: not a unit normal");
                // inside the face, towards its centre: the same point and,
                // where the surface has a tangent plane, the same normal
                let (nu, nv) = (u + 1e-7 * (1.0 / 3.0 - u), v + 1e-7 * (1.0 / 3.0 - v));
                let near = ev.eval(f, nu, nv).unwrap();
                let vert = mesh.ct.vtx(3 * f as u32 + i as u32);
                assert!((near.position - s.position).length() < 1e-5 * size, "{name} face {f} corner {i}: position");
                if has_tangent_plane(&mesh, vert) {
                    let dot = near.normal.dot(s.normal);
                    assert!(dot > 1.0 - 1e-6, "{name} face {f} corner {i} (vertex {vert}): normals {dot}");
                }
            }
        }
    }
}
