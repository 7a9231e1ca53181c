//! Checking what Python passed (flat views of numpy arrays the Python layer
//! has already shaped) and making the arrays given back.

use crate::guard::Msg;
use glam::Vec3;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use rayon::prelude::*;

/// Faces as flat corner lists: face `f` is `corners[starts[f]..starts[f + 1]]`.
#[derive(Clone, Debug, Default)]
pub struct Faces {
    /// Where each face starts, then the number of corners.
    pub starts: Vec<u32>,
    /// Vertex ids, face after face.
    pub corners: Vec<u32>,
}

impl Faces {
    /// Number of faces.
    pub fn len(&self) -> usize {
        self.starts.len().saturating_sub(1)
    }
    /// Whether every face is a triangle.
    pub fn all_triangles(&self) -> bool {
        self.corners.len() == 3 * self.len()
    }
}

/// Most corners an input may have (the library's ids are 32-bit, and its
/// refinement multiplies them).
const MAX_CORNERS: usize = (u32::MAX / 8) as usize;

/// The positions of `flat` (`x y z` per vertex), refusing NaN, infinite
/// and single-precision-overflowing coordinates (the library computes in
/// `f32`).
///
/// # Errors
/// Naming the first bad vertex.
pub fn positions(flat: &[f64]) -> Result<Vec<Vec3>, Msg> {
    if !flat.len().is_multiple_of(3) {
        return Err(format!("vertices must have 3 coordinates each, got {} numbers", flat.len()));
    }
    if flat.len() / 3 >= u32::MAX as usize {
        return Err(format!("{} vertices: more than 32-bit vertex ids allow", flat.len() / 3));
    }
    let mut out = Vec::with_capacity(flat.len() / 3);
    for (i, p) in flat.chunks_exact(3).enumerate() {
        if p.iter().any(|x| !x.is_finite()) {
            return Err(format!("vertex {i} has a non-finite coordinate (NaN or infinity)"));
        }
        if p.iter().any(|x| x.abs() > f64::from(f32::MAX)) {
            return Err(format!(
                "vertex {i} has a coordinate beyond single precision ({:e})",
                p.iter().fold(0.0f64, |m, x| m.max(x.abs()))
            ));
        }
        out.push(Vec3::new(p[0] as f32, p[1] as f32, p[2] as f32));
    }
    Ok(out)
}

/// The faces `corners[starts[f]..starts[f + 1]]` on `nv` vertices, every
/// index checked: not negative, below `nv`.
///
/// # Errors
/// Naming the first bad face and index, or bad `starts`.
pub fn faces(corners: &[i64], starts: &[i64], nv: usize) -> Result<Faces, Msg> {
    if corners.len() > MAX_CORNERS {
        return Err(format!("{} face corners: more than the library's 32-bit ids allow", corners.len()));
    }
    let ok = starts.first() == Some(&0)
        && starts.last() == Some(&(corners.len() as i64))
        && starts.windows(2).all(|w| w[0] <= w[1]);
    if !ok {
        return Err("face offsets must rise from 0 to the number of corners".into());
    }
    let mut out = Faces { starts: Vec::with_capacity(starts.len()), corners: Vec::with_capacity(corners.len()) };
    out.starts.extend(starts.iter().map(|&s| s as u32));
    for f in 0..starts.len() - 1 {
        for &i in &corners[starts[f] as usize..starts[f + 1] as usize] {
            if i < 0 {
                return Err(format!("face {f} uses the negative vertex index {i}"));
            }
            if i as u64 >= nv as u64 {
                return Err(format!("face {f} uses vertex index {i}, but there are only {nv} vertices"));
            }
            out.corners.push(i as u32);
        }
    }
    Ok(out)
}

/// Creases as `(v0, v1, sharpness)`, from `edges` (2 ids each) and
/// `sharpness` on `nv` vertices.
///
/// # Errors
/// A bad index or sharpness, or lengths that differ.
pub fn creases(edges: &[i64], sharpness: &[f64], nv: usize) -> Result<Vec<(u32, u32, f32)>, Msg> {
    if edges.len() != 2 * sharpness.len() {
        return Err(format!("{} crease edges but {} sharpness values", edges.len() / 2, sharpness.len()));
    }
    let mut out = Vec::with_capacity(sharpness.len());
    for (k, (e, &s)) in edges.chunks_exact(2).zip(sharpness).enumerate() {
        if e.iter().any(|&i| i < 0 || i as u64 >= nv as u64) {
            return Err(format!("crease {k} names vertex ({}, {}), but there are {nv} vertices", e[0], e[1]));
        }
        let s = subdiv::mesh::checked_sharpness(s).map_err(|e| format!("crease {k} has {e}"))?;
        out.push((e[0] as u32, e[1] as u32, s));
    }
    Ok(out)
}

/// The faces `ids` of `m` faces, the holes: each checked in range.
///
/// # Errors
/// The first id out of range.
pub fn holes(ids: &[i64], m: usize) -> Result<Vec<u32>, Msg> {
    ids.iter()
        .enumerate()
        .map(|(k, &f)| match u32::try_from(f) {
            Ok(f) if (f as usize) < m => Ok(f),
            _ => Err(format!("hole {k} names face {f}, but there are {m} faces")),
        })
        .collect()
}

/// A `(rows, cols)` float64 array owning `flat`.
///
/// # Errors
/// When `flat` does not hold `rows * cols` values (a bug).
pub fn f64_array(py: Python<'_>, flat: Vec<f64>, cols: usize) -> PyResult<Bound<'_, PyArray2<f64>>> {
    let rows = flat.len().checked_div(cols).unwrap_or(0);
    let a =
        Array2::from_shape_vec((rows, cols), flat).map_err(|e| crate::guard::SubdivError::new_err(e.to_string()))?;
    Ok(a.into_pyarray(py))
}

/// A `(rows, cols)` int64 array owning `flat`.
///
/// # Errors
/// When `flat` does not hold `rows * cols` values (a bug).
pub fn i64_array(py: Python<'_>, flat: Vec<i64>, cols: usize) -> PyResult<Bound<'_, PyArray2<i64>>> {
    let rows = flat.len().checked_div(cols).unwrap_or(0);
    let a =
        Array2::from_shape_vec((rows, cols), flat).map_err(|e| crate::guard::SubdivError::new_err(e.to_string()))?;
    Ok(a.into_pyarray(py))
}

/// Elements converted per task of the parallel conversions.
const CHUNK: usize = 1 << 16;

/// `points` as flat float64 `x y z` values (converted in parallel into
/// memory from the library's allocator, pre-faulted: the output of a
/// large subdivision is tens of megabytes of fresh pages).
pub fn flat_f64<P: Point>(points: &[P]) -> Vec<f64> {
    let mut out = subdiv::mem::zeroed::<f64>(points.len() * 3);
    out.par_chunks_mut(3 * CHUNK).zip(points.par_chunks(CHUNK)).for_each(|(o, p)| {
        for (o, p) in o.chunks_exact_mut(3).zip(p) {
            o.copy_from_slice(&p.xyz());
        }
    });
    out
}

/// A refined point handed to Python: computed in f32 or in f64.
pub trait Point: Copy + Send + Sync {
    /// The coordinates in f64 (exact).
    fn xyz(self) -> [f64; 3];
}

impl Point for Vec3 {
    fn xyz(self) -> [f64; 3] {
        self.as_dvec3().to_array()
    }
}

impl Point for glam::DVec3 {
    fn xyz(self) -> [f64; 3] {
        self.to_array()
    }
}

/// Columns `a..b` of `rows`, flat (row by row), copied in parallel as
/// [`flat_f64`] converts.
pub fn columns<const N: usize>(rows: &[[f64; N]], a: usize, b: usize) -> Vec<f64> {
    let k = b - a;
    let mut out = subdiv::mem::zeroed::<f64>(rows.len() * k);
    out.par_chunks_mut(k * CHUNK).zip(rows.par_chunks(CHUNK)).for_each(|(o, r)| {
        for (o, r) in o.chunks_exact_mut(k).zip(r) {
            o.copy_from_slice(&r[a..b]);
        }
    });
    out
}

/// `ids` as int64, each through `f` (in parallel, as [`flat_f64`]).
pub fn ids_i64(ids: &[u32], f: impl Fn(u32) -> i64 + Sync) -> Vec<i64> {
    let mut out = subdiv::mem::zeroed::<i64>(ids.len());
    out.par_chunks_mut(CHUNK).zip(ids.par_chunks(CHUNK)).for_each(|(o, i)| {
        for (o, &i) in o.iter_mut().zip(i) {
            *o = f(i);
        }
    });
    out
}
