//! `subdiv.Refiner`'s native half: a control mesh refined once, its
//! control vertices moved and its edges creased as often as wanted, only
//! what an edit reaches evaluated again (the library's [`subdiv::Refiner`]).
//! Float32 positions come from the refiner's own levels; float64 ones are
//! the caller's float64 control rows refined with the f64 weights.

use crate::arrays::{f64_array, i64_array};
use crate::build::{Control, Remap};
use crate::guard::{Msg, msg, run};
use crate::ops::{CreaseArgs, MeshArgs, control, face_size, named};
use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;

/// A refined control mesh that can be edited.
#[pyclass(module = "subdiv._subdiv")]
pub struct NativeRefiner {
    inner: subdiv::Refiner,
    remap: Remap,
    /// The caller's rows (flat float64), kept up to date with the moves:
    /// what a float64 refinement reads and the unused vertices' rows.
    input: Vec<f64>,
    /// Faces of the finest level (caller's ids, flat) and their size.
    faces: (Vec<i64>, usize),
    /// The caller's rows each step changed (`None`: a sharpness step),
    /// done and undone, beside the library's history.
    rows: (Vec<Option<Rows>>, Vec<Option<Rows>>),
}

/// Rows of the caller's vertices a move changed: ids, before, after.
type Rows = (Vec<usize>, Vec<[f64; 3]>, Vec<[f64; 3]>);

impl NativeRefiner {
    /// The library's id of the caller's vertex `i`.
    fn library_id(&self, i: i64) -> Result<u32, Msg> {
        let n = self.remap.n_input;
        let i = u32::try_from(i)
            .ok()
            .filter(|&i| (i as usize) < n)
            .ok_or_else(|| format!("vertex {i} is not one of the {n} vertices"))?;
        self.remap.inverse()(i).ok_or_else(|| format!("vertex {i} is in no face: moving it changes no surface"))
    }

    /// The finest positions, float64 rows in the caller's numbering.
    fn positions(&self, precise: bool) -> Result<Vec<f64>, Msg> {
        if !precise {
            return Ok(self.remap.positions(self.inner.positions(), &self.input));
        }
        let control: Vec<f64> = self
            .remap
            .control_f64(&self.input, self.inner.control(), false)
            .iter()
            .flat_map(|p| p.to_array())
            .collect();
        let fine = self.inner.refine(&control, 3).map_err(msg)?;
        let points: Vec<glam::DVec3> = fine.chunks_exact(3).map(glam::DVec3::from_slice).collect();
        Ok(self.remap.positions(&points, &self.input))
    }
}

#[pymethods]
impl NativeRefiner {
    /// Builds the refiner: `mesh` and `creases` as for `subdivide`, `names`
    /// the scheme, beta and boundary.
    #[new]
    fn new(
        py: Python<'_>,
        mesh: MeshArgs<'_>,
        creases: CreaseArgs<'_>,
        names: (String, String, String),
        levels: u32,
    ) -> PyResult<Self> {
        let s = mesh.slices(&creases)?;
        let input = s.vertices().to_vec();
        run(py, None, || {
            let (scheme, opts) = named(&names)?;
            let (c, remap) = control(&s, scheme, false)?;
            let mesh = match c {
                Control::Tri(mesh) => mesh,
                Control::Poly(mesh) => mesh.triangulated(),
            };
            let inner = subdiv::Refiner::new(&mesh, scheme, levels, &opts).map_err(msg)?;
            let faces = match inner.polygons() {
                Some(pt) => (remap.ids(pt.v_table()), face_size(pt)?),
                None => (remap.ids(inner.topology().v_table()), 3),
            };
            Ok(NativeRefiner { inner, remap, input, faces, rows: (Vec::new(), Vec::new()) })
        })
    }

    /// The finest level's vertices `(n2, 3)`; `precise`: refined in float64.
    fn vertices<'py>(&self, py: Python<'py>, precise: bool) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let v = self.positions(precise).map_err(|e| crate::guard::error(&e))?;
        f64_array(py, v, 3)
    }

    /// The finest level's faces `(m2, 3)` or `(m2, 4)`.
    fn faces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        i64_array(py, self.faces.0.clone(), self.faces.1)
    }

    /// Moves the caller's vertices `ids` to the rows of `to` `(k, 3)`;
    /// returns how many finest vertices changed.
    fn move_vertices(&mut self, ids: PyReadonlyArray1<'_, i64>, to: PyReadonlyArray2<'_, f64>) -> PyResult<usize> {
        let bad = |_| PyTypeError::new_err("arrays must be C-contiguous (the Python layer makes them so)");
        let (ids, to) = (ids.as_slice().map_err(bad)?, to.as_slice().map_err(bad)?);
        if to.len() != 3 * ids.len() {
            return Err(PyTypeError::new_err("positions must have shape (k, 3), one row per id"));
        }
        let err = |e: Msg| crate::guard::error(&e);
        let lib: Vec<u32> = ids.iter().map(|&i| self.library_id(i)).collect::<Result<_, _>>().map_err(err)?;
        let points = crate::arrays::positions(to).map_err(err)?;
        let changed = self.inner.move_vertices(&lib, &points).map_err(|e| err(msg(e)))?;
        let ids: Vec<usize> = ids.iter().map(|&i| i as usize).collect();
        let row = |i: usize, v: &[f64]| [v[3 * i], v[3 * i + 1], v[3 * i + 2]];
        let before = ids.iter().map(|&i| row(i, &self.input)).collect();
        let after: Vec<[f64; 3]> = to.chunks_exact(3).map(|r| [r[0], r[1], r[2]]).collect();
        self.put(&ids, &after);
        self.rows.0.push(Some((ids, before, after)));
        self.rows.1.clear();
        Ok(changed)
    }

    /// Sets the sharpness of the edge between the caller's vertices `a`
    /// and `b` (0 smooth, 10 or more infinitely sharp).
    fn set_sharpness(&mut self, a: i64, b: i64, sharpness: f64) -> PyResult<()> {
        let err = |e: Msg| crate::guard::error(&e);
        let (a, b) = (self.library_id(a).map_err(err)?, self.library_id(b).map_err(err)?);
        self.inner.set_edge_sharpness(a, b, sharpness as f32).map_err(|e| err(msg(e)))?;
        self.rows.0.push(None);
        self.rows.1.clear();
        Ok(())
    }

    /// Undoes the last edit; whether there was one. The caller's rows
    /// follow the control points back.
    fn undo(&mut self) -> bool {
        let Some(step) = self.rows.0.pop().filter(|_| self.inner.undo()) else { return false };
        if let Some((ids, before, _)) = &step {
            self.put(ids, before);
        }
        self.rows.1.push(step);
        true
    }

    /// Redoes the last undone edit; whether there was one.
    fn redo(&mut self) -> bool {
        let Some(step) = self.rows.1.pop().filter(|_| self.inner.redo()) else { return false };
        if let Some((ids, _, after)) = &step {
            self.put(ids, after);
        }
        self.rows.0.push(step);
        true
    }

    /// The finest vertices control vertex `i` influences (caller's ids).
    fn support<'py>(&mut self, py: Python<'py>, i: i64) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let v = self.library_id(i).map_err(|e| crate::guard::error(&e))?;
        let rows = self.inner.support(v);
        Ok(PyArray1::from_vec(py, self.remap.ids(&rows)))
    }
}

impl NativeRefiner {
    /// Writes the caller's rows `ids`.
    fn put(&mut self, ids: &[usize], rows: &[[f64; 3]]) {
        for (&i, r) in ids.iter().zip(rows) {
            self.input[3 * i..3 * i + 3].copy_from_slice(r);
        }
    }
}
