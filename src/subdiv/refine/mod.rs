//! Refinement, level after level (OpenSubdiv's `vtr` layer): the split of
//! the table ([`crate::mesh::split`], which knows no scheme), then the
//! scheme's rules ([`super::rules`]) for the new points: the smooth and
//! boundary rules over the whole level, and the points of sharp features
//! again through their stencils. The time of each phase is added to the
//! caller's [`Stats`]; what a level would cost is predicted before it is
//! allocated.

pub(crate) mod build;
pub(crate) mod poly;

use super::rules::crease::{Blend, OnLevel, edge_stencil, vertex_stencil};
use super::rules::features::{Features, Mask};
use super::rules::{Accumulate, Coord, Level, Rules, boundary_flags};
use super::scheme::{RulesFn, Stats, ms};
use crate::clock::Instant;
use crate::mesh::counts::Counts;
use crate::mesh::split::{self, EdgeIds, Owners};
use crate::mesh::{CornerTable, Creasing, Faces, VertexId, n, p};
use crate::{Error, Result};
use glam::Vec3;
use rayon::prelude::*;
use std::borrow::Cow;

/// Predicted peak bytes of refining a mesh with `nt` triangles, `nv`
/// vertices and `ne` edges once (new tables, positions and scratch, plus the
/// old level still alive).
pub(crate) fn predict_level_bytes(nt: u64, nv: u64, ne: u64) -> u64 {
    let new_corners = 12 * nt;
    let new_verts = nv + ne;
    let new = new_corners * 8 + new_verts * (8 + 12);
    let scratch = 3 * nt * 4 + ne * 4;
    let old = 3 * nt * 8 + nv * 20;
    new + scratch + old
}

/// A level's counts as a budget check walks them, for either kind of
/// table: what refining it once costs, and what it becomes.
pub(crate) trait LevelCounts: Copy {
    /// Predicted peak bytes of refining the level once.
    fn bytes(&self) -> u64;
    /// Bytes of the level itself (its table and points), held while later
    /// levels are made when the levels are kept.
    fn held_bytes(&self) -> u64;
    /// Whether the refined level's ids would not fit in 32 bits.
    fn ids_overflow(&self) -> bool;
    /// The faces the refinement makes.
    fn faces_after(&self) -> u64;
    /// The counts after one refinement.
    fn next(self) -> Self;
}

/// A triangle table's counts, as the budget walks them.
#[derive(Clone, Copy)]
pub(crate) struct TriangleCounts(pub(crate) Counts);

impl LevelCounts for TriangleCounts {
    fn bytes(&self) -> u64 {
        let c = &self.0;
        predict_level_bytes(c.faces, c.vertices, c.edges)
    }
    fn held_bytes(&self) -> u64 {
        // V and O (8 bytes a corner), positions, C and valences (20 a vertex)
        self.0.corners * 8 + self.0.vertices * 20
    }
    fn ids_overflow(&self) -> bool {
        12 * self.0.faces >= u64::from(u32::MAX) || self.0.vertices + self.0.edges >= u64::from(u32::MAX)
    }
    fn faces_after(&self) -> u64 {
        4 * self.0.faces
    }
    fn next(self) -> Self {
        TriangleCounts(self.0.triangle_split())
    }
}

/// Checks that `levels` levels of a table of `counts` fit in `limit` bytes
/// and 32-bit ids, each level's peak with the levels before it that are
/// `kept` (all but the one it splits, which the peak counts): the one
/// budget walk of both kinds of table ([`level_peaks`]).
///
/// # Errors
/// [`Error::TooLarge`] naming the first level that does not fit.
pub(crate) fn check_fit<C: LevelCounts>(counts: C, levels: u32, limit: Option<u64>, kept: bool) -> Result<()> {
    let limit_bytes = limit.unwrap_or(u64::MAX);
    for (level, counts, bytes) in level_peaks(counts, levels, kept) {
        if counts.ids_overflow() || bytes > limit_bytes {
            let limit = limit_bytes.min(bytes.min(u64::MAX / 2));
            return Err(Error::TooLarge { level, faces: counts.faces_after(), bytes, limit });
        }
    }
    Ok(())
}

/// The predicted peak bytes of each of `levels` levels of a table of
/// `counts`, level 1 first: `(level, the counts it splits, its peak with the
/// levels before it that are kept)`. The walk ends after a level whose ids
/// overflow (its successors' counts would too).
pub(crate) fn level_peaks<C: LevelCounts>(counts: C, levels: u32, kept: bool) -> impl Iterator<Item = (u32, C, u64)> {
    let mut state = Some((counts, 0u64));
    (1..=levels).map_while(move |level| {
        let (counts, held) = state.take()?;
        let bytes = counts.bytes().saturating_add(held);
        if !counts.ids_overflow() {
            let held = if kept { held.saturating_add(counts.held_bytes()) } else { held };
            state = Some((counts.next(), held));
        }
        Some((level, counts, bytes))
    })
}

/// One level: split plus the scheme's points. `boundary` holds the input
/// level's vertex boundary flags when the previous level produced them;
/// the new level's are made only when another level follows (`last` false).
/// With `faces_only` (for the last level of [`super::subdivide_mesh_faces_as`])
/// the split writes the new V table alone ([`split::split_faces`]), every
/// vertex id through that map.
pub(crate) struct OneLevel<'a, M, P: Coord = Vec3> {
    pub(crate) ct: Cow<'a, CornerTable>,
    pub(crate) positions: Cow<'a, [P]>,
    pub(crate) boundary: Option<Vec<bool>>,
    pub(crate) last: bool,
    pub(crate) faces_only: Option<&'a M>,
    pub(crate) creasing: Creasing,
    pub(crate) stats: &'a mut Stats,
}

/// What [`OneLevel`] makes: the next level's table and points (and its
/// vertex boundary flags when another level follows, and the owner corners
/// of the old level's edges in the split's order), or its faces alone.
pub(crate) enum Refined<I = u32, P = Vec3> {
    Table(CornerTable, Vec<P>, Option<Vec<bool>>, Vec<u32>),
    Faces(Faces<I, P>),
}

/// The split's part of [`Refined`].
enum NewTable<I> {
    Full(CornerTable, Option<Vec<bool>>),
    Faces(Vec<I>),
}

impl<I: VertexId, M: Fn(u32) -> I + Sync, P: Coord> RulesFn<Refined<I, P>> for OneLevel<'_, M, P> {
    fn call<R: Rules>(self, r: &R) -> Refined<I, P> {
        let old: &CornerTable = &self.ct;
        let boundary = self.boundary.unwrap_or_else(|| boundary_flags(old));
        let t0 = Instant::now();
        // the faces alone come without a list of owners (Owners::Bits)
        let (table, list, ids) = if let Some(id) = self.faces_only {
            let (v, ids) = split::split_faces(old, id);
            (NewTable::Faces(v), None, ids)
        } else {
            let ((ct, edges, next_boundary), (number_ms, _)) =
                split::split_with_boundary(old, (!self.last).then_some(&boundary[..]), self.creasing);
            self.stats.numbering_ms += number_ms;
            (NewTable::Full(ct, next_boundary), Some(edges.owners), edges.ids)
        };
        self.stats.split_ms += ms(t0.elapsed());
        let holes = if matches!(table, NewTable::Faces(_)) { old.split_holes() } else { Vec::new() };
        let owners = list.as_deref().map_or(Owners::Bits(&ids), Owners::List);
        let level = (self.ct, self.positions, boundary);
        let positions = level_points(r, level, (owners, &ids), self.creasing, self.stats);
        match table {
            NewTable::Full(ct, next_boundary) => Refined::Table(ct, positions, next_boundary, list.unwrap_or_default()),
            // the holes' children are left out of the faces
            NewTable::Faces(corners) => Refined::Faces(Faces { positions, corners, sides: 3 }.without(&holes)),
        }
    }
}

/// The new points of one level of `r` on `ct` (the old points `pos`, the
/// vertex boundary flags `boundary`): the smooth and boundary rules over
/// the whole level, the sharp features' stencils over them; vertex points
/// first, then edge points in `owners` order. In the points' precision.
fn level_points<R: Rules, P: Coord>(
    r: &R,
    (ct, pos, boundary): (Cow<'_, CornerTable>, Cow<'_, [P]>, Vec<bool>),
    (owners, ids): (Owners, &EdgeIds),
    creasing: Creasing,
    stats: &mut Stats,
) -> Vec<P> {
    let nv = ct.num_vertices();
    let features = Features::of(&*ct, creasing);
    let mut positions: Vec<P> = crate::mem::zeroed(nv + owners.len());
    let (vpart, epart) = positions.split_at_mut(nv);
    match features {
        None => {
            let lv = Level::with_boundary(&ct, boundary);
            points(r, &lv, owners, &pos, vpart, epart, stats);
        }
        Some(f) => with_features(r, f, (ct, pos, boundary), (owners, ids), (vpart, epart), stats),
    }
    positions
}

/// The smooth and boundary points of a level through `r`, timed into `stats`.
fn points<R: Rules, P: Coord>(
    r: &R,
    lv: &Level,
    owners: Owners,
    pos: &[P],
    vpart: &mut [P],
    epart: &mut [P],
    stats: &mut Stats,
) {
    let t0 = Instant::now();
    r.vertex_points(lv, pos, vpart, epart);
    let t1 = Instant::now();
    r.edge_points(lv, owners, pos, vpart, epart);
    stats.vertex_ms += ms(t1 - t0);
    stats.edge_ms += ms(t1.elapsed());
}

/// One level of `r` on the table `ct` with sharp features `f` (one-shot
/// subdivision): the scheme's own evaluation with the smooth and boundary
/// rules, then the points of the feature vertices and edges again through
/// their stencils. For [`Rules::CUT_AT_CREASES`] the level is first cut
/// open along its creases, in place (`ct`, `pos` and `boundary` are this
/// level's, discarded after). `ids` gives each corner's edge id; the
/// phases are timed into `stats`.
fn with_features<R: Rules, P: Coord>(
    r: &R,
    mut f: Features,
    level: (Cow<'_, CornerTable>, Cow<'_, [P]>, Vec<bool>),
    edges: (Owners, &EdgeIds),
    out: (&mut [P], &mut [P]),
    stats: &mut Stats,
) {
    let ((ct, pos, mut boundary), (owners, ids), (vout, eout)) = (level, edges, out);
    if R::CUT_AT_CREASES {
        let (mut ct, mut pos) = (ct.into_owned(), pos.into_owned());
        let corners = f.cut_corners(&ct);
        // the cut's ends are on its border (ids taken before the cut renames
        // their later sectors, which are new vertices, on the border too)
        for &c in &corners {
            boundary[ct.vtx(n(c)) as usize] = true;
            boundary[ct.vtx(p(c)) as usize] = true;
        }
        let copies = ct.cut_in_place(&corners);
        boundary.resize(ct.num_vertices(), true);
        for &v in &copies {
            pos.push(pos[v as usize]);
        }
        f.set_cut(copies);
        let lv = Level::with_boundary(&ct, boundary).with_features(Some(&f));
        let mut vcut = vec![P::ZERO; ct.num_vertices()];
        points(r, &lv, owners, &pos, &mut vcut, eout, stats);
        vout.copy_from_slice(&vcut[..vout.len()]);
        correct(r, &lv, &f, ids, &pos, vout, eout);
    } else {
        let lv = Level::with_boundary(&ct, boundary).with_features(Some(&f));
        points(r, &lv, owners, &pos, vout, eout, stats);
        correct(r, &lv, &f, ids, &pos, vout, eout);
    }
}

/// The feature vertices' and edges' points through their stencils.
fn correct<R: Rules, P: Coord>(
    r: &R,
    lv: &Level,
    f: &Features,
    ids: &EdgeIds,
    pos: &[P],
    vout: &mut [P],
    eout: &mut [P],
) {
    let vout = if R::MOVES_VERTICES { Some(vout) } else { None };
    // every feature edge is listed by its owner corner (Features::of)
    feature_points(&OnLevel { r, lv }, f, pos, vout, eout, |c| ids.rank(c) as usize);
}

/// The points of a level's sharp features through their blended stencils
/// ([`vertex_stencil`], [`edge_stencil`]), over the points the smooth rules
/// wrote: the vertices whose mask is not smooth into `vout` (none where the
/// scheme keeps its old vertices), every feature edge into `eout` at
/// `slot(owner corner)`. Shared by the triangle and the polygon schemes.
pub(crate) fn feature_points<B: Blend + Sync, P: Coord>(
    b: &B,
    f: &Features,
    pos: &[P],
    vout: Option<&mut [P]>,
    eout: &mut [P],
    slot: impl Fn(u32) -> usize + Sync,
) {
    if let Some(vout) = vout {
        let points: Vec<(usize, P)> = f
            .vertices()
            .par_iter()
            .with_min_len(256)
            .filter(|vf| vf.parent != Mask::Smooth)
            .map(|vf| {
                let mut acc = Accumulate::new(pos);
                vertex_stencil(b, vf.vertex, &mut acc);
                (vf.vertex as usize, acc.sum)
            })
            .collect();
        for (v, q) in points {
            vout[v] = q;
        }
    }
    let points: Vec<(usize, P)> = f
        .edges()
        .par_iter()
        .with_min_len(256)
        .map(|ef| {
            let mut acc = Accumulate::new(pos);
            edge_stencil(b, ef.owner, &mut acc);
            (slot(ef.owner), acc.sum)
        })
        .collect();
    for (e, q) in points {
        eout[e] = q;
    }
}
