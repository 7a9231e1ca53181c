//! Catmull-Clark and bilinear on polygons: OpenSubdiv 3.5's own output on
//! the fixtures of `scripts/catmark-fixtures.py` (smooth, n-gons, both
//! boundary options, creases uniform and Chaikin, corners, darts; texture
//! coordinates linear and smooth), the mathematics (affine invariance), and
//! the polygon formats' round trip.

mod common;

use common::{assert_same_points, read_points};
use glam::Vec3;
use std::path::PathBuf;
use subdiv::mesh::PolyMesh;
use subdiv::mesh::{BoundaryInterpolation, Creasing};
use subdiv::{Options, Scheme, subdivide};

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark").join(name)
}

/// The polygon mesh of a fixture, with its tags.
fn load(name: &str) -> PolyMesh {
    let m = subdiv::bundled::load(&fixture(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    PolyMesh::from_mesh(&m)
}

/// The face count OpenSubdiv wrote (`# faces N`).
fn osd_faces(path: &std::path::Path) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    text.lines().find_map(|l| l.strip_prefix("# faces ")).and_then(|n| n.trim().parse().ok()).unwrap()
}

#[test]
fn catmull_clark_equals_opensubdiv() {
    // thresholds: every comparison of Sdc::Crease at its boundary
    // (scripts/threshold-fixtures.py)
    let cases: [(&str, &str, Creasing, BoundaryInterpolation, &[u32]); 9] = [
        ("thresholds", "uniform", Creasing::Uniform, BoundaryInterpolation::EdgeOnly, &[1, 2, 3]),
        ("thresholds", "chaikin", Creasing::Chaikin, BoundaryInterpolation::EdgeOnly, &[1, 2, 3]),
        ("cube", "uniform", Creasing::Uniform, BoundaryInterpolation::EdgeOnly, &[1, 2, 3]),
        ("ngons", "uniform", Creasing::Uniform, BoundaryInterpolation::EdgeOnly, &[1, 2]),
        ("grid", "uniform", Creasing::Uniform, BoundaryInterpolation::EdgeOnly, &[2]),
        ("grid", "corners", Creasing::Uniform, BoundaryInterpolation::EdgeAndCorner, &[2]),
        ("cube_creases", "uniform", Creasing::Uniform, BoundaryInterpolation::EdgeOnly, &[2, 3]),
        ("cube_creases", "chaikin", Creasing::Chaikin, BoundaryInterpolation::EdgeOnly, &[3]),
        ("grid_dart", "uniform", Creasing::Uniform, BoundaryInterpolation::EdgeOnly, &[2]),
    ];
    for (name, opts, creasing, boundary, levels) in cases {
        let control = load(&format!("{name}.obj"));
        for &n in levels {
            let o = Options { creasing, boundary, ..Options::default() };
            let (fine, _) = subdivide(&control, Scheme::CatmullClark, n, &o).unwrap();
            let path = fixture(&format!("{name}.{opts}.L{n}.osd.txt"));
            let what = format!("{name} {opts} L{n}");
            assert_eq!(fine.pt.num_faces(), osd_faces(&path), "{what}: faces");
            assert!(fine.pt.is_quads(), "{what}: quads");
            assert_same_points(&fine.positions, &read_points(&path), 1e-5, &what);
        }
    }
}

/// An affine map of the control points maps every level the same way
/// (every stencil's weights sum to 1), creases and boundaries included.
#[test]
fn affine_maps_commute_with_the_polygon_schemes() {
    let m = glam::Affine3A::from_mat3_translation(
        glam::Mat3::from_cols(Vec3::new(1.2, 0.3, -0.1), Vec3::new(-0.4, 0.9, 0.2), Vec3::new(0.1, 0.05, 1.4)),
        Vec3::new(3.0, -2.0, 0.5),
    );
    for name in ["ngons.obj", "grid.obj", "cube_creases.obj"] {
        let control = load(name);
        let moved = PolyMesh {
            positions: control.positions.iter().map(|&p| m.transform_point3(p)).collect(),
            ..control.clone()
        };
        for scheme in Scheme::POLYGON {
            let (a, _) = subdivide(&control, scheme, 2, &Options::default()).unwrap();
            let (b, _) = subdivide(&moved, scheme, 2, &Options::default()).unwrap();
            for (p, q) in a.positions.iter().zip(&b.positions) {
                assert!(m.transform_point3(*p).distance(*q) < 1e-4, "{name} {scheme}");
            }
        }
    }
}

/// Bilinear: old vertices stay, edge points are midpoints, face points
/// centroids; Catmull-Clark keeps the old vertices' ids (row i of the
/// result is input vertex i's new position).
#[test]
fn bilinear_points_and_the_numbering_of_new_vertices() {
    let control = load("ngons.obj");
    let (fine, _) = subdivide(&control, Scheme::Bilinear, 1, &Options::default()).unwrap();
    let (nv, ne, nf) = (control.pt.num_vertices(), control.pt.num_edges(), control.pt.num_faces());
    assert_eq!(fine.positions.len(), nv + ne + nf);
    assert_eq!(&fine.positions[..nv], &control.positions[..]);
    for f in 0..nf as u32 {
        let r = control.pt.face_corners(f);
        let k = (r.end - r.start) as f32;
        let centroid = r.map(|c| control.positions[control.pt.vtx(c) as usize]).sum::<Vec3>() / k;
        assert!(fine.positions[nv + ne + f as usize].distance(centroid) < 1e-6);
    }
    let edge_points = &fine.positions[nv..nv + ne];
    for e in edge_points {
        // every edge point is the midpoint of some control edge
        let found = (0..control.pt.num_corners() as u32).any(|c| {
            let (a, b) = (control.pt.vtx(c), control.pt.vtx(control.pt.next(c)));
            ((control.positions[a as usize] + control.positions[b as usize]) * 0.5).distance(*e) < 1e-6
        });
        assert!(found, "{e}");
    }
    // a polygon mesh through the triangle pipeline gives the same points
    let mesh = subdiv::bundled::load(&fixture("ngons.obj")).unwrap();
    let (tri, _) = subdiv::subdivide(&mesh, Scheme::CatmullClark, 2, &Options::default()).unwrap();
    let (poly, _) = subdivide(&control, Scheme::CatmullClark, 2, &Options::default()).unwrap();
    assert_eq!(tri.positions, poly.positions);
    assert_eq!(tri.ct.num_triangles(), 2 * poly.pt.num_faces());
}

/// Faces as vertex lists, each rotated to start at its least id (a reader
/// may start a polygon at another corner), in file order.
fn face_lists(m: &PolyMesh) -> Vec<Vec<u32>> {
    m.faces()
        .map(|f| {
            let k = (0..f.len()).min_by_key(|&i| f[i]).unwrap_or(0);
            f[k..].iter().chain(&f[..k]).copied().collect()
        })
        .collect()
}

/// OBJ, PLY, OFF and `.ct` write polygons and read them back as the same
/// polygons (faces of 3 to 6 corners and the quads of a level), positions
/// exactly as written.
#[test]
fn polygon_formats_round_trip() {
    let dir = common::scratch_dir("poly-round-trip");
    let control = load("ngons.obj");
    let (level1, _) = subdivide(&control, Scheme::CatmullClark, 1, &Options::default()).unwrap();
    for (what, mesh) in [("ngons", &control), ("ngons L1", &level1)] {
        for ext in ["obj", "ply", "off", "ct"] {
            let path = dir.join(format!("{}.{ext}", what.replace(' ', "_")));
            subdiv::io::save_with(&path, mesh, &Default::default()).unwrap();
            let back = PolyMesh::from_mesh(&subdiv::bundled::load(&path).unwrap_or_else(|e| panic!("{ext}: {e}")));
            assert_eq!(face_lists(&back), face_lists(mesh), "{what} .{ext}: faces");
            for (a, b) in back.positions.iter().zip(&mesh.positions) {
                assert!((*a - *b).length() < 1e-6, "{what} .{ext}: {a} against {b}");
            }
        }
    }
}

/// A `.ct` polygon file's twin rows are checked: one that does not name the
/// corner across the same edge is refused with the row's line (faces of 3
/// to 6 corners before it).
#[test]
fn ct_polygon_twins_are_checked() {
    let dir = common::scratch_dir("poly-ct-twins");
    let path = dir.join("two.ct");
    let control = load("ngons.obj");
    subdiv::io::save_with(&path, &control, &Default::default()).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(subdiv::bundled::load(&path).is_ok());
    // Swap two twin entries: each row still names corners, but not the ones
    // across the same edge.
    // The twin rows follow the vertex count, the positions, `polygons F`
    // and the F face rows.
    let faces = control.pt.num_faces();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    // the last face's row: the faces before it have 3 to 6 corners, so its
    // line is found by the faces' sizes, not by equal shares
    let row = 1 + control.positions.len() + 1 + faces + (faces - 1);
    let mut ids: Vec<String> = lines[row].split_whitespace().map(str::to_string).collect();
    let k = ids.iter().position(|s| s != "-1").expect("an inner edge");
    let j = ids.iter().rposition(|s| s != "-1" && s != &ids[k]).unwrap_or(k);
    ids.swap(k, j);
    if k == j {
        ids[k] = "0".into();
    }
    lines[row] = ids.join(" ");
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    let err = subdiv::bundled::load(&path).expect_err("a wrong twin is refused").to_string();
    assert!(err.contains(&format!("two.ct:{}:", row + 1)) && err.contains("twin"), "{err}");
}

/// The `c x y z u v` lines of a face-varying fixture: each fine corner's
/// position and texture coordinate.
fn read_corners(path: &std::path::Path) -> Vec<[f32; 5]> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .filter_map(|l| l.strip_prefix("c "))
        .map(|l| {
            let x: Vec<f32> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            [x[0], x[1], x[2], x[3], x[4]]
        })
        .collect()
}

/// Texture coordinates through Catmull-Clark equal OpenSubdiv's
/// face-varying interpolation, linear (`FVAR_LINEAR_ALL`) and smooth
/// (`FVAR_LINEAR_CORNERS_ONLY`), on a cube unfolded as a cross (seams where
/// a vertex has two or three values), faces of 3 to 6 corners with a seam,
/// and an open grid with both boundary options: every fine corner's
/// (position, texture coordinate) is one of OpenSubdiv's, one for one.
#[test]
fn texture_coordinates_equal_opensubdiv_face_varying() {
    use subdiv::mesh::UvInterpolation;
    let (edge, corners) = (BoundaryInterpolation::EdgeOnly, BoundaryInterpolation::EdgeAndCorner);
    let (linear, smooth) = (UvInterpolation::Linear, UvInterpolation::Smooth);
    let (uniform, chaikin) = (Creasing::Uniform, Creasing::Chaikin);
    let cases = [
        ("cube_uv", "all.L2", linear, edge, uniform, 2),
        ("cube_uv", "corners.L2", smooth, edge, uniform, 2),
        ("ngons_uv", "all.L2", linear, edge, uniform, 2),
        ("ngons_uv", "corners.L2", smooth, edge, uniform, 2),
        ("grid_uv", "corners.L2", smooth, edge, uniform, 2),
        ("grid_uv", "corners.vtxcorners.L2", smooth, corners, uniform, 2),
        ("cube_creases_uv", "all.L2", linear, edge, uniform, 2),
        ("cube_creases_uv", "corners.L2", smooth, edge, uniform, 2),
        ("cube_creases_uv", "corners.chaikin.L3", smooth, edge, chaikin, 3),
    ];
    for (name, mode, uv, boundary, creasing, level) in cases {
        let opts = subdiv::io::ReadOptions { attributes: true, ..Default::default() };
        let loaded = subdiv::io::read(subdiv::io::Source::File(&fixture(&format!("{name}.obj"))), &opts).unwrap();
        let (control, attrs) = PolyMesh::from_mesh_with_attributes(&loaded.mesh, &loaded.attributes);
        let o = Options { uv, boundary, creasing, ..Options::default() };
        let (fine, _) = subdivide(&control, Scheme::CatmullClark, level, &o).unwrap();
        let fine_uv = subdiv::Refiner::new(&control, Scheme::CatmullClark, level, &o)
            .unwrap()
            .attributes(&attrs)
            .unwrap()
            .uv
            .expect("uvs");
        let want = read_corners(&fixture(&format!("{name}.uv.{mode}.osd.txt")));
        let what = format!("{name} {mode}");
        assert_eq!(fine_uv.len(), want.len(), "{what}: corners");
        let mut taken = vec![false; want.len()];
        for (c, t) in fine_uv.iter().enumerate() {
            let p = fine.positions[fine.pt.vtx(c as u32) as usize];
            let close = |w: &[f32; 5]| {
                (p - Vec3::new(w[0], w[1], w[2])).abs().max_element() < 1e-5
                    && (t.x - w[3]).abs() < 1e-5
                    && (t.y - w[4]).abs() < 1e-5
            };
            let k = (0..want.len()).find(|&k| !taken[k] && close(&want[k]));
            let k = k.unwrap_or_else(|| panic!("{what}: corner {c} at {p} with uv {t} is not OpenSubdiv's"));
            taken[k] = true;
        }
    }
}

/// Asking for a repair keeps the polygons of a file that needs none: the
/// bundled critter reads as its 172 quads either way.
#[test]
fn a_repair_with_nothing_to_mend_keeps_the_polygons() {
    for topology in [subdiv::io::Topology::Refuse, subdiv::io::Topology::Repair] {
        let opts = subdiv::io::ReadOptions { topology, ..Default::default() };
        let loaded = subdiv::bundled::read(std::path::Path::new("bundled:critter.obj"), &opts).unwrap();
        let pm = PolyMesh::from_mesh(&loaded.mesh);
        assert_eq!((pm.pt.num_faces(), pm.pt.is_quads()), (172, true), "{topology:?}");
    }
}

/// OpenSubdiv's two rules for triangles in a Catmull-Clark mesh
/// (`Sdc::Options::TriangleSubdivision`), quads and triangles mixed, a
/// semi-sharp crease among them (scripts/triangle-fixtures.py).
#[test]
fn both_triangle_rules_equal_opensubdiv() {
    use subdiv::mesh::TriangleSubdivision;
    let control = load("tri_quads.obj");
    let mut outs = Vec::new();
    for (rule, name) in [(TriangleSubdivision::Catmark, "catmark"), (TriangleSubdivision::Smooth, "smooth")] {
        for n in [1, 2] {
            let o = Options { triangles: rule, ..Options::default() };
            let (fine, _) = subdivide(&control, Scheme::CatmullClark, n, &o).unwrap();
            let path = fixture(&format!("tri_quads.{name}.L{n}.osd.txt"));
            let what = format!("tri_quads {name} L{n}");
            assert_eq!(fine.pt.num_faces(), osd_faces(&path), "{what}: faces");
            assert_same_points(&fine.positions, &read_points(&path), 1e-5, &what);
            // the plan records the same rule
            let plan = subdiv::StencilPlan::build(&control.triangulated().ct, Scheme::CatmullClark, n, &o).unwrap();
            let mut out = Vec::new();
            plan.apply(&control.positions, &mut subdiv::rules::PlanScratch::for_plan(&plan), &mut out);
            let worst = out.iter().zip(&fine.positions).map(|(a, b)| a.distance(*b)).fold(0.0f32, f32::max);
            assert!(worst < 1e-5, "{what}: the plan is {worst} away");
            outs.push(fine.positions);
        }
    }
    assert_ne!(outs[0], outs[2], "the smooth rule moves the points of the triangles' edges");
}
