//! The refiner: its stencils, recorded on first need from the levels it
//! kept, equal a whole recording; local updates equal full evaluation bit
//! for bit, the support is exactly what changes, undo and redo give back
//! the same bits, data of any width and precision refine as positions do,
//! and sharpness edits equal a fresh subdivision of the re-tagged mesh.
//!
//! `Refiner::new`'s points are the one-shot passes'; the first edit
//! evaluates every level by the rows (equal within rounding), as every
//! later edit does. Bit-for-bit comparisons take both sides after that.

mod common;

use common::{Rng, bundled, icosphere};
use glam::{DVec3, Vec3};
use subdiv::mesh::CreaseTag;
use subdiv::mesh::Tags;
use subdiv::{Mesh, Options, Refiner, Scheme, subdivide, subdivide_f64};

/// Where two point lists differ: the count and the largest difference (a
/// short message instead of both lists).
fn differ(a: &[Vec3], b: &[Vec3]) -> Option<(usize, f32)> {
    let n = a.iter().zip(b).filter(|(x, y)| x != y).count() + a.len().abs_diff(b.len());
    let max = a.iter().zip(b).map(|(x, y)| (*x - *y).abs().max_element()).fold(0.0, f32::max);
    (n > 0).then_some((n, max))
}

/// A refiner of `cage` whose levels were evaluated by their rows.
fn by_rows(cage: &Mesh, scheme: Scheme, levels: u32, opts: &Options) -> Refiner {
    let mut fresh = Refiner::new(cage, scheme, levels, opts).unwrap();
    fresh.set_control(&cage.positions);
    fresh
}

/// A refiner whose control points were all set anew: every row evaluated.
fn evaluated_afresh(r: &Refiner) -> (Vec<Vec3>, Vec<Vec3>) {
    let fresh = by_rows(&r.cage(), r.scheme(), r.levels(), r.options());
    (fresh.positions().to_vec(), fresh.normals().to_vec())
}

#[test]
fn the_stencils_recorded_from_the_kept_levels_equal_a_whole_recording() {
    use subdiv::StencilPlan;
    use subdiv::mesh::{BoundaryInterpolation, Creasing};
    let corners = Options { boundary: BoundaryInterpolation::EdgeAndCorner, ..Options::default() };
    let chaikin = Options { creasing: Creasing::Chaikin, ..Options::default() };
    let tags = Tags { creases: vec![CreaseTag { v0: 0, v1: 1, sharpness: 1.5 }], corners: vec![] };
    let mut all: Vec<(String, Mesh, Scheme, u32, Options)> =
        cases().into_iter().map(|(n, m, s, l)| (n.to_string(), m, s, l, Options::default())).collect();
    for scheme in [Scheme::Loop, Scheme::Butterfly, Scheme::CatmullClark] {
        all.push((format!("open grid {scheme:?}"), common::flat_grid(4), scheme, 3, corners));
        let cube = bundled("cube.obj");
        let (a, b) = (cube.ct.v_table()[0], cube.ct.v_table()[1]);
        let tags = Tags { creases: vec![CreaseTag { v0: a, v1: b, sharpness: 1.5 }], ..tags.clone() };
        let creased = Mesh { ct: cube.ct.clone().with_tags(&tags).unwrap(), positions: cube.positions };
        all.push((format!("creased cube {scheme:?}"), creased, scheme, 3, chaikin));
    }
    for (name, mesh, scheme, levels, opts) in all {
        let mut r = Refiner::new(&mesh, scheme, levels, &opts).unwrap();
        let fine = r.positions().to_vec();
        let whole = StencilPlan::build(&mesh.ct, scheme, levels, &opts).unwrap();
        let lazy = r.plan();
        assert_eq!(lazy.levels.len(), whole.levels.len(), "{name}");
        for (l, (a, b)) in lazy.levels.iter().zip(&whole.levels).enumerate() {
            assert_eq!((a.n_in, a.copy_vertices), (b.n_in, b.copy_vertices), "{name}: level {l}");
            assert_eq!((&a.offsets, &a.indices), (&b.offsets, &b.indices), "{name}: level {l} rows");
            assert_eq!(a.weights, b.weights, "{name}: level {l} weights");
        }
        assert_eq!(lazy.ct.v_table(), whole.ct.v_table(), "{name}: the finest topology");
        // the one-shot points and the rows' agree within rounding
        let mut rows = Vec::new();
        whole.apply(&mesh.positions, &mut Default::default(), &mut rows);
        let diff = fine.iter().zip(&rows).map(|(a, b)| (*a - *b).abs().max_element()).fold(0.0, f32::max);
        assert!(fine.len() == rows.len() && diff < 1e-5, "{name}: {diff}");
    }
}

fn cases() -> Vec<(&'static str, Mesh, Scheme, u32)> {
    let cube = bundled("cube.obj");
    let lprism = bundled("lprism.obj");
    vec![
        ("icosphere loop", icosphere(1), Scheme::Loop, 3),
        ("icosphere butterfly", icosphere(1), Scheme::ModifiedButterfly, 2),
        ("torus jarek", bundled("torus.obj"), Scheme::Jarek, 2),
        ("cube catmull-clark", cube.clone(), Scheme::CatmullClark, 3),
        ("lprism catmull-clark", lprism, Scheme::CatmullClark, 2),
        ("cube bilinear", cube, Scheme::Bilinear, 2),
    ]
}

#[test]
fn moving_vertices_updates_exactly_what_a_full_evaluation_gives() {
    let mut rng = Rng(7);
    for (name, mesh, scheme, levels) in cases() {
        let mut r = Refiner::new(&mesh, scheme, levels, &Options::default()).unwrap();
        let n = mesh.positions.len() as u32;
        for k in 0..5 {
            let ids: Vec<u32> = (0..1 + k).map(|_| (rng.next_u64() % n as u64) as u32).collect();
            let to: Vec<Vec3> = ids.iter().map(|&v| r.control()[v as usize] + rng.vec3() * 0.3).collect();
            let changed = r.move_vertices(&ids, &to).unwrap();
            assert!(changed > 0, "{name}: a move changes the surface");
            let (pos, normals) = evaluated_afresh(&r);
            assert_eq!(r.positions(), &pos[..], "{name}: step {k} positions");
            assert_eq!(r.normals(), &normals[..], "{name}: step {k} normals");
        }
    }
}

#[test]
fn the_support_is_exactly_where_the_surface_changes() {
    for (name, mesh, scheme, levels) in cases() {
        let mut r = Refiner::new(&mesh, scheme, levels, &Options::default()).unwrap();
        let v = 3;
        let support = r.support(v);
        let before = r.positions().to_vec();
        assert!(!support.is_empty() && support.len() < before.len(), "{name}: a local support");
        let to = r.control()[v as usize] + Vec3::new(0.37, -0.21, 0.53);
        r.move_vertices(&[v], &[to]).unwrap();
        let moved: Vec<u32> =
            (0..before.len() as u32).filter(|&i| r.positions()[i as usize] != before[i as usize]).collect();
        // every moved point is in the support; the support's points with a
        // non-zero weight moved (a zero weight, as a crease's, may not)
        assert!(moved.iter().all(|i| support.binary_search(i).is_ok()), "{name}: a point outside the support moved");
        assert!(moved.len() * 2 > support.len(), "{name}: {} of {} support points moved", moved.len(), support.len());
    }
}

#[test]
fn undo_and_redo_give_back_the_same_bits() {
    for (name, mesh, scheme, levels) in cases() {
        let mut r = by_rows(&mesh, scheme, levels, &Options::default());
        let first = (r.positions().to_vec(), r.normals().to_vec());
        r.move_vertices(&[0, 1], &[Vec3::splat(0.5), Vec3::splat(-0.25)]).unwrap();
        let moved = r.positions().to_vec();
        r.move_vertices(&[0], &[Vec3::new(2.0, 0.0, 0.0)]).unwrap();
        assert_eq!(r.history_len(), (2, 0));
        assert!(r.undo() && r.undo() && !r.undo(), "{name}");
        assert_eq!((r.positions().to_vec(), r.normals().to_vec()), first, "{name}: undone");
        assert!(r.redo(), "{name}");
        assert_eq!(r.positions(), &moved[..], "{name}: redone");
        r.move_vertices(&[2], &[Vec3::ZERO]).unwrap();
        assert!(!r.redo(), "{name}: a new step clears what was undone");
    }
}

#[test]
fn data_of_any_width_refines_as_the_positions_do() {
    for (name, mesh, scheme, levels) in cases() {
        let r = Refiner::new(&mesh, scheme, levels, &Options::default()).unwrap();
        let flat: Vec<f32> = mesh.positions.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
        let refined = r.refine(&flat, 3).unwrap();
        let as_points: Vec<Vec3> = refined.chunks(3).map(Vec3::from_slice).collect();
        let diff = as_points.iter().zip(r.positions()).map(|(a, b)| (*a - *b).abs().max_element()).fold(0.0, f32::max);
        assert!(diff < 1e-5, "{name}: positions as data differ by {diff}");
        // one channel: the x coordinate alone; five: x, y, z, 1, 2
        let x: Vec<f32> = mesh.positions.iter().map(|p| p.x).collect();
        let rx = r.refine(&x, 1).unwrap();
        assert!(rx.iter().zip(&as_points).all(|(a, p)| (a - p.x).abs() < 1e-6), "{name}: one channel");
        let five: Vec<f32> = mesh.positions.iter().flat_map(|p| [p.x, p.y, p.z, 1.0, 2.0]).collect();
        let r5 = r.refine(&five, 5).unwrap();
        assert!(r5.chunks(5).all(|c| (c[3] - 1.0).abs() < 1e-5 && (c[4] - 2.0).abs() < 1e-5), "{name}: constants kept");
        assert!(r.refine(&x, 2).is_err(), "{name}: a wrong width is refused");
    }
}

#[test]
fn double_data_equals_the_double_subdivision() {
    let mesh = icosphere(1);
    let far: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3() + DVec3::splat(1e6)).collect();
    let r = Refiner::new(&mesh, Scheme::Loop, 2, &Options::default()).unwrap();
    let flat: Vec<f64> = far.iter().flat_map(|p| p.to_array()).collect();
    let refined = r.refine(&flat, 3).unwrap();
    let (_, exact) = subdivide_f64(&mesh, &far, Scheme::Loop, 2, &Options::default()).unwrap();
    let diff =
        refined.chunks(3).zip(&exact).map(|(a, b)| (DVec3::from_slice(a) - *b).abs().max_element()).fold(0.0, f64::max);
    assert!(diff < 1e-9, "a million units out the f64 data keeps its digits ({diff})");
}

#[test]
fn double_data_after_a_sharpness_edit_equals_the_double_subdivision_of_the_retagged_cage() {
    for (name, mesh, scheme, levels) in cases() {
        let (a, b) = (mesh.ct.vtx(0), mesh.ct.vtx(1));
        let mut r = Refiner::new(&mesh, scheme, levels, &Options::default()).unwrap();
        let far: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3() * 3.0 + DVec3::splat(1e6)).collect();
        let flat: Vec<f64> = far.iter().flat_map(|p| p.to_array()).collect();
        let before = r.refine(&flat, 3).unwrap();
        r.set_edge_sharpness(a, b, 2.5).unwrap();
        let after = r.refine(&flat, 3).unwrap();
        let (_, exact) = subdivide_f64(&r.cage(), &far, scheme, levels, &Options::default()).unwrap();
        let exact: Vec<f64> = exact.iter().flat_map(|p| p.to_array()).collect();
        // the recorded rows sum in another order than the one-shot passes
        let worst = after.iter().zip(&exact).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(after.len() == exact.len() && worst < 1e-8, "{name}: the f64 rows follow the new tags ({worst})");
        // bilinear has no smooth rule for a crease to change
        assert!(scheme == Scheme::Bilinear || before != after, "{name}: the crease changes the surface");
    }
}

#[test]
fn a_sharpness_edit_equals_subdividing_the_retagged_mesh() {
    for (scheme, mesh) in [(Scheme::Loop, icosphere(1)), (Scheme::CatmullClark, bundled("cube.obj"))] {
        let mut r = by_rows(&mesh, scheme, 2, &Options::default());
        let plain = r.positions().to_vec();
        let (a, b) = (mesh.ct.v_table()[1], mesh.ct.v_table()[2]);
        r.set_edge_sharpness(a, b, 2.5).unwrap();
        let tags = Tags { creases: vec![CreaseTag { v0: a, v1: b, sharpness: 2.5 }], corners: vec![] };
        let tagged = Mesh { ct: mesh.ct.clone().with_tags(&tags).unwrap(), positions: mesh.positions.clone() };
        let expected = match scheme {
            Scheme::CatmullClark => Refiner::new(&tagged, scheme, 2, &Options::default()).unwrap().positions().to_vec(),
            _ => subdivide(&tagged, scheme, 2, &Options::default()).unwrap().0.positions,
        };
        let diff = r.positions().iter().zip(&expected).map(|(a, b)| (*a - *b).abs().max_element()).fold(0.0, f32::max);
        assert!(diff < 1e-5, "{scheme:?}: {diff}");
        assert_ne!(r.positions(), &plain[..], "{scheme:?}: the crease changed the surface");
        assert_eq!(r.tags().creases.len(), 1);
        r.undo();
        assert_eq!(differ(r.positions(), &plain), None, "{scheme:?}: undone");
        assert!(r.set_edge_sharpness(0, 0, 1.0).is_err(), "not an edge");
    }
}

#[test]
fn the_loop_refiner_equals_subdivide() {
    let mesh = icosphere(2);
    let r = Refiner::new(&mesh, Scheme::Loop, 2, &Options::default()).unwrap();
    let (fine, _) = subdivide(&mesh, Scheme::Loop, 2, &Options::default()).unwrap();
    assert_eq!(r.topology().v_table(), fine.ct.v_table());
    let diff =
        r.positions().iter().zip(&fine.positions).map(|(a, b)| (*a - *b).abs().max_element()).fold(0.0, f32::max);
    assert!(diff < 1e-6, "{diff}");
}

#[test]
fn bad_moves_are_refused_and_change_nothing() {
    let mut r = Refiner::new(&icosphere(1), Scheme::Loop, 1, &Options::default()).unwrap();
    let before = r.positions().to_vec();
    assert!(r.move_vertices(&[1000], &[Vec3::ZERO]).is_err());
    assert!(r.move_vertices(&[0, 1], &[Vec3::ZERO]).is_err());
    assert_eq!(r.positions(), &before[..]);
    assert_eq!(r.history_len(), (0, 0));
    assert!(r.support(1000).is_empty());
}

#[test]
fn a_sharpness_that_is_not_finite_and_at_least_0_is_refused_as_subdivide_refuses_it() {
    let mut r = Refiner::new(&icosphere(1), Scheme::Loop, 2, &Options::default()).unwrap();
    let ct = r.cage().ct;
    let c = ct.edge_owners().next().unwrap();
    let (a, b) = (ct.vtx(subdiv::mesh::n(c)), ct.vtx(subdiv::mesh::p(c)));
    r.set_edge_sharpness(a, b, 2.0).unwrap();
    let (before, tags) = (r.positions().to_vec(), r.tags());
    for bad in [f32::NAN, -1.0, f32::INFINITY, f32::NEG_INFINITY] {
        // the one validation: the message a file's tag or subdivide gets
        let why = subdiv::mesh::checked_sharpness(f64::from(bad)).unwrap_err();
        let e = r.set_edge_sharpness(a, b, bad).unwrap_err();
        assert!(matches!(e, subdiv::Error::Usage(_)), "{e}");
        assert_eq!(e.to_string(), format!("edge {a}-{b} has {why}"));
        let e = r.set_vertex_sharpness(a, bad).unwrap_err();
        assert_eq!(e.to_string(), format!("vertex {a} has {why}"));
        let mesh = r.cage();
        let tag = |sharpness| Tags { creases: vec![CreaseTag { v0: a, v1: b, sharpness }], ..Tags::default() };
        let e = mesh.ct.clone().with_tags(&tag(bad)).unwrap_err().to_string();
        assert!(e.contains(&why), "{e}");
    }
    assert!(why_nan().contains("NaN") && why_nan().ends_with("it must be finite and at least 0"), "{}", why_nan());
    assert_eq!(r.positions(), &before[..], "nothing changed");
    assert_eq!((r.tags(), r.history_len()), (tags, (1, 0)), "the edge kept its sharpness and no step was made");
    // 10 and more is infinitely sharp, stored as 10
    r.set_edge_sharpness(a, b, 1e30).unwrap();
    assert_eq!(r.tags().creases[0].sharpness, subdiv::mesh::INFINITE);
}

fn why_nan() -> String {
    subdiv::mesh::checked_sharpness(f64::NAN).unwrap_err()
}

#[test]
fn sharpness_edits_recorded_where_they_reach_equal_a_fresh_refiner_bit_for_bit() {
    use subdiv::mesh::{BoundaryInterpolation, Creasing};
    let chaikin = Options { creasing: Creasing::Chaikin, ..Options::default() };
    let corners = Options { boundary: BoundaryInterpolation::EdgeAndCorner, ..Options::default() };
    let no_boundary = Options { boundary: BoundaryInterpolation::None, ..Options::default() };
    let cases = [
        ("loop", icosphere(1), Scheme::Loop, Options::default()),
        ("loop chaikin", icosphere(1), Scheme::Loop, chaikin),
        ("butterfly", icosphere(1), Scheme::ModifiedButterfly, Options::default()),
        ("catmull-clark", bundled("lprism.obj"), Scheme::CatmullClark, Options::default()),
        ("catmull-clark chaikin", bundled("cube.obj"), Scheme::CatmullClark, chaikin),
        ("bilinear", bundled("cube.obj"), Scheme::Bilinear, Options::default()),
        ("open loop, corners", common::flat_grid(5), Scheme::Loop, corners),
        ("open catmull-clark, corners", common::flat_grid(5), Scheme::CatmullClark, corners),
        ("open catmull-clark, no boundary", common::flat_grid(5), Scheme::CatmullClark, no_boundary),
    ];
    for (name, mesh, scheme, opts) in cases {
        let mut r = Refiner::new(&mesh, scheme, 3, &opts).unwrap();
        let v = mesh.ct.v_table();
        // an edge made semi-sharp, its neighbour sharper, a corner, then
        // the first edge smooth again
        let edits: [(u32, u32, f32); 3] = [(v[0], v[1], 2.5), (v[1], v[2], 1.5), (v[0], v[1], 0.0)];
        for (k, &(a, b, s)) in edits.iter().enumerate() {
            r.set_edge_sharpness(a, b, s).unwrap();
            if k == 1 {
                r.set_vertex_sharpness(v[2], 3.0).unwrap();
            }
            let fresh = by_rows(&r.cage(), scheme, 3, &opts);
            assert_eq!(differ(r.positions(), fresh.positions()), None, "{name}: edit {k}");
            assert_eq!(differ(r.normals(), fresh.normals()), None, "{name}: edit {k} normals");
            let tags = |t: &subdiv::CornerTable| t.sharpness().map(|s| s.to_tags(t)).unwrap_or_default();
            assert_eq!(tags(r.topology()), tags(fresh.topology()), "{name}: edit {k}: the finest level's tags");
        }
        // moves after the edits read the recorded rows too
        r.move_vertices(&[v[1]], &[Vec3::new(0.3, 0.2, 0.9)]).unwrap();
        let mut fresh = by_rows(&r.cage(), scheme, 3, &opts);
        assert_eq!(differ(r.positions(), fresh.positions()), None, "{name}: a move after the edits");
        // the plan with the rows written in applies to the same points
        let mut out = Vec::new();
        let control = r.control().to_vec();
        r.plan().apply(&control, &mut Default::default(), &mut out);
        assert_eq!(differ(&out, fresh.positions()), None, "{name}: the baked plan");
        let _ = fresh.plan();
        while r.undo() {}
        let first = by_rows(&mesh, scheme, 3, &opts);
        assert_eq!(differ(r.positions(), first.positions()), None, "{name}: everything undone");
    }
}

#[test]
fn a_polygon_cage_refines_to_the_polygons_subdivide_makes() {
    use subdiv::mesh::PolyMesh;
    for (name, mesh) in [("cube", bundled("cube.obj")), ("lprism", bundled("lprism.obj"))] {
        let cage = PolyMesh::from_mesh(&mesh);
        for scheme in [Scheme::CatmullClark, Scheme::Bilinear] {
            let (fine, _) = subdivide(&cage, scheme, 2, &Options::default()).unwrap();
            let r = Refiner::new(&cage, scheme, 2, &Options::default()).unwrap();
            let polygons = r.polygons().expect("a polygon scheme's polygons");
            assert_eq!(polygons.v_table(), fine.pt.v_table(), "{name} {scheme}: the same quads");
            // the recorded rows sum in another order than the one-shot passes
            let worst = differ(r.positions(), &fine.positions).map_or(0.0, |d| d.1);
            assert!(r.positions().len() == fine.positions.len() && worst < 1e-5, "{name} {scheme}: points {worst}");
        }
        assert!(Refiner::new(&cage, Scheme::Loop, 1, &Options::default()).is_err(), "{name}: Loop takes triangles");
    }
}

/// Data refined after a sharpness edit follows the new tags, in f32 as in
/// f64: positions given as data land where the refiner's own points are.
#[test]
fn f32_data_after_a_sharpness_edit_follows_the_new_tags() {
    for (name, mesh, scheme, levels) in cases() {
        let (a, b) = (mesh.ct.vtx(0), mesh.ct.vtx(1));
        let mut r = Refiner::new(&mesh, scheme, levels, &Options::default()).unwrap();
        r.set_edge_sharpness(a, b, 2.5).unwrap();
        let flat: Vec<f32> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
        let data: Vec<Vec3> = r.refine(&flat, 3).unwrap().chunks_exact(3).map(Vec3::from_slice).collect();
        let worst = differ(&data, r.positions()).map_or(0.0, |d| d.1);
        assert!(data.len() == r.positions().len() && worst < 1e-5, "{name}: f32 data after the edit ({worst})");
    }
}

/// The memory budget counts the levels a refiner keeps: at the smallest
/// budget the last level alone fits in (`subdivide_faces`, which keeps no
/// earlier level), a refiner of the same levels is refused, naming its last
/// level; with the earlier levels' room added it is built.
#[test]
fn the_budget_counts_the_levels_a_refiner_keeps() {
    let cage = icosphere(2);
    let levels = 4;
    let fits = |bytes: u64| {
        let opts = Options { max_memory: Some(bytes), ..Options::default() };
        subdiv::subdivide_faces(&cage, Scheme::Loop, levels, &opts, |j| j).is_ok()
    };
    // the smallest budget the faces alone fit in (the check is monotone)
    let (mut lo, mut hi) = (1u64, 1u64 << 40);
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if fits(mid) { hi = mid } else { lo = mid + 1 }
    }
    assert!(fits(lo) && !fits(lo - 1), "the faces alone fit from {lo} bytes");
    let tight = Options { max_memory: Some(lo), ..Options::default() };
    match Refiner::new(&cage, Scheme::Loop, levels, &tight) {
        Err(subdiv::Error::TooLarge { level, .. }) => assert_eq!(level, levels, "the last level is the one refused"),
        other => panic!("a refiner keeping {levels} levels in {lo} bytes: {:?}", other.map(|r| r.levels())),
    }
    let roomy = Options { max_memory: Some(lo + lo / 2), ..Options::default() };
    let r = Refiner::new(&cage, Scheme::Loop, levels, &roomy).expect("the earlier levels are a third of the last");
    assert_eq!(r.levels(), levels);
}

/// `points` flat.
fn flat64(points: &[DVec3]) -> Vec<f64> {
    points.iter().flat_map(|p| p.to_array()).collect()
}

#[test]
fn f64_points_kept_through_edits_equal_refining_the_f64_control_points_whole_bit_for_bit() {
    use subdiv::mesh::BoundaryInterpolation;
    let no_boundary = Options { boundary: BoundaryInterpolation::None, ..Options::default() };
    let mut all = cases();
    all.push(("open catmull-clark, no boundary", common::flat_grid(4), Scheme::CatmullClark, 2));
    for (name, mesh, scheme, levels) in all {
        let opts = if name.contains("no boundary") { no_boundary } else { Options::default() };
        let mut r = Refiner::new(&mesh, scheme, levels, &opts).unwrap();
        let far: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3() * 3.0 + DVec3::splat(1e6)).collect();
        r.set_control_f64(&far).unwrap();
        let whole = |r: &Refiner| r.refine(&flat64(r.control_f64().unwrap()), 3).unwrap();
        assert_eq!(flat64(r.positions_f64().unwrap()), whole(&r), "{name}: kept = refined whole");
        let (ptr, ptr64) = (r.positions().as_ptr(), r.positions_f64().unwrap().as_ptr());
        let v = mesh.ct.v_table();
        let (a, b) = (v[0], v[1]);
        // a millimetre a million units out: lost in f32, kept in f64
        let to = [far[a as usize] + DVec3::new(1e-3, 0.0, 0.0), far[b as usize] - DVec3::new(0.0, 2e-3, 0.0)];
        let before = flat64(r.positions_f64().unwrap());
        let n = r.move_vertices_f64(&[a, b], &to).unwrap();
        assert_eq!(r.control_f64().unwrap()[a as usize], to[0], "{name}: the f64 position as given");
        assert_eq!(r.control()[a as usize], to[0].as_vec3(), "{name}: the f32 one rounded");
        assert_eq!(flat64(r.positions_f64().unwrap()), whole(&r), "{name}: after a move");
        let after = flat64(r.positions_f64().unwrap());
        let moved: Vec<u32> = (0..after.len() / 3)
            .filter(|&i| after[3 * i..3 * i + 3] != before[3 * i..3 * i + 3])
            .map(|i| i as u32)
            .collect();
        let listed = r.last_changed().to_vec();
        assert!(!moved.is_empty() && moved.iter().all(|i| listed.contains(i)), "{name}: every changed row listed");
        assert_eq!(listed.len(), n, "{name}: the count is the list's");
        let mut cage = r.cage();
        cage.positions = r.control().to_vec();
        let (_, exact) = subdivide_f64(&cage, r.control_f64().unwrap(), scheme, levels, &opts).unwrap();
        let worst = after.iter().zip(flat64(&exact)).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-8, "{name}: the f64 subdivision of the moved cage ({worst})");
        r.set_edge_sharpness(a, b, 2.5).unwrap();
        assert_eq!(flat64(r.positions_f64().unwrap()), whole(&r), "{name}: after a sharpness edit");
        r.move_vertices(&[b], &[Vec3::new(0.5, 0.25, 2.0)]).unwrap();
        assert_eq!(r.control_f64().unwrap()[b as usize], DVec3::new(0.5, 0.25, 2.0), "{name}: an f32 move widened");
        assert_eq!(flat64(r.positions_f64().unwrap()), whole(&r), "{name}: after an f32 move");
        assert!(r.undo() && r.undo(), "{name}");
        assert_eq!(flat64(r.positions_f64().unwrap()), after, "{name}: undone to the same bits");
        assert!(r.undo());
        assert_eq!(flat64(r.positions_f64().unwrap()), before, "{name}: back to the start");
        assert!(r.redo() && r.redo() && r.redo());
        assert_eq!(flat64(r.positions_f64().unwrap()), whole(&r), "{name}: redone");
        let ptrs = (r.positions().as_ptr(), r.positions_f64().unwrap().as_ptr());
        assert_eq!(ptrs, (ptr, ptr64), "{name}: the points never left their buffers");
    }
}

#[test]
fn a_sharpness_change_that_refines_anew_keeps_the_points_in_their_buffers() {
    use subdiv::mesh::BoundaryInterpolation;
    let opts = Options { boundary: BoundaryInterpolation::None, ..Options::default() };
    let mesh = common::flat_grid(4);
    let mut r = Refiner::new(&mesh, Scheme::Loop, 2, &opts).unwrap();
    r.move_vertices(&[0], &[Vec3::new(0.0, 0.0, 0.5)]).unwrap();
    let local = r.last_changed().len();
    let ptr = r.positions().as_ptr();
    // a border edge infinitely sharp: no longer a hole there
    let ct = r.cage().ct;
    let c = (0..ct.num_corners() as u32).find(|&c| ct.o(c).is_none()).unwrap();
    let (a, b) = (ct.vtx(subdiv::mesh::n(c)), ct.vtx(subdiv::mesh::p(c)));
    r.set_edge_sharpness(a, b, 10.0).unwrap();
    assert_eq!(r.positions().as_ptr(), ptr, "the finest points stayed where they were");
    assert_eq!(r.last_changed().len(), r.positions().len(), "refined anew: every row listed");
    assert!(local < r.positions().len());
    let fresh = by_rows(&r.cage(), Scheme::Loop, 2, &opts);
    assert_eq!(differ(r.positions(), fresh.positions()), None);
    assert!(r.undo());
    assert_eq!(r.positions().as_ptr(), ptr);
}

#[test]
fn bad_f64_points_are_refused_and_change_nothing() {
    let mesh = icosphere(1);
    let mut r = Refiner::new(&mesh, Scheme::Loop, 1, &Options::default()).unwrap();
    let wide: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    assert!(r.set_control_f64(&wide[1..]).is_err());
    let mut bad = wide.clone();
    bad[3].y = f64::NAN;
    assert!(r.set_control_f64(&bad).is_err());
    bad[3].y = 1e300;
    assert!(r.set_control_f64(&bad).is_err());
    assert!(r.positions_f64().is_none(), "not kept");
    r.set_control_f64(&wide).unwrap();
    let before = flat64(r.positions_f64().unwrap());
    assert!(r.move_vertices_f64(&[0], &[DVec3::new(f64::INFINITY, 0.0, 0.0)]).is_err());
    assert!(r.move_vertices_f64(&[999], &[DVec3::ZERO]).is_err());
    assert_eq!(flat64(r.positions_f64().unwrap()), before);
    assert_eq!(r.history_len(), (0, 0));
}
