//! What every reader of an indexed format produces before validation: a
//! triangle list with optional per-corner texture coordinates and per-vertex
//! colours, built into a [`Mesh`] (or repaired into one) in one place, with
//! errors naming the file. Also the guards shared by the binary readers:
//! counts checked against the bytes that remain before anything is
//! allocated.

use crate::mesh::Mesh;
use crate::mesh::attributes::Attributes;
use crate::mesh::repair::{RepairReport, repair};
use crate::{Error, Result};
use glam::{Vec2, Vec3};

/// A triangle list as read, before validation.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RawMesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Three vertex indices per triangle, counter-clockwise seen from outside.
    pub triangles: Vec<u32>,
    /// Texture coordinates, one per corner (three per triangle).
    pub uv: Option<Vec<Vec2>>,
    /// Linear RGB colours in [0, 1], one per vertex.
    pub colors: Option<Vec<Vec3>>,
    /// Material id of each triangle (into the file's material list), if any.
    pub materials: Option<Vec<u32>>,
}

impl RawMesh {
    /// Validates into a mesh with its attributes; unreferenced vertices are
    /// dropped (their colours with them).
    ///
    /// # Errors
    /// [`Error::Mesh`] naming `file` (vertex ids 0-based, as stored).
    pub fn build(self, file: &str) -> Result<(Mesh, Attributes)> {
        let RawMesh { positions, triangles, uv, colors, .. } = self;
        let used = colors.as_ref().map(|_| used_vertices(positions.len(), &triangles));
        let mesh = Mesh::from_triangles(positions, &triangles).map_err(|source| Error::Mesh {
            file: file.to_string(),
            line: None,
            source,
        })?;
        let colors =
            colors.zip(used).map(|(c, used)| c.into_iter().zip(used).filter(|(_, u)| *u).map(|(c, _)| c).collect());
        Ok((mesh, Attributes { uv, colors }))
    }

    /// Repairs into a mesh (see [`crate::mesh::repair()`]); attributes are not kept.
    ///
    /// # Errors
    /// Non-finite coordinates, indices out of range and a mesh with no face
    /// left, naming `file`.
    pub fn repaired(self, file: &str) -> Result<(Mesh, RepairReport)> {
        repair(self.positions, &self.triangles).map_err(|source| Error::Mesh {
            file: file.to_string(),
            line: None,
            source,
        })
    }

    /// Merges vertices at exactly the same position (bit for bit, `-0` and `0`
    /// alike) into one, so a triangle soup (STL) or a mesh split at its
    /// texture seams (glTF) becomes connected. Texture coordinates are per
    /// corner and stay as they are; a merged vertex keeps its first colour.
    pub fn weld(&mut self) {
        let key = |p: Vec3| p.to_array().map(|x| if x == 0.0 { 0 } else { x.to_bits() });
        let mut first = std::collections::HashMap::with_capacity(self.positions.len());
        let mut remap = Vec::with_capacity(self.positions.len());
        let (mut positions, mut colors) = (Vec::new(), self.colors.as_ref().map(|_| Vec::new()));
        for (i, &p) in self.positions.iter().enumerate() {
            let next = positions.len() as u32;
            let id = *first.entry(key(p)).or_insert(next);
            if id == next {
                positions.push(p);
                if let (Some(out), Some(c)) = (&mut colors, &self.colors) {
                    out.push(c[i]);
                }
            }
            remap.push(id);
        }
        for t in &mut self.triangles {
            // out-of-range indices stay out of range, to be reported by the build
            *t = remap.get(*t as usize).copied().unwrap_or(u32::MAX);
        }
        self.positions = positions;
        self.colors = colors;
    }

    /// Appends `other`, renumbering its vertices; an attribute that either
    /// side has is kept, the side without it getting defaults (texture
    /// coordinates (0, 0), white, material 0).
    pub fn append(&mut self, other: RawMesh) {
        let base = self.positions.len() as u32;
        let (nc0, nv0) = (self.triangles.len(), self.positions.len());
        self.triangles.extend(other.triangles.iter().map(|&i| i.saturating_add(base)));
        merge(&mut self.uv, other.uv, nc0, other.triangles.len(), Vec2::ZERO);
        merge(&mut self.colors, other.colors, nv0, other.positions.len(), Vec3::ONE);
        merge(&mut self.materials, other.materials, nc0 / 3, other.triangles.len() / 3, 0);
        self.positions.extend(other.positions);
    }
}

/// Concatenates optional per-element arrays: `a` (of `na` elements) then `b`
/// (of `nb`), filling the side that has none with `fill`.
fn merge<T: Copy>(a: &mut Option<Vec<T>>, b: Option<Vec<T>>, na: usize, nb: usize, fill: T) {
    match (a.as_mut(), b) {
        (None, None) => {}
        (Some(a), None) => a.resize(a.len() + nb, fill),
        (Some(a), Some(b)) => a.extend(b),
        (None, Some(b)) => {
            let mut v = vec![fill; na];
            v.extend(b);
            *a = Some(v);
        }
    }
}

/// Which of `n` vertices some triangle uses.
fn used_vertices(n: usize, triangles: &[u32]) -> Vec<bool> {
    let mut u = vec![false; n];
    for &i in triangles {
        if let Some(slot) = u.get_mut(i as usize) {
            *slot = true;
        }
    }
    u
}

/// A [`Error::Format`] on `file` at `element`.
pub fn format_err(file: &str, element: impl Into<String>, msg: impl Into<String>) -> Error {
    Error::Format { file: file.to_string(), element: element.into(), msg: msg.into() }
}

/// Checks that `count` records of at least `min_bytes` each fit in the
/// `available` bytes left, before a vector of `count` is allocated: a header
/// that claims more elements than the file could hold is refused.
///
/// # Errors
/// [`Error::Format`] naming `file` and `what`.
pub fn check_count(file: &str, what: &str, count: u64, min_bytes: u64, available: usize) -> Result<usize> {
    let need = count.saturating_mul(min_bytes.max(1));
    if need > available as u64 || count > u64::from(u32::MAX) {
        return Err(format_err(
            file,
            what,
            format!(
                "the header claims {count} elements, but only {available} bytes follow (at least {min_bytes} each needed)"
            ),
        ));
    }
    Ok(count as usize)
}
