//! Sharp features (docs/sharp-features.md): Loop against OpenSubdiv 3.5's own output,
//! and the mathematics every scheme must keep with creases.
mod common;

use common::{assert_same_points, icosphere, read_points, scratch_dir};
use glam::{Mat3, Vec3};
use std::path::PathBuf;
use subdiv::StencilPlan;
use subdiv::mesh::{BoundaryInterpolation, Creasing};
use subdiv::mesh::{CornerTag, CreaseTag, INFINITE, Tags};
use subdiv::rules::PlanScratch;
use subdiv::{Mesh, Options, Scheme, subdivide};

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/creases").join(name)
}

fn load(name: &str) -> Mesh {
    subdiv::bundled::load(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn opts(creasing: Creasing, boundary: BoundaryInterpolation) -> Options {
    Options { creasing, boundary, max_memory: Some(1 << 32), ..Options::default() }
}

fn sub(m: &Mesh, s: Scheme, levels: u32, o: &Options) -> Mesh {
    subdivide(m, s, levels, o).unwrap().0
}

#[test]
fn loop_with_tags_equals_opensubdiv() {
    // thresholds: every comparison of Sdc::Crease at its boundary (s < 1,
    // s <= 1, s = 10, Chaikin's child dart past s = 1; scripts/threshold-fixtures.py)
    let cases: [(&str, &[&str], u32); 6] = [
        ("thresholds", &["uniform", "chaikin"], 3),
        ("cube_sharp", &["uniform"], 3),
        ("tet_semi", &["uniform", "chaikin"], 3),
        ("ico_crease", &["uniform", "chaikin"], 2),
        ("grid_open", &["uniform", "corners"], 3),
        ("torus_semi", &["uniform", "chaikin"], 2),
    ];
    for (name, options, levels) in cases {
        let m = load(&format!("{name}.obj"));
        assert!(m.ct.sharpness().is_some(), "{name}: the tags were read");
        for &o in options {
            let op = match o {
                "chaikin" => opts(Creasing::Chaikin, BoundaryInterpolation::EdgeOnly),
                "corners" => opts(Creasing::Uniform, BoundaryInterpolation::EdgeAndCorner),
                _ => opts(Creasing::Uniform, BoundaryInterpolation::EdgeOnly),
            };
            for l in 1..=levels {
                let ours = sub(&m, Scheme::Loop, l, &op);
                let theirs = read_points(&fixture(&format!("{name}.{o}.L{l}.osd.txt")));
                assert_same_points(&ours.positions, &theirs, 2e-6, &format!("{name} {o} L{l}"));
            }
        }
    }
}

/// The bundled cube with its 12 edges tagged infinitely sharp.
fn sharp_cube() -> Mesh {
    load("cube_sharp.obj")
}

/// Is `q` on the surface of the unit cube, and on which faces.
fn cube_faces_of(q: Vec3, eps: f32) -> Vec<(usize, f32)> {
    let mut f = Vec::new();
    for k in 0..3 {
        for side in [0.0, 1.0] {
            if (q[k] - side).abs() < eps {
                f.push((k, side));
            }
        }
    }
    f
}

#[test]
fn an_all_sharp_cube_stays_a_cube_in_every_scheme() {
    let cube = sharp_cube();
    for s in Scheme::TRIANGLE {
        for levels in 1..=3 {
            let fine = sub(&cube, s, levels, &Options::default());
            // every triangle lies in one face of the cube: its three points
            // share a coordinate fixed at 0 or 1, and stay inside [0, 1]^3
            for tri in fine.triangles().chunks_exact(3) {
                let ps: Vec<Vec3> = tri.iter().map(|&v| fine.positions[v as usize]).collect();
                let common: Vec<_> = cube_faces_of(ps[0], 1e-5)
                    .into_iter()
                    .filter(|&(k, side)| ps.iter().all(|q| (q[k] - side).abs() < 1e-5))
                    .collect();
                assert!(!common.is_empty(), "{s} L{levels}: triangle {ps:?} is not in a face of the cube");
                for q in &ps {
                    assert!(q.cmpge(Vec3::splat(-1e-5)).all() && q.cmple(Vec3::splat(1.0 + 1e-5)).all(), "{s}: {q}");
                }
            }
        }
    }
}

/// A coarse torus (8 steps around, 6 around the tube), with one closed
/// crease loop around the tube: the vertices in the half plane y = 0, x > 0,
/// and the 6 edges between them.
fn torus_with_loop(sharpness: f32) -> (Mesh, Vec<u32>) {
    let (nu, nv) = (8u32, 6u32);
    let id = |a: u32, b: u32| (a % nu) * nv + (b % nv);
    let mut pos = Vec::new();
    for a in 0..nu {
        for b in 0..nv {
            let (u, v) = (std::f32::consts::TAU * a as f32 / nu as f32, std::f32::consts::TAU * b as f32 / nv as f32);
            let r = 1.0 + 0.4 * v.cos();
            pos.push(Vec3::new(r * u.cos(), r * u.sin(), 0.4 * v.sin()));
        }
    }
    let mut tris = Vec::new();
    for a in 0..nu {
        for b in 0..nv {
            tris.extend_from_slice(&[
                id(a, b),
                id(a + 1, b),
                id(a + 1, b + 1),
                id(a, b),
                id(a + 1, b + 1),
                id(a, b + 1),
            ]);
        }
    }
    let m = Mesh::from_triangles(pos, &tris).unwrap();
    let on = |v: u32| on_loop(m.positions[v as usize]);
    let mut creases = Vec::new();
    for c in m.ct.edge_owners() {
        let (a, b) = (m.ct.vtx(subdiv::mesh::n(c)), m.ct.vtx(subdiv::mesh::p(c)));
        if on(a) && on(b) {
            creases.push(CreaseTag { v0: a, v1: b, sharpness });
        }
    }
    assert_eq!(creases.len(), 6, "the loop around the tube");
    let ring: Vec<u32> = (0..m.positions.len() as u32).filter(|&v| on(v)).collect();
    let ct = m.ct.clone().with_tags(&Tags { creases, corners: vec![] }).unwrap();
    (Mesh { ct, positions: m.positions }, ring)
}

#[test]
fn a_loop_crease_is_the_cubic_b_spline_of_its_polygon() {
    // Loop: crease vertices 1/8, 3/4, 1/8 of their crease neighbours, crease
    // edges 1/2, 1/2 (docs/sharp-features.md §6.1): check against the polygon directly
    let (m, ring) = torus_with_loop(INFINITE);
    let fine = sub(&m, Scheme::Loop, 1, &Options::default());
    let neighbours = |v: u32| -> Vec<u32> { m.ct.ring(v).filter(|q| ring.contains(q)).collect() };
    for &v in &ring {
        let nb = neighbours(v);
        assert_eq!(nb.len(), 2, "vertex {v} has two crease neighbours");
        let want = m.positions[v as usize] * 0.75 + (m.positions[nb[0] as usize] + m.positions[nb[1] as usize]) * 0.125;
        assert!(fine.positions[v as usize].distance(want) < 1e-6, "crease vertex {v}");
    }
    // the crease edge points are the midpoints: the new vertex on each crease
    // edge lies in the plane of the polygon, and there are as many as edges
    let on_plane = fine.positions[m.positions.len()..].iter().filter(|&&q| on_loop(q)).count();
    assert_eq!(on_plane, ring.len(), "one new point per crease edge stays on the polygon's plane");
}

#[test]
fn crease_points_depend_on_the_crease_polygon_alone() {
    // moving every vertex off the crease leaves the points on the crease
    // where they were, for every scheme (the butterfly family: the 4-point
    // rule; Loop: the B-spline; Jarek: its curve rule)
    let (m, ring) = torus_with_loop(INFINITE);
    let mut moved = m.clone();
    for (v, q) in moved.positions.iter_mut().enumerate() {
        if !ring.contains(&(v as u32)) {
            *q *= 1.3 + 0.1 * (v % 3) as f32;
        }
    }
    for s in Scheme::TRIANGLE {
        let (a, b) = (sub(&m, s, 2, &Options::default()), sub(&moved, s, 2, &Options::default()));
        let crease: Vec<usize> = (0..a.positions.len()).filter(|&i| on_loop(a.positions[i])).collect();
        assert!(crease.len() >= 4 * ring.len(), "{s}: the crease points after two levels");
        for i in crease {
            assert!(a.positions[i].distance(b.positions[i]) < 1e-5, "{s}: crease point {i} moved");
        }
    }
}

#[test]
fn the_butterfly_crease_is_the_four_point_curve() {
    let (m, ring) = torus_with_loop(INFINITE);
    for s in [Scheme::Butterfly, Scheme::ModifiedButterfly] {
        let fine = sub(&m, s, 1, &Options::default());
        // old vertices stay
        for v in 0..m.positions.len() {
            assert_eq!(fine.positions[v], m.positions[v], "{s}: vertex {v} moved");
        }
        // each crease edge point: -1/16, 9/16, 9/16, -1/16 along the polygon
        let nb = |v: u32| -> Vec<u32> { m.ct.ring(v).filter(|q| ring.contains(q)).collect() };
        let (owners, ids) = edge_points(&m);
        for (c, id) in owners.into_iter().zip(ids) {
            let (p1, p2) = (m.ct.vtx(subdiv::mesh::n(c)), m.ct.vtx(subdiv::mesh::p(c)));
            if !(ring.contains(&p1) && ring.contains(&p2)) {
                continue;
            }
            let p0 = nb(p1).into_iter().find(|&q| q != p2).unwrap();
            let p3 = nb(p2).into_iter().find(|&q| q != p1).unwrap();
            let at = |v: u32| m.positions[v as usize];
            let want = (at(p1) + at(p2)) * (9.0 / 16.0) - (at(p0) + at(p3)) / 16.0;
            assert!(fine.positions[id].distance(want) < 1e-6, "{s}: crease edge ({p1}, {p2})");
        }
    }
}

/// Is `q` in the half plane of the torus's crease loop?
fn on_loop(q: Vec3) -> bool {
    q.y.abs() < 1e-5 && q.x > 0.0
}

/// Owner corner and new vertex id of every edge of `m` (the split numbers
/// edge vertices `V + e` in owner order).
fn edge_points(m: &Mesh) -> (Vec<u32>, Vec<usize>) {
    let owners: Vec<u32> = m.ct.edge_owners().collect();
    let ids = (0..owners.len()).map(|e| m.positions.len() + e).collect();
    (owners, ids)
}

#[test]
fn integer_sharpness_k_is_k_sharp_levels_then_smooth() {
    for s in Scheme::TRIANGLE {
        for k in 1..=2u32 {
            let (semi, _) = torus_with_loop(k as f32);
            let (inf, _) = torus_with_loop(INFINITE);
            let direct = sub(&semi, s, 3, &Options::default());
            let sharp = sub(&inf, s, k, &Options::default());
            let untagged = Mesh { ct: sharp.ct.clone().with_tags(&Tags::default()).unwrap(), ..sharp };
            let then = sub(&untagged, s, 3 - k, &Options::default());
            for (i, (a, b)) in direct.positions.iter().zip(&then.positions).enumerate() {
                assert!(a.distance(*b) < 1e-5, "{s} k = {k}: vertex {i}: {a} vs {b}");
            }
        }
    }
}

#[test]
fn sharpness_zero_is_the_smooth_result_bit_for_bit() {
    let m = icosphere(1);
    let creases: Vec<CreaseTag> =
        m.ct.edge_owners()
            .take(20)
            .map(|c| CreaseTag { v0: m.ct.vtx(subdiv::mesh::n(c)), v1: m.ct.vtx(subdiv::mesh::p(c)), sharpness: 0.0 })
            .collect();
    let tagged = Mesh {
        ct: m.ct.clone().with_tags(&Tags { creases, corners: vec![CornerTag { vertex: 0, sharpness: 0.0 }] }).unwrap(),
        ..m.clone()
    };
    assert!(tagged.ct.sharpness().is_none());
    for s in Scheme::TRIANGLE {
        let (a, b) = (sub(&m, s, 3, &Options::default()), sub(&tagged, s, 3, &Options::default()));
        assert!(a.positions == b.positions, "{s}");
    }
}

#[test]
fn affine_maps_commute_with_creased_subdivision() {
    let cases = [load("ico_crease.obj"), load("grid_open.obj"), load("tet_semi.obj"), sharp_cube()];
    let a = Mat3::from_cols(Vec3::new(1.2, 0.3, -0.1), Vec3::new(-0.2, 0.9, 0.4), Vec3::new(0.1, -0.5, 1.1));
    let t = Vec3::new(3.0, -2.0, 0.5);
    for m in &cases {
        let mapped = Mesh { positions: m.positions.iter().map(|&p| a * p + t).collect(), ct: m.ct.clone() };
        for s in Scheme::TRIANGLE {
            for o in [Options::default(), opts(Creasing::Chaikin, BoundaryInterpolation::EdgeAndCorner)] {
                let x = sub(m, s, 2, &o);
                let y = sub(&mapped, s, 2, &o);
                for (p, q) in x.positions.iter().zip(&y.positions) {
                    let want = a * *p + t;
                    assert!(want.distance(*q) < 2e-4 * (1.0 + want.length()), "{s}: {want} vs {q}");
                }
            }
        }
    }
}

/// For a plan built in a locality order (`StencilPlan::build_local`): the
/// id in the plain subdivision of `ct` of each vertex of the plan's finest
/// level, found from the topology alone: control vertex `v` is plan vertex
/// `order.new_vertex(v)`, and level by level the vertex made on an edge is
/// matched to the vertex made on the edge between the matched end points.
fn plain_ids(ct: &subdiv::CornerTable, order: &subdiv::mesh::Relabel, levels: u32) -> Vec<u32> {
    use std::collections::HashMap;
    use subdiv::mesh::split;
    use subdiv::mesh::{n, p};
    let mut map = order.old_vertices();
    let (mut local, mut plain) = (ct.relabelled(order), ct.clone());
    for _ in 0..levels {
        let ((l2, le), (p2, pe)) = (split(&local), split(&plain));
        let ends = |t: &subdiv::CornerTable, c: u32| (t.vtx(n(c)), t.vtx(p(c)));
        let mut plain_edge = HashMap::new();
        for (e, &c) in pe.owners.iter().enumerate() {
            let (a, b) = ends(&plain, c);
            plain_edge.insert((a.min(b), a.max(b)), e as u32);
        }
        let (nl, np) = (local.num_vertices() as u32, plain.num_vertices() as u32);
        for &c in &le.owners {
            let (a, b) = ends(&local, c);
            let (a, b) = (map[a as usize], map[b as usize]);
            map.push(np + plain_edge[&(a.min(b), a.max(b))]);
        }
        assert_eq!(map.len() as u32, nl + le.owners.len() as u32);
        (local, plain) = (l2, p2);
    }
    map
}

#[test]
fn the_stencil_plans_record_the_crease_rules_in_either_order() {
    let cases = [load("ico_crease.obj"), load("grid_open.obj"), load("tet_semi.obj"), load("torus_semi.obj")];
    for m in &cases {
        for s in Scheme::TRIANGLE {
            for o in [Options::default(), opts(Creasing::Chaikin, BoundaryInterpolation::EdgeAndCorner)] {
                let full = sub(m, s, 3, &o);
                // in the control mesh's own order: vertex for vertex
                let plan = StencilPlan::build(&m.ct, s, 3, &o).unwrap();
                let mut out = Vec::new();
                plan.apply(&m.positions, &mut PlanScratch::default(), &mut out);
                assert_eq!(out.len(), full.positions.len());
                for (i, (p, q)) in out.iter().zip(&full.positions).enumerate() {
                    assert!(p.distance(*q) < 1e-5, "{s}: vertex {i}: plan {p} vs subdivision {q}");
                }
                // in a locality order: the same surface under a vertex map
                let plan = StencilPlan::build_local(&m.ct, s, 3, &o).unwrap();
                let order = plan.order().expect("a locality order");
                let mut out = Vec::new();
                plan.apply(&m.positions, &mut PlanScratch::default(), &mut out);
                let ids = plain_ids(&m.ct, order, 3);
                assert_eq!(out.len(), full.positions.len());
                for (i, (p, &j)) in out.iter().zip(&ids).enumerate() {
                    let q = full.positions[j as usize];
                    assert!(p.distance(q) < 1e-5, "{s}: plan vertex {i} = vertex {j}: {p} vs {q}");
                }
                // the same triangles, corner for corner under the map
                let mut a: Vec<[u32; 3]> =
                    plan.ct.v_table().chunks_exact(3).map(|t| canon(t.iter().map(|&v| ids[v as usize]))).collect();
                let mut b: Vec<[u32; 3]> =
                    full.ct.v_table().chunks_exact(3).map(|t| canon(t.iter().copied())).collect();
                a.sort_unstable();
                b.sort_unstable();
                assert!(a == b, "{s}: the plan's triangles are the subdivision's");
            }
        }
    }
}

/// A triangle rotated to start at its smallest vertex id.
fn canon(t: impl Iterator<Item = u32>) -> [u32; 3] {
    let t: Vec<u32> = t.collect();
    let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}

#[test]
fn the_packed_plan_equals_its_csr_rows_bit_for_bit() {
    // StencilPlan::apply evaluates weight classes (subdiv::packed); the CSR
    // rows, level by level, are the reference, creased levels included
    let cases = [load("ico_crease.obj"), load("grid_open.obj"), load("torus_semi.obj")];
    for m in &cases {
        for s in Scheme::TRIANGLE {
            for o in [Options::default(), opts(Creasing::Chaikin, BoundaryInterpolation::EdgeAndCorner)] {
                for plan in
                    [StencilPlan::build(&m.ct, s, 3, &o).unwrap(), StencilPlan::build_local(&m.ct, s, 3, &o).unwrap()]
                {
                    let moved: Vec<Vec3> =
                        m.positions.iter().enumerate().map(|(i, p)| *p + Vec3::splat((i % 7) as f32 * 0.01)).collect();
                    let mut out = Vec::new();
                    plan.apply(&moved, &mut PlanScratch::default(), &mut out);
                    let mut csr = moved.clone();
                    for lv in &plan.levels {
                        let mut next = vec![Vec3::ZERO; lv.n_out()];
                        lv.apply(&csr, &mut next);
                        csr = next;
                    }
                    assert!(out == csr, "{s}: packed and CSR rows differ");
                }
            }
        }
    }
}

#[test]
fn tags_round_trip_through_obj_and_ct() {
    let m = load("ico_crease.obj");
    let dir = scratch_dir("creases-roundtrip");
    for ext in ["obj", "ct"] {
        let path = dir.join(format!("ico.{ext}"));
        subdiv::io::save(&path, &m).unwrap();
        let back = subdiv::bundled::load(&path).unwrap();
        assert_eq!(back.ct.sharpness(), m.ct.sharpness(), "{ext}");
        let (a, b) = (sub(&m, Scheme::Loop, 2, &Options::default()), sub(&back, Scheme::Loop, 2, &Options::default()));
        assert!(a.positions == b.positions, "{ext}: the reloaded mesh subdivides the same");
    }
}

#[test]
fn bad_tags_are_refused_with_file_and_line() {
    let dir = scratch_dir("creases-bad");
    let head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    for (tag, want) in [
        ("t crease 2/1/0 0 9 1", "vertex"),
        ("t crease 2/1/0 0 1 nan", "sharpness"),
        ("t crease 2/1/0 0 1 -2", "sharpness"),
        ("t crease 2/1/0 0 1 inf", "sharpness inf: it must be finite and at least 0"),
        ("t corner 1/1/0 0 -1", "sharpness -1: it must be finite and at least 0"),
        ("t corner 1/1/0 7 1", "vertex"),
        ("t crease 2/1/0 0", "crease"),
    ] {
        let p = dir.join("bad.obj");
        std::fs::write(&p, format!("{head}{tag}\n")).unwrap();
        let e = subdiv::bundled::load(&p).unwrap_err().to_string();
        assert!(e.contains("bad.obj:9"), "{tag}: {e}");
        assert!(e.contains(want), "{tag}: {e}");
    }
}

#[test]
fn the_crease_angle_finds_the_cube_edges_and_info_counts_them() {
    let plain = common::bundled("cube.obj");
    let auto = plain.ct.clone().with_angle_creases(&plain.positions, 40.0);
    let tagged = sharp_cube();
    assert_eq!(auto.sharpness(), tagged.ct.sharpness(), "the 12 edges at 90 degrees, not the diagonals at 0");
    assert!(plain.ct.clone().with_angle_creases(&plain.positions, 95.0).sharpness().is_none());
    let s = subdiv::rules::summary(&auto, BoundaryInterpolation::EdgeOnly);
    assert_eq!((s.sharp_edges, s.infinite_edges, s.corners, s.darts, s.crease_vertices), (12, 12, 8, 0, 0));
    // the icosphere fixture: a dart at the end of its infinitely sharp edge,
    // two semi-sharp crease paths
    let ico = load("ico_crease.obj");
    let s = subdiv::rules::summary(&ico.ct, BoundaryInterpolation::EdgeOnly);
    assert_eq!(s.sharp_edges, 6);
    assert_eq!(s.infinite_edges, 1);
    assert!(s.darts >= 2 && s.crease_vertices >= 2, "{s:?}");
    // edge-and-corner makes the open grid's corners of one triangle sharp
    // (two; the other two have two triangles each)
    let grid = load("grid_open.obj");
    let (a, b) = (
        subdiv::rules::summary(&grid.ct, BoundaryInterpolation::EdgeOnly),
        subdiv::rules::summary(&grid.ct, BoundaryInterpolation::EdgeAndCorner),
    );
    assert_eq!(b.sharp_vertices, a.sharp_vertices + 2, "{a:?} {b:?}");
    // on polygons, the corners of one polygon: all four of a quad grid's,
    // though its fan gives two of them two triangles
    let quads =
        subdiv::bundled::load(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark/grid.obj"))
            .unwrap();
    let pt = subdiv::mesh::PolyTable::from_corner_table(&quads.ct);
    let (a, b) = (
        subdiv::rules::poly_summary(&pt, BoundaryInterpolation::EdgeOnly),
        subdiv::rules::poly_summary(&pt, BoundaryInterpolation::EdgeAndCorner),
    );
    assert_eq!((b.sharp_vertices, b.corners), (a.sharp_vertices + 4, a.corners + 4), "{a:?} {b:?}");
    let fan = subdiv::rules::summary(&quads.ct, BoundaryInterpolation::EdgeAndCorner);
    assert_eq!(fan.sharp_vertices, 2, "{fan:?}");
}

#[test]
fn loop_limit_positions_follow_the_crease_curve() {
    // a vertex keeps its id through every split, so its limit at level 2 is
    // where four more levels take it
    let (m, ring) = torus_with_loop(INFINITE);
    let l2 = sub(&m, Scheme::Loop, 2, &Options::default());
    let l6 = sub(&m, Scheme::Loop, 6, &Options::default());
    let lim = subdiv::eval::loop_limit_positions(&l2);
    let smooth = subdiv::eval::loop_limit_positions(&Mesh {
        ct: l2.ct.clone().with_tags(&Tags::default()).unwrap(),
        positions: l2.positions.clone(),
    });
    let (mut worst, mut worst_smooth) = (0.0f32, 0.0f32);
    for v in 0..l2.positions.len() {
        if on_loop(l2.positions[v]) {
            worst = worst.max(lim[v].distance(l6.positions[v]));
            worst_smooth = worst_smooth.max(smooth[v].distance(l6.positions[v]));
        }
    }
    assert!(!ring.is_empty());
    assert!(worst < 2e-4, "crease limit {worst}");
    assert!(worst_smooth > 20.0 * worst, "the smooth mask is visibly off the crease ({worst_smooth} vs {worst})");
}

/// The smallest angle (degrees) between the normals of the two faces of any
/// infinitely sharp edge of `m`.
fn min_sharp_dihedral(m: &Mesh) -> f32 {
    let fnorm = subdiv::mesh::face_normals(&m.ct, &m.positions);
    let s = m.ct.sharpness().expect("sharp edges");
    s.sharp_corners()
        .iter()
        .filter(|&&(_, x)| x >= INFINITE)
        .filter_map(|&(c, _)| {
            let o = m.ct.o(c)?;
            let (a, b) = (fnorm[(c / 3) as usize].normalize(), fnorm[(o / 3) as usize].normalize());
            Some(a.dot(b).clamp(-1.0, 1.0).acos().to_degrees())
        })
        .fold(180.0, f32::min)
}

#[test]
fn the_l_prism_keeps_its_sharp_edges_at_every_level_and_scheme() {
    // its feature edges (90 and 270 degrees) tagged by angle stay sharp: the
    // faces on either side keep meeting at a real angle, where untagged
    // subdivision rounds them off
    let m = common::bundled("lprism.obj");
    let tagged = Mesh { ct: m.ct.clone().with_angle_creases(&m.positions, 40.0), positions: m.positions.clone() };
    for s in Scheme::TRIANGLE {
        for levels in 1..=3 {
            let fine = sub(&tagged, s, levels, &Options::default());
            let angle = min_sharp_dihedral(&fine);
            assert!(angle > 80.0, "{s} L{levels}: a sharp edge's faces meet at only {angle} degrees");
        }
    }
    // untagged, Loop rounds the same edges (measured on the edges that the
    // tags would have kept)
    let smooth = sub(&m, Scheme::Loop, 3, &Options::default());
    let sharp_fine = sub(&tagged, Scheme::Loop, 3, &Options::default());
    let rounded = Mesh {
        ct: smooth.ct.clone().with_tags(&sharp_fine.ct.sharpness().unwrap().to_tags(&sharp_fine.ct)).unwrap(),
        ..smooth
    };
    assert!(min_sharp_dihedral(&rounded) < 30.0);
}
