//! A locality order for a table's faces and vertices, and the table
//! relabelled in it.
//!
//! A mesh's faces come in whatever order its file lists them: scan lines for
//! a range-scanned model, so that two neighbouring triangles may lie
//! thousands of entries apart. Every level of a subdivision inherits that
//! order (`split.rs`: a level's corners are its parent triangles' in four
//! blocks, its edge vertices numbered in corner order), so a per-frame
//! evaluation that gathers each point's neighbours gathers them from all
//! over its arrays. Numbering the control mesh once in breadth-first order
//! over its faces, and its vertices by first use in that order, keeps
//! neighbours within one front of the search apart (about the square root of
//! the face count for a surface), at every level. For the bunny animated at
//! level 2 the fastest frame went from 4.4-4.8 to 3.6-3.9 ms, the median
//! from 5.3-8.3 to 3.9-4.9 (docs/performance.md).
//!
//! The relabelled table is the same surface with other ids: it carries the
//! sharp features, and its edge generations restart (the relabelled table is
//! a control table, every edge of generation 0).

use super::{BORDER, CornerTable, Mesh};

/// A renumbering of a table's faces and vertices (see the module docs).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Relabel {
    /// `faces[i]` is the old face that becomes face `i`.
    faces: Vec<u32>,
    /// `vertex[v]` is the new id of old vertex `v`.
    vertex: Vec<u32>,
}

impl Relabel {
    /// Faces in breadth-first order across edges, one connected piece
    /// after the other (each started at its first face in the old order);
    /// vertices numbered by first use in the new face order. O(corners).
    pub(crate) fn breadth_first(ct: &CornerTable) -> Relabel {
        let nt = ct.num_triangles();
        let o = ct.o_table();
        let mut seen = vec![false; nt];
        let mut faces: Vec<u32> = Vec::with_capacity(nt);
        for seed in 0..nt {
            if seen[seed] {
                continue;
            }
            seen[seed] = true;
            let mut head = faces.len();
            faces.push(seed as u32);
            while head < faces.len() {
                let t = faces[head] as usize;
                head += 1;
                for &x in &o[3 * t..3 * t + 3] {
                    // O entries are BORDER or corners of the table (its invariants)
                    if x != BORDER && !seen[x as usize / 3] {
                        seen[x as usize / 3] = true;
                        faces.push(x / 3);
                    }
                }
            }
        }
        let nv = ct.num_vertices();
        let mut vertex = vec![BORDER; nv];
        let mut next = 0u32;
        for &t in &faces {
            for &v in &ct.v_table()[3 * t as usize..3 * t as usize + 3] {
                if vertex[v as usize] == BORDER {
                    vertex[v as usize] = next;
                    next += 1;
                }
            }
        }
        // every vertex of a table has a corner; kept total all the same
        for id in vertex.iter_mut().filter(|id| **id == BORDER) {
            *id = next;
            next += 1;
        }
        Relabel { faces, vertex }
    }

    #[cfg(test)]
    /// The new id of old vertex `v`.
    pub(crate) fn new_vertex(&self, v: u32) -> u32 {
        self.vertex[v as usize]
    }

    #[cfg(test)]
    /// The old face that became face `i`.
    pub(crate) fn old_face(&self, i: u32) -> u32 {
        self.faces[i as usize]
    }

    /// `old[j]` is the old id of new vertex `j` (the inverse of
    /// `Self::new_vertex`).
    pub fn old_vertices(&self) -> Vec<u32> {
        let mut old = vec![0u32; self.vertex.len()];
        for (v, &j) in self.vertex.iter().enumerate() {
            old[j as usize] = v as u32;
        }
        old
    }

    /// `new[t]`: the new id of old face `t`.
    fn new_faces(&self) -> Vec<u32> {
        let mut new = vec![0u32; self.faces.len()];
        for (i, &t) in self.faces.iter().enumerate() {
            new[t as usize] = i as u32;
        }
        new
    }
}

impl CornerTable {
    /// This table with faces and vertices renumbered by `r` (made for this
    /// table): old face `r.old_face(i)` is face `i` with its corners in the
    /// same rotation, old vertex `v` is vertex `r.new_vertex(v)`. Sharp
    /// features and holes are carried; edge generations are not (the result is a
    /// control table).
    ///
    /// # Panics
    /// If `r` was made for a table with other counts.
    pub fn relabelled(&self, r: &Relabel) -> CornerTable {
        assert!(
            r.faces.len() == self.num_triangles() && r.vertex.len() == self.num_vertices(),
            "a relabelling made for this table"
        );
        let new_face = r.new_faces();
        let corner = |c: u32| if c == BORDER { BORDER } else { 3 * new_face[c as usize / 3] + c % 3 };
        let (v, o) = (self.v_table(), self.o_table());
        let mut v2 = Vec::with_capacity(v.len());
        let mut o2 = Vec::with_capacity(o.len());
        for &t in &r.faces {
            let t = 3 * t as usize;
            v2.extend(v[t..t + 3].iter().map(|&x| r.vertex[x as usize]));
            o2.extend(o[t..t + 3].iter().map(|&x| corner(x)));
        }
        let mut vc = vec![0u32; self.num_vertices()];
        let mut valence = vec![0u32; self.num_vertices()];
        for (old, &new) in r.vertex.iter().enumerate() {
            vc[new as usize] = corner(self.c_table()[old]);
            valence[new as usize] = self.valences()[old];
        }
        let sharpness = self.sharpness().map(|s| s.relabelled(corner, |x| r.vertex[x as usize]));
        // A bijection of faces that keeps each face's corner rotation, and
        // of vertices, maps a table with the invariants (CornerTable's docs)
        // to one with them: O still pairs the same edges, reversed; each fan
        // maps to a fan, and C[v] to the same (first) corner of it.
        // edge generations (hidden polygon diagonals among them) go with
        // their corners
        let generations = self.generations().map(|g| {
            let old = g.corners();
            let mut new = vec![0u8; old.len()];
            for (c, &x) in old.iter().enumerate() {
                new[corner(c as u32) as usize] = x;
            }
            super::Generations::explicit(new, g.level())
        });
        let holes = self.holes().iter().map(|&t| new_face[t as usize]).collect();
        CornerTable::from_parts(v2, o2, vc, valence)
            .with_sharpness(sharpness)
            .with_holes(holes)
            .with_generations(generations)
    }
}

impl Mesh {
    /// This mesh relabelled by `r` (see [`CornerTable::relabelled`]): the
    /// same surface, positions moved with their vertices.
    pub fn relabelled(&self, r: &Relabel) -> Mesh {
        let positions = r.old_vertices().iter().map(|&v| self.positions[v as usize]).collect();
        Mesh { ct: self.ct.relabelled(r), positions }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;

    /// The triangles of a mesh as sets of vertex positions' bits, rotated to
    /// start at the smallest, sorted: equal for the same surface whatever
    /// the ids.
    fn triangles_by_position(m: &Mesh) -> Vec<[[u32; 3]; 3]> {
        let mut out: Vec<[[u32; 3]; 3]> =
            m.ct.v_table()
                .chunks_exact(3)
                .map(|t| {
                    let p = |i: usize| m.positions[t[i] as usize].to_array().map(f32::to_bits);
                    let tri = [p(0), p(1), p(2)];
                    let k = (0..3).min_by_key(|&k| tri[k]).unwrap_or(0);
                    [tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]]
                })
                .collect();
        out.sort_unstable();
        out
    }

    #[test]
    fn the_relabelled_table_is_a_valid_table_of_the_same_surface() {
        for m in [shapes::icosphere(2), shapes::grid(6), shapes::icosphere(0)] {
            let r = Relabel::breadth_first(&m.ct);
            let q = m.relabelled(&r);
            // the same triangles, in the same rotation, under the new ids
            assert_eq!(triangles_by_position(&q), triangles_by_position(&m));
            for i in 0..q.ct.num_triangles() as u32 {
                let t = r.old_face(i) as usize;
                let old: Vec<u32> = m.ct.v_table()[3 * t..3 * t + 3].iter().map(|&v| r.new_vertex(v)).collect();
                assert_eq!(&q.ct.v_table()[3 * i as usize..3 * i as usize + 3], &old[..], "face {i}");
            }
            // the validating constructor accepts its V and O and finds its C
            // and valences (C may pick another corner of an interior fan)
            let rebuilt = CornerTable::from_vo(q.ct.v_table().to_vec(), q.ct.o_table().to_vec(), q.ct.num_vertices())
                .expect("a valid table");
            assert_eq!(rebuilt.valences(), q.ct.valences());
            for v in 0..q.ct.num_vertices() as u32 {
                assert_eq!(q.ct.vtx(q.ct.corner_of(v)), v, "C[{v}] is a corner of {v}");
                if q.ct.is_boundary_vertex(v) {
                    assert_eq!(q.ct.corner_of(v), rebuilt.corner_of(v), "a boundary fan starts at its first corner");
                }
            }
        }
    }

    #[test]
    fn breadth_first_keeps_neighbours_close_and_numbers_every_face_and_vertex_once() {
        let m = shapes::icosphere(4);
        // scatter the faces first, as a scanned model's file does
        let scatter = Relabel {
            faces: (0..m.ct.num_triangles() as u32).map(|i| (i * 7919) % m.ct.num_triangles() as u32).collect(),
            vertex: (0..m.ct.num_vertices() as u32).collect(),
        };
        assert!({
            let mut f = scatter.faces.clone();
            f.sort_unstable();
            f.dedup();
            f.len() == m.ct.num_triangles()
        });
        let scattered = m.relabelled(&scatter);
        let r = Relabel::breadth_first(&scattered.ct);
        let mut faces = r.faces.clone();
        faces.sort_unstable();
        assert!(faces.iter().enumerate().all(|(i, &t)| i as u32 == t), "a permutation of the faces");
        let mut verts = r.vertex.clone();
        verts.sort_unstable();
        assert!(verts.iter().enumerate().all(|(i, &v)| i as u32 == v), "a permutation of the vertices");
        // mean id distance between the faces across each edge
        let spread = |ct: &CornerTable| {
            let o = ct.o_table();
            let d: u64 =
                (0..o.len()).filter(|&c| o[c] != BORDER).map(|c| (c / 3).abs_diff(o[c] as usize / 3) as u64).sum();
            d as f64 / o.len() as f64
        };
        let ordered = scattered.relabelled(&r);
        assert!(
            spread(&ordered.ct) * 10.0 < spread(&scattered.ct),
            "neighbours closer: {} against {}",
            spread(&ordered.ct),
            spread(&scattered.ct)
        );
    }

    #[test]
    fn sharp_features_follow_their_edges_and_vertices() {
        use crate::mesh::sharpness::{CornerTag, CreaseTag, Tags};
        let m = shapes::icosphere(1);
        let (a, b) = (m.ct.vtx(1), m.ct.vtx(2));
        let tags = Tags {
            creases: vec![CreaseTag { v0: a, v1: b, sharpness: 2.5 }],
            corners: vec![CornerTag { vertex: 5, sharpness: 1.0 }],
        };
        let m = Mesh { ct: m.ct.with_tags(&tags).expect("valid tags"), positions: m.positions };
        let r = Relabel::breadth_first(&m.ct);
        let q = m.relabelled(&r);
        let c = q.ct.corner_opposite(r.new_vertex(a), r.new_vertex(b)).expect("the edge is still there");
        assert_eq!(q.ct.edge_sharpness(c), 2.5);
        let s = q.ct.sharpness().expect("sharpness carried");
        assert_eq!(s.vertex(r.new_vertex(5)), 1.0);
        assert_eq!(s.sharp_corners().len(), m.ct.sharpness().map_or(0, |s| s.sharp_corners().len()));
    }
}
