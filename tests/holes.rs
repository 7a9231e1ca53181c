//! Holes (OpenSubdiv's `t hole`) and `--boundary none` against OpenSubdiv
//! 3.5's own output (tests/fixtures/*/holes.*, scripts/hole-fixtures.py):
//! every vertex where OpenSubdiv puts it, and the faces written those
//! OpenSubdiv keeps, for Loop and Catmull-Clark; the tags round-trip.

mod common;

use common::{assert_same_points, read_points, scratch_dir};
use glam::Vec3;
use std::path::PathBuf;
use subdiv::mesh::BoundaryInterpolation;
use subdiv::{Options, Scheme};

fn fixture(folder: &str, name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(folder).join(name)
}

/// The centres of the faces of an OBJ text (its `v` and `f` lines).
fn face_centres(text: &str) -> Vec<Vec3> {
    let v: Vec<Vec3> = text
        .lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let c: Vec<f32> = l.split_whitespace().take(3).map(|x| x.parse().unwrap()).collect();
            Vec3::new(c[0], c[1], c[2])
        })
        .collect();
    text.lines()
        .filter_map(|l| l.strip_prefix("f "))
        .map(|l| {
            let ids: Vec<usize> = l.split_whitespace().map(|t| t.split('/').next().unwrap().parse().unwrap()).collect();
            ids.iter().map(|&i| v[i - 1]).sum::<Vec3>() / ids.len() as f32
        })
        .collect()
}

#[test]
fn holes_and_boundary_none_equal_opensubdiv() {
    let dir = scratch_dir("holes");
    for (folder, scheme) in [("catmark", Scheme::CatmullClark), ("creases", Scheme::Loop)] {
        let control = fixture(folder, "holes.obj");
        let mesh = subdiv::bundled::load(&control).unwrap();
        assert!(!mesh.ct.holes().is_empty(), "{folder}: the hole tags were read");
        for (boundary, name) in [(BoundaryInterpolation::EdgeOnly, "edge"), (BoundaryInterpolation::None, "none")] {
            for level in [1, 2] {
                let what = format!("{scheme} {name} L{level}");
                let theirs = fixture(folder, &format!("holes.{name}.L{level}.osd.txt"));
                let opts = Options { boundary, ..Options::default() };
                let (fine, _) = subdiv::subdivide(&mesh, scheme, level, &opts).unwrap();
                // every vertex, those of the holes too, where OpenSubdiv puts it
                assert_same_points(&fine.positions, &read_points(&theirs), 1e-5, &what);
                // the faces written: OpenSubdiv's, the holes' children left out
                let out = dir.join(format!("{folder}-{name}-{level}.obj"));
                subdiv::io::save(&out, &fine).unwrap();
                let (ours, osd) = (std::fs::read_to_string(&out).unwrap(), std::fs::read_to_string(&theirs).unwrap());
                let (a, b) = (face_centres(&ours), face_centres(&osd));
                assert!(b.len() < fine.ct.num_triangles(), "{what}: OpenSubdiv leaves faces out");
                assert_same_points(&a, &b, 1e-5, &format!("{what}: face centres"));
            }
        }
    }
}

#[test]
fn hole_tags_round_trip_and_bad_ones_are_refused() {
    let dir = scratch_dir("hole-tags");
    let control = fixture("catmark", "holes.obj");
    let mesh = subdiv::bundled::load(&control).unwrap();
    // a control mesh keeps its holes as tags in OBJ
    let out = dir.join("control.obj");
    subdiv::io::save(&out, &mesh).unwrap();
    let back = subdiv::bundled::load(&out).unwrap();
    assert_eq!(back.ct.holes(), mesh.ct.holes());
    let poly = subdiv::mesh::PolyMesh::from_mesh(&back);
    assert_eq!(poly.pt.holes(), [7, 12], "the file's faces");
    // a tag naming no face is refused at its line
    let text = std::fs::read_to_string(&control).unwrap().replace("t hole 2/0/0 7 12", "t hole 1/0/0 99");
    let e = common::mesh_of(text.as_bytes(), "bad.obj").unwrap_err().to_string();
    assert!(e.contains("bad.obj") && e.contains("face 99 out of range"), "{e}");
    let e = common::mesh_of(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nt hole x 0\n", "bad.obj").unwrap_err().to_string();
    assert!(e.contains("hole tag"), "{e}");
}

#[test]
fn holes_are_neither_drawn_nor_picked() {
    let mesh = subdiv::bundled::load(&fixture("catmark", "holes.obj")).unwrap();
    let opts = Options::default();
    let (fine, _) = subdiv::subdivide(&mesh, Scheme::CatmullClark, 2, &opts).unwrap();
    let filled = subdiv::Mesh { ct: fine.ct.clone().with_holes(Vec::new()), positions: fine.positions.clone() };
    // a ray straight down through the middle of a hole's children misses
    let t = fine.ct.holes()[0];
    let v = fine.ct.v_table();
    let centre = (0..3).map(|k| fine.positions[v[3 * t as usize + k] as usize]).sum::<Vec3>() / 3.0;
    let (origin, dir) = (centre + Vec3::Z * 10.0, -Vec3::Z);
    assert!(subdiv::pick::first_hit(&filled, origin, dir).is_some());
    assert!(subdiv::pick::first_hit(&fine, origin, dir).is_none(), "a hole is picked");
    #[cfg(feature = "viewer")]
    {
        let Some(mut off) = common::offscreen(240, 180) else { return };
        let opts = subdiv::render::RenderOptions { width: 240, height: 180, ..Default::default() };
        let cam = subdiv::render::default_camera(&filled, &opts);
        let mut covered = |m: &subdiv::Mesh| {
            let gm = off.upload(m).unwrap();
            let img = off.render_one(cam, &gm, None, subdiv::render::Shading::Phong.look()).unwrap();
            let bg = |x: u32, y: u32| {
                let b = subdiv::render::background_srgb8_at(y, img.height());
                (0..3).all(|i| img.get_pixel(x, y).0[i].abs_diff(b[i]) <= 1)
            };
            (0..240).flat_map(|x| (0..180).map(move |y| (x, y))).filter(|&(x, y)| !bg(x, y)).count()
        };
        let (with, without) = (covered(&fine), covered(&filled));
        // two of 25 faces are holes: about 8% of the surface's pixels
        assert!((with as f64) < 0.96 * without as f64, "holes drawn: {with} pixels against {without}");
    }
}
