//! The native module of the `subdiv` Python package (`subdiv._subdiv`).
//!
//! The Python layer (`python/subdiv/__init__.py`) turns array-likes into
//! C-contiguous, aligned float64 and int64 arrays and checks their shapes; this
//! module checks every value again (indices, coordinates, names, counts),
//! hands the work to the library with the GIL released, on the requested
//! threads, every panic caught, and returns numpy arrays it allocated once.

mod arrays;
mod build;
mod evaluate;
mod files;
mod guard;
mod ops;
mod options;
mod refiner;
#[cfg(feature = "viewer")]
mod view;

use pyo3::prelude::*;

#[pymodule]
fn _subdiv(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SubdivError", m.py().get_type::<guard::SubdivError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("HAS_VIEWER", cfg!(feature = "viewer"))?;
    m.add("MAX_THREADS", guard::MAX_THREADS)?;
    m.add_function(wrap_pyfunction!(guard::_panic_for_tests, m)?)?;
    m.add_function(wrap_pyfunction!(ops::subdivide_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(ops::plan_levels, m)?)?;
    m.add_function(wrap_pyfunction!(ops::limit_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate::evaluate_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate::tessellate_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(files::load_file, m)?)?;
    m.add_class::<refiner::NativeRefiner>()?;
    m.add_function(wrap_pyfunction!(files::save_file, m)?)?;
    m.add_function(wrap_pyfunction!(files::subdivide_file, m)?)?;
    #[cfg(feature = "viewer")]
    {
        m.add_function(wrap_pyfunction!(view::render_image, m)?)?;
        m.add_function(wrap_pyfunction!(view::view_window, m)?)?;
    }
    Ok(())
}
