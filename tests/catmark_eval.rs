//! Exact Catmull-Clark limit evaluation (`subdiv::eval`, ptex faces)
//! against independent truths: the limit masks of the level-4 refinement at
//! the dyadic points of levels 0 to 4 (subdivision and masks, not the
//! evaluator), finite differences of positions for the derivatives, and
//! continuity across the edges between quads.

mod common;

use glam::DVec3;
use std::path::PathBuf;
use subdiv::Evaluator;
use subdiv::eval::frames_at;
use subdiv::eval::{QUAD, ptex_faces};
use subdiv::mesh::PolyMesh;
use subdiv::mesh::{BoundaryInterpolation, Creasing};
use subdiv::{Mesh, Options, Scheme, subdivide};

fn load(name: &str) -> PolyMesh {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark").join(name);
    PolyMesh::from_mesh(&subdiv::bundled::load(&path).unwrap_or_else(|e| panic!("{name}: {e}")))
}

/// The fixture meshes (scripts/catmark-fixtures.py): smooth, creased
/// (infinite, semi-sharp, a corner), open both ways, n-gons. No dart: the
/// mask the truth would use there is not the limit of the dart's rules.
fn cases() -> Vec<(&'static str, PolyMesh, Options)> {
    let d = Options::default;
    vec![
        ("cube", load("cube.obj"), d()),
        ("cube_creases", load("cube_creases.obj"), d()),
        ("cube_creases chaikin", load("cube_creases.obj"), Options { creasing: Creasing::Chaikin, ..d() }),
        ("grid", load("grid.obj"), d()),
        ("grid corners", load("grid.obj"), Options { boundary: BoundaryInterpolation::EdgeAndCorner, ..d() }),
        ("ngons", load("ngons.obj"), d()),
    ]
}

fn size(m: &PolyMesh) -> f64 {
    let (mut lo, mut hi) = (DVec3::MAX, DVec3::MIN);
    for p in &m.positions {
        lo = lo.min(p.as_dvec3());
        hi = hi.max(p.as_dvec3());
    }
    (hi - lo).length()
}

/// The quadrant of `(u, v)` and the child's `(s, t)` (the split makes quad
/// `c` of corner `c`: vertex, edge leaving, face point, edge entering).
fn quadrant(u: f64, v: f64) -> (u32, f64, f64) {
    match (u > 0.5, v > 0.5) {
        (false, false) => (0, 2.0 * u, 2.0 * v),
        (true, false) => (1, 2.0 * v, 2.0 - 2.0 * u),
        (true, true) => (2, 2.0 - 2.0 * u, 2.0 - 2.0 * v),
        (false, true) => (3, 2.0 - 2.0 * v, 2.0 * u),
    }
}

/// The vertex at the dyadic point `(u, v)` of ptex face `(f, corner)`, by
/// the split's numbering through `levels` (levels[0] the control mesh).
fn vertex_at(levels: &[PolyMesh], (f, corner): (u32, u32), mut u: f64, mut v: f64, k: usize) -> u32 {
    let (mut face, mut at) = match corner {
        u32::MAX => (f, 0),
        c => (levels[0].pt.face_corners(f).start + c, 1),
    };
    for _ in 0..k {
        let (q, s, t) = quadrant(u, v);
        face = levels[at].pt.face_corners(face).start + q;
        (u, v, at) = (s, t, at + 1);
    }
    let corner = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].iter().position(|&c| c == (u, v)).expect("a corner");
    levels[at].pt.vtx(levels[at].pt.face_corners(face).start + corner as u32)
}

#[test]
fn dyadic_points_are_the_limits_of_subdivided_vertices() {
    for (name, poly, opts) in cases() {
        let mesh: Mesh = poly.triangulated();
        let ev = Evaluator::new(&mesh, Scheme::CatmullClark, &opts).unwrap();
        let ptex = ptex_faces(&poly.pt);
        assert_eq!(ev.num_faces(), ptex.len(), "{name}: the evaluator's faces are the ptex faces");
        let mut levels = vec![poly.clone()];
        for _ in 0..5 {
            levels.push(subdivide(levels.last().unwrap(), Scheme::CatmullClark, 1, &opts).unwrap().0);
        }
        let fine = &levels[5];
        let limits = frames_at(&fine.pt, &fine.positions, opts.creasing);
        let mut worst = 0.0f64;
        for (p, &face) in ptex.iter().enumerate() {
            for k in 0..=4usize {
                let d = f64::from(1u32 << k);
                for i in 0..=(1u32 << k) {
                    for j in 0..=(1u32 << k) {
                        let (u, v) = (f64::from(i) / d, f64::from(j) / d);
                        let want = limits[vertex_at(&levels, face, u, v, k) as usize].position.as_dvec3();
                        let got = ev.eval(p, u, v).unwrap().position;
                        worst = worst.max((got - want).length() / size(&poly));
                    }
                }
            }
        }
        // the reference is computed in f32
        assert!(worst < 2e-6, "{name}: worst relative distance {worst:e}");
    }
}

fn random_points(n: usize, per_face: usize, seed: u64) -> Vec<(usize, f64, f64)> {
    let mut rng = common::Rng(seed);
    let mut out = Vec::new();
    for p in 0..n {
        for _ in 0..per_face {
            let (a, b) = (f64::from(rng.next_f32()) * 0.5 + 0.5, f64::from(rng.next_f32()) * 0.5 + 0.5);
            out.push((p, 0.02 + 0.96 * a, 0.02 + 0.96 * b));
        }
    }
    out
}

#[test]
fn derivatives_match_finite_differences() {
    let h = 1e-5;
    for (name, poly, opts) in cases() {
        let ev = Evaluator::new(&poly.triangulated(), Scheme::CatmullClark, &opts).unwrap();
        let size = size(&poly);
        for (p, u, v) in random_points(ev.num_faces(), 3, 7) {
            let s = ev.eval(p, u, v).unwrap();
            let at = |du: f64, dv: f64| ev.eval(p, u + du, v + dv).unwrap();
            let (pu, mu, pv, mv) = (at(h, 0.0), at(-h, 0.0), at(0.0, h), at(0.0, -h));
            let close = |a: DVec3, b: DVec3, tol: f64| (a - b).length() <= tol * (size + b.length());
            let (du, dv) = ((pu.position - mu.position) / (2.0 * h), (pv.position - mv.position) / (2.0 * h));
            assert!(close(s.du, du, 1e-6) && close(s.dv, dv, 1e-6), "{name} ptex {p} ({u}, {v}): first derivatives");
            let (duu, duv, dvv) =
                ((pu.du - mu.du) / (2.0 * h), (pv.du - mv.du) / (2.0 * h), (pv.dv - mv.dv) / (2.0 * h));
            assert!(
                close(s.duu, duu, 1e-4) && close(s.duv, duv, 1e-4) && close(s.dvv, dvv, 1e-4),
                "{name} ptex {p} ({u}, {v}): second derivatives"
            );
            assert!(s.du.cross(s.dv).normalize().dot(s.normal) > 1.0 - 1e-12);
        }
    }
}

#[test]
fn quads_meet_their_neighbours_with_one_tangent_plane() {
    let param = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    for (name, poly, opts) in cases().into_iter().filter(|c| c.1.pt.is_quads()) {
        let ev = Evaluator::new(&poly.triangulated(), Scheme::CatmullClark, &opts).unwrap();
        let pt = &poly.pt;
        for c in 0..pt.num_corners() as u32 {
            let Some(x) = pt.twin(c) else { continue };
            let (f, g) = (pt.face(c), pt.face(x));
            let (i, j) = ((c % 4) as usize, (x % 4) as usize);
            for t in [0.2, 0.5, 0.9] {
                // the edge leaves corner i of f and, reversed, corner j of g
                let on = |k: usize, t: f64| {
                    let (a, b) = (param[k], param[(k + 1) % 4]);
                    (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
                };
                let ((uf, vf), (ug, vg)) = (on(i, t), on(j, 1.0 - t));
                let (a, b) = (ev.eval(f as usize, uf, vf).unwrap(), ev.eval(g as usize, ug, vg).unwrap());
                assert!((a.position - b.position).length() < 1e-9 * size(&poly), "{name}: edge of corner {c} at {t}");
                if pt.sharpness().is_none_or(|s| s.corner(c) < subdiv::mesh::INFINITE) {
                    assert!(a.normal.dot(b.normal) > 1.0 - 1e-9, "{name}: normals across corner {c}'s edge at {t}");
                }
            }
        }
    }
}

#[test]
fn bad_points_are_refused() {
    let poly = load("ngons.obj");
    let ev = Evaluator::new(&poly.triangulated(), Scheme::CatmullClark, &Options::default()).unwrap();
    let n = ev.num_faces();
    assert!(ev.eval(n, 0.5, 0.5).unwrap_err().to_string().contains("out of range"));
    for (u, v) in [(-0.1, 0.5), (0.5, 1.1), (f64::NAN, 0.5)] {
        assert!(ev.eval(0, u, v).is_err(), "({u}, {v})");
    }
    assert!(ev.eval(0, 1.0, 1.0).is_ok());
    let e = Evaluator::new(&poly.triangulated(), Scheme::Bilinear, &Options::default()).err().expect("refused");
    assert!(e.to_string().contains("bilinear"), "{e}");
}

/// `text` (an OBJ) with every face listed from its corner `r` (mod its size).
fn rotated_faces(text: &str, r: usize) -> String {
    let mut out = String::new();
    for line in text.lines() {
        match line.strip_prefix("f ") {
            Some(rest) => {
                let ids: Vec<&str> = rest.split_whitespace().collect();
                let k = r % ids.len();
                out.push_str(&format!("f {} {}\n", ids[k..].join(" "), ids[..k].join(" ")));
            }
            None => out.push_str(&format!("{line}\n")),
        }
    }
    out
}

/// `(u, v)` of a quad's ptex face listed from corner `r` of the first
/// listing, in the first listing's parameters (corner `i` of the new one
/// is corner `i + r` of the old: `(0,0) -> corner r`).
fn unrotate(r: usize, (mut u, mut v): (f64, f64)) -> (f64, f64) {
    for _ in 0..r % 4 {
        (u, v) = (1.0 - v, u);
    }
    (u, v)
}

#[test]
fn ptex_parameters_follow_the_files_corner_order() {
    let fixtures = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark");
    let params = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.3, 0.1), (0.8, 0.45)];
    for name in ["cube.obj", "ngons.obj", "grid.obj"] {
        let text = std::fs::read_to_string(fixtures.join(name)).unwrap();
        let first = common::mesh_of(text.as_bytes(), name).unwrap();
        let ptex = ptex_faces(&PolyMesh::from_mesh(&first).pt);
        let reference = Evaluator::new(&first, Scheme::CatmullClark, &Options::default()).unwrap();
        // corner 0 of every quad as the file lists it is its ptex (0, 0):
        // the limit there is nearer that control vertex than the others'
        let faces: Vec<Vec<usize>> = text
            .lines()
            .filter_map(|l| l.strip_prefix("f "))
            .map(|l| l.split_whitespace().map(|t| t.parse::<usize>().unwrap() - 1).collect())
            .collect();
        let mut next_ptex = 0;
        for face in &faces {
            if face.len() == 4 {
                let at = reference.eval(next_ptex, 0.0, 0.0).unwrap().position.as_vec3();
                let d = |i: usize| (first.positions[face[i]] - at).length();
                assert!((1..4).all(|i| d(0) < d(i)), "{name} ptex {next_ptex}: (0, 0) is not at its first corner");
            }
            next_ptex += if face.len() == 4 { 1 } else { face.len() };
        }
        // the same faces listed from every other corner: the same surface,
        // its parameters turned with the listing
        for r in 1..6 {
            let mesh = common::mesh_of(rotated_faces(&text, r).as_bytes(), name).unwrap();
            let ev = Evaluator::new(&mesh, Scheme::CatmullClark, &Options::default()).unwrap();
            assert_eq!(ev.num_faces(), ptex.len());
            for (p, &(f, k)) in ptex.iter().enumerate() {
                let n = faces[f as usize].len();
                for &uv in &params {
                    let (q, (u, v)) = if n == 4 {
                        (p, unrotate(r, uv))
                    } else {
                        // ptex k of the new listing is corner k + r of the old
                        let k_old = (k as usize + r) % n;
                        (p - k as usize + k_old, uv)
                    };
                    let (a, b) = (ev.eval(p, uv.0, uv.1).unwrap(), reference.eval(q, u, v).unwrap());
                    assert!(
                        (a.position - b.position).length() < 1e-9 && a.normal.dot(b.normal) > 1.0 - 1e-9,
                        "{name} listed from corner {r}: ptex {p} at {uv:?} is not the first listing's ptex {q} at ({u}, {v})"
                    );
                }
            }
        }
    }
}

/// OpenSubdiv's limit normals (`tan1 x tan2`) at the control vertices of
/// a limit fixture of level 1 (scripts/osd-fvar-limit-fixtures.py), found
/// by their level-1 positions (a control vertex keeps its id).
fn osd_normals(poly: &PolyMesh, opts: &Options, fixture: &str) -> Vec<DVec3> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark").join(fixture);
    let text = std::fs::read_to_string(&path).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .filter_map(|l| l.strip_prefix("l "))
        .map(|l| l.split_whitespace().map(|t| t.parse().unwrap()).collect())
        .collect();
    let (fine, _) = subdivide(poly, Scheme::CatmullClark, 1, opts).unwrap();
    (0..poly.positions.len())
        .map(|v| {
            let p = fine.positions[v].as_dvec3();
            let r = rows.iter().find(|r| (DVec3::new(r[0], r[1], r[2]) - p).abs().max_element() < 1e-5).unwrap();
            let (t1, t2) = (DVec3::new(r[6], r[7], r[8]), DVec3::new(r[9], r[10], r[11]));
            t1.cross(t2).normalize()
        })
        .collect()
}

#[test]
fn every_corner_of_an_open_or_creased_mesh_has_a_finite_limit_normal() {
    let truth = [("grid", "grid.limit.uniform.L1.osd.txt"), ("grid corners", "grid.limit.corners.L1.osd.txt")];
    for (name, poly, opts) in cases() {
        let ev = Evaluator::new(&poly.triangulated(), Scheme::CatmullClark, &opts).unwrap();
        let osd = truth.iter().find(|t| t.0 == name).map(|t| osd_normals(&poly, &opts, t.1));
        let ptex = ptex_faces(&poly.pt);
        let size = size(&poly);
        for (p, &(f, k)) in ptex.iter().enumerate() {
            let corners: Vec<u32> = poly.pt.face_corners(f).collect();
            for (i, (u, v)) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)].into_iter().enumerate() {
                let s = ev.eval(p, u, v).unwrap();
                assert!(s.position.is_finite() && s.normal.is_finite(), "{name} ptex {p} ({u}, {v}): {s:?}");
                assert!((s.normal.length() - 1.0).abs() < 1e-12, "{name} ptex {p} ({u}, {v}): not a unit normal");
                let near = ev.eval(p, u + 1e-7 * (0.5 - u), v + 1e-7 * (0.5 - v)).unwrap();
                assert!((near.position - s.position).length() < 1e-5 * size, "{name} ptex {p} ({u}, {v}): position");
                // on the open grids, at every control vertex: OpenSubdiv's
                // limit normal (its tangent masks)
                let vertex = match k {
                    QUAD => Some(corners[i]),
                    _ => (i == 0).then_some(corners[k as usize]),
                };
                if let (Some(osd), Some(c)) = (&osd, vertex) {
                    let want = osd[poly.pt.vtx(c) as usize];
                    assert!(s.normal.dot(want) > 1.0 - 1e-9, "{name} ptex {p} ({u}, {v}): {} against {want}", s.normal);
                }
            }
        }
    }
}

/// The exact limit at every vertex of a Catmull-Clark level (what the
/// curvature colours evaluate: `eval::poly_vertex_params` follows the quad
/// split's layout to each vertex's ptex face and `(u, v)`) is the limit of
/// that vertex: the limit masks of the level (refined on where a semi-sharp
/// feature is left), on quads and n-gons, closed, open and creased. The
/// level is the triangulated one `subdivide` gives, as `render` draws it,
/// and the same when made in two steps, as the viewer makes a level
/// through its proxy.
#[test]
fn every_vertex_of_a_level_is_evaluated_at_its_own_limit() {
    use subdiv::eval::limit_frames;
    use subdiv::eval::{poly_vertex_params, vertex_samples};
    for (name, poly, opts) in cases() {
        let mesh: Mesh = poly.triangulated();
        let size = size(&poly);
        for levels in 0..=3 {
            let fine = subdiv::subdivide(&mesh, Scheme::CatmullClark, levels, &opts).unwrap().0;
            if levels >= 2 {
                let one = subdiv::subdivide(&mesh, Scheme::CatmullClark, 1, &opts).unwrap().0;
                let two_steps = subdiv::subdivide(&one, Scheme::CatmullClark, levels - 1, &opts).unwrap().0;
                assert_eq!(two_steps.ct.v_table(), fine.ct.v_table(), "{name} L{levels}: the same quads in two steps");
            }
            let params = poly_vertex_params(&poly.pt, &fine.ct, levels).unwrap();
            assert!(params.iter().all(|&(p, u, v)| p < ptex_faces(&poly.pt).len()
                && (0.0..=1.0).contains(&u)
                && (0.0..=1.0).contains(&v)));
            let samples = vertex_samples(&mesh, &fine, Scheme::CatmullClark, levels, &opts).unwrap();
            let level = subdivide(&poly, Scheme::CatmullClark, levels, &opts).unwrap().0;
            let limits = limit_frames(&level, &opts).unwrap();
            assert_eq!((samples.len(), limits.len()), (fine.positions.len(), fine.positions.len()));
            let mut worst = 0.0f64;
            for (s, l) in samples.iter().zip(&limits) {
                worst = worst.max((s.position - l.position.as_dvec3()).length() / size);
            }
            // the level and its masks are computed in f32
            assert!(worst < 2e-6, "{name} L{levels}: worst relative distance {worst:e}");
        }
        // a table that is not such a level is refused
        let other = subdiv::subdivide(&mesh, Scheme::CatmullClark, 2, &opts).unwrap().0;
        assert!(poly_vertex_params(&poly.pt, &other.ct, 1).is_err(), "{name}");
    }
}
