//! Cutting a corner table open along chosen edges: the table a scheme sees
//! when sharp edges act as boundaries for every stencil that reaches them
//! (docs/sharp-features.md §6.2). The cut edges become border edges on both sides, and a
//! vertex whose fan the cut separates into sectors gets one vertex per
//! sector, so every existing boundary rule applies unchanged.
//!
//! Corner ids do not change; vertex ids do not change except for the extra
//! sectors, which get ids from `num_vertices()` up. Only the vertices on cut
//! edges are visited, so the cost is a copy of the tables plus the work at
//! the cut.

use super::{BORDER, CornerTable, n, p};

/// A table cut open (see the module docs).
#[derive(Clone, Debug)]
pub(crate) struct Cut {
    /// The cut table.
    pub table: CornerTable,
    /// For vertex `num_vertices() + i` of the cut table (of the uncut one),
    /// the vertex it is a copy of.
    pub copies: Vec<u32>,
}

impl Cut {}

impl CornerTable {
    /// This table cut open along the edges opposite `corners` (an interior
    /// edge may be listed at one or both of its corners; border corners are
    /// ignored). The result is a valid table: O stays an involution, every
    /// sector is one fan with its first corner in `C`.
    pub(crate) fn cut_at(&self, corners: &[u32]) -> Cut {
        // the sharpness stays: its corners are the same, now on the border
        let mut table = self.clone();
        let copies = table.cut_in_place(corners);
        Cut { table, copies }
    }

    /// [`CornerTable::cut_at`] in place: returns the copies (cut vertex
    /// `num_vertices() + i`, numbered before the cut, is a copy of
    /// `copies[i]`). Costs the work at the cut only.
    pub(crate) fn cut_in_place(&mut self, corners: &[u32]) -> Vec<u32> {
        // the touched vertices' corners, read from the uncut fans
        let mut touched = Vec::with_capacity(2 * corners.len());
        for &c in corners {
            if self.o(c).is_some() {
                touched.push(self.vtx(n(c)));
                touched.push(self.vtx(p(c)));
            }
        }
        touched.sort_unstable();
        touched.dedup();
        let mut fan_start = Vec::with_capacity(touched.len() + 1);
        let mut fans = Vec::new();
        for &x in &touched {
            fan_start.push(fans.len());
            fans.extend(self.fan(x));
        }
        fan_start.push(fans.len());
        for &c in corners {
            if let Some(x) = self.o(c) {
                self.o[c as usize] = BORDER;
                self.o[x as usize] = BORDER;
            }
        }
        let nv = self.num_vertices() as u32;
        let mut copies = Vec::new();
        let mut seen = Vec::new();
        for (k, &x) in touched.iter().enumerate() {
            let fan = &fans[fan_start[k]..fan_start[k + 1]];
            seen.clear();
            seen.resize(fan.len(), false);
            let mut first_sector = true;
            for i in 0..fan.len() {
                if seen[i] {
                    continue;
                }
                // every touched vertex has a cut edge, so its fan is open in
                // the cut O and unswinging stops within the fan
                let mut start = fan[i];
                while self.o[p(start) as usize] != BORDER {
                    start = p(self.o[p(start) as usize]);
                }
                // the first sector keeps the vertex id, the others are copies
                let id = if first_sector {
                    x
                } else {
                    copies.push(x);
                    nv + copies.len() as u32 - 1
                };
                first_sector = false;
                let mut count = 0u32;
                let mut c = start;
                loop {
                    if let Some(j) = fan.iter().position(|&f| f == c) {
                        seen[j] = true;
                    }
                    self.v[c as usize] = id;
                    count += 1;
                    let next = self.o[n(c) as usize];
                    if next == BORDER {
                        break;
                    }
                    c = n(next);
                }
                if id == x {
                    self.vc[x as usize] = start;
                    self.valence[x as usize] = count + 1;
                } else {
                    self.vc.push(start);
                    self.valence.push(count + 1);
                }
            }
        }
        copies
    }
}

impl CornerTable {
    /// The table cut open along its sharp edges (every interior edge with
    /// sharpness > 0), for shading that shows a crease as a crease: one
    /// normal per side. `None` when it has none.
    pub(crate) fn cut_at_sharp_edges(&self) -> Option<Cut> {
        let s = self.sharpness()?;
        let corners: Vec<u32> = s.sharp_corners().iter().map(|&(c, _)| c).collect();
        (!corners.is_empty()).then(|| self.cut_at(&corners))
    }
}

impl Cut {
    /// `positions` of the uncut table extended with the copies' positions.
    pub(crate) fn positions(&self, positions: &[glam::Vec3]) -> Vec<glam::Vec3> {
        let mut out = Vec::with_capacity(positions.len() + self.copies.len());
        out.extend_from_slice(positions);
        out.extend(self.copies.iter().map(|&v| positions[v as usize]));
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::topology::check_invariants;

    #[test]
    fn cutting_a_tetrahedron_along_a_closed_loop_gives_two_pieces() {
        // cut the three edges of one face's boundary loop: that face
        // becomes an island, the other three faces a cap with a border
        let (ct, _, _) = CornerTable::build(4, &[0, 2, 1, 0, 3, 2, 0, 1, 3, 1, 2, 3], None).unwrap();
        let loop_corners: Vec<u32> = (0..3).collect(); // face 0's corners face its three edges
        let cut = ct.cut_at(&loop_corners);
        assert_eq!(cut.table.num_border_edges(), 6);
        assert_eq!(cut.copies.len(), 3, "vertices 0, 2, 1 each split in two");
        check_invariants(&cut.table).unwrap();
        for (i, &x) in cut.copies.iter().enumerate() {
            assert!(x < 3, "copy {i} of {x}");
        }
    }

    #[test]
    fn a_single_cut_edge_makes_a_slit() {
        let ico = crate::mesh::shapes::icosahedron();
        let c = 0u32;
        let cut = ico.ct.cut_at(&[c]);
        assert!(cut.copies.is_empty(), "one cut edge does not separate a fan");
        assert_eq!(cut.table.num_border_edges(), 2);
        check_invariants(&cut.table).unwrap();
        let (a, b) = (ico.ct.vtx(n(c)), ico.ct.vtx(p(c)));
        assert!(cut.table.is_boundary_vertex(a) && cut.table.is_boundary_vertex(b));
        assert_eq!(cut.table.valence(a), 6, "a slit vertex has one more edge end");
    }
}
