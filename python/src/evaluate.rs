//! `evaluate`: the exact Loop or Catmull-Clark limit surface at points
//! `(face, u, v)`, the native half of `subdiv.evaluate` (the library's `subdiv eval`).

use crate::arrays::{columns, f64_array, i64_array};
use crate::build::Control;
use crate::guard::run;
use crate::ops::{CreaseArgs, MeshArgs, control, named};
use numpy::{PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use subdiv::Evaluator;

/// Positions `(k, 3)`, unit normals `(k, 3)` and `(H, K)` per point `(k, 2)`
/// (`(0, 2)` unless `curvature`).
type Samples<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<f64>>);

/// The exact limit at control face `face[i]`, parameters `uv[i]`
/// (`points` is `(face, uv)`): Loop on triangles (barycentric),
/// Catmull-Clark on ptex faces (the unit square); `names` are the scheme and options, `creases` as for
/// `subdivide`, `threads` the worker threads (`None`: the shared pool).
///
/// # Errors
/// `SubdivError` for anything the library refuses: a face out of range or
/// at an interior vertex of valence 2, a point outside its face, a scheme
/// without an exact evaluation, a mesh the library does not build.
#[pyfunction]
pub fn evaluate_arrays<'py>(
    py: Python<'py>,
    mesh: MeshArgs<'py>,
    creases: CreaseArgs<'py>,
    names: crate::options::Names,
    points: (PyReadonlyArray1<'py, i64>, PyReadonlyArray2<'py, f64>),
    flags: (bool, bool),
    threads: Option<usize>,
) -> PyResult<Samples<'py>> {
    // second derivatives asked; float64 control points taken as given
    let (curvature, precise) = flags;
    let (face, uv) = points;
    let s = mesh.slices(&creases)?;
    if uv.shape()[1] != 2 || uv.shape()[0] != face.len() {
        return Err(PyTypeError::new_err("uv must have shape (k, 2) with one row per face index"));
    }
    let bad = |_| PyTypeError::new_err("arrays must be C-contiguous and aligned (the Python layer makes them so)");
    let (face, uv) = (face.as_slice().map_err(bad)?, uv.as_slice().map_err(bad)?);
    let (p, n, hk) = run(py, threads, || {
        let Limit { mesh, points64, scheme, opts } = limit_control(&s, &names, precise)?;
        let ev = Evaluator::new_f64(&mesh, &points64, scheme, &opts).map_err(|e| e.to_string())?;
        let mut points = Vec::with_capacity(face.len());
        for (i, (&f, w)) in face.iter().zip(uv.chunks_exact(2)).enumerate() {
            let f = usize::try_from(f).map_err(|_| format!("point {}: face {f} out of range", i + 1))?;
            points.push((f, w[0], w[1]));
        }
        // only the columns asked for are kept (a million points: 48 or 64 MB)
        let err = |e: subdiv::Error| e.to_string();
        Ok(if curvature {
            let out = ev.eval_rows::<8>(&points, true).map_err(err)?;
            (columns(&out, 0, 3), columns(&out, 3, 6), columns(&out, 6, 8))
        } else {
            let out = ev.eval_rows::<6>(&points, false).map_err(err)?;
            (columns(&out, 0, 3), columns(&out, 3, 6), Vec::new())
        })
    })?;
    Ok((f64_array(py, p, 3)?, f64_array(py, n, 3)?, f64_array(py, hk, 2)?))
}

/// What the exact limit is evaluated from: the control mesh as the
/// evaluator takes it (polygons fanned), its points in f64, the scheme and
/// its options.
struct Limit {
    mesh: subdiv::Mesh,
    points64: Vec<glam::DVec3>,
    scheme: subdiv::Scheme,
    opts: subdiv::Options,
}

/// The [`Limit`] of the caller's arrays: float64 vertices as the caller
/// gave them (`precise`), float32 ones as the library rounds them.
fn limit_control(s: &crate::ops::Slices<'_>, names: &crate::options::Names, precise: bool) -> Result<Limit, String> {
    let (scheme, opts) = named(names)?;
    let (c, remap) = control(s, scheme, false)?;
    let mesh = match c {
        Control::Tri(mesh) => mesh,
        Control::Poly(mesh) => mesh.triangulated(),
    };
    let points64 = remap.control_f64(s.vertices(), &mesh.positions, !precise);
    Ok(Limit { mesh, points64, scheme, opts })
}

/// Positions `(k, 3)`, unit normals `(k, 3)`, triangles `(t, 3)`, each
/// vertex's control face `(k, 1)` and `(u, v)` there `(k, 2)`, and the
/// tolerance, the largest distance measured and whether it is met.
type Tessellated<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<i64>>,
    Bound<'py, PyArray2<i64>>,
    Bound<'py, PyArray2<f64>>,
    (f64, f64, bool),
);

/// The limit surface within `tolerance` (`1e-3`: a distance; `1e-4x`: a
/// fraction of the control points' bounding-box diagonal, as the command
/// line reads it) as `subdiv tessellate` makes it; `names`, `creases`,
/// `precise` and `threads` as for [`evaluate_arrays`].
///
/// # Errors
/// `SubdivError` for what the library refuses (a tolerance that is not a
/// positive distance, a scheme without an exact limit, a tessellation over
/// the memory budget, a mesh it does not build).
#[pyfunction]
pub fn tessellate_arrays<'py>(
    py: Python<'py>,
    mesh: MeshArgs<'py>,
    creases: CreaseArgs<'py>,
    names: crate::options::Names,
    tolerance: String,
    precise: bool,
    threads: Option<usize>,
) -> PyResult<Tessellated<'py>> {
    let s = mesh.slices(&creases)?;
    let out = run(py, threads, || {
        let t: subdiv::Tolerance = tolerance.parse().map_err(|e: subdiv::Error| e.to_string())?;
        let Limit { mesh, points64, scheme, opts } = limit_control(&s, &names, precise)?;
        subdiv::tessellate(&mesh, &points64, scheme, &opts, t).map_err(|e| e.to_string())
    })?;
    let flat = |v: &[glam::DVec3]| v.iter().flat_map(|p| p.to_array()).collect::<Vec<f64>>();
    let triangles = out.triangles.iter().flatten().map(|&i| i64::from(i)).collect();
    let face = out.params.iter().map(|p| i64::from(p.0)).collect();
    let uv = out.params.iter().flat_map(|p| [p.1, p.2]).collect();
    let s = out.stats;
    Ok((
        f64_array(py, flat(&out.positions), 3)?,
        f64_array(py, flat(&out.normals), 3)?,
        i64_array(py, triangles, 3)?,
        i64_array(py, face, 1)?,
        f64_array(py, uv, 2)?,
        (s.tolerance, s.measured, s.met),
    ))
}
