//! The tetrahedron animation: paths file, frame count, re-evaluation through
//! the stencil plan against full subdivision.

mod common;
use common::*;
use subdiv::anim::{Animation, Paths, Tweak};
use subdiv::{Mesh, Options, Scheme, subdivide};

fn tet_paths() -> Paths {
    Paths::load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("paths/tetrahedron.paths"), &Default::default())
        .unwrap()
}

#[test]
fn tetrahedron_paths_fit_the_model_and_give_k_times_2_pow_n_frames() {
    let tet = bundled("tetrahedron.obj");
    let p = tet_paths();
    assert_eq!((p.vertex_count(), p.keys_per_vertex), (4, 4));
    p.check_model(&tet, "tetrahedron.paths").unwrap();
    let mut a = Animation::new(&tet, &p, Tweak::FourPoint, 5, Scheme::Loop, 5, &Options::default()).unwrap();
    assert_eq!(a.frame_count(), 128);
    assert_eq!(a.topology().num_triangles(), 4 * 4usize.pow(5));
    // the 4-point tweak interpolates: frame 32k is key k
    for k in 0..4 {
        assert_eq!(a.control(32 * k), (0..4).map(|v| p.polygon(v)[k]).collect::<Vec<_>>().as_slice());
    }
    // every frame equals a full subdivision of that frame's control mesh,
    // numbered in the plan's locality order
    let order = a.plan().order().expect("animations are evaluated in a locality order").clone();
    for f in [0, 1, 17, 64, 127] {
        let control = Mesh { ct: tet.ct.clone(), positions: a.control(f).to_vec() }.relabelled(&order);
        let (full, _) = subdivide(&control, Scheme::Loop, 5, &Options::default()).unwrap();
        let (pos, nrm) = a.evaluate(f);
        assert_eq!(pos.len(), full.positions.len());
        for (x, y) in pos.iter().zip(&full.positions) {
            assert!((*x - *y).abs().max_element() < 1e-6);
        }
        assert!(nrm.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
        // the packed one-ring normals are the area-weighted normals of the mesh
        for (n, m) in nrm.iter().zip(full.vertex_normals()) {
            assert!(n.distance(m) < 1e-4, "frame {f}: normal {n} vs {m}");
        }
    }
    // the mismatching model is refused with both counts
    let e = p.check_model(&bundled("cube.obj"), "tetrahedron.paths").unwrap_err();
    assert!(e.to_string().contains("4 vertices") && e.to_string().contains("8"), "{e}");
}

#[test]
fn every_model_can_animate_with_generated_paths() {
    for name in BUNDLED {
        let m = bundled(name);
        let p = Paths::generated(&m, 4);
        for t in Tweak::ALL {
            let mut a = Animation::new(&m, &p, t, 2, Scheme::Jarek, 1, &Options::default()).unwrap();
            assert_eq!(a.frame_count(), 16);
            let first: Vec<_> = a.evaluate(0).0.to_vec();
            let later: Vec<_> = a.evaluate(5).0.to_vec();
            assert!(first.iter().zip(&later).any(|(x, y)| x.distance(*y) > 1e-4), "{name}: the mesh moves");
        }
    }
    let m = bundled("torus.obj");
    assert!(
        Animation::new(&m, &Paths::generated(&m, 4), Tweak::Jarek, 20, Scheme::Loop, 1, &Options::default()).is_err()
    );
}

/// Catmull-Clark and bilinear animate through their stencil plans: every
/// frame equals a direct subdivision of that frame's control polygons
/// (creases uniform and Chaikin, semi-sharp edges, corners, a boundary with
/// both options, faces of 3 to 6 corners), the finest level drawn as its
/// quads' triangles and shaded with the normals of each vertex's ring of
/// edge neighbours.
#[test]
fn polygon_schemes_animate_like_a_direct_subdivision() {
    use subdiv::mesh::{BoundaryInterpolation, Creasing};
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark");
    let chaikin = Options { creasing: Creasing::Chaikin, ..Options::default() };
    let corners = Options { boundary: BoundaryInterpolation::EdgeAndCorner, ..Options::default() };
    let cases = [
        ("ngons.obj", Scheme::CatmullClark, 3, Options::default()),
        ("cube_creases.obj", Scheme::CatmullClark, 3, chaikin),
        ("grid_dart.obj", Scheme::CatmullClark, 2, Options::default()),
        ("grid.obj", Scheme::CatmullClark, 2, corners),
        ("ngons.obj", Scheme::Bilinear, 2, Options::default()),
    ];
    for (name, scheme, level, opts) in cases {
        let m = subdiv::bundled::load(&dir.join(name)).unwrap();
        let p = Paths::generated(&m, 4);
        let mut a = Animation::new(&m, &p, Tweak::FourPoint, 2, scheme, level, &opts).unwrap();
        let order = a.plan().order().cloned();
        for f in [0, 3, 9] {
            let control = Mesh { ct: m.ct.clone(), positions: a.control(f).to_vec() };
            let control = match &order {
                Some(o) => control.relabelled(o),
                None => control,
            };
            let (full, _) = subdivide(&control, scheme, level, &opts).unwrap();
            let what = format!("{name} {scheme} L{level} frame {f}");
            assert_eq!(a.topology().v_table(), full.ct.v_table(), "{what}: topology");
            let (pos, nrm) = a.evaluate(f);
            for (x, y) in pos.iter().zip(&full.positions) {
                assert!((*x - *y).abs().max_element() < 1e-5, "{what}: {x} against {y}");
            }
            for (v, n) in nrm.iter().enumerate() {
                let m = edge_ring_normal(&subdiv::mesh::PolyMesh::from_mesh(&full), v as u32);
                assert!(n.distance(m) < 1e-4, "{what}: normal {n} against {m}");
            }
        }
    }
}

/// The unit normal of the polygon of `v`'s edge neighbours in fan order
/// (with `v` itself on the boundary), by Newell's sum of cross products.
fn edge_ring_normal(m: &subdiv::mesh::PolyMesh, v: u32) -> glam::Vec3 {
    let pt = &m.pt;
    let mut ring: Vec<glam::Vec3> = pt.fan(v).map(|c| m.positions[pt.vtx(pt.next(c)) as usize]).collect();
    if pt.is_boundary_vertex(v) {
        let last = pt.fan(v).last().expect("a fan");
        ring.push(m.positions[pt.vtx(pt.prev(last)) as usize]);
        ring.insert(0, m.positions[v as usize]);
    }
    let k = ring.len();
    (0..k).map(|i| ring[i].cross(ring[(i + 1) % k])).sum::<glam::Vec3>().normalize()
}

/// Per-vertex data through the animation's plan (what `animate --color
/// file` draws) lands on its finest level's vertices in the plan's
/// locality order: a colour that is an affine function of the control
/// positions is the same function of the evaluated positions.
#[test]
fn colours_through_the_plan_follow_its_vertex_order() {
    let m = icosphere(1);
    let p = Paths::generated(&m, 4);
    let mut a = Animation::new(&m, &p, Tweak::FourPoint, 2, Scheme::Loop, 3, &Options::default()).unwrap();
    assert!(a.plan().order().is_some(), "the plan is renumbered: the test means something");
    let colour = |q: glam::Vec3| q * 0.25 + glam::Vec3::splat(0.5);
    let control: Vec<glam::Vec3> = a.control(0).iter().map(|&q| colour(q)).collect();
    let mut fine = Vec::new();
    a.plan().apply(&control, &mut subdiv::rules::PlanScratch::default(), &mut fine);
    let (pos, _) = a.evaluate(0);
    let worst = fine.iter().zip(pos).map(|(c, &q)| c.distance(colour(q))).fold(0.0, f32::max);
    assert!(worst < 1e-5, "colours follow the positions' order ({worst})");
}
