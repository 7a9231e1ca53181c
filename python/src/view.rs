//! `subdiv.render` (offscreen, wgpu; Mesa's software Vulkan suffices) and
//! `subdiv.view` (the viewer's window), with the feature `viewer`.

use crate::build::Control;
use crate::guard::{Msg, SubdivError, msg, run};
use crate::ops::{CreaseArgs, MeshArgs, control};
use crate::options;
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray3};
use pyo3::prelude::*;
use subdiv::io::{save, save_with};
use subdiv::render::{RenderOptions, Shading};
use subdiv::{Mesh, Scheme, subdivide};

/// Largest image side `render` makes.
const MAX_SIDE: u32 = 8192;

/// The mesh refined `levels` times, as triangles.
fn refined(c: Control, scheme: Scheme, levels: u32, opts: &subdiv::Options) -> Result<Mesh, Msg> {
    match c {
        Control::Tri(m) => subdivide(&m, scheme, levels, opts).map(|r| r.0).map_err(msg),
        Control::Poly(m) => subdivide(&m, scheme, levels, opts).map(|r| r.0.triangulated()).map_err(msg),
    }
}

/// `subdiv.render`'s work: an RGBA image `(height, width, 4)`; `names`
/// are the scheme, beta, boundary and shading.
///
/// # Errors
/// `SubdivError` for a refused mesh, name or size, or without a GPU adapter.
#[pyfunction]
pub fn render_image<'py>(
    py: Python<'py>,
    mesh: MeshArgs<'py>,
    creases: CreaseArgs<'py>,
    names: (String, String, String, String),
    levels: u32,
    size: (u32, u32),
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let (w, h) = size;
    if !(1..=MAX_SIDE).contains(&w) || !(1..=MAX_SIDE).contains(&h) {
        return Err(SubdivError::new_err(format!(
            "size must be between 1 and {MAX_SIDE} pixels a side, got {w} x {h}"
        )));
    }
    // the image, its readback and the render targets: about 16 bytes a pixel
    let bytes = u64::from(w) * u64::from(h) * 16;
    if subdiv::mem::default_memory_limit().is_some_and(|limit| bytes > limit) {
        return Err(SubdivError::new_err(format!("a {w} x {h} image needs more memory than is available")));
    }
    let s = mesh.slices(&creases)?;
    let img = run(py, None, || {
        let shading: Shading = names.3.parse::<Shading>()?;
        let scheme = options::scheme(&names.0)?;
        let opts = options::options(&names.1, &names.2)?;
        let fine = refined(control(&s, scheme, false)?.0, scheme, levels, &opts)?;
        let ro = RenderOptions { shading, width: w, height: h, ..RenderOptions::default() };
        subdiv::render::render_image(&fine, None, &ro).map_err(msg)
    })?;
    let (iw, ih) = img.dimensions();
    let a = Array3::from_shape_vec((ih as usize, iw as usize, 4), img.into_raw())
        .map_err(|e| SubdivError::new_err(e.to_string()))?;
    Ok(a.into_pyarray(py))
}

/// `subdiv.view`'s work: the viewer's window on the mesh (written to a
/// temporary PLY file the viewer opens), returning when it is closed;
/// `names` are the scheme, beta and boundary; `frames` closes it after
/// that many frames, saving the last to the screenshot path when given.
///
/// # Errors
/// `SubdivError` for a refused mesh, or when no window can open.
#[pyfunction]
pub fn view_window<'py>(
    py: Python<'py>,
    mesh: MeshArgs<'py>,
    names: (String, String, String),
    levels: u32,
    flags: (bool, bool),
    frames: (Option<u32>, Option<std::path::PathBuf>),
) -> PyResult<()> {
    let none = CreaseArgs::empty(py);
    let s = mesh.slices(&none)?;
    run(py, None, || {
        let scheme = options::scheme(&names.0)?;
        let opts = options::options(&names.1, &names.2)?;
        let (c, _) = control(&s, scheme, false)?;
        let file = TempFile::new()?;
        match &c {
            Control::Tri(m) => save(&file.0, m),
            Control::Poly(m) => save_with(&file.0, m, &Default::default()),
        }
        .map_err(msg)?;
        let (wireframe, cage) = flags;
        subdiv::app::run(subdiv::app::ViewOptions {
            model: Some(file.0.clone()),
            scheme,
            opts,
            level: levels,
            wireframe,
            control: cage,
            frames: frames.0,
            screenshot: frames.1,
            ..Default::default()
        })
        .map_err(msg)
    })
}

/// A file in the temporary folder, removed when dropped.
struct TempFile(std::path::PathBuf);

impl TempFile {
    fn new() -> Result<TempFile, Msg> {
        static COUNT: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
        let k = COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let name = format!("subdiv-view-{}-{k}.ply", std::process::id());
        Ok(TempFile(std::env::temp_dir().join(name)))
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}
