//! The regular Loop patch: the three-direction quartic box spline over one
//! triangle whose three vertices have valence 6 (Loop 1987; Stam,
//! "Evaluation of Loop Subdivision Surfaces", 1998, §2).
//!
//! ```text
//! support, on the triangular lattice (edges along (1,0), (0,1), (1,1)),
//! the triangle c0 = (0,0), c1 = (1,0), c2 = (1,1):
//!
//!            11(1,2)  10(2,2)
//!      3(0,1)    2(1,1)    9(2,1)
//!  4(-1,0)   0(0,0)    1(1,0)    8(2,0)
//!      5(-1,-1)  6(0,-1)   7(1,-1)
//!
//! parameter: P(u, v) = (1 - u - v) c0 + u c1 + v c2, lattice (x, y) = (u + v, v)
//! ```
//!
//! The order is the one [`super::support`] walks on a mesh: `c0`, the ring
//! of `c0` counter-clockwise from `c1` (`c1 c2 3 4 5 6`), then the three
//! outer neighbours of `c1` (`7 8 9`) and the two of `c2` (`10 11`).
//!
//! The 12 basis functions are **derived here from the subdivision rules**,
//! not copied from a table: the limit surface over the triangle is a quartic
//! polynomial (15 coefficients), so its values at 15 points determine it.
//! [`BoxSpline::derive`] subdivides each control point's unit impulse twice
//! on the infinite lattice with Loop's regular masks (vertex `10/16, 1/16`;
//! edge `3/8, 3/8, 1/8, 1/8`), applies the regular limit mask (`1/2` and
//! `1/12` on each of the six neighbours) at the 15 level-2 points of the
//! triangle, `(u, v) = (i/4, j/4)`, and solves the 15 x 15 Vandermonde system
//! for the monomial coefficients. The unit tests check the partition of
//! unity, symmetry and polynomial reproduction; `tests/loop_eval.rs`
//! compares with OpenSubdiv's regular patches.

use glam::DVec3;

/// Exponents `(i, j)` of the 15 quartic monomials `s^i t^j`, `i + j <= 4`.
pub(crate) const MONOMIALS: [(u8, u8); 15] = [
    (0, 0),
    (1, 0),
    (0, 1),
    (2, 0),
    (1, 1),
    (0, 2),
    (3, 0),
    (2, 1),
    (1, 2),
    (0, 3),
    (4, 0),
    (3, 1),
    (2, 2),
    (1, 3),
    (0, 4),
];

/// Lattice coordinates of the 12 support points, in walk order (module docs).
pub(crate) const SUPPORT: [(i32, i32); 12] =
    [(0, 0), (1, 0), (1, 1), (0, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (2, 0), (2, 1), (2, 2), (1, 2)];

/// The six lattice neighbours.
const NEIGHBOURS: [(i32, i32); 6] = [(1, 0), (1, 1), (0, 1), (-1, 0), (-1, -1), (0, -1)];

/// The box spline's basis: `coef[m][k]`, the coefficient of monomial `m` in
/// the basis function of support point `k`.
#[derive(Clone, Debug)]
pub(crate) struct BoxSpline {
    pub(crate) coef: [[f64; 12]; 15],
    /// The same transposed, `12 x 15` row-major: the basis function of each
    /// support point by monomial (the layout [`jet`] reads).
    pub(crate) basis: Vec<f64>,
}

/// A point of a patch and its derivatives in the patch's own `(s, t)`.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Jet {
    pub(crate) p: DVec3,
    pub(crate) ds: DVec3,
    pub(crate) dt: DVec3,
    pub(crate) dss: DVec3,
    pub(crate) dst: DVec3,
    pub(crate) dtt: DVec3,
}

/// A function on a square window of the lattice, zero outside it.
struct Grid {
    lo: i32,
    n: i32,
    vals: Vec<f64>,
}

impl Grid {
    fn new(lo: i32, n: i32) -> Grid {
        Grid { lo, n, vals: vec![0.0; (n * n) as usize] }
    }
    fn get(&self, x: i32, y: i32) -> f64 {
        let (i, j) = (x - self.lo, y - self.lo);
        if (0..self.n).contains(&i) && (0..self.n).contains(&j) { self.vals[(i * self.n + j) as usize] } else { 0.0 }
    }
    fn set(&mut self, x: i32, y: i32, v: f64) {
        let (i, j) = (x - self.lo, y - self.lo);
        self.vals[(i * self.n + j) as usize] = v;
    }
    fn ring_sum(&self, x: i32, y: i32) -> f64 {
        NEIGHBOURS.iter().map(|&(dx, dy)| self.get(x + dx, y + dy)).sum()
    }
    /// One step of regular Loop subdivision on the lattice.
    fn subdivide(&self) -> Grid {
        let mut out = Grid::new(2 * self.lo - 2, 2 * self.n + 4);
        for x in out.lo..out.lo + out.n {
            for y in out.lo..out.lo + out.n {
                let (px, py) = (x.div_euclid(2), y.div_euclid(2));
                let v = match (x.rem_euclid(2), y.rem_euclid(2)) {
                    (0, 0) => 10.0 / 16.0 * self.get(px, py) + self.ring_sum(px, py) / 16.0,
                    d => {
                        // the edge from p to p + d and its two opposite vertices
                        let (o1, o2) = match d {
                            (1, 0) => ((1, 1), (0, -1)),
                            (0, 1) => ((1, 1), (-1, 0)),
                            _ => ((1, 0), (0, 1)),
                        };
                        0.375 * (self.get(px, py) + self.get(px + d.0, py + d.1))
                            + 0.125 * (self.get(px + o1.0, py + o1.1) + self.get(px + o2.0, py + o2.1))
                    }
                };
                out.set(x, y, v);
            }
        }
        out
    }
}

impl BoxSpline {
    /// The basis, derived from Loop's regular rules (module docs).
    pub(crate) fn derive() -> BoxSpline {
        // the 15 level-2 points of the triangle and their (u, v)
        let mut points = Vec::with_capacity(15);
        for x in 0..=4 {
            for y in 0..=x {
                points.push((x, y, f64::from(x - y) / 4.0, f64::from(y) / 4.0));
            }
        }
        let vandermonde: Vec<[f64; 15]> = points.iter().map(|&(_, _, u, v)| monomials(u, v)).collect();
        let mut rhs = vec![[0.0; 12]; 15];
        for (k, &(sx, sy)) in SUPPORT.iter().enumerate() {
            let mut g = Grid::new(-4, 10);
            g.set(sx, sy, 1.0);
            let g = g.subdivide().subdivide();
            for (row, &(x, y, _, _)) in points.iter().enumerate() {
                rhs[row][k] = 0.5 * g.get(x, y) + g.ring_sum(x, y) / 12.0;
            }
        }
        let coef = solve(vandermonde, rhs);
        let basis = (0..12).flat_map(|k| coef.iter().map(move |row| row[k])).collect();
        BoxSpline { coef, basis }
    }
}

/// The 15 monomials at `(s, t)`.
fn monomials(s: f64, t: f64) -> [f64; 15] {
    let mut out = [0.0; 15];
    for (m, &(i, j)) in MONOMIALS.iter().enumerate() {
        out[m] = s.powi(i32::from(i)) * t.powi(i32::from(j));
    }
    out
}

/// The patch whose support point `i` has the basis function with monomial
/// coefficients `basis[15 i .. 15 i + 15]`, over the points `c`, at
/// `(s, t)`; the second derivatives only when `second`.
pub(crate) fn jet(basis: &[f64], c: &[DVec3], s: f64, t: f64, second: bool) -> Jet {
    coefficients(basis, c).jet(s, t, second)
}

/// A patch as a polynomial with vector coefficients, one per monomial of
/// [`MONOMIALS`]: what [`jet`] needs of the support, so that the points of
/// one patch can share it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Poly(pub(crate) [DVec3; 15]);

/// The polynomial of the patch with basis `basis` (as [`jet`]) over the
/// points `c`: each coefficient summed point by point, five monomials at a
/// time so that the sums stay in registers.
pub(crate) fn coefficients(basis: &[f64], c: &[DVec3]) -> Poly {
    let mut q = [DVec3::ZERO; 15];
    for m0 in [0, 5, 10] {
        let mut acc = [DVec3::ZERO; 5];
        for (row, &p) in basis.chunks_exact(15).zip(c) {
            for (a, &w) in acc.iter_mut().zip(&row[m0..m0 + 5]) {
                *a += p * w;
            }
        }
        q[m0..m0 + 5].copy_from_slice(&acc);
    }
    Poly(q)
}

impl Poly {
    /// The point and derivatives at `(s, t)`; the second derivatives only
    /// when `second`. Each derivative sums only the monomials it does not
    /// zero: `d/ds s^i t^j = i s^(i-1) t^j` (order as [`MONOMIALS`]).
    #[inline]
    pub(crate) fn jet(&self, s: f64, t: f64, second: bool) -> Jet {
        let q = &self.0;
        let (s2, t2, st) = (s * s, t * t, s * t);
        let (s3, t3) = (s2 * s, t2 * t);
        let sum = |terms: &[(usize, f64)]| terms.iter().fold(DVec3::ZERO, |acc, &(m, w)| acc + q[m] * w);
        let p = q[0]
            + sum(&[
                (1, s),
                (2, t),
                (3, s2),
                (4, st),
                (5, t2),
                (6, s3),
                (7, s2 * t),
                (8, s * t2),
                (9, t3),
                (10, s2 * s2),
                (11, s3 * t),
                (12, s2 * t2),
                (13, s * t3),
                (14, t2 * t2),
            ]);
        let ds = q[1]
            + sum(&[
                (3, 2.0 * s),
                (4, t),
                (6, 3.0 * s2),
                (7, 2.0 * st),
                (8, t2),
                (10, 4.0 * s3),
                (11, 3.0 * s2 * t),
                (12, 2.0 * s * t2),
                (13, t3),
            ]);
        let dt = q[2]
            + sum(&[
                (4, s),
                (5, 2.0 * t),
                (7, s2),
                (8, 2.0 * st),
                (9, 3.0 * t2),
                (11, s3),
                (12, 2.0 * s2 * t),
                (13, 3.0 * s * t2),
                (14, 4.0 * t3),
            ]);
        let mut jet = Jet { p, ds, dt, ..Jet::default() };
        if second {
            jet.dss = q[3] * 2.0 + sum(&[(6, 6.0 * s), (7, 2.0 * t), (10, 12.0 * s2), (11, 6.0 * st), (12, 2.0 * t2)]);
            jet.dst = q[4] + sum(&[(7, 2.0 * s), (8, 2.0 * t), (11, 3.0 * s2), (12, 4.0 * st), (13, 3.0 * t2)]);
            jet.dtt = q[5] * 2.0 + sum(&[(8, 2.0 * s), (9, 6.0 * t), (12, 2.0 * s2), (13, 6.0 * st), (14, 12.0 * t2)]);
        }
        jet
    }
}

/// Solves `a x = b` (15 x 15, 12 right-hand sides) by Gaussian elimination
/// with partial pivoting; `a` is a fixed, well-conditioned Vandermonde
/// matrix of distinct points, so every pivot is non-zero.
fn solve(mut a: Vec<[f64; 15]>, mut b: Vec<[f64; 12]>) -> [[f64; 12]; 15] {
    let n = 15;
    for col in 0..n {
        let pivot = (col..n).max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs())).unwrap_or(col);
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in 0..n {
            if row != col {
                let f = a[row][col] / a[col][col];
                if f != 0.0 {
                    let (pa, pb) = (a[col], b[col]);
                    a[row].iter_mut().zip(pa).for_each(|(x, p)| *x -= f * p);
                    b[row].iter_mut().zip(pb).for_each(|(x, p)| *x -= f * p);
                }
            }
        }
    }
    let mut x = [[0.0; 12]; 15];
    for row in 0..n {
        for k in 0..12 {
            x[row][k] = b[row][k] / a[row][row];
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lattice_points(f: impl Fn(f64, f64) -> f64) -> Vec<DVec3> {
        // the lattice point (x, y) as a point of the plane z = f(x, y)
        SUPPORT.iter().map(|&(x, y)| DVec3::new(f64::from(x), f64::from(y), f(f64::from(x), f64::from(y)))).collect()
    }

    #[test]
    fn the_basis_is_a_partition_of_unity() {
        let b = BoxSpline::derive();
        for (m, row) in b.coef.iter().enumerate() {
            let sum: f64 = row.iter().sum();
            let want = if m == 0 { 1.0 } else { 0.0 };
            assert!((sum - want).abs() < 1e-12, "monomial {m}: {sum}");
        }
    }

    #[test]
    fn linear_functions_are_reproduced() {
        // a box spline reproduces linear functions exactly (and quadratics
        // up to a constant); on the plane z = 2x - 3y + 1 the patch lies in it
        let b = BoxSpline::derive();
        let pts = lattice_points(|x, y| 2.0 * x - 3.0 * y + 1.0);
        for &(u, v) in &[(0.1, 0.2), (0.7, 0.05), (0.3, 0.3)] {
            let j = jet(&b.basis, &pts, u, v, true);
            let (x, y) = (u + v, v);
            assert!((j.p - DVec3::new(x, y, 2.0 * x - 3.0 * y + 1.0)).length() < 1e-12, "{:?}", j.p);
            // d/du moves along (1, 0), d/dv along (1, 1) on the lattice
            assert!((j.ds - DVec3::new(1.0, 0.0, 2.0)).length() < 1e-12);
            assert!((j.dt - DVec3::new(1.0, 1.0, -1.0)).length() < 1e-12);
            assert!(j.dss.length() < 1e-12 && j.dst.length() < 1e-12 && j.dtt.length() < 1e-12);
        }
    }

    #[test]
    fn quadratics_keep_their_second_derivatives() {
        // Loop reproduces quadratic polynomials up to lower-order terms:
        // the second derivatives of z = x^2 are exact
        let b = BoxSpline::derive();
        let j = jet(&b.basis, &lattice_points(|x, _| x * x), 0.25, 0.4, true);
        // z = (u + v)^2: z_uu = z_uv = z_vv = 2
        assert!((j.dss.z - 2.0).abs() < 1e-12 && (j.dst.z - 2.0).abs() < 1e-12 && (j.dtt.z - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_polynomial_jet_is_its_value_and_its_difference_quotients() {
        // any coefficients: the value against the monomials summed directly,
        // each derivative against central differences of the one below
        let q = Poly(std::array::from_fn(|m| DVec3::new(m as f64 - 7.0, (m * m) as f64 * 0.1, 1.0 / (m as f64 + 1.0))));
        let h = 1e-5;
        for &(s, t) in &[(0.2, 0.3), (0.9, 0.05), (0.0, 0.0), (0.4, 0.6)] {
            let j = q.jet(s, t, true);
            let direct: DVec3 = q.0.iter().zip(monomials(s, t)).map(|(&c, w)| c * w).sum();
            assert!((j.p - direct).length() < 1e-12, "value at ({s}, {t})");
            let at = |s, t| q.jet(s, t, true);
            let close = |a: DVec3, b: DVec3, what: &str| {
                assert!((a - b).length() < 1e-6 * (1.0 + b.length()), "{what} at ({s}, {t}): {a} vs {b}")
            };
            close(j.ds, (at(s + h, t).p - at(s - h, t).p) / (2.0 * h), "ds");
            close(j.dt, (at(s, t + h).p - at(s, t - h).p) / (2.0 * h), "dt");
            close(j.dss, (at(s + h, t).ds - at(s - h, t).ds) / (2.0 * h), "dss");
            close(j.dst, (at(s, t + h).ds - at(s, t - h).ds) / (2.0 * h), "dst");
            close(j.dtt, (at(s, t + h).dt - at(s, t - h).dt) / (2.0 * h), "dtt");
            let first = q.jet(s, t, false);
            assert_eq!((first.p, first.ds, first.dt), (j.p, j.ds, j.dt));
        }
    }

    #[test]
    fn the_corners_are_the_regular_limit_positions() {
        let b = BoxSpline::derive();
        let pts: Vec<DVec3> = (0..12).map(|k| DVec3::new(k as f64, (k * k) as f64 * 0.1, (k % 3) as f64)).collect();
        // c0's limit: 1/2 c0 + 1/12 of its ring (walk entries 1..7)
        let want = pts[0] * 0.5 + pts[1..7].iter().sum::<DVec3>() / 12.0;
        assert!((jet(&b.basis, &pts, 0.0, 0.0, false).p - want).length() < 1e-12);
    }
}
