//! Refinement of polygon meshes (Catmull-Clark, bilinear), level after
//! level: the quad split ([`crate::mesh::poly::split`]), then the new
//! points. Face points first, then edge points from them, then vertex
//! points from both (the direct evaluation of the masks of
//! [`crate::subdiv::rules::catmull_clark`], reusing the face points instead
//! of expanding them), then the points of sharp features again through
//! their blended stencils. New vertex ids: old vertices keep theirs, edge
//! `e` is `nv + e`, face `f` is `nv + ne + f`.

use super::super::rules::catmull_clark::{PolyLevel, PolyOn, PolyRules, smooth_triangle_edge};
use super::super::rules::features::Features;
use super::super::rules::{Coord, scatter_parts};

use crate::clock::Instant;
use crate::mesh::poly::{PolyMesh, PolyTable, split};
use crate::mesh::split::{EdgeIds, Owners};
use crate::mesh::{BORDER, Creasing};
use crate::mesh::{Faces, VertexId};
use crate::subdiv::scheme::{Stats, ms};
use rayon::prelude::*;

/// One level of `r` on the table `pt` with the points `pos` (f32 or f64:
/// the same passes, the weights rounded to the points' precision), timed
/// into `stats`: the next table and its points.
pub(crate) fn level<R: PolyRules, P: Coord>(
    r: &R,
    (pt, pos): (&PolyTable, &[P]),
    creasing: Creasing,
    stats: &mut Stats,
) -> (PolyTable, Vec<P>) {
    let t0 = Instant::now();
    let (next, edges) = split::split(pt, creasing);
    stats.split_ms += ms(t0.elapsed());
    let positions = points(r, (pt, pos), (Owners::List(&edges.owners), &edges.ids), creasing, stats);
    (next, positions)
}

/// [`level`] as faces alone (its quads, without twins, C or valences: the
/// last level of [`crate::subdiv::subdivide_poly_faces_as`]), every vertex
/// id through `id`.
pub(crate) fn level_faces<R: PolyRules, I: VertexId>(
    r: &R,
    mesh: &PolyMesh,
    (creasing, id): (Creasing, &(impl Fn(u32) -> I + Sync)),
    stats: &mut Stats,
) -> Faces<I> {
    let t0 = Instant::now();
    let (corners, ids) = split::split_faces(&mesh.pt, id);
    stats.split_ms += ms(t0.elapsed());
    let positions = points(r, (&mesh.pt, &mesh.positions), (Owners::Bits(&ids), &ids), creasing, stats);
    // the quads of a hole's corners are left out
    let mut holes: Vec<u32> = mesh.pt.holes().iter().flat_map(|&f| mesh.pt.face_corners(f)).collect();
    holes.sort_unstable();
    Faces { positions, corners, sides: 4 }.without(&holes)
}

/// The points of the level after `mesh`, whose edges the split numbered
/// (`owners` in edge order, `ids` per corner): face points, then vertex
/// points (the edge part, not yet written, serving as their scratch
/// memory), then edge points.
fn points<R: PolyRules, P: Coord>(
    r: &R,
    (old, pos): (&PolyTable, &[P]),
    (owners, ids): (Owners, &EdgeIds),
    creasing: Creasing,
    stats: &mut Stats,
) -> Vec<P> {
    let (nv, ne, nf) = (old.num_vertices(), owners.len(), old.num_faces());
    let mut positions: Vec<P> = crate::mem::zeroed(nv + ne + nf);
    let (vpart, rest) = positions.split_at_mut(nv);
    let (epart, fpart) = rest.split_at_mut(ne);
    let features = if R::SMOOTH { Features::of(old, creasing) } else { None };
    let lv = PolyLevel { pt: old, features: features.as_ref() };
    let t1 = Instant::now();
    face_points(old, pos, fpart);
    let t2 = Instant::now();
    vertex_points::<R, P>(&lv, pos, fpart, vpart, epart);
    let t3 = Instant::now();
    edge_points(r, &lv, owners, pos, fpart, epart);
    stats.edge_ms += ms(t2 - t1) + ms(t3.elapsed());
    stats.vertex_ms += ms(t3 - t2);
    if let Some(f) = &features {
        let slot = |c: u32| ids.edge(c, old.twin_entry(c)) as usize;
        super::feature_points(&PolyOn { r, lv: &lv }, f, pos, Some(vpart), epart, slot);
    }
    positions
}

/// Every face's point: the average of its vertices.
fn face_points<P: Coord>(pt: &PolyTable, pos: &[P], out: &mut [P]) {
    if pt.is_quads() {
        // the same sums in the same order, without a face lookup per face:
        // 70 k quads to level 3, one thread, warm, 2 ms of the 24 that face
        // and edge points take
        let (quads, _) = pt.v_table().as_chunks::<4>();
        out.par_chunks_mut(4096).zip(quads.par_chunks(4096)).for_each(|(qs, vs)| {
            for (q, v) in qs.iter_mut().zip(vs) {
                let sum = v.iter().fold(P::ZERO, |s, &j| s + pos[j as usize]);
                *q = sum.over(4.0);
            }
        });
        return;
    }
    out.par_iter_mut().enumerate().with_min_len(4096).for_each(|(f, q)| {
        let r = pt.face_corners(f as u32);
        let k = f64::from(r.end - r.start);
        *q = r.fold(P::ZERO, |s, c| s + pos[pt.vtx(c) as usize]).over(k);
    });
}

/// How many edges ahead [`edge_points`] prefetches the face point across
/// the edge: 70 k quads to level 3, one thread, warm (`examples/phases`,
/// face and edge points), 26.9-27.8 ms without, 24.3-26.5 with (32), about
/// the same with 64.
const AHEAD: usize = 32;

/// Every edge's point, in owner order, from the face points `fp`.
fn edge_points<R: PolyRules, P: Coord>(r: &R, lv: &PolyLevel, owners: Owners, pos: &[P], fp: &[P], out: &mut [P]) {
    let pt = lv.pt;
    // the smooth triangle rule: only a control level has triangles
    let triangles = r.smooth_triangles() && !pt.is_quads();
    owners.par_pieces(out, |out, own| {
        for (i, (q, &c)) in out.iter_mut().zip(own).enumerate() {
            // the face across the edge is far in memory: its point is
            // fetched ahead, as the triangle schemes' edge pass does
            if let Some(&x) = own.get(i + AHEAD) {
                let t = pt.twin_entry(x);
                if t != BORDER {
                    crate::cpu::prefetch(fp, pt.face(t) as usize);
                }
            }
            let (a, b) = (pos[pt.vtx(c) as usize], pos[pt.vtx(pt.next(c)) as usize]);
            *q = match pt.twin(c) {
                Some(t) if R::SMOOTH => {
                    let (f0, f1) = (pt.face(c), pt.face(t));
                    let tri = triangles.then(|| smooth_triangle_edge(pt.face_size(f0), pt.face_size(f1))).flatten();
                    match tri {
                        // the weights rounded to the points' precision, as a sink rounds them
                        Some((we, wf)) => (a + b).times(we) + (fp[f0 as usize] + fp[f1 as usize]).times(wf),
                        None => (a + b + fp[f0 as usize] + fp[f1 as usize]).times(0.25),
                    }
                }
                _ => (a + b).times(0.5),
            };
        }
    });
}

/// Every old vertex's new position, from the face points `fp`. The sums
/// over each vertex's edges and faces are scattered from the corners in
/// order (corner `c` adds its edge's far end and its face's point to
/// `V[c]`: each edge leaving a vertex and each face at it has exactly one
/// such corner), which reads the tables as streams instead of walking every
/// fan through the twins; each thread sums its range of corners into a
/// buffer of its own (taken from `scratch` as far as it holds them), and
/// the buffers are added per vertex.
fn vertex_points<R: PolyRules, P: Coord>(lv: &PolyLevel, pos: &[P], fp: &[P], out: &mut [P], scratch: &mut [P]) {
    let pt = lv.pt;
    if !R::SMOOTH {
        out.par_iter_mut().zip(pos.par_iter()).with_min_len(8192).for_each(|(q, &p)| *q = p);
        return;
    }
    let nc = pt.num_corners();
    // parts of the size alone (the same bits on any number of threads)
    let parts = crate::mesh::scatter_count(nc + 1, 1 << 16);
    // an all-quad table is cut at whole quads and scattered a quad at a
    // time, next and face by arithmetic (the same sums in the same order:
    // 70 k quads to level 3, one thread, warm, 23.5-25.4 to 20.2-21.4 ms)
    let quads = pt.is_quads();
    let bound = |k: usize| if quads { (k * nc / parts) & !3 } else { k * nc / parts };
    let scatter = |acc: &mut [P], k: usize| {
        let range = bound(k)..bound(k + 1);
        if quads {
            let (vs, _) = pt.v_table()[range.clone()].as_chunks::<4>();
            for (i, v) in vs.iter().enumerate() {
                let f = fp[range.start / 4 + i];
                for j in 0..4 {
                    acc[v[j] as usize] += pos[v[(j + 1) % 4] as usize] + f;
                }
            }
            return;
        }
        for c in range.start as u32..range.end as u32 {
            let far = pos[pt.vtx(pt.next(c)) as usize];
            acc[pt.vtx(c) as usize] += far + fp[pt.face(c) as usize];
        }
    };
    let extra = &scatter_parts(out, parts, scratch, scatter);
    out.par_iter_mut().enumerate().with_min_len(4096).for_each(|(v, q)| {
        let p = pos[v];
        if pt.is_boundary_vertex(v as u32) {
            let (a, b) = lv.border_neighbours(v as u32);
            *q = (pos[a as usize] + pos[b as usize]).times(0.125) + p.times(0.75);
            return;
        }
        // (n - 2) / n and n^2 in f64, then rounded to the points' precision:
        // an f32 quotient rounded through f64 is the f32 quotient (53 >= 2 x 24 + 2)
        let n = f64::from(pt.valences()[v]);
        let sum = extra.iter().fold(*q, |s, e| s + e[v]);
        *q = p.times((n - 2.0) / n) + sum.over(n * n);
    });
}

/// A polygon table's counts, as the budget walks them.
#[derive(Clone, Copy)]
pub(crate) struct PolygonCounts(pub(crate) crate::mesh::counts::Counts);

impl super::LevelCounts for PolygonCounts {
    fn bytes(&self) -> u64 {
        let (h, nv, ne, nf) = (self.0.corners, self.0.vertices, self.0.edges, self.0.faces);
        // new V and T (8 bytes a corner), positions, C and valences (20 a
        // vertex), the old level alive, and the new level drawn as
        // triangles (2h of them: V, O and a generation, 27 bytes each)
        4 * h * 8 + (nv + ne + nf) * 20 + h * 8 + nv * 20 + 2 * h * 27
    }
    fn held_bytes(&self) -> u64 {
        // V and T (8 bytes a corner), positions, C and valences (20 a vertex)
        self.0.corners * 8 + self.0.vertices * 20
    }
    fn ids_overflow(&self) -> bool {
        let c = &self.0;
        4 * c.corners + 4 >= u64::from(u32::MAX) || c.vertices + c.edges + c.faces >= u64::from(u32::MAX)
    }
    fn faces_after(&self) -> u64 {
        self.0.corners
    }
    fn next(self) -> Self {
        PolygonCounts(self.0.quad_split())
    }
}
