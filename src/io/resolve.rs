//! The one place where a file is found and read: the files the user names
//! (models, key paths, curves, evaluation points: [`super::read_file`]) and
//! those a model names (MTL libraries and their textures, glTF buffers and
//! images, COLLADA images).
//!
//! - Only regular files are read: a device (`/dev/zero`), a FIFO, a socket
//!   or a folder is refused. Files are opened without blocking (a FIFO with
//!   no writer would otherwise wait forever) and checked on the open handle,
//!   so the check and the read see the same file.
//! - At most the declared length is read (glTF's `byteLength`), and never
//!   more than the budget's `file-bytes` and what is left of `total-bytes`.
//! - [`Scope::Folder`] (glTF, COLLADA: references are URIs) confines the
//!   reference to the model's folder after percent-decoding: no absolute
//!   path, no scheme, no `..` leaving the folder, and no link leading out
//!   of it. [`Scope::Anywhere`] (OBJ's `mtllib` and `map_Kd`, where paths
//!   outside the folder are common practice) lets a relative or absolute
//!   path go anywhere; regular files and the budget still apply.
//!
//! A refused reference is an error naming the file and the reference.

use super::limits::Budget;
use super::raw::format_err;
use crate::Result;
use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// Where a reference may lead.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scope {
    /// Inside the model's folder only (glTF, COLLADA).
    Folder,
    /// Anywhere the user could read (OBJ's `mtllib`, `map_Kd`).
    Anywhere,
}

/// Finds and reads the files a model names, against the model's budget.
pub struct Resolver<'a> {
    /// The model, as messages name it.
    file: &'a str,
    /// The model's folder; `None` for a model read from memory, whose
    /// references cannot be resolved.
    folder: Option<PathBuf>,
    budget: &'a Budget,
}

impl<'a> Resolver<'a> {
    /// A resolver for the model `file` in `folder`.
    pub(crate) fn new(file: &'a str, folder: Option<PathBuf>, budget: &'a Budget) -> Resolver<'a> {
        Resolver { file, folder, budget }
    }

    /// The file `reference` (as written in `element` of the model, a path
    /// or a relative URI) names, checked for `scope`: the path it stands for
    /// exists and is a regular file, inside the model's folder for
    /// [`Scope::Folder`].
    ///
    /// # Errors
    /// [`crate::Error::Format`] naming the model, the element and the
    /// reference.
    pub(crate) fn resolve(&self, reference: &str, scope: Scope, element: &str) -> Result<PathBuf> {
        let Some(folder) = &self.folder else {
            let shown = crate::error::clean(reference, 60);
            let why = "the model was read from memory, so there is no folder to find it in";
            return Err(format_err(self.file, element, format!("'{shown}': {why}")));
        };
        self.resolve_in(folder, reference, scope, element)
    }

    /// [`Resolver::resolve`] relative to `folder` (the folder of an MTL
    /// library, for its textures) instead of the model's.
    ///
    /// # Errors
    /// As [`Resolver::resolve`].
    pub(crate) fn resolve_in(&self, folder: &Path, reference: &str, scope: Scope, element: &str) -> Result<PathBuf> {
        let shown = crate::error::clean(reference, 60);
        let refuse = |why: &str| format_err(self.file, element, format!("'{shown}': {why}"));
        let path = match scope {
            Scope::Folder => folder.join(confined(reference).map_err(|why| refuse(&why))?),
            Scope::Anywhere if reference.trim().is_empty() => return Err(refuse("names no file")),
            Scope::Anywhere => folder.join(reference.trim()),
        };
        if !path.exists() {
            return Err(refuse("no such file"));
        }
        if scope == Scope::Folder {
            // a link inside the folder must not lead out of it
            let real = path.canonicalize().map_err(|e| refuse(&e.to_string()))?;
            let base = folder.canonicalize().map_err(|e| refuse(&e.to_string()))?;
            if !real.starts_with(&base) {
                return Err(refuse("leads out of the model's folder"));
            }
        }
        Ok(path)
    }

    /// Reads the regular file `path` (from [`Resolver::resolve`]) that
    /// `element` names: at most `declared` bytes when given, within the
    /// budget.
    ///
    /// # Errors
    /// A file that is not regular, cannot be read or is over the budget,
    /// naming the model, the element and the file.
    pub(crate) fn read(&self, path: &Path, declared: Option<u64>, element: &str) -> Result<Vec<u8>> {
        let shown = crate::error::clean(&path.display().to_string(), 60).into_owned();
        let at = format!("{element} ({shown})");
        read_regular(path, declared, self.budget, self.file, &at)
    }

    /// The model's folder (`None` for a model read from memory).
    pub(crate) fn folder(&self) -> Option<&Path> {
        self.folder.as_deref()
    }
}

/// The relative path a URI names inside its folder: percent-decoded, with
/// `\` taken as a separator too; refused when it has a scheme, is absolute
/// or climbs out of the folder with `..`.
fn confined(uri: &str) -> std::result::Result<PathBuf, String> {
    let decoded = percent_decode(uri.trim());
    if decoded.contains('\0') {
        return Err("contains a NUL byte".into());
    }
    let scheme = decoded
        .split_once(':')
        .is_some_and(|(s, _)| !s.is_empty() && s.bytes().all(|b| b.is_ascii_alphanumeric() || b"+-.".contains(&b)));
    if scheme {
        return Err("only relative references inside the model's folder are read (it has a scheme or a drive)".into());
    }
    let unified = decoded.replace('\\', "/");
    let mut out = PathBuf::new();
    let mut depth = 0usize;
    for c in Path::new(&unified).components() {
        match c {
            Component::Normal(p) => {
                out.push(p);
                depth += 1;
            }
            Component::CurDir => {}
            Component::ParentDir if depth > 0 => {
                out.pop();
                depth -= 1;
            }
            Component::ParentDir => return Err("leads out of the model's folder ('..')".into()),
            Component::RootDir | Component::Prefix(_) => return Err("is an absolute path".into()),
        }
    }
    if depth == 0 {
        return Err("names no file".into());
    }
    Ok(out)
}

/// `%20` and friends decoded (invalid sequences kept as they are).
pub(crate) fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        match (b[i], b.get(i + 1).copied().and_then(hex), b.get(i + 2).copied().and_then(hex)) {
            (b'%', Some(h), Some(l)) => {
                out.push((h * 16 + l) as u8);
                i += 3;
            }
            (c, ..) => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Opens `path` for reading without blocking (a FIFO without a writer
/// would block the open).
fn open_nonblocking(path: &Path) -> std::io::Result<std::fs::File> {
    let mut o = std::fs::OpenOptions::new();
    o.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        o.custom_flags(libc::O_NONBLOCK);
    }
    o.open(path)
}

/// Reads the regular file `path` (`at` names it in messages, as part of
/// `file`): at most `declared` bytes, within `budget`.
///
/// # Errors
/// Not a regular file, an I/O error, or over the budget.
pub(crate) fn read_regular(
    path: &Path,
    declared: Option<u64>,
    budget: &Budget,
    file: &str,
    at: &str,
) -> Result<Vec<u8>> {
    let f = open_nonblocking(path).map_err(|e| format_err(file, at, e.to_string()))?;
    let meta = f.metadata().map_err(|e| format_err(file, at, e.to_string()))?;
    if !meta.is_file() {
        return Err(format_err(file, at, "not a regular file (a device, a pipe or a folder is never read)"));
    }
    let len = declared.map_or(meta.len(), |d| d.min(meta.len()));
    budget.take_bytes(len, file, at)?;
    let mut bytes = Vec::with_capacity(len as usize);
    f.take(len).read_to_end(&mut bytes).map_err(|e| format_err(file, at, e.to_string()))?;
    Ok(bytes)
}

/// Reads a file the user named (a model, key paths, a curve, evaluation
/// points): the same rules as the files a model names, a regular file only
/// (a device, a FIFO, a socket or a folder is refused without blocking),
/// its length taken from the budget before anything is read.
///
/// # Errors
/// Not a regular file, an I/O error or over the budget, one line naming
/// the file.
pub(crate) fn read_model(path: &Path, budget: &Budget, file: &str) -> Result<Vec<u8>> {
    if std::fs::metadata(path).is_ok_and(|m| m.is_dir()) {
        return Err(format_err(file, "file", "is a folder, not a file to read"));
    }
    read_regular(path, None, budget, file, "file")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uris_stay_inside_the_folder() {
        assert_eq!(confined("a/b%20c.bin").unwrap(), PathBuf::from("a/b c.bin"));
        assert_eq!(confined("a/../b.bin").unwrap(), PathBuf::from("b.bin"));
        for bad in [
            "../x.bin",
            "%2e%2e/x.bin",
            "a/../../x",
            "/etc/passwd",
            "%2Fetc%2Fpasswd",
            "..\\x",
            "C:/x",
            "file:///x",
            ".",
        ] {
            assert!(confined(bad).is_err(), "{bad}");
        }
    }
}
