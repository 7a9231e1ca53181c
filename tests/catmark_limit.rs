//! Catmull-Clark limit positions and tangents against OpenSubdiv 3.5's
//! `PrimvarRefiner::Limit` (fixtures of scripts/osd-fvar-limit-fixtures.py:
//! smooth, n-gons, an open grid both ways, a dart, creases uniform and
//! Chaikin with semi-sharp edges and a corner), mask for mask, and against
//! the mathematics: the limit is the same point from the next level, the
//! refined mesh converges to it, and the normals agree with finite
//! differences of the refined surface.

mod common;

use glam::Vec3;
use std::path::PathBuf;
use subdiv::eval::{LimitFrame, frame_from, frames_at, limit_frames, limit_positions_f64};
use subdiv::mesh::PolyMesh;
use subdiv::mesh::{BoundaryInterpolation, Creasing};
use subdiv::{Options, Scheme, subdivide};

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark").join(name)
}

fn load(name: &str) -> PolyMesh {
    PolyMesh::from_mesh(&subdiv::bundled::load(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}")))
}

/// One vertex of a limit fixture: refined position, limit position, tan1,
/// tan2, the far end of OpenSubdiv's edge 0.
struct OsdVertex {
    refined: Vec3,
    limit: Vec3,
    tan1: Vec3,
    tan2: Vec3,
    e0: Vec3,
}

fn read_limit(name: &str) -> Vec<OsdVertex> {
    let text = std::fs::read_to_string(fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    text.lines()
        .filter_map(|l| l.strip_prefix("l "))
        .map(|l| {
            let x: Vec<f32> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            let v = |i: usize| Vec3::new(x[i], x[i + 1], x[i + 2]);
            OsdVertex { refined: v(0), limit: v(3), tan1: v(6), tan2: v(9), e0: v(12) }
        })
        .collect()
}

/// The fixture vertex at `p` (refined positions are distinct).
fn osd_at(osd: &[OsdVertex], p: Vec3, what: &str) -> usize {
    osd.iter()
        .position(|o| (o.refined - p).abs().max_element() < 1e-5)
        .unwrap_or_else(|| panic!("{what}: no vertex at {p}"))
}

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol * b.abs().max_element().max(1.0)
}

struct Case {
    name: &'static str,
    opts: &'static str,
    level: u32,
    creasing: Creasing,
    boundary: BoundaryInterpolation,
}

const CASES: [Case; 8] = {
    use BoundaryInterpolation::{EdgeAndCorner, EdgeOnly};
    use Creasing::{Chaikin, Uniform};
    [
        Case { name: "cube", opts: "uniform", level: 1, creasing: Uniform, boundary: EdgeOnly },
        Case { name: "cube", opts: "uniform", level: 2, creasing: Uniform, boundary: EdgeOnly },
        Case { name: "ngons", opts: "uniform", level: 1, creasing: Uniform, boundary: EdgeOnly },
        Case { name: "grid", opts: "uniform", level: 1, creasing: Uniform, boundary: EdgeOnly },
        Case { name: "grid", opts: "corners", level: 1, creasing: Uniform, boundary: EdgeAndCorner },
        Case { name: "grid_dart", opts: "uniform", level: 1, creasing: Uniform, boundary: EdgeOnly },
        Case { name: "cube_creases", opts: "uniform", level: 2, creasing: Uniform, boundary: EdgeOnly },
        Case { name: "cube_creases", opts: "chaikin", level: 3, creasing: Chaikin, boundary: EdgeOnly },
    ]
};

/// The refined level `case` names and its options.
fn level_of(case: &Case) -> (PolyMesh, Options) {
    let o = Options { creasing: case.creasing, boundary: case.boundary, ..Options::default() };
    let (fine, _) = subdivide(&load(&format!("{}.obj", case.name)), Scheme::CatmullClark, case.level, &o).unwrap();
    (fine, o)
}

/// Where our limit position differs from OpenSubdiv's (at a dart, whose
/// smooth mask OpenSubdiv uses is not its eigenvector), ours is the one the
/// refined surface converges to: seven more levels lie ten times nearer to
/// ours than to OpenSubdiv's, and within 1e-4 of it.
fn exact_where_opensubdiv_is_not(fine: &PolyMesh, o: &Options, v: usize, ours: Vec3, theirs: Vec3, what: &str) {
    let (deep, _) = subdivide(fine, Scheme::CatmullClark, 7, o).unwrap();
    let (to_ours, to_theirs) = (deep.positions[v].distance(ours), deep.positions[v].distance(theirs));
    assert!(
        to_ours < 1e-4 && to_ours * 10.0 < to_theirs,
        "{what} vertex {v}: ours {ours}, OpenSubdiv's {theirs}; level +7 is {to_ours} from ours, {to_theirs} from OpenSubdiv's"
    );
}

/// Mask for mask: on the level the fixture was evaluated at, every vertex's
/// limit position and both tangents equal OpenSubdiv's, its fan started at
/// OpenSubdiv's edge 0 (the masks' frame); the rules are the level's own,
/// semi-sharp edges counting as sharp, as OpenSubdiv's `Limit` takes them.
#[test]
fn limit_masks_equal_opensubdiv() {
    for case in &CASES {
        let what = format!("{} {} L{}", case.name, case.opts, case.level);
        let (fine, o) = level_of(case);
        let osd = read_limit(&format!("{}.limit.{}.L{}.osd.txt", case.name, case.opts, case.level));
        assert_eq!(osd.len(), fine.positions.len(), "{what}: vertices");
        let pt = &fine.pt;
        for v in 0..pt.num_vertices() as u32 {
            let o_v = &osd[osd_at(&osd, fine.positions[v as usize], &what)];
            let first = pt
                .fan(v)
                .find(|&c| (fine.positions[pt.vtx(pt.next(c)) as usize] - o_v.e0).abs().max_element() < 1e-5)
                .unwrap_or_else(|| panic!("{what}: vertex {v} has no edge to OpenSubdiv's e0"));
            let f = frame_from(pt, &fine.positions, o.creasing, v, first).expect("quads");
            let at = format!("{what} vertex {v} at {}", fine.positions[v as usize]);
            if !close(f.position, o_v.limit, 1e-5) {
                exact_where_opensubdiv_is_not(&fine, &o, v as usize, f.position, o_v.limit, &at);
            }
            assert!(close(f.tan1, o_v.tan1, 1e-4), "{at}: tan1 {} against {}", f.tan1, o_v.tan1);
            assert!(close(f.tan2, o_v.tan2, 1e-4), "{at}: tan2 {} against {}", f.tan2, o_v.tan2);
        }
    }
}

/// The frames of a whole level (each fan from its own first corner) give
/// OpenSubdiv's positions and normals: where edge 0 falls changes the
/// tangents, not their plane.
#[test]
fn limit_normals_equal_opensubdiv_from_any_edge() {
    for case in &CASES {
        let what = format!("{} {} L{}", case.name, case.opts, case.level);
        let (fine, o) = level_of(case);
        let osd = read_limit(&format!("{}.limit.{}.L{}.osd.txt", case.name, case.opts, case.level));
        let frames = frames_at(&fine.pt, &fine.positions, o.creasing);
        for (v, f) in frames.iter().enumerate() {
            let o_v = &osd[osd_at(&osd, fine.positions[v], &what)];
            let want = LimitFrame { position: o_v.limit, tan1: o_v.tan1, tan2: o_v.tan2 };
            if !close(f.position, want.position, 1e-5) {
                exact_where_opensubdiv_is_not(&fine, &o, v, f.position, want.position, &what);
            }
            let interior_crease = !fine.pt.is_boundary_vertex(v as u32) && f.tan1.dot(want.tan1) < 0.0;
            // an interior crease's two sides are two surfaces: OpenSubdiv's
            // frame takes the side after its edge 0, ours after our first
            if !interior_crease {
                assert!(
                    f.normal().distance(want.normal()) < 1e-4,
                    "{what} vertex {v}: {} against {}",
                    f.normal(),
                    want.normal()
                );
            }
        }
    }
}

/// Faces of 3 to 6 corners: the limit refines once (OpenSubdiv's masks are
/// for quads; its `Limit` on the control level is off by up to 0.07) and
/// equals OpenSubdiv's limit of the same vertices one level down.
#[test]
fn limit_of_ngons_refines_to_quads_first() {
    let control = load("ngons.obj");
    assert!(!control.pt.is_quads());
    let frames = limit_frames(&control, &Options::default()).unwrap();
    let osd = read_limit("ngons.limit.uniform.L1.osd.txt");
    // OpenSubdiv numbers the children of the old vertices first, in order
    for (v, f) in frames.iter().enumerate() {
        assert!(close(f.position, osd[v].limit, 1e-5), "vertex {v}: {} against {}", f.position, osd[v].limit);
    }
}

/// A semi-sharp crease is not sharp in the limit: the limit refines until
/// it has decayed, so level 2 of the creased cube (edges of sharpness 1.3,
/// 2.2, 1.7, a corner of 2.5) gets OpenSubdiv's limit from level 3, where
/// nothing semi-sharp is left, not its level-2 `Limit` (off by 0.157).
#[test]
fn limit_waits_for_semi_sharp_features_to_decay() {
    let case = &CASES[6];
    let (fine, o) = level_of(case);
    let frames = limit_frames(&fine, &o).unwrap();
    let at2 = read_limit("cube_creases.limit.uniform.L2.osd.txt");
    let at3 = read_limit("cube_creases.limit.uniform.L3.osd.txt");
    let mut differs = 0;
    for (v, f) in frames.iter().enumerate() {
        let i = osd_at(&at2, fine.positions[v], "cube_creases L2");
        // vertex i of level 3 is the child of vertex i of level 2
        assert!(close(f.position, at3[i].limit, 1e-5), "vertex {v}: {} against {}", f.position, at3[i].limit);
        differs += usize::from(!close(at2[i].limit, at3[i].limit, 1e-3));
    }
    assert!(differs > 0, "the fixture has vertices where level 2's rules are not the limit's");
}

/// The limit is a fixed point of refinement: the frames of a level's
/// vertices equal those of the same vertices one level finer (positions
/// exactly up to rounding, normals too), on smooth, open, darted and
/// creased meshes; and the refined mesh converges to it.
#[test]
fn limit_is_the_same_from_the_next_level_and_the_mesh_converges() {
    for case in &CASES {
        let what = format!("{} {} L{}", case.name, case.opts, case.level);
        let (fine, o) = level_of(case);
        let here = limit_frames(&fine, &o).unwrap();
        let (finer, _) = subdivide(&fine, Scheme::CatmullClark, 1, &o).unwrap();
        let next = limit_frames(&finer, &o).unwrap();
        let (deep, _) = subdivide(&fine, Scheme::CatmullClark, 6, &o).unwrap();
        let dart = case.name == "grid_dart";
        for (v, f) in here.iter().enumerate() {
            let g = next[v];
            assert!(close(f.position, g.position, 1e-5), "{what} vertex {v}: {} then {}", f.position, g.position);
            // a dart's tangents are OpenSubdiv's smooth masks, not its own
            // eigenvectors: its normal may turn a little from level to level
            let turn = if dart { 2e-2 } else { 1e-4 };
            assert!(f.normal().distance(g.normal()) < turn, "{what} vertex {v}: normal");
            let gap = deep.positions[v].distance(f.position);
            assert!(gap < 2e-3, "{what} vertex {v}: level +6 is {gap} from the limit");
        }
    }
}

/// The f64 limit: OpenSubdiv's limit positions from the f64 control points
/// (ngons, refined to quads first; the creased cube, refined until its
/// semi-sharp features decay), and a million units from the origin the
/// same surface moved, to f64's digits there.
#[test]
fn the_f64_limit_equals_opensubdiv_and_keeps_its_digits_far_out() {
    for (name, fixture_name, opts) in [
        ("ngons.obj", "ngons.limit.uniform.L1.osd.txt", Options::default()),
        ("cube_creases.obj", "cube_creases.limit.uniform.L3.osd.txt", Options::default()),
    ] {
        let control = load(name);
        let exact: Vec<glam::DVec3> = control.positions.iter().map(|p| p.as_dvec3()).collect();
        let ours = limit_positions_f64(&control, &exact, &opts).unwrap();
        let osd = read_limit(fixture_name);
        // OpenSubdiv numbers the children of the old vertices first, in order
        for (v, p) in ours.iter().enumerate() {
            assert!(close(p.as_vec3(), osd[v].limit, 1e-5), "{name} vertex {v}: {p} against {}", osd[v].limit);
        }
        let shift = glam::DVec3::new(1e6, -2e6, 3e6);
        let far: Vec<glam::DVec3> = exact.iter().map(|p| *p + shift).collect();
        let moved = limit_positions_f64(&control, &far, &opts).unwrap();
        let worst = moved.iter().zip(&ours).map(|(a, b)| (*a - shift - *b).abs().max_element()).fold(0.0, f64::max);
        assert!(worst < 1e-8, "{name}: a million units out the limit keeps its digits ({worst})");
    }
    assert!(limit_positions_f64(&load("ngons.obj"), &[], &Options::default()).is_err(), "a wrong count is refused");
}
