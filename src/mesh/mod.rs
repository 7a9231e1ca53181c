//! The corner table (Rossignac, Safonova, Szymczak, "Edgebreaker on a Corner
//! Table", SMI 2001): triangle `t` owns corners `3t, 3t+1, 3t+2`; `V[c]` is the
//! vertex of corner `c` and `O[c]` the corner facing `c` across the edge
//! opposite `c`, or [`BORDER`] when that edge is on the boundary.
//!
//! Operators (`n`, `p`, `o`, `l`, `r`, `s`, `u`) are tiny inline functions on
//! corner ids. Never treat `O[c] == c` as a border (docs/schemes.md §7.2): the
//! sentinel is `u32::MAX`, and [`CornerTable::o`] returns `Option`.
//!
//! Besides V and O the table keeps, per vertex, one corner `C[v]` (for a
//! boundary vertex the first corner of its fan, so that swinging forward visits
//! the whole fan) and the valence (number of incident edges). All four arrays
//! are propagated through a 1-to-4 split in linear time ([`split`]).

pub(crate) mod attributes;
mod build;
pub(crate) mod coord;
pub(crate) mod counts;
pub(crate) mod cut;
pub(crate) mod draw;
pub(crate) mod edges;
pub(crate) mod edit;
pub(crate) mod inspect;
pub(crate) mod lineage;
pub(crate) mod normals;
pub(crate) mod options;
pub(crate) mod order;
pub(crate) mod pick;
pub(crate) mod poly;
pub(crate) mod repair;
pub(crate) mod scene;
pub(crate) mod shapes;
pub(crate) mod sharpness;
pub(crate) mod smooth;
pub(crate) mod split;
pub(crate) mod topology;

use glam::Vec3;
use rayon::prelude::*;

// The mesh layer as the library's users see it: its modules are the crate's
// own, and what a caller needs is named here once.
pub use attributes::{
    Attributes, Material, MaterialGroups, Texture, UvInterpolation, Wrap, refine_corner_uvs, refine_face_ids,
};
pub use build::BuildReport;
pub use edit::{EditError, flip_edge, split_edge};
pub use inspect::{
    colormap, corner_ops, displacement_from_control, poly_corner_ops, vertex_counts_per_level, vertex_creation_level,
};
pub use normals::face_normals;
pub use options::{FileScheme, ShapeOptions, TriangleSubdivision};
pub use order::Relabel;
pub use poly::{PolyBuildReport, PolyMesh, PolyTable};
pub use repair::{RepairReport, repair};
pub use scene::{Prim, Scene, UpAxis};
pub use shapes::icosphere;
pub use sharpness::{
    BoundaryInterpolation, CornerTag, CreaseTag, Creasing, INFINITE, Sharpness, Tags, checked_sharpness,
};
pub use smooth::{TAUBIN_LAMBDA, TAUBIN_MU, laplacian, smooth_f64, taubin};
pub use split::{number_edges, refine_linear, split, split_linear};
pub use topology::{Topology, check_invariants, topology};

/// Axis-aligned bounds `(min, max)` of points; zero when there are none.
pub(crate) fn bounds_of<'a>(points: impl IntoIterator<Item = &'a Vec3>) -> (Vec3, Vec3) {
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
/// Whether corner `c`, whose raw O entry is `o_entry`, names its edge once for the
/// mesh: a border corner always does, an interior edge by its smaller corner.
/// (`BORDER` is `u32::MAX`, so this is `c < o`.)
#[inline(always)]
pub(crate) fn owns_edge(c: u32, o_entry: u32) -> bool {
    c < o_entry
}

/// Connectivity of a triangle mesh: V, O, one corner per vertex and valences.
///
/// The tables are private: a `CornerTable` is made only by the validating
/// constructors ([`CornerTable::build`], [`CornerTable::from_vo`]), by the
/// 1-to-4 [`split`] of a valid table and by the edits of `edit`, each of
/// which keeps the invariants that the rest of the crate relies on (the
/// split's parallel raw-pointer writes, indexed by O, among them):
///
/// * `V` has `3 F` entries, each `< num_vertices()`, no triangle using a
///   vertex twice; corner and vertex ids are below [`BORDER`];
/// * `O` has `3 F` entries, each [`BORDER`] or a corner `x < 3 F` with
///   `O[x] = c`, `x != c`, and the two corners' edges the same one reversed;
/// * every vertex has exactly one fan; `C[v]` is a corner of `v`, the first
///   of its fan for a boundary vertex; `valence[v]` is its number of
///   incident edges.
///
/// Where they are established: `from_vo` checks V and O entry by entry and
/// walks every fan to fill C and the valences (`build` makes O from V and
/// then goes through `from_vo`; `Default` is the empty table). The split
/// writes V', O', C' and the valences by the formulas of docs/schemes.md §7.4-7.5
/// from a table that has the invariants (`tests/topology.rs` checks them
/// against a rebuild for every scheme and level). Each edit changes O in
/// pairs, both ends of every entry it writes, and recomputes C and the
/// valence of each vertex it touches from its fan (`tests/edit.rs` checks
/// a rebuild after every edit).
///
/// Outside the crate the fields cannot be set, nor the struct be built by
/// hand:
///
/// ```compile_fail,E0616
/// let mut ct = subdiv::CornerTable::default();
/// ct.o = vec![0, 0, 0]; // error: field `o` is private
/// ```
///
/// ```compile_fail,E0451
/// let ct = subdiv::CornerTable { v: vec![0, 1, 2], o: vec![7, 7, 7], vc: vec![0, 1, 2], valence: vec![2; 3] };
/// ```
#[derive(Clone, Debug, PartialEq, Default)]
pub struct CornerTable {
    /// `V[c]`: vertex of corner `c` (3 per triangle, counter-clockwise).
    v: Vec<u32>,
    /// `O[c]`: opposite corner, or [`BORDER`].
    o: Vec<u32>,
    /// `C[v]`: one corner of vertex `v`; for boundary vertices the corner `c`
    /// with `u(c)` undefined (the first of the fan in swing order).
    vc: Vec<u32>,
    /// Number of edges incident to each vertex.
    valence: Vec<u32>,
    /// Sharp edges and vertices, when there are any.
    sharpness: Option<Box<Sharpness>>,
    /// The triangles that are holes (OpenSubdiv's hole tags: left out of
    /// the surface, their vertices still shaping their neighbours), sorted;
    /// `None` when there are none.
    holes: Option<Box<[u32]>>,
    /// Edge generations, when the table comes from splits (`None`: a
    /// control table, every edge of generation 0).
    generations: Option<Box<Generations>>,
}

/// The level at which every edge was created: `corner(c)` is the
/// generation of the edge opposite `c` (from `v(n(c))` to `v(p(c))`), so
/// both corners of an interior edge hold the same value. Generation 0 is a
/// piece of a control-mesh edge; generation `j >= 1` an edge made inside a
/// face by the `j`-th split; [`Generations::HIDDEN`] a diagonal drawn
/// inside a polygon (a fanned face's, a triangulated quad's), which is no
/// edge of the polygon mesh and never drawn as one (once a triangle scheme
/// splits the table it is an edge like the others, of generation 0).
/// Saturates below `HIDDEN`.
///
/// Derived, not stored, for a table made by triangle splits: its
/// generations are fixed by the corner layout of the split (see [`split`])
/// from those of the table the splits started from (all 0 for a control
/// table, or given per corner, `base`, for a triangulated polygon mesh), so
/// only the triangle count before each split is kept.
/// [`Generations::corner`] walks one corner back through the splits;
/// [`Generations::corners`] writes all of them, level by level, for the
/// renderer.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct Generations {
    /// Per corner, the generations of the table the splits started from
    /// (`None`: all 0), and the level it was made at.
    base: Option<(Vec<u8>, u8)>,
    /// Triangles of the table before each split, oldest first.
    splits: Vec<usize>,
}

impl Generations {
    /// The generation of a polygon's inner diagonal: never drawn.
    pub const HIDDEN: u8 = 31;

    /// The generations of a table (a triangulated polygon mesh made at
    /// `level`) given per corner.
    pub(crate) fn explicit(corners: Vec<u8>, level: u8) -> Generations {
        Generations { base: Some((corners, level)), splits: Vec::new() }
    }
    /// Whether some edge may be [`Self::HIDDEN`]: only a table given its
    /// generations per corner (a triangulated polygon mesh) and not split
    /// since (a triangle split shows every edge).
    pub(crate) fn may_hide(&self) -> bool {
        self.splits.is_empty() && self.base.as_ref().is_some_and(|(b, _)| b.contains(&Self::HIDDEN))
    }
    /// The newest generation of the table.
    pub fn level(&self) -> u8 {
        let base = self.base.as_ref().map_or(0, |b| b.1);
        (base as usize + self.splits.len()).min(Self::HIDDEN as usize - 1) as u8
    }
    /// The generation of the edge opposite corner `c` (split.rs, "Edge
    /// generations"): in the split of a table with `nt` triangles, a
    /// central corner (`c < 3nt`) and the first corner `A` of a corner
    /// triangle face edges of the new generation; `n(A)` and `p(A)` of the
    /// corner triangle `k` of old triangle `t` face halves of old edges,
    /// those opposite the old corners `3t + (k+1)%3` and `3t + (k+2)%3`.
    pub fn corner(&self, c: u32) -> u8 {
        let base_level = self.base.as_ref().map_or(0, |b| b.1) as usize;
        let mut c = c as usize;
        for (j, &nt) in self.splits.iter().enumerate().rev() {
            let (nc, generation) = (3 * nt, (base_level + j + 1).min(Self::HIDDEN as usize - 1) as u8);
            if c < nc {
                return generation;
            }
            let (k, rest) = ((c - nc) / nc, (c - nc) % nc);
            let (t, i) = (rest / 3, rest % 3);
            if i == 0 {
                return generation;
            }
            c = 3 * t + (k + i) % 3;
        }
        let g = self.base.as_ref().map_or(0, |b| b.0.get(c).copied().unwrap_or(0));
        // a triangle split makes a hidden diagonal a real edge
        if g == Self::HIDDEN && !self.splits.is_empty() { 0 } else { g }
    }
    /// [`Self::corner`] of every corner, written split by split from the
    /// base table's (four streams per old triangle, in parallel).
    pub fn corners(&self) -> Vec<u8> {
        let base_level = self.base.as_ref().map_or(0, |b| b.1) as usize;
        let mut corner = match &self.base {
            // a triangle split makes a hidden diagonal a real edge
            Some((b, _)) if !self.splits.is_empty() => {
                b.iter().map(|&g| if g == Self::HIDDEN { 0 } else { g }).collect()
            }
            Some((b, _)) => b.clone(),
            None => vec![0u8; self.splits.first().map_or(0, |&nt| 3 * nt)],
        };
        for (j, &nt) in self.splits.iter().enumerate() {
            debug_assert_eq!(corner.len(), 3 * nt);
            corner = split::split_generations(&corner, (base_level + j + 1).min(Self::HIDDEN as usize - 1) as u8);
        }
        corner
    }
    /// The generations of the split of a table with these generations and
    /// `nt` triangles.
    pub(crate) fn after_split(&self, nt: usize) -> Generations {
        let mut splits = self.splits.clone();
        splits.push(nt);
        Generations { base: self.base.clone(), splits }
    }
}

impl CornerTable {
    /// The V table: `v_table()[c]` is the vertex of corner `c`, three
    /// corners per triangle (the triangle index list).
    #[inline(always)]
    pub fn v_table(&self) -> &[u32] {
        &self.v
    }
    /// The raw O table: `o_table()[c]` is the corner opposite `c`, or
    /// [`BORDER`]. Prefer the checked operator [`Self::o`], which says
    /// `None` for the border; the raw table is for passes over all corners.
    #[inline(always)]
    pub fn o_table(&self) -> &[u32] {
        &self.o
    }
    /// The C table: `c_table()[v]` is one corner of vertex `v` (for a
    /// boundary vertex the first of its fan).
    #[inline(always)]
    pub fn c_table(&self) -> &[u32] {
        &self.vc
    }
    /// The valence (number of incident edges) of every vertex.
    #[inline(always)]
    pub fn valences(&self) -> &[u32] {
        &self.valence
    }
    /// The valence of vertex `v`.
    #[inline(always)]
    pub fn valence(&self, v: u32) -> u32 {
        self.valence[v as usize]
    }
    /// `C[v]`: one corner of vertex `v`, the first of its fan on the boundary.
    #[inline(always)]
    pub(crate) fn corner_of(&self, v: u32) -> u32 {
        self.vc[v as usize]
    }
    /// The raw O entry of corner `c`: the opposite corner or [`BORDER`]
    /// (the checked operator is [`Self::o`]).
    #[inline(always)]
    pub fn o_entry(&self, c: u32) -> u32 {
        self.o[c as usize]
    }
    /// The tables, for the crate's own constructors and edits.
    pub(crate) fn from_parts(v: Vec<u32>, o: Vec<u32>, vc: Vec<u32>, valence: Vec<u32>) -> CornerTable {
        CornerTable { v, o, vc, valence, sharpness: None, holes: None, generations: None }
    }
    /// The triangles that are holes, sorted (empty: none). A hole is not
    /// part of the surface (not drawn, not written, not picked) but its
    /// vertices and edges are the table's like any other, so the rules
    /// around it are those of a closed mesh; its children after a split are
    /// holes too.
    #[inline]
    pub fn holes(&self) -> &[u32] {
        self.holes.as_deref().unwrap_or(&[])
    }
    /// Whether triangle `t` is a hole.
    #[inline]
    pub(crate) fn is_hole(&self, t: u32) -> bool {
        self.holes.as_deref().is_some_and(|h| h.binary_search(&t).is_ok())
    }
    /// This table with the triangles `holes` (ids in range, any order) as
    /// its holes, replacing any it had.
    pub fn with_holes(mut self, mut holes: Vec<u32>) -> CornerTable {
        holes.retain(|&t| (t as usize) < self.num_triangles());
        holes.sort_unstable();
        holes.dedup();
        self.holes = (!holes.is_empty()).then(|| holes.into_boxed_slice());
        self
    }
    /// The holes after a 1-to-4 split of this table: the central child of
    /// triangle `t` keeps its id, the corner children are `nt (j + 1) + t`.
    pub(crate) fn split_holes(&self) -> Vec<u32> {
        let nt = self.num_triangles() as u32;
        let mut out: Vec<u32> = (0..4).flat_map(|j| self.holes().iter().map(move |&t| j * nt + t)).collect();
        out.sort_unstable();
        out
    }
    /// Sharp edges and vertices (`None`: every edge but the border is
    /// smooth, every vertex smooth).
    #[inline]
    pub fn sharpness(&self) -> Option<&Sharpness> {
        self.sharpness.as_deref()
    }
    /// This table with the sharpness that `tags` give it (replacing any it
    /// had); see `Sharpness::from_tags`.
    ///
    /// # Errors
    /// [`crate::MeshError::BadTag`] for a tag naming a vertex or an edge
    /// that does not exist, or an invalid sharpness.
    pub fn with_tags(self, tags: &Tags) -> Result<CornerTable, crate::MeshError> {
        let s = Sharpness::from_tags(&self, tags)?;
        Ok(self.with_sharpness(s))
    }
    /// This table with `sharpness`, which must have been made for it (or
    /// by the split of its parent).
    pub(crate) fn with_sharpness(mut self, sharpness: Option<Sharpness>) -> CornerTable {
        self.sharpness = sharpness.map(Box::new);
        self
    }
    /// The edge generations (`None`: a control table, all of generation 0).
    #[inline]
    pub fn generations(&self) -> Option<&Generations> {
        self.generations.as_deref()
    }
    /// The level this table was made at: 0 for a control table.
    #[inline]
    pub fn level(&self) -> u8 {
        self.generations.as_ref().map_or(0, |g| g.level())
    }
    /// Generation of the edge opposite corner `c` (0 on a control table).
    #[inline]
    pub fn edge_generation(&self, c: u32) -> u8 {
        self.generations.as_ref().map_or(0, |g| g.corner(c))
    }
    /// This table with `generations`, which must have been made for it by
    /// the split of its parent.
    pub(crate) fn with_generations(mut self, generations: Option<Generations>) -> CornerTable {
        self.generations = generations.map(Box::new);
        self
    }
    /// Forgets the generations (an edit changed the edges: the table counts
    /// as a new control table).
    pub(crate) fn clear_generations(&mut self) {
        self.generations = None;
    }
    /// Sharpness of the edge opposite corner `c`: [`sharpness::INFINITE`]
    /// on the border, the tagged value (or 0) inside.
    #[inline]
    pub fn edge_sharpness(&self, c: u32) -> f32 {
        if self.o[c as usize] == BORDER {
            sharpness::INFINITE
        } else {
            self.sharpness.as_ref().map_or(0.0, |s| s.corner(c))
        }
    }
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
    pub(crate) fn l(&self, c: u32) -> Option<u32> {
        self.o(n(c))
    }
    /// Right neighbour `o(p(c))`: across the edge `(v(c), v(n(c)))`.
    #[inline]
    pub(crate) fn r(&self, c: u32) -> Option<u32> {
        self.o(p(c))
    }
    /// Swing `n(o(n(c)))`: the corner of the same vertex in the next triangle
    /// counter-clockwise; `None` at the border.
    #[inline(always)]
    pub(crate) fn s(&self, c: u32) -> Option<u32> {
        self.o(n(c)).map(n)
    }
    /// Unswing `p(o(p(c)))`, the inverse of [`Self::s`]; `None` at the border.
    #[inline(always)]
    pub(crate) fn u(&self, c: u32) -> Option<u32> {
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
    /// The two boundary neighbours `(q_first, q_last)` of vertex `v`, or
    /// `None` when `v` is interior: `q_first` across the border edge of
    /// `C[v]`, `q_last` at the end of the fan.
    pub(crate) fn boundary_neighbours(&self, v: u32) -> Option<(u32, u32)> {
        let first = self.vc[v as usize];
        if self.o[p(first) as usize] != BORDER {
            return None;
        }
        // a boundary fan is open: swinging forward from its first corner
        // reaches the other border edge after at most valence - 1 steps
        let mut c = first;
        while let Some(x) = self.s(c) {
            c = x;
        }
        Some((self.vtx(n(first)), self.vtx(p(c))))
    }
    /// Whether the table has no border (a closed surface).
    pub(crate) fn is_closed(&self) -> bool {
        !self.o.contains(&BORDER)
    }
    /// Number of border edges (corners whose opposite is the border).
    pub fn num_border_edges(&self) -> usize {
        self.o.iter().filter(|&&x| x == BORDER).count()
    }
    /// The corner owning each edge (see `owns_edge`), in corner order: the
    /// edge is the one opposite it, from `v(n(c))` to `v(p(c))`.
    pub fn edge_owners(&self) -> impl Iterator<Item = u32> + '_ {
        self.o.iter().enumerate().map(|(c, &x)| (c as u32, x)).filter(|&(c, x)| owns_edge(c, x)).map(|(c, _)| c)
    }
    /// Number of edges: each interior edge has two corners, each border edge one.
    pub(crate) fn num_edges(&self) -> usize {
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

/// A mesh as its faces alone, every face with the same number of corners
/// (`sides`: 3 for triangles, 4 for quads): positions and the vertex of
/// every corner (counter-clockwise), without the adjacency of a
/// [`CornerTable`] or a polygon table. What a subdivision gives when its
/// caller only writes or copies the faces ([`crate::subdiv::subdivide_faces`],
/// `crate::subdiv::subdivide_poly_faces_as`): the last level then skips its
/// adjacency tables. The vertex ids are the library's `u32` unless the
/// caller asked for others (`crate::subdiv::subdivide_mesh_faces_as`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Faces<I = u32, P = Vec3> {
    /// One position per vertex (f32, or f64 from `subdivide_faces_f64`).
    pub positions: Vec<P>,
    /// The vertex of every corner, `sides` corners a face.
    pub corners: Vec<I>,
    /// Corners per face.
    pub sides: usize,
}

/// A vertex id as a faces-only subdivision can write it: the library's own
/// `u32`, or whatever a caller maps it to (a wider integer, its own
/// numbering) in the pass that writes the faces.
pub trait VertexId: bytemuck::Zeroable + Copy + Send + Sync {}
impl<T: bytemuck::Zeroable + Copy + Send + Sync> VertexId for T {}

impl Faces {}

impl<I: VertexId> Faces<I> {
    /// The triangles of `mesh` (copied), every vertex id `j` as `id(j)`;
    /// its holes left out (every vertex kept, as OpenSubdiv writes them).
    pub(crate) fn of_mapped(mesh: &Mesh, id: impl Fn(u32) -> I + Sync) -> Faces<I> {
        Faces::of_table(&mesh.ct, mesh.positions.clone(), id)
    }
}

impl<I: VertexId, P> Faces<I, P> {
    /// The triangles of `ct` with `positions`, as [`Faces::of_mapped`].
    pub(crate) fn of_table(ct: &CornerTable, positions: Vec<P>, id: impl Fn(u32) -> I + Sync) -> Faces<I, P> {
        let v = ct.v_table();
        let corners = if ct.holes().is_empty() {
            v.par_iter().with_min_len(1 << 14).map(|&j| id(j)).collect()
        } else {
            let kept = (0..ct.num_triangles() as u32).filter(|&t| !ct.is_hole(t));
            kept.flat_map(|t| v[3 * t as usize..3 * t as usize + 3].iter().map(|&j| id(j))).collect()
        };
        Faces { positions, corners, sides: 3 }
    }

    /// These faces without those listed in `holes` (sorted face ids).
    pub(crate) fn without(mut self, holes: &[u32]) -> Faces<I, P> {
        if holes.is_empty() {
            return self;
        }
        let s = self.sides;
        let mut k = 0;
        let mut out = Vec::with_capacity(self.corners.len() - s * holes.len());
        for (f, face) in self.corners.chunks_exact(s).enumerate() {
            if holes.get(k) == Some(&(f as u32)) {
                k += 1;
                continue;
            }
            out.extend_from_slice(face);
        }
        self.corners = out;
        self
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.corners.len() / self.sides.max(1)
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
    pub(crate) fn from_triangles_report(
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
        self.ct.v_table()
    }
    /// Axis-aligned bounds `(min, max)`; zero for an empty mesh.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        bounds_of(&self.positions)
    }
    /// Area-weighted vertex normals (see `normals::vertex_normals`).
    pub fn vertex_normals(&self) -> Vec<Vec3> {
        normals::vertex_normals(&self.ct, &self.positions)
    }
}

/// The most parts a scatter pass is cut into.
const SCATTER_PARTS: usize = 2;

/// How many parts a scatter pass over `n` items is cut into, at least
/// `least` items a part: a count of the size alone, never of the threads
/// that run it, so that the sums (each part's, then the parts added in
/// order) and with them the bits of every point are the same on any
/// number of threads. At most [`SCATTER_PARTS`]: one thread then adds a
/// second accumulator for the largest levels (a pass over points already
/// read), two run the parts side by side.
pub(crate) fn scatter_count(n: usize, least: usize) -> usize {
    n.div_ceil(least.max(1)).clamp(1, SCATTER_PARTS)
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
            assert_eq!(n(c) / 3, c / 3);
        }
    }
}
