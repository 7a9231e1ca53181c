//! The corner table (Rossignac, Safonova, Szymczak, "Edgebreaker on a Corner
//! Table", SMI 2001): triangle `t` owns corners `3t, 3t+1, 3t+2`; `V[c]` is the
//! vertex of corner `c` and `O[c]` the corner facing `c` across the edge
//! opposite `c`, or [`BORDER`] when that edge is on the boundary.
//!
//! Operators (`n`, `p`, `o`, `l`, `r`, `s`, `u`) are tiny inline functions on
//! corner ids. Never treat `O[c] == c` as a border (schemes.md 7.2): the
//! sentinel is `u32::MAX`, and [`CornerTable::o`] returns `Option`.
//!
//! Besides V and O the table keeps, per vertex, one corner `C[v]` (for a
//! boundary vertex the first corner of its fan, so that swinging forward visits
//! the whole fan) and the valence (number of incident edges). All four arrays
//! are propagated through a 1-to-4 split in linear time ([`crate::subdiv::split`]).

mod build;
pub mod edit;
pub mod inspect;
pub mod normals;
pub mod repair;
pub mod shapes;
pub mod smooth;
pub mod topology;

pub use build::BuildReport;
use glam::Vec3;
pub use repair::{RepairReport, repair};

/// Axis-aligned bounds `(min, max)` of points; zero when there are none.
pub fn bounds_of<'a>(points: impl IntoIterator<Item = &'a Vec3>) -> (Vec3, Vec3) {
    let (lo, hi) =
        points.into_iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(lo, hi), &q| (lo.min(q), hi.max(q)));
    if lo.cmple(hi).all() { (lo, hi) } else { (Vec3::ZERO, Vec3::ZERO) }
}

/// Sentinel in the O table: the edge opposite this corner is a border edge.
pub const BORDER: u32 = u32::MAX;

/// Next corner in the same triangle.
#[inline(always)]
pub fn n(c: u32) -> u32 {
    if c % 3 == 2 { c - 2 } else { c + 1 }
}
/// Previous corner in the same triangle (`n(n(c))`).
#[inline(always)]
pub fn p(c: u32) -> u32 {
    if c.is_multiple_of(3) { c + 2 } else { c - 1 }
}
/// Triangle of a corner.
#[inline(always)]
pub fn t(c: u32) -> u32 {
    c / 3
}
/// Whether corner `c`, whose opposite is `o`, names its edge once for the
/// mesh: a border corner always does, an interior edge by its smaller corner.
/// (`BORDER` is `u32::MAX`, so this is `c < o`.)
#[inline(always)]
pub fn owns_edge(c: u32, o: u32) -> bool {
    c < o
}

/// Connectivity of a triangle mesh: V, O, one corner per vertex and valences.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct CornerTable {
    /// `V[c]`: vertex of corner `c` (3 per triangle, counter-clockwise).
    pub v: Vec<u32>,
    /// `O[c]`: opposite corner, or [`BORDER`].
    pub o: Vec<u32>,
    /// `C[v]`: one corner of vertex `v`; for boundary vertices the corner `c`
    /// with `u(c)` undefined (the first of the fan in swing order).
    pub vc: Vec<u32>,
    /// Number of edges incident to each vertex.
    pub valence: Vec<u32>,
}

impl CornerTable {
    /// Number of corners (3 per triangle).
    #[inline]
    pub fn num_corners(&self) -> usize {
        self.v.len()
    }
    /// Number of triangles.
    #[inline]
    pub fn num_triangles(&self) -> usize {
        self.v.len() / 3
    }
    /// Number of vertices.
    #[inline]
    pub fn num_vertices(&self) -> usize {
        self.vc.len()
    }
    /// Vertex of corner `c`.
    #[inline(always)]
    pub fn vtx(&self, c: u32) -> u32 {
        self.v[c as usize]
    }
    /// Opposite corner, `None` across a border edge.
    #[inline(always)]
    pub fn o(&self, c: u32) -> Option<u32> {
        let x = self.o[c as usize];
        (x != BORDER).then_some(x)
    }
    /// Is the edge opposite `c` a border edge?
    #[inline(always)]
    pub fn is_border(&self, c: u32) -> bool {
        self.o[c as usize] == BORDER
    }
    /// Left neighbour `o(n(c))`: across the edge `(v(c), v(p(c)))`.
    #[inline]
    pub fn l(&self, c: u32) -> Option<u32> {
        self.o(n(c))
    }
    /// Right neighbour `o(p(c))`: across the edge `(v(c), v(n(c)))`.
    #[inline]
    pub fn r(&self, c: u32) -> Option<u32> {
        self.o(p(c))
    }
    /// Swing `n(o(n(c)))`: the corner of the same vertex in the next triangle
    /// counter-clockwise; `None` at the border.
    #[inline(always)]
    pub fn s(&self, c: u32) -> Option<u32> {
        self.o(n(c)).map(n)
    }
    /// Unswing `p(o(p(c)))`, the inverse of [`Self::s`]; `None` at the border.
    #[inline(always)]
    pub fn u(&self, c: u32) -> Option<u32> {
        self.o(p(c)).map(p)
    }
    /// Is vertex `v` on the boundary?
    #[inline]
    pub fn is_boundary_vertex(&self, v: u32) -> bool {
        self.o[p(self.vc[v as usize]) as usize] == BORDER
    }
    /// The corners around vertex `v`, in swing order, starting at `C[v]`.
    pub fn fan(&self, v: u32) -> Fan<'_> {
        let start = self.vc[v as usize];
        Fan { ct: self, start, next: Some(start) }
    }
    /// The neighbours of `v` in swing order (`valence(v)` of them). For a
    /// boundary vertex the first and last are its two boundary neighbours.
    pub fn ring(&self, v: u32) -> Ring<'_> {
        let start = self.vc[v as usize];
        Ring { ct: self, start, next: Some(start), tail: None }
    }
    /// The two boundary neighbours `(q_first, q_last)` of boundary vertex `v`:
    /// `q_first` across the border edge of `C[v]`, `q_last` at the end of the fan.
    pub fn boundary_neighbours(&self, v: u32) -> (u32, u32) {
        let first = self.vc[v as usize];
        let mut c = first;
        while let Some(x) = self.s(c) {
            c = x;
        }
        (self.vtx(n(first)), self.vtx(p(c)))
    }
    /// Number of border edges (corners whose opposite is the border).
    pub fn num_border_edges(&self) -> usize {
        self.o.iter().filter(|&&x| x == BORDER).count()
    }
    /// Number of edges: each interior edge has two corners, each border edge one.
    /// The corner owning each edge (see [`owns_edge`]), in corner order: the
    /// edge is the one opposite it, from `v(n(c))` to `v(p(c))`.
    pub fn edge_owners(&self) -> impl Iterator<Item = u32> + '_ {
        self.o.iter().enumerate().map(|(c, &o)| (c as u32, o)).filter(|&(c, o)| owns_edge(c, o)).map(|(c, _)| c)
    }
    pub fn num_edges(&self) -> usize {
        (self.num_corners() + self.num_border_edges()) / 2
    }
}

/// Iterator over the corners of one vertex (see [`CornerTable::fan`]).
pub struct Fan<'a> {
    ct: &'a CornerTable,
    start: u32,
    next: Option<u32>,
}

impl Iterator for Fan<'_> {
    type Item = u32;
    #[inline]
    fn next(&mut self) -> Option<u32> {
        let c = self.next?;
        self.next = self.ct.s(c).filter(|&x| x != self.start);
        Some(c)
    }
}

/// Iterator over the neighbours of one vertex (see [`CornerTable::ring`]).
pub struct Ring<'a> {
    ct: &'a CornerTable,
    start: u32,
    next: Option<u32>,
    tail: Option<u32>,
}

impl Iterator for Ring<'_> {
    type Item = u32;
    #[inline]
    fn next(&mut self) -> Option<u32> {
        match self.next {
            Some(c) => {
                self.next = self.ct.s(c).filter(|&x| x != self.start);
                if self.ct.s(c).is_none() {
                    // end of a boundary fan: one more neighbour across the last edge
                    self.tail = Some(self.ct.vtx(p(c)));
                }
                Some(self.ct.vtx(n(c)))
            }
            None => self.tail.take(),
        }
    }
}

/// A triangle mesh: connectivity plus one position per vertex.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Connectivity.
    pub ct: CornerTable,
    /// One position per vertex.
    pub positions: Vec<Vec3>,
}

impl Mesh {
    /// Builds a mesh from positions and a flat triangle index list, validating
    /// it (see [`CornerTable::build`]). Unreferenced vertices are dropped.
    ///
    /// # Errors
    /// Any [`crate::MeshError`] found by validation.
    pub fn from_triangles(positions: Vec<Vec3>, triangles: &[u32]) -> Result<Mesh, crate::MeshError> {
        Self::from_triangles_report(positions, triangles).map(|(m, _)| m)
    }

    /// Like [`Mesh::from_triangles`], also returning what the build found.
    ///
    /// # Errors
    /// Any [`crate::MeshError`] found by validation.
    pub fn from_triangles_report(
        positions: Vec<Vec3>,
        triangles: &[u32],
    ) -> Result<(Mesh, BuildReport), crate::MeshError> {
        let (ct, report, kept) = CornerTable::build(positions.len(), triangles, Some(&positions))?;
        let positions = match &kept {
            Some(kept) => kept.iter().map(|&i| positions[i as usize]).collect(),
            None => positions,
        };
        Ok((Mesh { ct, positions }, report))
    }

    /// The triangle index list (the V table), three per triangle.
    pub fn triangles(&self) -> &[u32] {
        &self.ct.v
    }
    /// Axis-aligned bounds `(min, max)`; zero for an empty mesh.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        bounds_of(&self.positions)
    }
    /// Area-weighted vertex normals (see [`normals::vertex_normals`]).
    pub fn vertex_normals(&self) -> Vec<Vec3> {
        normals::vertex_normals(&self.ct, &self.positions)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    #[test]
    fn next_prev_cycle() {
        for c in 0..30u32 {
            assert_eq!(n(n(n(c))), c);
            assert_eq!(p(n(c)), c);
            assert_eq!(p(c), n(n(c)));
            assert_eq!(t(n(c)), t(c));
        }
    }
}
