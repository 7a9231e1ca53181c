//! Bezier curves and bicubic tensor-product patches by de Casteljau's
//! algorithm, and the CS184 `.bzc` / `.bez` files (docs/schemes.md §10).
//!
//! ```text
//! de Casteljau, degree n, control points P_0 .. P_n, parameter t:
//!     P_i^(0) = P_i
//!     P_i^(r) = (1 - t) P_i^(r-1) + t P_{i+1}^(r-1),   r = 1..n, i = 0..n-r
//!     C(t) = P_0^(n)          (= sum_i binom(n, i) (1-t)^(n-i) t^i P_i, Bernstein form)
//!     cubic, t = 1/2: C = (P0 + 3 P1 + 3 P2 + P3) / 8
//! bicubic patch, control points P[i][j] (row i, column j), u along a row:
//!     S(u, v) = de Casteljau at v of the four points Q_i = de Casteljau at u of row i
//!     (either order gives the same point); S(0,0) = P[0][0], S(1,0) = P[0][3],
//!     S(0,1) = P[3][0], S(1,1) = P[3][3]
//! ```
//! Files (docs/schemes.md §10.3; jirehcwe/p2-mesh-editor `bez/teapot.bez`):
//! * `.bzc`: a count `n`, then `n` points `x y`.
//! * `.bez`: a count `N` of patches, then per patch 16 points `x y z`, row by
//!   row (4 lines of 4 points in the files we know; read as a token stream).
//!
//! Both are parsed as whitespace-separated tokens; a `#` starts a comment to
//! the end of the line (not in the CS184 files, allowed so that bundled files
//! can name their source). Every error names the file and line; counts are
//! checked against the tokens present before anything is allocated; nothing
//! panics on garbage.
//!
//! Tessellation: each patch is sampled on an `(n+1) x (n+1)` grid in `(u, v)`,
//! each grid square cut into two triangles `(i,j) (i+1,j) (i+1,j+1)` and
//! `(i,j) (i+1,j+1) (i,j+1)` (`i` along `u`), so faces are counter-clockwise
//! about `S_u x S_v`. Patch boundaries are welded: points closer than
//! `1e-6 x` the bounding-box diagonal become one vertex (exactly equal points
//! always do). Triangles that become degenerate by welding (the teapot's lid
//! and bottom patches have a row of coincident control points) are dropped.

use super::raw::RawMesh;
use super::{Format, Input, Keeps};
use crate::{Error, MeshError, Result};
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::ops::{Add, Mul};

/// One level of de Casteljau: the `len - 1` points `(1 - t) P_i + t P_{i+1}`
/// (what CS184's `evaluateStep` shows as the intermediate polygon).
pub fn de_casteljau_step<T: Copy + Add<Output = T> + Mul<f32, Output = T>>(points: &[T], t: f32) -> Vec<T> {
    points.windows(2).map(|w| w[0] * (1.0 - t) + w[1] * t).collect()
}

/// The point at `t` of the Bezier curve with control points `points`
/// (de Casteljau; `None` for no points).
pub fn de_casteljau<T: Copy + Add<Output = T> + Mul<f32, Output = T>>(points: &[T], t: f32) -> Option<T> {
    let mut work = points.to_vec();
    for len in (1..work.len()).rev() {
        for i in 0..len {
            work[i] = work[i] * (1.0 - t) + work[i + 1] * t;
        }
    }
    work.first().copied()
}

/// `segments + 1` points of the curve at `t = k / segments` (at least one
/// segment; empty for no control points).
pub fn curve_polyline(points: &[Vec2], segments: usize) -> Vec<Vec2> {
    let s = segments.max(1);
    (0..=s).filter_map(|k| de_casteljau(points, k as f32 / s as f32)).collect()
}

/// The de Casteljau construction at `t`: the segments of the intermediate
/// polygons `P^(1) .. P^(n-1)` (each segment as two consecutive points, in
/// level order), and the curve point `C(t) = P_0^(n)` (`None` for no points).
/// A curve of `n + 1` control points gives `n (n - 1) / 2` segments.
pub(crate) fn de_casteljau_construction(points: &[Vec2], t: f32) -> (Vec<Vec2>, Option<Vec2>) {
    let mut level = points.to_vec();
    let mut segments = Vec::new();
    while level.len() > 1 {
        level = de_casteljau_step(&level, t);
        for w in level.windows(2) {
            segments.extend_from_slice(w);
        }
    }
    (segments, level.first().copied())
}

/// A bicubic tensor-product Bezier patch: `p[i][j]`, row `i` (along `v`),
/// column `j` (along `u`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Patch {
    /// Control points, row by row as in the file.
    pub p: [[Vec3; 4]; 4],
}

impl Patch {
    /// `S(u, v)`: de Casteljau at `u` along each row, then at `v` on the four results.
    pub fn eval(&self, u: f32, v: f32) -> Vec3 {
        let q = self.p.map(|row| cubic(row, u));
        cubic(q, v)
    }
    /// `S(u, v)` the other way round: at `v` down each column first, then at `u`.
    pub fn eval_columns_first(&self, u: f32, v: f32) -> Vec3 {
        let cols: [Vec3; 4] =
            std::array::from_fn(|j| cubic([self.p[0][j], self.p[1][j], self.p[2][j], self.p[3][j]], v));
        cubic(cols, u)
    }
}

/// De Casteljau on exactly four points.
fn cubic(p: [Vec3; 4], t: f32) -> Vec3 {
    let s = 1.0 - t;
    let a = [p[0] * s + p[1] * t, p[1] * s + p[2] * t, p[2] * s + p[3] * t];
    let b = [a[0] * s + a[1] * t, a[1] * s + a[2] * t];
    b[0] * s + b[1] * t
}

/// Whitespace tokens with their 1-based line numbers; `#` comments skipped.
struct Tokens<'a> {
    toks: Vec<(&'a str, usize)>,
    pos: usize,
    file: &'a str,
    last_line: usize,
}

impl<'a> Tokens<'a> {
    fn new(text: &'a str, file: &'a str) -> Self {
        let mut toks = Vec::new();
        for (i, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or("");
            toks.extend(line.split_whitespace().map(|t| (t, i + 1)));
        }
        let last_line = text.lines().count().max(1);
        Tokens { toks, pos: 0, file, last_line }
    }
    fn remaining(&self) -> usize {
        self.toks.len() - self.pos
    }
    fn err(&self, line: usize, msg: String) -> Error {
        Error::Parse { file: self.file.to_string(), line, msg }
    }
    fn next(&mut self, what: &str) -> Result<(&'a str, usize)> {
        let t = self
            .toks
            .get(self.pos)
            .copied()
            .ok_or_else(|| self.err(self.last_line, format!("unexpected end of file: expected {what}")))?;
        self.pos += 1;
        Ok(t)
    }
    fn count(&mut self, what: &str) -> Result<(usize, usize)> {
        let (t, line) = self.next(what)?;
        let n = t
            .parse::<usize>()
            .map_err(|_| self.err(line, format!("expected {what} (an integer >= 0), found '{t}'")))?;
        Ok((n, line))
    }
    fn float(&mut self, what: &str) -> Result<f32> {
        let (t, line) = self.next(what)?;
        match t.parse::<f32>() {
            Ok(x) if x.is_finite() => Ok(x),
            Ok(_) => Err(self.err(line, format!("{what} is not a finite number: '{t}'"))),
            Err(_) => Err(self.err(line, format!("expected {what} (a number), found '{t}'"))),
        }
    }
    fn finish(&self) -> Result<()> {
        match self.toks.get(self.pos) {
            Some(&(t, line)) => Err(self.err(line, format!("unexpected data after the last control point: '{t}'"))),
            None => Ok(()),
        }
    }
}

/// Parses a `.bzc` curve: the control points. `file` names the source in errors.
///
/// # Errors
/// [`Error::Parse`] with the line: a bad or missing count, a count larger than
/// the points present, a non-number or non-finite coordinate, trailing data.
pub fn parse_bzc(text: &str, file: &str) -> Result<Vec<Vec2>> {
    let mut tk = Tokens::new(text, file);
    let (n, line) = tk.count("the number of control points")?;
    if n == 0 || n > tk.remaining() / 2 {
        let msg = format!("the file declares {n} control points but holds {} coordinate pairs", tk.remaining() / 2);
        return Err(tk.err(line, msg));
    }
    let mut pts = Vec::with_capacity(n);
    for i in 0..n {
        let x = tk.float(&format!("x of control point {}", i + 1))?;
        let y = tk.float(&format!("y of control point {}", i + 1))?;
        pts.push(Vec2::new(x, y));
    }
    tk.finish()?;
    Ok(pts)
}

/// Parses a `.bez` file into its patches. `file` names the source in errors.
///
/// # Errors
/// [`Error::Parse`] with the line, as [`parse_bzc`].
pub fn parse_bez(text: &str, file: &str) -> Result<Vec<Patch>> {
    let mut tk = Tokens::new(text, file);
    let (n, line) = tk.count("the number of patches")?;
    if n == 0 || n > tk.remaining() / 48 {
        let msg = format!("the file declares {n} patches but holds coordinates for {}", tk.remaining() / 48);
        return Err(tk.err(line, msg));
    }
    let mut patches = Vec::with_capacity(n);
    for k in 0..n {
        let mut p = [[Vec3::ZERO; 4]; 4];
        for (i, row) in p.iter_mut().enumerate() {
            for (j, q) in row.iter_mut().enumerate() {
                let what = |c: &str| format!("{c} of control point ({i}, {j}) of patch {}", k + 1);
                *q = Vec3::new(tk.float(&what("x"))?, tk.float(&what("y"))?, tk.float(&what("z"))?);
            }
        }
        patches.push(Patch { p });
    }
    tk.finish()?;
    Ok(patches)
}

/// The `.bez` row of [`super::FORMATS`]: patches tessellated
/// [`BEZ_RESOLUTION`] times a side.
pub const BEZ_FORMAT: Format = Format {
    name: "Bezier patches",
    extensions: &["bez"],
    sniff: |_| false,
    reader: Some(read_bez),
    writer: None,
    written_as: &[],
    poly_writer: None,
    faces_writer: None,
    keeps: Keeps { uv: false, colors: false, materials: false, creases: false, holes: false },
};

/// The `.bzc` row of [`super::FORMATS`]: a curve, not a mesh (the viewer
/// and `info` read it with [`parse_bzc`]).
pub const BZC_FORMAT: Format = Format {
    name: "a Bezier curve (.bzc)",
    extensions: &["bzc"],
    sniff: |_| false,
    reader: None,
    writer: None,
    written_as: &[],
    poly_writer: None,
    faces_writer: None,
    keeps: Keeps { uv: false, colors: false, materials: false, creases: false, holes: false },
};

/// Samples per patch side when a `.bez` file is opened as a mesh.
pub const BEZ_RESOLUTION: u32 = 8;

/// Reads a `.bez` file as its tessellation.
///
/// # Errors
/// Parse errors with the line; over the budget.
fn read_bez(input: &Input) -> Result<RawMesh> {
    let patches = parse_bez(input.text()?, input.file)?;
    let n = u64::from(BEZ_RESOLUTION);
    let count = patches.len() as u64;
    input.budget.take_vertices(count * (n + 1) * (n + 1), input.file, "patches")?;
    input.budget.take_faces(count * 2 * n * n, input.file, "patches")?;
    tessellate_raw(&patches, BEZ_RESOLUTION).map_err(|source| Error::Mesh {
        file: input.file.to_string(),
        line: None,
        source,
    })
}

/// Tessellates `patches` at `n` segments per patch side (at least 1) and
/// welds shared boundary points (see the module docs); no validation.
///
/// # Errors
/// [`MeshError::Empty`] for no patches; [`MeshError::TooManyElements`] when
/// the grid does not fit 32-bit ids.
pub fn tessellate_raw(patches: &[Patch], n: u32) -> Result<RawMesh, MeshError> {
    if patches.is_empty() {
        return Err(MeshError::Empty);
    }
    let n = n.max(1) as usize;
    let too_many = || MeshError::TooManyElements { what: format!("{} patches at {n} segments a side", patches.len()) };
    let fits = |x: Option<usize>| x.filter(|&t| t < u32::MAX as usize / 8).ok_or_else(too_many);
    let per = fits((n + 1).checked_mul(n + 1))?;
    let total = fits(per.checked_mul(patches.len()))?;
    let tri_total = fits(n.checked_mul(2 * n).and_then(|t| t.checked_mul(patches.len())))?;
    let mut pts = Vec::with_capacity(total);
    for patch in patches {
        for j in 0..=n {
            for i in 0..=n {
                pts.push(patch.eval(i as f32 / n as f32, j as f32 / n as f32));
            }
        }
    }
    let (positions, remap) = weld(&pts);
    let mut triangles = Vec::with_capacity(3 * tri_total);
    for k in 0..patches.len() {
        let id = |i: usize, j: usize| remap[k * per + j * (n + 1) + i];
        for j in 0..n {
            for i in 0..n {
                for tri in [[id(i, j), id(i + 1, j), id(i + 1, j + 1)], [id(i, j), id(i + 1, j + 1), id(i, j + 1)]] {
                    if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
                        triangles.extend_from_slice(&tri);
                    }
                }
            }
        }
    }
    Ok(RawMesh::from_triangles(positions, triangles))
}

/// Merges points within `1e-6 x` the bounding-box diagonal (exactly equal
/// points always): returns the kept positions (first occurrence) and the new
/// id of every input point. A hash grid of cell size = the tolerance, each
/// point compared with the representatives in its 27 neighbouring cells.
fn weld(pts: &[Vec3]) -> (Vec<Vec3>, Vec<u32>) {
    let (lo, hi) = pts.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), &q| (a.min(q), b.max(q)));
    let eps = (1e-6 * (hi - lo).length()).max(f32::MIN_POSITIVE);
    let cell = |q: Vec3| ((q - lo) / eps).floor().as_i64vec3();
    let mut grid: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    let mut kept: Vec<Vec3> = Vec::new();
    let mut remap = Vec::with_capacity(pts.len());
    for &q in pts {
        let c = cell(q);
        let mut found = None;
        'search: for dz in -1..=1 {
            for dy in -1..=1 {
                for dx in -1..=1 {
                    if let Some(ids) = grid.get(&[c.x + dx, c.y + dy, c.z + dz])
                        && let Some(&k) = ids.iter().find(|&&k| kept[k as usize].distance(q) <= eps)
                    {
                        found = Some(k);
                        break 'search;
                    }
                }
            }
        }
        let id = found.unwrap_or_else(|| {
            let k = kept.len() as u32;
            kept.push(q);
            grid.entry(c.to_array()).or_default().push(k);
            k
        });
        remap.push(id);
    }
    (kept, remap)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubic_midpoint_is_one_three_three_one() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::ONE];
        let want = (p[0] + 3.0 * p[1] + 3.0 * p[2] + p[3]) / 8.0;
        assert!(cubic(p, 0.5).abs_diff_eq(want, 1e-7));
        assert!(de_casteljau(&p, 0.5).unwrap().abs_diff_eq(want, 1e-7));
        assert_eq!(de_casteljau_step(&p, 0.5).len(), 3);
        assert_eq!(de_casteljau::<Vec3>(&[], 0.5), None);
    }

    #[test]
    fn parse_errors_name_the_line() {
        let e = parse_bzc("2\n0 0\n1 x\n", "c.bzc").unwrap_err().to_string();
        assert!(e.starts_with("c.bzc:3:"), "{e}");
        let e = parse_bzc("3\n0 0\n1 1\n", "c.bzc").unwrap_err().to_string();
        assert!(e.starts_with("c.bzc:1:"), "{e}");
        let e = parse_bez("99999999999999\n", "t.bez").unwrap_err().to_string();
        assert!(e.starts_with("t.bez:1:"), "{e}");
        assert!(parse_bez("", "t.bez").is_err());
        assert!(parse_bzc("-1 0 0", "c.bzc").is_err());
    }
}
