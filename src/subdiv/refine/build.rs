//! The one level builder (OpenSubdiv's `TopologyRefinerFactory` and
//! `RefineUniform`): the budget check, the boundary tagging and the level
//! loop, written once for both kinds of table behind [`Table`] (the
//! triangle table under the 1-to-4 split, the polygon table under the quad
//! split, as `vtr/triRefinement` and `vtr/quadRefinement` behind one
//! `vtr/refinement`), generic over the point type, with a [`Keep`] that
//! says what it keeps. Every consumer reads its [`Built`]: `subdivide` and
//! its faces-only and f64 forms, the [`crate::Refiner`], the stencil plans,
//! a vertex's stencil, the inspectors and the limit frames; none splits on
//! its own.

use super::{Refined, check_fit};
use crate::Result;
use crate::clock::Instant;
use crate::mesh::counts::Counts;
use crate::mesh::poly::PolyTable;
use crate::mesh::{BoundaryInterpolation, CornerTable, Creasing};
use crate::subdiv::rules::Coord;
use crate::subdiv::rules::features::boundary_tagged;
use crate::subdiv::scheme::{Options, Scheme, Stats, with_rules};
use crate::subdiv::tables::plan::LevelTables;
use std::borrow::Cow;

/// What [`build`] keeps of the levels it makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Keep {
    /// Every level's table and points (what a [`crate::Refiner`] keeps).
    Levels,
    /// The finest table and points alone (each level gives the last up).
    Finest,
    /// Every level's table, no points (stencil plans, inspectors): the
    /// control points are not read.
    Tables,
    /// The finest table and points one level short of the levels asked for
    /// (whose budget is checked), and what the last one needs: a caller
    /// that makes the last level as faces alone.
    BeforeFaces,
}

/// A table the builder refines, level after level.
pub(crate) trait Table: Clone + Default + Sized {
    /// What a level tells about the table it was made from, kept beside
    /// it: the owner corners of its edges (triangles), nothing (polygons).
    type Owners: Default;
    /// What one level hands the next: the triangle split's vertex boundary
    /// flags (made with the split, so the next level need not).
    type Carry: Default;
    /// Its counts, for the budget.
    fn counts(&self) -> Counts;
    /// Whether the counts walk the quad split.
    const QUADS: bool;
    /// The table with the boundary option's corners (or holes) tagged;
    /// `None`: as it is.
    fn tagged(&self, boundary: BoundaryInterpolation) -> Option<Self>;
    /// One level of topology: the next table and this one's owners.
    fn split(&self, creasing: Creasing) -> (Self, Self::Owners);
    /// One level of `scheme` with points `pos`, phases timed into `stats`.
    fn level<P: Coord>(
        table: Cow<'_, Self>,
        pos: Cow<'_, [P]>,
        carry: &mut Self::Carry,
        how: (Scheme, &Options, bool),
        stats: &mut Stats,
    ) -> (Self, Vec<P>, Self::Owners);
    /// Faces, for [`Stats::faces_per_level`].
    fn faces(&self) -> usize;
    /// The kept levels as the plans and the refiner hold them.
    fn into_tables(kept: Vec<(Self, Self::Owners)>) -> LevelTables;
}

/// The levels' tables a build keeps, each with its owners.
pub(crate) type Kept<T> = Vec<(T, <T as Table>::Owners)>;

/// What [`build`] made.
pub(crate) struct Built<T: Table, P> {
    /// The levels' tables (their boundary corners applied, their sharpness
    /// that level's) with their owners: every level's with
    /// [`Keep::Levels`] and [`Keep::Tables`], else none.
    pub(crate) kept: Kept<T>,
    /// The finest table: the tagged control table when no level was made.
    pub(crate) fine: T,
    /// Points: every level's with [`Keep::Levels`] (the control points
    /// first), the finest alone with [`Keep::Finest`] and
    /// [`Keep::BeforeFaces`], none with [`Keep::Tables`].
    pub(crate) points: Vec<Vec<P>>,
    /// What the next level needs ([`Keep::BeforeFaces`]).
    pub(crate) carry: T::Carry,
    /// The phases' times and the faces of each level.
    pub(crate) stats: Stats,
}

/// `levels` levels of `scheme` on `cage` with the control points `control`
/// (unread with [`Keep::Tables`]): the budget checked for all of them
/// before any is allocated, the boundary option's corners tagged on the
/// control table, then level after level, keeping what `keep` says.
/// `progress(level, levels)` after each level may stop the work (`false`):
/// what was made so far comes back.
///
/// # Errors
/// [`crate::Error::TooLarge`] when a level would exceed the options'
/// memory budget or 32-bit ids.
pub(crate) fn build<T: Table, P: Coord>(
    cage: &T,
    control: &[P],
    (scheme, levels, opts): (Scheme, u32, &Options),
    keep: Keep,
    progress: &mut dyn FnMut(u32, u32) -> bool,
) -> Result<Built<T, P>> {
    let t0 = Instant::now();
    let limit = opts.max_memory.or_else(crate::mem::default_memory_limit);
    check(cage.counts(), T::QUADS, levels, limit, keep == Keep::Levels)?;
    let mut built = Built {
        kept: Vec::with_capacity(levels as usize),
        fine: cage.tagged(opts.boundary).unwrap_or_else(|| cage.clone()),
        points: if keep == Keep::Tables { Vec::new() } else { vec![control.to_vec()] },
        carry: T::Carry::default(),
        stats: Stats::default(),
    };
    let made = if keep == Keep::BeforeFaces { levels.saturating_sub(1) } else { levels };
    for level in 1..=made {
        let last = level == levels;
        built.next_level(keep, (scheme, opts, last));
        if !progress(level, levels) {
            break;
        }
    }
    built.stats.finish(t0);
    Ok(built)
}

impl<T: Table, P: Coord> Built<T, P> {
    /// Makes the level after [`Built::fine`], keeping what `keep` says.
    fn next_level(&mut self, keep: Keep, (scheme, opts, last): (Scheme, &Options, bool)) {
        let (next, owners) = match keep {
            Keep::Tables => self.fine.split(opts.creasing),
            Keep::Levels => {
                let pos = self.points.last().map_or(&[][..], Vec::as_slice);
                let how = (scheme, opts, last);
                let (next, pts, owners) =
                    T::level(Cow::Borrowed(&self.fine), pos.into(), &mut self.carry, how, &mut self.stats);
                self.points.push(pts);
                (next, owners)
            }
            // each level owns (and may cut open) the one before it
            Keep::Finest | Keep::BeforeFaces => {
                let (table, pos) = (std::mem::take(&mut self.fine), self.points.pop().unwrap_or_default());
                let how = (scheme, opts, last);
                let (next, pts, _) =
                    T::level(Cow::Owned(table), Cow::Owned(pos), &mut self.carry, how, &mut self.stats);
                self.points.push(pts);
                self.stats.faces_per_level.push(next.faces());
                self.fine = next;
                return;
            }
        };
        self.stats.faces_per_level.push(next.faces());
        self.kept.push((std::mem::replace(&mut self.fine, next), owners));
    }
}

/// Checks that `levels` levels of a table of `counts` fit in `limit` bytes
/// and 32-bit ids, the earlier levels held too when they are `kept`: the
/// one budget check of the levels.
///
/// # Errors
/// [`crate::Error::TooLarge`] naming the first level that does not fit.
pub(crate) fn check(counts: Counts, quads: bool, levels: u32, limit: Option<u64>, kept: bool) -> Result<()> {
    match quads {
        true => check_fit(super::poly::PolygonCounts(counts), levels, limit, kept),
        false => check_fit(super::TriangleCounts(counts), levels, limit, kept),
    }
}

impl Table for CornerTable {
    type Owners = Vec<u32>;
    type Carry = Option<Vec<bool>>;
    const QUADS: bool = false;

    fn counts(&self) -> Counts {
        Counts::of_triangles(self)
    }
    fn tagged(&self, boundary: BoundaryInterpolation) -> Option<Self> {
        boundary_tagged(self, boundary)
    }
    fn split(&self, creasing: Creasing) -> (Self, Vec<u32>) {
        let (next, edges) = crate::mesh::split::split_with(self, creasing);
        (next, edges.owners)
    }
    fn level<P: Coord>(
        ct: Cow<'_, Self>,
        positions: Cow<'_, [P]>,
        boundary: &mut Option<Vec<bool>>,
        (scheme, opts, last): (Scheme, &Options, bool),
        stats: &mut Stats,
    ) -> (Self, Vec<P>, Vec<u32>) {
        let one = super::OneLevel {
            ct,
            positions,
            boundary: boundary.take(),
            last,
            faces_only: None::<&fn(u32) -> u32>,
            creasing: opts.creasing,
            stats,
        };
        match with_rules(scheme, opts, one) {
            Refined::Table(next, points, next_boundary, owners) => {
                *boundary = next_boundary;
                (next, points, owners)
            }
            // faces come only when a level is asked for them
            Refined::Faces(_) => unreachable!("a level made faces without being asked"),
        }
    }
    fn faces(&self) -> usize {
        self.num_triangles()
    }
    fn into_tables(kept: Vec<(Self, Vec<u32>)>) -> LevelTables {
        LevelTables::Triangles(kept)
    }
}

impl Table for PolyTable {
    type Owners = ();
    type Carry = ();
    const QUADS: bool = true;

    fn counts(&self) -> Counts {
        Counts::of_polygons(self)
    }
    fn tagged(&self, boundary: BoundaryInterpolation) -> Option<Self> {
        boundary_tagged(self, boundary)
    }
    fn split(&self, creasing: Creasing) -> (Self, ()) {
        (crate::mesh::poly::split::split(self, creasing).0, ())
    }
    fn level<P: Coord>(
        pt: Cow<'_, Self>,
        pos: Cow<'_, [P]>,
        _: &mut (),
        (scheme, opts, _): (Scheme, &Options, bool),
        stats: &mut Stats,
    ) -> (Self, Vec<P>, ()) {
        use crate::subdiv::rules::catmull_clark::{Bilinear, CatmullClark};
        let from = (&*pt, &*pos);
        let (next, points) = match scheme {
            Scheme::Bilinear => super::poly::level(&Bilinear, from, opts.creasing, stats),
            _ => super::poly::level(&CatmullClark::new(opts), from, opts.creasing, stats),
        };
        (next, points, ())
    }
    fn faces(&self) -> usize {
        self.num_faces()
    }
    fn into_tables(kept: Vec<(Self, ())>) -> LevelTables {
        LevelTables::Polygons(kept.into_iter().map(|(pt, ())| pt).collect())
    }
}

/// The level tables of `levels` levels of `scheme` on `cage` and the
/// finest table ([`Keep::Tables`]): what a stencil plan records its rows
/// on.
///
/// # Errors
/// As [`build`].
pub(crate) fn tables<T: Table>(cage: &T, how: (Scheme, u32, &Options)) -> Result<(Kept<T>, T)> {
    let b = build::<T, glam::Vec3>(cage, &[], how, Keep::Tables, &mut |_, _| true)?;
    Ok((b.kept, b.fine))
}
