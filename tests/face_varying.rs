//! Texture coordinates in all six of OpenSubdiv's face-varying modes
//! (`Sdc::Options::FVarLinearInterpolation`), for Catmull-Clark and Loop,
//! against OpenSubdiv 3.5's own output (tests/fixtures/*/fvar.*,
//! scripts/fvar-fixtures.py): three charts meeting at a vertex, a dart,
//! open chart borders.

mod common;

use glam::{Vec2, Vec3};
use std::path::PathBuf;
use subdiv::mesh::UvInterpolation;
use subdiv::{Options, Scheme};

fn fixture(folder: &str, name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures").join(folder).join(name)
}

/// Every face corner of an OBJ's faces as (position, texture coordinate).
fn osd_corners(path: &std::path::Path) -> Vec<(Vec3, Vec2)> {
    let text = std::fs::read_to_string(path).unwrap();
    let num = |l: &str| -> Vec<f32> { l.split_whitespace().map(|x| x.parse().unwrap()).collect() };
    let v: Vec<Vec3> = text.lines().filter_map(|l| l.strip_prefix("v ")).map(|l| Vec3::from_slice(&num(l))).collect();
    let t: Vec<Vec2> = text.lines().filter_map(|l| l.strip_prefix("vt ")).map(|l| Vec2::from_slice(&num(l))).collect();
    text.lines()
        .filter_map(|l| l.strip_prefix("f "))
        .flat_map(|l| {
            l.split_whitespace()
                .map(|c| {
                    let mut ids = c.split('/').map(|x| x.parse::<usize>().unwrap() - 1);
                    let (a, b) = (ids.next().unwrap(), ids.next().unwrap());
                    (v[a], t[b])
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// The worst distance from one of `ours` to the nearest of `theirs` at
/// the same position, in texture space.
fn worst_uv(ours: &[(Vec3, Vec2)], theirs: &[(Vec3, Vec2)]) -> f32 {
    ours.iter()
        .map(|&(p, t)| {
            theirs.iter().filter(|q| q.0.distance(p) < 1e-5).map(|q| q.1.distance(t)).fold(f32::INFINITY, f32::min)
        })
        .fold(0.0, f32::max)
}

#[test]
fn every_face_varying_mode_equals_opensubdiv() {
    for (folder, scheme) in [("catmark", Scheme::CatmullClark), ("creases", Scheme::Loop)] {
        let (mesh, attrs) = common::load_with_attributes(&fixture(folder, "fvar.obj"));
        let mut results = Vec::new();
        for mode in UvInterpolation::ALL {
            let what = format!("{scheme} {}", mode.name());
            let opts = Options { uv: mode, ..Options::default() };
            let (fine, _) = subdiv::subdivide(&mesh, scheme, 2, &opts).unwrap();
            let fa = subdiv::Refiner::new(&mesh, scheme, 2, &opts).unwrap().attributes(&attrs).unwrap();
            let uv = fa.uv.expect("texture coordinates refined");
            assert_eq!(uv.len(), fine.ct.num_corners(), "{what}");
            let ours: Vec<(Vec3, Vec2)> =
                fine.ct.v_table().iter().zip(&uv).map(|(&v, &t)| (fine.positions[v as usize], t)).collect();
            let theirs = osd_corners(&fixture(folder, &format!("fvar.{}.L2.osd.obj", mode.name())));
            let (a, b) = (worst_uv(&ours, &theirs), worst_uv(&theirs, &ours));
            assert!(a < 1e-5 && b < 1e-5, "{what}: texture coordinates {a} / {b} from OpenSubdiv's");
            results.push(ours);
        }
        // the modes differ on this layout (corners, junction, dart, borders)
        for i in 1..results.len() {
            if UvInterpolation::ALL[i] != UvInterpolation::CornersPlus1 {
                assert!(worst_uv(&results[i], &results[i - 1]) > 1e-3, "{scheme}: mode {i} changes nothing");
            }
        }
    }
}
