//! Texture coordinates and colours through subdivision: UVs linear inside
//! each triangle with seams kept, colours with the scheme's weights, OBJ
//! round trips, parser errors and the command line.

mod common;
use common::*;
use glam::{Vec2, Vec3};
use subdiv::mesh::{Attributes, refine_corner_uvs};
use subdiv::{Options, Scheme, subdivide};

#[test]
fn uvs_are_linear_inside_triangles_and_seams_stay_sharp() {
    // A flat 6x6 grid; the right half is a second chart shifted by (100, 0).
    let mesh = grid(6, 6, |i, j| Vec3::new(i, j, 0.0));
    let chart = |tri: &[u32], pos: &[Vec3]| {
        let cx = tri.iter().map(|&v| pos[v as usize].x).sum::<f32>() / 3.0;
        if cx > 3.0 { Vec2::new(100.0, 0.0) } else { Vec2::ZERO }
    };
    let uv: Vec<Vec2> = mesh
        .triangles()
        .chunks_exact(3)
        .flat_map(|t| {
            let off = chart(t, &mesh.positions);
            t.iter().map(move |&v| (v, off))
        })
        .map(|(v, off)| mesh.positions[v as usize].truncate() + off)
        .collect();
    for levels in 1..=3 {
        // midpoint keeps every point on the plane, so uv must equal (x, y) + the chart offset
        let (fine, _) = subdivide(&mesh, Scheme::Midpoint, levels, &Options::default()).unwrap();
        let fuv = refine_corner_uvs(&uv, levels);
        assert_eq!(fuv.len(), fine.ct.v_table().len());
        for (t, tri) in fine.ct.v_table().chunks_exact(3).enumerate() {
            let off = chart(tri, &fine.positions);
            for k in 0..3 {
                let want = fine.positions[tri[k] as usize].truncate() + off;
                assert!(
                    (fuv[3 * t + k] - want).length() < 1e-5,
                    "level {levels} triangle {t}: {} vs {want}",
                    fuv[3 * t + k]
                );
            }
        }
    }
}

#[test]
fn colours_use_the_scheme_weights_and_reproduce_affine_fields() {
    let mesh = bundled("torus.obj");
    let (lo, hi) = mesh.bounds();
    let field =
        |q: Vec3| Vec3::splat(0.2) + 0.6 * (q - lo) / (hi - lo).max(Vec3::splat(1e-6)) * Vec3::new(1.0, 0.5, 0.25);
    let attrs = Attributes {
        uv: None,
        materials: None,
        options: Default::default(),
        colors: Some(mesh.positions.iter().map(|&q| field(q)).collect()),
    };
    for scheme in [Scheme::Loop, Scheme::Midpoint, Scheme::Jarek] {
        let (fine, _) = subdivide(&mesh, scheme, 2, &Options::default()).unwrap();
        let out = subdiv::Refiner::new(&mesh, scheme, 2, &Options::default()).unwrap().attributes(&attrs).unwrap();
        let colors = out.colors.unwrap();
        assert_eq!(colors.len(), fine.positions.len());
        for (c, q) in colors.iter().zip(&fine.positions) {
            assert!((*c - field(*q)).length() < 1e-4, "{scheme}: {c} vs {}", field(*q));
        }
    }
    // Overshoot of an interpolating scheme is clamped into [0, 1].
    let spiky = Attributes {
        uv: None,
        materials: None,
        options: Default::default(),
        colors: Some((0..mesh.positions.len()).map(|i| if i % 2 == 0 { Vec3::ONE } else { Vec3::ZERO }).collect()),
    };
    let out = subdiv::Refiner::new(&mesh, Scheme::Butterfly, 1, &Options::default())
        .unwrap()
        .attributes(&spiky)
        .unwrap()
        .colors
        .unwrap();
    assert!(out.iter().all(|c| c.cmpge(Vec3::ZERO).all() && c.cmple(Vec3::ONE).all()));
}

#[test]
fn obj_round_trip_with_texture_coordinates_and_colours() {
    let text = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nv 1 1 0 0.5 0.5 0.5\nv 9 9 9 1 1 1\n\
                vt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nf 1/1 2/2 3/3\nf 2/2 4/4 3/3\n";
    let (mesh, attrs) = with_attributes(text.as_bytes(), "t.obj").unwrap();
    assert_eq!(mesh.positions.len(), 4, "the unused vertex 5 is dropped");
    let colors = attrs.colors.clone().unwrap();
    assert_eq!(colors, vec![Vec3::X, Vec3::Y, Vec3::Z, Vec3::splat(0.5)], "colours follow the renumbering");
    assert_eq!(attrs.uv.as_ref().unwrap()[4], Vec2::ONE);
    let mut bytes = Vec::new();
    subdiv::io::write_obj_with(&mesh, &attrs, &mut |b| {
        bytes.extend_from_slice(b);
        Ok(())
    })
    .unwrap();
    let (again, attrs2) = with_attributes(&bytes, "again.obj").unwrap();
    assert_eq!(
        (again.ct.v_table().to_vec(), again.positions.clone()),
        (mesh.ct.v_table().to_vec(), mesh.positions.clone())
    );
    assert_eq!(attrs2, attrs);
}

#[test]
fn bad_texture_and_colour_records_name_the_line() {
    for (text, line, what) in [
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", 5, "texture index 2"),
        ("v 0 0 0\nv 1 0 0 red 0 0\n", 2, "colour 'red'"),
        ("vt 0 nan\n", 1, "not finite"),
        ("vt 0\n", 1, "texture coordinate has 1"),
    ] {
        let e = with_attributes(text.as_bytes(), "bad.obj").unwrap_err().to_string();
        assert!(e.contains(&format!("bad.obj:{line}")) && e.contains(what), "{e}");
    }
}

#[test]
#[cfg(feature = "cli")]
fn subdivide_command_carries_attributes_into_obj() {
    let dir = scratch_dir("attrs");
    let input = dir.join("quad.obj");
    std::fs::write(&input, "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nv 1 1 0 1 1 1\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nf 1/1 2/2 4/4 3/3\n").unwrap();
    let output = dir.join("quad2.obj");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_subdiv"))
        .args(["subdivide", input.to_str().unwrap(), output.to_str().unwrap(), "-s", "loop", "-n", "2"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (mesh, attrs) = load_with_attributes(&output);
    assert_eq!(mesh.ct.num_triangles(), 2 * 16);
    assert_eq!(attrs.uv.unwrap().len(), 3 * 32);
    let colors = attrs.colors.unwrap();
    assert_eq!(colors.len(), mesh.positions.len());
    // PLY keeps the colours, not the texture coordinates: those are dropped,
    // with a note, and the colours are the OBJ's, point for point
    let ply = dir.join("quad2.ply");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_subdiv"))
        .args(["subdivide", input.to_str().unwrap(), ply.to_str().unwrap(), "-s", "loop", "-n", "2"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("keeps no texture coordinates") && !err.contains("colours"), "{err}");
    let (from_ply, ply_attrs) = load_with_attributes(&ply);
    assert!(ply_attrs.uv.is_none());
    assert_eq!(from_ply.positions, mesh.positions, "the same refinement");
    let ply_colors = ply_attrs.colors.expect("PLY keeps the colours");
    let off = ply_colors.iter().zip(&colors).map(|(a, b)| (*a - *b).abs().max_element()).fold(0.0, f32::max);
    assert!(off <= 1.0 / 255.0, "PLY's colours are the OBJ's within a byte's step: {off}");
    let _ = std::fs::remove_dir_all(&dir);
}
