//! Edge generations carried by the split: both corners of an edge agree, the
//! count of every generation follows its closed form, and the edges of
//! generation 0 lie on the control edges.
//!
//! Closed form, for a control mesh with `F` triangles and `H = 3F` corners
//! (half-edges) after `k` splits: a half-edge of generation 0 is halved by
//! each split, so there are `3F 2^k` of them; split `j` makes 3 interior
//! edges (6 half-edges) in each of its `F 4^(j-1)` triangles, halved by the
//! `k - j` later splits: `6F 4^(j-1) 2^(k-j)` half-edges of generation `j`.
//! They add up to `3F 4^k`, every corner of level `k`.

mod common;
use common::*;
use glam::Vec3;
use subdiv::mesh::refine_linear;
use subdiv::mesh::{n, p};
use subdiv::{Mesh, Options, Scheme};

/// Number of corners of each generation `0..=k`.
fn histogram(m: &Mesh, k: usize) -> Vec<u64> {
    let mut h = vec![0u64; k + 1];
    for c in 0..m.ct.num_corners() as u32 {
        let g = m.ct.edge_generation(c) as usize;
        assert!(g <= k, "generation {g} at level {k}");
        h[g] += 1;
    }
    h
}

fn closed_form(f0: u64, k: u32) -> Vec<u64> {
    let mut v = vec![3 * f0 * (1 << k)];
    for j in 1..=k {
        v.push(6 * f0 * 4u64.pow(j - 1) * (1 << (k - j)));
    }
    v
}

#[test]
fn control_table_is_generation_zero() {
    let m = bundled("torus.obj");
    assert!(m.ct.generations().is_none());
    assert_eq!(m.ct.level(), 0);
    assert!((0..m.ct.num_corners() as u32).all(|c| m.ct.edge_generation(c) == 0));
}

#[test]
fn opposite_corners_agree_and_counts_follow_the_closed_form() {
    for (name, mesh) in all_meshes() {
        for scheme in [Scheme::Loop, Scheme::Butterfly] {
            let f0 = mesh.ct.num_triangles() as u64;
            let levels = if f0 > 500 { 2 } else { 3 };
            let mut cur = mesh.clone();
            for k in 1..=levels {
                cur = subdiv::subdivide(&cur, scheme, 1, &Options::default()).unwrap().0;
                let ctx = format!("{name} {scheme} level {k}");
                assert_eq!(cur.ct.level() as u32, k, "{ctx}: level");
                for c in 0..cur.ct.num_corners() as u32 {
                    if let Some(x) = cur.ct.o(c) {
                        assert_eq!(cur.ct.edge_generation(c), cur.ct.edge_generation(x), "{ctx}: corner {c} and {x}");
                    }
                }
                assert_eq!(histogram(&cur, k as usize), closed_form(f0, k), "{ctx}: counts per generation");
            }
        }
    }
}

#[test]
fn several_levels_at_once_equal_one_at_a_time() {
    let mesh = bundled("cube.obj");
    let once = subdiv::subdivide(&mesh, Scheme::Loop, 3, &Options::default()).unwrap().0;
    let mut step = mesh.clone();
    for _ in 0..3 {
        step = subdiv::subdivide(&step, Scheme::Loop, 1, &Options::default()).unwrap().0;
    }
    let (a, b) = (once.ct.generations().unwrap(), step.ct.generations().unwrap());
    assert_eq!(a.corners(), b.corners());
}

/// The two readings of the generations agree: one corner walked back through
/// the splits, and every corner written split by split.
#[test]
fn one_corner_at_a_time_equals_all_at_once() {
    for name in ["cube.obj", "lprism.obj"] {
        let mut m = bundled(name);
        for level in 1..=3u8 {
            m = subdiv::subdivide(&m, Scheme::Loop, 1, &Options::default()).unwrap().0;
            let g = m.ct.generations().unwrap();
            assert_eq!(g.level(), level);
            let all = g.corners();
            assert_eq!(all.len(), m.ct.num_corners());
            for (c, &e) in all.iter().enumerate() {
                assert_eq!(g.corner(c as u32), e, "{name}: level {level}, corner {c}");
            }
            assert_eq!(all.iter().copied().max(), Some(level), "{name}: newest generation");
        }
    }
}

/// Whether `q` lies on the segment `a`-`b` (within `tol` of its length).
fn on_segment(q: Vec3, a: Vec3, b: Vec3, tol: f32) -> bool {
    let ab = b - a;
    let t = (q - a).dot(ab) / ab.length_squared();
    (-tol..=1.0 + tol).contains(&t) && (a + ab * t).distance(q) <= tol * ab.length()
}

#[test]
fn generation_zero_edges_lie_on_control_edges() {
    for name in ["tetrahedron.obj", "cube.obj", "lprism.obj"] {
        let control = bundled(name);
        let segs: Vec<(Vec3, Vec3)> = control
            .ct
            .edge_owners()
            .map(|c| {
                (control.positions[control.ct.vtx(n(c)) as usize], control.positions[control.ct.vtx(p(c)) as usize])
            })
            .collect();
        // midpoint scheme: every new point lies on the control surface
        let fine = refine_linear(&control, 3);
        let (mut zero, mut inner) = (0, 0);
        for c in fine.ct.edge_owners() {
            let (a, b) = (fine.positions[fine.ct.vtx(n(c)) as usize], fine.positions[fine.ct.vtx(p(c)) as usize]);
            let on_control = segs.iter().any(|&(s, e)| on_segment(a, s, e, 1e-5) && on_segment(b, s, e, 1e-5));
            if fine.ct.edge_generation(c) == 0 {
                assert!(on_control, "{name}: generation-0 edge {a} {b} off the control edges");
                zero += 1;
            } else {
                assert!(!on_control, "{name}: edge of generation {} on a control edge", fine.ct.edge_generation(c));
                inner += 1;
            }
        }
        assert_eq!(zero, segs.len() * 8, "{name}: each control edge in 2^3 pieces");
        assert!(inner > 0);
    }
}

#[test]
fn an_edit_makes_a_new_control_table() {
    let mut m = subdiv::subdivide(&bundled("cube.obj"), Scheme::Loop, 1, &Options::default()).unwrap().0;
    assert_eq!(m.ct.level(), 1);
    let c = m.ct.edge_owners().next().unwrap();
    subdiv::mesh::split_edge(&mut m, c, 0.5);
    assert_eq!(m.ct.level(), 0);
    assert!((0..m.ct.num_corners() as u32).all(|c| m.ct.edge_generation(c) == 0));
}
