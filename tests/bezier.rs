//! De Casteljau curves and bicubic patches, `.bzc` / `.bez` files
//! (schemes.md 10): the algorithm against the Bernstein form, interpolation
//! of corner control points, planarity, the bundled teapot, and fuzzed input.

mod common;
use common::*;
use glam::{Vec2, Vec3};
use subdiv::MeshError;
use subdiv::io::Topology;
use subdiv::io::bezier::{
    Patch, curve_polyline, de_casteljau, de_casteljau_step, parse_bez, parse_bzc, tessellate_raw,
};
use subdiv::mesh::RepairReport;
use subdiv::mesh::{check_invariants, topology};
use subdiv::{Error, Mesh};

/// The tessellation built as the reading pipeline builds it, `topology` deciding.
fn build(patches: &[Patch], n: u32, topology: Topology) -> Result<(Mesh, RepairReport), MeshError> {
    let raw = tessellate_raw(patches, n)?;
    match raw.build("t.bez", topology, false) {
        Ok((m, _, notes)) => Ok((m, notes.repair.unwrap_or_default())),
        Err(Error::Mesh { source, .. }) => Err(source),
        Err(other) => panic!("{other}"),
    }
}

fn tessellate(patches: &[Patch], n: u32) -> Result<Mesh, MeshError> {
    build(patches, n, Topology::Refuse).map(|(m, _)| m)
}

fn tessellate_repaired(patches: &[Patch], n: u32) -> Result<(Mesh, RepairReport), MeshError> {
    build(patches, n, Topology::Repair)
}

fn load_bez(path: &std::path::Path) -> subdiv::Result<Vec<Patch>> {
    parse_bez(&std::fs::read_to_string(path).unwrap(), &path.display().to_string())
}

fn load_bzc(path: &std::path::Path) -> subdiv::Result<Vec<Vec2>> {
    parse_bzc(&std::fs::read_to_string(path).unwrap(), &path.display().to_string())
}

fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// sum_i binom(n, i) (1 - t)^(n - i) t^i P_i, in f64.
fn bernstein(p: &[Vec3], t: f64) -> Vec3 {
    let n = p.len() - 1;
    p.iter()
        .enumerate()
        .map(|(i, q)| q.as_dvec3() * (binom(n, i) * (1.0 - t).powi((n - i) as i32) * t.powi(i as i32)))
        .sum::<glam::DVec3>()
        .as_vec3()
}

#[test]
fn de_casteljau_equals_the_bernstein_form() {
    let mut rng = Rng(42);
    for degree in 0..=8 {
        let p: Vec<Vec3> = (0..=degree).map(|_| rng.vec3() * 3.0).collect();
        for _ in 0..20 {
            let t = 0.5 + 0.5 * rng.next_f32();
            let a = de_casteljau(&p, t).unwrap();
            let b = bernstein(&p, f64::from(t));
            assert!(a.distance(b) < 1e-5, "degree {degree}, t = {t}: {a} vs {b}");
        }
        // endpoints interpolate
        assert!(de_casteljau(&p, 0.0).unwrap().distance(p[0]) < 1e-6);
        assert!(de_casteljau(&p, 1.0).unwrap().distance(p[degree]) < 1e-6);
        // repeated steps end at the same point
        let mut q = p.clone();
        while q.len() > 1 {
            q = de_casteljau_step(&q, 0.3);
        }
        assert!(q[0].distance(bernstein(&p, 0.3)) < 1e-5);
    }
}

fn random_patch(rng: &mut Rng) -> Patch {
    Patch { p: std::array::from_fn(|_| std::array::from_fn(|_| rng.vec3() * 2.0)) }
}

#[test]
fn patches_interpolate_corners_and_rows() {
    let mut rng = Rng(9);
    for _ in 0..10 {
        let pa = random_patch(&mut rng);
        let p = pa.p;
        for (u, v, want) in [(0.0, 0.0, p[0][0]), (1.0, 0.0, p[0][3]), (0.0, 1.0, p[3][0]), (1.0, 1.0, p[3][3])] {
            assert!(pa.eval(u, v).distance(want) < 1e-5, "corner ({u}, {v})");
        }
        for _ in 0..10 {
            let (u, v) = (0.5 + 0.5 * rng.next_f32(), 0.5 + 0.5 * rng.next_f32());
            // either order of the tensor product gives the same point
            assert!(pa.eval(u, v).distance(pa.eval_columns_first(u, v)) < 1e-5);
            // the v = 0 edge is the Bezier curve of row 0, the u = 0 edge that of column 0
            assert!(pa.eval(u, 0.0).distance(de_casteljau(&p[0], u).unwrap()) < 1e-5);
            let col0 = [p[0][0], p[1][0], p[2][0], p[3][0]];
            assert!(pa.eval(0.0, v).distance(de_casteljau(&col0, v).unwrap()) < 1e-5);
            // tensor product = sum of B_i(v) B_j(u) P_ij
            let rows: Vec<Vec3> = (0..4).map(|i| bernstein(&p[i], f64::from(u))).collect();
            assert!(pa.eval(u, v).distance(bernstein(&rows, f64::from(v))) < 1e-4);
        }
    }
}

/// Control points on a (tilted) plane give a planar, valid, consistently
/// oriented mesh with (n+1)^2 vertices and 2 n^2 triangles.
#[test]
fn a_flat_patch_tessellates_to_a_planar_mesh() {
    let (o, a, b) = (Vec3::new(1.0, -2.0, 0.5), Vec3::new(1.0, 0.2, 0.3), Vec3::new(-0.1, 1.0, 0.6));
    let nrm = a.cross(b).normalize();
    let mut rng = Rng(4);
    // an irregular grid of control points in the plane (not a bilinear patch)
    let p = std::array::from_fn(|i| {
        std::array::from_fn(|j| o + a * (j as f32 + 0.3 * rng.next_f32()) + b * (i as f32 + 0.3 * rng.next_f32()))
    });
    let n = 7;
    let mesh = tessellate(&[Patch { p }], n).unwrap();
    assert_eq!(mesh.positions.len(), ((n + 1) * (n + 1)) as usize);
    assert_eq!(mesh.ct.num_triangles(), (2 * n * n) as usize);
    check_invariants(&mesh.ct).unwrap();
    for q in &mesh.positions {
        assert!((*q - o).dot(nrm).abs() < 1e-5, "{q} is off the plane");
    }
    // faces counter-clockwise about S_u x S_v = a x b
    for f in subdiv::mesh::face_normals(&mesh.ct, &mesh.positions) {
        assert!(f.normalize().dot(nrm) > 0.999);
    }
}

/// Two patches sharing a row of control points weld along it.
#[test]
fn adjacent_patches_are_welded() {
    let mut rng = Rng(8);
    let first = random_patch(&mut rng);
    let mut second = random_patch(&mut rng);
    second.p[0] = first.p[3]; // first's v = 1 edge is second's v = 0 edge
    let n = 5;
    let raw = tessellate_raw(&[first, second], n).unwrap();
    assert_eq!(raw.positions.len(), ((n + 1) * (2 * n + 1)) as usize);
    let mesh = tessellate(&[first, second], n).unwrap();
    let topo = topology(&mesh.ct);
    assert_eq!((topo.components, topo.boundary_loops, topo.euler), (1, 1, 1));
}

#[test]
fn the_teapot_parses_and_tessellates() {
    let patches = load_bez(&model_path("teapot.bez")).unwrap();
    assert_eq!(patches.len(), 32);
    // first patch, first control point: 1.4 0 2.4 (Newell's data, Z up)
    assert_eq!(patches[0].p[0][0], Vec3::new(1.4, 0.0, 2.4));
    for n in [1, 4, 8] {
        let raw = tessellate_raw(&patches, n).unwrap();
        // welding: far fewer vertices than 32 separate grids
        assert!(raw.positions.len() < 32 * ((n + 1) * (n + 1)) as usize);
        let (mesh, _report) = tessellate_repaired(&patches, n).unwrap();
        check_invariants(&mesh.ct).unwrap();
        let (lo, hi) = mesh.bounds();
        // spout tip at x = 3.3 (patch 19), handle at x = -3, lid knob at z = 3.15, bottom at z = 0
        assert!(lo.z.abs() < 1e-5 && (hi.z - 3.15).abs() < 1e-3, "{lo} {hi}");
        assert!((lo.x + 3.0).abs() < 0.1 && hi.x > 3.2 && hi.x < 3.5, "{lo} {hi}");
        // the handle touches the body at one point: the direct build refuses it as a bowtie
        if n >= 4 {
            let e = tessellate(&patches, n).unwrap_err();
            assert!(matches!(e, MeshError::NonManifoldVertex { fans: 2, .. }), "{e}");
            let v = match e {
                MeshError::NonManifoldVertex { vertex, .. } => vertex as usize,
                _ => unreachable!(),
            };
            assert!(raw.positions[v].distance(Vec3::new(-2.0, 0.0, 0.9)) < 1e-6);
            // 4 components (body, lid, handle, spout) and nothing lost
            assert_eq!(topology(&mesh.ct).components, 4);
            assert_eq!(mesh.ct.num_triangles() * 3, raw.corners.len());
        }
    }
}

#[test]
fn the_bundled_curve_parses() {
    let pts = load_bzc(&model_path("curve.bzc")).unwrap();
    assert_eq!(pts.len(), 5);
    let line = curve_polyline(&pts, 16);
    assert_eq!(line.len(), 17);
    assert_eq!(line[0], pts[0]);
    assert!(line[16].distance(pts[4]) < 1e-6);
    // the curve stays in the convex hull, here the unit square
    assert!(line.iter().all(|q| q.cmpge(Vec2::ZERO).all() && q.cmple(Vec2::ONE).all()));
}

/// Mutated and random inputs give errors (with a line) or meshes, never a
/// panic; whatever parses tessellates and repairs without panicking.
#[test]
fn fuzzed_files_never_panic() {
    let teapot = std::fs::read_to_string(model_path("teapot.bez")).unwrap();
    let curve = std::fs::read_to_string(model_path("curve.bzc")).unwrap();
    let junk = ["nan", "inf", "-inf", "1e39", "-1", "0", "99999999999999999999", "abc", "", "3.", "-0", "1e-45", "#"];
    let mut rng = Rng(1234);
    let mut pick = |n: usize| ((rng.next_f32() * 0.5 + 0.5) * n as f32) as usize % n.max(1);
    let mut ok = 0;
    for round in 0..300 {
        for (src, is_bez) in [(&teapot, true), (&curve, false)] {
            let mut toks: Vec<String> = src.split_inclusive(char::is_whitespace).map(str::to_string).collect();
            match round % 5 {
                0 => {
                    let k = pick(toks.len());
                    toks[k] = format!("{} ", junk[pick(junk.len())]);
                }
                1 => toks.truncate(pick(toks.len())),
                2 => {
                    let k = pick(toks.len());
                    toks.remove(k);
                }
                3 => {
                    let k = pick(toks.len());
                    let t = toks[k].clone();
                    toks.insert(k, t);
                }
                _ => {
                    // byte garbage, lossily decoded
                    let bytes: Vec<u8> = (0..pick(200)).map(|_| pick(256) as u8).collect();
                    toks = vec![String::from_utf8_lossy(&bytes).into_owned()];
                }
            }
            let text: String = toks.concat();
            if is_bez {
                match parse_bez(&text, "fuzz.bez") {
                    Ok(p) => {
                        ok += 1;
                        let _ = tessellate_repaired(&p, 2);
                        let _ = tessellate(&p, 2);
                    }
                    Err(e) => assert!(e.to_string().starts_with("fuzz.bez:"), "{e}"),
                }
            } else {
                match parse_bzc(&text, "fuzz.bzc") {
                    Ok(p) => {
                        ok += 1;
                        let _ = curve_polyline(&p, 8);
                    }
                    Err(e) => assert!(e.to_string().starts_with("fuzz.bzc:"), "{e}"),
                }
            }
        }
    }
    assert!(ok > 0, "no mutant parsed: the mutations are too destructive to test tessellation");
    // huge counts are refused before allocating
    assert!(parse_bez("4000000000\n1 2 3", "x.bez").is_err());
    assert!(parse_bzc("18446744073709551615 0 0", "x.bzc").is_err());
}

#[test]
fn absurd_resolutions_are_refused() {
    let patches = load_bez(&model_path("teapot.bez")).unwrap();
    assert!(matches!(tessellate_raw(&patches, u32::MAX), Err(MeshError::TooManyElements { .. })));
    assert!(matches!(tessellate_raw(&patches, 100_000), Err(MeshError::TooManyElements { .. })));
    assert!(matches!(tessellate_raw(&[], 4), Err(MeshError::Empty)));
    // 0 segments means 1
    assert_eq!(tessellate_raw(&patches[..1], 0).unwrap(), tessellate_raw(&patches[..1], 1).unwrap());
}
