//! The `.paths` text format (docs/design.md §7):
//!
//! ```text
//! # comment
//! paths <vertex count> <keys per vertex>
//! x y z        keys of vertex 0, in order (a closed polygon)
//! ...          then the keys of vertex 1, and so on
//! ```
//! The reader names the line of every problem and checks the counts against
//! the header before allocating; [`Paths::check_model`] checks the vertex
//! count against the model.

use crate::io::{Limits, atomic_write};
use crate::{Error, Mesh, Result};
use glam::Vec3;
use std::io::Write;
use std::path::Path;

/// Key polygons, one per control vertex.
#[derive(Clone, Debug, PartialEq)]
pub struct Paths {
    /// Keys per vertex (`K`).
    pub keys_per_vertex: usize,
    /// `keys[v * K + k]`: key `k` of vertex `v`.
    pub keys: Vec<Vec3>,
}

impl Paths {
    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.keys.len().checked_div(self.keys_per_vertex).unwrap_or(0)
    }
    /// The key polygon of vertex `v`.
    pub fn polygon(&self, v: usize) -> &[Vec3] {
        &self.keys[v * self.keys_per_vertex..(v + 1) * self.keys_per_vertex]
    }

    /// Parses `.paths` text; `file` names the source in errors.
    ///
    /// # Errors
    /// [`Error::Parse`] naming the line: a missing or malformed header, a bad
    /// number, a non-finite coordinate, too few or too many key lines.
    pub fn parse(text: &str, file: &str) -> Result<Paths> {
        let err = |line: usize, msg: String| Error::Parse { file: file.to_string(), line, msg };
        let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l.split('#').next().unwrap_or("").trim()));
        let mut lines = lines.by_ref().filter(|(_, l)| !l.is_empty());
        let Some((hl, header)) = lines.next() else {
            return Err(err(1, "empty file: expected 'paths <vertex count> <keys per vertex>'".into()));
        };
        let h: Vec<&str> = header.split_ascii_whitespace().collect();
        if h.len() != 3 || h[0] != "paths" {
            return Err(err(hl, format!("expected 'paths <vertex count> <keys per vertex>', found '{header}'")));
        }
        let nv: usize = h[1].parse().map_err(|_| err(hl, format!("bad vertex count '{}'", h[1])))?;
        let k: usize = h[2].parse().map_err(|_| err(hl, format!("bad key count '{}'", h[2])))?;
        if k == 0 || nv == 0 {
            return Err(err(hl, "vertex and key counts must be at least 1".into()));
        }
        let total = nv.checked_mul(k).filter(|&t| t <= text.len() / 6 + 1).ok_or_else(|| {
            err(hl, format!("header claims {nv} x {k} keys, more than the file's {} bytes can hold", text.len()))
        })?;
        let mut keys = Vec::with_capacity(total);
        let mut last = hl;
        for (ln, l) in lines {
            last = ln;
            if keys.len() == total {
                return Err(err(ln, format!("more key lines than the header's {nv} vertices x {k} keys")));
            }
            let t: Vec<&str> = l.split_ascii_whitespace().collect();
            if t.len() != 3 {
                return Err(err(ln, format!("expected 'x y z', found {} values", t.len())));
            }
            let mut xyz = [0f32; 3];
            for (slot, s) in xyz.iter_mut().zip(&t) {
                *slot = s.parse().map_err(|_| err(ln, format!("'{s}' is not a number")))?;
                if !slot.is_finite() {
                    return Err(err(ln, format!("non-finite coordinate '{s}'")));
                }
            }
            keys.push(Vec3::from_array(xyz));
        }
        if keys.len() != total {
            return Err(err(
                last,
                format!(
                    "file ends after {} key lines; the header promises {nv} vertices x {k} keys = {total} (vertex {} has only {} keys)",
                    keys.len(),
                    keys.len() / k,
                    keys.len() % k
                ),
            ));
        }
        Ok(Paths { keys_per_vertex: k, keys })
    }

    /// Loads a `.paths` file through the reading pipeline
    /// ([`crate::io::read_text_file`]): a regular file within `limits`.
    ///
    /// # Errors
    /// As `crate::io::read_file` and [`Paths::parse`].
    pub fn load(path: &Path, limits: &Limits) -> Result<Paths> {
        let text = crate::io::read_text_file(path, limits)?;
        Self::parse(&text, &path.display().to_string())
    }

    /// Writes `.paths` text.
    ///
    /// # Errors
    /// I/O errors.
    pub(crate) fn write(&self, w: &mut dyn Write) -> std::io::Result<()> {
        writeln!(w, "paths {} {}", self.vertex_count(), self.keys_per_vertex)?;
        for (i, p) in self.keys.iter().enumerate() {
            if i % self.keys_per_vertex == 0 {
                writeln!(w, "# vertex {}", i / self.keys_per_vertex)?;
            }
            writeln!(w, "{} {} {}", p.x, p.y, p.z)?;
        }
        Ok(())
    }

    /// Saves a `.paths` file atomically.
    ///
    /// # Errors
    /// I/O errors naming the file.
    pub(crate) fn save(&self, path: &Path) -> Result<()> {
        atomic_write(path, |w| self.write(w).map_err(|e| Error::io(path, e)))
    }

    /// Checks that the paths fit `mesh` (one polygon per vertex).
    ///
    /// # Errors
    /// [`Error::CountMismatch`] naming both counts.
    pub fn check_model(&self, mesh: &Mesh, file: &str) -> Result<()> {
        if self.vertex_count() != mesh.positions.len() {
            return Err(Error::CountMismatch {
                what: format!("{file}: paths for the model"),
                unit: "vertices",
                expected: mesh.positions.len(),
                found: self.vertex_count(),
            });
        }
        Ok(())
    }

    /// A generated animation for any model: each vertex swings on a small
    /// closed loop (radius 6% of the bounding-box diagonal) around its rest
    /// position, along its normal and a tangent, with a phase that travels
    /// across the model, so every model can be animated.
    pub fn generated(mesh: &Mesh, keys: usize) -> Paths {
        let keys = keys.max(3);
        let (lo, hi) = mesh.bounds();
        let diag = (hi - lo).length().max(1e-6);
        let r = 0.06 * diag;
        let normals = mesh.vertex_normals();
        let mut out = Vec::with_capacity(mesh.positions.len() * keys);
        for (p, n) in mesh.positions.iter().zip(&normals) {
            let t = n.any_orthonormal_vector();
            let phase = std::f32::consts::TAU * ((*p - lo).dot(Vec3::new(0.7, 0.5, 0.3)) / diag);
            for k in 0..keys {
                let a = std::f32::consts::TAU * k as f32 / keys as f32 + phase;
                out.push(*p + *n * (r * a.sin()) + t * (0.5 * r * a.cos()));
            }
        }
        Paths { keys_per_vertex: keys, keys: out }
    }

    /// The frames of a sampled animation (a USD stage's time samples: each
    /// frame one position per vertex, all of one count) as keys: vertex
    /// `v`'s key `k` is its position in frame `k`. `None` for fewer than
    /// two frames or frames of different counts.
    pub fn of_frames(frames: &[Vec<Vec3>]) -> Option<Paths> {
        let n = frames.first()?.len();
        if frames.len() < 2 || frames.iter().any(|f| f.len() != n) {
            return None;
        }
        let keys = (0..n).flat_map(|v| frames.iter().map(move |f| f[v])).collect();
        Some(Paths { keys_per_vertex: frames.len(), keys })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_errors() {
        let p = Paths { keys_per_vertex: 2, keys: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(0.5, -1.25, 3.0)] };
        let mut buf = Vec::new();
        p.write(&mut buf).unwrap();
        let q = Paths::parse(std::str::from_utf8(&buf).unwrap(), "t").unwrap();
        assert_eq!(p, q);
        let e = Paths::parse("paths 2 2\n0 0 0\n1 0 0\n0 1 0\n", "short.paths").unwrap_err();
        assert!(matches!(e, Error::Parse { line: 4, .. }), "{e}");
        assert!(e.to_string().contains("vertex 1 has only 1 keys"), "{e}");
        let e = Paths::parse("# c\npaths 1 2\n0 0 0\n1 x 0\n", "bad.paths").unwrap_err();
        assert!(matches!(e, Error::Parse { line: 4, .. }), "{e}");
        let e = Paths::parse("paths 1 1\n0 0 0\n1 1 1\n", "long.paths").unwrap_err();
        assert!(matches!(e, Error::Parse { line: 3, .. }), "{e}");
        let e = Paths::parse("path 1 1\n", "hdr.paths").unwrap_err();
        assert!(matches!(e, Error::Parse { line: 1, .. }), "{e}");
        let e = Paths::parse("paths 1000000000000 1000000\n", "huge.paths").unwrap_err();
        assert!(e.to_string().contains("more than the file"), "{e}");
        let e = Paths::parse("paths 1 1\n0 inf 0\n", "inf.paths").unwrap_err();
        assert!(matches!(e, Error::Parse { line: 2, .. }), "{e}");
    }
}
