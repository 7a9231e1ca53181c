//! # subdiv: subdivision surfaces on corner tables, triangles and polygons
//!
//! The library is four layers, data flowing one way:
//! [`io`] (OBJ with MTL materials, `.ct`, PLY, STL, OFF, glTF, COLLADA,
//! USD stages with their prims, `.paths`) → [`mesh`] (Rossignac's corner table: V, O,
//! one corner per vertex, valences; and its polygon form, faces of any size
//! then quads, `mesh::poly`) → `subdiv` (the shared 1-to-4 and quad
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
//! [`subdivide_model`] is the one call for a model read from a file: its
//! mesh, attributes and f64 points, for a destination
//! ([`io::destination`]); it picks the path (a [`Refiner`] for attributes,
//! the faces alone, polygons, f64) and [`io::save_refined`] writes what it
//! made; [`subdivide_file`] reads a file, refines it so and writes it (the
//! command line's `subdivide` and `batch`, Python's `subdivide_file`).
//!
//! Vocabulary (as OpenSubdiv): a *mask* gives a new vertex in terms of the
//! previous level, a *stencil* in terms of any earlier level; *even* points
//! are the old vertices' new positions, *odd* points the new edge vertices.

#![warn(missing_docs)]
#![warn(unreachable_pub)]
// Items that only the viewer calls are dead in a build without it (the
// library alone, the Python package); dead code is checked in the full
// build (clippy in CI).
#![cfg_attr(not(feature = "viewer"), allow(dead_code))]

pub mod anim;
pub mod bundled;
pub(crate) mod clock;
pub mod cpu;
pub(crate) mod error;
pub mod io;
pub mod mem;
pub mod mesh;
pub(crate) mod subdiv;

#[cfg(feature = "viewer")]
pub mod render;

#[cfg(feature = "viewer")]
pub mod app;

// One way in per operation: reading, saving, subdividing, refining, the
// stencil plan, the exact evaluator; the namespaces below hold what these take
// and give.
pub use error::{Error, MeshError, Result, clean as clean_error};
pub use io::{read, save};
pub use mesh::{BORDER, CornerTable, Mesh};
pub use subdiv::eval::Evaluator;
pub use subdiv::tables::StencilPlan;
pub use subdiv::{
    Cage, Control, Demand, Destination, FacesOnly, FileJob, FileSummary, Flags, LoopBeta, Model, Options, Part,
    Refinement, Refiner, Scalar, Scheme, ScreenTolerance, Stats, Subdivided, Surface, Tessellation, TessellationStats,
    Tessellator, Tolerance, parts_by_options, subdivide, subdivide_f64, subdivide_faces, subdivide_faces_f64,
    subdivide_file, subdivide_model, subdivide_model_as, subdivide_parts, tessellate,
};

#[cfg(feature = "viewer")]
pub use render::render_image;

pub mod eval {
    //! Exact limit evaluation ([`crate::Evaluator`]): what a sample holds,
    //! the points it is asked at, the Loop and Catmull-Clark limit formulas
    //! per vertex, and the curvature colours.
    pub use crate::subdiv::eval::catmark::{QUAD, ptex_faces};
    pub use crate::subdiv::eval::catmark_limit::{
        LimitFrame, frame_from, frames_at, limit_frames, limit_positions_f64,
    };
    pub use crate::subdiv::eval::{
        Domain, EDGE_SLACK, Sample, evaluate_one, parse_points_in, poly_vertex_params, vertex_samples,
    };
    pub use crate::subdiv::rules::limit::{
        butterfly_normals, loop_limit_normals, loop_limit_positions, loop_limit_positions_f64,
        loop_limit_positions_with,
    };
    /// Curvature as colour: which curvature, its range and the colour scale.
    pub mod color {
        pub use crate::subdiv::eval::color::{
            CurvatureKind, HalfWidth, MAX_ISOLINES, PERCENTILE, SCHEMES, Scale, check_scheme, normalized, vertex_areas,
            vertex_curvatures,
        };
    }
}

pub mod pick {
    //! Picking: a ray against a mesh, and a hit on a refined level traced
    //! back to the control face and vertex it came from, with the limit
    //! surface there.
    pub use crate::mesh::pick::{Hit, first_hit, nearest_hit};
    pub use crate::subdiv::pick::{ControlFace, ControlVertex, Level, Limit, Pick, neighbourhood, pick};
}

pub mod rules {
    //! The rules made visible: the stencil plan's levels and rows, one
    //! vertex's stencil, the sharp features a mesh carries, the level each
    //! vertex was made at and the predicted sizes. (Attributes, texture
    //! coordinates, colours and materials, come from
    //! [`crate::Refiner::attributes`].)
    pub use crate::subdiv::inspect::{creation_levels, displacement};
    pub use crate::subdiv::rules::features::{Summary, poly_summary, summary, with_boundary_corners};
    pub use crate::subdiv::sizes::ControlCounts;
    pub use crate::subdiv::stencil::{Stencil, stencil};
    pub use crate::subdiv::tables::{LevelPlan, PlanScratch, Point};
    pub use crate::subdiv::{PlanF64, plan_f64};
}
