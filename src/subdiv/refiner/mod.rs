//! The refiner: a control mesh's topology refined once, any data served on
//! it many times (OpenSubdiv's `Far::TopologyRefiner` with its
//! `PrimvarRefiner` and stencil table in one object).
//!
//! [`Refiner::new`] refines the cage by the one-shot passes (it is what
//! [`crate::subdivide`] runs) and keeps every level: its table, with what
//! the rules need to record its stencils, and its points. The stencils are
//! recorded from those tables on first need, by the same rule code. From
//! then on:
//!
//! - any per-vertex data of any width is refined through the recorded rows,
//!   in f32 or f64 ([`Refiner::refine`], the f64 weights recorded in f64);
//! - moving control vertices ([`Refiner::move_vertices`]) re-evaluates only
//!   their support: at each level the rows that read a changed point of the
//!   level above, found through the transposed rows, then the normals of
//!   the changed finest points and of their neighbours. The result is
//!   bit-identical to evaluating every row again ([`Refiner::set_control`]);
//! - a sharpness change ([`Refiner::set_edge_sharpness`]) records the
//!   stencils again for the new tags and re-evaluates;
//! - every change is a step of a history ([`Refiner::undo`],
//!   [`Refiner::redo`]) that stores what changed, not the mesh.
//!
//! The rooms: `store` (what is kept and the accessors), `edit` (moves,
//! support, the touched rows and their evaluation), `full` (every row of
//! every level again), `normals` (the finest rings and normals), `data`
//! (per-vertex data through the rows), `sharpness` (the sharpness setters)
//! over `retag` (the rows a tag change reaches, recorded again), `history`
//! (undo and redo), `precise` (the f64 points), `attributes` (colours,
//! texture coordinates, materials) and `topology` (the kept tables and
//! the plans recorded from them).

mod attributes;
mod data;
mod edit;
mod full;
mod history;
mod normals;
mod precise;
mod retag;
mod sharpness;
mod store;
mod topology;

pub use data::Scalar;

use super::{Levels, Options, Scheme, Stats};
use crate::{CornerTable, Error, Result};
use edit::EditTables;
use glam::{DVec3, Vec3};
use history::History;
use retag::Patches;
use std::sync::OnceLock;
use topology::Topology;

/// A control mesh refined `levels` times with one scheme: every level's
/// table and points kept, its stencils recorded from them on first need,
/// any data refined on demand, edits applied where they reach. See the module's
/// documentation.
///
/// ```
/// use subdiv::{Mesh, Options, Refiner, Scheme};
/// use glam::Vec3;
/// let pos = vec![Vec3::new(1., 1., 1.), Vec3::new(1., -1., -1.), Vec3::new(-1., 1., -1.), Vec3::new(-1., -1., 1.)];
/// let mesh = Mesh::from_triangles(pos, &[0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2]).unwrap();
/// let mut r = Refiner::new(&mesh, Scheme::Loop, 2, &Options::default()).unwrap();
/// let changed = r.move_vertices(&[0], &[Vec3::new(2., 2., 2.)]).unwrap();
/// assert!(changed > 0 && changed < r.positions().len() + 1);
/// r.undo();
/// assert_eq!(r.control()[0], Vec3::new(1., 1., 1.));
/// ```
pub struct Refiner {
    /// The control topology with its current tags.
    cage: CornerTable,
    /// Every level's table, the finest, and the stencils made from them.
    topo: Topology,
    /// Points of every level: `[0]` the control points, last the finest.
    /// Each buffer is allocated once: edits write into it.
    points: Vec<Vec<Vec3>>,
    /// The same in f64, kept once asked for ([`Refiner::set_control_f64`]).
    precise: Option<Vec<Vec<DVec3>>>,
    /// The finest level's normals, made on first use and then kept up to
    /// date by every edit.
    normals: OnceLock<Vec<Vec3>>,
    /// The finest level's ring polygons ([`normals::Rings`]; `None` where
    /// a fan does not chain), made with the normals.
    rings: OnceLock<Option<normals::Rings>>,
    /// The tables an edit walks (built on the first edit: a refiner that
    /// only serves data never pays for them).
    edit: Option<EditTables>,
    history: History,
    /// Rows recorded again after sharpness edits.
    patches: Patches,
    /// Whether the cage was a polygon table: attributes come and go per
    /// polygon corner.
    from_polygons: bool,
    /// The face-varying topology of the texture coordinates last served.
    face_varying: attributes::FaceVaryingCache,
    /// What the one-shot refinement took, phase by phase.
    stats: Stats,
}

impl Refiner {
    /// Refines `levels` levels of `scheme` on `cage`'s topology (its tags
    /// and holes included) at its positions, keeping every level.
    ///
    /// # Errors
    /// [`Error::TooLarge`] when a level would not fit in memory; a polygon
    /// scheme's refusal of the mesh.
    pub fn new<C: super::Cage>(cage: &C, scheme: Scheme, levels: u32, opts: &Options) -> Result<Refiner> {
        Self::with_progress(cage, (scheme, levels, opts), &mut |_, _| true)
    }

    /// [`Refiner::new`] calling `progress(level_done, levels)` after each
    /// level; if it returns `false` the refiner holds the levels done.
    ///
    /// # Errors
    /// As [`Refiner::new`].
    pub(crate) fn with_progress<C: super::Cage>(
        cage: &C,
        (scheme, levels, opts): (Scheme, u32, &Options),
        progress: &mut dyn FnMut(u32, u32) -> bool,
    ) -> Result<Refiner> {
        let (mesh, polygons) = cage.as_triangles(crate::subdiv::cage::sealed::Token::NEW);
        if polygons && !scheme.is_polygonal() {
            return Err(Error::Usage(format!("{scheme} subdivides triangles: fan the polygons first")));
        }
        let kept = cage.levels_kept(crate::subdiv::cage::sealed::Token::NEW, (scheme, levels, opts), progress)?;
        let mut r = Self::of_levels(mesh.into_owned().ct, kept, scheme, opts);
        r.from_polygons = polygons;
        Ok(r)
    }

    /// A refiner holding `levels` of `scheme` made on `cage`.
    fn of_levels(cage: CornerTable, mut levels: Levels, scheme: Scheme, opts: &Options) -> Refiner {
        let topo = Topology::of(&mut levels, scheme, opts);
        Refiner {
            cage,
            patches: Patches::sized(topo.levels()),
            topo,
            points: levels.points,
            precise: None,
            normals: OnceLock::new(),
            rings: OnceLock::new(),
            edit: None,
            history: History::default(),
            from_polygons: false,
            face_varying: Default::default(),
            stats: levels.stats,
        }
    }
}
