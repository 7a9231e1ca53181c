//! Seeing the corner table and the rules (`subdiv info --corner`,
//! `--stencil`): the corner operators against an O table built here from the
//! file's triangles alone; the stencils against the published weights
//! (exact in f64), against the subdivision applied to unit vectors, and
//! their rules named level by level.

mod common;
use common::*;
use std::collections::{BTreeMap, HashMap};
use subdiv::mesh::corner_ops;
use subdiv::mesh::{n, p};
use subdiv::mesh::{number_edges, split_linear};
use subdiv::rules::{Stencil, stencil};
use subdiv::{LoopBeta, Mesh, Options, Scheme, subdivide};

/// O from the triangles alone: the corner facing the same edge the other
/// way.
fn brute_o(tris: &[u32]) -> Vec<Option<u32>> {
    let opposite = |c: usize| (tris[n(c as u32) as usize], tris[p(c as u32) as usize]);
    let facing: HashMap<(u32, u32), u32> = (0..tris.len()).map(|c| (opposite(c), c as u32)).collect();
    (0..tris.len())
        .map(|c| {
            let (a, b) = opposite(c);
            facing.get(&(b, a)).copied()
        })
        .collect()
}

#[test]
fn corner_operators_equal_a_table_built_from_the_triangles() {
    let meshes = [
        ("tetrahedron", bundled("tetrahedron.obj")),
        ("icosphere", icosphere(1)),
        ("hemisphere", hemisphere()),
        ("grid", flat_grid(3)),
        ("fan", disk_fan(5, 2)),
    ];
    for (name, m) in meshes {
        let tris = m.ct.v_table().to_vec();
        let o = brute_o(&tris);
        let on = |x: Option<u32>, f: fn(u32) -> u32| x.map(f);
        for c in 0..tris.len() as u32 {
            let got = corner_ops(&m.ct, c).unwrap();
            let what = format!("{name} corner {c}");
            assert_eq!((got.corner, got.triangle, got.vertex), (c, c / 3, tris[c as usize]), "{what}");
            assert_eq!((got.n, got.p), (3 * (c / 3) + (c + 1) % 3, 3 * (c / 3) + (c + 2) % 3), "{what}");
            assert_eq!(got.o, o[c as usize], "{what}: o");
            assert_eq!(got.l, o[n(c) as usize], "{what}: l = o(n)");
            assert_eq!(got.r, o[p(c) as usize], "{what}: r = o(p)");
            assert_eq!(got.s, on(o[n(c) as usize], n), "{what}: s = n(o(n))");
            assert_eq!(got.u, on(o[p(c) as usize], p), "{what}: u = p(o(p))");
        }
        assert!(corner_ops(&m.ct, tris.len() as u32).is_none());
    }
}

/// The stencil of `v` as a map (zeros dropped).
fn weights(s: &Stencil) -> BTreeMap<u32, f64> {
    s.weights.iter().copied().collect()
}

fn assert_weights(s: &Stencil, want: &[(u32, f64)], what: &str) {
    let mut w: BTreeMap<u32, f64> = BTreeMap::new();
    for &(j, x) in want {
        *w.entry(j).or_insert(0.0) += x;
    }
    w.retain(|_, x| *x != 0.0);
    let got = weights(s);
    let same = got.len() == w.len() && got.iter().zip(&w).all(|((i, x), (j, y))| i == j && (x - y).abs() <= 1e-12);
    assert!(same, "{what}:\n  stencil   {got:?}\n  published {w:?}");
    let total: f64 = got.values().sum();
    assert!((total - 1.0).abs() <= 1e-12, "{what}: the weights sum to {total}");
}

/// An interior vertex 0 of valence `k` whose neighbours are regular
/// interior vertices, and its ring in swing order.
fn ev_beside_regular(k: usize) -> (Mesh, Vec<u32>) {
    let m = split_linear(&disk_fan(k, 2));
    let ring: Vec<u32> = m.ct.ring(0).collect();
    (m, ring)
}

/// The id `subdivide` gives the point of edge `(a, b)` at level 1.
fn edge_vertex(m: &Mesh, a: u32, b: u32) -> u32 {
    let owners = number_edges(&m.ct).owners;
    let e = owners.iter().position(|&c| {
        let (x, y) = (m.ct.vtx(n(c)), m.ct.vtx(p(c)));
        (x, y) == (a, b) || (x, y) == (b, a)
    });
    (m.positions.len() + e.expect("an edge")) as u32
}

#[test]
fn stencils_equal_the_published_weights_exactly() {
    let o = Options::default();
    for k in 3..=12 {
        let (m, ring) = ev_beside_regular(k);
        // Loop's vertex rule (Loop 1987), both betas
        for beta_kind in [LoopBeta::Loop, LoopBeta::Warren] {
            let beta = beta_kind.beta(k as u32);
            let opts = Options { loop_beta: beta_kind, ..o };
            let s = stencil(&m, Scheme::Loop, 1, &opts, 0).unwrap();
            let mut want = vec![(0, 1.0 - k as f64 * beta)];
            want.extend(ring.iter().map(|&q| (q, beta)));
            assert_weights(&s, &want, &format!("Loop vertex, valence {k}, {beta_kind:?}"));
            assert!(s.rules.last().unwrap().1.contains(&format!("valence {k}")), "{:?}", s.rules);
        }
        // the modified butterfly's extraordinary rule (Zorin, Schroder,
        // Sweldens 1996): 3/4 v + sum s_j e_j (valence 6 is regular)
        if k == 6 {
            continue;
        }
        let s_j = |j: usize| -> f64 {
            match k {
                3 => [5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0][j],
                4 => [3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0][j],
                _ => {
                    let t = std::f64::consts::TAU * j as f64 / k as f64;
                    (0.25 + t.cos() + 0.5 * (2.0 * t).cos()) / k as f64
                }
            }
        };
        let v = edge_vertex(&m, 0, ring[0]);
        let s = stencil(&m, Scheme::ModifiedButterfly, 1, &o, v).unwrap();
        let mut want = vec![(0, 0.75)];
        want.extend((0..k).map(|j| (ring[j], s_j(j))));
        assert_weights(&s, &want, &format!("modified butterfly, valence {k}"));
        assert!(s.rules[0].1.contains(&format!("valence-{k}")), "{:?}", s.rules);
    }
    // Loop's edge and boundary rules (Hoppe et al. 1994), butterfly's 8 points
    let g = flat_grid(4);
    let id = |i: u32, j: u32| j * 5 + i;
    let (a, b) = (id(2, 2), id(3, 3));
    let e = edge_vertex(&g, a, b);
    let s = stencil(&g, Scheme::Loop, 1, &o, e).unwrap();
    assert_weights(&s, &[(a, 0.375), (b, 0.375), (id(3, 2), 0.125), (id(2, 3), 0.125)], "Loop edge");
    let s = stencil(&g, Scheme::Butterfly, 1, &o, e).unwrap();
    let eight = [
        (a, 0.5),
        (b, 0.5),
        (id(3, 2), 0.125),
        (id(2, 3), 0.125),
        (id(2, 1), -0.0625),
        (id(4, 3), -0.0625),
        (id(1, 2), -0.0625),
        (id(3, 4), -0.0625),
    ];
    assert_weights(&s, &eight, "8-point butterfly");
    let s = stencil(&g, Scheme::Loop, 1, &o, id(2, 0)).unwrap();
    assert_weights(&s, &[(id(2, 0), 0.75), (id(1, 0), 0.125), (id(3, 0), 0.125)], "Loop boundary vertex");
    assert!(s.rules.last().unwrap().1.contains("boundary vertex"), "{:?}", s.rules);
    let e = edge_vertex(&g, id(2, 0), id(3, 0));
    let s = stencil(&g, Scheme::Loop, 1, &o, e).unwrap();
    assert_weights(&s, &[(id(2, 0), 0.5), (id(3, 0), 0.5)], "Loop boundary edge");
    assert!(s.rules[0].1.contains("boundary edge"), "{:?}", s.rules);
    // Catmull-Clark's vertex rule on quads: (n-2)/n + 1/(4n) v, 3/(2n^2)
    // each edge end, 1/(4n^2) each diagonal (Catmull, Clark 1978)
    let positions: Vec<glam::Vec3> =
        (0..8).map(|i| glam::Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, (i >> 2) as f32)).collect();
    let faces = [0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5];
    let starts: Vec<u32> = (0..=6).map(|f| 4 * f).collect();
    let cube = subdiv::mesh::PolyMesh::from_faces(positions, &starts, &faces).unwrap().0.triangulated();
    let s = stencil(&cube, Scheme::CatmullClark, 1, &o, 0).unwrap();
    let nf = 3.0;
    let mut want = vec![(0, (nf - 2.0) / nf + 1.0 / (4.0 * nf))];
    let pm = subdiv::mesh::PolyMesh::from_mesh(&cube);
    for c in pm.pt.fan(0) {
        want.push((pm.pt.vtx(pm.pt.next(c)), 3.0 / (2.0 * nf * nf)));
        want.push((pm.pt.vtx(pm.pt.next(pm.pt.next(c))), 1.0 / (4.0 * nf * nf)));
    }
    assert_weights(&s, &want, "Catmull-Clark vertex, valence 3");
}

/// Control vertex `j`'s unit vector (in x) refined: the column `j` of the
/// subdivision matrix.
fn column(m: &Mesh, scheme: Scheme, levels: u32, opts: &Options, j: usize) -> Vec<f32> {
    let mut unit = m.clone();
    unit.positions
        .iter_mut()
        .enumerate()
        .for_each(|(i, q)| *q = glam::Vec3::new(f32::from(u8::from(i == j)), 0.0, 0.0));
    subdivide(&unit, scheme, levels, opts).unwrap().0.positions.iter().map(|q| q.x).collect()
}

#[test]
fn stencils_are_the_subdivision_matrix_applied_to_unit_vectors() {
    let chaikin = Options { creasing: subdiv::mesh::Creasing::Chaikin, ..Options::default() };
    let cases: Vec<(Mesh, Options)> = vec![
        (hemisphere(), Options::default()),
        (
            subdiv::bundled::load(
                &std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/creases/thresholds.obj"),
            )
            .unwrap(),
            chaikin,
        ),
    ];
    for scheme in Scheme::ALL {
        for (m, opts) in &cases {
            let levels = 2;
            let fine = subdivide(m, scheme, levels, opts).unwrap().0;
            let nv = fine.positions.len() as u32;
            let picks = [0, 3, m.positions.len() as u32 + 1, nv / 2, nv - 1];
            let stencils: Vec<Stencil> = picks.iter().map(|&v| stencil(m, scheme, levels, opts, v).unwrap()).collect();
            for j in 0..m.positions.len() {
                let col = column(m, scheme, levels, opts, j);
                for s in &stencils {
                    let w = weights(s).get(&(j as u32)).copied().unwrap_or(0.0);
                    let got = f64::from(col[s.vertex as usize]);
                    assert!((got - w).abs() < 2e-6, "{scheme} vertex {}: control {j}: {w} against {got}", s.vertex);
                }
            }
            for s in &stencils {
                let total: f64 = s.weights.iter().map(|w| w.1).sum();
                assert!((total - 1.0).abs() <= 1e-12, "{scheme} vertex {}: sum {total}", s.vertex);
                let at = fine.positions[s.vertex as usize].as_dvec3();
                assert!((s.position - at).length() < 1e-5, "{scheme} vertex {}: position", s.vertex);
                assert!(!s.rules.is_empty());
            }
        }
    }
}

#[test]
fn the_lineage_names_the_rule_of_every_level() {
    let m = bundled("tetrahedron.obj");
    let o = Options::default();
    // a control vertex: every level's vertex rule
    let s = stencil(&m, Scheme::Loop, 2, &o, 0).unwrap();
    let levels: Vec<u32> = s.rules.iter().map(|r| r.0).collect();
    assert_eq!(levels, [0, 1, 2], "{:?}", s.rules);
    assert!(s.rules[1].1.contains("valence 3"), "{:?}", s.rules);
    // a vertex made at level 2: its edge rule alone
    let s = stencil(&m, Scheme::Loop, 2, &o, 12).unwrap();
    assert_eq!(s.rules.len(), 1, "{:?}", s.rules);
    assert_eq!(s.rules[0].0, 2);
    assert!(s.rules[0].1.contains("interior edge"), "{:?}", s.rules);
    // interpolating schemes keep their vertices
    let s = stencil(&m, Scheme::Butterfly, 2, &o, 5).unwrap();
    assert!(s.rules.iter().any(|r| r.1.contains("kept")), "{:?}", s.rules);
    // out of range: one line naming the count
    let e = stencil(&m, Scheme::Loop, 1, &o, 1000).unwrap_err().to_string();
    assert!(e.contains("out of range") && e.contains("10 vertices"), "{e}");
}
