//! The limit at a vertex on a sharp feature, for a point of a face at that
//! vertex: the last step of local subdivision (`local.rs`, `catmark.rs`)
//! once no semi-sharp feature is left near it, so the rules around the
//! vertex no longer change from level to level and the limit masks, left
//! eigenvectors of those rules, give the exact values.
//!
//! ```text
//! sector   the faces around v from F's corner back to the first sharp
//!          edge (or border) and on to the next: edges e_0 .. e_m in fan
//!          order (counter-clockwise about the faces' normal), m faces,
//!          the quads' far vertices f_0 .. f_{m-1}
//! crease   two sharp edges at v (a border vertex on no other sharp edge,
//!          or an interior crease; each side refines on its own):
//!            Loop  position 2/3 v + 1/6 (e_0 + e_m); normal t_along x
//!                  t_across with t_along = e_0 - e_m and t_across the
//!                  boundary mask of m faces (`rules::limit`); m > 6 has no
//!                  tangent plane (the rules are not C1 there): none
//!            Catmull-Clark  OpenSubdiv's crease masks over the m faces
//!                  (`eval::catmark_limit`)
//! corner   a sharp vertex, or three or more sharp edges: v stays; the
//!          sector's two sharp edges are crease curves ending at v, whose
//!          tangents there are e_0 - v and e_m - v, so the normal is their
//!          cross product, turned to the side of the sector's faces (a
//!          sector wider than a half turn reverses it); none where they are
//!          parallel
//! ```
//!
//! Darts and smooth vertices are not handled here (smooth ones by the power
//! tables or the patches, darts by subdividing to the cap).

use crate::mesh::poly::PolyTable;
use crate::mesh::sharpness::INFINITE;
use crate::mesh::{CornerTable, n, p};
use crate::subdiv::eval::catmark_limit::crease_frame;
use crate::subdiv::rules::limit::{MAX_BOUNDARY_FACES, boundary_across_weights};
use glam::DVec3;

/// The walk around a vertex that the sector needs, for either table.
pub(super) trait FanTable {
    /// The vertex of corner `x`.
    fn at(&self, x: u32) -> u32;
    /// The other end of the edge leaving `x` (counter-clockwise first).
    fn lead_end(&self, x: u32) -> u32;
    /// The other end of the edge entering `x`.
    fn trail_end(&self, x: u32) -> u32;
    /// A quad's vertex across from `x` (triangles: none).
    fn across(&self, x: u32) -> Option<u32>;
    /// Sharpness of the edge leaving `x` (infinite on the border).
    fn lead_sharpness(&self, x: u32) -> f32;
    /// Sharpness of the edge entering `x`.
    fn trail_sharpness(&self, x: u32) -> f32;
    /// The next corner of the vertex, across the entering edge.
    fn swing(&self, x: u32) -> Option<u32>;
    /// The previous corner of the vertex, across the leaving edge.
    fn unswing(&self, x: u32) -> Option<u32>;
    /// The vertex's own sharpness.
    fn vertex_sharpness(&self, v: u32) -> f32;
}

impl FanTable for CornerTable {
    fn at(&self, x: u32) -> u32 {
        self.vtx(x)
    }
    fn lead_end(&self, x: u32) -> u32 {
        self.vtx(n(x))
    }
    fn trail_end(&self, x: u32) -> u32 {
        self.vtx(p(x))
    }
    fn across(&self, _: u32) -> Option<u32> {
        None
    }
    fn lead_sharpness(&self, x: u32) -> f32 {
        self.edge_sharpness(p(x))
    }
    fn trail_sharpness(&self, x: u32) -> f32 {
        self.edge_sharpness(n(x))
    }
    fn swing(&self, x: u32) -> Option<u32> {
        self.s(x)
    }
    fn unswing(&self, x: u32) -> Option<u32> {
        self.u(x)
    }
    fn vertex_sharpness(&self, v: u32) -> f32 {
        self.sharpness().map_or(0.0, |s| s.vertex(v))
    }
}

impl FanTable for PolyTable {
    fn at(&self, x: u32) -> u32 {
        self.vtx(x)
    }
    fn lead_end(&self, x: u32) -> u32 {
        self.vtx(self.next(x))
    }
    fn trail_end(&self, x: u32) -> u32 {
        self.vtx(self.prev(x))
    }
    fn across(&self, x: u32) -> Option<u32> {
        Some(self.vtx(self.next(self.next(x))))
    }
    fn lead_sharpness(&self, x: u32) -> f32 {
        crate::mesh::edges::EdgeTable::edge_sharpness(self, x)
    }
    fn trail_sharpness(&self, x: u32) -> f32 {
        crate::mesh::edges::EdgeTable::edge_sharpness(self, self.prev(x))
    }
    fn swing(&self, x: u32) -> Option<u32> {
        PolyTable::swing(self, x)
    }
    fn unswing(&self, x: u32) -> Option<u32> {
        self.twin(x).map(|t| self.next(t))
    }
    fn vertex_sharpness(&self, v: u32) -> f32 {
        self.sharpness().map_or(0.0, |s| s.vertex(v))
    }
}

/// What a vertex is for [`vertex_limit`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Feature {
    Crease,
    Corner,
}

/// The sector of corner `c`'s face at its vertex (module docs): the
/// vertex, the edge ends `e`, the quads' far vertices `f` and what the
/// vertex is. `None` for a dart or a smooth vertex.
fn sector<T: FanTable>(t: &T, c: u32) -> Option<(u32, Vec<u32>, Vec<u32>, Feature)> {
    let v = t.at(c);
    // back to the sharp edge before c (or the border)
    let mut first = c;
    let mut closed = false;
    while t.lead_sharpness(first) <= 0.0 {
        match t.unswing(first) {
            Some(x) if x == c => {
                closed = true;
                break;
            }
            Some(x) => first = x,
            None => break,
        }
    }
    if closed {
        return None;
    }
    let (mut e, mut f) = (vec![t.lead_end(first)], Vec::new());
    let mut x = first;
    loop {
        f.extend(t.across(x));
        e.push(t.trail_end(x));
        if t.trail_sharpness(x) > 0.0 {
            break;
        }
        match t.swing(x) {
            Some(y) if y != first => x = y,
            _ => return None,
        }
    }
    let feature = if t.vertex_sharpness(v) > 0.0 || sharp_edges(t, c) > 2 { Feature::Corner } else { Feature::Crease };
    Some((v, e, f, feature))
}

/// The sharp edges at corner `c`'s vertex, the border's included.
fn sharp_edges<T: FanTable>(t: &T, c: u32) -> usize {
    let mut first = c;
    while let Some(x) = t.unswing(first).filter(|&x| x != c) {
        first = x;
    }
    let (mut count, mut x) = (0, first);
    loop {
        count += usize::from(t.lead_sharpness(x) > 0.0);
        match t.swing(x) {
            Some(y) if y != first => x = y,
            Some(_) => return count,
            None => return count + usize::from(t.trail_sharpness(x) > 0.0),
        }
    }
}

/// Whether every sharp feature of a table is infinitely sharp (or gone):
/// its rules are those of every level after it.
pub(super) fn stationary(s: Option<&crate::mesh::sharpness::Sharpness>) -> bool {
    let semi = |&(_, x): &(u32, f32)| x > 0.0 && x < INFINITE;
    s.is_none_or(|s| !s.sharp_corners().iter().any(semi) && !s.sharp_vertices().iter().any(semi))
}

/// The limit position and unit normal at corner `c`'s vertex for the
/// points of `c`'s face, on a stationary level (module docs); `None` for a
/// dart, a smooth vertex, a crease with no tangent plane or a corner whose
/// sector's edges are parallel.
pub(super) fn vertex_limit<T: FanTable>(t: &T, pos: impl Fn(u32) -> DVec3, c: u32) -> Option<(DVec3, DVec3)> {
    let (v, e, f, feature) = sector(t, c)?;
    let x = pos(v);
    let e: Vec<DVec3> = e.iter().map(|&i| pos(i)).collect();
    let f: Vec<DVec3> = f.iter().map(|&i| pos(i)).collect();
    let m = e.len() - 1;
    let (position, normal) = match feature {
        Feature::Crease if f.is_empty() => {
            if m > MAX_BOUNDARY_FACES {
                return None;
            }
            let across = if m == 1 {
                e[0] + e[1] - 2.0 * x
            } else {
                let w = boundary_across_weights(m);
                e.iter().zip(&w[1..]).fold(x * w[0], |s, (&q, &wi)| s + q * wi)
            };
            (x * (2.0 / 3.0) + (e[0] + e[m]) * (1.0 / 6.0), (e[0] - e[m]).cross(across))
        }
        Feature::Crease => {
            let (position, tan1, tan2) = crease_frame(x, &e, &f, 0, m);
            (position, tan1.cross(tan2))
        }
        Feature::Corner => {
            let normal = (e[0] - x).cross(e[m] - x);
            let side: DVec3 = (0..m)
                .map(|i| match f.get(i) {
                    Some(&q) => (q - x).cross(e[i + 1] - e[i]),
                    None => (e[i] - x).cross(e[i + 1] - x),
                })
                .sum();
            let scale = (e[0] - x).length() * (e[m] - x).length();
            if normal.length() <= 1e-9 * scale {
                return None;
            }
            (x, if normal.dot(side) < 0.0 { -normal } else { normal })
        }
    };
    let normal = normal.try_normalize()?;
    Some((position, normal))
}

/// The corner of a face nearest a point whose distance to it is within
/// `tol` (each corner's distance given), if any.
pub(super) fn at_corner(distances: &[f64], tol: f64) -> Option<usize> {
    let (i, d) = distances.iter().copied().enumerate().min_by(|a, b| a.1.total_cmp(&b.1))?;
    (d <= tol).then_some(i)
}

/// `normal` if it is a unit vector, else the first of `fallbacks` that
/// normalises, else `+z`: every sample the evaluators give is finite.
pub(super) fn finite_normal(normal: DVec3, fallbacks: impl IntoIterator<Item = DVec3>) -> DVec3 {
    if normal.is_finite() && (normal.length() - 1.0).abs() < 1e-6 {
        return normal;
    }
    fallbacks.into_iter().find_map(DVec3::try_normalize).unwrap_or(DVec3::Z)
}
