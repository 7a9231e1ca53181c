//! Reading and writing meshes: Wavefront OBJ, the corner-table text format
//! `.ct` (with its O table), and binary PLY output. Every writer goes through
//! [`atomic_write`], so a failure never leaves a truncated file behind.

pub mod ct;
pub mod obj;
pub mod ply;

use crate::mesh::Mesh;
use crate::{Error, Result};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Loads a mesh from `.obj` or `.ct` (chosen by extension; anything else is
/// read as OBJ).
///
/// # Errors
/// I/O, parse and validation errors, each naming the file (and line where
/// there is one).
pub fn load(path: &Path) -> Result<Mesh> {
    match ext(path).as_str() {
        "ct" => ct::load(path),
        _ => obj::load(path).map(|(m, _)| m),
    }
}

/// Saves a mesh as `.obj`, `.ply` or `.ct`, chosen by extension.
///
/// # Errors
/// An unknown extension or an I/O error.
pub fn save(path: &Path, mesh: &Mesh) -> Result<()> {
    match ext(path).as_str() {
        "obj" => obj::save(path, mesh),
        "ply" => ply::save(path, mesh),
        "ct" => ct::save(path, mesh),
        other => {
            Err(Error::Usage(format!("{}: unknown output format '.{other}' (use .obj, .ply or .ct)", path.display())))
        }
    }
}

fn ext(path: &Path) -> String {
    path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase()
}

/// Writes `path` through a temporary file in the same directory and renames
/// it into place only when `f` succeeded, so an existing file is never left
/// truncated.
///
/// # Errors
/// The error of `f`, or an I/O error naming `path`.
pub fn atomic_write(path: &Path, f: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "out".into());
    let tmp: PathBuf = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let file = std::fs::File::create(&tmp).map_err(|e| Error::io(path, e))?;
        let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
        f(&mut w)?;
        let file = w.into_inner().map_err(|e| Error::io(path, e.into_error()))?;
        file.sync_all().ok();
        std::fs::rename(&tmp, path).map_err(|e| Error::io(path, e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
