//! `subdivide`, the stencil plan behind `matrix`, and `limit`: the native
//! halves of the Python functions (the Python layer shapes the arrays).

use crate::arrays::{self, f64_array, i64_array};
use crate::build::{self, Control, Remap, Request};
use crate::guard::{Msg, msg, run};
use crate::options;
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use subdiv::eval::{loop_limit_normals, loop_limit_positions_f64, loop_limit_positions_with};
use subdiv::rules::ControlCounts;
use subdiv::rules::PlanF64;
use subdiv::rules::with_boundary_corners;
use subdiv::{Mesh, Options, Scheme, Surface};

/// The mesh as the Python layer passes it: vertices `(n, 3)` float64,
/// flat corners and face offsets (int64), all C-contiguous.
#[derive(FromPyObject)]
pub struct MeshArgs<'py>(
    pub PyReadonlyArray2<'py, f64>,
    pub PyReadonlyArray1<'py, i64>,
    pub PyReadonlyArray1<'py, i64>,
);

/// Creases and holes: flat edge vertex pairs (int64), their sharpness
/// (float64), and the faces that are holes (int64, the caller's face ids).
#[derive(FromPyObject)]
pub struct CreaseArgs<'py>(PyReadonlyArray1<'py, i64>, PyReadonlyArray1<'py, f64>, PyReadonlyArray1<'py, i64>);

/// Flat views of the arrays (no GIL needed to read them).
pub struct Slices<'a> {
    vertices: &'a [f64],
    corners: &'a [i64],
    starts: &'a [i64],
    crease_edges: &'a [i64],
    crease_sharpness: &'a [f64],
    holes: &'a [i64],
}

impl Slices<'_> {
    /// The vertices, flat `(x, y, z)` rows as the caller passed them.
    pub fn vertices(&self) -> &[f64] {
        self.vertices
    }
}

impl<'py> MeshArgs<'py> {
    /// The arrays' data, with the creases `c`.
    ///
    /// # Errors
    /// `TypeError` for vertices not `(n, 3)` or arrays not C-contiguous and aligned
    /// (the Python layer passes neither; a direct caller might).
    pub fn slices<'a>(&'a self, c: &'a CreaseArgs<'py>) -> PyResult<Slices<'a>> {
        if self.0.shape()[1] != 3 {
            return Err(PyTypeError::new_err("vertices must have shape (n, 3)"));
        }
        let bad = |_| PyTypeError::new_err("arrays must be C-contiguous and aligned (the Python layer makes them so)");
        Ok(Slices {
            vertices: self.0.as_slice().map_err(bad)?,
            corners: self.1.as_slice().map_err(bad)?,
            starts: self.2.as_slice().map_err(bad)?,
            crease_edges: c.0.as_slice().map_err(bad)?,
            crease_sharpness: c.1.as_slice().map_err(bad)?,
            holes: c.2.as_slice().map_err(bad)?,
        })
    }
}

/// The checked, validated control mesh of `s` for `scheme`.
pub fn control(s: &Slices<'_>, scheme: Scheme, repair: bool) -> Result<(Control, Remap), Msg> {
    let positions = arrays::positions(s.vertices)?;
    let nv = positions.len();
    let faces = arrays::faces(s.corners, s.starts, nv)?;
    let creases = arrays::creases(s.crease_edges, s.crease_sharpness, nv)?;
    let holes = arrays::holes(s.holes, faces.len())?;
    build::control(Request { positions, faces: &faces, scheme, repair, tags: (&creases, &holes) })
}

pub use options::named;

/// Two arrays: float64 points and a second array of `T` (faces, normals).
type Pair<'py, T> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<T>>);

/// Refined vertices (flat, caller's numbering), faces (flat) and their size.
type Refined = (Vec<f64>, Vec<i64>, usize);

/// `subdiv.subdivide`'s work: `(V2, F2)`.
///
/// # Errors
/// `SubdivError` for anything the library refuses.
#[pyfunction]
pub fn subdivide_arrays<'py>(
    py: Python<'py>,
    mesh: MeshArgs<'py>,
    creases: CreaseArgs<'py>,
    names: options::Names,
    levels: u32,
    flags: (bool, bool),
    threads: Option<usize>,
) -> PyResult<Pair<'py, i64>> {
    // repair the mesh; compute in f64 (float64 in) or f32
    let (repair, precise) = flags;
    let s = mesh.slices(&creases)?;
    let (v, f, k) = run(py, threads, || {
        let (scheme, opts) = named(&names)?;
        let (c, remap) = control(&s, scheme, repair)?;
        refine(&c, &remap, (scheme, levels, &opts), s.vertices, precise.then_some(repair))
    })?;
    Ok((f64_array(py, v, 3)?, i64_array(py, f, k)?))
}

/// Subdivides the control mesh and renumbers the result: one library call
/// ([`subdiv::subdivide_model_as`]) that takes the faces alone wherever they
/// do (the last level skips its adjacency tables and writes the caller's
/// int64 ids itself), in f32 or, `f64`, from the caller's float64 rows by
/// the same rules' f64 weights.
fn refine(
    c: &Control,
    remap: &Remap,
    (scheme, levels, opts): (Scheme, u32, &Options),
    input: &[f64],
    f64: Option<bool>,
) -> Result<Refined, Msg> {
    // the arrays refused before the library allocates them (a control
    // mesh's polygons in f32 are counted once made)
    match c {
        Control::Tri(mesh) => check_predicted(remap, ControlCounts::of(&mesh.ct), (scheme, levels), 3)?,
        Control::Poly(mesh) if levels > 0 || f64.is_some() => {
            check_predicted(remap, ControlCounts::of_poly(&mesh.pt), (scheme, levels), 4)?
        }
        Control::Poly(_) => {}
    }
    // `f64`: whether the mesh was repaired (its points then its own)
    let precise = f64.map(|repaired| match c {
        Control::Tri(mesh) => remap.control_f64(input, &mesh.positions, repaired),
        Control::Poly(mesh) => remap.control_f64(input, &mesh.positions, repaired),
    });
    let control = match c {
        Control::Tri(mesh) => subdiv::Control::Triangles(mesh),
        Control::Poly(mesh) => subdiv::Control::Polygons(mesh),
    };
    let none = subdiv::mesh::Attributes::default();
    let model = subdiv::Model { control, attrs: &none, precise: precise.as_deref() };
    let dest = subdiv::Destination { faces: subdiv::FacesOnly::Always, ..Default::default() };
    let how = subdiv::Refinement { scheme, levels, opts: *opts, f64: f64.is_some(), dest };
    let fine = subdiv::subdivide_model_as(&model, &how, |j| remap.id(j)).map_err(msg)?;
    hand_over(remap, fine, input)
}

/// [`check_output`] for the arrays `levels` levels of `scheme` will make
/// from a control mesh of `counts`, faces of `sides` corners, before the
/// library allocates them.
fn check_predicted(
    remap: &Remap,
    counts: ControlCounts,
    (scheme, levels): (Scheme, u32),
    sides: u64,
) -> Result<(), Msg> {
    let corners = counts.faces_at(scheme, levels).saturating_mul(sides);
    check_output(remap, counts.vertices_at(scheme, levels), corners)
}

/// The refined surface `fine` as the caller gets it: flat float64
/// positions in its numbering, its int64 corners (the faces alone as they
/// are; a table's faces that are no holes renumbered), the face size.
fn hand_over(remap: &Remap, fine: subdiv::Subdivided<i64>, input: &[f64]) -> Result<Refined, Msg> {
    let pos = fine.positions_f64;
    match fine.surface {
        Surface::Faces(f) => {
            let v = remap.positions(&f.positions, input);
            drop_later(f.positions);
            Ok((v, f.corners, f.sides))
        }
        Surface::FacesF64(f) => {
            let v = remap.positions(&f.positions, input);
            drop_later(f.positions);
            Ok((v, f.corners, f.sides))
        }
        Surface::Polygons(fine) => {
            let k = face_size(&fine.pt)?;
            let v = match &pos {
                Some(pos) => remap.positions(pos, input),
                None => {
                    check_output(remap, fine.positions.len() as u64, fine.pt.num_corners() as u64)?;
                    remap.positions(&fine.positions, input)
                }
            };
            let f = build::face_ids(remap, fine.pt.v_table(), k, fine.pt.holes());
            drop_later(fine);
            Ok((v, f, k))
        }
        Surface::Triangles(fine) => {
            let v = match &pos {
                Some(pos) => remap.positions(pos, input),
                None => remap.positions(&fine.positions, input),
            };
            let f = build::face_ids(remap, fine.ct.v_table(), 3, fine.ct.holes());
            drop_later(fine);
            Ok((v, f, 3))
        }
    }
}

/// Refuses output arrays (float64 points, int64 corners) larger than the
/// memory the library may use, before allocating them: the library checked
/// its own tables, these come on top.
///
/// # Errors
/// The bytes needed and available.
pub fn check_output(remap: &Remap, points: u64, corners: u64) -> Result<(), Msg> {
    let rows = points.saturating_add(remap.n_input as u64);
    let bytes = rows.saturating_mul(24).saturating_add(corners.saturating_mul(8));
    match subdiv::mem::default_memory_limit() {
        Some(limit) if bytes > limit => {
            Err(format!("the output arrays need {bytes} bytes, more than the {limit} bytes of memory available"))
        }
        _ => Ok(()),
    }
}

/// Frees `value` on another thread: unmapping the hundreds of megabytes of a
/// fine level's tables need not delay the caller.
fn drop_later<T: Send + 'static>(value: T) {
    // without a thread the closure, and the value with it, is dropped here
    let _ = std::thread::Builder::new().name("subdiv-free".into()).spawn(move || drop(value));
}

/// The size of every face of `pt`, when they all have one.
pub(crate) fn face_size(pt: &subdiv::mesh::PolyTable) -> Result<usize, Msg> {
    let k = pt.face_size(0) as usize;
    if (0..pt.num_faces() as u32).all(|f| pt.face_size(f) as usize == k) {
        Ok(k)
    } else {
        Err("the faces have different sizes: at levels=0 a mixed polygon mesh is no (m, k) array; ask for levels >= 1"
            .into())
    }
}

/// One level of a stencil plan: `(n_in, copies_vertices, offsets, indices, weights)`.
type PyLevel<'py> = (usize, bool, Bound<'py, PyArray1<u32>>, Bound<'py, PyArray1<u32>>, Bound<'py, PyArray1<f64>>);

/// Bytes a vertex of `subdiv.matrix`'s control mesh may cost before the
/// plan (positions, renumbering, the matrix's identity rows).
const MATRIX_BYTES_PER_VERTEX: u64 = 64;

/// `subdiv.matrix`'s work: the plan's levels (CSR rows, coarse to fine),
/// the finest faces in the caller's numbering, the kept vertices (`None`:
/// all) and the number of control vertices; on `threads` worker threads
/// (`None`: the shared pool).
///
/// # Errors
/// `SubdivError` for anything the library refuses, or for `n_vertices`
/// past the memory available.
#[pyfunction]
#[allow(clippy::type_complexity)]
pub fn plan_levels<'py>(
    py: Python<'py>,
    faces: (PyReadonlyArray1<'py, i64>, PyReadonlyArray1<'py, i64>),
    n_vertices: u64,
    creases: CreaseArgs<'py>,
    names: options::Names,
    levels: u32,
    threads: Option<usize>,
) -> PyResult<(Vec<PyLevel<'py>>, Bound<'py, PyArray2<i64>>, Option<Bound<'py, PyArray1<u32>>>, usize)> {
    let limit = subdiv::mem::default_memory_limit().unwrap_or(u64::MAX);
    if n_vertices >= u64::from(u32::MAX) || n_vertices.saturating_mul(MATRIX_BYTES_PER_VERTEX) > limit {
        return Err(crate::guard::SubdivError::new_err(format!(
            "n_vertices={n_vertices}: more vertices than fit in memory ({limit} bytes available)"
        )));
    }
    let zeros = numpy::PyArray2::<f64>::zeros(py, [n_vertices as usize, 3], false).readonly();
    let mesh = MeshArgs(zeros, faces.0, faces.1);
    let s = mesh.slices(&creases)?;
    let (plan, faces, k, remap) = run(py, threads, || {
        let (scheme, opts) = named(&names)?;
        let (c, remap) = control(&s, scheme, false)?;
        let (plan, faces, k) = plan_of(&c, &remap, scheme, levels, &opts)?;
        Ok((plan, faces, k, remap))
    })?;
    let lv = plan
        .levels
        .into_iter()
        .map(|l| {
            (
                l.n_in,
                l.copy_vertices,
                l.offsets.into_pyarray(py),
                l.indices.into_pyarray(py),
                l.weights.into_pyarray(py),
            )
        })
        .collect();
    Ok((lv, i64_array(py, faces, k)?, remap.kept.map(|k| k.into_pyarray(py)), remap.n_input))
}

/// The stencil plan of `c` in f64 (the rules' own weights, so a row sums
/// to one within rounding of f64) and its finest faces (caller's
/// numbering, face size).
fn plan_of(
    c: &Control,
    remap: &Remap,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<(PlanF64, Vec<i64>, usize), Msg> {
    let ct = match c {
        Control::Tri(m) => m.ct.clone(),
        Control::Poly(m) => m.pt.triangulated(),
    };
    let plan = subdiv::rules::plan_f64(&ct, scheme, levels, opts).map_err(msg)?;
    let (faces, k) = match (c, plan.poly.as_ref()) {
        (Control::Poly(m), _) if levels == 0 => {
            let k = face_size(&m.pt)?;
            (build::face_ids(remap, m.pt.v_table(), k, m.pt.holes()), k)
        }
        (Control::Poly(_), Some(pt)) => (build::face_ids(remap, pt.v_table(), 4, pt.holes()), 4),
        (Control::Poly(_), None) => return Err("a polygon plan without polygons (a bug)".into()),
        (Control::Tri(_), _) => (build::face_ids(remap, plan.ct.v_table(), 3, plan.ct.holes()), 3),
    };
    Ok((plan, faces, k))
}

/// `subdiv.limit`'s work: Loop limit positions and unit normals of every
/// vertex (a vertex no face uses keeps its position, normal zero), on
/// `threads` worker threads (`None`: the shared pool).
///
/// # Errors
/// `SubdivError` for anything the library refuses.
#[pyfunction]
pub fn limit_arrays<'py>(
    py: Python<'py>,
    mesh: MeshArgs<'py>,
    creases: CreaseArgs<'py>,
    names: (String, String),
    precise: bool,
    threads: Option<usize>,
) -> PyResult<Pair<'py, f64>> {
    let s = mesh.slices(&creases)?;
    let (p, n) = run(py, threads, || {
        let opts = options::options(&names.0, &names.1)?;
        let (c, remap) = control(&s, Scheme::Loop, false)?;
        let Control::Tri(mesh) = c else { return Err("Loop built a polygon table (a bug)".into()) };
        let mesh = Mesh { ct: with_boundary_corners(&mesh.ct, opts.boundary).into_owned(), positions: mesh.positions };
        let normals = loop_limit_normals(&mesh);
        let zeros = vec![0.0; 3 * remap.n_input];
        // float64 vertices: the limit of the caller's own rows, in f64
        let positions = match precise {
            true => {
                let control = remap.control_f64(s.vertices, &mesh.positions, false);
                remap.positions(&loop_limit_positions_f64(&mesh, &control, opts.loop_beta), s.vertices)
            }
            false => remap.positions(&loop_limit_positions_with(&mesh, opts.loop_beta), s.vertices),
        };
        Ok((positions, remap.positions(&normals, &zeros)))
    })?;
    Ok((f64_array(py, p, 3)?, f64_array(py, n, 3)?))
}

impl<'py> CreaseArgs<'py> {
    /// No creases.
    pub fn empty(py: Python<'py>) -> CreaseArgs<'py> {
        let e = PyArray1::<i64>::zeros(py, 0, false).readonly();
        let s = PyArray1::<f64>::zeros(py, 0, false).readonly();
        let h = PyArray1::<i64>::zeros(py, 0, false).readonly();
        CreaseArgs(e, s, h)
    }
}
