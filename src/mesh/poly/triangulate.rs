//! A polygon mesh as triangles, for what only draws or writes triangles
//! (the renderer, STL, glTF): every face fanned from its first corner, the
//! triangle table's O written by formula from the twins (no rebuild), the
//! sharpness carried to the corners naming the same edges, and the fan's
//! diagonals marked [`Generations::HIDDEN`] so that a wireframe shows the
//! polygons' own edges only.
//!
//! Face `f` with corners `c0 .. c(m-1)` becomes triangles `T_j = (c0,
//! c(j+1), c(j+2))`, `j = 0 .. m-3`, numbered from `t0 = start(f) - 2f`.
//! The triangle corner naming the polygon edge leaving `c_i` is `3 t0 + 2`
//! for `i = 0` (in `T_0`), `3 (t0 + i - 1)` for `0 < i < m - 1`, and
//! `3 (t0 + m - 3) + 1` for `i = m - 1`; the diagonal between `T_j` and
//! `T_(j+1)` pairs corner `3 (t0 + j) + 1` with `3 (t0 + j + 1) + 2`.

use super::{PolyMesh, PolyTable};
use crate::mesh::attributes::{Attributes, MaterialGroups};
use crate::mesh::sharpness::Sharpness;
use crate::mesh::{BORDER, CornerTable, Generations, Mesh};
#[cfg(test)]
use glam::Vec3;
use rayon::prelude::*;

impl PolyTable {
    /// The first triangle of face `f` in the fan.
    #[inline]
    fn first_triangle(&self, f: u32) -> u32 {
        self.face_corners(f).start - 2 * f
    }

    /// The triangle corner that names the polygon edge leaving corner `c`.
    #[inline]
    pub(crate) fn triangle_corner(&self, c: u32) -> u32 {
        let f = self.face(c);
        let r = self.face_corners(f);
        let (i, m, t0) = (c - r.start, r.end - r.start, self.first_triangle(f));
        if i == 0 {
            3 * t0 + 2
        } else if i == m - 1 {
            3 * (t0 + m - 3) + 1
        } else {
            3 * (t0 + i - 1)
        }
    }

    /// The polygon corner of every corner of [`PolyTable::triangulated`]
    /// (to carry per-corner values onto the triangles).
    pub(crate) fn fan_corners(&self) -> Vec<u32> {
        let mut out = Vec::with_capacity(3 * (self.num_corners() - 2 * self.num_faces()));
        for f in 0..self.num_faces() as u32 {
            let r = self.face_corners(f);
            for j in 0..(r.end - r.start) - 2 {
                out.extend_from_slice(&[r.start, r.start + j + 1, r.start + j + 2]);
            }
        }
        out
    }

    /// The table of the fanned faces (see the module docs), with its
    /// sharpness and edge generations (diagonals hidden).
    pub fn triangulated(&self) -> CornerTable {
        let nt = self.num_corners() - 2 * self.num_faces();
        let mut v = vec![0u32; 3 * nt];
        let mut o = vec![BORDER; 3 * nt];
        let mut g = vec![Generations::HIDDEN; 3 * nt];
        // every face writes its own triangles; faces are independent
        let tri_ranges: Vec<(u32, std::ops::Range<u32>)> =
            (0..self.num_faces() as u32).map(|f| (self.first_triangle(f), self.face_corners(f))).collect();
        let vp = SyncPtr(v.as_mut_ptr());
        let op = SyncPtr(o.as_mut_ptr());
        let gp = SyncPtr(g.as_mut_ptr());
        tri_ranges.par_iter().with_min_len(1024).for_each(|(t0, r)| {
            let m = r.end - r.start;
            for j in 0..m - 2 {
                let t = 3 * (t0 + j) as usize;
                let corners = [r.start, r.start + j + 1, r.start + j + 2];
                // SAFETY: triangle t belongs to this face alone (the fans of
                // the faces are disjoint ranges of triangles), so no other
                // thread writes corners t .. t + 3, and the vectors outlive
                // the parallel loop.
                unsafe {
                    for (k, &c) in corners.iter().enumerate() {
                        *vp.get().add(t + k) = self.vtx(c);
                    }
                    if j + 1 < m - 2 {
                        // the diagonal shared with the next triangle
                        *op.get().add(t + 1) = (t + 5) as u32;
                        *op.get().add(t + 5) = (t + 1) as u32;
                    }
                }
            }
            for c in r.clone() {
                let x = self.triangle_corner(c) as usize;
                let twin = self.twin_entry(c);
                // SAFETY: corner x is in this face's triangles (see above).
                unsafe {
                    *op.get().add(x) = if twin == BORDER { BORDER } else { self.triangle_corner(twin) };
                    *gp.get().add(x) = self.edge_generation(c);
                }
            }
        });
        // a valid polygon table's faces fanned are a valid triangle table:
        // the fans of its vertices are those of the polygons, the diagonals
        // only adding interior corners to them
        let ct = CornerTable::with_fans(v, o, self.num_vertices())
            .expect("the fan of a valid polygon table is a valid triangle table");
        let sharpness = self.sharpness().and_then(|s| {
            let corners = s.sharp_corners().iter().map(|&(c, x)| (self.triangle_corner(c), x)).collect();
            Sharpness::from_lists(corners, s.sharp_vertices().to_vec())
        });
        // a hole's triangles are holes
        let holes = self.holes().iter().flat_map(|&f| {
            let t0 = self.first_triangle(f);
            t0..t0 + self.face_size(f) - 2
        });
        let holes = holes.collect();
        ct.with_sharpness(sharpness)
            .with_holes(holes)
            .with_generations(Some(Generations::explicit(g, self.level().min(30) as u8)))
    }
}

/// A raw pointer shared by threads writing disjoint elements.
#[derive(Clone, Copy)]
struct SyncPtr<T>(*mut T);
// SAFETY: only used for writes to elements that exactly one thread writes
// (see `PolyTable::triangulated`), read after the parallel loop has joined.
unsafe impl<T> Send for SyncPtr<T> {}
unsafe impl<T> Sync for SyncPtr<T> {}

impl<T> SyncPtr<T> {
    #[inline(always)]
    fn get(self) -> *mut T {
        self.0
    }
}

impl PolyMesh {
    /// The mesh as triangles (see the module docs); vertex ids and
    /// positions are the same.
    pub fn triangulated(&self) -> Mesh {
        Mesh { ct: self.pt.triangulated(), positions: self.positions.clone() }
    }
}

impl PolyMesh {
    /// The polygon mesh a triangle mesh stands for: the triangles joined
    /// across the diagonals marked [`Generations::HIDDEN`] (what
    /// [`PolyMesh::triangulated`] and the readers' fanning of polygons
    /// mark) become one face each; every other triangle is a face of its
    /// own. Vertex ids are kept; the sharpness goes with its edges.
    pub fn from_mesh(mesh: &Mesh) -> PolyMesh {
        Self::joined(mesh).0
    }

    /// [`PolyMesh::from_mesh`] with the mesh's attributes moved onto the
    /// polygons: texture coordinates per polygon corner (from the corner of
    /// a triangle at the same vertex in the same face), colours as they are,
    /// a material per face.
    pub fn from_mesh_with_attributes(mesh: &Mesh, attrs: &Attributes) -> (PolyMesh, Attributes) {
        let (pm, of_corner) = Self::joined(mesh);
        // the triangle corner at V[c] in the triangle naming c's edge is n(x)
        let uv = attrs
            .uv
            .as_ref()
            .filter(|u| u.len() == mesh.ct.num_corners())
            .map(|u| of_corner.iter().map(|&x| u[crate::mesh::n(x) as usize]).collect());
        let materials = attrs.materials.as_ref().filter(|m| m.face.len() == mesh.ct.num_triangles()).map(|m| {
            let face = (0..pm.pt.num_faces() as u32)
                .map(|f| m.face[(of_corner[pm.pt.face_corners(f).start as usize] / 3) as usize])
                .collect();
            MaterialGroups { face, ..m.clone() }
        });
        (pm, Attributes { uv, colors: attrs.colors.clone(), materials, options: attrs.options })
    }

    /// The polygons of `mesh` and, for every polygon corner, the triangle
    /// corner naming its edge.
    fn joined(mesh: &Mesh) -> (PolyMesh, Vec<u32>) {
        let (pt, of_corner) = PolyTable::joined(&mesh.ct);
        (PolyMesh { pt, positions: mesh.positions.clone() }, of_corner)
    }

    /// Whether the mesh stands for polygons (it has hidden diagonals).
    pub fn is_polygonal(mesh: &Mesh) -> bool {
        mesh.ct.generations().is_some_and(Generations::may_hide)
            && (0..mesh.ct.num_corners() as u32).any(|c| mesh.ct.edge_generation(c) == Generations::HIDDEN)
    }
}

impl PolyTable {
    /// The polygon table a triangle table stands for (see
    /// [`PolyMesh::from_mesh`]).
    pub fn from_corner_table(ct: &CornerTable) -> PolyTable {
        Self::joined(ct).0
    }

    /// The polygons of `ct` and, for every polygon corner, the triangle
    /// corner naming its edge.
    fn joined(ct: &CornerTable) -> (PolyTable, Vec<u32>) {
        let (starts, corners, of_corner) = recover_faces(ct);
        // a polygon whose triangles are holes is a hole
        let holes: Vec<u32> = (0..starts.len().saturating_sub(1))
            .filter(|&f| ct.is_hole(of_corner[starts[f] as usize] / 3))
            .map(|f| f as u32)
            .collect();
        // the faces are those of a valid table, re-joined: a valid polygon table
        let (pt, _, kept) = PolyTable::build(ct.num_vertices(), &starts, &corners, None)
            .expect("the faces of a valid triangle table, joined across diagonals, are a valid polygon table");
        debug_assert!(kept.is_none());
        let pt = pt.with_holes(holes);
        let pt = match ct.sharpness() {
            None => pt,
            Some(s) => {
                // triangle corner -> the polygon corner naming the same edge
                let mut poly_of = vec![BORDER; ct.num_corners()];
                for (pc, &x) in of_corner.iter().enumerate() {
                    poly_of[x as usize] = pc as u32;
                }
                let sharp = s
                    .sharp_corners()
                    .iter()
                    .filter(|&&(x, _)| poly_of[x as usize] != BORDER)
                    .map(|&(x, v)| (poly_of[x as usize], v))
                    .collect();
                pt.with_sharpness(Sharpness::from_lists(sharp, s.sharp_vertices().to_vec()))
            }
        };
        (pt, of_corner)
    }
}

/// The faces of `ct` joined across hidden diagonals: face starts, corner
/// vertices, and for every polygon corner the triangle corner naming its
/// edge.
fn recover_faces(ct: &CornerTable) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let nt = ct.num_triangles();
    let hidden = |c: u32| ct.edge_generation(c) == Generations::HIDDEN && ct.o_entry(c) != BORDER;
    let any_hidden = ct.generations().is_some_and(Generations::may_hide) && (0..ct.num_corners() as u32).any(hidden);
    if !any_hidden {
        let starts = (0..=nt as u32).map(|t| 3 * t).collect();
        // triangle corner c names the edge opposite it, the polygon corner
        // the edge leaving it: corner c of the face leaves along the edge
        // opposite p(c)
        let of_corner = (0..ct.num_corners() as u32).map(crate::mesh::p).collect();
        return (starts, ct.v_table().to_vec(), of_corner);
    }
    // components of triangles across hidden edges (union by smaller id)
    let mut root: Vec<u32> = (0..nt as u32).collect();
    fn find(root: &mut [u32], mut t: u32) -> u32 {
        while root[t as usize] != t {
            root[t as usize] = root[root[t as usize] as usize];
            t = root[t as usize];
        }
        t
    }
    for c in 0..ct.num_corners() as u32 {
        if hidden(c) {
            let (a, b) = (find(&mut root, c / 3), find(&mut root, ct.o_entry(c) / 3));
            root[a.max(b) as usize] = a.min(b);
        }
    }
    // each component's outer half-edges, by component, then walked
    let mut comp_edges: Vec<(u32, u32, u32, u32)> = Vec::with_capacity(ct.num_corners());
    for c in 0..ct.num_corners() as u32 {
        if !hidden(c) {
            let r = find(&mut root, c / 3);
            comp_edges.push((r, ct.vtx(crate::mesh::n(c)), ct.vtx(crate::mesh::p(c)), c));
        }
    }
    comp_edges.sort_unstable();
    let (mut starts, mut corners, mut of_corner) = (vec![0u32], Vec::new(), Vec::new());
    for group in comp_edges.chunk_by(|x, y| x.0 == y.0) {
        // start -> (end, triangle corner): a polygon visits a vertex once,
        // and the group is sorted by start vertex
        let next = |v: u32| group.binary_search_by_key(&v, |e| e.1).ok().map(|i| &group[i]);
        // the polygon starts where the file's face did: a face is fanned
        // from its first corner, so that is corner 0 of its first triangle
        // (the component's root, its smallest id)
        let first = Some(ct.vtx(3 * group[0].0)).filter(|&v| next(v).is_some()).unwrap_or(group[0].1);
        let mut v = first;
        while let Some(&(_, _, end, x)) = next(v) {
            corners.push(v);
            of_corner.push(x);
            v = end;
            if v == first || corners.len() - *starts.last().unwrap_or(&0) as usize > group.len() {
                break;
            }
        }
        starts.push(corners.len() as u32);
    }
    (starts, corners, of_corner)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::topology::check_invariants;

    #[test]
    fn the_fan_has_the_table_a_rebuild_gives_and_hides_only_diagonals() {
        // a pentagon and a quad and a triangle around vertex 0, open
        let starts = [0u32, 5, 9, 12];
        let corners = [0, 1, 2, 3, 4, 0, 4, 5, 6, 0, 6, 1];
        let (pt, _, _) = PolyTable::build(7, &starts, &corners, None).unwrap();
        let ct = pt.triangulated();
        check_invariants(&ct).unwrap();
        let (rebuilt, _, _) = CornerTable::build(7, ct.v_table(), None).unwrap();
        assert_eq!(rebuilt.o_table(), ct.o_table());
        assert_eq!(ct.num_triangles(), 3 + 2 + 1);
        // 2 + 1 diagonals hidden, every polygon edge shown (generation 0)
        let hidden = (0..ct.num_corners() as u32).filter(|&c| ct.edge_generation(c) == Generations::HIDDEN).count();
        assert_eq!(hidden, 2 * 3);
        assert_eq!(crate::mesh::draw::edge_indices(&ct).len() / 2, pt.num_edges());
        // and the polygons come back from the triangles
        let positions = vec![Vec3::ZERO; 7];
        let back = PolyMesh::from_mesh(&Mesh { ct, positions });
        assert_eq!(back.pt.num_faces(), 3);
        let mut sizes: Vec<u32> = (0..3).map(|f| back.pt.face_size(f)).collect();
        sizes.sort_unstable();
        assert_eq!(sizes, vec![3, 4, 5]);
        assert_eq!(back.pt.num_edges(), pt.num_edges());
    }
}
