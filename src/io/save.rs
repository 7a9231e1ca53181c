//! One way to save whatever the library makes: a triangle table
//! ([`Mesh`]), a polygon table ([`PolyMesh`]) or faces alone ([`Faces`],
//! from [`crate::subdivide_faces`]), in f32 or, for the tables, in f64.

use super::{precise, save_faces, save_mesh, save_poly};
use crate::mesh::{Attributes, Faces, PolyMesh};
use crate::{Mesh, Result};
use glam::DVec3;
use std::path::Path;

mod sealed {
    pub trait Sealed {}
    impl Sealed for crate::Mesh {}
    impl Sealed for crate::mesh::PolyMesh {}
    impl Sealed for crate::mesh::Faces {}
}

/// What [`super::save`] and [`save_with`] write (sealed): a [`Mesh`], a
/// [`PolyMesh`] or [`Faces`].
pub trait Save: sealed::Sealed {
    /// Writes `self` to `path` by its extension, with `attrs` (call
    /// [`save_with`]).
    ///
    /// # Errors
    /// As [`save_with`].
    #[doc(hidden)]
    fn save_to(&self, path: &Path, attrs: &Attributes) -> Result<()>;
}

/// What [`save_f64`] writes (sealed): the tables, [`Mesh`] and [`PolyMesh`]
/// (faces alone have no f64 path, so the compiler refuses them).
pub trait SaveF64: Save {
    /// Writes `self`'s topology with the f64 `positions` to `path` (call
    /// [`save_f64`]).
    ///
    /// # Errors
    /// As [`save_f64`].
    #[doc(hidden)]
    fn save_f64_to(&self, path: &Path, positions: &[DVec3], attrs: &Attributes, keep_holes: bool) -> Result<()>;
}

impl Save for Mesh {
    fn save_to(&self, path: &Path, attrs: &Attributes) -> Result<()> {
        save_mesh(path, self, attrs)
    }
}

impl SaveF64 for Mesh {
    fn save_f64_to(&self, path: &Path, positions: &[DVec3], attrs: &Attributes, keep_holes: bool) -> Result<()> {
        precise::save_mesh_f64(path, self, positions, attrs, keep_holes)
    }
}

impl Save for PolyMesh {
    fn save_to(&self, path: &Path, attrs: &Attributes) -> Result<()> {
        save_poly(path, self, attrs)
    }
}

impl SaveF64 for PolyMesh {
    fn save_f64_to(&self, path: &Path, positions: &[DVec3], attrs: &Attributes, keep_holes: bool) -> Result<()> {
        precise::save_poly_f64(path, self, positions, attrs, keep_holes)
    }
}

impl Save for Faces {
    fn save_to(&self, path: &Path, attrs: &Attributes) -> Result<()> {
        save_faces(path, self, attrs)
    }
}

/// Saves `mesh` by extension with its attributes: texture coordinates and
/// colours where the format keeps them ([`super::keeps`]),
/// materials and sharpness tags likewise. A [`Mesh`] that stands for
/// polygons (fanned faces, its diagonals hidden) is written as polygons by
/// the formats that keep them (OBJ, PLY, OFF, `.ct`); a [`PolyMesh`] is
/// fanned for STL and `.glb`; [`Faces`] of three or four corners go to the
/// formats [`super::writes_faces`] names.
///
/// # Errors
/// An unknown extension, faces a format cannot take, or an I/O error, each
/// naming the file.
pub fn save_with(path: &Path, mesh: &impl Save, attrs: &Attributes) -> Result<()> {
    mesh.save_to(path, attrs)
}

/// Saves `mesh`'s topology with the f64 `positions` (one per vertex) at
/// full precision: OBJ with the shortest digits that read back to the same
/// f64, PLY with double properties; formats without doubles get them
/// rounded. `keep_holes`: holes written as the format keeps them (else the
/// faces in holes are left out).
///
/// # Errors
/// `positions` not one per vertex, an unknown extension or an
/// I/O error.
pub fn save_f64(
    path: &Path,
    mesh: &impl SaveF64,
    positions: &[DVec3],
    attrs: &Attributes,
    keep_holes: bool,
) -> Result<()> {
    mesh.save_f64_to(path, positions, attrs, keep_holes)
}
