//! Each scheme checked against its published mathematics, not against our
//! own output: hand-computed first levels, polynomial reproduction, weight
//! sums, interpolation, affine invariance and symmetry.

mod common;
use common::*;
use glam::{Mat3, Vec3};
use subdiv::StencilPlan;
use subdiv::{Mesh, Options, Scheme, subdivide};

fn sub(m: &Mesh, s: Scheme, levels: u32) -> Mesh {
    subdivide(m, s, levels, &Options::default()).unwrap().0
}

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    (a - b).abs().max_element() <= tol
}

/// The new vertex on the edge between input vertices a and b after one level.
fn edge_point(orig: &Mesh, fine: &Mesh, a: u32, b: u32) -> Vec3 {
    let (nv, _) = (orig.positions.len(), ());
    // the edge vertex is adjacent (in the fine mesh) to both a and b
    for tri in fine.ct.v_table().chunks_exact(3) {
        for k in 0..3 {
            let (x, y) = (tri[k], tri[(k + 1) % 3]);
            if x == a && y as usize >= nv {
                let e = y;
                if fine.ct.ring(e).any(|q| q == b) {
                    return fine.positions[e as usize];
                }
            }
        }
    }
    panic!("no edge point between {a} and {b}");
}

#[test]
fn tetrahedron_first_level_by_hand() {
    // P0 = (1,1,1), P1 = (1,-1,-1), P2 = (-1,1,-1), P3 = (-1,-1,1); sum = 0.
    let tet = bundled("tetrahedron.obj");
    let p0 = Vec3::ONE;
    // (scheme, edge point on (P0,P1), new P0)
    let cases = [
        // midpoint: (P0+P1)/2
        (Scheme::Midpoint, Vec3::new(1.0, 0.0, 0.0), p0),
        // Loop: 3/8(P0+P1) + 1/8(P2+P3) = (1/2,0,0); vertex 7/16 P0 + 3/16 (P1+P2+P3) = P0/4
        (Scheme::Loop, Vec3::new(0.5, 0.0, 0.0), p0 * 0.25),
        // butterfly: c's are P3,P3,P2,P2 -> 1/2(P0+P1) + 1/8(P2+P3) - 1/8(P2+P3) = (1,0,0)
        (Scheme::Butterfly, Vec3::new(1.0, 0.0, 0.0), p0),
        // modified butterfly, both ends valence 3: EV at P0 = 3/4 P0 + 5/12 P1 - 1/12 (P2+P3)
        // = 5/6 P0 + 1/2 P1; average with the P1 side = 2/3 (P0+P1) = (4/3,0,0)
        (Scheme::ModifiedButterfly, Vec3::new(4.0 / 3.0, 0.0, 0.0), p0),
        // Jarek: d = 1/8(avg ring - P0) = -P0/6; vertex 5/6 P0; edge (P0+P1)/2 + (P0+P1)/12 = (7/6,0,0)
        (Scheme::Jarek, Vec3::new(7.0 / 6.0, 0.0, 0.0), p0 * (5.0 / 6.0)),
    ];
    for (s, e01, v0) in cases {
        let f = sub(&tet, s, 1);
        assert!(close(edge_point(&tet, &f, 0, 1), e01, 1e-6), "{s}: edge point {:?}", edge_point(&tet, &f, 0, 1));
        assert!(close(f.positions[0], v0, 1e-6), "{s}: vertex point {:?}", f.positions[0]);
    }
}

#[test]
fn every_stencil_sums_to_one() {
    for (name, m) in all_meshes() {
        for s in Scheme::TRIANGLE {
            let plan = StencilPlan::build(&m.ct, s, 2, &Options::default()).unwrap();
            for (l, lvl) in plan.levels.iter().enumerate() {
                for r in 0..lvl.offsets.len() - 1 {
                    let (a, b) = (lvl.offsets[r] as usize, lvl.offsets[r + 1] as usize);
                    let sum: f32 = lvl.weights[a..b].iter().sum();
                    assert!((sum - 1.0).abs() < 1e-5, "{name} {s} level {l} row {r}: weights sum to {sum}");
                }
            }
        }
    }
    // Warren's beta and a non-zero tension too
    let m = disk_fan(16, 3);
    for opts in [
        Options { loop_beta: subdiv::LoopBeta::Warren, ..Default::default() },
        Options { tension: 0.03, ..Default::default() },
    ] {
        for s in [Scheme::Loop, Scheme::ModifiedButterfly] {
            let plan = StencilPlan::build(&m.ct, s, 2, &opts).unwrap();
            for lvl in &plan.levels {
                for r in 0..lvl.offsets.len() - 1 {
                    let sum: f32 = lvl.weights[lvl.offsets[r] as usize..lvl.offsets[r + 1] as usize].iter().sum();
                    assert!((sum - 1.0).abs() < 1e-5);
                }
            }
        }
    }
}

#[test]
fn interpolating_schemes_never_move_old_vertices() {
    for (name, m) in all_meshes() {
        for s in [Scheme::Midpoint, Scheme::Butterfly, Scheme::ModifiedButterfly] {
            let mut cur = m.clone();
            for _ in 0..3 {
                let f = sub(&cur, s, 1);
                assert_eq!(&f.positions[..cur.positions.len()], &cur.positions[..], "{name} {s}");
                cur = f;
            }
        }
    }
}

/// Distance from point q to triangle (a, b, c).
fn dist_to_triangle(q: Vec3, a: Vec3, b: Vec3, c: Vec3) -> f32 {
    let n = (b - a).cross(c - a);
    let nn = n.length_squared();
    if nn > 0.0 {
        let h = (q - a).dot(n) / nn;
        let proj = q - n * h;
        let inside = [(a, b), (b, c), (c, a)].iter().all(|&(x, y)| (y - x).cross(proj - x).dot(n) >= -1e-9);
        if inside {
            return (q - proj).length();
        }
    }
    let seg = |x: Vec3, y: Vec3| {
        let t = ((q - x).dot(y - x) / (y - x).length_squared().max(1e-20)).clamp(0.0, 1.0);
        (q - (x + (y - x) * t)).length()
    };
    seg(a, b).min(seg(b, c)).min(seg(c, a))
}

#[test]
fn midpoint_points_stay_on_the_input_surface() {
    for (name, m) in all_meshes() {
        if m.ct.num_triangles() > 300 {
            continue;
        }
        let f = sub(&m, Scheme::Midpoint, 3);
        let scale = {
            let (lo, hi) = m.bounds();
            (hi - lo).length()
        };
        for &q in &f.positions {
            let d =
                m.ct.v_table()
                    .chunks_exact(3)
                    .map(|t| {
                        dist_to_triangle(
                            q,
                            m.positions[t[0] as usize],
                            m.positions[t[1] as usize],
                            m.positions[t[2] as usize],
                        )
                    })
                    .fold(f32::MAX, f32::min);
            assert!(d < 1e-5 * scale, "{name}: point {q:?} is {d} off the surface");
        }
    }
}

/// Positions of a grid as (x, y, f(x, y)) over a regular lattice's affine image,
/// subdivided once; returns (parameter points from the midpoint split, result).
fn height_field(n: usize, s: Scheme, levels: u32, f: impl Fn(f32, f32) -> f32) -> (Mesh, Mesh) {
    let g = grid(n, n, |i, j| Vec3::new(i, j, f(i, j)));
    let uv = grid(n, n, |i, j| Vec3::new(i, j, 0.0));
    (sub(&uv, Scheme::Midpoint, levels), sub(&g, s, levels))
}

#[test]
fn butterfly_reproduces_cubics_on_a_regular_lattice() {
    // cubic in the lattice parameters; the grid is the affine image of the regular lattice
    let f = |x: f32, y: f32| {
        0.01 * (x * x * x - 2.0 * x * x * y + 0.5 * x * y * y + 0.3 * y * y * y) + 0.1 * x * y - 0.2 * y + 1.0
    };
    let n = 12;
    for s in [Scheme::Butterfly, Scheme::ModifiedButterfly] {
        let (uv, out) = height_field(n, s, 1, f);
        let mut checked = 0;
        for (q, p) in uv.positions.iter().zip(&out.positions) {
            // only points whose whole stencil is interior and regular (3 lattice units from the boundary)
            if q.x < 3.0 || q.y < 3.0 || q.x > n as f32 - 3.0 || q.y > n as f32 - 3.0 {
                continue;
            }
            assert!((p.x - q.x).abs() < 1e-4 && (p.y - q.y).abs() < 1e-4, "{s}: linear precision in x, y");
            assert!((p.z - f(q.x, q.y)).abs() < 1e-3, "{s}: cubic not reproduced at {q:?}: {} vs {}", p.z, f(q.x, q.y));
            checked += 1;
        }
        assert!(checked > 100);
    }
}

#[test]
fn modified_butterfly_keeps_an_affine_grid_affine_even_at_the_boundary() {
    // affine map of the parameter grid, with a straight boundary
    let a = Mat3::from_cols(Vec3::new(1.0, 0.2, 0.3), Vec3::new(0.4, 1.1, -0.2), Vec3::new(0.0, 0.0, 1.0));
    let b = Vec3::new(0.5, -1.0, 2.0);
    let n = 6;
    let g = grid(n, n, |i, j| a * Vec3::new(i, j, 0.0) + b);
    let uv = grid(n, n, |i, j| Vec3::new(i, j, 0.0));
    for s in [Scheme::ModifiedButterfly, Scheme::Butterfly, Scheme::Midpoint] {
        let out = sub(&g, s, 3);
        let par = sub(&uv, Scheme::Midpoint, 3);
        let nf = n as f32;
        let mut straight_boundary = 0;
        for (q, p) in par.positions.iter().zip(&out.positions) {
            // the 4-point curve rule rounds the boundary polygon's 90-degree corners
            // by design; everything else, including the straight boundary, stays affine
            let near_corner = [(0.0, 0.0), (nf, 0.0), (0.0, nf), (nf, nf)]
                .iter()
                .any(|&(cx, cy)| (q.x - cx).abs() + (q.y - cy).abs() < 2.6);
            if near_corner {
                continue;
            }
            if q.x == 0.0 || q.y == 0.0 || q.x == nf || q.y == nf {
                straight_boundary += 1;
            }
            assert!(close(*p, a * *q + b, 1e-4), "{s}: {p:?} is not the affine image {:?}", a * *q + b);
        }
        assert!(straight_boundary > 20);
    }
}

#[test]
fn modified_butterfly_reproduces_quadratics_next_to_a_straight_boundary() {
    let f = |x: f32, y: f32| 0.02 * (x * x - 1.5 * x * y + 0.7 * y * y) + 0.1 * x - 0.3 * y;
    let n = 8;
    let (uv, out) = height_field(n, Scheme::ModifiedButterfly, 1, f);
    let nf = n as f32;
    let mut boundary_row = 0;
    for (q, p) in uv.positions.iter().zip(&out.positions) {
        // skip the neighbourhood of the four grid corners (valence 2 and 3: ghost rule, linear only)
        let near_corner = [(0.0, 0.0), (nf, 0.0), (0.0, nf), (nf, nf)]
            .iter()
            .any(|&(cx, cy)| (q.x - cx).abs() + (q.y - cy).abs() < 2.6);
        if near_corner {
            continue;
        }
        if q.y < 1.0 || q.x < 1.0 || q.x > nf - 1.0 || q.y > nf - 1.0 {
            boundary_row += 1;
        }
        assert!((p.z - f(q.x, q.y)).abs() < 1e-4, "quadratic not reproduced at {q:?}: {} vs {}", p.z, f(q.x, q.y));
    }
    assert!(boundary_row > 20, "the test must cover points next to the boundary");
    // the classic butterfly with ghosts is only linear there: it must differ somewhere
    let (_, bf) = height_field(n, Scheme::Butterfly, 1, f);
    let worst = uv.positions.iter().zip(&bf.positions).map(|(q, p)| (p.z - f(q.x, q.y)).abs()).fold(0.0, f32::max);
    assert!(worst > 1e-3, "sanity: the ghost rule is not quadratic-precise");
}

#[test]
fn loop_and_jarek_reproduce_linear_functions() {
    // on a regular region: new points are the affine image of the midpoint-split parameters
    let a = Mat3::from_cols(Vec3::new(1.0, 0.1, 0.5), Vec3::new(-0.3, 0.9, 0.2), Vec3::Z);
    let n = 10;
    let g = grid(n, n, |i, j| a * Vec3::new(i, j, 0.0));
    let uv = grid(n, n, |i, j| Vec3::new(i, j, 0.0));
    for s in [Scheme::Loop, Scheme::Jarek] {
        let out = sub(&g, s, 1);
        let par = sub(&uv, Scheme::Midpoint, 1);
        let mut checked = 0;
        for (q, p) in par.positions.iter().zip(&out.positions) {
            let nf = n as f32;
            // corners of the grid are boundary corners whose rule moves them; skip their neighbourhood
            let near_corner = [(0.0, 0.0), (nf, 0.0), (0.0, nf), (nf, nf)]
                .iter()
                .any(|&(cx, cy)| (q.x - cx).abs() + (q.y - cy).abs() < 2.1);
            if near_corner {
                continue;
            }
            assert!(close(*p, a * *q, 1e-4), "{s}: {p:?} vs {:?}", a * *q);
            checked += 1;
        }
        assert!(checked > 300);
    }
}

#[test]
fn every_scheme_is_affine_invariant() {
    let a = Mat3::from_cols(Vec3::new(0.9, 0.3, -0.2), Vec3::new(0.1, 1.2, 0.4), Vec3::new(-0.3, 0.2, 0.8));
    let b = Vec3::new(3.0, -2.0, 1.5);
    for (name, m) in all_meshes() {
        let mut t = m.clone();
        for p in &mut t.positions {
            *p = a * *p + b;
        }
        for s in Scheme::TRIANGLE {
            let f1 = sub(&m, s, 2);
            let f2 = sub(&t, s, 2);
            for (p, q) in f1.positions.iter().zip(&f2.positions) {
                assert!(close(a * *p + b, *q, 2e-4 * (1.0 + q.abs().max_element())), "{name} {s}");
            }
        }
    }
}

/// Signed permutation matrices that map the mesh onto itself (as triangles).
fn symmetries(m: &Mesh) -> Vec<Mat3> {
    let mut out = Vec::new();
    let perms = [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]];
    for perm in perms {
        for signs in 0..8 {
            let mut cols = [Vec3::ZERO; 3];
            for (i, &pi) in perm.iter().enumerate() {
                let s = if signs & (1 << i) != 0 { -1.0 } else { 1.0 };
                cols[i][pi] = s;
            }
            let r = Mat3::from_cols(cols[0], cols[1], cols[2]);
            if r == Mat3::IDENTITY {
                continue;
            }
            // vertex map
            let map: Option<Vec<u32>> = m
                .positions
                .iter()
                .map(|&p| {
                    let q = r * p;
                    m.positions.iter().position(|&x| close(x, q, 1e-5)).map(|i| i as u32)
                })
                .collect();
            let Some(map) = map else { continue };
            let norm = |t: [u32; 3]| {
                let k = (0..3).min_by_key(|&k| t[k]).unwrap();
                [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
            };
            let mut tris: Vec<[u32; 3]> = m.ct.v_table().chunks_exact(3).map(|t| norm([t[0], t[1], t[2]])).collect();
            tris.sort_unstable();
            let reflect = r.determinant() < 0.0;
            let mut mapped: Vec<[u32; 3]> =
                m.ct.v_table()
                    .chunks_exact(3)
                    .map(|t| {
                        let (a, b, c) = (map[t[0] as usize], map[t[1] as usize], map[t[2] as usize]);
                        norm(if reflect { [a, c, b] } else { [a, b, c] })
                    })
                    .collect();
            mapped.sort_unstable();
            if mapped == tris {
                out.push(r);
            }
        }
    }
    out
}

#[test]
fn symmetric_inputs_stay_symmetric() {
    let mut cube = bundled("cube.obj");
    let (lo, hi) = cube.bounds();
    for p in &mut cube.positions {
        *p -= (lo + hi) * 0.5;
    }
    for (name, m, min_syms) in
        [("tetrahedron", bundled("tetrahedron.obj"), 23), ("cube", cube, 1), ("icosahedron", icosahedron(), 23)]
    {
        let syms = symmetries(&m);
        assert!(syms.len() >= min_syms, "{name}: found only {} symmetries", syms.len());
        for s in Scheme::TRIANGLE {
            let f = sub(&m, s, 2);
            // the point set maps onto itself: as multisets (a bijection, not
            // only every image present somewhere), rounded to 1e-4
            let key = |p: Vec3| (p * 1e4).round().as_i64vec3().to_array();
            let mut sorted: Vec<[i64; 3]> = f.positions.iter().map(|&p| key(p)).collect();
            sorted.sort_unstable();
            for r in &syms {
                let mut image: Vec<[i64; 3]> = f.positions.iter().map(|&p| key(*r * p)).collect();
                image.sort_unstable();
                assert_eq!(image, sorted, "{name} {s}: the symmetry {r:?} does not map the points onto themselves");
            }
        }
    }
}

#[test]
fn stencil_plan_equals_full_subdivision_for_random_positions() {
    let mut rng = Rng(0x9e3779b97f4a7c15);
    for (name, m) in all_meshes() {
        for s in Scheme::TRIANGLE {
            let levels = if m.ct.num_triangles() > 500 { 2 } else { 3 };
            let plan = StencilPlan::build(&m.ct, s, levels, &Options::default()).unwrap();
            let mut scratch = Default::default();
            let mut out = Vec::new();
            for _ in 0..2 {
                let mut moved = m.clone();
                for p in &mut moved.positions {
                    *p += rng.vec3() * 0.3;
                }
                plan.apply(&moved.positions, &mut scratch, &mut out);
                let full = sub(&moved, s, levels);
                assert_eq!(plan.ct, full.ct, "{name} {s}: plan topology");
                // 1e-6 relative: the direct path may sum in a different order (f32)
                for (a, b) in out.iter().zip(&full.positions) {
                    assert!(
                        close(*a, *b, 1e-6 * b.abs().max_element().max(1.0)),
                        "{name} {s}: plan {a:?} vs full {b:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn boundary_curves_follow_the_published_curve_rules() {
    // Loop's boundary is the cubic B-spline of the boundary polygon and the
    // butterflies' the 4-point curve: both independent of the interior, so
    // bending the interior must not move any boundary point.
    let g = disk_fan(12, 3);
    let mut bent = g.clone();
    for (v, p) in bent.positions.iter_mut().enumerate() {
        if !g.ct.is_boundary_vertex(v as u32) {
            p.z += 0.7;
        }
    }
    for s in Scheme::TRIANGLE {
        let (a, b) = (sub(&g, s, 2), sub(&bent, s, 2));
        for v in 0..a.positions.len() as u32 {
            if a.ct.is_boundary_vertex(v) {
                assert!(
                    close(a.positions[v as usize], b.positions[v as usize], 1e-6),
                    "{s}: boundary depends on the interior"
                );
            }
        }
    }
}

#[test]
fn translating_the_input_translates_every_output_point_by_the_same_vector() {
    // S(x + t) = S(x) + t exactly when every stencil sums to one; a stencil
    // summing to 1.25 (the modified butterfly's old valence-2 rule) moves the
    // new points by 1.25 t. Valence 2, 3 and 4, alone and beside regular
    // vertices; t is large so that a wrong sum cannot hide in rounding.
    let t = Vec3::new(8.0, -4.0, 2.0);
    for (name, m) in low_valence_meshes() {
        let mut moved = m.clone();
        for p in &mut moved.positions {
            *p += t;
        }
        for s in Scheme::TRIANGLE {
            for levels in [1, 2] {
                let (a, b) = (sub(&m, s, levels), sub(&moved, s, levels));
                for (i, (p, q)) in a.positions.iter().zip(&b.positions).enumerate() {
                    assert!(
                        close(*q - *p, t, 1e-4 * 8.0),
                        "{name} {s} level {levels}: point {i} moved by {:?}",
                        *q - *p
                    );
                }
            }
        }
    }
}

#[test]
fn stencils_at_low_valence_sum_to_one() {
    for (name, m) in low_valence_meshes() {
        for s in Scheme::TRIANGLE {
            let plan = StencilPlan::build(&m.ct, s, 1, &Options::default()).unwrap();
            let lvl = &plan.levels[0];
            for r in 0..lvl.offsets.len() - 1 {
                let sum: f32 = lvl.weights[lvl.offsets[r] as usize..lvl.offsets[r + 1] as usize].iter().sum();
                assert!((sum - 1.0).abs() < 1e-6, "{name} {s} row {r}: weights sum to {sum}");
            }
        }
    }
}

/// What the tension does (the mathematics first). Zorin's 10-point rule
/// (a 1/2 - w, b 1/8 + 2w, c -1/16 - w, d w; `--tension`, applied only to
/// interior edges whose ends are both regular) reproduces quadratics for
/// every w, and its stencil is symmetric under both reflections that fix
/// the edge, so every cubic centred at the edge's midpoint is odd in one of
/// the two directions and sums to zero on both sides: it reproduces cubics
/// for EVERY w, not only for the 8-point w = 0. No w reproduces all
/// quartics (along the edge x^4 needs w = 1/32, x^2 y^2 needs w = -1/16).
/// (Dyn-Levin-Gregory's own tension family, 1/2 a, 2w b, -w c, reproduces
/// quadratics, hence cubics, only at w = 1/16; it is our fixed `butterfly`.)
/// Checked exactly: lattice coordinates are integers, dyadic w keeps every
/// weight exact in f32, and f64 sums of these products are exact.
#[test]
fn ten_point_rule_reproduces_cubics_for_every_tension_and_not_quartics() {
    let n = 10;
    let m = grid(n, n, |i, j| Vec3::new(i, j, 0.0));
    let interior: Vec<bool> = (0..m.positions.len() as u32).map(|v| !m.ct.is_boundary_vertex(v)).collect();
    let at = |v: u32| (f64::from(m.positions[v as usize].x), f64::from(m.positions[v as usize].y));
    let monomial = |a: i32, b: i32| move |(x, y): (f64, f64)| x.powi(a) * y.powi(b);
    for w in [0.0, 1.0 / 32.0, -1.0 / 64.0, 3.0 / 64.0, 1.0 / 16.0] {
        let opts = Options { tension: w as f32, ..Default::default() };
        let lvl = &StencilPlan::build(&m.ct, Scheme::ModifiedButterfly, 1, &opts).unwrap().levels[0];
        let mut rows = 0;
        let mut worst_quartic = 0.0f64;
        for r in 0..lvl.offsets.len() - 1 {
            let (a, b) = (lvl.offsets[r] as usize, lvl.offsets[r + 1] as usize);
            let (idx, ws) = (&lvl.indices[a..b], &lvl.weights[a..b]);
            // only the regular rule: every source vertex interior
            if !idx.iter().all(|&v| interior[v as usize]) {
                continue;
            }
            rows += 1;
            assert_eq!(idx.len(), if w == 0.0 { 8 } else { 10 }, "w = {w}: row {r} is not the regular rule");
            let apply = |f: &dyn Fn((f64, f64)) -> f64| {
                idx.iter().zip(ws).map(|(&v, &wt)| f64::from(wt) * f(at(v))).sum::<f64>()
            };
            let mid = (apply(&|q| q.0), apply(&|q| q.1));
            for deg in 0..=4 {
                for ea in 0..=deg {
                    let f = monomial(ea, deg - ea);
                    let err = (apply(&f) - f(mid)).abs();
                    if deg <= 3 {
                        assert_eq!(err, 0.0, "w = {w}, row {r}: x^{ea} y^{} not reproduced", deg - ea);
                    } else {
                        worst_quartic = worst_quartic.max(err);
                    }
                }
            }
        }
        assert!(rows > 100, "w = {w}: only {rows} regular rows");
        assert!(worst_quartic > 1e-3, "w = {w}: quartics reproduced too (error {worst_quartic})");
    }
}

/// Zorin's valence-4 table (3/8, 0, -1/8, 0) and the cosine formula's values
/// at k = 4 (7/16, -1/16, -1/16, -1/16) differ by (e0 - e1 + e2 - e3)/16,
/// which vanishes when the ring is a parallelogram: only a ring that is not
/// one tells them apart. The same for the valence-3 table against the
/// formula (7/12, -1/6, -1/6): they differ by (e0 - (e1 + e2)/2)/6.
#[test]
fn modified_butterfly_low_valence_tables_on_rings_that_are_not_parallelograms() {
    let f64v = |q: Vec3| q.as_dvec3();
    for (name, m) in
        low_valence_meshes().into_iter().filter(|(n, _)| n.contains("split once") && !n.starts_with("pillow"))
    {
        let fine = sub(&m, Scheme::ModifiedButterfly, 1);
        let mut checked = 0;
        for v in 0..m.positions.len() as u32 {
            let k = m.ct.valence(v) as usize;
            if !(k == 3 || k == 4) {
                continue;
            }
            let ring: Vec<u32> = m.ct.ring(v).collect();
            let e = |j: usize| f64v(m.positions[ring[j % k] as usize]);
            let pv = f64v(m.positions[v as usize]);
            for (j0, &q0) in ring.iter().enumerate() {
                // e_0 = q0 is a regular interior vertex: the EV rule of v alone
                assert_eq!(m.ct.valence(q0), 6);
                let (e0, e1, e2) = (e(j0), e(j0 + 1), e(j0 + 2));
                let (table, formula, gap) = if k == 4 {
                    let e3 = e(j0 + 3);
                    (
                        pv * 0.75 + e0 * 0.375 - e2 * 0.125,
                        pv * 0.75 + e0 * (7.0 / 16.0) - (e1 + e2 + e3) / 16.0,
                        (e0 - e1 + e2 - e3) / 16.0,
                    )
                } else {
                    (
                        pv * 0.75 + e0 * (5.0 / 12.0) - (e1 + e2) / 12.0,
                        pv * 0.75 + e0 * (7.0 / 12.0) - (e1 + e2) / 6.0,
                        (e0 - (e1 + e2) * 0.5) / 6.0,
                    )
                };
                assert!(gap.length() > 1e-2, "{name}: the ring of {v} must not hide the difference");
                assert!(((formula - table) - gap).length() < 1e-12);
                let got = f64v(edge_point(&m, &fine, v, q0));
                assert!((got - table).length() < 1e-5, "{name}: valence {k} vertex {v}: {got:?} vs table {table:?}");
                checked += 1;
            }
        }
        assert!(checked >= 12, "{name}: {checked} edges checked");
    }
}
