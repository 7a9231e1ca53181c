//! Authoring the animation: the key positions the split-and-tweak paths
//! run through, recorded from the cage as it is shaped. `I` inserts a key:
//! the selected control vertices' current positions (every vertex's when
//! none is selected; the others hold their last key). A key can be set
//! again from the cage or deleted, the keys are saved as a `.paths` file
//! the command line's `animate` reads, and every change is a step of the
//! history.

use super::doc::{Doc, Problem};
use super::edit::Step;
use crate::anim::paths::Paths;
use glam::Vec3;
use std::path::Path;

/// What the Animation section's key rows ask for.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum KeyAction {
    /// Append a key from the cage (`I`).
    Insert,
    /// Key `k` again from the cage.
    Set(usize),
    /// Remove key `k` (at least one stays).
    Delete(usize),
    /// Write the keys as a `.paths` file.
    Save(std::path::PathBuf),
}

/// `paths` with key `at` (`None`: a new last key) taken from `cage` for
/// the vertices `ids` (all when empty); the other vertices keep theirs (a
/// new key: their last one).
fn keyed(paths: &Paths, cage: &[Vec3], ids: &[u32], at: Option<usize>) -> Paths {
    let k = paths.keys_per_vertex;
    let new = at.is_none();
    let kk = if new { k + 1 } else { k };
    let take = |v: usize| ids.is_empty() || ids.binary_search(&(v as u32)).is_ok();
    let mut keys = Vec::with_capacity(cage.len() * kk);
    for (v, &p) in cage.iter().enumerate() {
        let poly = paths.polygon(v);
        keys.extend_from_slice(poly);
        if new {
            keys.push(if take(v) { p } else { poly[k - 1] });
        } else if let Some(i) = at.filter(|_| take(v)) {
            keys[v * kk + i] = p;
        }
    }
    Paths { keys_per_vertex: kk, keys }
}

/// `paths` without key `at`.
fn without(paths: &Paths, at: usize) -> Paths {
    let k = paths.keys_per_vertex;
    let keys = paths
        .keys
        .chunks_exact(k)
        .flat_map(|poly| poly.iter().enumerate().filter(|(i, _)| *i != at).map(|(_, p)| *p))
        .collect();
    Paths { keys_per_vertex: k - 1, keys }
}

impl Doc {
    /// Carries out a key action.
    pub(crate) fn key(&mut self, action: KeyAction) {
        let paths = &self.anim.paths;
        let cage = &self.model.control.mesh.positions;
        if paths.vertex_count() != cage.len() {
            return self.fail(Problem::Other(crate::Error::Usage("the paths are not this cage's".into())));
        }
        let k = paths.keys_per_vertex;
        let next = match action {
            KeyAction::Insert => keyed(paths, cage, &self.edit.selected, None),
            KeyAction::Set(i) if i < k => keyed(paths, cage, &self.edit.selected, Some(i)),
            KeyAction::Delete(i) if i < k && k > 1 => without(paths, i),
            KeyAction::Save(path) => return self.save_paths(&path),
            _ => return,
        };
        let what = match action {
            KeyAction::Insert => format!("insert key {}", k + 1),
            KeyAction::Set(i) => format!("set key {}", i + 1),
            _ => "delete a key".to_string(),
        };
        let before = self.anim.paths.clone();
        self.install_paths(next.clone());
        self.edit.history.push_step(Step::Paths { what, before: Box::new(before), after: Box::new(next) });
    }

    /// Makes `paths` the animation's (rebuilt if it plays).
    pub(crate) fn install_paths(&mut self, paths: Paths) {
        self.anim.paths = paths;
        self.anim.paths_source = "edited in the viewer".into();
        if self.anim.active {
            self.request_animation();
        }
    }

    fn save_paths(&mut self, path: &Path) {
        match self.anim.paths.save(path) {
            Ok(()) => {
                self.anim.paths_source = path.display().to_string();
                self.status.notice = Some(format!("saved {}", path.display()));
            }
            Err(e) => self.fail(Problem::Other(e)),
        }
    }
}
