//! The polygon corner table: faces of any size at the control level, only
//! quads from the first Catmull-Clark (or bilinear) split on.
//!
//! A face of `k` corners owns `k` consecutive corner ids; corner `c` is at
//! vertex `V[c]`, and names the edge *leaving* it, from `V[c]` to
//! `V[next(c)]` (a triangle's corner names the edge opposite it instead;
//! both tables speak [`EdgeTable`]). Its twin `T[c]` is the corner across
//! that edge, at its other end: `V[T[c]] = V[next(c)]` and
//! `V[next(T[c])] = V[c]`, or [`BORDER`]. Around a vertex, `swing(c) =
//! T[prev(c)]` is the next corner of the fan (across the edge entering
//! `c`), `unswing(c) = next(T[c])` the previous one.
//!
//! At the control level the faces are stored by their first corners
//! (`starts`, and each corner's face); from the first split on every face
//! is a quad, corner `c` in face `c / 4`, `next` and `prev` by arithmetic,
//! and nothing else is stored (docs/schemes.md §12.1).

mod build;
pub(crate) mod join;
pub(crate) mod split;
mod triangulate;

use super::edges::EdgeTable;
use super::sharpness::{Sharpness, Tags};
use super::{BORDER, owns_edge};
use glam::Vec3;

pub use build::PolyBuildReport;

/// Connectivity of a polygon mesh: faces, V, T (twins), one corner per
/// vertex and valences.
///
/// Invariants (the same as [`super::CornerTable`]'s, established by
/// [`PolyTable::build`] and kept by the `split`): every face has at least
/// 3 corners and uses no vertex twice; `V` entries are below
/// `num_vertices()`; `T` is an involution without fixed points whose
/// pairs run along the same edge reversed, or [`BORDER`]; every vertex has
/// exactly one fan; `C[v]` is a corner of `v`, the first of its fan (its
/// edge leaves along the border) on the boundary; `valence[v]` counts its
/// edges; every vertex is used.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PolyTable {
    /// The first corner of every face and the end of the last (`F + 1`
    /// entries), and the face of every corner; `None`: every face is a quad.
    faces: Option<Faces>,
    /// `V[c]`: the vertex of corner `c`.
    v: Vec<u32>,
    /// `T[c]`: the corner across the edge leaving `c`, or [`BORDER`].
    t: Vec<u32>,
    /// `C[v]`: one corner of `v`, the first of its fan on the boundary.
    vc: Vec<u32>,
    /// Edges at each vertex.
    valence: Vec<u32>,
    /// Sharp edges (by the corners naming them) and vertices.
    sharpness: Option<Box<Sharpness>>,
    /// The faces that are holes, sorted (see [`crate::CornerTable::holes`]).
    holes: Option<Box<[u32]>>,
    /// How many splits made it (the edge generations follow).
    level: u32,
}

/// The faces of a control-level table with faces other than quads.
#[derive(Clone, Debug, PartialEq, Default)]
struct Faces {
    starts: Vec<u32>,
    face: Vec<u32>,
}

impl PolyTable {
    /// Faces.
    #[inline]
    pub fn num_faces(&self) -> usize {
        self.faces.as_ref().map_or(self.v.len() / 4, |f| f.starts.len() - 1)
    }
    /// Corners (the sum of the face sizes).
    #[inline]
    pub fn num_corners(&self) -> usize {
        self.v.len()
    }
    /// Vertices.
    #[inline]
    pub fn num_vertices(&self) -> usize {
        self.vc.len()
    }
    /// Edges: each interior edge has two corners, each border edge one.
    pub fn num_edges(&self) -> usize {
        (self.num_corners() + self.num_border_edges()) / 2
    }
    /// Border edges.
    pub(crate) fn num_border_edges(&self) -> usize {
        self.t.iter().filter(|&&x| x == BORDER).count()
    }
    /// Whether every face is a quad stored by arithmetic.
    #[inline]
    pub fn is_quads(&self) -> bool {
        self.faces.is_none()
    }
    /// The face of corner `c`.
    #[inline(always)]
    pub fn face(&self, c: u32) -> u32 {
        match &self.faces {
            None => c / 4,
            Some(f) => f.face[c as usize],
        }
    }
    /// The corners of face `f`.
    #[inline(always)]
    pub fn face_corners(&self, f: u32) -> std::ops::Range<u32> {
        match &self.faces {
            None => 4 * f..4 * f + 4,
            Some(x) => x.starts[f as usize]..x.starts[f as usize + 1],
        }
    }
    /// Corners of face `f`.
    #[inline(always)]
    pub fn face_size(&self, f: u32) -> u32 {
        let r = self.face_corners(f);
        r.end - r.start
    }
    /// The next corner of `c`'s face (counter-clockwise).
    #[inline(always)]
    pub fn next(&self, c: u32) -> u32 {
        match &self.faces {
            None => (c & !3) | ((c + 1) & 3),
            Some(f) => {
                let face = f.face[c as usize] as usize;
                if c + 1 == f.starts[face + 1] { f.starts[face] } else { c + 1 }
            }
        }
    }
    /// The previous corner of `c`'s face.
    #[inline(always)]
    pub fn prev(&self, c: u32) -> u32 {
        match &self.faces {
            None => (c & !3) | (c.wrapping_sub(1) & 3),
            Some(f) => {
                let face = f.face[c as usize] as usize;
                if c == f.starts[face] { f.starts[face + 1] - 1 } else { c - 1 }
            }
        }
    }
    /// The vertex of corner `c`.
    #[inline(always)]
    pub fn vtx(&self, c: u32) -> u32 {
        self.v[c as usize]
    }
    /// The raw twin entry of `c` ([`BORDER`] on the border).
    #[inline(always)]
    pub(crate) fn twin_entry(&self, c: u32) -> u32 {
        self.t[c as usize]
    }
    /// The corner across the edge leaving `c`.
    #[inline]
    pub fn twin(&self, c: u32) -> Option<u32> {
        let x = self.t[c as usize];
        (x != BORDER).then_some(x)
    }
    /// The next corner around `V[c]` (across the edge entering `c`).
    #[inline]
    pub(crate) fn swing(&self, c: u32) -> Option<u32> {
        self.twin(self.prev(c))
    }
    /// The V table.
    pub fn v_table(&self) -> &[u32] {
        &self.v
    }
    /// The twin table.
    pub(crate) fn t_table(&self) -> &[u32] {
        &self.t
    }
    /// Edges at each vertex.
    pub fn valences(&self) -> &[u32] {
        &self.valence
    }
    /// One corner of vertex `v`, the first of its fan on the boundary.
    #[inline]
    pub(crate) fn corner_of(&self, v: u32) -> u32 {
        self.vc[v as usize]
    }
    /// Whether `v` is on the border.
    #[inline]
    pub fn is_boundary_vertex(&self, v: u32) -> bool {
        self.t[self.vc[v as usize] as usize] == BORDER
    }
    /// The corners of vertex `v`, in fan order (from the first on the
    /// boundary).
    pub fn fan(&self, v: u32) -> impl Iterator<Item = u32> + '_ {
        let start = self.vc[v as usize];
        let mut next = Some(start);
        std::iter::from_fn(move || {
            let c = next?;
            next = self.swing(c).filter(|&x| x != start);
            Some(c)
        })
    }
    /// The corner owning each edge ([`owns_edge`] of its twin entry), in
    /// corner order.
    pub(crate) fn edge_owners(&self) -> impl Iterator<Item = u32> + '_ {
        self.t.iter().enumerate().filter(|&(c, &x)| owns_edge(c as u32, x)).map(|(c, _)| c as u32)
    }
    /// Sharp edges and vertices.
    pub fn sharpness(&self) -> Option<&Sharpness> {
        self.sharpness.as_deref()
    }
    /// This table with the sharpness `tags` give it (replacing any).
    ///
    /// # Errors
    /// [`crate::MeshError::BadTag`] for a tag naming a vertex or an edge
    /// that does not exist, or an invalid sharpness.
    pub fn with_tags(self, tags: &Tags) -> Result<PolyTable, crate::MeshError> {
        let s = Sharpness::from_tags(&self, tags)?;
        Ok(self.with_sharpness(s))
    }
    /// This table with `sharpness`, made for it.
    pub(crate) fn with_sharpness(mut self, sharpness: Option<Sharpness>) -> PolyTable {
        self.sharpness = sharpness.map(Box::new);
        self
    }
    /// The faces that are holes, sorted (empty: none; see
    /// [`crate::CornerTable::holes`]).
    #[inline]
    pub fn holes(&self) -> &[u32] {
        self.holes.as_deref().unwrap_or(&[])
    }
    /// Whether face `f` is a hole.
    #[inline]
    pub(crate) fn is_hole(&self, f: u32) -> bool {
        self.holes.as_deref().is_some_and(|h| h.binary_search(&f).is_ok())
    }
    /// This table with the faces `holes` (ids in range, any order) as its
    /// holes, replacing any it had.
    pub fn with_holes(mut self, mut holes: Vec<u32>) -> PolyTable {
        holes.retain(|&f| (f as usize) < self.num_faces());
        holes.sort_unstable();
        holes.dedup();
        self.holes = (!holes.is_empty()).then(|| holes.into_boxed_slice());
        self
    }
    /// How many splits made this table (0: a control table).
    pub(crate) fn level(&self) -> u32 {
        self.level
    }
    /// The generation of the edge leaving corner `c`: 0 for a piece of a
    /// control edge, `j` for an edge made inside a face by the `j`-th
    /// split. In a split, child corners `4x` and `4x + 3` lie along halves
    /// of the edges leaving `x` and `prev(x)`, `4x + 1` and `4x + 2` along
    /// the new inner edges ([`split`]); walking back level by level costs
    /// no stored byte per corner.
    pub(crate) fn edge_generation(&self, c: u32) -> u8 {
        let mut c = c;
        for level in (1..=self.level).rev() {
            match c % 4 {
                1 | 2 => return level.min(255) as u8,
                0 => c /= 4,
                // level > 1: the parent level is quads, prev by arithmetic
                _ => c = ((c / 4) & !3) | ((c / 4).wrapping_sub(1) & 3),
            }
        }
        0
    }
}

impl EdgeTable for PolyTable {
    fn num_vertices(&self) -> usize {
        PolyTable::num_vertices(self)
    }
    #[inline]
    fn twin_entry(&self, c: u32) -> u32 {
        self.t[c as usize]
    }
    #[inline]
    fn edge_ends(&self, c: u32) -> (u32, u32) {
        (self.v[c as usize], self.v[self.next(c) as usize])
    }
    fn valence(&self, v: u32) -> u32 {
        self.valence[v as usize]
    }
    fn is_boundary_vertex(&self, v: u32) -> bool {
        PolyTable::is_boundary_vertex(self, v)
    }
    fn sharpness(&self) -> Option<&Sharpness> {
        PolyTable::sharpness(self)
    }
    fn each_edge_at(&self, v: u32, f: &mut dyn FnMut(u32, u32)) {
        let mut last = None;
        for c in self.fan(v) {
            // the edge leaving c
            f(c, self.v[self.next(c) as usize]);
            last = Some(c);
        }
        // a boundary fan ends with the border edge entering its last corner
        if let Some(c) = last {
            let e = self.prev(c);
            if self.t[e as usize] == BORDER {
                f(e, self.v[e as usize]);
            }
        }
    }
}

/// A polygon mesh: connectivity plus one position per vertex.
#[derive(Clone, Debug, Default)]
pub struct PolyMesh {
    /// The table.
    pub pt: PolyTable,
    /// One position per vertex.
    pub positions: Vec<Vec3>,
}

impl PolyMesh {
    /// Builds and validates a polygon mesh from positions and faces (each
    /// face's corners from `face_starts[f]` to `face_starts[f + 1]` of
    /// `corners`). Unreferenced vertices are dropped.
    ///
    /// # Errors
    /// Any [`crate::MeshError`] found by validation, face ids those of the input.
    pub fn from_faces(
        positions: Vec<Vec3>,
        face_starts: &[u32],
        corners: &[u32],
    ) -> Result<(PolyMesh, PolyBuildReport), crate::MeshError> {
        let (pt, report, kept) = PolyTable::build(positions.len(), face_starts, corners, Some(&positions))?;
        let positions = match kept {
            Some(k) => k.iter().map(|&i| positions[i as usize]).collect(),
            None => positions,
        };
        Ok((PolyMesh { pt, positions }, report))
    }

    /// The faces as vertex-id lists: every face's corners in order.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        (0..self.pt.num_faces() as u32).map(|f| {
            let r = self.pt.face_corners(f);
            &self.pt.v[r.start as usize..r.end as usize]
        })
    }
}
