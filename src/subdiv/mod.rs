//! Subdivision: the shared 1-to-4 split plus one file of rules per scheme,
//! in three layers as OpenSubdiv's `sdc`, `vtr` and `far`:
//!
//! - [`rules`]: the schemes' masks (what weights make a new point), sharp
//!   features' rules, limit masks; no tables, no timing;
//! - [`refine`]: one level after another, the split
//!   ([`crate::mesh::split`], which knows no scheme) and the rules applied
//!   to the new points, with the time of each phase;
//! - [`tables`]: the stencil plans that record the rules once for a
//!   topology and re-apply them to new control points (animation,
//!   attributes), and their packed form.
//!
//! A level = `split` (new V, O, C, valences; edge numbering) + edge points for
//! every edge + vertex points (Loop, Jarek) or a copy (interpolating schemes).
//! Every rule reads the old level only; output arrays are allocated once per
//! level with their exact sizes (`V' = V + E`, `F' = 4F`); the work is spread
//! over rayon's threads in chunks.

pub(crate) mod cage;
pub(crate) mod eval;
mod file;
pub(crate) mod inspect;
mod model;
mod parts;
pub(crate) mod pick;
mod precise;
pub(crate) mod refine;
mod refiner;
pub(crate) mod rules;
mod scheme;
pub(crate) mod sizes;
pub(crate) mod stencil;
pub(crate) mod tables;
mod tess;

use crate::Result;
use crate::clock::Instant;
#[cfg(feature = "viewer")]
pub(crate) use crate::mesh::attributes::UvInterpolation;
use crate::mesh::poly::PolyMesh;
use crate::mesh::{CornerTable, Faces, Mesh, VertexId};
use glam::DVec3;
use refine::build::{Keep, build};
use refine::{OneLevel, Refined};
use rules::{catmull_clark, loop_};
use std::borrow::Cow;

pub use cage::{Cage, subdivide, subdivide_f64, subdivide_faces, subdivide_faces_f64};
pub use file::{Demand, FileJob, FileSummary, Flags, subdivide_file};
pub use loop_::LoopBeta;
pub use model::{
    Control, Destination, FacesOnly, Model, Refinement, Subdivided, Surface, subdivide_model, subdivide_model_as,
};
pub use parts::{Part, parts_by_options, subdivide_parts};
pub use precise::{PlanF64, plan_f64};
pub use refiner::{Refiner, Scalar};
pub use scheme::{Options, Scheme, Stats};
pub(crate) use scheme::{RulesFn, ms, with_rules};
#[cfg(feature = "viewer")]
pub(crate) use sizes::ControlCounts;
pub use tess::{ScreenTolerance, Tessellation, TessellationStats, Tessellator, Tolerance, tessellate};

/// Refines `mesh` `levels` times with `scheme`.
///
/// # Errors
/// [`crate::Error::TooLarge`] when a level would exceed the memory limit (checked
/// before it is allocated) or 32-bit corner ids.
pub(crate) fn subdivide_mesh(mesh: &Mesh, scheme: Scheme, levels: u32, opts: &Options) -> Result<(Mesh, Stats)> {
    subdivide_with_progress(mesh, scheme, levels, opts, |_, _| true)
}

/// [`subdivide`] calling `progress(level_done, levels)` after each level; if
/// it returns `false` the work stops and `Ok` holds the last finished level:
/// the finest of the levels a [`Refiner`] is made of (its stencils never
/// recorded, its cage table never made).
///
/// # Errors
/// See [`subdivide`].
pub(crate) fn subdivide_with_progress(
    mesh: &Mesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    mut progress: impl FnMut(u32, u32) -> bool,
) -> Result<(Mesh, Stats)> {
    Ok(refine_kept(mesh, (scheme, levels, opts), &mut progress)?.into_mesh())
}

/// Every level of a refinement, as the one-shot passes made them and a
/// [`Refiner`] keeps them: the table each level was made from (its boundary
/// corners applied, its sharpness that level's; for a triangle scheme with
/// the owner corners of its edges), the finest level's table, and the
/// points of every level, the control points first.
pub(crate) struct Levels<P = glam::Vec3> {
    pub(crate) tables: tables::plan::LevelTables,
    /// The finest triangles (a triangle scheme's).
    pub(crate) fine: Option<CornerTable>,
    /// The finest polygons (a polygon scheme's).
    pub(crate) fine_poly: Option<crate::mesh::poly::PolyTable>,
    pub(crate) points: Vec<Vec<P>>,
    pub(crate) stats: Stats,
}

impl Levels {
    /// The finest level as a mesh (a polygon scheme's fanned), and what
    /// refining took.
    fn into_mesh(mut self) -> (Mesh, Stats) {
        let positions = self.points.pop().unwrap_or_default();
        let ct = match (self.fine, &self.fine_poly) {
            (Some(ct), _) => ct,
            (None, Some(pt)) => pt.triangulated(),
            (None, None) => CornerTable::default(),
        };
        (Mesh { ct, positions }, self.stats)
    }

    /// A polygon scheme's finest level as polygons, and what refining took.
    ///
    /// # Errors
    /// [`crate::Error::Usage`] for a triangle scheme's levels.
    fn into_poly(mut self) -> Result<(PolyMesh, Stats)> {
        let positions = self.points.pop().unwrap_or_default();
        match self.fine_poly {
            Some(pt) => Ok((PolyMesh { pt, positions }, self.stats)),
            None => Err(crate::Error::Usage("a triangle scheme makes triangles, not polygons".into())),
        }
    }
}

/// The levels of `scheme` on `mesh` (a polygon scheme on the polygons it
/// stands for), each kept; `progress` as [`subdivide_with_progress`]'s.
///
/// # Errors
/// As [`subdivide`].
pub(crate) fn refine_kept(
    mesh: &Mesh,
    (scheme, levels, opts): (Scheme, u32, &Options),
    progress: &mut dyn FnMut(u32, u32) -> bool,
) -> Result<Levels> {
    if scheme.is_polygonal() {
        let poly = PolyMesh::from_mesh(mesh);
        return poly_kept((&poly.pt, &poly.positions), (scheme, levels, opts), progress);
    }
    let b = build(&mesh.ct, &mesh.positions, (scheme, levels, opts), Keep::Levels, progress)?;
    // no level: the control table itself, without the boundary's corner tags
    let fine = if b.kept.is_empty() { mesh.ct.clone() } else { b.fine };
    let tables = refine::build::Table::into_tables(b.kept);
    Ok(Levels { tables, fine: Some(fine), fine_poly: None, points: b.points, stats: b.stats })
}

/// [`refine_kept`] of the polygon table `pt` with the points `control`
/// (f32 or f64: the same passes) under a polygon scheme.
///
/// # Errors
/// As [`subdivide`]; a triangle scheme.
pub(crate) fn poly_kept<P: rules::Coord>(
    (pt, control): (&crate::mesh::poly::PolyTable, &[P]),
    (scheme, levels, opts): (Scheme, u32, &Options),
    progress: &mut dyn FnMut(u32, u32) -> bool,
) -> Result<Levels<P>> {
    if !scheme.is_polygonal() {
        return Err(crate::Error::Usage(format!("{scheme} subdivides triangles: fan the polygons first")));
    }
    let b = build(pt, control, (scheme, levels, opts), Keep::Levels, progress)?;
    let tables = refine::build::Table::into_tables(b.kept);
    Ok(Levels { tables, fine: None, fine_poly: Some(b.fine), points: b.points, stats: b.stats })
}

/// [`subdivide_faces`] with every vertex id `j` of the faces written as
/// `id(j)`, in the pass that writes them: for a caller that wants other ids
/// (wider integers, its own numbering) without converting a `u32` table
/// afterwards, which at bunny level 3 would be 53 MB written, read and
/// freed. The positions are those of [`subdivide_faces`], in its order.
///
/// # Errors
/// As [`subdivide`].
pub(crate) fn subdivide_mesh_faces_as<I: VertexId>(
    mesh: &Mesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    id: impl Fn(u32) -> I + Sync,
) -> Result<(Faces<I>, Stats)> {
    if scheme.is_polygonal() {
        let (fine, stats) = subdivide(mesh, scheme, levels, opts)?;
        return Ok((Faces::of_mapped(&fine, id), stats));
    }
    let (fine, stats) = refine_levels(mesh, &mesh.positions, (scheme, levels, opts), Some(&id), |_, _| true)?;
    Ok(match fine {
        Refined::Table(ct, positions, ..) => Faces::of_table(&ct, positions, id),
        Refined::Faces(t) => t,
    })
    .map(|t| (t, stats))
}

/// [`subdivide_mesh_faces_as`] from the f64 control points `control`: the
/// one-shot passes in f64 for a triangle scheme (a polygon scheme's levels
/// through [`precise::subdivide_mesh_f64`]).
///
/// # Errors
/// `control` not one point per vertex; as [`subdivide`].
pub(crate) fn subdivide_mesh_faces_f64<I: VertexId>(
    mesh: &Mesh,
    control: &[DVec3],
    (scheme, levels, opts): (Scheme, u32, &Options),
    id: impl Fn(u32) -> I + Sync,
) -> Result<(Faces<I, DVec3>, Stats)> {
    if scheme.is_polygonal() || control.len() != mesh.positions.len() {
        let (fine, positions) = precise::subdivide_mesh_f64(mesh, control, scheme, levels, opts)?;
        return Ok((Faces::of_table(&fine.ct, positions, id), Stats::default()));
    }
    let (fine, stats) = refine_levels(mesh, control, (scheme, levels, opts), Some(&id), |_, _| true)?;
    Ok(match fine {
        Refined::Table(ct, positions, ..) => Faces::of_table(&ct, positions, id),
        Refined::Faces(t) => t,
    })
    .map(|t| (t, stats))
}

/// The levels of a triangle scheme, the last one as faces only, its ids
/// through `faces_only`, when that is given (and the last level reached:
/// `progress` may stop the work earlier, after a level with its table).
pub(crate) fn refine_levels<I: VertexId, M: Fn(u32) -> I + Sync, P: rules::Coord>(
    mesh: &Mesh,
    control: &[P],
    (scheme, levels, opts): (Scheme, u32, &Options),
    faces_only: Option<&M>,
    mut progress: impl FnMut(u32, u32) -> bool,
) -> Result<(Refined<I, P>, Stats)> {
    let t0 = Instant::now();
    let keep = if faces_only.is_some() && levels > 0 { Keep::BeforeFaces } else { Keep::Finest };
    let mut b = build(&mesh.ct, control, (scheme, levels, opts), keep, &mut progress)?;
    if levels == 0 {
        // no level: the control table itself, without the boundary's corner tags
        return Ok((Refined::Table(mesh.ct.clone(), control.to_vec(), None, Vec::new()), b.stats));
    }
    let positions = b.points.pop().unwrap_or_default();
    let (Some(id), true) = (faces_only, b.stats.faces_per_level.len() + 1 == levels as usize) else {
        return Ok((Refined::Table(b.fine, positions, None, Vec::new()), b.stats));
    };
    // the last level as faces alone, its ids through `id`
    let one = OneLevel {
        ct: Cow::Owned(b.fine),
        positions: Cow::Owned(positions),
        boundary: b.carry,
        last: true,
        faces_only: Some(id),
        creasing: opts.creasing,
        stats: &mut b.stats,
    };
    let fine = with_rules(scheme, opts, one);
    if let Refined::Faces(f) = &fine {
        b.stats.faces_per_level.push(f.num_faces());
    }
    b.stats.finish(t0);
    Ok((fine, b.stats))
}

/// Refines the polygon mesh `mesh` `levels` times with a polygon scheme
/// (Catmull-Clark or bilinear; a triangle scheme is an error: fan the
/// mesh and use [`subdivide`]).
///
/// # Errors
/// [`crate::Error::TooLarge`] when a level would exceed the memory limit or
/// 32-bit ids; [`crate::Error::Usage`] for a triangle scheme.
pub(crate) fn subdivide_poly(
    mesh: &PolyMesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
) -> Result<(PolyMesh, Stats)> {
    subdivide_poly_with_progress(mesh, scheme, levels, opts, |_, _| true)
}

/// [`subdivide_poly`] calling `progress(level_done, levels)` after each
/// level; if it returns `false` the work stops and `Ok` holds the last
/// finished level.
///
/// # Errors
/// See [`subdivide_poly`].
pub(crate) fn subdivide_poly_with_progress(
    mesh: &PolyMesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    mut progress: impl FnMut(u32, u32) -> bool,
) -> Result<(PolyMesh, Stats)> {
    poly_kept((&mesh.pt, &mesh.positions), (scheme, levels, opts), &mut progress)?.into_poly()
}

/// The last level of a polygon scheme's quads alone, every vertex id `j`
/// written as `id(j)` in the pass that writes them (see
/// [`subdivide_mesh_faces_as`]).
///
/// # Errors
/// As [`subdivide_poly`]; no level.
pub(crate) fn subdivide_poly_faces_as<I: VertexId>(
    mesh: &PolyMesh,
    scheme: Scheme,
    levels: u32,
    opts: &Options,
    id: impl Fn(u32) -> I + Sync,
) -> Result<(Faces<I>, Stats)> {
    if levels == 0 {
        return Err(crate::Error::Usage("faces alone come from at least one level (quads after it)".into()));
    }
    if !scheme.is_polygonal() {
        return Err(crate::Error::Usage(format!("{scheme} subdivides triangles: fan the polygons first")));
    }
    // the levels before the last (none: the control mesh, its boundary's
    // corners tagged), then the last one as quads alone
    let mut b = build(&mesh.pt, &mesh.positions, (scheme, levels, opts), Keep::BeforeFaces, &mut |_, _| true)?;
    let before = PolyMesh { pt: b.fine, positions: b.points.pop().unwrap_or_default() };
    let mut stats = b.stats;
    let t0 = Instant::now();
    let fine = match scheme {
        Scheme::Bilinear => {
            refine::poly::level_faces(&catmull_clark::Bilinear, &before, (opts.creasing, &id), &mut stats)
        }
        _ => {
            let r = catmull_clark::CatmullClark::new(opts);
            refine::poly::level_faces(&r, &before, (opts.creasing, &id), &mut stats)
        }
    };
    stats.faces_per_level.push(fine.num_faces());
    stats.total_ms += ms(t0.elapsed());
    stats.huge_pages = Some(crate::mem::huge_pages());
    Ok((fine, stats))
}
