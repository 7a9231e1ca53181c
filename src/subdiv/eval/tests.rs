//! Internal checks of the evaluation: the power-table path against direct
//! subdivision of the same patch, and the parameter maps.

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
fn grouped_evaluation_equals_one_point_at_a_time() {
    // eval_map groups the points by face and shares each level-1 face's
    // support and polynomial between them; eval builds them per point. An
    // icosphere (valences 5 and 6) and the bundled critter (fanned quads:
    // valences 3 to 9, smooth and local faces), many points per face, in
    // random order, a few right at a corner
    let critter = crate::bundled::load(std::path::Path::new("bundled:critter.obj")).unwrap();
    for mesh in [shapes::icosphere(2), critter] {
        let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default()).unwrap();
        let faces: Vec<usize> = (0..ev.num_faces()).filter(|&f| ev.accepts(f)).collect();
        let mut x = 0x9e3779b97f4a7c15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
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
