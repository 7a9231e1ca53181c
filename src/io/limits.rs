//! The budget of one read. Everything a file can make us read or allocate
//! is counted against one [`Limits`]: the bytes of each file and of all of
//! them, the vertices and faces it may make us hold (counted as they are
//! emitted, so glTF instancing cannot multiply past them), the corners of
//! one polygon, distinct materials, MTL libraries, the pixels of a texture
//! after decoding, glTF node visits, and the length of a message line. A
//! count is checked before the memory it implies is allocated; over budget
//! the read stops with [`Error::Format`] naming the file, the element and
//! the limit, which the caller may raise (`--limit NAME=VALUE` on the
//! command line, the fields here in the API).

use crate::{Error, Result};
use std::cell::Cell;

/// The most a read may consume. [`Limits::default`] scales with the memory
/// the machine has free; every field can be set by the caller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// Bytes read from any one file (the model, an MTL library, a glTF
    /// buffer, a texture).
    pub file_bytes: u64,
    /// Bytes read in all for one model, the files it names included.
    pub total_bytes: u64,
    /// Vertices a file may make us hold, counted as they are read (glTF
    /// instances each count).
    pub vertices: u64,
    /// Faces a file may make us hold, counted as they are read (polygons;
    /// glTF instances each count).
    pub faces: u64,
    /// Corners of one polygon.
    pub face_size: u64,
    /// Distinct material names (`usemtl`, glTF materials).
    pub materials: u64,
    /// MTL libraries read (each distinct library is read once).
    pub libraries: u64,
    /// Pixels of one texture (decoded to 4 bytes a pixel).
    pub texture_pixels: u64,
    /// glTF node visits (a node reached along two paths counts twice).
    pub node_visits: u64,
    /// Characters of one error or warning line.
    pub message_chars: u64,
}

/// What each limit is called by [`Limits::set`] and in messages, with a
/// one-line description (`subdiv --help` lists them).
pub const LIMIT_NAMES: &[(&str, &str)] = &[
    ("file-bytes", "bytes read from any one file"),
    ("total-bytes", "bytes read in all for one model"),
    ("vertices", "vertices a file may make us hold"),
    ("faces", "faces a file may make us hold"),
    ("face-size", "corners of one polygon"),
    ("materials", "distinct material names"),
    ("libraries", "MTL libraries read"),
    ("texture-pixels", "pixels of one texture"),
    ("node-visits", "glTF node visits"),
    ("message-chars", "characters of one error or warning line"),
];

/// Bytes a vertex and a face of a file cost us until the corner table is
/// built (positions, the V table, the O table being built, scratch).
const BYTES_PER_VERTEX: u64 = 48;
const BYTES_PER_FACE: u64 = 96;

impl Limits {
    /// Limits for a machine with `memory` bytes to give: a file may make us
    /// hold about half of it, one file be at most a quarter of it.
    pub fn for_memory(memory: u64) -> Limits {
        let memory = memory.max(64 << 20);
        Limits {
            file_bytes: memory / 4,
            total_bytes: memory / 2,
            vertices: (memory / 2 / BYTES_PER_VERTEX).min(u64::from(u32::MAX) - 1),
            faces: (memory / 2 / BYTES_PER_FACE).min(u64::from(u32::MAX / 3)),
            face_size: 1 << 16,
            materials: 1 << 20,
            libraries: 64,
            // 8192 x 8192 at most: what a GPU texture holds
            texture_pixels: (memory / 64).min(1 << 26),
            node_visits: 1 << 20,
            message_chars: 300,
        }
    }

    /// The limit called `name` (see [`LIMIT_NAMES`]).
    pub fn get(&self, name: &str) -> Option<u64> {
        Some(match name {
            "file-bytes" => self.file_bytes,
            "total-bytes" => self.total_bytes,
            "vertices" => self.vertices,
            "faces" => self.faces,
            "face-size" => self.face_size,
            "materials" => self.materials,
            "libraries" => self.libraries,
            "texture-pixels" => self.texture_pixels,
            "node-visits" => self.node_visits,
            "message-chars" => self.message_chars,
            _ => return None,
        })
    }

    /// Sets the limit called `name` (see [`LIMIT_NAMES`]).
    ///
    /// # Errors
    /// [`Error::Usage`] for an unknown name.
    pub fn set(&mut self, name: &str, value: u64) -> Result<()> {
        let slot = match name {
            "file-bytes" => &mut self.file_bytes,
            "total-bytes" => &mut self.total_bytes,
            "vertices" => &mut self.vertices,
            "faces" => &mut self.faces,
            "face-size" => &mut self.face_size,
            "materials" => &mut self.materials,
            "libraries" => &mut self.libraries,
            "texture-pixels" => &mut self.texture_pixels,
            "node-visits" => &mut self.node_visits,
            "message-chars" => &mut self.message_chars,
            _ => {
                let known: Vec<&str> = LIMIT_NAMES.iter().map(|(n, _)| *n).collect();
                return Err(Error::Usage(format!("unknown limit '{name}' (known: {})", known.join(", "))));
            }
        };
        *slot = value;
        Ok(())
    }
}

impl Default for Limits {
    /// [`Limits::for_memory`] of 80% of the memory available now (8 GiB
    /// where that cannot be read).
    fn default() -> Limits {
        Limits::for_memory(crate::mem::default_memory_limit().unwrap_or(8 << 30))
    }
}

/// The running totals of one read against its [`Limits`]. Readers take
/// from it through `&Budget` (one read runs on one thread).
#[derive(Debug)]
pub struct Budget {
    limits: Limits,
    bytes: Cell<u64>,
    vertices: Cell<u64>,
    faces: Cell<u64>,
    libraries: Cell<u64>,
}

impl Budget {
    /// A fresh budget of `limits`.
    pub fn new(limits: Limits) -> Budget {
        Budget { limits, bytes: Cell::new(0), vertices: Cell::new(0), faces: Cell::new(0), libraries: Cell::new(0) }
    }

    /// The limits it counts against.
    pub(crate) fn limits(&self) -> &Limits {
        &self.limits
    }

    /// Checks that `n` of what `name` limits fits in one piece (a file's
    /// size, a polygon's corners, a texture's pixels), without taking it.
    ///
    /// # Errors
    /// [`Error::Format`] on `file` at `element`, naming the limit.
    pub(crate) fn check(&self, name: &str, n: u64, file: &str, element: &str) -> Result<()> {
        let limit = self.limits.get(name).unwrap_or(u64::MAX);
        let name = LIMIT_NAMES.iter().find(|(n, _)| *n == name).map_or("", |(n, _)| n);
        if n > limit {
            return Err(over(file, element, name, n, limit));
        }
        Ok(())
    }

    /// Takes `n` bytes read for `element` of `file` (the file itself, or a
    /// file it names), checking that one file's size too.
    ///
    /// # Errors
    /// Over `file-bytes` or `total-bytes`.
    pub(crate) fn take_bytes(&self, n: u64, file: &str, element: &str) -> Result<()> {
        self.check("file-bytes", n, file, element)?;
        take(&self.bytes, n, self.limits.total_bytes, file, element, "total-bytes")
    }

    /// Takes `n` more vertices emitted by `element` of `file`.
    ///
    /// # Errors
    /// Over `vertices`.
    pub(crate) fn take_vertices(&self, n: u64, file: &str, element: &str) -> Result<()> {
        take(&self.vertices, n, self.limits.vertices, file, element, "vertices")
    }

    /// Takes `n` more faces emitted by `element` of `file`.
    ///
    /// # Errors
    /// Over `faces`.
    pub(crate) fn take_faces(&self, n: u64, file: &str, element: &str) -> Result<()> {
        take(&self.faces, n, self.limits.faces, file, element, "faces")
    }

    /// Takes one more MTL library, named by `element` of `file`.
    ///
    /// # Errors
    /// Over `libraries`.
    pub(crate) fn take_library(&self, file: &str, element: &str) -> Result<()> {
        take(&self.libraries, 1, self.limits.libraries, file, element, "libraries")
    }
}

/// Adds `n` to `total`, refusing past `limit`.
fn take(total: &Cell<u64>, n: u64, limit: u64, file: &str, element: &str, name: &'static str) -> Result<()> {
    let t = total.get().saturating_add(n);
    if t > limit {
        return Err(over(file, element, name, t, limit));
    }
    total.set(t);
    Ok(())
}

/// The error of a count over its limit.
fn over(file: &str, element: &str, name: &'static str, n: u64, limit: u64) -> Error {
    Error::OverBudget { file: file.to_string(), element: element.to_string(), limit: name, value: n, max: limit }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_named_limit_can_be_read_and_set() {
        let mut l = Limits::for_memory(1 << 30);
        for (k, (name, _)) in LIMIT_NAMES.iter().enumerate() {
            l.set(name, 1000 + k as u64).unwrap();
            assert_eq!(l.get(name), Some(1000 + k as u64), "{name}");
        }
        assert!(l.set("nonsense", 1).is_err());
    }

    #[test]
    fn a_budget_refuses_past_its_totals_and_names_the_limit() {
        let b = Budget::new(Limits { faces: 10, ..Limits::for_memory(1 << 30) });
        b.take_faces(6, "a.obj", "line 3").unwrap();
        let e = b.take_faces(5, "a.obj", "line 9").unwrap_err().to_string();
        assert!(e.starts_with("a.obj: line 9:") && e.contains("faces limit of 10"), "{e}");
        // what was refused was not taken
        b.take_faces(4, "a.obj", "line 10").unwrap();
    }
}
