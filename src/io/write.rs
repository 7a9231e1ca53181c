//! Writing files safely: every writer goes through [`atomic_write`] or
//! [`atomic_write_pieces`], so a failure never leaves a truncated file and
//! a planted link is never followed. The new file is first written in the
//! output's folder without a name (Linux's `O_TMPFILE`; elsewhere under a
//! fresh name of its own, created exclusively, so no existing file or link
//! there is opened), made durable, then linked in at the output's name or
//! renamed over the output. A process killed mid-write leaves no file
//! behind on Linux. A device or a pipe (`/dev/null`, `/dev/stdout`) is
//! written into as it is.

use crate::{Error, Result};
use std::io::Write;
use std::path::{Path, PathBuf};

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
    // no threads in the browser: format and write in turn
    if cfg!(target_arch = "wasm32") {
        for h in head {
            sink(h)?;
        }
        return (0..jobs).try_for_each(|k| sink(&format(k)));
    }
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

/// Writes `rows` as text (atomically): one line per row, its numbers
/// separated by spaces, each the shortest decimal that reads back as the
/// same double (an exponent where that is shorter; `NaN`, `inf`, `-inf`),
/// formatted in parallel pieces and written in order. At most 10 numbers a
/// row.
///
/// # Errors
/// I/O errors naming `path`.
pub fn write_rows<const N: usize>(path: &Path, rows: &[[f64; N]]) -> Result<()> {
    // about 1 MB of text a job
    const ROWS: usize = 1 << 13;
    let chunks: Vec<&[[f64; N]]> = rows.chunks(ROWS).collect();
    atomic_write(path, |w| {
        let mut sink = |b: &[u8]| w.write_all(b).map_err(|e| Error::io(path, e));
        write_formatted(&[], chunks.len(), |k| super::text::f64_lines(chunks[k]), &mut sink)
    })
}

/// Writes parameter points (atomically), one `f u v` line each: the points
/// file `subdiv eval` reads ([`crate::eval::parse_points_in`]), `u` and `v`
/// the shortest decimals that read back as the same doubles.
///
/// # Errors
/// I/O errors naming `path`.
pub fn write_points(path: &Path, points: &[(u32, f64, f64)]) -> Result<()> {
    atomic_write(path, |w| {
        for &(f, u, v) in points {
            writeln!(w, "{f} {u} {v}").map_err(|e| Error::io(path, e))?;
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
pub(crate) fn atomic_write(path: &Path, f: impl FnOnce(&mut dyn Write) -> Result<()>) -> Result<()> {
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
/// puts it at `path`; on an error `path` is left as it was. On Linux the
/// temporary file has no name while it is written (`O_TMPFILE`), so a
/// process killed at any moment (`kill -9`) leaves nothing behind: it is
/// linked in at `path` when that is free, else under a temporary name
/// renamed over `path` at once. Elsewhere, or where the file system has no
/// unnamed files, it is a named file from the start; the name is short and
/// random (so an output name as long as the file system allows still works)
/// and the file is created exclusively: a file or link planted at that name
/// is never opened, a new name is drawn instead.
fn replace(path: &Path, write: impl FnOnce(&std::fs::File) -> Result<()>) -> Result<()> {
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    #[cfg(target_os = "linux")]
    if let Some(file) = unnamed::create(dir) {
        // on an error the file goes with its descriptor
        write(&file)?;
        file.sync_all().ok();
        return unnamed::link(&file, dir, path).map_err(|e| Error::io(path, e));
    }
    let (tmp, file) = create_temporary(dir).map_err(|e| Error::io(path, e))?;
    let result = (|| {
        write(&file)?;
        file.sync_all().ok();
        std::fs::rename(&tmp, path).map_err(|e| Error::io(path, e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// A new file in `dir` under a random name ([`temporary_name`]), created
/// exclusively (`create_new`: never an existing file, never through a
/// link); a name that exists is drawn again.
fn create_temporary(dir: &Path) -> std::io::Result<(PathBuf, std::fs::File)> {
    let mut last = None;
    for attempt in 0u32..16 {
        let tmp = temporary_name(dir, attempt);
        match std::fs::OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => return Ok((tmp, f)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => last = Some(e),
            Err(e) => return Err(e),
        }
    }
    Err(last.unwrap_or_else(|| std::io::Error::other("no free temporary name")))
}

/// A random name in `dir`, `.subdiv-<16 hex digits>.tmp` (`attempt`: the
/// how-manieth try).
fn temporary_name(dir: &Path, attempt: u32) -> PathBuf {
    use std::hash::{BuildHasher, Hasher};
    // RandomState is seeded from the operating system's randomness
    let mut h = std::hash::RandomState::new().build_hasher();
    h.write_u32(std::process::id());
    h.write_u32(attempt);
    dir.join(format!(".subdiv-{:016x}.tmp", h.finish()))
}

/// Files without a name until they are complete (Linux's `O_TMPFILE`),
/// named through `/proc/self/fd`.
#[cfg(target_os = "linux")]
mod unnamed {
    use std::ffi::CString;
    use std::fs::File;
    use std::io::{Error, ErrorKind, Result};
    use std::os::fd::AsRawFd;
    use std::os::unix::ffi::OsStrExt;
    use std::path::Path;

    /// An unnamed file in `dir`, or `None` where there is none to be had
    /// (a file system or kernel without `O_TMPFILE`, no `/proc`): the
    /// caller then writes a named one.
    pub(super) fn create(dir: &Path) -> Option<File> {
        use std::os::unix::fs::OpenOptionsExt;
        if !Path::new("/proc/self/fd").is_dir() {
            return None;
        }
        std::fs::OpenOptions::new().write(true).custom_flags(libc::O_TMPFILE).open(dir).ok()
    }

    /// Gives `file` the name `path`: a link made there when nothing is
    /// (never through a link planted there), else a link under a temporary
    /// name in `dir` renamed over `path`.
    pub(super) fn link(file: &File, dir: &Path, path: &Path) -> Result<()> {
        let from = CString::new(format!("/proc/self/fd/{}", file.as_raw_fd()))?;
        match link_at(&from, path) {
            Err(e) if e.kind() == ErrorKind::AlreadyExists => {}
            done => return done,
        }
        for attempt in 0u32..16 {
            let tmp = super::temporary_name(dir, attempt);
            match link_at(&from, &tmp) {
                Ok(()) => {
                    let renamed = std::fs::rename(&tmp, path);
                    if renamed.is_err() {
                        let _ = std::fs::remove_file(&tmp);
                    }
                    return renamed;
                }
                Err(e) if e.kind() == ErrorKind::AlreadyExists => {}
                Err(e) => return Err(e),
            }
        }
        Err(Error::other("no free temporary name"))
    }

    /// `linkat` of the file named by `from` (a `/proc/self/fd` entry,
    /// followed) to the new name `to`; `AlreadyExists` when `to` exists.
    fn link_at(from: &CString, to: &Path) -> Result<()> {
        let to = CString::new(to.as_os_str().as_bytes())?;
        // SAFETY: both pointers are to NUL-terminated strings that live
        // across the call; linkat only reads them and changes no memory.
        let r = unsafe {
            libc::linkat(libc::AT_FDCWD, from.as_ptr(), libc::AT_FDCWD, to.as_ptr(), libc::AT_SYMLINK_FOLLOW)
        };
        if r == 0 { Ok(()) } else { Err(Error::last_os_error()) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn a_link_planted_in_the_folder_is_never_followed() {
        let dir = crate::io::TestDir::new("planted-link");
        let victim = dir.0.join("victim");
        std::fs::write(&victim, b"keep me").unwrap();
        // links at every name the old scheme could have used, and some
        for name in [".out.obj.tmp".to_string(), format!(".out.obj.{}.tmp", std::process::id())] {
            std::os::unix::fs::symlink(&victim, dir.0.join(name)).unwrap();
        }
        let out = dir.0.join("out.obj");
        atomic_write(&out, |w| w.write_all(b"new").map_err(|e| Error::io(&out, e))).unwrap();
        assert_eq!(std::fs::read(&victim).unwrap(), b"keep me");
        assert_eq!(std::fs::read(&out).unwrap(), b"new");
    }

    #[test]
    fn an_output_name_as_long_as_the_file_system_allows_works() {
        let dir = crate::io::TestDir::new("long-name");
        let out = dir.0.join(format!("{}.obj", "n".repeat(251)));
        atomic_write(&out, |w| w.write_all(b"x").map_err(|e| Error::io(&out, e))).unwrap();
        assert_eq!(std::fs::read(&out).unwrap(), b"x");
        let left: Vec<_> = std::fs::read_dir(&dir.0).unwrap().collect();
        assert_eq!(left.len(), 1, "no temporary file left behind");
    }

    /// While a file is written (and once it is written) its folder holds
    /// no name but the output's: a process killed mid-write leaves nothing.
    #[cfg(target_os = "linux")]
    #[test]
    fn a_file_being_written_has_no_name_in_the_folder() {
        let dir = crate::io::TestDir::new("unnamed");
        let out = dir.0.join("out.obj");
        let names = || -> Vec<String> {
            let entries = std::fs::read_dir(&dir.0).unwrap();
            entries.map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect()
        };
        for (text, before) in [(&b"first"[..], vec![]), (&b"second"[..], vec!["out.obj".to_string()])] {
            atomic_write(&out, |w| {
                w.write_all(text).map_err(|e| Error::io(&out, e))?;
                w.flush().map_err(|e| Error::io(&out, e))?;
                assert_eq!(names(), before, "mid-write");
                Ok(())
            })
            .unwrap();
            assert_eq!(std::fs::read(&out).unwrap(), text);
            assert_eq!(names(), ["out.obj"]);
        }
    }

    #[test]
    fn rows_are_written_in_order_over_many_jobs() {
        let dir = crate::io::TestDir::new("rows");
        let out = dir.0.join("rows.txt");
        // over ten jobs of 8192 rows, the last one short
        let rows: Vec<[f64; 3]> = (0..90_001).map(|i| [i as f64, i as f64 / 7.0, -(i as f64).sqrt()]).collect();
        write_rows(&out, &rows).unwrap();
        let text = std::fs::read_to_string(&out).unwrap();
        let back: Vec<[f64; 3]> = text
            .lines()
            .map(|l| {
                let x: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
                [x[0], x[1], x[2]]
            })
            .collect();
        assert_eq!(back, rows);
    }
}
