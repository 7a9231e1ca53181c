//! Running library work safely from Python: without the GIL, on the
//! requested number of threads, with every panic caught and every error
//! turned into `SubdivError`.

use pyo3::prelude::*;
use std::panic::{AssertUnwindSafe, catch_unwind};

pyo3::create_exception!(
    _subdiv,
    SubdivError,
    pyo3::exceptions::PyValueError,
    "A value the library refuses (a non-manifold mesh, an index out of range, a level too large for memory, ...), with the library's message."
);

/// Most worker threads a call may ask for.
pub const MAX_THREADS: usize = 256;

/// A library failure, as one line.
pub type Msg = String;

/// Any displayable error as a message.
pub fn msg(e: impl std::fmt::Display) -> Msg {
    e.to_string()
}

/// A library message as the `SubdivError` Python raises.
pub fn error(m: &str) -> PyErr {
    SubdivError::new_err(m.to_string())
}

/// Runs `f` with the GIL released (`Python::detach`, PyO3's
/// `allow_threads`), on `threads` worker threads (`None`: the shared
/// pool), turning an error or a panic into `SubdivError`.
///
/// # Errors
/// `SubdivError` with `f`'s message, or naming the panic.
pub fn run<T: Send>(py: Python<'_>, threads: Option<usize>, f: impl FnOnce() -> Result<T, Msg> + Send) -> PyResult<T> {
    let pool = pool(threads)?;
    run_on(py, pool.as_ref(), f)
}

/// [`run`] on a pool made once ([`pool`]; `None`: the shared pool), as a
/// refiner's edits run on the pool it was built with.
///
/// # Errors
/// As [`run`].
pub fn run_on<T: Send>(
    py: Python<'_>,
    pool: Option<&rayon::ThreadPool>,
    f: impl FnOnce() -> Result<T, Msg> + Send,
) -> PyResult<T> {
    let outcome = py.detach(move || {
        catch_unwind(AssertUnwindSafe(|| match pool {
            Some(p) => p.install(f),
            None => f(),
        }))
    });
    match outcome {
        Ok(Ok(value)) => Ok(value),
        Ok(Err(m)) => Err(SubdivError::new_err(m)),
        Err(panic) => Err(SubdivError::new_err(format!(
            "internal error (a bug in subdiv, please report it): {}",
            panic_text(panic.as_ref())
        ))),
    }
}

/// A pool of `threads` threads (`None`: none, the shared pool serves).
///
/// # Errors
/// `SubdivError` for a count outside `1..=MAX_THREADS`, or when the
/// threads cannot be started.
pub fn pool(threads: Option<usize>) -> PyResult<Option<rayon::ThreadPool>> {
    match threads {
        None => Ok(None),
        Some(k) if (1..=MAX_THREADS).contains(&k) => rayon::ThreadPoolBuilder::new()
            .num_threads(k)
            .build()
            .map(Some)
            .map_err(|e| SubdivError::new_err(format!("cannot start {k} threads: {e}"))),
        Some(k) => Err(SubdivError::new_err(format!("threads must be between 1 and {MAX_THREADS}, got {k}"))),
    }
}

/// The message a panic carried.
fn panic_text(p: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "a panic without a message".to_string()
    }
}

/// Panics inside [`run`], as a bug in the library would: for the test that
/// a panic reaches Python as `SubdivError` and never aborts the interpreter.
///
/// # Errors
/// Always `SubdivError`.
#[pyfunction]
pub fn _panic_for_tests(py: Python<'_>, threads: Option<usize>) -> PyResult<()> {
    run(py, threads, || -> Result<(), Msg> {
        use rayon::prelude::*;
        // on a worker thread too: rayon carries the panic back to the caller
        (0..64).into_par_iter().for_each(|i| assert!(i != 37, "a deliberate panic"));
        Ok(())
    })
}
