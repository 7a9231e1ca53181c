//! Stencil rows read from the stencil plan equal the published weights
//! (schemes.md, with its sources): Loop's vertex rule at valence 3, 4, 5, 6
//! and 7 and its edge rule (Loop 1987), Loop's boundary rules (Hoppe et al.
//! 1994), the Jarek stencils (schemes.md 6), the modified butterfly's regular
//! rule with and without tension, its valence 3, 4 and 5 extraordinary rules
//! (Zorin et al. 1996), the 4-point boundary rule (Dyn, Levin, Gregory 1987)
//! and the MESH rule next to a boundary (naspert/MESH, schemes.md 3.5).
//!
//! Weights that are dyadic fractions are compared exactly; the others (thirds,
//! cosines) to f32 rounding.

mod common;
use common::*;
use std::collections::BTreeMap;
use subdiv::StencilPlan;
use subdiv::mesh::{n, p};
use subdiv::mesh::{number_edges, split_linear};
use subdiv::rules::LevelPlan;
use subdiv::{CornerTable, LoopBeta, Mesh, Options, Scheme};

/// A row as vertex -> total weight (repeated ids added), zero weights dropped.
type Row = BTreeMap<u32, f64>;

fn plan(m: &Mesh, s: Scheme, opts: &Options) -> LevelPlan {
    StencilPlan::build(&m.ct, s, 1, opts).unwrap().levels.remove(0)
}

fn row(lv: &LevelPlan, r: usize) -> Row {
    let (a, b) = (lv.offsets[r] as usize, lv.offsets[r + 1] as usize);
    let mut out = Row::new();
    for (&i, &w) in lv.indices[a..b].iter().zip(&lv.weights[a..b]) {
        *out.entry(i).or_insert(0.0) += f64::from(w);
    }
    out.retain(|_, w| *w != 0.0);
    out
}

/// The row of the new vertex on edge (a, b).
fn edge_row(ct: &CornerTable, lv: &LevelPlan, a: u32, b: u32) -> Row {
    let owners = number_edges(ct).owners;
    let e = owners
        .iter()
        .position(|&c| {
            let (x, y) = (ct.vtx(n(c)), ct.vtx(p(c)));
            (x, y) == (a, b) || (x, y) == (b, a)
        })
        .unwrap_or_else(|| panic!("no edge ({a}, {b})"));
    let first = if lv.copy_vertices { 0 } else { lv.n_in };
    row(lv, first + e)
}

/// The row of old vertex `v` (approximating schemes only).
fn vertex_row(lv: &LevelPlan, v: u32) -> Row {
    assert!(!lv.copy_vertices);
    row(lv, v as usize)
}

fn expect(got: &Row, want: &[(u32, f64)], tol: f64, what: &str) {
    let mut w = Row::new();
    for &(i, x) in want {
        *w.entry(i).or_insert(0.0) += x;
    }
    w.retain(|_, x| *x != 0.0);
    let same = got.len() == w.len()
        && got.iter().zip(&w).all(|((i, x), (j, y))| i == j && (x - y).abs() <= tol * y.abs().max(1.0));
    assert!(same, "{what}:\n  plan      {got:?}\n  published {w:?}");
}

/// Grid vertex (i, j) of `grid(N, N, ..)`.
const N: usize = 6;
fn g(i: usize, j: usize) -> u32 {
    (j * (N + 1) + i) as u32
}
fn lattice() -> Mesh {
    grid(N, N, |i, j| glam::Vec3::new(i, j, 0.0))
}

/// An interior vertex 0 of valence `k` whose neighbours are all regular
/// interior vertices (a disk split once), and its ring in swing order.
fn ev_beside_regular(k: usize) -> (Mesh, Vec<u32>) {
    let m = split_linear(&disk_fan(k, 2));
    assert!(!m.ct.is_boundary_vertex(0) && m.ct.valence(0) as usize == k);
    let ring: Vec<u32> = m.ct.ring(0).collect();
    for &q in &ring {
        assert!(!m.ct.is_boundary_vertex(q) && m.ct.valence(q) == 6);
    }
    (m, ring)
}

const F32: f64 = 1e-7;

#[test]
fn loop_vertex_rule_at_valence_3_to_7() {
    // (n, beta, centre 1 - n beta) from schemes.md 5.1 (Loop's beta); exact
    // fractions at n = 3, 4, 6, the table's decimals at 5 and 7
    let table: [(usize, f64, f64, f64); 5] = [
        (3, 3.0 / 16.0, 7.0 / 16.0, 0.0),
        (4, 31.0 / 256.0, 33.0 / 64.0, 0.0),
        (5, 0.084093, 0.579534, 1e-6),
        (6, 1.0 / 16.0, 5.0 / 8.0, 0.0),
        (7, 0.049025, 0.656826, 1e-6),
    ];
    for (k, beta, centre, tol) in table {
        let (m, ring) = ev_beside_regular(k);
        let lv = plan(&m, Scheme::Loop, &Options::default());
        let mut want = vec![(0, centre)];
        want.extend(ring.iter().map(|&q| (q, beta)));
        expect(&vertex_row(&lv, 0), &want, tol, &format!("Loop vertex, n = {k}"));
        // the formula itself, to f32 rounding
        let c = 3.0 / 8.0 + 0.25 * (std::f64::consts::TAU / k as f64).cos();
        let formula = (5.0 / 8.0 - c * c) / k as f64;
        assert!((formula - beta).abs() < 1e-6, "n = {k}: beta {formula} vs the table's {beta}");
    }
    // Warren's beta: 3/(8n), 3/16 at n = 3
    for (k, beta) in [(3, 3.0 / 16.0), (4, 3.0 / 32.0), (8, 3.0 / 64.0)] {
        let (m, ring) = ev_beside_regular(k);
        let lv = plan(&m, Scheme::Loop, &Options { loop_beta: LoopBeta::Warren, ..Default::default() });
        let mut want = vec![(0, 1.0 - k as f64 * beta)];
        want.extend(ring.iter().map(|&q| (q, beta)));
        expect(&vertex_row(&lv, 0), &want, 0.0, &format!("Warren vertex, n = {k}"));
    }
}

#[test]
fn loop_edge_and_boundary_rules() {
    let m = lattice();
    let lv = plan(&m, Scheme::Loop, &Options::default());
    // interior edge (2,2)-(3,2), wings (3,3) and (2,1): 3/8, 3/8, 1/8, 1/8
    let want = [(g(2, 2), 0.375), (g(3, 2), 0.375), (g(3, 3), 0.125), (g(2, 1), 0.125)];
    expect(&edge_row(&m.ct, &lv, g(2, 2), g(3, 2)), &want, 0.0, "Loop interior edge");
    // border edge: 1/2, 1/2
    expect(&edge_row(&m.ct, &lv, g(2, 0), g(3, 0)), &[(g(2, 0), 0.5), (g(3, 0), 0.5)], 0.0, "Loop border edge");
    // boundary vertex: 3/4 v + 1/8 (q1 + q2), its interior neighbours unused
    let want = [(g(2, 0), 0.75), (g(1, 0), 0.125), (g(3, 0), 0.125)];
    expect(&vertex_row(&lv, g(2, 0)), &want, 0.0, "Loop boundary vertex");
    // a corner with a single face follows the same rule (EDGE_ONLY; not kept fixed)
    assert_eq!(m.ct.valence(g(N, 0)), 2);
    let want = [(g(N, 0), 0.75), (g(N - 1, 0), 0.125), (g(N, 1), 0.125)];
    expect(&vertex_row(&lv, g(N, 0)), &want, 0.0, "Loop corner with one face");
    // regular interior vertex: 5/8 and 1/16 for each of the six neighbours
    let mut want = vec![(g(2, 2), 0.625)];
    want.extend([(1, 2), (3, 2), (2, 1), (2, 3), (1, 1), (3, 3)].map(|(i, j)| (g(i, j), 0.0625)));
    expect(&vertex_row(&lv, g(2, 2)), &want, 0.0, "Loop regular vertex");
}

#[test]
fn jarek_stencils() {
    let m = lattice();
    let lv = plan(&m, Scheme::Jarek, &Options::default());
    let nbrs = |i: usize, j: usize| [(i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1), (i - 1, j - 1), (i + 1, j + 1)];
    // regular vertex: 7/8 and 1/48 each
    let mut want = vec![(g(2, 2), 7.0 / 8.0)];
    want.extend(nbrs(2, 2).map(|(i, j)| (g(i, j), 1.0 / 48.0)));
    expect(&vertex_row(&lv, g(2, 2)), &want, F32, "Jarek regular vertex");
    // regular edge (2,2)-(3,2): 53/96 each, wings -1/48, the other three
    // neighbours of each end -1/96
    let mut want = vec![(g(2, 2), 53.0 / 96.0), (g(3, 2), 53.0 / 96.0), (g(3, 3), -1.0 / 48.0), (g(2, 1), -1.0 / 48.0)];
    want.extend([(1, 2), (2, 3), (1, 1), (4, 2), (3, 1), (4, 3)].map(|(i, j)| (g(i, j), -1.0 / 96.0)));
    expect(&edge_row(&m.ct, &lv, g(2, 2), g(3, 2)), &want, F32, "Jarek regular edge");
    // boundary: the Jarek curve rules [1, 14, 1]/16 and [-1, 17, 17, -1]/32
    let want = [(g(1, 0), 1.0 / 16.0), (g(2, 0), 14.0 / 16.0), (g(3, 0), 1.0 / 16.0)];
    expect(&vertex_row(&lv, g(2, 0)), &want, 0.0, "Jarek boundary vertex");
    let want = [(g(1, 0), -1.0 / 32.0), (g(2, 0), 17.0 / 32.0), (g(3, 0), 17.0 / 32.0), (g(4, 0), -1.0 / 32.0)];
    expect(&edge_row(&m.ct, &lv, g(2, 0), g(3, 0)), &want, 0.0, "Jarek border edge");
    // extraordinary vertex of valence 5: 7/8 and 1/40 each; its edge to a
    // regular neighbour e: (v + e)/2 - (d_v + d_e)/2 with d = 1/8 (avg - .)
    let (m, ring) = ev_beside_regular(5);
    let lv = plan(&m, Scheme::Jarek, &Options::default());
    let mut want = vec![(0, 7.0 / 8.0)];
    want.extend(ring.iter().map(|&q| (q, 1.0 / 40.0)));
    expect(&vertex_row(&lv, 0), &want, F32, "Jarek vertex, valence 5");
    let e = ring[0];
    let mut want = vec![(0, 0.5 + 1.0 / 16.0), (e, 0.5 + 1.0 / 16.0)];
    want.extend(ring.iter().map(|&q| (q, -1.0 / 80.0)));
    want.extend(m.ct.ring(e).map(|q| (q, -1.0 / 96.0)));
    expect(&edge_row(&m.ct, &lv, 0, e), &want, F32, "Jarek edge at valence 5");
}

#[test]
fn modified_butterfly_regular_and_boundary_rules() {
    let m = lattice();
    let (a1, a2) = (g(2, 2), g(3, 2));
    let (b, c, d) = ([g(3, 3), g(2, 1)], [g(2, 3), g(4, 3), g(1, 1), g(3, 1)], [g(1, 2), g(4, 2)]);
    // 10-point rule: a 1/2 - w, b 1/8 + 2w, c -1/16 - w, d w (w = 0: the 8-point butterfly)
    for w in [0.0, 1.0 / 32.0, -1.0 / 64.0] {
        let lv = plan(&m, Scheme::ModifiedButterfly, &Options { tension: w as f32, ..Default::default() });
        let mut want = vec![(a1, 0.5 - w), (a2, 0.5 - w)];
        want.extend(b.map(|x| (x, 0.125 + 2.0 * w)));
        want.extend(c.map(|x| (x, -0.0625 - w)));
        want.extend(d.map(|x| (x, w)));
        expect(&edge_row(&m.ct, &lv, a1, a2), &want, 0.0, &format!("10-point rule, w = {w}"));
        let bf = plan(&m, Scheme::Butterfly, &Options::default());
        if w == 0.0 {
            expect(&edge_row(&m.ct, &bf, a1, a2), &want, 0.0, "8-point butterfly");
        }
    }
    let lv = plan(&m, Scheme::ModifiedButterfly, &Options::default());
    // border edge: the 4-point rule -1/16, 9/16, 9/16, -1/16
    let want = [(g(1, 0), -1.0 / 16.0), (g(2, 0), 9.0 / 16.0), (g(3, 0), 9.0 / 16.0), (g(4, 0), -1.0 / 16.0)];
    expect(&edge_row(&m.ct, &lv, g(2, 0), g(3, 0)), &want, 0.0, "4-point border edge");
    // interior edge from the regular boundary vertex b = (2,0) to the
    // regular interior vertex i = (3,1) (lattice (0,0) -> (1/2, h)):
    // b 3/8, i 5/8, boundary wing (3,0) 1/16, interior wing (2,1) 3/16,
    // b's other boundary neighbour (1,0) -1/16, i + (1,0) = (4,1) -1/16,
    // i + (0,1) = (3,2) -1/8, i + (1,1) = (4,2) 0
    let want = [
        (g(2, 0), 3.0 / 8.0),
        (g(3, 1), 5.0 / 8.0),
        (g(3, 0), 1.0 / 16.0),
        (g(2, 1), 3.0 / 16.0),
        (g(1, 0), -1.0 / 16.0),
        (g(4, 1), -1.0 / 16.0),
        (g(3, 2), -1.0 / 8.0),
    ];
    expect(&edge_row(&m.ct, &lv, g(2, 0), g(3, 1)), &want, 0.0, "MESH rule next to the boundary");
}

#[test]
fn modified_butterfly_extraordinary_rules() {
    // edge from an extraordinary vertex v of valence k to a regular e_0:
    // 3/4 v + sum s_j e_j, e_j around v from e_0 (Zorin et al. 1996; the
    // valence 3 and 4 tables, the table of schemes.md 3.4 for k = 5)
    let tables: [(usize, &[f64], f64); 3] = [
        (3, &[5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0], F32),
        (4, &[3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0], 0.0),
        (5, &[0.35, 0.030902, -0.080902, -0.080902, 0.030902], 1e-6),
    ];
    for (k, s, tol) in tables {
        let (m, ring) = ev_beside_regular(k);
        let lv = plan(&m, Scheme::ModifiedButterfly, &Options::default());
        for j0 in 0..k {
            let mut want = vec![(0, 0.75)];
            want.extend((0..k).map(|j| (ring[(j0 + j) % k], s[j])));
            expect(&edge_row(&m.ct, &lv, 0, ring[j0]), &want, tol, &format!("EV rule, k = {k}, e_0 = {}", ring[j0]));
        }
    }
}
