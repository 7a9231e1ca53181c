//! `subdivide_faces` (the last level without O, C or valence) gives the same
//! bits as `subdivide`: positions and V table, for every triangle scheme,
//! open and closed meshes, creases, corners, semi-sharp decay, both boundary
//! options, any level count and any thread count; and `subdivide` writes
//! the same file either way.

mod common;
use common::*;
use subdiv::mesh::{BoundaryInterpolation, Creasing};
use subdiv::mesh::{CornerTag, CreaseTag, Tags};
use subdiv::{LoopBeta, Mesh, Options, Scheme, subdivide, subdivide_faces};

/// `mesh` with every edge of the first `k` triangles tagged `s` and its
/// vertex 0 a corner of sharpness `corner`.
fn creased(mut mesh: Mesh, k: u32, s: f32, corner: f32) -> Mesh {
    let v = mesh.ct.v_table().to_vec();
    let creases = (0..3 * k as usize)
        .map(|c| CreaseTag { v0: v[c], v1: v[if c % 3 == 2 { c - 2 } else { c + 1 }], sharpness: s })
        .collect();
    let tags = Tags { creases, corners: vec![CornerTag { vertex: 0, sharpness: corner }] };
    mesh.ct = mesh.ct.clone().with_tags(&tags).unwrap();
    mesh
}

fn cases() -> Vec<(String, Mesh, Options)> {
    let d = Options::default;
    let corners = Options { boundary: BoundaryInterpolation::EdgeAndCorner, ..d() };
    let chaikin = Options { creasing: Creasing::Chaikin, ..d() };
    let warren = Options { loop_beta: LoopBeta::Warren, ..d() };
    let open = grid(6, 5, |i, j| glam::Vec3::new(i + 0.3 * j, j, 0.1 * (i * j).sin()));
    vec![
        ("icosphere".into(), icosphere(2), d()),
        ("icosphere, Warren".into(), icosphere(1), warren),
        ("open grid".into(), open.clone(), d()),
        ("open grid, corners".into(), open, corners),
        ("hemisphere".into(), hemisphere(), d()),
        ("disk fan".into(), disk_fan(9, 2), d()),
        ("infinite creases".into(), creased(icosphere(1), 6, 10.0, 10.0), d()),
        ("semi-sharp".into(), creased(icosphere(1), 5, 1.5, 0.7), d()),
        ("semi-sharp, Chaikin".into(), creased(icosphere(1), 5, 2.3, 1.2), chaikin),
        ("creased grid, corners".into(), creased(disk_fan(7, 2), 4, 10.0, 2.0), corners),
    ]
}

const SCHEMES: [Scheme; 5] =
    [Scheme::Loop, Scheme::Midpoint, Scheme::Butterfly, Scheme::ModifiedButterfly, Scheme::Jarek];

fn assert_same_bits(name: &str, full: &Mesh, faces: &subdiv::mesh::Faces) {
    assert_eq!(full.ct.v_table(), &faces.corners[..], "{name}: V table");
    assert_eq!(full.positions.len(), faces.positions.len(), "{name}: vertex count");
    for (i, (a, b)) in full.positions.iter().zip(&faces.positions).enumerate() {
        assert_eq!(a.to_array().map(f32::to_bits), b.to_array().map(f32::to_bits), "{name}: vertex {i}");
    }
}

#[test]
fn faces_only_equal_the_full_subdivision_bit_for_bit() {
    for (name, mesh, opts) in cases() {
        for scheme in SCHEMES {
            for levels in 0..=3 {
                let (full, st) = subdivide(&mesh, scheme, levels, &opts).unwrap();
                let (faces, st_faces) = subdivide_faces(&mesh, scheme, levels, &opts, |j| j).unwrap();
                let what = format!("{name}, {scheme}, {levels} levels");
                assert_same_bits(&what, &full, &faces);
                assert_eq!(st.faces_per_level, st_faces.faces_per_level, "{what}");
                assert_eq!((faces.num_faces(), faces.sides), (full.ct.num_triangles(), 3), "{what}");
            }
        }
    }
}

#[test]
fn faces_only_equal_the_full_subdivision_on_any_thread_count() {
    // creased and smooth, the last split over several of its parallel
    // chunks (61,440 corners before the last level, 16,384 a chunk)
    for (name, mesh) in [("creased", creased(icosphere(4), 40, 1.7, 3.0)), ("smooth", icosphere(4))] {
        let (full, _) = subdivide(&mesh, Scheme::Loop, 2, &Options::default()).unwrap();
        assert!(full.ct.num_corners() / 4 > 3 * 16_384, "{name}: several chunks");
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let (faces, _) =
                pool.install(|| subdivide_faces(&mesh, Scheme::Loop, 2, &Options::default(), |j| j)).unwrap();
            assert_same_bits(&format!("{name} icosphere on {threads} threads"), &full, &faces);
        }
    }
}

#[test]
fn polygon_schemes_give_their_triangulated_faces() {
    let mesh = icosphere(1);
    for scheme in [Scheme::CatmullClark, Scheme::Bilinear] {
        let (full, _) = subdivide(&mesh, scheme, 2, &Options::default()).unwrap();
        let (faces, _) = subdivide_faces(&mesh, scheme, 2, &Options::default(), |j| j).unwrap();
        assert_same_bits(&format!("{scheme}"), &full, &faces);
    }
}

#[test]
fn faces_are_written_as_the_mesh_is() {
    use subdiv::io;
    use subdiv::mesh::Attributes;
    let (full, _) = subdivide(&icosphere(2), Scheme::Loop, 2, &Options::default()).unwrap();
    let (faces, _) = subdivide_faces(&icosphere(2), Scheme::Loop, 2, &Options::default(), |j| j).unwrap();
    let colors = Attributes { colors: Some(full.positions.iter().map(|p| p.abs()).collect()), ..Default::default() };
    let uv = Attributes {
        uv: Some(full.ct.v_table().iter().map(|&v| glam::Vec2::new(v as f32 * 1e-4, 0.5)).collect()),
        ..Default::default()
    };
    let dir = scratch_dir("faces_only");
    let mut checked = 0;
    for ext in ["ply", "obj", "off", "stl", "glb"] {
        assert!(io::writes_faces(std::path::Path::new(&format!("a.{ext}")), false), "{ext}");
        for attrs in [Attributes::default(), colors.clone(), uv.clone()] {
            let (a, b) = (dir.join(format!("mesh.{ext}")), dir.join(format!("faces.{ext}")));
            io::save_with(&a, &full, &attrs).unwrap();
            io::save_with(&b, &faces, &attrs).unwrap();
            assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap(), "{ext}");
            checked += 1;
        }
    }
    assert_eq!(checked, 15);
    // the formats that keep creases need the table for a creased mesh; .ct always
    assert!(!io::writes_faces(std::path::Path::new("a.obj"), true));
    assert!(io::writes_faces(std::path::Path::new("a.ply"), true));
    assert!(!io::writes_faces(std::path::Path::new("a.ct"), false));
    let err = io::save_with(&dir.join("faces.ct"), &faces, &Attributes::default()).unwrap_err().to_string();
    assert!(err.contains("faces.ct"), "{err}");
}

fn load_poly(name: &str) -> subdiv::mesh::PolyMesh {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark").join(name);
    subdiv::mesh::PolyMesh::from_mesh(&subdiv::bundled::load(&path).unwrap())
}

fn poly_cases() -> Vec<(&'static str, subdiv::mesh::PolyMesh, Options)> {
    let d = Options::default;
    vec![
        ("cube", load_poly("cube.obj"), d()),
        ("cube_creases", load_poly("cube_creases.obj"), d()),
        ("cube_creases chaikin", load_poly("cube_creases.obj"), Options { creasing: Creasing::Chaikin, ..d() }),
        ("grid", load_poly("grid.obj"), d()),
        ("grid corners", load_poly("grid.obj"), Options { boundary: BoundaryInterpolation::EdgeAndCorner, ..d() }),
        ("ngons", load_poly("ngons.obj"), d()),
    ]
}

#[test]
fn quads_alone_equal_the_polygon_subdivision_bit_for_bit() {
    use subdiv::{subdivide, subdivide_faces};
    for (name, mesh, opts) in poly_cases() {
        for scheme in [Scheme::CatmullClark, Scheme::Bilinear] {
            for levels in 1..=3 {
                let what = format!("{name}, {scheme}, {levels} levels");
                let (full, st) = subdivide(&mesh, scheme, levels, &opts).unwrap();
                let (faces, st_faces) = subdivide_faces(&mesh, scheme, levels, &opts, |j| j).unwrap();
                assert_eq!(faces.sides, 4, "{what}");
                assert_eq!(full.pt.v_table(), &faces.corners[..], "{what}: corners");
                let bits = |p: &[glam::Vec3]| p.iter().flat_map(|q| q.to_array().map(f32::to_bits)).collect::<Vec<_>>();
                assert_eq!(bits(&full.positions), bits(&faces.positions), "{what}: positions");
                assert_eq!(st.faces_per_level, st_faces.faces_per_level, "{what}");
            }
        }
        assert!(subdivide_faces(&mesh, Scheme::CatmullClark, 0, &opts, |j| j).is_err(), "{name}: no levels");
        assert!(subdivide_faces(&mesh, Scheme::Loop, 1, &opts, |j| j).is_err(), "{name}: a triangle scheme");
    }
}

#[test]
fn quads_are_written_as_the_polygon_mesh_is() {
    use subdiv::io;
    use subdiv::mesh::{Attributes, Material, MaterialGroups};
    let control = load_poly("ngons.obj");
    let (full, _) = subdiv::subdivide(&control, Scheme::CatmullClark, 2, &Options::default()).unwrap();
    let (faces, _) = subdiv::subdivide_faces(&control, Scheme::CatmullClark, 2, &Options::default(), |j| j).unwrap();
    let nf = full.pt.num_faces();
    let colors = Attributes { colors: Some(full.positions.iter().map(|p| p.abs()).collect()), ..Default::default() };
    let uv = Attributes {
        uv: Some(full.pt.v_table().iter().map(|&v| glam::Vec2::new(v as f32 * 1e-3, 0.25)).collect()),
        materials: Some(MaterialGroups {
            face: (0..nf as u32).map(|f| f % 2).collect(),
            list: vec![Material::named("a"), Material::named("b")],
            libraries: vec![],
            scene: None,
        }),
        ..Default::default()
    };
    let dir = scratch_dir("faces_only_quads");
    for ext in ["ply", "obj", "off", "stl", "glb"] {
        for attrs in [Attributes::default(), colors.clone(), uv.clone()] {
            let (a, b) = (dir.join(format!("poly.{ext}")), dir.join(format!("quads.{ext}")));
            io::save_with(&a, &full, &attrs).unwrap();
            io::save_with(&b, &faces, &attrs).unwrap();
            assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap(), "{ext}");
        }
    }
    // faces that are neither triangles nor quads, or name a missing vertex
    let five = subdiv::mesh::Faces { sides: 5, ..faces.clone() };
    assert!(io::save_with(&dir.join("five.ply"), &five, &Attributes::default()).is_err());
    let mut broken = faces.clone();
    broken.corners[7] = broken.positions.len() as u32;
    let err = io::save_with(&dir.join("broken.stl"), &broken, &Attributes::default()).unwrap_err().to_string();
    assert!(err.contains("corner 7"), "{err}");
}

/// A renumbering as a caller might ask for it: wider ids, the first `keep`
/// vertices moved to the end of a longer list, the others shifted.
fn renumber(j: u32, keep: u32) -> i64 {
    if j < keep { 1_000_000 + i64::from(j) } else { i64::from(j - keep) }
}

#[test]
fn ids_written_through_a_map_are_the_mapped_table() {
    use subdiv::subdivide_faces;
    for (name, mesh, opts) in cases() {
        for scheme in [Scheme::Loop, Scheme::Butterfly, Scheme::CatmullClark] {
            for levels in 0..=2 {
                let what = format!("{name}, {scheme}, {levels} levels");
                let (plain, _) = subdivide_faces(&mesh, scheme, levels, &opts, |j| j).unwrap();
                let (wide, _) = subdivide_faces(&mesh, scheme, levels, &opts, |j| renumber(j, 5)).unwrap();
                let mapped: Vec<i64> = plain.corners.iter().map(|&j| renumber(j, 5)).collect();
                assert_eq!(wide.corners, mapped, "{what}: corners");
                assert_eq!(wide.positions, plain.positions, "{what}: positions");
                assert_eq!(wide.sides, plain.sides, "{what}");
            }
        }
    }
}

#[test]
fn quad_ids_written_through_a_map_are_the_mapped_table() {
    use subdiv::subdivide_faces;
    for (name, mesh, opts) in poly_cases() {
        for levels in 1..=2 {
            let what = format!("{name}, {levels} levels");
            let (plain, _) = subdivide_faces(&mesh, Scheme::CatmullClark, levels, &opts, |j| j).unwrap();
            let (wide, _) = subdivide_faces(&mesh, Scheme::CatmullClark, levels, &opts, |j| renumber(j, 3)).unwrap();
            let mapped: Vec<i64> = plain.corners.iter().map(|&j| renumber(j, 3)).collect();
            assert_eq!(wide.corners, mapped, "{what}: corners");
            assert_eq!(wide.positions, plain.positions, "{what}: positions");
        }
    }
}

/// The f64 faces alone (`subdivide_faces_f64`: the same one-shot passes in
/// f64, the last level without its tables) equal the f64 levels with their
/// tables (`subdivide_f64`) bit for bit, for every triangle scheme and
/// case; and a million units out they are the f32 positions' to f32's
/// spacing, which says both run the same rules.
#[test]
fn f64_faces_only_equal_the_f64_subdivision_bit_for_bit() {
    for (name, mesh, opts) in cases() {
        let control: Vec<glam::DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        for scheme in SCHEMES {
            for levels in 1..=2 {
                let what = format!("{name}, {scheme} L{levels}");
                let (full, pos) = subdiv::subdivide_f64(&mesh, &control, scheme, levels, &opts).unwrap();
                let (faces, _) = subdiv::subdivide_faces_f64(&mesh, &control, scheme, levels, &opts, |j| j).unwrap();
                assert_eq!(faces.positions, pos, "{what}: positions");
                let kept: Vec<u32> = (0..full.ct.num_triangles() as u32)
                    .filter(|t| full.ct.holes().binary_search(t).is_err())
                    .flat_map(|t| full.ct.v_table()[3 * t as usize..3 * t as usize + 3].to_vec())
                    .collect();
                assert_eq!(faces.corners, kept, "{what}: faces");
                let (single, _) = subdivide(&mesh, scheme, levels, &opts).unwrap();
                let worst = single.positions.iter().zip(&pos).map(|(a, b)| (a.as_dvec3() - *b).abs().max_element());
                assert!(worst.fold(0.0, f64::max) < 1e-5, "{what}: f32 and f64 run the same rules");
            }
        }
    }
    let bad = subdiv::subdivide_faces_f64(&icosphere(1), &[], Scheme::Loop, 1, &Options::default(), |j| j);
    assert!(bad.is_err(), "a wrong count of control points is refused");
}
