//! How a table's counts grow through its split: the one home of the
//! recurrence that the budget checks, the predicted counts of `info` and
//! the panel, and the inspectors' creation levels all read.
//!
//! - The 1-to-4 triangle split ([`super::split`]): every edge gets a vertex
//!   and every triangle four children, `V' = V + E`, `E' = 2E + 3F`,
//!   `F' = 4F` (`E` counting border edges once; docs/schemes.md §1).
//! - The quad split ([`super::poly::split`]): a vertex on every edge and in
//!   every face, one quad per corner, `V' = V + E + F`, `E' = 2E + H`,
//!   `F' = H`, `H' = 4H` (`H` the corners).
//!
//! Every scheme of a kind uses the same split, so the counts hold for all
//! of them; the arithmetic saturates, so a prediction far past memory is
//! large, never wrapped.

/// A table's vertices, edges, faces and corners.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Counts {
    pub(crate) vertices: u64,
    pub(crate) edges: u64,
    pub(crate) faces: u64,
    pub(crate) corners: u64,
}

impl Counts {
    /// The counts of the triangle table `ct`.
    pub(crate) fn of_triangles(ct: &super::CornerTable) -> Counts {
        let faces = ct.num_triangles() as u64;
        let edges = (3 * faces + ct.num_border_edges() as u64) / 2;
        Counts { vertices: ct.num_vertices() as u64, edges, faces, corners: 3 * faces }
    }

    /// The counts of the polygon table `pt`.
    pub(crate) fn of_polygons(pt: &super::poly::PolyTable) -> Counts {
        Counts {
            vertices: pt.num_vertices() as u64,
            edges: pt.num_edges() as u64,
            faces: pt.num_faces() as u64,
            corners: pt.num_corners() as u64,
        }
    }

    /// After one 1-to-4 triangle split.
    pub(crate) fn triangle_split(self) -> Counts {
        let Counts { vertices: v, edges: e, faces: f, .. } = self;
        let faces = f.saturating_mul(4);
        Counts {
            vertices: v.saturating_add(e),
            edges: e.saturating_mul(2).saturating_add(f.saturating_mul(3)),
            faces,
            corners: faces.saturating_mul(3),
        }
    }

    /// After one quad split.
    pub(crate) fn quad_split(self) -> Counts {
        let Counts { vertices: v, edges: e, faces: f, corners: h } = self;
        Counts {
            vertices: v.saturating_add(e).saturating_add(f),
            edges: e.saturating_mul(2).saturating_add(h),
            faces: h,
            corners: h.saturating_mul(4),
        }
    }

    /// After `levels` splits of the kind `quads` says.
    pub(crate) fn after(self, quads: bool, levels: u32) -> Counts {
        (0..levels).fold(self, |c, _| if quads { c.quad_split() } else { c.triangle_split() })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_counts_are_the_split_tables_own() {
        let m = crate::mesh::shapes::icosphere(0);
        let mut ct = m.ct.clone();
        let mut c = Counts::of_triangles(&ct);
        for _ in 0..3 {
            ct = crate::mesh::split(&ct).0;
            c = c.triangle_split();
            assert_eq!(c, Counts::of_triangles(&ct));
        }
    }
}
