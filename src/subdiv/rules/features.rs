//! Sharp features in the rules: which rule each vertex and edge of a level
//! gets, and how a scheme's masks are blended (docs/sharp-features.md §5-6; OpenSubdiv
//! `sdc/crease.cpp`, `sdc/scheme.h` `ComputeEdgeVertexMask` and
//! `ComputeVertexVertexMask`).
//!
//! The rules are the same for every scheme; only the masks differ:
//!
//! ```text
//! vertex rule     s_v > 0: corner; else by its sharp edges (border edges
//!                 count, they are infinitely sharp): 0 smooth, 1 dart,
//!                 2 crease, 3+ corner
//! vertex point    smooth, dart: the scheme's smooth mask
//!                 crease: the scheme's curve mask with the two crease
//!                         neighbours (Loop 3/4, 1/8, 1/8)
//!                 corner: v
//!                 a transition (the rule of the vertex after the split,
//!                 found from the subdivided sharpness, differs):
//!                 w * parent mask + (1 - w) * child mask, w the mean
//!                 sharpness of the features that become smooth, <= 1
//!                 (ComputeFractionalWeightAtVertex)
//! edge point      s = 0: the smooth mask; both halves staying sharp after
//!                 the split: the crease mask; else
//!                 s * crease mask + (1 - s) * smooth mask (s > 1 only
//!                 with Chaikin: see `edge_weight`)
//! ```
//!
//! Everything is sparse: only the vertices on sharp edges (and tagged ones)
//! and the sharp edges are classified; the rest of the level runs the
//! scheme's ordinary rules. Schemes whose smooth stencils reach across
//! edges ([`super::Rules::CUT_AT_CREASES`]: the butterfly family) evaluate them on
//! the level cut open along the edges that are creases at this level
//! ([`crate::mesh::cut`]), so a crease acts as a boundary for every stencil
//! that reaches it.

use crate::mesh::edges::EdgeTable;
use crate::mesh::poly::PolyTable;
use crate::mesh::sharpness::{BoundaryInterpolation, EdgeDecay, INFINITE, Sharpness, decrement};
use crate::mesh::{BORDER, CornerTable, Creasing, owns_edge};
use rayon::prelude::*;
use std::borrow::Cow;

/// Which mask a vertex point uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mask {
    /// The scheme's smooth mask (smooth and dart vertices).
    Smooth,
    /// The scheme's curve mask along the crease through these two neighbours.
    Crease(u32, u32),
    /// The vertex stays.
    Corner,
}

/// OpenSubdiv's vertex rules (`Sdc::Crease::Rule`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Rule {
    /// No sharp edge.
    Smooth,
    /// One sharp edge: the smooth mask, the edge keeps its crease rule.
    Dart,
    /// Two sharp edges.
    Crease,
    /// Three or more sharp edges, or a sharp vertex.
    Corner,
}

/// The rule and masks of one vertex on a sharp feature.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct VertexFeature {
    /// The vertex.
    pub vertex: u32,
    /// Its rule at this level.
    pub rule: Rule,
    /// The mask of this level's rule.
    pub parent: Mask,
    /// The mask of the rule it has after the split.
    pub child: Mask,
    /// Weight of `parent` (`1 - weight` goes to `child`); 1 without a
    /// transition.
    pub weight: f32,
}

/// An edge whose point uses the crease mask, fully or in part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct EdgeFeature {
    /// Its owner corner.
    pub owner: u32,
    /// Weight of the crease mask (1: a crease at this level; otherwise
    /// `1 - weight` goes to the smooth mask, negative past 1: see
    /// `edge_weight`).
    pub weight: f32,
}

/// The sharp features of one level, classified (see the module docs). Ids
/// are those of the uncut level; where the level is cut open
/// ([`Features::set_cut`]) the cut table's extra vertices map back through
/// [`Features::original`].
#[derive(Clone, Debug, Default)]
pub(crate) struct Features {
    vertices: Vec<VertexFeature>,
    edges: Vec<EdgeFeature>,
    nv: u32,
    copies: Vec<u32>,
}

/// One incident edge of a vertex: the neighbour and the edge's sharpness
/// now and after the split (at this vertex).
#[derive(Clone, Copy)]
struct Incident {
    other: u32,
    now: f32,
    next: f32,
}

impl Features {
    /// Classifies the sharp features of `ct`, or `None` when it has no
    /// sharpness (its borders are handled by every scheme's boundary rules).
    /// Parallel over the feature vertices and edges.
    pub(crate) fn of<T: EdgeTable>(ct: &T, creasing: Creasing) -> Option<Features> {
        let sharp = ct.sharpness()?;
        let decay = sharp.edge_decay(ct, creasing);
        let mut candidates: Vec<u32> = sharp.sharp_vertices().iter().map(|&(v, _)| v).collect();
        for &(c, _) in sharp.sharp_corners() {
            let (a, b) = ct.edge_ends(c);
            candidates.push(a);
            candidates.push(b);
        }
        candidates.sort_unstable();
        candidates.dedup();
        let vertices: Vec<VertexFeature> = candidates
            .par_iter()
            .with_min_len(256)
            .map_init(Vec::new, |inc, &v| classify_vertex(ct, &decay, v, sharp.vertex(v), inc))
            .collect();
        let mut edges: Vec<EdgeFeature> = sharp
            .sharp_corners()
            .par_iter()
            .with_min_len(256)
            .filter(|&&(c, _)| owns_edge(c, ct.twin_entry(c)))
            .map(|&(c, _)| EdgeFeature { owner: c, weight: edge_weight(ct, &decay, c) })
            .collect();
        // border edges at a feature vertex: their crease curve may end there
        for &v in &candidates {
            if !ct.is_boundary_vertex(v) {
                continue;
            }
            ct.each_edge_at(v, &mut |c, _| {
                if ct.twin_entry(c) == BORDER {
                    edges.push(EdgeFeature { owner: c, weight: 1.0 });
                }
            });
        }
        edges.par_sort_unstable_by_key(|e| e.owner);
        edges.dedup_by_key(|e| e.owner);
        Some(Features { vertices, edges, nv: ct.num_vertices() as u32, copies: Vec::new() })
    }

    /// Records that the level is evaluated cut open: cut vertex
    /// `nv + i` is a copy of `copies[i]`.
    pub(crate) fn set_cut(&mut self, copies: Vec<u32>) {
        self.copies = copies;
    }

    /// The uncut level's vertex that vertex `v` of the level's (possibly
    /// cut) table stands for.
    #[inline]
    pub(crate) fn original(&self, v: u32) -> u32 {
        if v < self.nv { v } else { self.copies[(v - self.nv) as usize] }
    }

    /// The copies made by the cut ([`Features::set_cut`]).
    pub(crate) fn copies(&self) -> &[u32] {
        &self.copies
    }

    /// The classified vertices, sorted by vertex.
    pub(crate) fn vertices(&self) -> &[VertexFeature] {
        &self.vertices
    }

    /// The edges that use the crease mask, sorted by owner corner.
    pub(crate) fn edges(&self) -> &[EdgeFeature] {
        &self.edges
    }

    /// The feature of vertex `v`, if it has one.
    #[inline]
    pub(crate) fn vertex(&self, v: u32) -> Option<&VertexFeature> {
        self.vertices.binary_search_by_key(&v, |f| f.vertex).ok().map(|i| &self.vertices[i])
    }

    /// The crease weight of the edge owned by `c`, if it has one.
    #[inline]
    pub(crate) fn edge(&self, c: u32) -> Option<f32> {
        self.edges.binary_search_by_key(&c, |e| e.owner).ok().map(|i| self.edges[i].weight)
    }

    /// The corners of the edges that are creases at this level (weight
    /// exactly 1, not border): where the level is cut for [`super::Rules::CUT_AT_CREASES`].
    pub(crate) fn cut_corners(&self, ct: &CornerTable) -> Vec<u32> {
        self.edges.iter().filter(|e| e.weight == 1.0 && ct.o_entry(e.owner) != BORDER).map(|e| e.owner).collect()
    }

    /// The neighbour of `v` that continues the crease through `v` beyond
    /// `from` (the other end of `v`'s second crease edge), or `None` where
    /// the crease curve ends at `v` (a dart or a corner). A vertex without
    /// a feature is a regular boundary vertex: its crease is the border,
    /// found in `ct`, the level's table (the cut does not touch it).
    pub(crate) fn crease_continues(&self, ct: &CornerTable, v: u32, from: u32) -> Option<u32> {
        match self.vertex(v) {
            Some(f) => match f.parent {
                Mask::Crease(a, b) => Some(if a == from { b } else { a }),
                _ => None,
            },
            None => {
                let (a, b) = ct.boundary_neighbours(v)?;
                let (a, b) = (self.original(a), self.original(b));
                Some(if a == from { b } else { a })
            }
        }
    }
}

/// The incident edges of `v` with their sharpness now and after the split.
fn incident<T: EdgeTable>(ct: &T, decay: &EdgeDecay, v: u32, out: &mut Vec<Incident>) {
    out.clear();
    ct.each_edge_at(v, &mut |c, other| {
        let s = ct.edge_sharpness(c);
        out.push(Incident { other, now: s, next: decay.at(s, v) });
    });
}

/// A rule and its mask from a vertex's sharpness and its edges' (`now` or
/// `next` values).
fn rule_of(vertex_sharpness: f32, edges: &[Incident], next: bool) -> (Rule, Mask) {
    let sharp = |e: &&Incident| if next { e.next > 0.0 } else { e.now > 0.0 };
    if vertex_sharpness > 0.0 {
        return (Rule::Corner, Mask::Corner);
    }
    let mut it = edges.iter().filter(sharp);
    match (it.next(), it.next(), it.next()) {
        (None, _, _) => (Rule::Smooth, Mask::Smooth),
        (Some(_), None, _) => (Rule::Dart, Mask::Smooth),
        (Some(a), Some(b), None) => (Rule::Crease, Mask::Crease(a.other, b.other)),
        _ => (Rule::Corner, Mask::Corner),
    }
}

fn classify_vertex<T: EdgeTable>(ct: &T, decay: &EdgeDecay, v: u32, sv: f32, inc: &mut Vec<Incident>) -> VertexFeature {
    incident(ct, decay, v, inc);
    let (rule, parent) = rule_of(sv, inc, false);
    let sv_next = decrement(sv);
    let (_, child) = rule_of(sv_next, inc, true);
    // ComputeFractionalWeightAtVertex: the features that become smooth
    let (mut sum, mut count) = (0.0f32, 0u32);
    if sv > 0.0 && sv_next <= 0.0 {
        sum += sv;
        count += 1;
    }
    for e in inc.iter() {
        let decays = match decay.is_uniform() {
            true => e.now > 0.0 && e.now <= 1.0,
            false => e.now > 0.0 && e.next <= 0.0,
        };
        if decays {
            sum += e.now;
            count += 1;
        }
    }
    let weight = if parent == child || count == 0 { 1.0 } else { (sum / count as f32).min(1.0) };
    VertexFeature { vertex: v, rule, parent, child, weight }
}

/// Weight of the crease mask for the sharp edge owned by `c`
/// (`ComputeEdgeVertexMask`).
///
/// OpenSubdiv asks the rule of the edge's child vertex: a crease when both
/// halves stay sharp after the split (weight 1), else (a dart or smooth
/// child) the parent's crease mask blended with the smooth one by the
/// edge's sharpness `s`, unclamped. Under uniform decay both halves stay
/// sharp exactly when `s > 1`, so the weight is `min(s, 1)`; under Chaikin
/// an edge of `s > 1` whose half decays to 0 at a vertex with softer edges
/// gets `s` itself, past 1 (`Refinement::reclassifySemisharpVertices`
/// makes its child a dart; `PrimvarRefiner` passes that rule on).
fn edge_weight<T: EdgeTable>(ct: &T, decay: &EdgeDecay, c: u32) -> f32 {
    let s = ct.edge_sharpness(c);
    let (a, b) = ct.edge_ends(c);
    if s >= INFINITE || (decay.at(s, a) > 0.0 && decay.at(s, b) > 0.0) {
        return 1.0;
    }
    s
}

/// The table the schemes see for level 0 with `boundary`: for
/// [`BoundaryInterpolation::EdgeAndCorner`] every boundary vertex with a
/// single face becomes an infinitely sharp corner (OpenSubdiv's
/// `TopologyRefinerFactory` does the same before refining); otherwise `ct`.
pub fn with_boundary_corners(ct: &CornerTable, boundary: BoundaryInterpolation) -> Cow<'_, CornerTable> {
    boundary_tagged(ct, boundary).map_or(Cow::Borrowed(ct), Cow::Owned)
}

/// A table of either kind as the boundary options change it: its holes,
/// the faces around a vertex, and copies with more holes or corners.
pub(crate) trait BoundaryTags: EdgeTable + Clone {
    /// The faces tagged as holes.
    fn hole_faces(&self) -> &[u32];
    /// Calls `f` with every face around `v`.
    fn each_face_at(&self, v: u32, f: &mut dyn FnMut(u32));
    /// The table with `holes` as its holes.
    fn holed(self, holes: Vec<u32>) -> Self;
    /// The table with `s` as its sharp features.
    fn sharpened(self, s: Option<Sharpness>) -> Self;
}

impl BoundaryTags for CornerTable {
    fn hole_faces(&self) -> &[u32] {
        self.holes()
    }
    fn each_face_at(&self, v: u32, f: &mut dyn FnMut(u32)) {
        self.fan(v).for_each(|c| f(c / 3));
    }
    fn holed(self, holes: Vec<u32>) -> Self {
        self.with_holes(holes)
    }
    fn sharpened(self, s: Option<Sharpness>) -> Self {
        self.with_sharpness(s)
    }
}

impl BoundaryTags for PolyTable {
    fn hole_faces(&self) -> &[u32] {
        self.holes()
    }
    fn each_face_at(&self, v: u32, f: &mut dyn FnMut(u32)) {
        self.fan(v).for_each(|c| f(self.face(c)));
    }
    fn holed(self, holes: Vec<u32>) -> Self {
        self.with_holes(holes)
    }
    fn sharpened(self, s: Option<Sharpness>) -> Self {
        self.with_sharpness(s)
    }
}

/// `t` as the schemes see it for the control level with `boundary`, or
/// `None` when the option changes nothing: with
/// [`BoundaryInterpolation::EdgeAndCorner`] every boundary vertex with a
/// single face is an infinitely sharp corner; with
/// [`BoundaryInterpolation::None`] the faces at a boundary vertex with a
/// border edge not tagged infinitely sharp are holes (both as OpenSubdiv's
/// `TopologyRefinerFactory` does before it sharpens the border).
pub(crate) fn boundary_tagged<T: BoundaryTags>(t: &T, boundary: BoundaryInterpolation) -> Option<T> {
    if boundary == BoundaryInterpolation::None {
        let holes = boundary_holes(t);
        return (!holes.is_empty()).then(|| {
            let all = t.hole_faces().iter().copied().chain(holes).collect();
            t.clone().holed(all)
        });
    }
    let corners = boundary_corners(t, boundary);
    (!corners.is_empty()).then(|| t.clone().sharpened(Sharpness::with_corners(t.sharpness().cloned(), &corners)))
}

/// The faces [`BoundaryInterpolation::None`] leaves out: those at a
/// boundary vertex with a border edge not tagged infinitely sharp.
fn boundary_holes<T: BoundaryTags>(t: &T) -> Vec<u32> {
    let tagged = |c: u32| t.sharpness().map_or(0.0, |s| s.corner(c));
    let mut out = Vec::new();
    for v in 0..t.num_vertices() as u32 {
        if !t.is_boundary_vertex(v) {
            continue;
        }
        let mut soft = false;
        t.each_edge_at(v, &mut |c, _| soft |= t.twin_entry(c) == BORDER && tagged(c) < INFINITE);
        if soft {
            t.each_face_at(v, &mut |f| out.push(f));
        }
    }
    out
}

/// The vertices `boundary` makes corners: with
/// [`BoundaryInterpolation::EdgeAndCorner`] the boundary vertices with a
/// single face (two edges, in either table), else none.
pub(crate) fn boundary_corners<T: EdgeTable>(t: &T, boundary: BoundaryInterpolation) -> Vec<u32> {
    if boundary != BoundaryInterpolation::EdgeAndCorner {
        return Vec::new();
    }
    (0..t.num_vertices() as u32).filter(|&v| t.valence(v) == 2 && t.is_boundary_vertex(v)).collect()
}

/// What `subdiv info` reports of a table's sharp features.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Summary {
    /// Tagged interior edges with sharpness > 0.
    pub sharp_edges: usize,
    /// Of those, the infinitely sharp ones.
    pub infinite_edges: usize,
    /// Vertices with a sharpness of their own.
    pub sharp_vertices: usize,
    /// Vertices with the corner rule (3+ sharp edges, border edges
    /// included, or a sharp vertex).
    pub corners: usize,
    /// Vertices with exactly one sharp edge.
    pub darts: usize,
    /// Vertices on a tagged crease with exactly two sharp edges (plain
    /// boundary vertices are not counted).
    pub crease_vertices: usize,
}

/// Counts the sharp features of `ct` (with `boundary`'s corners), as the
/// triangle schemes see them.
pub fn summary(ct: &CornerTable, boundary: BoundaryInterpolation) -> Summary {
    count(&*with_boundary_corners(ct, boundary))
}

/// Counts the sharp features of the polygon table `pt` (with `boundary`'s
/// corners), as the polygon schemes see them: `boundary` pins the
/// vertices of one polygon, where a fan may give a corner two triangles.
pub fn poly_summary(pt: &PolyTable, boundary: BoundaryInterpolation) -> Summary {
    let corners = boundary_corners(pt, boundary);
    if corners.is_empty() {
        return count(pt);
    }
    let sharp = Sharpness::with_corners(pt.sharpness().cloned(), &corners);
    count(&pt.clone().with_sharpness(sharp))
}

/// The counts of [`summary`] and [`poly_summary`], corners already applied.
fn count<T: EdgeTable>(t: &T) -> Summary {
    let Some(sharp) = t.sharpness() else { return Summary::default() };
    let owned = |&&(c, _): &&(u32, f32)| owns_edge(c, t.twin_entry(c)) && t.twin_entry(c) != BORDER;
    let mut s = Summary {
        sharp_edges: sharp.sharp_corners().iter().filter(owned).count(),
        infinite_edges: sharp.sharp_corners().iter().filter(owned).filter(|&&(_, x)| x >= INFINITE).count(),
        sharp_vertices: sharp.sharp_vertices().len(),
        ..Summary::default()
    };
    if let Some(f) = Features::of(t, Creasing::Uniform) {
        for v in f.vertices() {
            match v.rule {
                Rule::Corner => s.corners += 1,
                Rule::Dart => s.darts += 1,
                Rule::Crease => s.crease_vertices += 1,
                Rule::Smooth => {}
            }
        }
    }
    s
}
