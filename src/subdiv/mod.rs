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
pub(crate) mod inspect;
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

use crate::Result;
pub(crate) use crate::mem::default_memory_limit;
#[cfg(feature = "viewer")]
pub(crate) use crate::mesh::attributes::UvInterpolation;
use crate::mesh::poly::PolyMesh;
use crate::mesh::{CornerTable, Faces, Mesh, VertexId};
use glam::DVec3;
pub(crate) use refine::check_levels_fit;
use refine::{OneLevel, Refined};
use rules::{catmull_clark, features, loop_};
use std::borrow::Cow;
use std::time::Instant;

pub use cage::{Cage, subdivide, subdivide_f64, subdivide_faces, subdivide_faces_f64};
pub use loop_::LoopBeta;
pub use parts::{Part, parts_by_options, subdivide_parts};
pub use precise::{PlanF64, plan_f64};
pub use refiner::{Refiner, Scalar};
pub use scheme::{Options, Scheme, Stats};
pub(crate) use scheme::{RulesFn, ms, with_rules};
#[cfg(feature = "viewer")]
pub(crate) use sizes::ControlCounts;

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
    let t0 = Instant::now();
    check_levels_fit(&mesh.ct, levels, opts.max_memory.or_else(default_memory_limit), true)?;
    let mut stats = Stats::default();
    let mut cur = features::with_boundary_corners(&mesh.ct, opts.boundary).into_owned();
    let mut points = vec![mesh.positions.clone()];
    let (mut kept, mut boundary) = (Vec::with_capacity(levels as usize), None);
    for level in 1..=levels {
        let one = OneLevel {
            ct: Cow::Borrowed(&cur),
            positions: Cow::Borrowed(points.last().map_or(&[][..], Vec::as_slice)),
            boundary: boundary.take(),
            last: level == levels,
            faces_only: None::<&fn(u32) -> u32>,
            creasing: opts.creasing,
            stats: &mut stats,
        };
        let Refined::Table(next, next_points, next_boundary, owners) = with_rules(scheme, opts, one) else {
            unreachable!("a level made faces without being asked")
        };
        boundary = next_boundary;
        stats.faces_per_level.push(next.num_triangles());
        kept.push((std::mem::replace(&mut cur, next), owners));
        points.push(next_points);
        if !progress(level, levels) {
            break;
        }
    }
    stats.finish(t0);
    // no level: the control table itself, without the boundary's corner tags
    let fine = if kept.is_empty() { mesh.ct.clone() } else { cur };
    let tables = tables::plan::LevelTables::Triangles(kept);
    Ok(Levels { tables, fine: Some(fine), fine_poly: None, points, stats })
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
    let t0 = Instant::now();
    refine::poly::check_levels_fit(pt, levels, opts.max_memory.or_else(default_memory_limit), true)?;
    let mut stats = Stats::default();
    let mut cur = features::boundary_tagged(pt, opts.boundary).unwrap_or_else(|| pt.clone());
    let (mut kept, mut points) = (Vec::with_capacity(levels as usize), Vec::with_capacity(levels as usize + 1));
    points.push(control.to_vec());
    for level in 1..=levels {
        let from = (&cur, points.last().map_or(&[][..], Vec::as_slice));
        let (next, next_points) = match scheme {
            Scheme::Bilinear => refine::poly::level(&catmull_clark::Bilinear, from, opts.creasing, &mut stats),
            _ => refine::poly::level(&catmull_clark::CatmullClark::new(opts), from, opts.creasing, &mut stats),
        };
        stats.faces_per_level.push(next.num_faces());
        kept.push(std::mem::replace(&mut cur, next));
        points.push(next_points);
        if !progress(level, levels) {
            break;
        }
    }
    stats.finish(t0);
    let tables = tables::plan::LevelTables::Polygons(kept);
    Ok(Levels { tables, fine: None, fine_poly: Some(cur), points, stats })
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
    let limit = opts.max_memory.or_else(default_memory_limit);
    let mut stats = Stats::default();
    check_levels_fit(&mesh.ct, levels, limit, false)?;
    let mut cur: Option<(CornerTable, Vec<P>)> = None;
    let mut boundary: Option<Vec<bool>> = None;
    let mut base = Some(features::with_boundary_corners(&mesh.ct, opts.boundary));
    for level in 1..=levels {
        // each level after the first owns (and may cut, see refine::with_features)
        // the one before it
        let (ct, positions) = match cur.take() {
            Some((t, p)) => (Cow::Owned(t), Cow::Owned(p)),
            None => (base.take().unwrap_or(Cow::Borrowed(&mesh.ct)), Cow::Borrowed(control)),
        };
        let last = level == levels;
        let (boundary_in, creasing) = (boundary.take(), opts.creasing);
        let one = OneLevel {
            ct,
            positions,
            boundary: boundary_in,
            last,
            faces_only: faces_only.filter(|_| last),
            creasing,
            stats: &mut stats,
        };
        match with_rules(scheme, opts, one) {
            Refined::Table(next, points, next_boundary, _) => {
                boundary = next_boundary;
                stats.faces_per_level.push(next.num_triangles());
                cur = Some((next, points));
            }
            Refined::Faces(t) => {
                stats.faces_per_level.push(t.num_faces());
                stats.finish(t0);
                return Ok((Refined::Faces(t), stats));
            }
        }
        if !progress(level, levels) {
            break;
        }
    }
    stats.finish(t0);
    let (ct, positions) = cur.unwrap_or_else(|| (mesh.ct.clone(), control.to_vec()));
    Ok((Refined::Table(ct, positions, None, Vec::new()), stats))
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
    let limit = opts.max_memory.or_else(default_memory_limit);
    refine::poly::check_levels_fit(&mesh.pt, levels, limit, false)?;
    // the levels before the last (none: the control mesh, its boundary's
    // corners tagged as subdivide_poly tags them), then the last one
    let (before, mut stats) = subdivide_poly(mesh, scheme, levels - 1, opts)?;
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
