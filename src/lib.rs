//! # subdiv: subdivision surfaces on corner tables, triangles and polygons
//!
//! The library is four layers, data flowing one way:
//! [`io`] (OBJ with MTL materials, `.ct`, PLY, STL, OFF, glTF, COLLADA,
//! `.paths`) → [`mesh`] (Rossignac's corner table: V, O,
//! one corner per vertex, valences; and its polygon form, faces of any size
//! then quads, [`mesh::poly`]) → [`subdiv`] (the shared 1-to-4 and quad
//! splits with linear-time O and twin updates, one file of rules per scheme,
//! Catmull-Clark's limit, stencil plans) →
//! [`anim`] (split-and-tweak paths). The renderer and the window (feature
//! `viewer`) only see flat arrays.
//!
//! Input that is not a manifold mesh is refused with a typed [`MeshError`]
//! naming the elements; [`mesh::repair()`] (CLI: `subdiv repair`, or `--repair`
//! on `subdivide` and `info`) instead cuts non-manifold edges, splits
//! non-manifold vertices, fixes the orientation and drops degenerate,
//! duplicate and unreferenced elements, reporting what it changed.
//!
//! ```
//! use subdiv::{Mesh, Scheme, Options, subdivide};
//! use glam::Vec3;
//! // a tetrahedron, faces counter-clockwise seen from outside
//! let pos = vec![Vec3::new(1., 1., 1.), Vec3::new(1., -1., -1.), Vec3::new(-1., 1., -1.), Vec3::new(-1., -1., 1.)];
//! let tris = [0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2];
//! let mesh = Mesh::from_triangles(pos, &tris).unwrap();
//! let (fine, stats) = subdivide(&mesh, Scheme::Loop, 3, &Options::default()).unwrap();
//! assert_eq!(fine.ct.num_triangles(), 4 * 4 * 4 * 4);
//! assert_eq!(stats.faces_per_level, vec![16, 64, 256]);
//! ```
//!
//! Vocabulary (as OpenSubdiv): a *mask* gives a new vertex in terms of the
//! previous level, a *stencil* in terms of any earlier level; *even* points
//! are the old vertices' new positions, *odd* points the new edge vertices.

#![warn(missing_docs)]

pub mod anim;
pub mod bundled;
pub mod cpu;
pub mod error;
pub mod io;
pub mod mem;
pub mod mesh;
pub mod subdiv;

#[cfg(feature = "viewer")]
pub mod render;

#[cfg(feature = "viewer")]
pub mod app;

pub use error::{Error, MeshError, Result};
pub use mesh::{BORDER, CornerTable, Mesh};
pub use subdiv::{
    LoopBeta, Options, Refiner, Scheme, Stats, subdivide, subdivide_f64, subdivide_faces, subdivide_faces_as,
    subdivide_poly, subdivide_poly_f64, subdivide_poly_faces, subdivide_poly_faces_as,
};
