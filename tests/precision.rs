//! Double precision, the caller's choice: a bipyramid a million units from
//! the origin (where f32's spacing is 0.06) subdivided in f64 equals the
//! textbook rules computed here independently in f64 (midpoint, Loop,
//! modified butterfly), the interpolating schemes keep the control vertices
//! bit for bit, the f64 topology is the f32 one, and `subdivide --precision
//! f64` writes OBJ and PLY that read back to the same doubles.

mod common;

use glam::DVec3;
use std::collections::HashMap;
use std::f64::consts::PI;
use subdiv::{Mesh, Options, Scheme};

/// A closed bipyramid over a pentagon: apexes of valence 5, equator
/// vertices of valence 4, irregular coordinates, centred at `c`.
fn bipyramid(c: f64) -> (Vec<DVec3>, Vec<[usize; 3]>) {
    let n = 5;
    let mut v: Vec<DVec3> = (0..n)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / n as f64;
            DVec3::new(0.7 * a.cos() + 0.01 * k as f64, 0.7 * a.sin(), 0.012_345_678_9 * k as f64)
        })
        .collect();
    v.push(DVec3::new(0.01, -0.02, 1.1));
    v.push(DVec3::new(0.0, 0.03, -0.9));
    let f = (0..n).flat_map(|k| [[k, (k + 1) % n, n], [(k + 1) % n, k, n + 1]]).collect();
    (v.into_iter().map(|p| p + DVec3::splat(c)).collect(), f)
}

/// The textbook rules, one level of a closed triangle mesh, in f64.
#[derive(Clone, Copy, Debug)]
enum Textbook {
    Midpoint,
    Loop,
    ModifiedButterfly,
}

/// The neighbours of `a` in order around it, starting at `b`.
fn ring(f: &[[usize; 3]], a: usize, b: usize) -> Vec<usize> {
    let next = |x: usize| -> usize {
        // the face with the directed edge (a, x) has its third corner next
        let t = f.iter().find(|t| (0..3).any(|i| t[i] == a && t[(i + 1) % 3] == x)).unwrap();
        let i = (0..3).find(|&i| t[i] == a).unwrap();
        t[(i + 2) % 3]
    };
    let mut out = vec![b];
    let mut x = next(b);
    while x != b {
        out.push(x);
        x = next(x);
    }
    out
}

/// Zorin's extraordinary-vertex stencil of edge (a, b) from a's side.
fn ev(v: &[DVec3], f: &[[usize; 3]], a: usize, b: usize) -> DVec3 {
    let r = ring(f, a, b);
    let k = r.len();
    let s = |j: usize| -> f64 {
        match k {
            3 => [5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0][j],
            4 => [3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0][j],
            _ => {
                let t = 2.0 * PI * j as f64 / k as f64;
                (0.25 + t.cos() + 0.5 * (2.0 * t).cos()) / k as f64
            }
        }
    };
    v[a] * 0.75 + (0..k).map(|j| v[r[j]] * s(j)).sum::<DVec3>()
}

fn edge_point(rule: Textbook, v: &[DVec3], f: &[[usize; 3]], (a, b): (usize, usize)) -> DVec3 {
    let (ra, rb) = (ring(f, a, b), ring(f, b, a));
    match rule {
        Textbook::Midpoint => (v[a] + v[b]) * 0.5,
        Textbook::Loop => (v[a] + v[b]) * 0.375 + (v[ra[1]] + v[rb[1]]) * 0.125,
        Textbook::ModifiedButterfly => match (ra.len() == 6, rb.len() == 6) {
            (true, true) => {
                // the wings: across the outer edges of faces (a, b, c) and (b, a, d)
                let (c, d) = (ra[1], rb[1]);
                let across = |x: usize, y: usize| ring(f, x, y)[1];
                let w = [across(a, c), across(c, b), across(d, a), across(b, d)];
                (v[a] + v[b]) * 0.5 + (v[c] + v[d]) * 0.125 - w.iter().map(|&x| v[x]).sum::<DVec3>() * 0.0625
            }
            (false, true) => ev(v, f, a, b),
            (true, false) => ev(v, f, b, a),
            (false, false) => (ev(v, f, a, b) + ev(v, f, b, a)) * 0.5,
        },
    }
}

fn vertex_point(rule: Textbook, v: &[DVec3], f: &[[usize; 3]], a: usize) -> DVec3 {
    let Textbook::Loop = rule else { return v[a] };
    let b = f.iter().find_map(|t| (0..3).find(|&i| t[i] == a).map(|i| t[(i + 1) % 3])).unwrap();
    let r = ring(f, a, b);
    let n = r.len() as f64;
    let beta = (0.625 - (0.375 + 0.25 * (2.0 * PI / n).cos()).powi(2)) / n;
    v[a] * (1.0 - n * beta) + r.iter().map(|&x| v[x]).sum::<DVec3>() * beta
}

fn textbook_level(rule: Textbook, v: &[DVec3], f: &[[usize; 3]]) -> (Vec<DVec3>, Vec<[usize; 3]>) {
    let mut out: Vec<DVec3> = (0..v.len()).map(|a| vertex_point(rule, v, f, a)).collect();
    let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
    let mut faces = Vec::new();
    for t in f {
        let mut m = [0; 3];
        for i in 0..3 {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            m[i] = *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                out.push(edge_point(rule, v, f, (a, b)));
                out.len() - 1
            });
        }
        faces.extend([[t[0], m[0], m[2]], [m[0], t[1], m[1]], [m[2], m[1], t[2]], [m[0], m[1], m[2]]]);
    }
    (out, faces)
}

/// The worst distance from each of `ours` to the nearest of `theirs`.
fn worst(ours: &[DVec3], theirs: &[DVec3]) -> f64 {
    ours.iter().map(|p| theirs.iter().map(|q| p.distance(*q)).fold(f64::INFINITY, f64::min)).fold(0.0, f64::max)
}

fn mesh_of(v: &[DVec3], f: &[[usize; 3]]) -> Mesh {
    let tris: Vec<u32> = f.iter().flatten().map(|&i| i as u32).collect();
    Mesh::from_triangles(v.iter().map(|p| p.as_vec3()).collect(), &tris).unwrap()
}

#[test]
fn far_from_the_origin_double_precision_equals_the_textbook_rules() {
    let (v, f) = bipyramid(1e6);
    let mesh = mesh_of(&v, &f);
    for (scheme, rule) in [
        (Scheme::Midpoint, Textbook::Midpoint),
        (Scheme::Loop, Textbook::Loop),
        (Scheme::ModifiedButterfly, Textbook::ModifiedButterfly),
    ] {
        let (ours_mesh, ours) = subdiv::subdivide_f64(&mesh, &v, scheme, 2, &Options::default()).unwrap();
        let (v1, f1) = textbook_level(rule, &v, &f);
        let (theirs, f2) = textbook_level(rule, &v1, &f1);
        assert_eq!((ours.len(), ours_mesh.ct.num_triangles()), (theirs.len(), f2.len()), "{scheme}: counts");
        let (a, b) = (worst(&ours, &theirs), worst(&theirs, &ours));
        assert!(a < 1e-9 && b < 1e-9, "{scheme}: {a:e} / {b:e} from the textbook rules in f64");
        // single precision cannot: the same level in f32 is far off
        let (single, _) = subdiv::subdivide(&mesh, scheme, 2, &Options::default()).unwrap();
        let s: Vec<DVec3> = single.positions.iter().map(|p| p.as_dvec3()).collect();
        assert!(worst(&s, &theirs) > 1e-3, "{scheme}: f32 is as good as f64 here?");
    }
}

#[test]
fn interpolating_schemes_keep_the_control_vertices_bit_for_bit() {
    let (v, f) = bipyramid(1e6 + 0.123_456_789_012);
    let mesh = mesh_of(&v, &f);
    for scheme in [Scheme::Midpoint, Scheme::Butterfly, Scheme::ModifiedButterfly] {
        let (_, fine) = subdiv::subdivide_f64(&mesh, &v, scheme, 3, &Options::default()).unwrap();
        assert_eq!(&fine[..v.len()], &v[..], "{scheme}");
    }
}

#[test]
fn the_double_precision_levels_are_the_single_precision_levels_in_f64() {
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark/tagged.obj");
    let loaded = subdiv::io::read(subdiv::io::Source::File(&file), &Default::default()).unwrap();
    let precise = loaded.precise.expect("OBJ keeps its digits");
    let (mesh, opts) =
        (loaded.mesh, Options { boundary: subdiv::mesh::BoundaryInterpolation::EdgeAndCorner, ..Default::default() });
    let poly = subdiv::mesh::PolyMesh::from_mesh(&mesh);
    for scheme in Scheme::TRIANGLE.into_iter().chain(Scheme::POLYGON) {
        let (single, double): (Vec<glam::Vec3>, Vec<DVec3>) = if scheme.is_polygonal() {
            let (s, _) = subdiv::subdivide(&poly, scheme, 2, &opts).unwrap();
            let (d, p) = subdiv::subdivide_f64(&poly, &precise, scheme, 2, &opts).unwrap();
            assert_eq!(s.pt.v_table(), d.pt.v_table(), "{scheme}: faces");
            (s.positions, p)
        } else {
            let (s, _) = subdiv::subdivide(&mesh, scheme, 2, &opts).unwrap();
            let (d, p) = subdiv::subdivide_f64(&mesh, &precise, scheme, 2, &opts).unwrap();
            assert_eq!(s.ct.v_table(), d.ct.v_table(), "{scheme}: faces");
            (s.positions, p)
        };
        assert_eq!(single.len(), double.len(), "{scheme}: vertices");
        let far = single.iter().zip(&double).map(|(s, d)| s.as_dvec3().distance(*d)).fold(0.0, f64::max);
        assert!(far < 1e-5, "{scheme}: the f64 level is {far} from the f32 one");
    }
}

/// The `v` records of an OBJ in f64.
#[cfg(feature = "cli")]
fn obj_points(text: &str) -> Vec<DVec3> {
    let num = |l: &str| -> Vec<f64> { l.split_whitespace().map(|x| x.parse().unwrap()).collect() };
    text.lines().filter_map(|l| l.strip_prefix("v ")).map(|l| DVec3::from_slice(&num(l))).collect()
}

/// The vertices of a binary little-endian PLY whose x, y, z are doubles.
#[cfg(feature = "cli")]
fn ply_points(bytes: &[u8]) -> Vec<DVec3> {
    let end = bytes.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let header = std::str::from_utf8(&bytes[..end]).unwrap();
    assert!(header.contains("property double x\nproperty double y\nproperty double z\n"), "{header}");
    let n: usize = header.lines().find_map(|l| l.strip_prefix("element vertex ")).unwrap().parse().unwrap();
    let d = |k: usize| f64::from_le_bytes(bytes[end + 8 * k..end + 8 * k + 8].try_into().unwrap());
    (0..n).map(|i| DVec3::new(d(3 * i), d(3 * i + 1), d(3 * i + 2))).collect()
}

#[test]
#[cfg(feature = "cli")]
fn subdivide_with_double_precision_writes_obj_and_ply_that_read_back_to_the_same_doubles() {
    let dir = common::scratch_dir("precision");
    let (v, f) = bipyramid(1e6);
    let input = dir.join("far.obj");
    let mut text: String = v.iter().map(|p| format!("v {:?} {:?} {:?}\n", p.x, p.y, p.z)).collect();
    text += &f.iter().map(|t| format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1)).collect::<String>();
    std::fs::write(&input, text).unwrap();
    let (_, expected) = subdiv::subdivide_f64(&mesh_of(&v, &f), &v, Scheme::Loop, 2, &Options::default()).unwrap();
    let run = |out: &str, precision: &str| {
        let path = dir.join(out);
        let st = std::process::Command::new(env!("CARGO_BIN_EXE_subdiv"))
            .args(["subdivide", input.to_str().unwrap(), path.to_str().unwrap(), "-s", "loop", "-n", "2"])
            .args(["--precision", precision])
            .output()
            .unwrap();
        assert!(st.status.success(), "{}", String::from_utf8_lossy(&st.stderr));
        std::fs::read(&path).unwrap()
    };
    assert_eq!(obj_points(&String::from_utf8(run("d.obj", "f64")).unwrap()), expected, "OBJ");
    assert_eq!(ply_points(&run("d.ply", "f64")), expected, "PLY");
    // the default, f32, is not
    let single = obj_points(&String::from_utf8(run("s.obj", "f32")).unwrap());
    assert!(worst(&single, &expected) > 1e-3, "f32 output as exact as f64's?");
    // Catmull-Clark's quads, through the polygon writer
    let path = dir.join("cc.obj");
    let st = std::process::Command::new(env!("CARGO_BIN_EXE_subdiv"))
        .args(["subdivide", input.to_str().unwrap(), path.to_str().unwrap(), "-s", "catmull-clark", "-n", "1"])
        .args(["--precision", "f64"])
        .output()
        .unwrap();
    assert!(st.status.success(), "{}", String::from_utf8_lossy(&st.stderr));
    let text = std::fs::read_to_string(&path).unwrap();
    let poly = subdiv::mesh::PolyMesh::from_mesh(&mesh_of(&v, &f));
    let (fine, quads) = subdiv::subdivide_f64(&poly, &v, Scheme::CatmullClark, 1, &Options::default()).unwrap();
    assert_eq!(obj_points(&text), quads, "Catmull-Clark's OBJ");
    assert_eq!(
        text.lines().filter(|l| l.starts_with("f ") && l.split_whitespace().count() == 5).count(),
        fine.pt.num_faces()
    );
}

/// A planar grid of `n` x `n` vertices, an affine image of the integer
/// lattice a million units out: triangles (two per cell) or quads.
fn affine_grid(n: usize, quads: bool) -> (Vec<DVec3>, Vec<u32>) {
    let c = DVec3::splat(1e6) + DVec3::new(0.123_456_789, -0.987_654_321, 0.5);
    let (a, b) = (DVec3::new(0.7, -0.2, 0.13), DVec3::new(0.31, 0.9, 0.05));
    let v = (0..n * n).map(|k| c + a * (k % n) as f64 + b * (k / n) as f64).collect();
    let id = |i: usize, j: usize| (j * n + i) as u32;
    let mut f = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let (p, q, r, s) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            f.extend(if quads { vec![p, q, r, s] } else { vec![p, q, r, p, r, s] });
        }
    }
    (v, f)
}

#[test]
fn exact_evaluation_of_double_control_points_is_exact_to_1e_12_relative() {
    // on regular patches an affine control net's limit is the same affine
    // map (linear precision), so the exact value is known in closed form
    let (v, tris) = affine_grid(9, false);
    let mesh = Mesh::from_triangles(v.iter().map(|p| p.as_vec3()).collect(), &tris).unwrap();
    let ev = subdiv::Evaluator::new_f64(&mesh, &v, Scheme::Loop, &Options::default()).unwrap();
    let single = subdiv::Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
    let interior =
        |t: usize| tris[3 * t..3 * t + 3].iter().all(|&x| (2..7).contains(&(x % 9)) && (2..7).contains(&(x / 9)));
    let (mut worst64, mut worst32) = (0.0f64, 0.0f64);
    for t in (0..tris.len() / 3).filter(|&t| interior(t)) {
        let [a, b, c] = [0, 1, 2].map(|k| v[tris[3 * t + k] as usize]);
        for (u, w) in [(0.2, 0.3), (1.0 / 3.0, 1.0 / 3.0), (0.05, 0.9)] {
            let exact = a * (1.0 - u - w) + b * u + c * w;
            worst64 = worst64.max(ev.eval(t, u, w).unwrap().position.distance(exact) / exact.length());
            worst32 = worst32.max(single.eval(t, u, w).unwrap().position.distance(exact) / exact.length());
        }
    }
    assert!(worst64 < 1e-12, "Loop from f64 control points: {worst64:e} relative");
    assert!(worst32 > 1e-9, "f32 control points as exact? {worst32:e}");
    // Catmull-Clark: bilinear in each regular quad of an affine net
    let (v, quads) = affine_grid(9, true);
    let starts: Vec<u32> = (0..=quads.len() as u32 / 4).map(|f| 4 * f).collect();
    let poly = subdiv::mesh::PolyMesh::from_faces(v.iter().map(|p| p.as_vec3()).collect(), &starts, &quads);
    let mesh = poly.unwrap().0.triangulated();
    let ev = subdiv::Evaluator::new_f64(&mesh, &v, Scheme::CatmullClark, &Options::default()).unwrap();
    let mut worst = 0.0f64;
    for f in (0..quads.len() / 4).filter(|&f| (2..6).contains(&(f % 8)) && (2..6).contains(&(f / 8))) {
        let [a, b, c] = [0, 1, 2].map(|k| v[quads[4 * f + k] as usize]);
        let (u, w) = (0.3, 0.7);
        let exact = a + (b - a) * u + (c - b) * w;
        worst = worst.max(ev.eval(f, u, w).unwrap().position.distance(exact) / exact.length());
    }
    assert!(worst < 1e-12, "Catmull-Clark from f64 control points: {worst:e} relative");
}

#[test]
#[cfg(feature = "cli")]
fn loop_limit_positions_in_double_precision_equal_the_textbook_mask() {
    let dir = common::scratch_dir("precision-limit");
    let (v, f) = bipyramid(1e6);
    let input = dir.join("far.obj");
    let mut text: String = v.iter().map(|p| format!("v {:?} {:?} {:?}\n", p.x, p.y, p.z)).collect();
    text += &f.iter().map(|t| format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1)).collect::<String>();
    std::fs::write(&input, text).unwrap();
    // Loop's limit mask: (1 - n chi) v + chi (sum of the ring), chi = 1 / (n + 3 / (8 beta))
    let expected: Vec<DVec3> = (0..v.len())
        .map(|a| {
            let b = f.iter().find_map(|t| (0..3).find(|&i| t[i] == a).map(|i| t[(i + 1) % 3])).unwrap();
            let r = ring(&f, a, b);
            let n = r.len() as f64;
            let beta = (0.625 - (0.375 + 0.25 * (2.0 * PI / n).cos()).powi(2)) / n;
            let chi = 1.0 / (n + 3.0 / (8.0 * beta));
            v[a] * (1.0 - n * chi) + r.iter().map(|&x| v[x]).sum::<DVec3>() * chi
        })
        .collect();
    let run = |out: &str, precision: &str| {
        let path = dir.join(out);
        let st = std::process::Command::new(env!("CARGO_BIN_EXE_subdiv"))
            .args(["limit", input.to_str().unwrap(), path.to_str().unwrap(), "--precision", precision])
            .output()
            .unwrap();
        assert!(st.status.success(), "{}", String::from_utf8_lossy(&st.stderr));
        obj_points(&std::fs::read_to_string(&path).unwrap())
    };
    let double = run("d.obj", "f64");
    let far = double.iter().zip(&expected).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    assert!(far < 1e-9, "f64 limit {far:e} from the mask");
    let single = run("s.obj", "f32");
    let far = single.iter().zip(&expected).map(|(a, b)| a.distance(*b)).fold(0.0, f64::max);
    assert!(far > 1e-3, "f32 limit as exact as f64's? {far:e}");
}

/// `limit` (f64 by default) and `smooth --precision f64` read the file's
/// digits, compute in f64 and write them: a Catmull-Clark limit and Taubin
/// smoothing of a grid a million units out equal the library's f64 results
/// on the same digits, which single precision does not come near.
#[test]
#[cfg(feature = "cli")]
fn limit_and_smooth_compute_and_write_in_double_precision() {
    let dir = common::scratch_dir("precision-cc-limit");
    let (v, quads) = affine_grid(6, true);
    let input = dir.join("grid.obj");
    let mut text: String = v.iter().map(|p| format!("v {:?} {:?} {:?}\n", p.x, p.y, p.z)).collect();
    for q in quads.chunks_exact(4) {
        text += &format!("f {} {} {} {}\n", q[0] + 1, q[1] + 1, q[2] + 1, q[3] + 1);
    }
    std::fs::write(&input, text).unwrap();
    let run = |args: &[&str], out: &str| {
        let path = dir.join(out);
        let st = std::process::Command::new(env!("CARGO_BIN_EXE_subdiv"))
            .args([args[0], input.to_str().unwrap(), path.to_str().unwrap()])
            .args(&args[1..])
            .output()
            .unwrap();
        assert!(st.status.success(), "{}", String::from_utf8_lossy(&st.stderr));
        obj_points(&std::fs::read_to_string(&path).unwrap())
    };
    let mesh = subdiv::bundled::load(&input).unwrap();
    let poly = subdiv::mesh::PolyMesh::from_mesh(&mesh);
    let limit = subdiv::eval::limit_positions_f64(&poly, &v, &Options::default()).unwrap();
    assert!(worst(&run(&["limit", "-s", "catmull-clark"], "l.obj"), &limit) < 1e-9, "the default limit is f64");
    let single = run(&["limit", "-s", "catmull-clark", "--precision", "f32"], "ls.obj");
    assert!(worst(&single, &limit) > 1e-3, "an f32 limit as exact as f64's?");
    // the command's default lambda and mu, parsed as it parses them
    let smooth = subdiv::mesh::smooth_f64(&mesh, &v, 10, "0.6307".parse().unwrap(), Some("-0.6732".parse().unwrap()));
    assert!(worst(&run(&["smooth", "--precision", "f64"], "s.obj"), &smooth) < 1e-9, "f64 smoothing");
    let single = run(&["smooth"], "ss.obj");
    assert!(worst(&single, &smooth) > 1e-3, "f32 smoothing as exact as f64's?");
}
