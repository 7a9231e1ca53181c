//! The patch at an interior extraordinary vertex (valence `N != 6`), Stam
//! 1998 §3 with his eigen decomposition replaced by an exact equivalent
//! that needs no eigenvectors (so valence 3 and the even valences, where
//! eigenvalues repeat across blocks, need no care).
//!
//! ```text
//! support of the triangle (x, a, b), K = N + 6 points (walk order):
//!     x, the ring r_0 = a, r_1 = b, ..., r_{N-1} of x, three outer
//!     neighbours of a, two of b (as the regular patch, super::patch)
//! one subdivision step maps it to the support of the corner child
//! (x', e(x,a), e(x,b)):           C_1 = A C_0              A: K x K
//! and the other three children are regular patches:
//!     child 1 (e(x,a), a', e(a,b)), child 2 (e(x,b), e(a,b), b'),
//!     child 3 (e(x,a), e(a,b), e(x,b))       support_k = P_k C_1 (12 x K)
//! a point with u + v in (2^-(m+1), 2^-m] lies in child k of level m:
//!     P(u, v) = patch_k(P_k A^m C_0) at (s, t) = child_k(2^m (u, v))
//! ```
//!
//! A and P_k are **computed, not tabulated**: [`Template`] builds the
//! support's neighbourhood (x, the ring, the outer vertices) as a small
//! mesh whose points are the unit vectors of R^K, subdivides it once with
//! Loop's smooth rules (the same rules and beta as [`super::super::rules::loop_`],
//! in f64) and walks the child supports. Vertices whose ring the template
//! does not close get no value, and a support that needed one is a bug the
//! unit tests would catch.
//!
//! Bounded cost: `A = 1 l^T + B` with `l` the limit mask (the left
//! eigenvector of eigenvalue 1, `l^T A = l^T`, `A 1 = 1`) and `B 1 = 0`,
//! `l^T B = 0`, so `A^m C = 1 (l . C) + B^m (C - 1 (l . C))`. The table
//! holds `(B / lambda)^(2^j)` for `j <= 10` (`lambda` the subdominant
//! eigenvalue `3/8 + cos(2 pi / N) / 4`), so any `m < 2048` (every positive
//! f64 `u + v` needs `m <= 1074`) costs at most 11 matrix-vector products;
//! the limit point is exact and the surface near it is `l . C +
//! lambda^m (...)`, with no cancellation however close the point is.

use super::patch::BoxSpline;
use crate::subdiv::LoopBeta;
use glam::DVec3;
use std::collections::HashMap;

/// Powers of two in the table: `m < 2^POWERS`.
const POWERS: usize = 11;

/// The exact evaluation data of one valence.
#[derive(Clone, Debug)]
pub(crate) struct Extraordinary {
    /// The support size `N + 6`.
    pub(crate) k: usize,
    /// The normalisation `lambda` of the power table.
    pub(crate) lambda: f64,
    /// The limit mask on the support.
    pub(crate) limit: Vec<f64>,
    /// The tangent masks on the support (`cos` and `sin` around the ring).
    pub(crate) tangents: [Vec<f64>; 2],
    /// `(B / lambda)^(2^j)`, row-major `k x k`.
    powers: Vec<Vec<f64>>,
    /// Per child 1, 2, 3: the basis of its patch on the support, by
    /// monomial (`k x 15`, the box spline's basis times `P_k`; the layout
    /// [`super::patch::jet`] reads).
    pub(crate) picks: [Vec<f64>; 3],
}

/// Directed edge -> the third vertex of its triangle.
struct Template {
    tris: Vec<[u32; 3]>,
    opp: HashMap<(u32, u32), u32>,
    nv: u32,
}

impl Template {
    fn new(tris: Vec<[u32; 3]>, nv: u32) -> Template {
        let mut opp = HashMap::new();
        for t in &tris {
            for i in 0..3 {
                opp.insert((t[i], t[(i + 1) % 3]), t[(i + 2) % 3]);
            }
        }
        Template { tris, opp, nv }
    }

    /// `x` with its ring r_i, outer vertices q_i (across r_i r_{i+1}) and
    /// p_i (between q_{i-1} and q_i), so every r_i has valence 6.
    fn around(valence: u32) -> Template {
        let n = valence;
        let (r, q, p) = (|i: u32| 1 + i % n, |i: u32| 1 + n + i % n, |i: u32| 1 + 2 * n + i % n);
        let mut tris = Vec::new();
        for i in 0..n {
            let prev = i + n - 1;
            tris.push([0, r(i), r(i + 1)]);
            tris.push([r(i + 1), r(i), q(i)]);
            tris.push([r(i), q(prev), p(i)]);
            tris.push([r(i), p(i), q(i)]);
        }
        Template::new(tris, 1 + 3 * n)
    }

    /// The ring of `v` counter-clockwise from `start`, or `None` if open.
    fn ring(&self, v: u32, start: u32) -> Option<Vec<u32>> {
        let mut out = vec![start];
        let mut w = *self.opp.get(&(v, start))?;
        while w != start {
            out.push(w);
            w = *self.opp.get(&(v, w))?;
            if out.len() > self.tris.len() {
                return None;
            }
        }
        Some(out)
    }

    /// The support of triangle `(c0, c1, c2)` in walk order.
    fn support(&self, c0: u32, c1: u32, c2: u32) -> Option<Vec<u32>> {
        let ring0 = self.ring(c0, c1)?;
        let ring1 = self.ring(c1, c2)?;
        let ring2 = self.ring(c2, c0)?;
        if ring0.get(1) != Some(&c2) || ring1.len() != 6 || ring2.len() != 6 {
            return None;
        }
        let mut out = vec![c0];
        out.extend(&ring0);
        out.extend(&ring1[3..6]);
        out.extend(&ring2[3..5]);
        Some(out)
    }
}

type Point = Option<Vec<f64>>;

fn combine(terms: &[(&Point, f64)]) -> Point {
    let mut out = vec![0.0; terms[0].0.as_ref()?.len()];
    for (p, w) in terms {
        for (o, x) in out.iter_mut().zip(p.as_ref()?) {
            *o += w * x;
        }
    }
    Some(out)
}

/// One step of Loop's smooth rules on the template: the child template, its
/// points, and the child id of the edge point of each parent edge.
fn refine(t: &Template, pts: &[Point], beta: LoopBeta) -> (Template, Vec<Point>, HashMap<(u32, u32), u32>) {
    let mut child: Vec<Point> = Vec::new();
    for v in 0..t.nv {
        let start = t.tris.iter().find(|tr| tr[0] == v).map(|tr| tr[1]);
        let ring = start.and_then(|s| t.ring(v, s));
        child.push(ring.and_then(|ring| {
            let b = beta.beta(ring.len() as u32);
            let mut terms = vec![(&pts[v as usize], 1.0 - ring.len() as f64 * b)];
            terms.extend(ring.iter().map(|&w| (&pts[w as usize], b)));
            combine(&terms)
        }));
    }
    let mut edges = HashMap::new();
    let mut tris = Vec::new();
    let mut edge = |a: u32, b: u32, child: &mut Vec<Point>| -> u32 {
        let key = (a.min(b), a.max(b));
        *edges.entry(key).or_insert_with(|| {
            let (o1, o2) = (t.opp.get(&(a, b)), t.opp.get(&(b, a)));
            child.push(match (o1, o2) {
                (Some(&c), Some(&d)) => combine(&[
                    (&pts[a as usize], 0.375),
                    (&pts[b as usize], 0.375),
                    (&pts[c as usize], 0.125),
                    (&pts[d as usize], 0.125),
                ]),
                _ => None,
            });
            child.len() as u32 - 1
        })
    };
    for &[a, b, c] in &t.tris {
        let (ab, bc, ca) = (edge(a, b, &mut child), edge(b, c, &mut child), edge(c, a, &mut child));
        tris.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
    }
    let nv = child.len() as u32;
    (Template::new(tris, nv), child, edges)
}

fn rows(t: &Template, pts: &[Point], support: Option<Vec<u32>>) -> Vec<Vec<f64>> {
    let support = support.unwrap_or_else(|| unreachable!("the template holds every child support"));
    support.iter().map(|&v| pts[v as usize].clone().unwrap_or_else(|| unreachable!("{v} of {}", t.nv))).collect()
}

impl Extraordinary {
    /// The tables of valence `valence >= 3` under `beta`.
    pub(crate) fn new(valence: u32, beta: LoopBeta, spline: &BoxSpline) -> Extraordinary {
        let n = valence as usize;
        let k = n + 6;
        let t = Template::around(valence);
        let support = t.support(0, 1, 2).unwrap_or_else(|| unreachable!("the template closes x's support"));
        let mut pts: Vec<Point> = vec![None; t.nv as usize];
        for (i, &v) in support.iter().enumerate() {
            let mut e = vec![0.0; k];
            e[i] = 1.0;
            pts[v as usize] = Some(e);
        }
        let (c, cpts, e) = refine(&t, &pts, beta);
        let ex = |a: u32, b: u32| e[&(a.min(b), a.max(b))];
        let (xa, xb, ab) = (ex(0, 1), ex(0, 2), ex(1, 2));
        let a = rows(&c, &cpts, c.support(0, xa, xb));
        let children = [c.support(xa, 1, ab), c.support(xb, ab, 2), c.support(xa, ab, xb)];
        let picks = children.map(|s| pick(spline, &rows(&c, &cpts, s), k));

        let b = beta.beta(valence);
        let chi = 1.0 / (n as f64 + 3.0 / (8.0 * b));
        let mut limit = vec![0.0; k];
        limit[0] = 1.0 - n as f64 * chi;
        limit[1..=n].iter_mut().for_each(|w| *w = chi);
        let angle = |i: usize| 2.0 * std::f64::consts::PI * i as f64 / n as f64;
        let mut tangents = [vec![0.0; k], vec![0.0; k]];
        for i in 0..n {
            tangents[0][1 + i] = angle(i).cos();
            tangents[1][1 + i] = angle(i).sin();
        }
        let lambda = 0.375 + 0.25 * angle(1).cos();
        let powers = power_table(&a, &limit, lambda);
        Extraordinary { k, lambda, limit, tangents, powers, picks }
    }

    /// `(B / lambda)^m c` for the support points `c` (with `l . c = 0`),
    /// using `tmp` (as long as `c`) as scratch.
    pub(crate) fn power(&self, m: u32, c: &mut [DVec3], tmp: &mut [DVec3]) {
        for (j, table) in self.powers.iter().enumerate() {
            if m >> j & 1 == 1 {
                for (row, out) in table.chunks_exact(self.k).zip(tmp.iter_mut()) {
                    *out = row.iter().zip(c.iter()).map(|(&w, &p)| p * w).sum();
                }
                c.copy_from_slice(tmp);
            }
        }
    }
}

/// The box spline's basis through the pick rows: `k x 15`, support point
/// `i`'s monomial coefficients `sum_j coef[m][j] rows[j][i]`.
fn pick(spline: &BoxSpline, rows: &[Vec<f64>], k: usize) -> Vec<f64> {
    let mut out = vec![0.0; 15 * k];
    for (m, coef) in spline.coef.iter().enumerate() {
        for (j, row) in rows.iter().enumerate() {
            for i in 0..k {
                out[i * 15 + m] += coef[j] * row[i];
            }
        }
    }
    out
}

/// `(B / lambda)^(2^j)` for `j < POWERS`, `B = A - 1 l^T`.
fn power_table(a: &[Vec<f64>], limit: &[f64], lambda: f64) -> Vec<Vec<f64>> {
    let k = limit.len();
    let mut b = vec![0.0; k * k];
    for i in 0..k {
        for j in 0..k {
            b[i * k + j] = (a[i][j] - limit[j]) / lambda;
        }
    }
    let mut out = vec![b];
    while out.len() < POWERS {
        let last = &out[out.len() - 1];
        let mut sq = vec![0.0; k * k];
        for i in 0..k {
            for l in 0..k {
                let w = last[i * k + l];
                if w != 0.0 {
                    for j in 0..k {
                        sq[i * k + j] += w * last[l * k + j];
                    }
                }
            }
        }
        out.push(sq);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn matrix(valence: u32) -> (Vec<Vec<f64>>, Vec<f64>) {
        let t = Template::around(valence);
        let k = valence as usize + 6;
        let support = t.support(0, 1, 2).unwrap();
        let mut pts: Vec<Point> = vec![None; t.nv as usize];
        for (i, &v) in support.iter().enumerate() {
            let mut e = vec![0.0; k];
            e[i] = 1.0;
            pts[v as usize] = Some(e);
        }
        let (c, cpts, e) = refine(&t, &pts, LoopBeta::Loop);
        let ex = |a: u32, b: u32| e[&(a.min(b), a.max(b))];
        let a = rows(&c, &cpts, c.support(0, ex(0, 1), ex(0, 2)));
        let ev = Extraordinary::new(valence, LoopBeta::Loop, &BoxSpline::derive());
        (a, ev.limit)
    }

    #[test]
    fn the_limit_mask_is_a_left_eigenvector_and_rows_sum_to_one() {
        for valence in [3, 4, 5, 6, 7, 8, 12] {
            let (a, l) = matrix(valence);
            for (i, row) in a.iter().enumerate() {
                assert!((row.iter().sum::<f64>() - 1.0).abs() < 1e-12, "valence {valence} row {i}");
            }
            for j in 0..l.len() {
                let la: f64 = (0..l.len()).map(|i| l[i] * a[i][j]).sum();
                assert!((la - l[j]).abs() < 1e-12, "valence {valence}: (l A)_{j} = {la}, l_{j} = {}", l[j]);
            }
        }
    }

    #[test]
    fn the_subdominant_eigenvalue_is_the_ring_frequency() {
        // the tangent masks are left eigenvectors of eigenvalue lambda
        for valence in [3, 5, 7, 9] {
            let (a, _) = matrix(valence);
            let ev = Extraordinary::new(valence, LoopBeta::Loop, &BoxSpline::derive());
            for t in &ev.tangents {
                for j in 0..ev.k {
                    let ta: f64 = (0..ev.k).map(|i| t[i] * a[i][j]).sum();
                    assert!((ta - ev.lambda * t[j]).abs() < 1e-12, "valence {valence} column {j}");
                }
            }
        }
    }

    #[test]
    fn the_power_table_is_bounded_and_squares() {
        let ev = Extraordinary::new(5, LoopBeta::Loop, &BoxSpline::derive());
        let big = ev.powers.iter().flatten().fold(0.0f64, |m, &x| m.max(x.abs()));
        assert!(big < 10.0, "entries of (B / lambda)^(2^j) stay bounded: {big}");
        // applying 2^j + 2^j through the table equals 2^(j+1)
        let mut c: Vec<DVec3> = (0..ev.k).map(|i| DVec3::new(i as f64, 1.0, -(i as f64))).collect();
        let mean: DVec3 = c.iter().zip(&ev.limit).map(|(p, &w)| *p * w).sum();
        c.iter_mut().for_each(|p| *p -= mean);
        let (mut two, mut four, mut tmp) = (c.clone(), c.clone(), c.clone());
        ev.power(2, &mut two, &mut tmp);
        ev.power(2, &mut two, &mut tmp);
        ev.power(4, &mut four, &mut tmp);
        for (x, y) in two.iter().zip(&four) {
            assert!((*x - *y).length() < 1e-12);
        }
    }
}
