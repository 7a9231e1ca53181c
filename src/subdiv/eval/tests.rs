//! Internal checks of the evaluation: the power-table path against direct
//! subdivision of the same patch, and the parameter maps.

use super::loop_surface::{child_of, level_of, rotation, scale2};
use super::*;
use crate::mesh::shapes;

#[test]
fn children_tile_the_triangle_and_keep_orientation() {
    for &(u, v) in &[(0.1, 0.1), (0.7, 0.1), (0.1, 0.8), (0.3, 0.3), (0.49, 0.02)] {
        let (_, a) = child_of((u, v), true);
        let (s, t) = a.apply((u, v));
        assert!(s >= -1e-12 && t >= -1e-12 && s + t <= 1.0 + 1e-12, "({u}, {v}) -> ({s}, {t})");
        let det = a.j[0][0] * a.j[1][1] - a.j[0][1] * a.j[1][0];
        assert!(det > 0.0);
    }
    for i in 0..3 {
        let r = rotation(i);
        let det = r.j[0][0] * r.j[1][1] - r.j[0][1] * r.j[1][0];
        assert_eq!(det, 1.0);
        // corner i goes to (0, 0)
        let corner = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)][i];
        assert_eq!(r.apply(corner), (0.0, 0.0));
    }
}

#[test]
fn levels_put_the_point_in_the_outer_half() {
    for s in [1.0, 0.75, 0.5, 0.3, 0.25, 1e-3, 1e-100, 5e-324] {
        let m = level_of(s);
        let x = scale2(s, m);
        assert!(x > 0.5 && x <= 1.0, "s {s}: m {m}, s 2^m = {x}");
    }
}

#[test]
fn the_surface_is_continuous_around_an_extraordinary_vertex() {
    // the icosahedron: every vertex has valence 5; approach one along a ray
    // and across the boundary between the power-table levels
    let mesh = shapes::icosahedron();
    let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
    let at_vertex = ev.eval(0, 0.0, 0.0).unwrap();
    let mut last = f64::INFINITY;
    for k in 1..60 {
        let s = 0.5f64.powi(k);
        let here = ev.eval(0, 0.3 * s, 0.2 * s).unwrap();
        let d = (here.position - at_vertex.position).length();
        assert!(d < last, "distance to the vertex grows at 2^-{k}");
        last = d;
        // either side of a level boundary
        let a = ev.eval(0, 0.25 * s * (1.0 + 1e-9), 0.25 * s * (1.0 + 1e-9)).unwrap();
        let b = ev.eval(0, 0.25 * s * (1.0 - 1e-9), 0.25 * s * (1.0 - 1e-9)).unwrap();
        assert!((a.position - b.position).length() < 1e-6 * s.max(1e-300) + 1e-15, "jump at level {k}");
        assert!(a.normal.dot(b.normal) > 1.0 - 1e-6);
    }
    assert!(last < 1e-12);
}

#[test]
/// The quad lineage of the mesh layer against a subdivision (here, where
/// both layers are known).
fn a_point_of_a_refined_quad_finds_its_level_one_parameters() {
    use crate::mesh::lineage::{quad_origin, quad_parent, quad_point};
    use crate::mesh::poly::PolyMesh;
    use crate::subdiv::{Options, Scheme, subdivide_poly};
    use glam::Vec3;
    // bilinear subdivision of the unit square keeps every point at its
    // own parameters: level-1 quad 0 (corner 0's) is [0, 1/2]^2
    let square =
        PolyMesh::from_faces(vec![Vec3::ZERO, Vec3::X, Vec3::ONE.with_z(0.0), Vec3::Y], &[0, 4], &[0, 1, 2, 3])
            .expect("a square")
            .0;
    for levels in 1..4 {
        let fine = subdivide_poly(&square, Scheme::Bilinear, levels, &Options::default()).expect("levels").0;
        let tris = fine.pt.triangulated();
        for t in 0..tris.num_triangles() as u32 {
            let at = |k: u32| fine.positions[tris.vtx(3 * t + k) as usize];
            let (b1, b2) = (0.3, 0.2);
            let p = at(0) * 0.5 + at(1) * b1 as f32 + at(2) * b2 as f32;
            let (q, [u, v]) = quad_point(t, levels, b1, b2);
            assert_eq!(q, quad_origin(t, levels));
            // quad q's quarter of the square, mapped back to the square
            let [x, y] = quad_parent(q, [u, v]);
            assert!((f64::from(p.x) - x).abs() < 1e-6 && (f64::from(p.y) - y).abs() < 1e-6, "{t} at {levels}");
        }
    }
}

#[test]
/// The levels of local subdivision kept from one point to the next (points
/// of a face share them until their children part) give every point what
/// it gets evaluated alone, on both schemes' local paths: a bumped grid,
/// every face near its border.
fn points_evaluated_together_equal_points_evaluated_alone() {
    let mut mesh = shapes::grid(4);
    for p in &mut mesh.positions {
        p.z = (0.9 * p.x).sin() * (0.7 * p.y).cos();
    }
    for scheme in [Scheme::Loop, Scheme::CatmullClark] {
        let ev = Evaluator::new(&mesh, scheme, &Options::default()).unwrap();
        let faces = ev.num_faces();
        // a face's points in an order that leaves its children and comes back
        let uv = [(0.05, 0.05), (0.6, 0.3), (0.02, 0.9), (0.3, 0.3), (0.051, 0.049), (0.9, 0.05), (0.0, 0.0)];
        let points: Vec<(usize, f64, f64)> =
            (0..faces).flat_map(|f| uv.iter().map(move |&(u, v)| (f, u, v * (1.0 - u)))).collect();
        let together = ev.eval_map(&points, false, |s| s.position).unwrap();
        for (&(f, u, v), got) in points.iter().zip(&together) {
            let alone = ev.eval_with(f, u, v, false).unwrap().position;
            assert_eq!(*got, alone, "{scheme:?} face {f} at ({u}, {v})");
        }
    }
}
