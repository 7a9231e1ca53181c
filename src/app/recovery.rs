//! Where the unsaved edits of a session go while it runs, so that a crash,
//! a kill or a closed tab loses nothing: one OBJ copy of the control mesh
//! per model, named by the FNV-1a hash of the model's absolute path (the
//! same model finds its copy again in any later session). On the desktop
//! the copies are files in the user's state folder; in the browser they are
//! entries of the page's local storage.

use crate::Mesh;
use crate::mesh::attributes::Attributes;
use std::path::{Path, PathBuf};

/// A store of recovery copies.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Recovery {
    /// A folder of `<hash>.obj` files.
    #[cfg_attr(target_arch = "wasm32", allow(dead_code))]
    Folder(PathBuf),
    /// The page's `localStorage`, keys `subdiv-recovery-<hash>`.
    #[cfg(target_arch = "wasm32")]
    Page,
}

/// The name a model's copy goes by: the hash of its absolute path (or of
/// the built-in model's name).
fn key(model: Option<&Path>) -> String {
    let key = match model {
        Some(p) => std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf()).to_string_lossy().into_owned(),
        None => super::doc::BUILTIN_NAME.to_string(),
    };
    let hash = key.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3));
    format!("{hash:016x}")
}

/// The recovery file of the model at `path` (or the built-in one) in `dir`.
pub(crate) fn recovery_file(dir: &Path, model: Option<&Path>) -> PathBuf {
    dir.join(format!("{}.obj", key(model)))
}

/// The control mesh as OBJ text in memory (the page's store and its
/// downloads: no files there).
#[cfg(target_arch = "wasm32")]
pub(crate) fn obj_bytes(mesh: &Mesh, attrs: &Attributes) -> crate::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    crate::io::obj::write_obj_with(mesh, attrs, &mut |b| {
        bytes.extend_from_slice(b);
        Ok(())
    })?;
    Ok(bytes)
}

impl Recovery {
    /// The user's store: `$XDG_STATE_HOME/subdiv/recovery` (else
    /// `~/.local/state/...`, `%LOCALAPPDATA%` on Windows), or the page's
    /// storage in the browser. `None` where there is none.
    pub(crate) fn for_user() -> Option<Recovery> {
        #[cfg(target_arch = "wasm32")]
        return Some(Recovery::Page);
        #[cfg(not(target_arch = "wasm32"))]
        {
            let env = |k: &str| std::env::var_os(k).filter(|v| !v.is_empty()).map(PathBuf::from);
            let state = env("XDG_STATE_HOME")
                .or_else(|| env("LOCALAPPDATA"))
                .or_else(|| env("HOME").map(|h| h.join(".local").join("state")));
            state.map(|d| Recovery::Folder(d.join("subdiv").join("recovery")))
        }
    }

    /// Writes the copy of `model`'s control mesh.
    ///
    /// # Errors
    /// When the folder or the storage refuses it (full, not allowed).
    pub(crate) fn write(&self, model: Option<&Path>, mesh: &Mesh, attrs: &Attributes) -> crate::Result<()> {
        match self {
            Recovery::Folder(dir) => std::fs::create_dir_all(dir)
                .map_err(|e| crate::Error::io(dir, e))
                .and_then(|()| crate::io::save_with(&recovery_file(dir, model), mesh, attrs)),
            #[cfg(target_arch = "wasm32")]
            Recovery::Page => {
                let text = obj_bytes(mesh, attrs)?;
                let text = String::from_utf8_lossy(&text);
                super::page::storage_set(&format!("subdiv-recovery-{}", key(model)), &text)
            }
        }
    }

    /// Removes the copy of `model` (nothing when there is none).
    pub(crate) fn remove(&self, model: Option<&Path>) {
        match self {
            Recovery::Folder(dir) => _ = std::fs::remove_file(recovery_file(dir, model)),
            #[cfg(target_arch = "wasm32")]
            Recovery::Page => super::page::storage_remove(&format!("subdiv-recovery-{}", key(model))),
        }
    }

    /// Whether there is a copy of `model`.
    pub(crate) fn exists(&self, model: Option<&Path>) -> bool {
        match self {
            Recovery::Folder(dir) => recovery_file(dir, model).is_file(),
            #[cfg(target_arch = "wasm32")]
            Recovery::Page => super::page::storage_get(&format!("subdiv-recovery-{}", key(model))).is_some(),
        }
    }

    /// The copy of `model`, read, when there is one.
    pub(crate) fn read(&self, model: Option<&Path>) -> Option<crate::Result<Mesh>> {
        let opts = crate::io::ReadOptions::default();
        match self {
            Recovery::Folder(dir) => {
                let file = recovery_file(dir, model);
                file.is_file().then(|| crate::io::read(crate::io::Source::File(&file), &opts).map(|l| l.mesh))
            }
            #[cfg(target_arch = "wasm32")]
            Recovery::Page => {
                let text = super::page::storage_get(&format!("subdiv-recovery-{}", key(model)))?;
                let source = crate::io::Source::Bytes { bytes: text.as_bytes(), name: "recovered.obj", folder: None };
                Some(crate::io::read(source, &opts).map(|l| l.mesh))
            }
        }
    }
}
