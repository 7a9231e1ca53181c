//! Reading and writing meshes. In: Wavefront OBJ, the corner-table text
//! format `.ct` (with its O table), `.bez` Bezier patches, PLY (ASCII and
//! binary), STL (ASCII and binary), OFF, glTF 2.0 (`.gltf`, `.glb`) and
//! COLLADA (`.dae`). Out: OBJ, `.ct`, PLY, STL, OFF and `.glb`. The format is
//! chosen by extension ([`Format::of`]), by content where the extension says
//! nothing. Every writer goes through [`atomic_write`], so a failure never
//! leaves a truncated file behind. No reader panics or allocates more than
//! its input can hold (`tests/io.rs` fuzzes them all).

pub mod bezier;
pub mod ct;
pub mod dae;
pub mod gltf;
pub mod obj;
pub mod off;
pub mod ply;
pub mod raw;
pub mod stl;
mod text;

/// The mesh formats, as [`Format::of`] tells them apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Wavefront OBJ (`.obj`; also any unknown extension).
    Obj,
    /// The corner-table text format (`.ct`).
    Ct,
    /// Bicubic Bezier patches (`.bez`).
    Bez,
    /// A Bezier curve (`.bzc`): not a mesh.
    Bzc,
    /// Stanford PLY (`.ply`).
    Ply,
    /// STL (`.stl`).
    Stl,
    /// Object File Format (`.off`).
    Off,
    /// glTF 2.0 (`.gltf`, `.glb`).
    Gltf,
    /// COLLADA (`.dae`).
    Dae,
}

/// The extensions every reader accepts (lower case, no dot): what file
/// dialogs and drag and drop offer.
pub const READ_EXTENSIONS: &[&str] = &["obj", "ct", "bez", "bzc", "ply", "stl", "off", "gltf", "glb", "dae"];

/// The extensions [`save`] writes.
pub const WRITE_EXTENSIONS: &[&str] = &["obj", "ct", "ply", "stl", "off", "glb"];

impl Format {
    /// The format of `file` by its extension; without a known one, by the
    /// first bytes of its content (`ply`, `solid` or a binary STL's size,
    /// `OFF`, `glTF` or `{`, `<`), else OBJ.
    pub fn of(file: &str, bytes: &[u8]) -> Format {
        match ext(Path::new(file)).as_str() {
            "obj" => Format::Obj,
            "ct" => Format::Ct,
            "bez" => Format::Bez,
            "bzc" => Format::Bzc,
            "ply" => Format::Ply,
            "stl" => Format::Stl,
            "off" => Format::Off,
            "gltf" | "glb" => Format::Gltf,
            "dae" => Format::Dae,
            _ => Format::sniff(bytes),
        }
    }

    fn sniff(bytes: &[u8]) -> Format {
        let start = bytes.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(bytes.len());
        let head = &bytes[start..];
        if bytes.starts_with(b"ply") {
            Format::Ply
        } else if bytes.starts_with(b"glTF") || head.starts_with(b"{") {
            Format::Gltf
        } else if head.starts_with(b"<") {
            Format::Dae
        } else if stl::is_binary(bytes) || head.starts_with(b"solid") {
            Format::Stl
        } else if head.starts_with(b"OFF") || head.starts_with(b"COFF") {
            Format::Off
        } else {
            Format::Obj
        }
    }

    /// Reads the formats that go through [`raw::RawMesh`].
    fn raw(self, bytes: &[u8], file: &str) -> Option<Result<raw::RawMesh>> {
        Some(match self {
            Format::Ply => ply::parse(bytes, file),
            Format::Stl => stl::parse(bytes, file),
            Format::Off => off::parse(bytes, file),
            Format::Gltf => gltf::parse(bytes, file),
            Format::Dae => dae::parse(bytes, file),
            _ => return None,
        })
    }
}

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
    let format = Format::of(file, bytes);
    if let Some(raw) = format.raw(bytes, file) {
        return raw?.build(file).map(|(m, _)| m);
    }
    match format {
        Format::Bzc => Err(not_a_mesh(file)),
        Format::Ct => ct::parse(text(bytes, file)?, file),
        Format::Bez => bezier::tessellate(&bezier::parse_bez(text(bytes, file)?, file)?, BEZ_RESOLUTION)
            .map_err(|source| Error::Mesh { file: file.to_string(), line: None, source }),
        _ => obj::from_bytes(bytes, file).map(|(m, _)| m),
    }
}

/// [`from_bytes`] with the file's attributes: texture coordinates and
/// vertex colours where the format has them (empty otherwise).
///
/// # Errors
/// As [`load`].
pub fn from_bytes_with_attributes(bytes: &[u8], file: &str) -> Result<(Mesh, crate::mesh::attributes::Attributes)> {
    let format = Format::of(file, bytes);
    if let Some(raw) = format.raw(bytes, file) {
        return raw?.build(file);
    }
    match format {
        Format::Obj => obj::from_bytes_with_attributes(bytes, file),
        _ => Ok((from_bytes(bytes, file)?, Default::default())),
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
    let format = Format::of(file, bytes);
    if let Some(raw) = format.raw(bytes, file) {
        return raw?.repaired(file);
    }
    match format {
        Format::Bzc => Err(not_a_mesh(file)),
        Format::Ct => {
            let raw = ct::parse_raw(text(bytes, file)?, file)?;
            let lines = raw.triangle_lines;
            repair(raw.positions, &raw.triangles).map_err(|e| Error::Mesh {
                file: file.to_string(),
                line: e.face().and_then(|f| lines.get(f).copied()),
                source: e,
            })
        }
        Format::Bez => bezier::tessellate_repaired(&bezier::parse_bez(text(bytes, file)?, file)?, BEZ_RESOLUTION)
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
    let format = Format::of(&file, bytes);
    let (positions, triangles, base) = if let Some(raw) = format.raw(bytes, &file) {
        let raw = raw?;
        (raw.positions, raw.triangles, 0)
    } else {
        match format {
            Format::Bzc => return Err(not_a_mesh(&file)),
            Format::Ct => {
                let raw = ct::parse_raw(text(bytes, &file)?, &file)?;
                (raw.positions, raw.triangles, 0)
            }
            Format::Bez => {
                let raw = bezier::tessellate_raw(&bezier::parse_bez(text(bytes, &file)?, &file)?, BEZ_RESOLUTION)
                    .map_err(|source| Error::Mesh { file: file.clone(), line: None, source })?;
                (raw.positions, raw.triangles, 0)
            }
            _ => {
                let raw = obj::parse(bytes, &file)?;
                (raw.positions, raw.triangles, 1)
            }
        }
    };
    let (mesh, mut report) = crate::mesh::repair::repair_with_cap(positions, &triangles, usize::MAX)
        .map_err(|e| Error::Mesh { file, line: None, source: e.shift_vertices(base) })?;
    report.id_base = base;
    Ok((mesh, report))
}

/// Saves a mesh as `.obj`, `.ply`, `.ct`, `.stl`, `.off` or `.glb`, chosen
/// by extension.
///
/// # Errors
/// An unknown extension or an I/O error.
pub fn save(path: &Path, mesh: &Mesh) -> Result<()> {
    save_with(path, mesh, &Default::default())
}

/// Whether [`save_with`] writes texture coordinates or colours to `path`'s
/// format: OBJ and `.glb` keep both, PLY and OFF colours only.
pub fn keeps_attributes(path: &Path) -> bool {
    matches!(ext(path).as_str(), "obj" | "glb" | "ply" | "off")
}

/// [`save`] with the mesh's attributes where the format keeps them (see
/// [`keeps_attributes`]); elsewhere they are dropped.
///
/// # Errors
/// As [`save`].
pub fn save_with(path: &Path, mesh: &Mesh, attrs: &crate::mesh::attributes::Attributes) -> Result<()> {
    let colors = attrs.colors.as_deref();
    match ext(path).as_str() {
        "obj" if attrs.is_empty() => obj::save(path, mesh),
        "obj" => obj::save_with(path, mesh, attrs),
        "ply" => ply::save_with(path, mesh, colors),
        "ct" => ct::save(path, mesh),
        "stl" => stl::save(path, mesh),
        "off" => off::save_with(path, mesh, colors),
        "glb" => gltf::save(path, mesh, attrs),
        other => Err(Error::UnknownFormat {
            path: path.display().to_string(),
            ext: other.to_string(),
            direction: "output",
            known: ".obj, .ply, .ct, .stl, .off or .glb",
        }),
    }
}

fn ext(path: &Path) -> String {
    path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase()
}

/// Writes `head` and then the texts of `jobs` formatted in parallel, in
/// job order, to `sink`: a helper thread formats batches of jobs over
/// rayon's threads while this thread writes the batch before (and `head`
/// while the first batch is formatted), so formatting and writing overlap.
/// Memory stays bounded by two batches. For text, whose pieces' offsets are
/// known only once formatted (OBJ); records of fixed size go through
/// [`atomic_write_pieces`] instead.
///
/// # Errors
/// The first error of `sink`; formatting stops after it.
pub(crate) fn write_formatted(
    head: &[&[u8]],
    jobs: usize,
    format: impl Fn(usize) -> Vec<u8> + Sync,
    sink: &mut dyn FnMut(&[u8]) -> Result<()>,
) -> Result<()> {
    use rayon::prelude::*;
    // jobs are chunks of about 1 MB: four keep two threads formatting while
    // the previous four are written, with about 10 MB in flight (16 held
    // 40 MB more of fresh pages for the same speed at bunny level 3)
    const BATCH: usize = 4;
    let format = &format;
    std::thread::scope(|scope| {
        // one batch in flight: the formatter waits while the writer is behind
        let (tx, rx) = std::sync::mpsc::sync_channel::<Vec<Vec<u8>>>(1);
        scope.spawn(move || {
            for start in (0..jobs).step_by(BATCH) {
                let texts = (start..(start + BATCH).min(jobs)).into_par_iter().map(format).collect();
                if tx.send(texts).is_err() {
                    return; // the writer failed
                }
            }
        });
        for h in head {
            sink(h)?;
        }
        for texts in rx {
            for t in texts {
                sink(&t)?;
            }
        }
        Ok(())
    })
}

/// A file that asks the kernel to start writing back every 16 MiB as soon
/// as it is written (`sync_file_range`, Linux), so that the disk works while
/// the rest is formatted and the final `fsync` waits for the tail only.
struct WriteAhead<'a> {
    file: &'a std::fs::File,
    /// Bytes written so far.
    written: u64,
    /// Bytes whose write-back has been started.
    started: u64,
}

impl WriteAhead<'_> {
    const STEP: u64 = 16 << 20;
}

impl Write for WriteAhead<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let k = self.file.write(buf)?;
        self.written += k as u64;
        if self.written - self.started >= Self::STEP {
            start_write_back(self.file, self.started, self.written - self.started);
            self.started = self.written;
        }
        Ok(k)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

/// Asks the kernel to start writing `len` bytes of `file` from `offset`
/// back to the disk, without waiting (`sync_file_range`, Linux; elsewhere
/// nothing): the final `fsync` then waits for what is left only.
fn start_write_back(file: &std::fs::File, offset: u64, len: u64) {
    #[cfg(target_os = "linux")]
    {
        use std::os::fd::AsRawFd;
        // SAFETY: the descriptor belongs to `file`, open while it is
        // borrowed; sync_file_range only starts the write-back of that range
        // and reads or changes no memory of ours. An error (an old kernel, a
        // file system without it) only means that the final fsync does all
        // the work, so it is ignored.
        unsafe {
            libc::sync_file_range(
                file.as_raw_fd(),
                offset as libc::off64_t,
                len as libc::off64_t,
                libc::SYNC_FILE_RANGE_WRITE,
            );
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = (file, offset, len);
}

/// Buffer of the writers' files: small records are gathered, while a
/// formatted chunk (hundreds of kilobytes, see [`write_formatted`]) is at
/// least this large and goes straight to the file. With a 1 MiB buffer the
/// chunks below 1 MiB (every PLY face chunk, every OBJ face chunk) were
/// copied through it first: 100 MB of copying for the bunny at level 3.
const WRITE_BUFFER: usize = 64 << 10;

/// Writes `path` through a temporary file in the same directory and renames
/// it into place only when `f` succeeded, so an existing file is never left
/// truncated.
///
/// # Errors
/// The error of `f`, or an I/O error naming `path`.
pub fn atomic_write(path: &Path, f: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
    if let Some(file) = open_device(path)? {
        let mut w = std::io::BufWriter::with_capacity(WRITE_BUFFER, file);
        f(&mut w)?;
        return w.into_inner().map(drop).map_err(|e| Error::io(path, e.into_error()));
    }
    replace(path, |file| {
        let mut w = std::io::BufWriter::with_capacity(WRITE_BUFFER, WriteAhead { file, written: 0, started: 0 });
        f(&mut w)?;
        w.into_inner().map(drop).map_err(|e| Error::io(path, e.into_error()))
    })
}

/// [`atomic_write`] for a file whose pieces have offsets known before any
/// is made (a header and records of fixed size): `piece(k)` gives piece
/// `k`'s offset and bytes, and the pieces are made and written in parallel,
/// each at its offset (`pwrite`), its write-back started at once, so that
/// the copying into the page cache runs on every thread. Into a device or
/// a pipe they are written in order, so piece `k + 1` must start where
/// piece `k` ends.
///
/// # Errors
/// An I/O error naming `path`.
pub(crate) fn atomic_write_pieces<'a>(
    path: &Path,
    pieces: usize,
    piece: impl Fn(usize) -> (u64, std::borrow::Cow<'a, [u8]>) + Sync,
) -> Result<()> {
    let io = |e| Error::io(path, e);
    if let Some(mut file) = open_device(path)? {
        return (0..pieces).try_for_each(|k| file.write_all(&piece(k).1).map_err(io));
    }
    #[cfg(unix)]
    return replace(path, |file| {
        use rayon::prelude::*;
        use std::os::unix::fs::FileExt;
        (0..pieces).into_par_iter().try_for_each(|k| {
            let (offset, bytes) = piece(k);
            file.write_all_at(&bytes, offset).map_err(io)?;
            start_write_back(file, offset, bytes.len() as u64);
            Ok(())
        })
    });
    #[cfg(not(unix))]
    atomic_write(path, |w| (0..pieces).try_for_each(|k| w.write_all(&piece(k).1).map_err(io)))
}

/// `path` opened for writing when it is a device or a pipe (`/dev/null`,
/// `/dev/stdout`): written into, never replaced by a renamed file.
fn open_device(path: &Path) -> Result<Option<std::fs::File>> {
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir()) {
        let file = std::fs::OpenOptions::new().write(true).open(path).map_err(|e| Error::io(path, e))?;
        return Ok(Some(file));
    }
    Ok(None)
}

/// Writes a temporary file beside `path` with `write`, makes it durable
/// (`fsync`, so that a crash cannot leave a renamed but empty file) and
/// renames it over `path`; on an error the temporary file is removed and
/// `path` left as it was.
fn replace(path: &Path, write: impl FnOnce(&std::fs::File) -> Result<()>) -> Result<()> {
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "out".into());
    let tmp: PathBuf = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let file = std::fs::File::create(&tmp).map_err(|e| Error::io(path, e))?;
        write(&file)?;
        file.sync_all().ok();
        std::fs::rename(&tmp, path).map_err(|e| Error::io(path, e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// A fresh directory for one unit test's files, removed when dropped.
#[cfg(test)]
pub(crate) struct TestDir(pub(crate) PathBuf);

#[cfg(test)]
impl TestDir {
    pub(crate) fn new(name: &str) -> TestDir {
        let dir = std::env::temp_dir().join(format!("subdiv-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temporary directory");
        TestDir(dir)
    }
}

#[cfg(test)]
impl Drop for TestDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
