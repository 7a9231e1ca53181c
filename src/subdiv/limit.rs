//! Loop limit positions and exact Loop limit normals ("snap to limit"),
//! schemes.md 5.3 and 5.4, plus tangent-mask normals for the interpolating
//! butterfly schemes (schemes.md 4).
//!
//! Every mask here is a left eigenvector of the local subdivision matrix, so
//! applying it to the control points of ANY level gives the value at the same
//! point of the limit surface (positions: eigenvalue 1) or a vector along the
//! limit tangent (tangents: the subdominant eigenvalues).
//!
//! ## Limit positions (schemes.md 5.3)
//! ```text
//! interior vertex v, valence n, neighbours p_i, Loop's beta(n):
//!     chi   = 1 / (n + 3 / (8 beta))
//!     v_inf = (1 - n chi) v + chi sum p_i
//!     regular (n = 6, beta = 1/16): v_inf = 1/2 v + 1/12 sum p_i
//!     n = 3 (beta = 3/16):          v_inf = 2/5 v + 1/5 sum p_i
//!     Warren's beta: chi = 1/(2n) for every n
//! boundary vertex, boundary neighbours q1, q2 (cubic B-spline limit):
//!     v_inf = 2/3 v + 1/6 (q1 + q2)
//! ```
//! Source: Loop 1987; Hoppe et al. 1994; OpenSubdiv `sdc/loopScheme.h`
//! (`assignSmoothLimitMask`, `assignCreaseLimitMask`, whose comment explains
//! why (1/6, 2/3, 1/6), not (1/5, 3/5, 1/5), matches the (1/2, 1/2) boundary
//! edge rule and (1/8, 3/4, 1/8) boundary vertex rule used by [`super::loop_`]).
//! Our boundary rule has no corners (a manifold vertex has exactly two border
//! edges; valence-2 vertices are smooth, OpenSubdiv's `EDGE_ONLY`), so every
//! boundary vertex uses the crease mask.
//!
//! ## Limit tangents (schemes.md 5.4)
//! ```text
//! interior vertex, neighbours p_0 .. p_{n-1} counter-clockwise, centre weight 0:
//!     t1 = sum cos(2 pi i / n) p_i,   t2 = sum sin(2 pi i / n) p_i
//!     normal = normalize(t1 x t2)
//!     regular: t1 = (1, 1/2, -1/2, -1, -1/2, 1/2), t2 = (0, r, r, 0, -r, -r), r = sqrt(3)/2
//! boundary vertex, ring e_0 .. e_m counter-clockwise from one border edge to
//! the other (m faces), centre v:
//!     t_along  = e_0 - e_m                      (OpenSubdiv: 3/2 (e_0 - e_m))
//!     t_across (points into the surface):
//!       m = 1: e_0 + e_1 - 2 v
//!       m = 2: e_1 - v
//!       m = 3: -2 v - e_0 + 2 e_1 + 2 e_2 - e_3
//!       m >= 4, theta = pi / m: centre 0, e_0 and e_m: -sin(theta),
//!               e_i (0 < i < m): 2 (1 - cos(theta)) sin(i theta)
//!     normal = normalize(t_along x t_across)
//! ```
//! Source: OpenSubdiv `sdc/loopScheme.h` `assignSmoothLimitTangentMasks` and
//! `assignCreaseLimitTangentMasks` (scaled: only directions matter for a
//! normal). Every tangent mask sums to 0, so it is translation invariant.
//! Where the cross product vanishes (degenerate geometry) the vertex falls back
//! to the area-weighted face normal ([`crate::mesh::normals`], schemes.md 4.4).
//!
//! Ring order: [`CornerTable::ring`] lists the neighbours in swing order,
//! which is counter-clockwise seen from outside for counter-clockwise faces;
//! for a boundary vertex it starts across the border edge of `C[v]` and ends
//! across the other border edge, the interior lying counter-clockwise from
//! `e_0`. So `t1 x t2` (interior) and `t_along x t_across` (boundary) point to
//! the same side as the face normals.

use super::LoopBeta;
use crate::mesh::normals::vertex_normals;
use crate::mesh::{CornerTable, Mesh};
use glam::{DVec3, Vec3};
use std::f64::consts::PI;

/// Loop limit positions with Loop's original beta (the default of
/// [`crate::Options`]); one per vertex, same ids as `mesh.positions`.
pub fn loop_limit_positions(mesh: &Mesh) -> Vec<Vec3> {
    loop_limit_positions_with(mesh, LoopBeta::Loop)
}

/// Loop limit positions for the vertex weights `beta` (Loop's or Warren's):
/// the masks of the module docs. The limit of a boundary vertex does not
/// depend on `beta`.
pub fn loop_limit_positions_with(mesh: &Mesh, beta: LoopBeta) -> Vec<Vec3> {
    let ct = &mesh.ct;
    let pos = &mesh.positions;
    let mut ring = Vec::with_capacity(16);
    (0..ct.num_vertices() as u32)
        .map(|v| {
            let x = pos[v as usize].as_dvec3();
            if ct.is_boundary_vertex(v) {
                let (q1, q2) = ct.boundary_neighbours(v);
                let q = pos[q1 as usize].as_dvec3() + pos[q2 as usize].as_dvec3();
                return (x * (2.0 / 3.0) + q * (1.0 / 6.0)).as_vec3();
            }
            ring.clear();
            ring.extend(ct.ring(v));
            let k = ring.len() as u32;
            let chi = 1.0 / (f64::from(k) + 3.0 / (8.0 * beta.beta(k)));
            let sum: DVec3 = ring.iter().map(|&q| pos[q as usize].as_dvec3()).sum();
            (x * (1.0 - f64::from(k) * chi) + sum * chi).as_vec3()
        })
        .collect()
}

/// The two limit tangents of the Loop surface at vertex `v` (interior:
/// `(t1, t2)`; boundary: `(t_along, t_across)`), unnormalised; their cross
/// product points along the limit normal. See the module docs for the masks.
pub fn loop_limit_tangents(ct: &CornerTable, pos: &[Vec3], v: u32) -> (Vec3, Vec3) {
    let ring: Vec<DVec3> = ct.ring(v).map(|q| pos[q as usize].as_dvec3()).collect();
    let x = pos[v as usize].as_dvec3();
    let (t1, t2) = if ct.is_boundary_vertex(v) {
        let m = ring.len() - 1;
        let along = ring[0] - ring[m];
        let across = match m {
            1 => ring[0] + ring[1] - 2.0 * x,
            2 => ring[1] - x,
            3 => -2.0 * x - ring[0] + 2.0 * ring[1] + 2.0 * ring[2] - ring[3],
            _ => {
                let th = PI / m as f64;
                let ends = (ring[0] + ring[m]) * -th.sin();
                let w = 2.0 * (1.0 - th.cos());
                ring[1..m].iter().enumerate().fold(ends, |s, (i, &e)| s + e * (w * ((i + 1) as f64 * th).sin()))
            }
        };
        (along, across)
    } else {
        let k = ring.len() as f64;
        ring.iter().enumerate().fold((DVec3::ZERO, DVec3::ZERO), |(a, b), (i, &e)| {
            let th = 2.0 * PI * i as f64 / k;
            (a + e * th.cos(), b + e * th.sin())
        })
    };
    (t1.as_vec3(), t2.as_vec3())
}

/// Exact Loop limit normals: unit, one per vertex, oriented like the face
/// normals (counter-clockwise faces seen from outside). Computed from the
/// tangent masks of the module docs; a vertex whose tangents are parallel or
/// zero gets the area-weighted face normal instead.
pub fn loop_limit_normals(mesh: &Mesh) -> Vec<Vec3> {
    tangent_normals(mesh, loop_limit_tangents)
}

/// Normals from a per-vertex tangent pair, with the area-weighted fallback.
fn tangent_normals(mesh: &Mesh, tangents: impl Fn(&CornerTable, &[Vec3], u32) -> (Vec3, Vec3)) -> Vec<Vec3> {
    let ct = &mesh.ct;
    let mut fallback: Option<Vec<Vec3>> = None;
    (0..ct.num_vertices() as u32)
        .map(|v| {
            let (a, b) = tangents(ct, &mesh.positions, v);
            // relative test: a cross product tiny against |a| |b| means parallel tangents
            let c = a.cross(b);
            if c.length() > 1e-6 * a.length() * b.length() && c.is_finite() {
                c.normalize()
            } else {
                fallback.get_or_insert_with(|| vertex_normals(ct, &mesh.positions))[v as usize]
            }
        })
        .collect()
}

/// Tangent-mask normals for the interpolating butterfly schemes (schemes.md 4;
/// the masks there were derived as left eigenvectors of the butterfly
/// subdivision matrix, eigenvalue 1/2, and are our own result):
/// ```text
/// interior vertex, valence k (4.2; for k = 6 this is the 1-ring part of the
/// regular 19-point mask 4.1, "a good approximation", exact in the limit of
/// refinement for a smooth surface), centre weight 0:
///     t1 = sum cos(2 pi j / k) e_j,   t2 = sum sin(2 pi j / k) e_j
/// boundary vertex (4.3): along the boundary, the 4-point curve's exact mask
///     t_along = (1/12) (p_{-2} - 8 p_{-1} + 8 p_{+1} - p_{+2})
/// with p_{+1} = e_0, p_{-1} = e_m the boundary neighbours and p_{+2}, p_{-2}
/// the next boundary vertices; across: no verified mask, so the vector from
/// v to the centroid of the interior neighbours (or, with none, of e_0 and
/// e_m), with its component along t_along removed (4.3's second option).
/// ```
/// The vertex positions of an interpolating scheme are already on the limit
/// surface (limit mask = identity), so only normals need masks. Unit normals,
/// oriented like the face normals; degenerate tangents fall back to the
/// area-weighted face normal.
pub fn butterfly_normals(mesh: &Mesh) -> Vec<Vec3> {
    tangent_normals(mesh, butterfly_tangents)
}

/// The tangent pair of [`butterfly_normals`] at vertex `v`.
fn butterfly_tangents(ct: &CornerTable, pos: &[Vec3], v: u32) -> (Vec3, Vec3) {
    let ids: Vec<u32> = ct.ring(v).collect();
    let ring: Vec<DVec3> = ids.iter().map(|&q| pos[q as usize].as_dvec3()).collect();
    let x = pos[v as usize].as_dvec3();
    if !ct.is_boundary_vertex(v) {
        let k = ring.len() as f64;
        let (a, b) = ring.iter().enumerate().fold((DVec3::ZERO, DVec3::ZERO), |(a, b), (i, &e)| {
            let th = 2.0 * PI * i as f64 / k;
            (a + e * th.cos(), b + e * th.sin())
        });
        return (a.as_vec3(), b.as_vec3());
    }
    let m = ring.len() - 1;
    let (e0, em) = (ids[0], ids[m]);
    // next boundary vertices: e_0's boundary neighbour other than v, same for e_m
    let other = |q: u32| {
        let (a, b) = ct.boundary_neighbours(q);
        if a == v { b } else { a }
    };
    let p2 = pos[other(e0) as usize].as_dvec3();
    let m2 = pos[other(em) as usize].as_dvec3();
    let along = (m2 - 8.0 * ring[m] + 8.0 * ring[0] - p2) / 12.0;
    let centroid = if m >= 2 {
        ring[1..m].iter().copied().sum::<DVec3>() / (m - 1) as f64
    } else {
        // one face: its third vertex is a boundary neighbour; use the triangle's centroid
        (ring[0] + ring[1] + x) / 3.0
    };
    let d = centroid - x;
    let l2 = along.length_squared();
    let across = if l2 > 0.0 { d - along * (d.dot(along) / l2) } else { d };
    (along.as_vec3(), across.as_vec3())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regular_position_mask_is_half_and_twelfths() {
        // chi(6) with beta = 1/16: 1 / (6 + 6) = 1/12; centre 1 - 6/12 = 1/2
        let beta = LoopBeta::Loop.beta(6);
        let chi = 1.0 / (6.0 + 3.0 / (8.0 * beta));
        assert!((chi - 1.0 / 12.0).abs() < 1e-12);
        // n = 3: chi = 1/5
        let chi3 = 1.0 / (3.0 + 3.0 / (8.0 * LoopBeta::Loop.beta(3)));
        assert!((chi3 - 0.2).abs() < 1e-12);
        // Warren: chi = 1/(2n)
        for k in 4..12u32 {
            let c = 1.0 / (f64::from(k) + 3.0 / (8.0 * LoopBeta::Warren.beta(k)));
            assert!((c - 1.0 / (2.0 * f64::from(k))).abs() < 1e-12);
        }
    }

    #[test]
    fn boundary_across_masks_sum_to_zero() {
        for m in 4..40usize {
            let th = PI / m as f64;
            let w = 2.0 * (1.0 - th.cos());
            let s: f64 = -2.0 * th.sin() + (1..m).map(|i| w * (i as f64 * th).sin()).sum::<f64>();
            assert!(s.abs() < 1e-12, "m = {m}: {s}");
        }
    }
}
