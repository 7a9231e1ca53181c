//! What sharp features need of a table's edges, for the triangle corner
//! table and the polygon table alike: which corner names each edge (a
//! triangle's corner names the edge opposite it, a polygon's corner the edge
//! leaving it), its twin across the edge, the edge's two ends, and the
//! edges around a vertex. [`super::sharpness`] (tags, decay) and the
//! classification of sharp features (`subdiv::rules::features`) are written
//! once against this.

use super::sharpness::{INFINITE, Sharpness};
use super::{BORDER, CornerTable, n, p};

/// A table's edges, named by corners.
pub trait EdgeTable: Sync {
    /// Vertices.
    fn num_vertices(&self) -> usize;
    /// The corner across the edge `c` names, or [`BORDER`].
    fn twin_entry(&self, c: u32) -> u32;
    /// The two ends of the edge `c` names.
    fn edge_ends(&self, c: u32) -> (u32, u32);
    /// Edges at vertex `v`.
    fn valence(&self, v: u32) -> u32;
    /// Whether `v` has a border edge.
    fn is_boundary_vertex(&self, v: u32) -> bool;
    /// The table's sharp features.
    fn sharpness(&self) -> Option<&Sharpness>;
    /// Calls `f(corner, other end)` for every edge at `v` once, border edges
    /// included, in fan order.
    fn each_edge_at(&self, v: u32, f: &mut dyn FnMut(u32, u32));
    /// The corner naming the edge between `a` and `b` (either direction),
    /// when there is one.
    fn edge_between(&self, a: u32, b: u32) -> Option<u32> {
        if a as usize >= self.num_vertices() {
            return None;
        }
        let mut found = None;
        self.each_edge_at(a, &mut |c, other| {
            if other == b && found.is_none() {
                found = Some(c);
            }
        });
        found
    }
    /// Sharpness of the edge `c` names: [`INFINITE`] on the border.
    #[inline]
    fn edge_sharpness(&self, c: u32) -> f32 {
        if self.twin_entry(c) == BORDER { INFINITE } else { self.sharpness().map_or(0.0, |s| s.corner(c)) }
    }
}

impl EdgeTable for CornerTable {
    fn num_vertices(&self) -> usize {
        CornerTable::num_vertices(self)
    }
    #[inline]
    fn twin_entry(&self, c: u32) -> u32 {
        self.o_entry(c)
    }
    #[inline]
    fn edge_ends(&self, c: u32) -> (u32, u32) {
        (self.vtx(n(c)), self.vtx(p(c)))
    }
    fn valence(&self, v: u32) -> u32 {
        CornerTable::valence(self, v)
    }
    fn is_boundary_vertex(&self, v: u32) -> bool {
        CornerTable::is_boundary_vertex(self, v)
    }
    fn sharpness(&self) -> Option<&Sharpness> {
        CornerTable::sharpness(self)
    }
    fn each_edge_at(&self, v: u32, f: &mut dyn FnMut(u32, u32)) {
        let mut last = None;
        for c in self.fan(v) {
            // edge (v, v(n(c))) is opposite p(c)
            f(p(c), self.vtx(n(c)));
            last = Some(c);
        }
        // a boundary fan's last edge, (v(p(last)), v), is opposite n(last)
        if let Some(c) = last
            && self.o_entry(n(c)) == BORDER
        {
            f(n(c), self.vtx(p(c)));
        }
    }
}
