//! Opening a USD stage within the reading promise: every layer, reference
//! and payload the stage names is found by [`Confined`] (inside the
//! stage's folder only, regular files only, within the budget), and every
//! call into the `openusd` crate runs under [`guarded`], so a panic in it
//! on hostile bytes becomes one line naming the file.

use crate::io::Input;
use crate::io::limits::Budget;
use crate::io::raw::format_err;
use crate::{Error, Result};
use openusd::ar::{self, Asset, ResolvedPath};
use std::cell::{Cell, RefCell};
use std::io::{Cursor, Read};
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// What the resolver shares with the reader: the root layer's bytes, the
/// folder, the budget of the files it reads and the first refusal.
struct Shared {
    /// The file as messages name it.
    file: String,
    /// The canonical folder of the stage; `None` for a stage read from memory.
    folder: Option<PathBuf>,
    /// The root layer's identifier (its bytes are `root`, already read).
    root_id: String,
    root: Vec<u8>,
    budget: Budget,
    /// Layers opened (each open counts against `node-visits`).
    opens: Cell<u64>,
    /// Why the first reference was refused.
    refused: RefCell<Option<Error>>,
}

/// The resolver of a stage's layers: the root from memory, every other
/// layer inside the root's folder (after following links), read through
/// [`crate::io::resolve`]'s regular-file reader within the budget.
#[derive(Clone)]
pub(super) struct Confined(Rc<Shared>);

impl Confined {
    /// The resolver of the stage `input` holds, in `folder`.
    pub(super) fn new(input: &Input, folder: Option<&Path>) -> Confined {
        let budget = Budget::new(*input.budget.limits());
        // the root's bytes were taken by the read already; count them here too
        let _ = budget.take_bytes(input.bytes.len() as u64, input.file, "file");
        let folder = folder.and_then(|f| f.canonicalize().ok());
        let name = Path::new(input.file).file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let ext = match input.bytes {
            b if b.starts_with(openusd::usdc::MAGIC) => "usdc",
            b if b.starts_with(b"PK") => "usdz",
            _ => "usda",
        };
        let name = if name.to_ascii_lowercase().ends_with(&format!(".{ext}")) { name } else { format!("{name}.{ext}") };
        let base = folder.clone().unwrap_or_else(|| PathBuf::from("/nonexistent-memory-stage"));
        Confined(Rc::new(Shared {
            file: input.file.to_string(),
            folder,
            root_id: base.join(name).to_string_lossy().into_owned(),
            root: input.bytes.to_vec(),
            budget,
            opens: Cell::new(0),
            refused: RefCell::new(None),
        }))
    }

    /// The identifier the stage is opened by.
    pub(super) fn root_id(&self) -> &str {
        &self.0.root_id
    }

    /// The first reference refused, if any: the error of the whole read.
    pub(super) fn refusal(&self) -> Option<Error> {
        self.0.refused.borrow_mut().take()
    }

    /// Records `why` `reference` is refused (the first one is reported).
    fn refuse(&self, reference: &str, why: &str) {
        let mut r = self.0.refused.borrow_mut();
        if r.is_none() {
            let shown = crate::error::clean(reference, 80);
            *r = Some(format_err(&self.0.file, "layer", format!("'{shown}': {why}")));
        }
    }

    /// Records an error (over the budget) as the refusal and gives it back
    /// as an I/O error for the crate.
    fn fail(&self, e: Error) -> std::io::Error {
        let msg = e.to_string();
        let mut r = self.0.refused.borrow_mut();
        if r.is_none() {
            *r = Some(e);
        }
        std::io::Error::other(msg)
    }

    /// The plain file `id` names, when it lies inside the folder.
    fn confine(&self, id: &str) -> Option<PathBuf> {
        let Some(folder) = &self.0.folder else {
            self.refuse(id, "the stage was read from memory, so there is no folder to find it in");
            return None;
        };
        let path = Path::new(id);
        let Ok(real) = path.canonicalize() else {
            self.refuse(id, "no such file");
            return None;
        };
        if !real.starts_with(folder) {
            self.refuse(id, "leads out of the stage's folder");
            return None;
        }
        if !real.is_file() {
            self.refuse(id, "not a regular file");
            return None;
        }
        Some(real)
    }

    /// The bytes of the layer or package at `path` (the root from memory).
    fn bytes_of(&self, path: &str) -> std::io::Result<Vec<u8>> {
        let s = &self.0;
        let opens = s.opens.get() + 1;
        s.opens.set(opens);
        if let Err(e) = s.budget.check("node-visits", opens, &s.file, "layers opened") {
            return Err(self.fail(e));
        }
        if path == s.root_id {
            return Ok(s.root.clone());
        }
        let real = self.confine(path).ok_or_else(|| std::io::Error::other("refused"))?;
        let at = format!("layer ({})", crate::error::clean(path, 60));
        crate::io::resolve::read_regular(&real, None, &s.budget, &s.file, &at).map_err(|e| self.fail(e))
    }

    /// The entry `inner` of the package at `package`, within the budget.
    fn entry_of(&self, package: &str, inner: &str) -> std::io::Result<Vec<u8>> {
        let bytes = self.bytes_of(package)?;
        let mut zip = zip::ZipArchive::new(Cursor::new(bytes)).map_err(std::io::Error::other)?;
        let mut entry = zip.by_name(inner).map_err(std::io::Error::other)?;
        let at = format!("package entry '{}'", crate::error::clean(inner, 60));
        self.0.budget.take_bytes(entry.size(), &self.0.file, &at).map_err(|e| self.fail(e))?;
        let mut out = Vec::new();
        let size = entry.size();
        entry.by_ref().take(size).read_to_end(&mut out)?;
        Ok(out)
    }
}

impl ar::Resolver for Confined {
    fn create_identifier(&self, asset_path: &str, anchor: Option<&ResolvedPath>) -> String {
        if asset_path == self.0.root_id {
            return asset_path.to_string();
        }
        ar::DefaultResolver::new().create_identifier(asset_path, anchor)
    }

    fn resolve(&self, asset_path: &str) -> Option<ResolvedPath> {
        if asset_path == self.0.root_id {
            return Some(ResolvedPath::new(asset_path));
        }
        if ar::is_package_relative_path(asset_path) {
            let (package, inner) = ar::split_package_relative_path_outer(asset_path)?;
            let package = self.resolve(&package)?;
            return Some(ResolvedPath::new(ar::join_package_relative_path(&package.to_string_lossy(), &inner)));
        }
        self.confine(asset_path).map(ResolvedPath::new)
    }

    fn resolve_for_new_asset(&self, _asset_path: &str) -> Option<ResolvedPath> {
        None
    }

    fn open_asset(&self, resolved: &ResolvedPath) -> std::io::Result<Box<dyn Asset>> {
        let path = resolved.to_string_lossy();
        let bytes = match ar::split_package_relative_path_outer(&path) {
            Some((package, inner)) if ar::is_package_relative_path(&path) => self.entry_of(&package, &inner)?,
            _ => self.bytes_of(&path)?,
        };
        if bytes.starts_with(openusd::usdc::MAGIC) {
            let name = crate::error::clean(&path, 60).into_owned();
            check_crate(&bytes, &format!("{}: layer {name}", self.0.file)).map_err(|e| self.fail(e))?;
        }
        Ok(Box::new(Cursor::new(bytes)))
    }

    fn get_modification_timestamp(&self, _: &str, _: &ResolvedPath) -> Option<std::time::SystemTime> {
        None
    }

    fn identity(&self) -> String {
        "subdiv-confined".into()
    }
}

thread_local! {
    /// Whether this thread is inside [`guarded`] (its panics are caught and
    /// reported as one line, so the hook stays quiet).
    static QUIET: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f` (calls into the `openusd` crate on `file`'s bytes), turning a
/// panic into one line naming the file; the panic's message is not printed.
///
/// # Errors
/// `f`'s own, or [`Error::Format`] for a panic.
pub(super) fn guarded<T>(file: &str, f: impl FnOnce() -> Result<T>) -> Result<T> {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
    let was = QUIET.with(|q| q.replace(true));
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
    QUIET.with(|q| q.set(was));
    outcome.unwrap_or_else(|p| {
        let what = p
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| p.downcast_ref::<String>().cloned())
            .unwrap_or_default();
        Err(format_err(
            file,
            "stage",
            format!("not a stage the USD reader can read ({})", crate::error::clean(&what, 120)),
        ))
    })
}

/// Checks a crate file's (`.usdc`) frame before the `openusd` crate reads
/// it: the magic, a table of contents inside the file, and every section
/// it lists inside the file, so a truncated or garbage file is refused here.
///
/// # Errors
/// [`Error::Format`] naming `file` and what is wrong.
pub(super) fn check_crate(bytes: &[u8], file: &str) -> Result<()> {
    let bad = |msg: String| Err(format_err(file, "crate file", msg));
    let u64_at = |at: usize| -> Option<u64> {
        let b = bytes.get(at..at.checked_add(8)?)?;
        Some(u64::from_le_bytes(b.try_into().ok()?))
    };
    if bytes.len() < 88 || !bytes.starts_with(openusd::usdc::MAGIC) {
        return bad(format!("{} bytes, not a USD crate file (no PXR-USDC header)", bytes.len()));
    }
    let n = bytes.len() as u64;
    let Some(toc) = u64_at(16).filter(|&t| t.checked_add(8).is_some_and(|e| e <= n)) else {
        return bad(format!("its table of contents lies outside its {n} bytes (truncated?)"));
    };
    let count = u64_at(toc as usize).unwrap_or(u64::MAX);
    // a section record is a 16-byte name and two u64s
    if count > (n - toc - 8) / 32 {
        return bad(format!("its table of contents claims {count} sections, more than its bytes hold (truncated?)"));
    }
    for k in 0..count as usize {
        let at = toc as usize + 8 + 32 * k;
        let (start, size) = (u64_at(at + 16).unwrap_or(u64::MAX), u64_at(at + 24).unwrap_or(u64::MAX));
        if start.checked_add(size).is_none_or(|e| e > n) {
            return bad(format!("section {k} ({start} + {size} bytes) lies outside its {n} bytes (truncated?)"));
        }
    }
    Ok(())
}
