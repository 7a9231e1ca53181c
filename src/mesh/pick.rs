//! Ray picking on a triangle mesh: which edge lies under the cursor. Pure
//! geometry (glam only); the viewer turns a click into a ray and asks here.
//!
//! ```text
//! ray r(t) = origin + t dir, t > 0; triangle (a, b, c), e1 = b - a, e2 = c - a
//! Moller-Trumbore: p = dir x e2, det = e1 . p (|det| < 1e-12: parallel, miss)
//!     s = origin - a,   u = (s . p) / det,   q = s x e1,   v = (dir . q) / det
//!     t = (e2 . q) / det;   hit when u >= 0, v >= 0, u + v <= 1, t > 0
//! ```
//! The nearest hit triangle wins (a scan over all triangles, in parallel:
//! a click is rare, a million triangles take milliseconds, and a tree over
//! them would have to be rebuilt with every level and edit); in it, the edge
//! nearest to the hit point is the one picked, named as the corner table
//! names an edge of a face: by the corner opposite it.

use super::{Mesh, n, p};
use glam::Vec3;

#[cfg(test)]
/// The ray parameter `t > 0` where `origin + t * dir` crosses the triangle
/// `tri`, or `None` when it misses (or runs parallel to its plane).
pub(crate) fn ray_triangle(origin: Vec3, dir: Vec3, tri: [Vec3; 3]) -> Option<f32> {
    ray_triangle_uv(origin, dir, tri).map(|(t, _, _)| t)
}

/// [`ray_triangle`] with the barycentric weights `(u, v)` of the hit's
/// corners 1 and 2: the hit is `(1 - u - v) a + u b + v c`.
pub(crate) fn ray_triangle_uv(origin: Vec3, dir: Vec3, tri: [Vec3; 3]) -> Option<(f32, f32, f32)> {
    let [a, b, c] = tri;
    let (e1, e2) = (b - a, c - a);
    let pv = dir.cross(e2);
    let det = e1.dot(pv);
    if det.abs() < 1e-12 {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - a;
    let u = s.dot(pv) * inv;
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    let t = e2.dot(q) * inv;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some((t, u, v))
}

/// Where a ray first meets a mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The triangle hit.
    pub triangle: u32,
    /// The ray parameter of the hit (its distance for a unit direction).
    pub t: f32,
    /// Barycentric weights of the triangle's corners 1 and 2 at the hit.
    pub uv: (f32, f32),
    /// The hit point.
    pub point: Vec3,
}

/// Triangles per parallel work item of [`nearest_hit`].
const HIT_CHUNK: usize = 1 << 14;

/// The first triangle of `mesh` that the ray `origin + t dir` hits (a scan
/// of every triangle, split over the threads: 10 ms for a million triangles
/// on two cores, `tests/pick.rs`).
pub fn nearest_hit(mesh: &Mesh, origin: Vec3, dir: Vec3) -> Option<Hit> {
    use rayon::prelude::*;
    let pos = &mesh.positions;
    let best = mesh
        .ct
        .v_table()
        .par_chunks(3 * HIT_CHUNK)
        .enumerate()
        .filter_map(|(k, chunk)| {
            let mut best: Option<(f32, u32, f32, f32)> = None;
            for (i, tri) in chunk.chunks_exact(3).enumerate() {
                // a hole is no part of the surface
                if mesh.ct.is_hole((k * HIT_CHUNK + i) as u32) {
                    continue;
                }
                let corners = [pos[tri[0] as usize], pos[tri[1] as usize], pos[tri[2] as usize]];
                if let Some((t, u, v)) = ray_triangle_uv(origin, dir, corners)
                    && best.is_none_or(|b| t < b.0)
                {
                    best = Some((t, (k * HIT_CHUNK + i) as u32, u, v));
                }
            }
            best
        })
        .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)))?;
    let (t, triangle, u, v) = best;
    Some(Hit { triangle, t, uv: (u, v), point: origin + dir * t })
}

/// The first triangle of `mesh` that the ray hits and the hit point.
pub fn first_hit(mesh: &Mesh, origin: Vec3, dir: Vec3) -> Option<(u32, Vec3)> {
    nearest_hit(mesh, origin, dir).map(|h| (h.triangle, h.point))
}

/// Distance from `x` to the segment `(a, b)`.
pub(crate) fn distance_to_segment(x: Vec3, a: Vec3, b: Vec3) -> f32 {
    let d = b - a;
    let s = ((x - a).dot(d) / d.length_squared().max(1e-30)).clamp(0.0, 1.0);
    (a + d * s).distance(x)
}

/// The corner of `mesh` whose opposite edge is nearest to where the ray
/// `origin + t * dir` first hits the surface, or `None` when the ray misses.
pub(crate) fn pick_edge(mesh: &Mesh, origin: Vec3, dir: Vec3) -> Option<u32> {
    let (t, hit) = first_hit(mesh, origin, dir)?;
    let v = mesh.ct.v_table();
    let at = |c: u32| mesh.positions[v[c as usize] as usize];
    (0..3u32)
        .map(|k| {
            let c = 3 * t + k;
            (distance_to_segment(hit, at(n(c)), at(p(c))), c)
        })
        .min_by(|x, y| x.0.total_cmp(&y.0))
        .map(|(_, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Mesh {
        // two triangles in z = 0 sharing the diagonal (0,0)-(1,1)
        let pos = vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
        Mesh::from_triangles(pos, &[0, 1, 2, 0, 2, 3]).expect("a valid square")
    }

    #[test]
    fn a_ray_through_a_triangle_hits_it_at_its_distance() {
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let t = ray_triangle(Vec3::new(0.25, 0.25, 2.0), -Vec3::Z, tri).expect("hit");
        assert!((t - 2.0).abs() < 1e-6);
        assert_eq!(ray_triangle(Vec3::new(0.75, 0.75, 2.0), -Vec3::Z, tri), None, "outside the triangle");
        assert_eq!(ray_triangle(Vec3::new(0.25, 0.25, 2.0), Vec3::Z, tri), None, "behind the origin");
        assert_eq!(ray_triangle(Vec3::new(0.25, 0.25, 2.0), Vec3::X, tri), None, "parallel to the plane");
    }

    #[test]
    fn the_nearest_triangle_wins() {
        let m = square();
        let lifted = Mesh { ct: m.ct.clone(), positions: m.positions.iter().map(|q| *q + Vec3::Z).collect() };
        // the same square twice: one at z = 0, one at z = 1; from above, z = 1 is hit first
        let (t, hit) = first_hit(&lifted, Vec3::new(0.8, 0.2, 5.0), -Vec3::Z).expect("hit");
        assert_eq!(t, 0);
        assert!((hit - Vec3::new(0.8, 0.2, 1.0)).length() < 1e-6);
    }

    #[test]
    fn the_edge_nearest_to_the_hit_is_picked() {
        let m = square();
        let v = m.ct.v_table();
        let edge = |c: u32| {
            let (a, b) = (v[n(c) as usize], v[p(c) as usize]);
            (a.min(b), a.max(b))
        };
        // near the diagonal, inside triangle 0
        let c = pick_edge(&m, Vec3::new(0.55, 0.5, 1.0), -Vec3::Z).expect("hit");
        assert_eq!(edge(c), (0, 2));
        // near the bottom edge (0, 1)
        let c = pick_edge(&m, Vec3::new(0.5, 0.05, 1.0), -Vec3::Z).expect("hit");
        assert_eq!(edge(c), (0, 1));
        assert_eq!(pick_edge(&m, Vec3::new(3.0, 3.0, 1.0), -Vec3::Z), None);
        assert!((distance_to_segment(Vec3::new(2.0, 1.0, 0.0), Vec3::ZERO, Vec3::X) - 2f32.sqrt()).abs() < 1e-6);
    }
}
