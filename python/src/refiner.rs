//! `subdiv.Refiner`'s native half: a control mesh refined once, its
//! control vertices moved and its edges creased as often as wanted, only
//! what an edit reaches evaluated again (the library's [`subdiv::Refiner`]),
//! every edit with the GIL released.
//!
//! The refined vertices are a read-only numpy view that the edits update
//! in place, in the input's precision: float32 input shows the refiner's
//! own f32 points, float64 input the f64 points the refiner keeps beside
//! them (the caller's rows refined with the rules' f64 weights, updated
//! where each edit reaches). Where the library keeps every vertex the
//! caller passed (the renumbering is the identity) the view is the
//! refiner's own memory; where it dropped vertices no face uses, the view
//! is a copy in the caller's numbering held here, of which each edit
//! writes only the rows it changed. An edit returns those rows.

use crate::arrays::i64_array;
use crate::build::{Control, Remap, face_ids};
use crate::guard::{Msg, error, msg, pool, run_on};
use crate::ops::{CreaseArgs, MeshArgs, control, face_size};
use crate::options::{Names, named};
use glam::DVec3;
use numpy::ndarray::ArrayView2;
use numpy::{Element, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::sync::Arc;

/// The finest points in the caller's numbering, where the library
/// renumbers (flat `x y z` rows, allocated once, never reassigned).
enum Mirror {
    /// The renumbering is the identity: the view is the refiner's memory.
    None,
    /// Float32 input.
    F32(Box<[f32]>),
    /// Float64 input.
    F64(Box<[f64]>),
}

/// A refined control mesh that can be edited.
#[pyclass(module = "subdiv._subdiv")]
pub struct NativeRefiner {
    /// Never replaced after `new` (the views point into it).
    inner: subdiv::Refiner,
    remap: Remap,
    /// The library's id of each caller's vertex (`u32::MAX`: in no face),
    /// where the library renumbers.
    to_library: Option<Vec<u32>>,
    /// Float64 input: the refiner keeps f64 points, the view shows them.
    precise: bool,
    /// Never reassigned after `new` (the views point into it).
    mirror: Mirror,
    /// Corners of a finest face (3, or 4 for the polygon schemes).
    sides: usize,
    /// The pool the construction and every edit run on (`None`: the
    /// shared pool).
    pool: Option<Arc<rayon::ThreadPool>>,
}

impl NativeRefiner {
    /// The library's id of the caller's vertex `i`.
    fn library_id(&self, i: i64) -> Result<u32, Msg> {
        let n = self.remap.n_input;
        let i = u32::try_from(i)
            .ok()
            .filter(|&i| (i as usize) < n)
            .ok_or_else(|| format!("vertex {i} is not one of the {n} vertices"))?;
        match &self.to_library {
            None => Ok(i),
            Some(map) => Some(map[i as usize])
                .filter(|&j| j != u32::MAX)
                .ok_or_else(|| format!("vertex {i} is in no face: moving it changes no surface")),
        }
    }

    /// After an edit: the rows it changed, in the caller's numbering, and
    /// those rows of the mirror written.
    fn follow(&mut self) -> Vec<i64> {
        let NativeRefiner { inner, remap, mirror, .. } = self;
        let rows = inner.last_changed();
        match mirror {
            Mirror::None => {}
            Mirror::F32(m) => {
                let p = inner.positions();
                for &j in rows {
                    let i = remap.id(j) as usize;
                    m[3 * i..3 * i + 3].copy_from_slice(&p[j as usize].to_array());
                }
            }
            Mirror::F64(m) => {
                let p = inner.positions_f64().unwrap_or(&[]);
                for &j in rows {
                    let i = remap.id(j) as usize;
                    m[3 * i..3 * i + 3].copy_from_slice(&p[j as usize].to_array());
                }
            }
        }
        remap.ids(rows)
    }

    /// The mirror of `inner`'s finest points, where `remap` renumbers;
    /// the vertices no face uses carried from `input` (flat, float64).
    fn mirror(inner: &subdiv::Refiner, remap: &Remap, input: &[f64], precise: bool) -> Mirror {
        if remap.kept.is_none() {
            return Mirror::None;
        }
        match inner.positions_f64().filter(|_| precise) {
            Some(fine) => Mirror::F64(remap.positions(fine, input).into_boxed_slice()),
            // float32 input: its rows are exact in f32
            None => Mirror::F32(remap.positions(inner.positions(), input).iter().map(|&x| x as f32).collect()),
        }
    }
}

/// A read-only numpy array `(n, 3)` over `flat`, its base `owner`.
///
/// # Safety
/// `flat` must stay allocated and in place, and must not be written
/// through a path that numpy does not see as a write by the owner's
/// methods, for as long as `owner` lives (the array keeps it alive).
unsafe fn view<'py, T: Element>(flat: &[T], owner: Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let py = owner.py();
    let a = ArrayView2::from_shape((flat.len() / 3, 3), flat).map_err(|e| error(&e.to_string()))?;
    // SAFETY: this function's contract: the memory outlives `owner`, which
    // the array holds as its base.
    let array = unsafe { PyArray2::borrow_from_array(&a, owner) };
    let flags = PyDict::new(py);
    flags.set_item("write", false)?;
    // read-only, for good: its base exposes no writable buffer, so numpy
    // refuses to make it writeable again
    array.call_method("setflags", (), Some(&flags))?;
    Ok(array.into_any())
}

#[pymethods]
impl NativeRefiner {
    /// Builds the refiner: `mesh` and `creases` as for `subdivide`, `names`
    /// the scheme and options; `precise`: float64 input (the refiner
    /// keeps f64 points); `threads` the worker threads of the construction
    /// and of every edit (`None`: the shared pool). What the first edit
    /// would build is built now.
    #[new]
    fn new(
        py: Python<'_>,
        mesh: MeshArgs<'_>,
        creases: CreaseArgs<'_>,
        names: Names,
        levels: u32,
        precise: bool,
        threads: Option<usize>,
    ) -> PyResult<Self> {
        let s = mesh.slices(&creases)?;
        let pool = pool(threads)?.map(Arc::new);
        run_on(py, pool.clone().as_deref(), || {
            let (scheme, opts) = named(&names)?;
            let (c, remap) = control(&s, scheme, false)?;
            let mesh = match c {
                Control::Tri(mesh) => mesh,
                Control::Poly(mesh) => mesh.triangulated(),
            };
            let mut inner = subdiv::Refiner::new(&mesh, scheme, levels, &opts).map_err(msg)?;
            let sides = match inner.polygons() {
                Some(pt) => face_size(pt)?,
                None => 3,
            };
            // the first edit then costs what later ones do
            inner.prepare_edits();
            if precise {
                let control = remap.control_f64(s.vertices(), inner.control(), false);
                inner.set_control_f64(&control).map_err(msg)?;
            }
            let to_library = remap.kept.as_ref().map(|_| {
                let inverse = remap.inverse();
                (0..remap.n_input as u32).map(|i| inverse(i).unwrap_or(u32::MAX)).collect()
            });
            let mirror = Self::mirror(&inner, &remap, s.vertices(), precise);
            Ok(NativeRefiner { inner, remap, to_library, precise, mirror, sides, pool })
        })
    }

    /// The finest level's vertices `(n2, 3)`, in the input's precision: a
    /// read-only view that every edit updates in place (no copy).
    fn vertices(slf: Bound<'_, Self>) -> PyResult<Bound<'_, PyAny>> {
        let this = slf.borrow();
        let owner = slf.clone().into_any();
        // SAFETY: the memory viewed is this object's: its `mirror` (a
        // boxed slice never reassigned after `new`) or its refiner's finest
        // points (`inner` is never replaced, and the library keeps them in
        // one buffer for the refiner's life, rebuilds included:
        // `Refiner::positions`, `Refiner::positions_f64`). So it stays
        // allocated and in place while this object lives, which the view
        // keeps alive as its base. Only the edits (methods of this object)
        // write it, in place, as a numpy array is written in place.
        unsafe {
            match (&this.mirror, this.inner.positions_f64().filter(|_| this.precise)) {
                (Mirror::F32(m), _) => view(m, owner),
                (Mirror::F64(m), _) => view(m, owner),
                (Mirror::None, Some(fine)) => view(bytemuck::cast_slice::<DVec3, f64>(fine), owner),
                (Mirror::None, None) => view(bytemuck::cast_slice::<glam::Vec3, f32>(this.inner.positions()), owner),
            }
        }
    }

    /// The finest level's faces `(m2, 3)` or `(m2, 4)`, holes left out.
    fn faces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        let f = run_on(py, self.pool.clone().as_deref(), || {
            Ok(match self.inner.polygons() {
                Some(pt) => face_ids(&self.remap, pt.v_table(), self.sides, pt.holes()),
                None => {
                    let ct = self.inner.topology();
                    face_ids(&self.remap, ct.v_table(), 3, ct.holes())
                }
            })
        })?;
        i64_array(py, f, self.sides)
    }

    /// Moves the caller's vertices `ids` to the rows of `to` `(k, 3)`;
    /// returns the finest rows that changed (caller's numbering).
    fn move_vertices<'py>(
        &mut self,
        py: Python<'py>,
        ids: PyReadonlyArray1<'py, i64>,
        to: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let bad = |_| PyTypeError::new_err("arrays must be C-contiguous and aligned (the Python layer makes them so)");
        let (ids, to) = (ids.as_slice().map_err(bad)?, to.as_slice().map_err(bad)?);
        if to.len() != 3 * ids.len() {
            return Err(PyTypeError::new_err("positions must have shape (k, 3), one row per id"));
        }
        let rows = run_on(py, self.pool.clone().as_deref(), || {
            let lib: Vec<u32> = ids.iter().map(|&i| self.library_id(i)).collect::<Result<_, _>>()?;
            let points = crate::arrays::positions(to)?;
            if self.precise {
                let wide: Vec<DVec3> = to.chunks_exact(3).map(DVec3::from_slice).collect();
                self.inner.move_vertices_f64(&lib, &wide).map_err(msg)?;
            } else {
                self.inner.move_vertices(&lib, &points).map_err(msg)?;
            }
            Ok(self.follow())
        })?;
        Ok(PyArray1::from_vec(py, rows))
    }

    /// Sets the sharpness of the edge between the caller's vertices `a`
    /// and `b` (0 smooth, 10 or more infinitely sharp); returns the finest
    /// rows that changed.
    fn set_sharpness<'py>(
        &mut self,
        py: Python<'py>,
        a: i64,
        b: i64,
        sharpness: f64,
    ) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let s = subdiv::mesh::checked_sharpness(sharpness).map_err(|e| error(&format!("edge {a}-{b} has {e}")))?;
        let rows = run_on(py, self.pool.clone().as_deref(), || {
            let (la, lb) = (self.library_id(a)?, self.library_id(b)?);
            // the library names its own ids
            let caller = |e: subdiv::Error| msg(e).replace(&format!("{la}-{lb}"), &format!("{a}-{b}"));
            self.inner.set_edge_sharpness(la, lb, s).map_err(caller)?;
            Ok(self.follow())
        })?;
        Ok(PyArray1::from_vec(py, rows))
    }

    /// Undoes the last edit; whether there was one.
    fn undo(&mut self, py: Python<'_>) -> PyResult<bool> {
        run_on(py, self.pool.clone().as_deref(), || {
            let done = self.inner.undo();
            if done {
                self.follow();
            }
            Ok(done)
        })
    }

    /// Redoes the last undone edit; whether there was one.
    fn redo(&mut self, py: Python<'_>) -> PyResult<bool> {
        run_on(py, self.pool.clone().as_deref(), || {
            let done = self.inner.redo();
            if done {
                self.follow();
            }
            Ok(done)
        })
    }

    /// The finest vertices control vertex `i` influences (caller's ids).
    fn support<'py>(&mut self, py: Python<'py>, i: i64) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let rows = run_on(py, self.pool.clone().as_deref(), || {
            let v = self.library_id(i)?;
            Ok(self.remap.ids(&self.inner.support(v)))
        })?;
        Ok(PyArray1::from_vec(py, rows))
    }
}
