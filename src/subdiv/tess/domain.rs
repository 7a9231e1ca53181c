//! The tessellation's domain: the patches the evaluator parameterises
//! (Loop: control triangles; Catmull-Clark: ptex faces) and the edges they
//! share, so that every point on a shared edge is made once and both sides
//! use it (no crack, no T-junction).
//!
//! A patch's corners are *keys*: a control vertex, the midpoint of a
//! control edge (a corner of an n-gon's ptex faces) or the centre of an
//! n-gon. A patch side runs from corner `s` to corner `s + 1` and is one
//! *domain edge* or two: a Catmull-Clark quad whose edge it shares with an
//! n-gon's ptex faces has that edge in two halves, meeting at the
//! midpoint, because the n-gon's side is a half.

use super::grid::{CORNERS_QUAD, CORNERS_TRI};
use crate::mesh::Mesh;
use crate::mesh::poly::{PolyMesh, PolyTable};
use crate::subdiv::eval::catmark::{QUAD, ptex_faces};
use std::collections::HashMap;

/// One patch: a face of the evaluator's domain.
#[derive(Clone, Debug)]
pub(super) struct Patch {
    /// The evaluator's face (Loop: the triangle; Catmull-Clark: the ptex face).
    pub face: u32,
    /// A unit square (Catmull-Clark) rather than a triangle (Loop).
    pub quad: bool,
    /// The corners' keys (three used on a triangle).
    pub corners: [u32; 4],
    /// The sides, corner `s` to corner `s + 1`.
    pub sides: [Side; 4],
}

impl Patch {
    /// Corners (and sides): 3 or 4.
    pub(super) fn sides(&self) -> usize {
        if self.quad { 4 } else { 3 }
    }

    /// Corner `k`'s `(u, v)`.
    pub(super) fn corner_uv(&self, k: usize) -> (f64, f64) {
        if self.quad { CORNERS_QUAD[k % 4] } else { CORNERS_TRI[k % 3] }
    }

    /// The point at fraction `t` of side `s`.
    pub(super) fn side_uv(&self, s: usize, t: f64) -> (f64, f64) {
        let (a, b) = (self.corner_uv(s), self.corner_uv(s + 1));
        (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
    }
}

/// A side: one domain edge, or two halves.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Side {
    /// The domain edges in order from the side's first corner, each with
    /// whether it runs the other way (from its `ends[1]`).
    pub parts: [(u32, bool); 2],
    /// 1 or 2.
    pub count: u8,
}

/// An edge of the domain, between two keys, shared by the patches on
/// either side.
#[derive(Clone, Copy, Debug)]
pub(super) struct DomainEdge {
    /// Its end keys, in the direction its points are listed.
    pub ends: [u32; 2],
    /// The patch, side and part it was first met on (its points are
    /// evaluated there).
    pub owner: (u32, u8, u8),
}

/// The patches and their shared edges.
pub(super) struct Domain {
    pub patches: Vec<Patch>,
    pub edges: Vec<DomainEdge>,
    /// Keys: vertices, then edge midpoints, then face centres.
    pub num_keys: usize,
}

/// Collects the domain edges, each made once for the key pair and the
/// control edge it lies on.
#[derive(Default)]
struct Edges {
    edges: Vec<DomainEdge>,
    index: HashMap<(u32, u32), u32>,
}

impl Edges {
    /// The part of a side from key `a` to key `b`, found by `id` (unique
    /// per domain edge); made here the first time, owned by `owner`.
    fn part(&mut self, id: (u32, u32), a: u32, b: u32, owner: (u32, u8, u8)) -> (u32, bool) {
        let next = self.edges.len() as u32;
        let e = *self.index.entry(id).or_insert(next);
        if e == next {
            self.edges.push(DomainEdge { ends: [a, b], owner });
        }
        (e, self.edges[e as usize].ends[0] != a)
    }
}

/// Dense numbers of the control edges, by the corner that owns each
/// (`owner(c)` gives the corner standing for `c`'s edge).
fn edge_numbers(corners: usize, owner: impl Fn(u32) -> u32) -> Vec<u32> {
    let mut number = vec![u32::MAX; corners];
    let mut next = 0;
    for c in 0..corners as u32 {
        let o = owner(c) as usize;
        if number[o] == u32::MAX {
            number[o] = next;
            next += 1;
        }
        number[c as usize] = number[o];
    }
    number
}

/// Loop's domain: every control triangle but the holes.
pub(super) fn triangles(mesh: &Mesh) -> Domain {
    let ct = &mesh.ct;
    let nv = ct.num_vertices() as u32;
    // the edge opposite corner c, numbered by the smaller corner of its two
    let number = edge_numbers(ct.num_corners(), |c| ct.o(c).map_or(c, |o| o.min(c)));
    let mut edges = Edges::default();
    let mut patches = Vec::with_capacity(ct.num_triangles());
    for f in 0..ct.num_triangles() as u32 {
        if ct.is_hole(f) {
            continue;
        }
        let key = |i: u32| ct.vtx(3 * f + i % 3);
        let id = patches.len() as u32;
        let mut sides = [Side::default(); 4];
        for (s, side) in sides.iter_mut().enumerate().take(3) {
            let s3 = s as u32;
            let e = number[(3 * f + (s3 + 2) % 3) as usize];
            let part = edges.part((nv + e, u32::MAX), key(s3), key(s3 + 1), (id, s as u8, 0));
            *side = Side { parts: [part, (0, false)], count: 1 };
        }
        patches.push(Patch { face: f, quad: false, corners: [key(0), key(1), key(2), 0], sides });
    }
    Domain { patches, edges: edges.edges, num_keys: nv as usize + ct.num_corners() }
}

/// Catmull-Clark's domain: the ptex faces of every polygon but the holes.
pub(super) fn ptex(mesh: &PolyMesh) -> Domain {
    let pt = &mesh.pt;
    let nv = pt.num_vertices() as u32;
    let number = edge_numbers(pt.num_corners(), |c| pt.twin(c).map_or(c, |t| t.min(c)));
    let ne = number.iter().copied().max().map_or(0, |m| m + 1);
    // an edge with an n-gon on either side is met in halves by its ptex faces
    let mut halved = vec![false; ne as usize];
    for f in 0..pt.num_faces() as u32 {
        if pt.face_size(f) != 4 && !pt.is_hole(f) {
            for c in pt.face_corners(f) {
                halved[number[c as usize] as usize] = true;
            }
        }
    }
    let mut b =
        PtexBuilder { pt, number: &number, halved: &halved, nv, ne, edges: Edges::default(), patches: Vec::new() };
    for (p, &(f, corner)) in ptex_faces(pt).iter().enumerate() {
        if !pt.is_hole(f) {
            b.patch(p as u32, f, corner);
        }
    }
    Domain { patches: b.patches, edges: b.edges.edges, num_keys: (nv + ne) as usize + pt.num_faces() }
}

/// Makes the ptex patches and their edges.
struct PtexBuilder<'a> {
    pt: &'a PolyTable,
    number: &'a [u32],
    halved: &'a [bool],
    nv: u32,
    ne: u32,
    edges: Edges,
    patches: Vec<Patch>,
}

impl PtexBuilder<'_> {
    /// The key of the midpoint of the edge leaving corner `c`.
    fn mid(&self, c: u32) -> u32 {
        self.nv + self.number[c as usize]
    }

    /// The patch of ptex face `p`: polygon `f`, its corner `corner` ([`QUAD`]
    /// for a quad).
    fn patch(&mut self, p: u32, f: u32, corner: u32) {
        let id = self.patches.len() as u32;
        let pt = self.pt;
        let mut sides = [Side::default(); 4];
        let corners = if corner == QUAD {
            let c: Vec<u32> = pt.face_corners(f).collect();
            for s in 0..4 {
                sides[s] = self.whole_side(c[s], c[(s + 1) % 4], (id, s as u8));
            }
            [pt.vtx(c[0]), pt.vtx(c[1]), pt.vtx(c[2]), pt.vtx(c[3])]
        } else {
            let c = pt.face_corners(f).start + corner;
            let before = pt.prev(c);
            let (v, centre) = (pt.vtx(c), self.nv + self.ne + f);
            let (m_out, m_in) = (self.mid(c), self.mid(before));
            let one = |part| Side { parts: [part, (0, false)], count: 1 };
            sides[0] = one(self.edges.part((m_out, v), v, m_out, (id, 0, 0)));
            sides[1] = one(self.edges.part((m_out, centre), m_out, centre, (id, 1, 0)));
            sides[2] = one(self.edges.part((m_in, centre), centre, m_in, (id, 2, 0)));
            sides[3] = one(self.edges.part((m_in, v), m_in, v, (id, 3, 0)));
            [v, m_out, centre, m_in]
        };
        self.patches.push(Patch { face: p, quad: true, corners, sides });
    }

    /// The side of a quad along the edge leaving corner `c` (to corner
    /// `d`), whole or in halves.
    fn whole_side(&mut self, c: u32, d: u32, (id, s): (u32, u8)) -> Side {
        let (a, b, m) = (self.pt.vtx(c), self.pt.vtx(d), self.mid(c));
        if !self.halved[self.number[c as usize] as usize] {
            let part = self.edges.part((m, u32::MAX), a, b, (id, s, 0));
            return Side { parts: [part, (0, false)], count: 1 };
        }
        let first = self.edges.part((m, a), a, m, (id, s, 0));
        let second = self.edges.part((m, b), m, b, (id, s, 1));
        Side { parts: [first, second], count: 2 }
    }
}
