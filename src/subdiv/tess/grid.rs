//! One patch's triangles, from its interior rate `n` and the points its
//! sides already have (shared with the neighbours, so any number per side).
//!
//! When every side has `n` equal segments the patch is the regular grid of
//! rate `n` (`n^2` triangles on a triangle, `2 n^2` on a square). Otherwise
//! the grid of rate `n` keeps its inside (the points one step or more from
//! the border: rate `n - 3` on a triangle, `n - 2` on a square; the centre
//! alone when `n` is small) and a ring of triangles joins that inner
//! border to the sides' points, side by side: walking the outer and the
//! inner row of a side together, each step advances the row whose next
//! point comes first along the side, so that every triangle has one edge
//! on one row and its third corner on the other (the stitching of
//! hardware tessellators' outer rings).
//!
//! ```text
//!   side points (any)   o---o-o--o---o
//!                        \  |/ \ |  /
//!   inner row             *-----*--*      grid of rate n inside
//! ```

/// A triangle's corners in `(u, v)`: `c0 c1 c2` of the barycentric point
/// `(1 - u - v) c0 + u c1 + v c2`.
pub(super) const CORNERS_TRI: [(f64, f64); 3] = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)];

/// A ptex face's corners in `(u, v)`.
pub(super) const CORNERS_QUAD: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];

/// A point of a patch: its output vertex and its `(u, v)` on the patch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Pt {
    pub id: u32,
    pub uv: (f64, f64),
}

/// The points a patch adds inside, in the order [`triangulate`] numbers
/// them from its `first` id.
pub(super) fn interior(quad: bool, n: u32, uniform: bool) -> Vec<(f64, f64)> {
    let nf = f64::from(n);
    let mut out = Vec::new();
    if !uniform && n < 3 {
        out.push(if quad { (0.5, 0.5) } else { (1.0 / 3.0, 1.0 / 3.0) });
        return out;
    }
    for j in 1..n {
        for i in 1..n {
            if quad || i + j < n {
                out.push((f64::from(i) / nf, f64::from(j) / nf));
            }
        }
    }
    out
}

/// The fraction of the way from `a` to `b` that `p` lies at.
fn along(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    ((p.0 - a.0) * dx + (p.1 - a.1) * dy) / (dx * dx + dy * dy)
}

/// The triangles of a patch (counter-clockwise in `(u, v)`): `sides[s]`
/// lists side `s`'s points from corner `s` to corner `s + 1`, both
/// included, `n + 1` equally spaced where `uniform`; the inside points are
/// those of [`interior`] (with the same `uniform`), numbered from `first`.
pub(super) fn triangulate(
    quad: bool,
    (n, uniform): (u32, bool),
    sides: &[Vec<Pt>],
    first: u32,
    out: &mut Vec<[Pt; 3]>,
) {
    let inside = interior(quad, n, uniform);
    let lattice = Lattice { quad, n, first, sides, uniform };
    if uniform {
        lattice.cells(0, n, out);
        return;
    }
    if n < 3 {
        let centre = Pt { id: first, uv: inside[0] };
        for pts in sides {
            zip(pts, &[centre], out);
        }
        return;
    }
    lattice.cells(1, n - 1, out);
    for (s, pts) in sides.iter().enumerate() {
        zip(pts, &lattice.inner_row(s), out);
    }
}

/// The grid of rate `n` over a patch, and where its points come from.
struct Lattice<'a> {
    quad: bool,
    n: u32,
    first: u32,
    sides: &'a [Vec<Pt>],
    uniform: bool,
}

impl Lattice<'_> {
    /// Grid point `(i, j)`: a side's point on the border of a uniform
    /// patch, else an inside point.
    fn at(&self, i: u32, j: u32) -> Pt {
        let n = self.n;
        let uv = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
        if self.uniform {
            let side = |s: usize, k: u32| self.sides[s][k as usize];
            if j == 0 {
                return side(0, i);
            }
            if self.quad {
                match (i, j) {
                    (i, _) if i == n => return side(1, j),
                    (_, j) if j == n => return side(2, n - i),
                    (0, _) => return side(3, n - j),
                    _ => {}
                }
            } else if i + j == n {
                return side(1, j);
            } else if i == 0 {
                return side(2, n - j);
            }
        }
        // inside points are listed row by row, i and j from 1 (`interior`)
        let row = |j: u32| if self.quad { (j - 1) * (n - 1) } else { (j - 1) * (2 * n - j - 2) / 2 };
        Pt { id: self.first + row(j) + (i - 1), uv }
    }

    /// The cells of the grid with both indices in `lo..=hi` (the triangle's
    /// sum at most `hi` too), two triangles each.
    fn cells(&self, lo: u32, hi: u32, out: &mut Vec<[Pt; 3]>) {
        for j in lo..hi {
            for i in lo..hi {
                if !self.quad && i + j >= hi {
                    continue;
                }
                let (a, b, d) = (self.at(i, j), self.at(i + 1, j), self.at(i, j + 1));
                if self.quad {
                    let c = self.at(i + 1, j + 1);
                    out.push([a, b, c]);
                    out.push([a, c, d]);
                    continue;
                }
                out.push([a, b, d]);
                if i + j + 1 < hi {
                    out.push([b, self.at(i + 1, j + 1), d]);
                }
            }
        }
    }

    /// The inner row facing side `s`, from the inner corner at corner `s`
    /// to the one at corner `s + 1` (for `n >= 3`).
    fn inner_row(&self, s: usize) -> Vec<Pt> {
        let n = self.n;
        let m = if self.quad { n - 1 } else { n - 2 };
        (1..=m)
            .map(|k| {
                let r = m + 1 - k; // k counts up from the corner, r down
                let (i, j) = match (self.quad, s) {
                    (_, 0) => (k, 1),
                    (true, 1) => (n - 1, k),
                    (true, 2) => (r, n - 1),
                    (true, _) => (1, r),
                    (false, 1) => (n - 1 - k, k),
                    (false, _) => (1, r),
                };
                self.at(i, j)
            })
            .collect()
    }
}

/// The ring between a side's points `outer` and the inner row `inner`
/// (both in the side's direction; `inner` may be one point): the points of
/// both rows are taken in the order of their projections on the side.
fn zip(outer: &[Pt], inner: &[Pt], out: &mut Vec<[Pt; 3]>) {
    let (p, q) = (outer.len() - 1, inner.len() - 1);
    let (oa, ob) = (outer[0].uv, outer[p].uv);
    let t_out = |i: usize| along(oa, ob, outer[i].uv);
    let t_in = |j: usize| along(oa, ob, inner[j].uv);
    let (mut i, mut j) = (0, 0);
    while i < p || j < q {
        let next_out = if i < p { t_out(i + 1) } else { f64::INFINITY };
        let next_in = if j < q { t_in(j + 1) } else { f64::INFINITY };
        if next_out <= next_in {
            out.push([outer[i], outer[i + 1], inner[j]]);
            i += 1;
        } else {
            out.push([outer[i], inner[j + 1], inner[j]]);
            j += 1;
        }
    }
}
