//! The propagated O table equals a rebuilt one, and the counts of every level
//! follow V' = V + E, F' = 4F, with Euler characteristic and boundary loops
//! unchanged.

mod common;
use common::*;
use subdiv::mesh::{check_invariants, topology};
use subdiv::{CornerTable, Options, Scheme};

#[test]
fn propagated_o_equals_rebuilt_for_every_scheme_and_level() {
    for (name, mesh) in all_meshes() {
        for scheme in Scheme::TRIANGLE {
            let mut cur = mesh.clone();
            let t0 = topology(&cur.ct);
            let max_level = if mesh.ct.num_triangles() > 500 { 3 } else { 4 };
            for level in 1..=max_level {
                let before = topology(&cur.ct);
                let (next, _) = subdiv::subdivide(&cur, scheme, 1, &Options::default()).unwrap();
                let ctx = format!("{name} {scheme} level {level}");
                check_invariants(&next.ct).unwrap_or_else(|e| panic!("{ctx}: {e}"));
                let (rebuilt, rep, kept) = CornerTable::build(next.positions.len(), next.ct.v_table(), None).unwrap();
                assert!(kept.is_none() && rep.unreferenced == 0, "{ctx}: unreferenced vertices after split");
                assert_eq!(rebuilt.o_table(), next.ct.o_table(), "{ctx}: propagated O differs from rebuilt O");
                assert_eq!(rebuilt.valences(), next.ct.valences(), "{ctx}: valences differ");
                for c in 0..next.ct.num_corners() as u32 {
                    if let Some(x) = next.ct.o(c) {
                        assert_eq!(next.ct.o(x), Some(c), "{ctx}: o(o(c)) != c");
                    }
                }
                let after = topology(&next.ct);
                assert_eq!(after.vertices, before.vertices + before.edges, "{ctx}: V' = V + E");
                assert_eq!(after.faces, 4 * before.faces, "{ctx}: F' = 4F");
                assert_eq!(after.edges, 2 * before.edges + 3 * before.faces, "{ctx}: E' = 2E + 3F");
                assert_eq!(after.border_edges, 2 * before.border_edges, "{ctx}: border edges double");
                assert_eq!(after.euler, t0.euler, "{ctx}: Euler characteristic");
                assert_eq!(after.boundary_loops, t0.boundary_loops, "{ctx}: boundary loops");
                assert_eq!(after.components, t0.components, "{ctx}: components");
                assert_eq!(after.genus, t0.genus, "{ctx}: genus");
                cur = next;
            }
        }
    }
}

#[test]
fn topology_of_known_meshes() {
    let t = topology(&bundled("torus.obj").ct);
    assert_eq!((t.vertices, t.faces, t.genus, t.boundary_loops), (512, 1024, 1, 0));
    assert_eq!(t.valence_histogram[6], 512);
    let t = topology(&bundled("tetrahedron.obj").ct);
    assert_eq!((t.vertices, t.edges, t.faces, t.euler, t.genus), (4, 6, 4, 2, 0));
    let t = topology(&flat_grid(8).ct);
    assert_eq!((t.boundary_loops, t.border_edges, t.genus, t.euler), (1, 32, 0, 1));
    let t = topology(&hemisphere().ct);
    assert_eq!((t.boundary_loops, t.components, t.genus), (1, 1, 0));
    let d = disk_fan(16, 3);
    assert_eq!(d.ct.valences()[0], 16);
    assert_eq!(topology(&d.ct).boundary_loops, 1);
}

#[test]
fn ct_files_round_trip_with_their_o_table() {
    for name in BUNDLED {
        let obj = bundled(name);
        let ct = bundled(&name.replace(".obj", ".ct"));
        assert_eq!(obj.ct, ct.ct, "{name}: .ct table differs from the OBJ's");
        assert_eq!(obj.positions, ct.positions);
        let mut buf = Vec::new();
        subdiv::io::write_ct(&mut buf, &obj).unwrap();
        let src = subdiv::io::Source::Bytes { bytes: &buf, name: "mem.ct", folder: None };
        let back = subdiv::io::read(src, &Default::default()).unwrap().mesh;
        assert_eq!(back.ct, obj.ct);
        assert_eq!(back.positions, obj.positions);
    }
}
