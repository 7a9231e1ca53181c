//! One way in to subdivide a cage, whatever it is: a triangle table
//! ([`Mesh`], every scheme; polygon schemes read its fanned polygons) or a
//! polygon table ([`PolyMesh`], Catmull-Clark and bilinear), in f32 or f64,
//! whole or faces only. [`Cage`] is sealed: the two tables are the cages.

use super::{Options, Scheme, Stats};
use crate::Result;
use crate::mesh::poly::PolyMesh;
use crate::mesh::{Faces, Mesh, VertexId};
use glam::DVec3;

/// The cages' part of the refinement, out of reach of other crates: the
/// methods [`Cage`] stands for, implemented by the two tables only.
// the methods reach `Levels` (the crate's own) but take a Token
#[allow(private_interfaces)]
pub(crate) mod sealed {
    use super::super::{Options, Scheme, Stats};
    use crate::Result;
    use crate::mesh::poly::PolyMesh;
    use crate::mesh::{Faces, Mesh, VertexId};
    use glam::DVec3;

    /// The argument every method of [`Sealed`] takes: only this crate
    /// makes one, so no other crate calls them (through a [`super::Cage`]
    /// bound either).
    pub struct Token(());

    impl Token {
        pub(crate) const NEW: Token = Token(());
    }

    /// What every cage does (see [`super::Cage`]).
    pub trait Sealed: Sized {
        /// `levels` levels of `scheme`; see [`super::subdivide`].
        ///
        /// # Errors
        /// As [`super::subdivide`].
        fn refined(&self, _: Token, scheme: Scheme, levels: u32, opts: &Options) -> Result<(Self, Stats)>;
        /// The refined positions in f64; see [`super::subdivide_f64`].
        ///
        /// # Errors
        /// As [`super::subdivide_f64`].
        fn refined_f64(
            &self,
            _: Token,
            control: &[DVec3],
            scheme: Scheme,
            levels: u32,
            opts: &Options,
        ) -> Result<(Self, Vec<DVec3>)>;
        /// The last level's faces only; see [`super::subdivide_faces`].
        ///
        /// # Errors
        /// As [`super::subdivide_faces`].
        fn refined_faces<I: VertexId>(
            &self,
            _: Token,
            scheme: Scheme,
            levels: u32,
            opts: &Options,
            id: impl Fn(u32) -> I + Sync,
        ) -> Result<(Faces<I>, Stats)>;
        /// The last level's faces from f64 control points; see
        /// [`super::subdivide_faces_f64`].
        ///
        /// # Errors
        /// As [`super::subdivide_faces_f64`].
        fn refined_faces_f64<I: VertexId>(
            &self,
            _: Token,
            control: &[DVec3],
            how: (Scheme, u32, &Options),
            id: impl Fn(u32) -> I + Sync,
        ) -> Result<(Faces<I, DVec3>, Stats)>;
        /// The cage as the triangle table the refiner records on (a polygon
        /// table fanned, its diagonals hidden) and whether it is polygons.
        fn as_triangles(&self, _: Token) -> (std::borrow::Cow<'_, Mesh>, bool);
        /// Every level, kept for a [`crate::Refiner`].
        ///
        /// # Errors
        /// As [`super::subdivide`].
        fn levels_kept(
            &self,
            _: Token,
            how: (Scheme, u32, &Options),
            progress: &mut dyn FnMut(u32, u32) -> bool,
        ) -> Result<crate::subdiv::Levels>;
    }

    impl Sealed for Mesh {
        fn refined(&self, _: Token, scheme: Scheme, levels: u32, opts: &Options) -> Result<(Mesh, Stats)> {
            super::super::subdivide_mesh(self, scheme, levels, opts)
        }
        fn refined_f64(
            &self,
            _: Token,
            control: &[DVec3],
            scheme: Scheme,
            levels: u32,
            opts: &Options,
        ) -> Result<(Mesh, Vec<DVec3>)> {
            super::super::precise::subdivide_mesh_f64(self, control, scheme, levels, opts)
        }
        fn refined_faces<I: VertexId>(
            &self,
            _: Token,
            scheme: Scheme,
            levels: u32,
            opts: &Options,
            id: impl Fn(u32) -> I + Sync,
        ) -> Result<(Faces<I>, Stats)> {
            super::super::subdivide_mesh_faces_as(self, scheme, levels, opts, id)
        }
        fn refined_faces_f64<I: VertexId>(
            &self,
            _: Token,
            control: &[DVec3],
            how: (Scheme, u32, &Options),
            id: impl Fn(u32) -> I + Sync,
        ) -> Result<(Faces<I, DVec3>, Stats)> {
            super::super::subdivide_mesh_faces_f64(self, control, how, id)
        }
        fn as_triangles(&self, _: Token) -> (std::borrow::Cow<'_, Mesh>, bool) {
            (std::borrow::Cow::Borrowed(self), false)
        }
        fn levels_kept(
            &self,
            _: Token,
            how: (Scheme, u32, &Options),
            progress: &mut dyn FnMut(u32, u32) -> bool,
        ) -> Result<super::super::Levels> {
            super::super::refine_kept(self, how, progress)
        }
    }

    impl Sealed for PolyMesh {
        fn refined(&self, _: Token, scheme: Scheme, levels: u32, opts: &Options) -> Result<(PolyMesh, Stats)> {
            super::super::subdivide_poly(self, scheme, levels, opts)
        }
        fn refined_f64(
            &self,
            _: Token,
            control: &[DVec3],
            scheme: Scheme,
            levels: u32,
            opts: &Options,
        ) -> Result<(PolyMesh, Vec<DVec3>)> {
            super::super::precise::subdivide_poly_f64(self, control, scheme, levels, opts)
        }
        fn refined_faces<I: VertexId>(
            &self,
            _: Token,
            scheme: Scheme,
            levels: u32,
            opts: &Options,
            id: impl Fn(u32) -> I + Sync,
        ) -> Result<(Faces<I>, Stats)> {
            super::super::subdivide_poly_faces_as(self, scheme, levels, opts, id)
        }
        fn refined_faces_f64<I: VertexId>(
            &self,
            _: Token,
            control: &[DVec3],
            (scheme, levels, opts): (Scheme, u32, &Options),
            id: impl Fn(u32) -> I + Sync,
        ) -> Result<(Faces<I, DVec3>, Stats)> {
            if levels == 0 {
                return Err(crate::Error::Usage("faces alone come from at least one level (quads after it)".into()));
            }
            let (fine, positions) = super::super::precise::subdivide_poly_f64(self, control, scheme, levels, opts)?;
            let corners = fine.pt.v_table().iter().map(|&j| id(j)).collect();
            let faces = Faces { positions, corners, sides: 4 }.without(fine.pt.holes());
            Ok((faces, Stats::default()))
        }
        fn as_triangles(&self, _: Token) -> (std::borrow::Cow<'_, Mesh>, bool) {
            (std::borrow::Cow::Owned(self.triangulated()), true)
        }
        fn levels_kept(
            &self,
            _: Token,
            how: (Scheme, u32, &Options),
            progress: &mut dyn FnMut(u32, u32) -> bool,
        ) -> Result<super::super::Levels> {
            super::super::poly_kept((&self.pt, &self.positions), how, progress)
        }
    }
}

/// A control mesh that [`subdivide`], [`subdivide_f64`] and
/// [`subdivide_faces`] refine: [`Mesh`] (triangles) or [`PolyMesh`]
/// (polygons). The refined mesh is of the same kind. Sealed: the two
/// tables are the cages, and what a cage does is the library's own.
#[allow(private_bounds)]
pub trait Cage: sealed::Sealed {}

impl Cage for Mesh {}
impl Cage for PolyMesh {}

/// Refines `cage` `levels` times with `scheme`: a [`Mesh`] under any
/// scheme (a polygon scheme reads the polygons its hidden diagonals
/// stand for), a [`PolyMesh`] under Catmull-Clark or bilinear.
///
/// # Errors
/// [`crate::Error::TooLarge`] when a level would exceed the memory limit
/// (checked before it is allocated) or 32-bit corner ids;
/// [`crate::Error::Usage`] for a triangle scheme on a [`PolyMesh`] (fan it
/// first).
pub fn subdivide<C: Cage>(cage: &C, scheme: Scheme, levels: u32, opts: &Options) -> Result<(C, Stats)> {
    cage.refined(sealed::Token::NEW, scheme, levels, opts)
}

/// [`subdivide`] of `cage`'s topology with the control positions `control`
/// in f64: the refined mesh (its `positions` the f64 ones rounded to f32,
/// for drawing) and the refined positions in f64, computed with the f64
/// weights of the same stencils.
///
/// # Errors
/// `control` not one position per vertex of `cage`; as [`subdivide`].
pub fn subdivide_f64<C: Cage>(
    cage: &C,
    control: &[DVec3],
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<(C, Vec<DVec3>)> {
    cage.refined_f64(sealed::Token::NEW, control, scheme, levels, opts)
}

/// [`subdivide`] for a caller that needs only the faces of the result (to
/// write them or hand them over): the same positions and faces, but the
/// last level writes no O, C or valence table, no sharpness and no edge
/// generations (at bunny level 3, 70 of the 150 MB `subdivide` writes).
/// Every vertex id `j` of the faces is written as `id(j)` in the pass that
/// writes them (`|j| j` keeps `u32`), so a caller that wants other ids
/// converts no table afterwards. `tests/faces_only.rs` checks that both give
/// the same bits.
///
/// # Errors
/// As [`subdivide`]; [`crate::Error::Usage`] for no levels of a
/// [`PolyMesh`] (the faces of a control mesh need not be quads).
pub fn subdivide_faces<C: Cage, I: VertexId>(
    cage: &C,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    id: impl Fn(u32) -> I + Sync,
) -> Result<(Faces<I>, Stats)> {
    cage.refined_faces(sealed::Token::NEW, scheme, levels, opts, id)
}

/// [`subdivide_faces`] from the control positions `control` in f64: the
/// last level's faces and their positions in f64, computed with the f64
/// weights of the same rules (a triangle scheme through the same one-shot
/// passes as f32, in f64).
///
/// # Errors
/// `control` not one position per vertex of `cage`; as [`subdivide_faces`].
pub fn subdivide_faces_f64<C: Cage, I: VertexId>(
    cage: &C,
    control: &[DVec3],
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    id: impl Fn(u32) -> I + Sync,
) -> Result<(Faces<I, DVec3>, Stats)> {
    cage.refined_faces_f64(sealed::Token::NEW, control, (scheme, levels, opts), id)
}
