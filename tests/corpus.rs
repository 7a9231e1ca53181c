//! The bad-input corpus: generated meshes with every kind of defect the
//! repair handles (non-manifold edges with 3 and 4 faces, bowtie vertices,
//! unreferenced and isolated vertices, duplicate, zero-area and repeated-index
//! faces, inconsistent orientation, a Möbius band) next to valid but awkward
//! ones (valence-2 boundary corners, valence 16 and 24 fans, several
//! components, a single triangle, an empty mesh).
//!
//! For each: without repair, the build either succeeds and every scheme
//! refines it to level 3 with a valid corner table, or it fails with the
//! expected typed [`MeshError`]. With repair, every mesh but the empty one
//! builds, reports exactly the expected changes, and refines to level 3 with
//! every scheme.

mod common;
use common::*;
use glam::Vec3;
use subdiv::mesh::{RepairReport, repair};
use subdiv::mesh::{check_invariants, topology};
use subdiv::{Mesh, MeshError, Options, Scheme};

/// Any count is accepted (the exact number depends on search order).
const ANY: usize = usize::MAX;

struct Case {
    name: &'static str,
    soup: Soup,
    /// The build error expected without repair; `None`: the input is valid.
    error: Option<fn(&MeshError) -> bool>,
    /// Expected repair counts: degenerate faces, duplicate faces,
    /// non-manifold edges, flipped faces, split vertices, unreferenced vertices.
    counts: [usize; 6],
}

fn counts(r: &RepairReport) -> [usize; 6] {
    [
        r.degenerate_faces.count,
        r.duplicate_faces.count,
        r.non_manifold_edges.count,
        r.flipped_faces.count,
        r.split_vertices.count,
        r.unreferenced_vertices.count,
    ]
}

fn grid_soup() -> Soup {
    Soup::of(&grid(4, 3, |i, j| Vec3::new(i, j, 0.1 * i * j)))
}

fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    let mut add =
        |name, soup, error: Option<fn(&MeshError) -> bool>, counts| v.push(Case { name, soup, error, counts });

    add(
        "fin_3_faces",
        soup_fin(3),
        Some(|e| matches!(e, MeshError::NonManifoldEdge { faces: 3, .. })),
        [0, 0, 1, 0, 2, 0],
    );
    add(
        "fin_4_faces",
        soup_fin(4),
        Some(|e| matches!(e, MeshError::NonManifoldEdge { faces: 4, .. })),
        [0, 0, 1, 0, 2, 0],
    );
    add(
        "two_tets_on_an_edge",
        soup_two_tets_on_edge(),
        Some(|e| matches!(e, MeshError::NonManifoldEdge { v0: 0, v1: 1, faces: 4, .. })),
        [0, 0, 1, 0, 2, 0],
    );
    add(
        "bowtie_disks",
        soup_bowtie_disks(),
        Some(|e| matches!(e, MeshError::NonManifoldVertex { vertex: 0, fans: 2 })),
        [0, 0, 0, 0, 1, 0],
    );
    add(
        "two_tets_on_a_vertex",
        soup_two_tets_on_vertex(),
        Some(|e| matches!(e, MeshError::NonManifoldVertex { vertex: 0, fans: 2 })),
        [0, 0, 0, 0, 1, 0],
    );

    // unreferenced vertices: two before the grid's, one after
    let mut s = grid_soup();
    s.positions.splice(0..0, [Vec3::splat(9.0), Vec3::splat(-9.0)]);
    s.triangles.iter_mut().for_each(|i| *i += 2);
    s.positions.push(Vec3::ONE);
    add("unreferenced_vertices", s, None, [0, 0, 0, 0, 0, 3]);

    let mut s = Soup { positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y], triangles: vec![0, 1, 2] };
    s.positions.extend((0..4).map(|i| Vec3::new(5.0, i as f32, 5.0)));
    add("isolated_vertices", s, None, [0, 0, 0, 0, 0, 4]);

    let mut s = Soup::of(&icosahedron());
    s.triangles.extend_from_within(0..3);
    add("duplicate_face", s, Some(|e| matches!(e, MeshError::NonManifoldEdge { faces: 3, .. })), [0, 1, 0, 0, 0, 0]);

    // a duplicate reversed and rotated: (a, b, c) -> (b, a, c)
    let mut s = grid_soup();
    let (a, b, c) = (s.triangles[9], s.triangles[10], s.triangles[11]);
    s.triangles.extend([b, a, c]);
    add(
        "duplicate_face_reversed",
        s,
        Some(|e| matches!(e, MeshError::NonManifoldEdge { faces: 3, .. })),
        [0, 1, 0, 0, 0, 0],
    );

    // a zero-area sliver on the border edge (0, 1): its third vertex sits on vertex 0
    let mut s = grid_soup();
    let q = s.positions.len() as u32;
    s.positions.push(s.positions[0]);
    s.triangles.extend([0, 1, q]);
    add("zero_area_face", s, Some(|e| matches!(e, MeshError::InconsistentOrientation { .. })), [1, 0, 0, 0, 0, 1]);

    let mut s = grid_soup();
    s.triangles.extend([0, 0, 1]);
    add("repeated_index_face", s, Some(|e| matches!(e, MeshError::DegenerateFace { .. })), [1, 0, 0, 0, 0, 0]);

    let mut s = Soup::of(&icosphere(1));
    for f in [5, 40, 77] {
        s.flip(f);
    }
    add("flipped_faces", s, Some(|e| matches!(e, MeshError::InconsistentOrientation { .. })), [0, 0, 0, 3, 0, 0]);

    add(
        "mobius_band",
        soup_mobius(6),
        Some(|e| matches!(e, MeshError::InconsistentOrientation { .. })),
        [0, 0, 0, ANY, ANY, 0],
    );

    add(
        "klein_bottle",
        soup_klein(6, 6),
        Some(|e| matches!(e, MeshError::InconsistentOrientation { .. })),
        [0, 0, 0, ANY, ANY, 0],
    );

    add("valence_2_corners", Soup::of(&flat_grid(4)), None, [0; 6]);
    add("fan_valence_16", Soup::of(&disk_fan(16, 2)), None, [0; 6]);
    add("cylinder_fans_valence_24", soup_cylinder_fans(24, 2), None, [0; 6]);

    let mut s = Soup::of(&icosahedron());
    s.append(&grid_soup(), Vec3::new(5.0, 0.0, 0.0));
    s.append(&Soup { positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y], triangles: vec![0, 1, 2] }, Vec3::splat(-5.0));
    s.append(&soup_cylinder_fans(5, 1), Vec3::new(0.0, 5.0, 0.0));
    add("four_components", s, None, [0; 6]);

    add(
        "single_triangle",
        Soup { positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y], triangles: vec![0, 1, 2] },
        None,
        [0; 6],
    );
    add("empty", Soup { positions: vec![Vec3::ZERO; 3], triangles: vec![] }, Some(|e| *e == MeshError::Empty), [0; 6]);
    v
}

/// Refines `mesh` one level at a time to level 3 with every scheme, checking
/// the corner table and the counts after each level.
fn refine_all(name: &str, mesh: &Mesh) {
    let t0 = topology(&mesh.ct);
    for scheme in Scheme::TRIANGLE {
        let mut cur = mesh.clone();
        for level in 1..=3 {
            let ctx = format!("{name}: {scheme} level {level}");
            let (next, _) =
                subdiv::subdivide(&cur, scheme, 1, &Options::default()).unwrap_or_else(|e| panic!("{ctx}: {e}"));
            check_invariants(&next.ct).unwrap_or_else(|e| panic!("{ctx}: {e}"));
            assert_eq!(next.ct.num_triangles(), 4 * cur.ct.num_triangles(), "{ctx}: F' = 4F");
            assert!(next.positions.iter().all(|q| q.is_finite()), "{ctx}: non-finite position");
            let t = topology(&next.ct);
            assert_eq!(
                (t.euler, t.components, t.boundary_loops),
                (t0.euler, t0.components, t0.boundary_loops),
                "{ctx}"
            );
            cur = next;
        }
    }
}

#[test]
fn without_repair_valid_meshes_refine_and_invalid_ones_give_the_typed_error() {
    for case in cases() {
        let built = Mesh::from_triangles(case.soup.positions.clone(), &case.soup.triangles);
        match (built, case.error) {
            (Ok(mesh), None) => refine_all(case.name, &mesh),
            (Err(e), Some(expected)) => assert!(expected(&e), "{}: unexpected error {e:?}", case.name),
            (Ok(_), Some(_)) => panic!("{}: expected an error, but the mesh built", case.name),
            (Err(e), None) => panic!("{}: expected a valid mesh, got {e}", case.name),
        }
    }
}

#[test]
fn with_repair_every_nonempty_mesh_refines_with_every_scheme() {
    for case in cases() {
        let result = repair(case.soup.positions.clone(), &case.soup.triangles);
        if case.soup.triangles.is_empty() {
            assert_eq!(result.unwrap_err(), MeshError::Empty);
            continue;
        }
        let (mesh, report) = result.unwrap_or_else(|e| panic!("{}: repair failed: {e}", case.name));
        let name = case.name;
        // the result passes the ordinary validating build unchanged
        let rebuilt = Mesh::from_triangles(mesh.positions.clone(), mesh.ct.v_table())
            .unwrap_or_else(|e| panic!("{name}: repaired mesh does not build: {e}"));
        assert_eq!(rebuilt.ct, mesh.ct, "{name}");
        check_invariants(&mesh.ct).unwrap_or_else(|e| panic!("{name}: {e}"));
        // the report says exactly what was expected
        for (k, (&got, &want)) in counts(&report).iter().zip(&case.counts).enumerate() {
            assert!(want == ANY || got == want, "{name}: count {k} is {got}, expected {want}\n{report}");
        }
        assert_eq!(report.faces_out, mesh.ct.num_triangles(), "{name}");
        assert_eq!(report.vertices_out, mesh.positions.len(), "{name}");
        assert_eq!(
            report.faces_out,
            case.soup.faces() - report.degenerate_faces.count - report.duplicate_faces.count,
            "{name}: only degenerate and duplicate faces are dropped"
        );
        assert_eq!(
            report.vertices_out,
            case.soup.positions.len() + report.added_vertices - report.unreferenced_vertices.count,
            "{name}: vertex bookkeeping"
        );
        if case.error.is_none() {
            assert!(!report.changed_faces(), "{name}: a valid mesh was changed\n{report}");
        }
        // every output position is an input position
        assert!(mesh.positions.iter().all(|q| case.soup.positions.contains(q)), "{name}");
        // repairing again finds nothing
        let (again, rep2) = repair(mesh.positions.clone(), mesh.ct.v_table()).unwrap();
        assert!(rep2.is_empty(), "{name}: second repair changed something\n{rep2}");
        assert_eq!(again.ct, mesh.ct, "{name}");
        refine_all(name, &mesh);
    }
}

#[test]
fn repaired_topology_is_as_expected() {
    let top = |s: Soup| topology(&repair(s.positions, &s.triangles).unwrap().0.ct);
    // fins fall apart into separate triangles, every edge a border
    let t = top(soup_fin(3));
    assert_eq!((t.faces, t.components, t.border_edges), (3, 3, 9));
    // two tetrahedra on one edge: two closed tetrahedra again
    let t = top(soup_two_tets_on_edge());
    assert_eq!((t.components, t.border_edges, t.euler), (2, 0, 4));
    // closed bowtie: two closed tetrahedra, genus 0 each
    let t = top(soup_two_tets_on_vertex());
    assert_eq!((t.components, t.border_edges, t.euler, t.genus), (2, 0, 4, 0));
    // the Möbius band becomes an orientable strip: one component, a disk
    let t = top(soup_mobius(6));
    assert_eq!((t.faces, t.components, t.euler, t.boundary_loops), (12, 1, 1, 1));
    // the Klein bottle is cut open into an orientable surface with boundary
    let s = soup_klein(6, 6);
    let (m, r) = repair(s.positions, &s.triangles).unwrap();
    let t = topology(&m.ct);
    assert_eq!(t.faces, 72);
    assert!(t.border_edges > 0 && r.extra_cuts.count > 0, "{r}");
    // flipped faces on a sphere: back to a closed sphere
    let mut s = Soup::of(&icosphere(1));
    s.flip(7);
    let t = top(s);
    assert_eq!((t.euler, t.border_edges, t.genus), (2, 0, 0));
}

#[test]
fn all_defects_at_once_add_up() {
    // every case as a component of one soup: the repair is local, so the
    // counts of the whole are the sums of the counts of the parts
    let mut all = Soup::default();
    let mut want = [0usize; 6];
    let mut faces = 0;
    for (i, case) in cases().into_iter().enumerate() {
        if case.soup.triangles.is_empty() {
            continue;
        }
        let (m, r) = repair(case.soup.positions.clone(), &case.soup.triangles).unwrap();
        for (w, c) in want.iter_mut().zip(counts(&r)) {
            *w += c;
        }
        faces += m.ct.num_triangles();
        all.append(&case.soup, Vec3::new(10.0 * i as f32, 0.0, 0.0));
    }
    assert!(Mesh::from_triangles(all.positions.clone(), &all.triangles).is_err());
    let (mesh, report) = repair(all.positions, &all.triangles).unwrap();
    assert_eq!(counts(&report), want, "{report}");
    assert_eq!(mesh.ct.num_triangles(), faces);
    let (level2, _) = subdiv::subdivide(&mesh, Scheme::ModifiedButterfly, 2, &Options::default()).unwrap();
    check_invariants(&level2.ct).unwrap();
}

#[test]
fn corpus_covers_what_it_claims() {
    let built = |name: &str| {
        let c = cases().into_iter().find(|c| c.name == name).unwrap();
        Mesh::from_triangles(c.soup.positions, &c.soup.triangles).unwrap()
    };
    let max_valence = |m: &Mesh| m.ct.valences().iter().copied().max().unwrap();
    assert!(built("valence_2_corners").ct.valences().contains(&2));
    assert_eq!(max_valence(&built("fan_valence_16")), 16);
    assert_eq!(max_valence(&built("cylinder_fans_valence_24")), 24);
    assert_eq!(topology(&built("four_components").ct).components, 4);
    assert_eq!(topology(&built("cylinder_fans_valence_24").ct).border_edges, 0);
}

#[test]
fn random_soups_always_repair_into_valid_meshes() {
    // random triangles over a handful of vertices: fins, bowties, flips,
    // duplicates and non-orientable pieces in every combination
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut pick = |k: u32| ((rng.next_f32() + 1.0) * 0.5 * k as f32) as u32 % k;
    for round in 0..3000 {
        let nv = 4 + pick(6);
        let nt = 1 + pick(14) as usize;
        let positions: Vec<Vec3> =
            (0..nv).map(|i| Vec3::new(i as f32, (i * i % 7) as f32, (i * 3 % 5) as f32)).collect();
        let triangles: Vec<u32> = (0..3 * nt).map(|_| pick(nv)).collect();
        match repair(positions.clone(), &triangles) {
            Err(MeshError::Empty) => assert!(triangles.chunks(3).all(|t| t[0] == t[1] || t[1] == t[2] || t[0] == t[2])),
            Err(e) => panic!("round {round}: {e}"),
            Ok((mesh, report)) => {
                check_invariants(&mesh.ct).unwrap_or_else(|e| panic!("round {round}: {e}"));
                Mesh::from_triangles(mesh.positions.clone(), mesh.ct.v_table())
                    .unwrap_or_else(|e| panic!("round {round}: {triangles:?}: {e}\n{report}"));
                let (_, again) = repair(mesh.positions.clone(), mesh.ct.v_table()).unwrap();
                assert!(again.is_empty(), "round {round}: not a fixed point\n{again}");
            }
        }
    }
}
