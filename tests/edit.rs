//! Edge flip and edge split on the corner table: after any sequence of edits
//! O, C and the valences equal a rebuild from V, every corner-table identity
//! holds, and the counts change as the topology says.

mod common;
use common::*;
use glam::Vec3;
use subdiv::mesh::{BORDER, n, p};
use subdiv::mesh::{EditError, flip_edge, split_edge};
use subdiv::mesh::{check_invariants, topology};
use subdiv::{CornerTable, Mesh};

/// The triangles as a sorted list of rotation-normalised triples (keeps orientation).
fn triangle_set(ct: &CornerTable) -> Vec<[u32; 3]> {
    let mut v: Vec<[u32; 3]> = ct
        .v_table()
        .chunks_exact(3)
        .map(|t| {
            let k = (0..3).min_by_key(|&i| t[i]).unwrap();
            [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
        })
        .collect();
    v.sort_unstable();
    v
}

/// O, valences and the boundary fan starts equal a from-scratch build; every
/// identity holds; `from_vo` accepts V and O.
fn assert_consistent(ct: &CornerTable, what: &str) {
    check_invariants(ct).unwrap_or_else(|e| panic!("{what}: {e}"));
    let (rebuilt, report, kept) = CornerTable::build(ct.num_vertices(), ct.v_table(), None).unwrap();
    assert!(kept.is_none() && report.unreferenced == 0, "{what}: a vertex lost all its triangles");
    assert_eq!(rebuilt.o_table(), ct.o_table(), "{what}: O differs from a rebuild");
    assert_eq!(rebuilt.valences(), ct.valences(), "{what}: valences differ from a rebuild");
    for v in 0..ct.num_vertices() {
        if ct.is_boundary_vertex(v as u32) {
            assert_eq!(rebuilt.c_table()[v], ct.c_table()[v], "{what}: C[{v}] is not the fan start");
        }
    }
    CornerTable::from_vo(ct.v_table().to_vec(), ct.o_table().to_vec(), ct.num_vertices()).unwrap();
}

fn has_edge(ct: &CornerTable, a: u32, b: u32) -> bool {
    ct.ring(a).any(|q| q == b)
}

#[test]
fn flipping_twice_restores_the_mesh() {
    for (name, m) in all_meshes() {
        let before = triangle_set(&m.ct);
        let mut flipped = 0;
        let nc = m.ct.num_corners();
        for c in (0..nc as u32).step_by((nc / 200).max(1)) {
            let mut ct = m.ct.clone();
            let (w, a, b) = (ct.vtx(c), ct.vtx(n(c)), ct.vtx(p(c)));
            if flip_edge(&mut ct, c).is_err() {
                continue;
            }
            flipped += 1;
            let d = ct.vtx(p(c));
            assert_consistent(&ct, &format!("{name}: flip {c}"));
            assert!(
                has_edge(&ct, w, d) && !has_edge(&ct, a, b),
                "{name}: flip {c} did not replace ({a},{b}) by ({w},{d})"
            );
            assert_ne!(triangle_set(&ct), before);
            // the new diagonal (w, d) is opposite n(c): flipping it again gives (a, b) back
            flip_edge(&mut ct, n(c)).unwrap();
            assert_consistent(&ct, &format!("{name}: flip back {c}"));
            assert_eq!(triangle_set(&ct), before, "{name}: flip {c} twice");
        }
        if name != "tetrahedron.obj" && name != "single_triangle" {
            assert!(flipped > 0, "{name}: nothing could be flipped");
        }
    }
}

#[test]
fn bad_flips_are_refused() {
    // every flip on a tetrahedron would make a duplicate edge (and leave valence 2)
    let tet = bundled("tetrahedron.obj");
    for c in 0..12 {
        let mut ct = tet.ct.clone();
        assert!(flip_edge(&mut ct, c).is_err());
        assert_eq!(ct, tet.ct, "a refused flip changed the table");
    }
    let g = flat_grid(2);
    let border = (0..g.ct.num_corners() as u32).find(|&c| g.ct.is_border(c)).unwrap();
    let mut ct = g.ct.clone();
    assert_eq!(flip_edge(&mut ct, border), Err(EditError::BorderEdge { corner: border }));
    assert!(matches!(flip_edge(&mut ct, 10_000), Err(EditError::NoSuchCorner { .. })));
    // every refusal names a real reason
    for (name, m) in all_meshes() {
        for c in 0..m.ct.num_corners() as u32 {
            let mut ct = m.ct.clone();
            let (w, a, b) = (ct.vtx(c), ct.vtx(n(c)), ct.vtx(p(c)));
            match flip_edge(&mut ct, c) {
                Ok(()) => {
                    for v in [a, b] {
                        assert!(m.ct.is_boundary_vertex(v) || m.ct.valences()[v as usize] > 3, "{name}: {c}");
                    }
                }
                Err(EditError::BorderEdge { .. }) => assert!(m.ct.is_border(c)),
                Err(EditError::DuplicateEdge { v0, v1 }) => {
                    let d = m.ct.vtx(m.ct.o(c).unwrap());
                    assert_eq!((v0, v1), (w.min(d), w.max(d)));
                    assert!(w == d || has_edge(&m.ct, w, d), "{name}: {c}");
                }
                Err(EditError::LowValence { vertex }) => assert!(m.ct.valences()[vertex as usize] <= 3),
                Err(e) => panic!("{name}: {c}: {e}"),
            }
        }
    }
}

#[test]
fn split_adds_one_vertex_and_keeps_euler() {
    for (name, m) in all_meshes() {
        for c in (0..m.ct.num_corners() as u32).step_by(5) {
            let mut mm = m.clone();
            let border = m.ct.is_border(c);
            let (a, b) = (m.ct.vtx(n(c)), m.ct.vtx(p(c)));
            let t0 = topology(&m.ct);
            let v = split_edge(&mut mm, c, 0.25);
            assert_eq!(v as usize, m.positions.len());
            assert!(
                mm.positions[v as usize].distance(m.positions[a as usize].lerp(m.positions[b as usize], 0.25)) < 1e-6
            );
            assert_consistent(&mm.ct, &format!("{name}: split {c}"));
            let t1 = topology(&mm.ct);
            let (de, df) = if border { (2, 1) } else { (3, 2) };
            assert_eq!(t1.vertices, t0.vertices + 1, "{name}");
            assert_eq!(t1.edges, t0.edges + de, "{name}");
            assert_eq!(t1.faces, t0.faces + df, "{name}");
            assert_eq!((t1.euler, t1.genus, t1.boundary_loops), (t0.euler, t0.genus, t0.boundary_loops), "{name}");
            assert_eq!(mm.ct.valences()[v as usize], if border { 3 } else { 4 });
            assert!(has_edge(&mm.ct, a, v) && has_edge(&mm.ct, v, b) && !has_edge(&mm.ct, a, b));
            // old positions untouched
            assert_eq!(&mm.positions[..m.positions.len()], &m.positions[..]);
        }
    }
}

/// Random sequences of flips and splits on closed and open meshes keep the
/// table equal to a rebuild after every single edit.
#[test]
fn random_edit_sequences_stay_consistent() {
    let mut rng = Rng(99);
    let mut pick = |k: usize| ((rng.next_f32() * 0.5 + 0.5) * k as f32) as usize % k;
    for (name, m) in all_meshes() {
        let mut mesh: Mesh = m.clone();
        let euler = topology(&mesh.ct).euler;
        let (mut flips, mut splits) = (0, 0);
        for step in 0..150 {
            let c = pick(mesh.ct.num_corners()) as u32;
            if pick(3) < 2 {
                if flip_edge(&mut mesh.ct, c).is_ok() {
                    flips += 1;
                }
            } else {
                let t = 0.2 + 0.6 * (pick(1000) as f32 / 1000.0);
                split_edge(&mut mesh, c, t);
                splits += 1;
            }
            assert_eq!(mesh.positions.len(), mesh.ct.num_vertices());
            assert_consistent(&mesh.ct, &format!("{name}: step {step}"));
            assert_eq!(topology(&mesh.ct).euler, euler, "{name}: step {step}");
        }
        assert!(splits > 0 && (flips > 0 || name == "single_triangle"), "{name}: {flips} flips, {splits} splits");
        // the edited mesh still subdivides into a valid table
        let (fine, _) = subdiv::subdivide(&mesh, subdiv::Scheme::Loop, 1, &Default::default()).unwrap();
        check_invariants(&fine.ct).unwrap();
        assert!(fine.ct.o_table().iter().filter(|&&x| x == BORDER).count() == 2 * mesh.ct.num_border_edges());
        assert!(fine.positions.iter().all(|q: &Vec3| q.is_finite()));
    }
}
