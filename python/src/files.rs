//! `subdiv.load` and `subdiv.save`: every format the command line reads,
//! through the library's one reading pipeline and its budget.

use crate::arrays::{self, f64_array, i64_array};
use crate::guard::{Msg, msg, run};
use crate::ops::MeshArgs;
use glam::Vec2;
use numpy::PyArray2;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use std::path::PathBuf;
use subdiv::Mesh;
use subdiv::Scheme;
use subdiv::io;
use subdiv::io::{ReadOptions, Source, Topology};
use subdiv::mesh::PolyMesh;
use subdiv::mesh::{Attributes, FileScheme, ShapeOptions};

/// What a file held, flat: vertices, triangles, per-corner texture
/// coordinates, per-vertex colours, the polygons (corners, offsets) when
/// the file's faces were not all triangles, and the options it states.
type Read = (Vec<f64>, Vec<i64>, Option<Vec<f64>>, Option<Vec<f64>>, Option<(Vec<i64>, Vec<i64>)>, Named, Prims);

/// A stage's prims: path, the options it states, its triangles (ids of the
/// faces returned) and its local-to-world transform (row-major rows of
/// column vectors, 16 values).
type Prims = Vec<(String, Named, Vec<i64>, Vec<f64>)>;

/// Options by the names Python's functions take (`scheme`, `boundary`,
/// `fvar`, `triangles`, `creasing`) and the library's names of their values.
type Named = Vec<(&'static str, &'static str)>;

/// The options a file states, by name (only those it states).
fn named_options(o: &ShapeOptions) -> Named {
    let scheme = o.scheme.map(|s| match s {
        FileScheme::CatmullClark => Scheme::CatmullClark.name(),
        FileScheme::Loop => Scheme::Loop.name(),
        FileScheme::Bilinear => Scheme::Bilinear.name(),
        FileScheme::None => "none",
    });
    [
        ("scheme", scheme),
        ("boundary", o.boundary.map(|b| b.name())),
        ("fvar", o.fvar.map(|f| f.name())),
        ("triangles", o.triangles.map(|t| t.name())),
        ("creasing", o.creasing.map(|c| c.name())),
    ]
    .into_iter()
    .filter_map(|(k, v)| v.map(|v| (k, v)))
    .collect()
}

/// The arrays a file holds: `(vertices, faces, uv, colors, polygons,
/// options)`, `uv` `(3m, 2)` (one per triangle corner), `colors` `(n, 3)`,
/// `polygons` `(corners (c, 1), offsets (m + 1, 1))` or `None`, `options`
/// `(name, value)` pairs, `prims` a stage's `(path, options, triangles,
/// transform)`; `repair` mends a non-manifold mesh instead of refusing it;
/// `time` is the time code a stage's sampled points are read at; `threads`
/// the worker threads (`None`: the shared pool).
///
/// # Errors
/// `SubdivError` with the reader's message (file, line or element, problem).
#[pyfunction]
#[allow(clippy::type_complexity)]
pub fn load_file(
    py: Python<'_>,
    path: PathBuf,
    repair: bool,
    time: Option<f64>,
    threads: Option<usize>,
) -> PyResult<(
    Bound<'_, PyArray2<f64>>,
    Bound<'_, PyArray2<i64>>,
    Option<Bound<'_, PyArray2<f64>>>,
    Option<Bound<'_, PyArray2<f64>>>,
    Option<(Bound<'_, PyArray2<i64>>, Bound<'_, PyArray2<i64>>)>,
    Named,
    Prims,
)> {
    if time.is_some_and(|t| !t.is_finite()) {
        return Err(crate::guard::error("time must be a finite time code"));
    }
    let (v, f, uv, colors, polys, options, prims) = run(py, threads, || read(&path, repair, time))?;
    let uv = uv.map(|u| f64_array(py, u, 2)).transpose()?;
    let colors = colors.map(|c| f64_array(py, c, 3)).transpose()?;
    let polys = match polys {
        Some((c, s)) => Some((i64_array(py, c, 1)?, i64_array(py, s, 1)?)),
        None => None,
    };
    Ok((f64_array(py, v, 3)?, i64_array(py, f, 3)?, uv, colors, polys, options, prims))
}

/// Reads `path` with the default budget, attributes included (dropped by
/// a repair, which renumbers).
fn read(path: &std::path::Path, repair: bool, time: Option<f64>) -> Result<Read, Msg> {
    let topology = if repair { Topology::Repair } else { Topology::Refuse };
    let opts = ReadOptions { topology, time, ..ReadOptions::default() };
    let loaded = io::read(Source::File(path), &opts).map_err(msg)?;
    let mesh = &loaded.mesh;
    let prims = prims(&loaded.attributes);
    let Attributes { uv, colors, options, .. } = loaded.attributes;
    let uv = uv.map(|u| u.iter().flat_map(|p: &Vec2| [f64::from(p.x), f64::from(p.y)]).collect());
    let colors = colors.map(|c| arrays::flat_f64(&c));
    let polys = PolyMesh::is_polygonal(mesh).then(|| {
        let pm = PolyMesh::from_mesh(mesh);
        let corners = pm.pt.v_table().iter().map(|&v| i64::from(v)).collect();
        let mut starts: Vec<i64> =
            (0..pm.pt.num_faces() as u32).map(|f| i64::from(pm.pt.face_corners(f).start)).collect();
        starts.push(pm.pt.num_corners() as i64);
        (corners, starts)
    });
    let faces = mesh.triangles().iter().map(|&v| i64::from(v)).collect();
    Ok((arrays::flat_f64(&mesh.positions), faces, uv, colors, polys, named_options(&options), prims))
}

/// The prims of a stage's scene, each with its own options and triangles.
fn prims(attrs: &Attributes) -> Prims {
    let (Some(scene), Some(m)) = (attrs.scene(), attrs.materials.as_ref()) else { return Vec::new() };
    let mut out: Prims = scene
        .prims
        .iter()
        .map(|p| {
            // glam's column-major array is the row-major rows of column vectors' transpose
            let t = glam::DMat4::from_cols_array(&p.transform).transpose().to_cols_array().to_vec();
            (p.path.clone(), named_options(&p.options), Vec::new(), t)
        })
        .collect();
    for (t, &g) in m.face.iter().enumerate() {
        if let Some(prim) = scene.prim_of.get(g as usize).and_then(|&k| out.get_mut(k as usize)) {
            prim.2.push(t as i64);
        }
    }
    out
}

/// Writes the mesh to `path`, the format chosen by the extension; faces
/// that are not all triangles are written as polygons where the format
/// keeps them; `threads` as for [`load_file`].
///
/// # Errors
/// `SubdivError` for a mesh the library refuses, an unknown extension or
/// an I/O error.
#[pyfunction]
pub fn save_file(py: Python<'_>, path: PathBuf, mesh: MeshArgs<'_>, threads: Option<usize>) -> PyResult<()> {
    let MeshArgs(v, c, s) = &mesh;
    let bad = |_| PyTypeError::new_err("arrays must be C-contiguous and aligned");
    let (v, c, s) = (v.as_slice().map_err(bad)?, c.as_slice().map_err(bad)?, s.as_slice().map_err(bad)?);
    run(py, threads, || write(&path, v, c, s))
}

fn write(path: &std::path::Path, v: &[f64], c: &[i64], s: &[i64]) -> Result<(), Msg> {
    let positions = arrays::positions(v)?;
    let faces = arrays::faces(c, s, positions.len())?;
    if faces.all_triangles() {
        let mesh = Mesh::from_triangles(positions, &faces.corners).map_err(msg)?;
        io::save(path, &mesh).map_err(msg)
    } else {
        let (pm, _) = PolyMesh::from_faces(positions, &faces.starts, &faces.corners).map_err(msg)?;
        io::save_with(path, &pm, &Attributes::default()).map_err(msg)
    }
}

/// The option names of [`subdivide_file`]: scheme, beta, boundary, fvar,
/// triangles, creasing (`None`: the file's tag, else the default).
pub type FileNames = (Option<String>, String, Option<String>, Option<String>, Option<String>, Option<String>);

/// What [`subdivide_file`] did: the scheme refined by (as `subdiv
/// subdivide` says it), the levels, the input's vertices and faces, the
/// output's vertices and faces, the bytes written and the seconds taken.
type FileDone = (String, u32, usize, usize, usize, usize, Option<u64>, f64);

/// `subdiv.subdivide_file`'s work: `files` `(input, output)`, `input`
/// read, refined `levels` times by the options it states under the
/// `names` given, written to `output` (by extension, atomically), as `subdiv subdivide` and every file of
/// `subdiv batch` do: the library's one call, [`subdiv::subdivide_file`],
/// with the GIL released. `flags` are `(repair, f64)`; `time` and
/// `threads` as for [`load_file`].
///
/// # Errors
/// `SubdivError` with the library's message, naming `input` (prefixed
/// where the library's message names only the output or nothing).
#[pyfunction]
pub fn subdivide_file(
    py: Python<'_>,
    files: (PathBuf, PathBuf),
    levels: u32,
    names: FileNames,
    flags: (bool, bool),
    time: Option<f64>,
    threads: Option<usize>,
) -> PyResult<FileDone> {
    if time.is_some_and(|t| !t.is_finite()) {
        return Err(crate::guard::error("time must be a finite time code"));
    }
    let job = file_job(&names, levels, flags, time).map_err(|m| crate::guard::error(&m))?;
    let (input, output) = files;
    run(py, threads, || {
        let t0 = std::time::Instant::now();
        let s = subdiv::subdivide_file(&input, &output, &job, &mut |_| Ok(())).map_err(|e| naming(&input, &e))?;
        let bytes = std::fs::metadata(&output).ok().map(|m| m.len());
        let seconds = t0.elapsed().as_secs_f64();
        Ok((s.scheme, s.levels, s.input_vertices, s.input_faces, s.vertices, s.faces, bytes, seconds))
    })
}

/// The library's job for these names, levels and flags (`(repair, f64)`).
fn file_job(
    names: &FileNames,
    levels: u32,
    (repair, f64): (bool, bool),
    time: Option<f64>,
) -> Result<subdiv::FileJob, Msg> {
    use crate::options::parse;
    let (scheme, beta, boundary, fvar, triangles, creasing) = names;
    let flags = subdiv::Flags {
        scheme: scheme.as_deref().map(parse).transpose()?,
        loop_beta: parse(beta)?,
        boundary: boundary.as_deref().map(parse).transpose()?,
        uv: fvar.as_deref().map(parse).transpose()?,
        triangles: triangles.as_deref().map(parse).transpose()?,
        creasing: creasing.as_deref().map(parse).transpose()?,
        ..subdiv::Flags::default()
    };
    let topology = if repair { Topology::Repair } else { Topology::Refuse };
    let read = ReadOptions { topology, time, ..ReadOptions::default() };
    Ok(subdiv::FileJob { read, flags, levels, f64 })
}

/// The library's message `e`, naming `input` first where it does not.
fn naming(input: &std::path::Path, e: &subdiv::Error) -> Msg {
    let m = e.to_string();
    let shown = input.display().to_string();
    match m.contains(&shown) {
        true => m,
        false => format!("{}: {m}", subdiv::clean_error(&shown, 200)),
    }
}
