//! Reading and writing meshes: Wavefront OBJ, the corner-table text format
//! `.ct` (with its O table), and binary PLY output. Every writer goes through
//! [`atomic_write`], so a failure never leaves a truncated file behind.

pub mod bezier;
pub mod ct;
pub mod obj;
pub mod ply;

use crate::mesh::Mesh;
use crate::mesh::repair::{RepairReport, repair};
use crate::{Error, Result};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Loads a mesh from `.obj`, `.ct` or `.bez` (bicubic Bezier patches,
/// tessellated [`BEZ_RESOLUTION`] times per side), chosen by extension;
/// anything else is read as OBJ, except a `.bzc` curve, which is refused.
///
/// # Errors
/// I/O, parse and validation errors, each naming the file (and line where
/// there is one); [`Error::NotAMesh`] for a `.bzc` curve.
pub fn load(path: &Path) -> Result<Mesh> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    from_bytes(&bytes, &path.display().to_string())
}

/// [`load`] on a file's bytes; `file` names it in errors and its extension
/// chooses the format.
///
/// # Errors
/// As [`load`].
pub fn from_bytes(bytes: &[u8], file: &str) -> Result<Mesh> {
    match ext(Path::new(file)).as_str() {
        "bzc" => Err(not_a_mesh(file)),
        "ct" => ct::parse(text(bytes, file)?, file),
        "bez" => bezier::tessellate(&bezier::parse_bez(text(bytes, file)?, file)?, BEZ_RESOLUTION)
            .map_err(|source| Error::Mesh { file: file.to_string(), line: None, source }),
        _ => obj::from_bytes(bytes, file).map(|(m, _)| m),
    }
}

/// Loads a mesh from `.obj` or `.ct` like [`load`], but repairs bad topology
/// (non-manifold edges and vertices, inconsistent orientation, degenerate and
/// duplicate faces) instead of refusing it; see [`crate::mesh::repair`](mod@crate::mesh::repair). A
/// stored O table in a `.ct` is ignored (the repaired mesh gets a new one).
///
/// # Errors
/// I/O and parse errors, index out of range and non-finite coordinates (each
/// naming the file and line), and a mesh with no face left.
pub fn load_repaired(path: &Path) -> Result<(Mesh, RepairReport)> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    from_bytes_repaired(&bytes, &path.display().to_string())
}

/// [`load_repaired`] on a file's bytes (see [`from_bytes`]).
///
/// # Errors
/// As [`load_repaired`].
pub fn from_bytes_repaired(bytes: &[u8], file: &str) -> Result<(Mesh, RepairReport)> {
    match ext(Path::new(file)).as_str() {
        "bzc" => Err(not_a_mesh(file)),
        "ct" => {
            let raw = ct::parse_raw(text(bytes, file)?, file)?;
            let lines = raw.triangle_lines;
            repair(raw.positions, &raw.triangles).map_err(|e| Error::Mesh {
                file: file.to_string(),
                line: e.face().and_then(|f| lines.get(f).copied()),
                source: e,
            })
        }
        "bez" => bezier::tessellate_repaired(&bezier::parse_bez(text(bytes, file)?, file)?, BEZ_RESOLUTION)
            .map_err(|source| Error::Mesh { file: file.to_string(), line: None, source }),
        _ => obj::from_bytes_repaired(bytes, file),
    }
}

/// [`Error::NotAMesh`] for a `.bzc` curve given where a mesh is read.
fn not_a_mesh(file: &str) -> Error {
    Error::NotAMesh { file: file.to_string(), what: "a Bezier curve (.bzc)" }
}

/// The bytes of `file` as text; invalid UTF-8 is a parse error at its line.
///
/// # Errors
/// [`Error::Parse`] at the line of the first invalid byte.
pub fn text<'a>(bytes: &'a [u8], file: &str) -> Result<&'a str> {
    std::str::from_utf8(bytes).map_err(|e| Error::Parse {
        file: file.to_string(),
        line: bytes[..e.valid_up_to()].iter().filter(|&&b| b == b'\n').count() + 1,
        msg: "not text (invalid UTF-8)".into(),
    })
}

/// Samples per patch side when a `.bez` file of bicubic patches is opened as a mesh.
pub const BEZ_RESOLUTION: u32 = 8;

/// [`load_repaired`] with a report that keeps every id found (no cap): what
/// `subdiv info` lists for a mesh that does not build. Ids in the report are
/// those of the file (`id_base` 1 for OBJ).
///
/// # Errors
/// As [`load_repaired`].
pub fn analyze(path: &Path) -> Result<(Mesh, RepairReport)> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    analyze_bytes(&bytes, &path.display().to_string())
}

/// [`analyze`] on a file's bytes (see [`from_bytes`]).
///
/// # Errors
/// As [`load_repaired`].
pub fn analyze_bytes(bytes: &[u8], file: &str) -> Result<(Mesh, RepairReport)> {
    let file = file.to_string();
    let (positions, triangles, base) = match ext(Path::new(&file)).as_str() {
        "bzc" => return Err(not_a_mesh(&file)),
        "ct" => {
            let raw = ct::parse_raw(text(bytes, &file)?, &file)?;
            (raw.positions, raw.triangles, 0)
        }
        "bez" => {
            let raw = bezier::tessellate_raw(&bezier::parse_bez(text(bytes, &file)?, &file)?, BEZ_RESOLUTION)
                .map_err(|source| Error::Mesh { file: file.clone(), line: None, source })?;
            (raw.positions, raw.triangles, 0)
        }
        _ => {
            let raw = obj::parse(bytes, &file)?;
            (raw.positions, raw.triangles, 1)
        }
    };
    let (mesh, mut report) = crate::mesh::repair::repair_with_cap(positions, &triangles, usize::MAX)
        .map_err(|e| Error::Mesh { file, line: None, source: e.shift_vertices(base) })?;
    report.id_base = base;
    Ok((mesh, report))
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
        other => Err(Error::UnknownFormat {
            path: path.display().to_string(),
            ext: other.to_string(),
            direction: "output",
            known: ".obj, .ply or .ct",
        }),
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
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir()) {
        // a device or pipe (/dev/null, /dev/stdout): write into it, never
        // rename a temporary file over it
        let file = std::fs::OpenOptions::new().write(true).open(path).map_err(|e| Error::io(path, e))?;
        let mut w = std::io::BufWriter::with_capacity(1 << 20, file);
        f(&mut w)?;
        return w.into_inner().map(drop).map_err(|e| Error::io(path, e.into_error()));
    }
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
