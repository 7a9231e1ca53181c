//! One way to save whatever the library makes: a triangle table
//! ([`Mesh`]), a polygon table ([`PolyMesh`]) or faces alone ([`Faces`],
//! from [`crate::subdivide_faces`]), in f32 or, for the tables, in f64.

use crate::mesh::{Attributes, Faces, PolyMesh};
use crate::subdiv::{Subdivided, Surface};
use crate::{Mesh, Result};
use glam::DVec3;
use std::path::Path;

/// The writing itself, out of reach of other crates: the methods [`Save`]
/// and [`SaveF64`] stand for, each taking a [`sealed::Token`] only this
/// crate makes.
pub(crate) mod sealed {
    use super::super::{precise, save_faces, save_mesh, save_poly};
    use crate::mesh::{Attributes, Faces, PolyMesh};
    use crate::{Mesh, Result};
    use glam::DVec3;
    use std::path::Path;

    /// The argument of every method here: only this crate makes one.
    pub struct Token(());

    impl Token {
        pub(crate) const NEW: Token = Token(());
    }

    /// Writes a mesh with its attributes.
    pub trait Writes {
        /// Writes `self` to `path` by its extension, with `attrs`.
        ///
        /// # Errors
        /// As [`super::save_with`].
        fn save_to(&self, _: Token, path: &Path, attrs: &Attributes) -> Result<()>;
    }

    /// Writes a table's topology with f64 positions.
    pub trait WritesF64: Writes {
        /// Writes `self`'s topology with the f64 `positions` to `path`.
        ///
        /// # Errors
        /// As [`super::save_f64`].
        fn save_f64_to(
            &self,
            _: Token,
            path: &Path,
            positions: &[DVec3],
            attrs: &Attributes,
            keep_holes: bool,
        ) -> Result<()>;
    }

    impl Writes for Mesh {
        fn save_to(&self, _: Token, path: &Path, attrs: &Attributes) -> Result<()> {
            save_mesh(path, self, attrs)
        }
    }

    impl WritesF64 for Mesh {
        fn save_f64_to(&self, _: Token, path: &Path, p: &[DVec3], attrs: &Attributes, keep_holes: bool) -> Result<()> {
            precise::save_mesh_f64(path, self, p, attrs, keep_holes)
        }
    }

    impl Writes for PolyMesh {
        fn save_to(&self, _: Token, path: &Path, attrs: &Attributes) -> Result<()> {
            save_poly(path, self, attrs)
        }
    }

    impl WritesF64 for PolyMesh {
        fn save_f64_to(&self, _: Token, path: &Path, p: &[DVec3], attrs: &Attributes, keep_holes: bool) -> Result<()> {
            precise::save_poly_f64(path, self, p, attrs, keep_holes)
        }
    }

    impl Writes for Faces {
        fn save_to(&self, _: Token, path: &Path, attrs: &Attributes) -> Result<()> {
            save_faces(path, self, attrs)
        }
    }
}

/// What [`super::save`] and [`save_with`] write (sealed): a [`Mesh`], a
/// [`PolyMesh`] or [`Faces`].
#[allow(private_bounds)]
pub trait Save: sealed::Writes {}

/// What [`save_f64`] writes (sealed): the tables, [`Mesh`] and [`PolyMesh`]
/// (faces alone have no f64 path, so the compiler refuses them).
#[allow(private_bounds)]
pub trait SaveF64: Save + sealed::WritesF64 {}

impl Save for Mesh {}
impl SaveF64 for Mesh {}
impl Save for PolyMesh {}
impl SaveF64 for PolyMesh {}
impl Save for Faces {}

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
    mesh.save_to(sealed::Token::NEW, path, attrs)
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
    mesh.save_f64_to(sealed::Token::NEW, path, positions, attrs, keep_holes)
}

/// Saves what [`crate::subdivide_model`] made by extension, each surface
/// through its writer: the tables with [`save_with`], or with [`save_f64`]
/// where the refinement was in f64 (a control mesh's holes kept as the
/// format keeps them, a refined level's left out), faces alone with
/// [`save_with`].
///
/// # Errors
/// As [`save_with`] and [`save_f64`]; f64 faces alone, which no format
/// writes.
pub fn save_refined(path: &Path, refined: &Subdivided) -> Result<()> {
    let (attrs, keep_holes) = (&refined.attrs, refined.levels == 0);
    match (&refined.surface, &refined.positions_f64) {
        (Surface::Triangles(m), Some(p)) => save_f64(path, m, p, attrs, keep_holes),
        (Surface::Polygons(m), Some(p)) => save_f64(path, m, p, attrs, keep_holes),
        (Surface::Triangles(m), None) => save_with(path, m, attrs),
        (Surface::Polygons(m), None) => save_with(path, m, attrs),
        (Surface::Faces(f), _) => save_with(path, f, attrs),
        (Surface::FacesF64(_), _) => Err(crate::Error::Usage(format!(
            "{}: faces alone in f64 have no writer: refine with FacesOnly::Written or Never",
            path.display()
        ))),
    }
}
