//! Inspection values: creation levels follow the split's vertex numbering,
//! displacement from the control surface.

mod common;
use common::*;
use subdiv::mesh::{displacement_from_control, vertex_counts_per_level, vertex_creation_level};
use subdiv::{Mesh, Options, Scheme, subdivide};

fn sub(m: &Mesh, s: Scheme, levels: u32) -> Mesh {
    subdivide(m, s, levels, &Options::default()).unwrap().0
}

/// The predicted counts are the real ones, level by level, open and closed.
#[test]
fn vertex_counts_match_subdivision() {
    for (name, m) in all_meshes() {
        let counts = vertex_counts_per_level(&m.ct, 3);
        let mut cur = m.clone();
        assert_eq!(counts[0], m.positions.len(), "{name}");
        for (level, &want) in counts.iter().enumerate().skip(1) {
            cur = sub(&cur, Scheme::Midpoint, 1);
            assert_eq!(cur.positions.len(), want, "{name} level {level}");
        }
    }
}

/// The layout claim: after L levels, the vertices created at level <= k are
/// exactly the vertices of level k, with the same ids. For an interpolating
/// scheme they therefore keep their level-k positions; a vertex created at
/// level k is a new edge vertex there (id >= V_{k-1}).
#[test]
fn creation_level_matches_an_actual_subdivision() {
    for (name, m) in all_meshes() {
        let levels: Vec<Mesh> = (0..=3).map(|l| sub(&m, Scheme::ModifiedButterfly, l)).collect();
        let counts: Vec<usize> = levels.iter().map(|x| x.positions.len()).collect();
        let fine = &levels[3];
        let lv = vertex_creation_level(&counts, fine.positions.len());
        assert_eq!(lv.len(), fine.positions.len());
        for (i, &l) in lv.iter().enumerate() {
            let l = l as usize;
            // the level that created vertex i holds it at the same position, and no earlier level has it
            assert_eq!(levels[l].positions[i], fine.positions[i], "{name}: vertex {i} (level {l}) moved");
            if l > 0 {
                assert!(i >= counts[l - 1], "{name}: vertex {i} already existed before level {l}");
            }
        }
        // every level's new vertices are counted once
        for l in 0..=3u8 {
            let k = lv.iter().filter(|&&x| x == l).count();
            let want = if l == 0 { counts[0] } else { counts[l as usize] - counts[l as usize - 1] };
            assert_eq!(k, want, "{name}: level {l}");
        }
    }
}

/// Midpoint subdivision never leaves the control surface.
#[test]
fn midpoint_displacement_is_zero() {
    for (name, m) in all_meshes() {
        let fine = sub(&m, Scheme::Midpoint, 2);
        let d = displacement_from_control(&m, &fine, 2).unwrap();
        assert_eq!(d.len(), fine.positions.len());
        assert!(d.iter().all(|&x| x == 0.0), "{name}");
    }
}

/// Interpolating schemes keep the control vertices, approximating ones move
/// them: zero displacement at level-0 vertices for the butterflies, not for
/// Loop on a convex closed mesh; new vertices of a curved mesh move off the
/// control triangles for every smoothing scheme.
#[test]
fn interpolating_schemes_have_zero_displacement_at_control_vertices() {
    let m = icosahedron();
    let nv0 = m.positions.len();
    for s in [Scheme::Butterfly, Scheme::ModifiedButterfly, Scheme::Loop, Scheme::Jarek] {
        let fine = sub(&m, s, 3);
        let d = displacement_from_control(&m, &fine, 3).unwrap();
        let at_control = d[..nv0].iter().copied().fold(0.0f32, f32::max);
        if s.is_interpolating() {
            assert_eq!(at_control, 0.0, "{s}");
        } else {
            assert!(d[..nv0].iter().all(|&x| x > 0.05), "{s}: {at_control}");
        }
        assert!(d[nv0..].iter().copied().fold(0.0f32, f32::max) > 0.05, "{s}: new vertices did not move");
    }
}

/// Loop on a flat regular grid (affine image of the lattice): interior
/// vertices away from the boundary reproduce the midpoint positions exactly
/// (linear precision), so their displacement is 0 while the mesh is planar.
#[test]
fn loop_on_a_plane_has_no_displacement_normal_to_it() {
    let m = flat_grid(4);
    let fine = sub(&m, Scheme::Loop, 2);
    let d = displacement_from_control(&m, &fine, 2).unwrap();
    // Loop keeps a plane: the displacement is in-plane only
    for (q, &x) in fine.positions.iter().zip(&d) {
        assert_eq!(q.z, 0.0);
        assert!(x.is_finite());
    }
    // the centre vertex (2, 2) has a fully regular 2-ring: it does not move
    assert!(d[2 * 5 + 2] < 1e-6, "{}", d[12]);
}

#[test]
fn mismatched_meshes_are_an_error() {
    let m = icosahedron();
    let fine = sub(&m, Scheme::Loop, 2);
    assert!(displacement_from_control(&m, &fine, 1).is_err());
    assert!(displacement_from_control(&flat_grid(2), &fine, 2).is_err());
}
