//! Sharp features of a corner table: per-edge and per-vertex sharpness
//! (docs/sharp-features.md §1 and §4; OpenSubdiv `sdc/crease.h`, `vtr/refinement.cpp`).
//!
//! * An edge's sharpness `s` is 0 (smooth), `0 < s < 10` (semi-sharp: sharp
//!   rules for about `s` levels, then smooth) or `>= 10` ([`INFINITE`]).
//!   Border edges are always infinitely sharp and are not stored.
//! * A vertex's sharpness (a tagged corner) likewise.
//!
//! Both are **sparse**: most meshes have few sharp features, so the table
//! keeps a sorted list of the sharp corners (a sharp interior edge is listed
//! at both of its corners, by the corner opposite it) and of the sharp
//! vertices. A mesh without tags carries nothing, and the split and the
//! schemes pay nothing for it.
//!
//! Through a 1-to-4 split ([`Sharpness::split`], called by
//! [`crate::mesh::split`]) the two halves of a sharp edge get its subdivided
//! sharpness, the three new interior edges of every triangle are smooth, and
//! an old vertex's sharpness is subdivided too; the new vertices are smooth.
//! Subdivided sharpness (OpenSubdiv `Sdc::Crease`):
//!
//! ```text
//! uniform   s' = s - 1 (0 when s <= 1; infinite stays infinite)
//! Chaikin   at end vertex v of the half edge, with the other semi-sharp
//!           edges of v (sum S, count k including this one):
//!           s' = 3/4 s + 1/4 (S - s)/(k - 1) - 1   when k > 1, else s - 1;
//!           0 when s' <= 0 (SubdivideEdgeSharpnessAtVertex)
//! vertex    s' = s - 1 (0 when s <= 1; infinite stays infinite)
//! ```
//!
//! Split layout (docs/schemes.md §7.4): the half of the edge opposite corner `c`
//! that ends at `v(n(c))` is opposite corner `p(A(n(c)))` of the split, the
//! half that ends at `v(p(c))` is opposite `n(A(p(c)))`, with
//! `A(x) = 3 nt (x % 3 + 1) + 3 (x / 3)`.

use super::edges::EdgeTable;
use super::{BORDER, CornerTable, n, p};
use crate::MeshError;

/// Sharpness from which a feature is infinitely sharp (OpenSubdiv's
/// `SHARPNESS_INFINITE`).
pub const INFINITE: f32 = 10.0;

/// A sharpness value as every entry takes it (the readers' tags, Python's
/// crease arrays, the refiner's setters, the viewer's typed value): a
/// finite number at least 0, anything from [`INFINITE`] on stored as
/// infinite (the returned value).
///
/// # Errors
/// What is wrong, as a phrase for the caller to put after the element it
/// names: `sharpness NaN: it must be finite and at least 0` (so `crease 0
/// has sharpness NaN: ...`).
pub fn checked_sharpness(s: f64) -> Result<f32, String> {
    if s.is_finite() && s >= 0.0 {
        Ok(s.min(f64::from(INFINITE)) as f32)
    } else {
        Err(format!("sharpness {s}: it must be finite and at least 0"))
    }
}

/// How semi-sharp values decay from level to level (OpenSubdiv's
/// `Sdc::Options::CreasingMethod`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Creasing {
    /// `s - 1` per level (`CREASE_UNIFORM`).
    #[default]
    Uniform,
    /// Chaikin's curve rule on the sharpness along a crease (`CREASE_CHAIKIN`).
    Chaikin,
}

impl Creasing {
    /// Its name (`uniform`, `chaikin`), as [`std::str::FromStr`] reads it.
    pub fn name(self) -> &'static str {
        match self {
            Creasing::Uniform => "uniform",
            Creasing::Chaikin => "chaikin",
        }
    }
}

impl std::str::FromStr for Creasing {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "uniform" => Ok(Creasing::Uniform),
            "chaikin" => Ok(Creasing::Chaikin),
            _ => Err(format!("unknown creasing method '{s}' (expected uniform or chaikin)")),
        }
    }
}

/// Whether boundary vertices with a single face are corners (OpenSubdiv's
/// `Sdc::Options::VtxBoundaryInterpolation`; boundary edges are always
/// infinitely sharp).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum BoundaryInterpolation {
    /// Only the boundary edges are sharp (`VTX_BOUNDARY_EDGE_ONLY`): a
    /// boundary vertex with one face follows the boundary curve.
    #[default]
    EdgeOnly,
    /// Boundary vertices with one face are infinitely sharp corners too
    /// (`VTX_BOUNDARY_EDGE_AND_CORNER`).
    EdgeAndCorner,
    /// No boundary interpolation (`VTX_BOUNDARY_NONE`): the faces at a
    /// boundary vertex whose border edges are not all tagged infinitely
    /// sharp are holes, left out of the surface; their vertices still
    /// shape the interior.
    None,
}

impl BoundaryInterpolation {
    /// Its name (`edge`, `edge-and-corner`, `none`), as
    /// [`std::str::FromStr`] reads it.
    pub fn name(self) -> &'static str {
        match self {
            BoundaryInterpolation::EdgeOnly => "edge",
            BoundaryInterpolation::EdgeAndCorner => "edge-and-corner",
            BoundaryInterpolation::None => "none",
        }
    }
}

impl std::str::FromStr for BoundaryInterpolation {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "edge" | "edge-only" => Ok(BoundaryInterpolation::EdgeOnly),
            "edge-and-corner" | "corner" | "corners" => Ok(BoundaryInterpolation::EdgeAndCorner),
            "none" => Ok(BoundaryInterpolation::None),
            _ => Err(format!("unknown boundary interpolation '{s}' (expected edge, edge-and-corner or none)")),
        }
    }
}

/// A tagged sharp edge, by its two vertex ids.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CreaseTag {
    /// One end.
    pub v0: u32,
    /// The other end.
    pub v1: u32,
    /// Sharpness (0 smooth, `>= 10` infinite).
    pub sharpness: f32,
}

/// A tagged sharp vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CornerTag {
    /// The vertex.
    pub vertex: u32,
    /// Sharpness (`>= 10` infinite).
    pub sharpness: f32,
}

/// Sharp features as a file names them (OpenSubdiv's OBJ tags
/// `t crease 2/1/0 v0 v1 s` and `t corner 1/1/0 v s`, vertex ids 0-based).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tags {
    /// Sharp edges.
    pub creases: Vec<CreaseTag>,
    /// Sharp vertices.
    pub corners: Vec<CornerTag>,
}

impl Tags {
    /// Whether there is no tag at all.
    pub fn is_empty(&self) -> bool {
        self.creases.is_empty() && self.corners.is_empty()
    }
}

/// Sharpness of one level's edges and vertices (see the module docs).
///
/// Invariants (kept by every constructor): `corners` is sorted by corner
/// and holds both corners of every sharp interior edge with the same value;
/// `vertices` is sorted by vertex; every value is finite and `> 0`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sharpness {
    corners: Vec<(u32, f32)>,
    vertices: Vec<(u32, f32)>,
}

/// The error of a tag: `index` counts creases first, then corners.
fn tag_error(index: usize, msg: String) -> MeshError {
    MeshError::BadTag { index, msg }
}

/// Tag `index`'s sharpness `s`, checked ([`checked_sharpness`]).
fn check_value(index: usize, s: f32) -> Result<f32, MeshError> {
    checked_sharpness(f64::from(s)).map_err(|e| tag_error(index, e))
}

/// `s - 1` with OpenSubdiv's clamps (`Crease::decrementSharpness`).
#[inline]
pub(crate) fn decrement(s: f32) -> f32 {
    if s >= INFINITE {
        INFINITE
    } else if s > 1.0 {
        s - 1.0
    } else {
        0.0
    }
}

impl Sharpness {
    /// The sharpness the tags give to `ct`'s edges and vertices, or `None`
    /// when no tag is sharp. Sharpness above [`INFINITE`] is stored as
    /// infinite; a tag on a border edge is kept (borders are sharp anyway).
    ///
    /// # Errors
    /// [`MeshError::BadTag`] for a vertex out of range, an edge that does
    /// not exist, or a sharpness that is negative or NaN.
    pub(crate) fn from_tags<T: EdgeTable + ?Sized>(ct: &T, tags: &Tags) -> Result<Option<Sharpness>, MeshError> {
        let nv = ct.num_vertices() as u32;
        let mut corners = Vec::new();
        for (i, t) in tags.creases.iter().enumerate() {
            let s = check_value(i, t.sharpness)?;
            if t.v0 >= nv || t.v1 >= nv {
                return Err(tag_error(i, format!("edge ({}, {}) names a vertex >= {nv}", t.v0, t.v1)));
            }
            let Some(c) = ct.edge_between(t.v0, t.v1) else {
                return Err(tag_error(i, format!("there is no edge ({}, {})", t.v0, t.v1)));
            };
            // a zero is kept until the last tag of each edge has won, so
            // that it clears an earlier tag
            corners.push((c, s));
            let x = ct.twin_entry(c);
            if x != BORDER {
                corners.push((x, s));
            }
        }
        let mut vertices = Vec::new();
        for (j, t) in tags.corners.iter().enumerate() {
            let i = tags.creases.len() + j;
            let s = check_value(i, t.sharpness)?;
            if t.vertex >= nv {
                return Err(tag_error(i, format!("vertex {} does not exist (there are {nv})", t.vertex)));
            }
            vertices.push((t.vertex, s));
        }
        Ok(Self::from_lists(corners, vertices))
    }

    /// Sorts, removes duplicates (the last tag wins) and zeros.
    pub(crate) fn from_lists(mut corners: Vec<(u32, f32)>, mut vertices: Vec<(u32, f32)>) -> Option<Self> {
        for list in [&mut corners, &mut vertices] {
            // stable sort keeps tag order among equal ids: keep the last
            list.sort_by_key(|&(id, _)| id);
            let mut out: Vec<(u32, f32)> = Vec::with_capacity(list.len());
            for &(id, s) in list.iter() {
                match out.last_mut() {
                    Some(last) if last.0 == id => last.1 = s,
                    _ => out.push((id, s)),
                }
            }
            out.retain(|&(_, s)| s > 0.0);
            *list = out;
        }
        (!corners.is_empty() || !vertices.is_empty()).then_some(Sharpness { corners, vertices })
    }

    /// The tags that give this sharpness back (each sharp edge once, by its
    /// owner corner's vertices).
    pub fn to_tags<T: EdgeTable + ?Sized>(&self, ct: &T) -> Tags {
        let creases = self
            .corners
            .iter()
            .filter(|&&(c, _)| super::owns_edge(c, ct.twin_entry(c)))
            .map(|&(c, s)| {
                let (v0, v1) = ct.edge_ends(c);
                CreaseTag { v0, v1, sharpness: s }
            })
            .collect();
        let corners = self.vertices.iter().map(|&(v, s)| CornerTag { vertex: v, sharpness: s }).collect();
        Tags { creases, corners }
    }

    /// The sharp corners `(corner, sharpness of the edge opposite it)`,
    /// sorted by corner (border corners only where a tag named them).
    pub fn sharp_corners(&self) -> &[(u32, f32)] {
        &self.corners
    }

    /// The sharp vertices `(vertex, sharpness)`, sorted by vertex.
    pub fn sharp_vertices(&self) -> &[(u32, f32)] {
        &self.vertices
    }

    /// Stored sharpness of the edge opposite corner `c` (0 when untagged;
    /// a border edge is infinitely sharp whatever is stored, see
    /// [`CornerTable::edge_sharpness`]).
    pub fn corner(&self, c: u32) -> f32 {
        self.corners.binary_search_by_key(&c, |&(x, _)| x).map_or(0.0, |i| self.corners[i].1)
    }

    /// Sharpness of vertex `v` (0 when untagged).
    pub fn vertex(&self, v: u32) -> f32 {
        self.vertices.binary_search_by_key(&v, |&(x, _)| x).map_or(0.0, |i| self.vertices[i].1)
    }

    /// Adds infinitely sharp vertices (OpenSubdiv's `EDGE_AND_CORNER`
    /// boundary interpolation sharpens every boundary vertex with one face).
    pub(crate) fn with_corners(this: Option<Sharpness>, corners: &[u32]) -> Option<Sharpness> {
        let (c, mut v) = this.map_or((Vec::new(), Vec::new()), |s| (s.corners, s.vertices));
        v.extend(corners.iter().map(|&x| (x, INFINITE)));
        Self::from_lists(c, v)
    }

    /// Adds sharp edges `(corner, sharpness)` (either corner of an edge; a
    /// later value replaces an earlier one for the same edge).
    pub(crate) fn with_edges<T: EdgeTable + ?Sized>(
        this: Option<Sharpness>,
        ct: &T,
        edges: &[(u32, f32)],
    ) -> Option<Sharpness> {
        let (mut c, v) = this.map_or((Vec::new(), Vec::new()), |s| (s.corners, s.vertices));
        for &(x, s) in edges {
            let s = s.min(INFINITE);
            c.push((x, s));
            let y = ct.twin_entry(x);
            if y != BORDER {
                c.push((y, s));
            }
        }
        Self::from_lists(c, v)
    }

    /// This sharpness under new corner and vertex ids (bijections, as
    /// [`CornerTable::relabelled`] makes them), sorted again.
    pub(crate) fn relabelled(&self, corner: impl Fn(u32) -> u32, vertex: impl Fn(u32) -> u32) -> Sharpness {
        let mut corners: Vec<(u32, f32)> = self.corners.iter().map(|&(c, s)| (corner(c), s)).collect();
        let mut vertices: Vec<(u32, f32)> = self.vertices.iter().map(|&(v, s)| (vertex(v), s)).collect();
        corners.sort_unstable_by_key(|&(c, _)| c);
        vertices.sort_unstable_by_key(|&(v, _)| v);
        Sharpness { corners, vertices }
    }

    /// The sharpness after the 1-to-4 split of `old` (whose sharpness this
    /// is), decaying by `creasing`, or `None` when every value decayed to
    /// smooth. Linear in the number of sharp features (plus a sort of them).
    pub(crate) fn split(&self, old: &CornerTable, creasing: Creasing) -> Option<Sharpness> {
        let nt3 = 3 * old.num_triangles() as u32;
        // A(x): first corner of the corner triangle of v(x)
        let a = |x: u32| nt3 * (x % 3 + 1) + 3 * (x / 3);
        let decay = self.edge_decay(old, creasing);
        let sub = |s: f32, v: u32| decay.at(s, v);
        let mut corners = Vec::with_capacity(2 * self.corners.len());
        for &(c, s) in &self.corners {
            let (cn, cp) = (n(c), p(c));
            // the half ending at v(n(c)) and the half ending at v(p(c))
            corners.push((p(a(cn)), sub(s, old.vtx(cn))));
            corners.push((n(a(cp)), sub(s, old.vtx(cp))));
        }
        let vertices = self.vertices.iter().map(|&(v, s)| (v, decrement(s))).collect();
        Self::from_lists(corners, vertices)
    }

    /// How the edges of `ct` (whose sharpness this is) decay at each end
    /// vertex through the next split.
    pub(crate) fn edge_decay<'a, T: EdgeTable>(&self, ct: &'a T, creasing: Creasing) -> EdgeDecay<'a> {
        let chaikin = creasing == Creasing::Chaikin;
        let sums = if chaikin { self.semi_sharp_sums(ct) } else { Vec::new() };
        EdgeDecay { ct, chaikin, sums }
    }

    /// Per vertex with a semi-sharp edge: (sum, count) of its semi-sharp
    /// edges' sharpness, sorted by vertex.
    fn semi_sharp_sums<T: EdgeTable + ?Sized>(&self, ct: &T) -> Vec<(u32, f32, u32)> {
        let mut ends: Vec<(u32, f32)> = Vec::new();
        for &(c, s) in &self.corners {
            // a border edge is infinitely sharp whatever its tag says
            let twin = ct.twin_entry(c);
            if s < INFINITE && twin != BORDER && super::owns_edge(c, twin) {
                let (a, b) = ct.edge_ends(c);
                ends.push((a, s));
                ends.push((b, s));
            }
        }
        ends.sort_by_key(|&(v, _)| v);
        let mut sums: Vec<(u32, f32, u32)> = Vec::new();
        for (v, s) in ends {
            match sums.last_mut() {
                Some(last) if last.0 == v => {
                    last.1 += s;
                    last.2 += 1;
                }
                _ => sums.push((v, s, 1)),
            }
        }
        sums
    }
}

/// The subdivided sharpness of a level's edges at their end vertices (see
/// [`Sharpness::edge_decay`]).
pub(crate) struct EdgeDecay<'a> {
    ct: &'a dyn EdgeTable,
    chaikin: bool,
    sums: Vec<(u32, f32, u32)>,
}

impl EdgeDecay<'_> {
    /// The sharpness of the half, ending at `v`, of an edge of sharpness
    /// `s` after the split.
    #[inline]
    pub(crate) fn at(&self, s: f32, v: u32) -> f32 {
        if self.chaikin { chaikin_at(s, v, self.ct.valence(v), &self.sums) } else { decrement(s) }
    }
    /// Whether the decay is uniform (`s - 1`).
    pub(crate) fn is_uniform(&self) -> bool {
        !self.chaikin
    }
}

/// Chaikin's subdivided sharpness of a semi-sharp (or infinite) edge `s` at
/// its end vertex `v` of valence `valence` (OpenSubdiv
/// `Crease::SubdivideEdgeSharpnessAtVertex`).
fn chaikin_at(s: f32, v: u32, valence: u32, sums: &[(u32, f32, u32)]) -> f32 {
    if s >= INFINITE {
        return INFINITE;
    }
    if s <= 0.0 {
        return 0.0;
    }
    let mut t = s;
    if valence >= 2
        && let Ok(i) = sums.binary_search_by_key(&v, |&(x, _, _)| x)
    {
        let (_, sum, count) = sums[i];
        if count > 1 {
            t = 0.75 * s + 0.25 * (sum - s) / (count - 1) as f32;
        }
    }
    t -= 1.0;
    if t > 0.0 { t } else { 0.0 }
}

impl CornerTable {
    /// This table with every interior edge whose two faces' normals differ
    /// by more than `degrees` made infinitely sharp, besides the sharpness
    /// it has (Hoppe's feature test, Blender's "auto smooth" angle).
    /// Degenerate faces (no normal) make no edge sharp.
    pub fn with_angle_creases(self, positions: &[glam::Vec3], degrees: f32) -> CornerTable {
        let fnorm = super::normals::face_normals(&self, positions);
        let cos = degrees.to_radians().cos();
        let sharp: Vec<(u32, f32)> = self
            .edge_owners()
            .filter_map(|c| {
                let x = self.o(c)?;
                let (a, b) = (fnorm[(c / 3) as usize].try_normalize()?, fnorm[(x / 3) as usize].try_normalize()?);
                (a.dot(b) < cos).then_some((c, INFINITE))
            })
            .collect();
        if sharp.is_empty() {
            return self;
        }
        let s = Sharpness::with_edges(self.sharpness.as_deref().cloned(), &self, &sharp);
        self.with_sharpness(s)
    }

    /// The corner opposite the edge `(a, b)` (in either direction), by
    /// walking `a`'s fan; `None` when there is no such edge.
    pub(crate) fn corner_opposite(&self, a: u32, b: u32) -> Option<u32> {
        self.edge_between(a, b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tet() -> CornerTable {
        CornerTable::build(4, &[0, 2, 1, 0, 3, 2, 0, 1, 3, 1, 2, 3], None).unwrap().0
    }

    #[test]
    fn tags_find_both_corners_of_an_edge() {
        let ct = tet();
        let tags = Tags {
            creases: vec![CreaseTag { v0: 0, v1: 1, sharpness: 2.5 }],
            corners: vec![CornerTag { vertex: 3, sharpness: 12.0 }],
        };
        let s = Sharpness::from_tags(&ct, &tags).unwrap().unwrap();
        assert_eq!(s.sharp_corners().len(), 2);
        for &(c, v) in s.sharp_corners() {
            let e = [ct.vtx(n(c)), ct.vtx(p(c))];
            assert!(e == [0, 1] || e == [1, 0], "{e:?}");
            assert_eq!(v, 2.5);
        }
        assert_eq!(s.vertex(3), INFINITE);
        assert_eq!(s.to_tags(&ct).creases.len(), 1);
    }

    #[test]
    fn the_last_tag_of_an_element_wins_zero_included() {
        let ct = tet();
        let crease = |v0, v1, sharpness| CreaseTag { v0, v1, sharpness };
        let corner = |vertex, sharpness| CornerTag { vertex, sharpness };
        // a zero after a sharp tag clears it, whichever way the edge is named
        let tags =
            Tags { creases: vec![crease(0, 1, 3.0), crease(1, 0, 0.0)], corners: vec![corner(2, 5.0), corner(2, 0.0)] };
        assert_eq!(Sharpness::from_tags(&ct, &tags).unwrap(), None);
        // and a sharp tag after a zero sets it
        let tags = Tags { creases: vec![crease(0, 1, 0.0), crease(0, 1, 2.0)], corners: vec![] };
        let s = Sharpness::from_tags(&ct, &tags).unwrap().unwrap();
        assert!(s.sharp_corners().iter().all(|&(_, v)| v == 2.0) && s.sharp_corners().len() == 2);
    }

    #[test]
    fn bad_tags_are_refused_with_their_index() {
        let ct = tet();
        let bad = |creases: Vec<CreaseTag>, corners: Vec<CornerTag>| {
            Sharpness::from_tags(&ct, &Tags { creases, corners }).unwrap_err()
        };
        let e = bad(vec![CreaseTag { v0: 0, v1: 9, sharpness: 1.0 }], vec![]);
        assert!(matches!(e, MeshError::BadTag { index: 0, .. }), "{e}");
        let e = bad(vec![CreaseTag { v0: 0, v1: 1, sharpness: f32::NAN }], vec![]);
        assert!(matches!(e, MeshError::BadTag { index: 0, .. }), "{e}");
        let e = bad(vec![], vec![CornerTag { vertex: 4, sharpness: 1.0 }]);
        assert!(matches!(e, MeshError::BadTag { index: 0, .. }), "{e}");
        let e = bad(vec![CreaseTag { v0: 0, v1: 1, sharpness: 1.0 }], vec![CornerTag { vertex: 0, sharpness: -1.0 }]);
        assert!(matches!(e, MeshError::BadTag { index: 1, .. }), "{e}");
        // an open mesh: (1, 2) exists only as a border edge, (0, 2) not at all
        let (open, _, _) = CornerTable::build(4, &[0, 1, 3, 1, 2, 3], None).unwrap();
        assert!(open.corner_opposite(1, 2).is_some() && open.corner_opposite(2, 1).is_some());
        assert!(open.corner_opposite(0, 2).is_none());
    }

    #[test]
    fn decay_is_opensubdivs() {
        assert_eq!(decrement(2.5), 1.5);
        assert_eq!(decrement(1.0), 0.0);
        assert_eq!(decrement(0.3), 0.0);
        assert_eq!(decrement(INFINITE), INFINITE);
        // Chaikin at a vertex with edges 3 and 1: 3/4 3 + 1/4 1 - 1 = 3/2.
        let sums = [(7, 4.0, 2)];
        assert_eq!(chaikin_at(3.0, 7, 4, &sums), 1.5);
        // and edge 1 there: 3/4 1 + 1/4 3 - 1 = 1/2
        assert_eq!(chaikin_at(1.0, 7, 4, &sums), 0.5);
        // a lone semi-sharp edge decays uniformly
        assert_eq!(chaikin_at(1.0, 8, 4, &sums), 0.0);
    }
}
