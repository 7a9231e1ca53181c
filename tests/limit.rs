//! Loop limit positions and normals (schemes.md 5.3, 5.4) and butterfly
//! tangent normals (schemes.md 4), checked against the mathematics: masks are
//! left eigenvectors (same limit point / tangent plane from any level), the
//! mesh converges to the limit positions, finite differences of the limit
//! surface agree with the tangent-mask normals, planes and affine functions
//! are reproduced.

mod common;
use common::*;
use glam::{Mat3, Vec3};
use subdiv::eval::{butterfly_normals, loop_limit_normals, loop_limit_positions, loop_limit_positions_with};
use subdiv::{LoopBeta, Mesh, Options, Scheme, subdivide};

fn sub(m: &Mesh, s: Scheme, levels: u32) -> Mesh {
    subdivide(m, s, levels, &Options::default()).unwrap().0
}

/// Angle between two vectors (atan2 form: accurate for tiny angles).
fn angle(a: Vec3, b: Vec3) -> f32 {
    a.cross(b).length().atan2(a.dot(b))
}

fn scale(m: &Mesh) -> f32 {
    let (lo, hi) = m.bounds();
    (hi - lo).length()
}

/// A lumpy closed mesh: the icosahedron with every vertex moved, so no
/// symmetry makes the normals trivially radial.
fn lumpy_icosahedron() -> Mesh {
    let mut m = icosahedron();
    let mut rng = Rng(7);
    for q in &mut m.positions {
        *q = *q * (1.0 + 0.15 * rng.next_f32()) + rng.vec3() * 0.1;
    }
    m
}

fn test_meshes() -> Vec<(String, Mesh)> {
    let mut v = all_meshes();
    v.push(("lumpy_icosahedron".into(), lumpy_icosahedron()));
    v
}

/// Limit masks applied at level k and at level k+1 give the same point for
/// every vertex of level k (eigenvalue 1): exact up to rounding.
#[test]
fn limit_positions_are_the_same_from_the_next_level() {
    for beta in [LoopBeta::Loop, LoopBeta::Warren] {
        let opts = Options { loop_beta: beta, ..Options::default() };
        for (name, m) in test_meshes() {
            let m1 = subdivide(&m, Scheme::Loop, 1, &opts).unwrap().0;
            let m2 = subdivide(&m1, Scheme::Loop, 1, &opts).unwrap().0;
            let (l0, l1, l2) = (
                loop_limit_positions_with(&m, beta),
                loop_limit_positions_with(&m1, beta),
                loop_limit_positions_with(&m2, beta),
            );
            let tol = 2e-6 * scale(&m);
            for i in 0..m.positions.len() {
                assert!(l0[i].distance(l1[i]) < tol, "{name} {beta:?}: vertex {i}: {} vs {}", l0[i], l1[i]);
            }
            for i in 0..m1.positions.len() {
                assert!(l1[i].distance(l2[i]) < tol, "{name} {beta:?}: level-1 vertex {i}");
            }
        }
    }
}

/// Repeated Loop subdivision converges to the limit positions: the distance
/// of each control vertex from its limit point shrinks at least by half per
/// level (subdominant non-tangent eigenvalue <= 0.37 for valence <= 16) and
/// is tiny after 6 levels.
#[test]
fn subdivision_converges_to_limit_positions() {
    for (name, m) in test_meshes() {
        let lim = loop_limit_positions(&m);
        let nv = m.positions.len();
        let mut cur = m.clone();
        let mut prev = f32::MAX;
        let tol = 1e-5 * scale(&m);
        for level in 1..=6 {
            cur = sub(&cur, Scheme::Loop, 1);
            let d = (0..nv).map(|i| cur.positions[i].distance(lim[i])).fold(0.0f32, f32::max);
            if prev > 20.0 * tol {
                assert!(d <= 0.5 * prev, "{name}: level {level}: {d} vs {prev}");
            }
            prev = d;
            if cur.ct.num_triangles() > 200_000 {
                break;
            }
        }
        assert!(prev < 2e-3 * scale(&m), "{name}: still {prev} from the limit");
    }
}

/// The tangent masks are eigenvectors too: the limit normal of a vertex is
/// the same whether computed at level k or k+1.
#[test]
fn limit_normals_are_the_same_from_the_next_level() {
    for (name, m) in test_meshes() {
        let m1 = sub(&m, Scheme::Loop, 1);
        let m2 = sub(&m1, Scheme::Loop, 1);
        let (n0, n1, n2) = (loop_limit_normals(&m), loop_limit_normals(&m1), loop_limit_normals(&m2));
        for i in 0..m.positions.len() {
            assert!(angle(n0[i], n1[i]) < 1e-3, "{name}: vertex {i}: {} vs {}", n0[i], n1[i]);
        }
        for i in 0..m1.positions.len() {
            assert!(angle(n1[i], n2[i]) < 1e-3, "{name}: level-1 vertex {i}: {} vs {}", n1[i], n2[i]);
        }
        for nrm in &n2 {
            assert!((nrm.length() - 1.0).abs() < 1e-5);
        }
    }
}

/// Finite differences: the area-weighted face normals of the limit surface,
/// sampled three levels finer (limit positions of the refined mesh), agree
/// with the tangent-mask normals at the old vertices, interior and boundary,
/// regular and extraordinary.
#[test]
fn limit_normals_match_finite_differences() {
    let cases = [
        ("lumpy icosahedron L2", sub(&lumpy_icosahedron(), Scheme::Loop, 2), 0.05f32),
        ("torus L1", sub(&bundled("torus.obj"), Scheme::Loop, 1), 0.05),
        // one-sided face normals at the boundary are only first-order accurate
        ("hemisphere L1", sub(&hemisphere(), Scheme::Loop, 1), 1.0),
        ("disk fan 16", disk_fan(16, 3), 0.5),
    ];
    for (name, m, tol_deg) in cases {
        let nrm = loop_limit_normals(&m);
        let fine = sub(&m, Scheme::Loop, 3);
        let surf = Mesh { ct: fine.ct.clone(), positions: loop_limit_positions(&fine) };
        let fd = surf.vertex_normals();
        let mut worst = 0.0f32;
        for i in 0..m.positions.len() {
            worst = worst.max(angle(nrm[i], fd[i]).to_degrees());
        }
        assert!(worst < tol_deg, "{name}: worst angle {worst} degrees");
        // orientation: like the face normals of the control mesh
        let coarse = m.vertex_normals();
        for i in 0..m.positions.len() {
            assert!(nrm[i].dot(coarse[i]) > 0.0, "{name}: vertex {i} points inward");
        }
    }
}

/// A planar mesh's limit normals are exactly the plane normal, with
/// boundary vertices of every fan size and interior extraordinary vertices.
#[test]
fn planar_meshes_have_the_plane_normal() {
    let rot = Mat3::from_axis_angle(Vec3::new(1.0, 2.0, 0.5).normalize(), 0.7);
    let flat_fan = {
        let mut m = disk_fan(7, 3);
        for q in &mut m.positions {
            q.z = 0.0;
        }
        m
    };
    for (name, m) in [
        ("grid", flat_grid(5)),
        ("skewed grid", grid(6, 4, |i, j| Vec3::new(i + 0.4 * j, 0.7 * j, 0.0))),
        ("flat fan", flat_fan),
    ] {
        for level in 0..2 {
            let mut m = sub(&m, Scheme::Loop, level);
            for q in &mut m.positions {
                *q = rot * *q + Vec3::new(3.0, -1.0, 2.0);
            }
            let want = rot * Vec3::Z;
            for (i, nrm) in loop_limit_normals(&m).iter().enumerate() {
                assert!(nrm.distance(want) < 1e-5, "{name} level {level}: vertex {i}: {nrm}");
            }
            for (i, nrm) in butterfly_normals(&m).iter().enumerate() {
                assert!(nrm.distance(want) < 1e-5, "{name} level {level}: butterfly vertex {i}: {nrm}");
            }
        }
    }
}

/// Affine reproduction: the limit masks are affine combinations, so samples
/// of a linear function z = f(x, y) have limit points on the same plane (any
/// mesh), and on a regular lattice with a straight boundary the limit of
/// every vertex except the grid's corners is the vertex itself (linear
/// precision of the regular and boundary masks).
#[test]
fn affine_functions_are_reproduced() {
    let f = |x: f32, y: f32| 0.3 * x - 1.2 * y + 0.5;
    let mut fan = disk_fan(9, 3);
    for q in &mut fan.positions {
        q.z = f(q.x, q.y);
    }
    for (i, l) in loop_limit_positions(&fan).iter().enumerate() {
        assert!((l.z - f(l.x, l.y)).abs() < 1e-5, "fan vertex {i}: {l}");
    }
    let (n, m) = (6, 5);
    let g = grid(n, m, |i, j| Vec3::new(2.0 * i + 0.5 * j, 1.5 * j, f(2.0 * i + 0.5 * j, 1.5 * j)));
    let lim = loop_limit_positions(&g);
    for j in 0..=m {
        for i in 0..=n {
            let corner = (i == 0 || i == n) && (j == 0 || j == m);
            let v = j * (n + 1) + i;
            let (p, l) = (g.positions[v], lim[v]);
            assert!((l.z - f(l.x, l.y)).abs() < 1e-5, "grid vertex {v}: {l}");
            if !corner {
                assert!(p.distance(l) < 1e-5, "grid vertex ({i}, {j}) moved: {p} -> {l}");
            }
        }
    }
}

/// The limit positions commute with affine maps.
#[test]
fn limit_positions_are_affine_invariant() {
    let a = Mat3::from_cols(Vec3::new(1.0, 0.2, -0.3), Vec3::new(0.5, 1.5, 0.1), Vec3::new(-0.2, 0.4, 0.8));
    let b = Vec3::new(0.3, -2.0, 1.0);
    for (name, m) in test_meshes() {
        let mut t = m.clone();
        for q in &mut t.positions {
            *q = a * *q + b;
        }
        let (l, lt) = (loop_limit_positions(&m), loop_limit_positions(&t));
        for i in 0..l.len() {
            assert!((a * l[i] + b).distance(lt[i]) < 1e-4, "{name}: vertex {i}");
        }
    }
}

/// Butterfly normals on a butterfly-refined smooth mesh agree with the face
/// normals of a finer butterfly level (interpolating: the old vertices are on
/// the limit surface). Tight where the masks are exact (regular 2-ring, or an
/// extraordinary vertex with regular neighbours), looser where only the
/// 1-ring approximation applies (a regular vertex next to an extraordinary
/// one) and at the boundary (across-tangent from face normals).
#[test]
fn butterfly_normals_match_finite_differences() {
    for (name, m, exact_deg, approx_deg) in [
        ("lumpy icosahedron", sub(&lumpy_icosahedron(), Scheme::ModifiedButterfly, 2), 0.1f32, 2.5f32),
        ("torus", sub(&bundled("torus.obj"), Scheme::ModifiedButterfly, 1), 0.05, 0.05),
        ("hemisphere", sub(&hemisphere(), Scheme::ModifiedButterfly, 1), 0.1, 4.0),
    ] {
        let nrm = butterfly_normals(&m);
        let fine = sub(&m, Scheme::ModifiedButterfly, 3);
        let fd = fine.vertex_normals();
        let (mut exact, mut approx) = (0.0f32, 0.0f32);
        for i in 0..m.positions.len() {
            let v = i as u32;
            let interior = |q: u32| !m.ct.is_boundary_vertex(q);
            let ring_regular = m.ct.ring(v).all(|q| interior(q) && m.ct.valences()[q as usize] == 6);
            let a = angle(nrm[i], fd[i]).to_degrees();
            if interior(v) && ring_regular {
                exact = exact.max(a);
            } else {
                approx = approx.max(a);
            }
        }
        assert!(exact < exact_deg, "{name}: worst angle {exact} degrees where the masks are exact");
        assert!(approx < approx_deg, "{name}: worst angle {approx} degrees elsewhere");
    }
}

/// The 8-point butterfly reproduces cubics, so on a regular lattice (an
/// affine image of the triangular lattice) with heights from a cubic
/// polynomial the limit surface IS the cubic's graph: the 19-point tangent
/// masks must give its exact normal at every vertex with a regular 2-ring.
#[test]
fn butterfly_normals_are_exact_on_cubics() {
    let f = |x: f32, y: f32| 0.01 * (x * x * x - 2.0 * x * y * y + 3.0 * y * y) - 0.05 * x * y + 0.2 * x;
    let fx = |x: f32, y: f32| 0.01 * (3.0 * x * x - 2.0 * y * y) - 0.05 * y + 0.2;
    let fy = |x: f32, y: f32| 0.01 * (-4.0 * x * y + 6.0 * y) - 0.05 * x;
    let n = 8;
    let m = grid(n, n, |i, j| Vec3::new(i, j, f(i, j)));
    let nrm = butterfly_normals(&m);
    let mut checked = 0;
    for j in 2..=n - 2 {
        for i in 2..=n - 2 {
            let v = j * (n + 1) + i;
            let (x, y) = (i as f32, j as f32);
            let want = Vec3::new(-fx(x, y), -fy(x, y), 1.0).normalize();
            assert!(angle(nrm[v], want) < 1e-4, "vertex ({i}, {j}): {} vs {want}", nrm[v]);
            checked += 1;
        }
    }
    assert_eq!(checked, 25);
    // the same after a level of the butterfly itself (the surface does not change)
    let fine = sub(&m, Scheme::Butterfly, 1);
    let nf = butterfly_normals(&fine);
    for v in [4 * (n + 1) + 4, 3 * (n + 1) + 5] {
        assert!(angle(nf[v], nrm[v]) < 1e-4);
    }
}

/// A boundary vertex with more than 6 faces has no mask-defined limit normal
/// (not C1): it gets the area-weighted face normal; one with 6 faces uses
/// the mask, which on a planar fan is the plane normal.
#[test]
fn high_valence_boundary_vertices_fall_back() {
    for faces in [6u32, 8, 11] {
        let mut pos = vec![Vec3::ZERO];
        let mut tris = Vec::new();
        for i in 0..=faces {
            let a = std::f32::consts::PI * i as f32 / faces as f32;
            // a bent fan: heights vary so the fallback differs from any plane normal
            pos.push(Vec3::new(a.cos(), a.sin(), 0.3 * (1.7 * i as f32).sin()));
            if i > 0 {
                tris.extend([0, i, i + 1]);
            }
        }
        let m = Mesh::from_triangles(pos, &tris).unwrap();
        assert_eq!(m.ct.valences()[0], faces + 1);
        let got = loop_limit_normals(&m)[0];
        let area = m.vertex_normals()[0];
        if faces > 6 {
            assert_eq!(got, area, "{faces} faces");
        } else {
            assert!(angle(got, area) > 1e-3, "{faces} faces: the mask was not used");
            // the mask's normal is invariant under refinement
            let fine = sub(&m, Scheme::Loop, 1);
            assert!(angle(got, loop_limit_normals(&fine)[0]) < 1e-3);
        }
    }
}
