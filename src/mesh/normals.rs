//! Vertex normals: the area-weighted average of the incident face normals
//! (docs/schemes.md §6.6), computed per triangle and gathered per vertex in parallel.

use super::CornerTable;
use glam::{Vec3, Vec3A};
use rayon::prelude::*;

/// Unnormalised face normals (cross product of two edges: length = 2 x area).
pub fn face_normals(ct: &CornerTable, pos: &[Vec3]) -> Vec<Vec3> {
    let mut out = vec![Vec3::ZERO; ct.num_triangles()];
    face_normals_into(ct, pos, &mut out);
    out
}

/// [`face_normals`] into a caller-owned buffer (no allocation per frame).
pub(crate) fn face_normals_into(ct: &CornerTable, pos: &[Vec3], out: &mut [Vec3]) {
    out.par_iter_mut().zip(ct.v_table().par_chunks_exact(3)).with_min_len(4096).for_each(|(f, tri)| {
        let a = pos[tri[0] as usize];
        *f = (pos[tri[1] as usize] - a).cross(pos[tri[2] as usize] - a);
    });
}

/// Area-weighted unit vertex normals: every face's normal (twice its area)
/// added to its three vertices, face after face, by each thread into its
/// own sums over a share of the faces, then the sums added and normalised.
/// One pass over the faces and one over the vertices, in parallel, with no
/// face-normal array and no list of the faces around each vertex (building
/// that list is a serial counting sort: at bunny level 3 it made this
/// function take 94-135 ms instead of 47-58). A vertex whose faces all have
/// zero area gets `Vec3::Z`. For a fixed topology evaluated many times,
/// keep a [`VertexRings`] (or a [`VertexFaces`]).
pub(crate) fn vertex_normals(ct: &CornerTable, pos: &[Vec3]) -> Vec<Vec3> {
    face_vertex_normals(ct.v_table(), pos)
}

/// [`vertex_normals`] of the triangles `tris` (a V table, three vertex
/// ids a triangle) over the vertices `pos`: the faces alone, no adjacency.
pub(crate) fn face_vertex_normals(tris: &[u32], pos: &[Vec3]) -> Vec<Vec3> {
    // parts of the size alone: the bits of every normal are the same on any
    // number of threads
    let threads = super::scatter_count(tris.len(), 3 << 16);
    let per = tris.len().div_ceil(3 * threads) * 3;
    let mut sums: Vec<Vec<Vec3>> = (0..threads).map(|_| crate::mem::zeroed(pos.len())).collect();
    sums.par_iter_mut().enumerate().for_each(|(k, acc)| {
        for tri in tris[(k * per).min(tris.len())..((k + 1) * per).min(tris.len())].chunks_exact(3) {
            let (a, b, c) = (tri[0] as usize, tri[1] as usize, tri[2] as usize);
            let (pa, pb, pc) = (pos[a], pos[b], pos[c]);
            let n = (pb - pa).cross(pc - pa);
            acc[a] += n;
            acc[b] += n;
            acc[c] += n;
        }
    });
    // `threads >= 1`: the first thread's sums, then the others' added
    let (first, rest) = sums.split_at(1);
    let mut out: Vec<Vec3> = crate::mem::zeroed(pos.len());
    out.par_iter_mut().zip(first[0].par_iter()).enumerate().with_min_len(8192).for_each(|(v, (o, s))| {
        let sum = rest.iter().fold(*s, |x, r| x + r[v]);
        *o = sum.try_normalize().map_or(Vec3::Z, Vec3::from);
    });
    out
}

/// The faces around every vertex as one compressed list (CSR): built once
/// for a fixed topology, it turns the per-frame normal gather into
/// sequential reads instead of a fan walk through the O table.
#[derive(Clone, Debug, Default)]
pub(crate) struct VertexFaces {
    /// `faces[offsets[v]..offsets[v + 1]]` are the triangles around `v`.
    offsets: Vec<u32>,
    faces: Vec<u32>,
}

impl VertexFaces {
    /// Counting sort of the corners by vertex (O(corners)).
    pub(crate) fn new(ct: &CornerTable) -> VertexFaces {
        let nv = ct.num_vertices();
        let mut offsets = vec![0u32; nv + 1];
        for &v in ct.v_table() {
            offsets[v as usize + 1] += 1;
        }
        for i in 0..nv {
            offsets[i + 1] += offsets[i];
        }
        let mut next = offsets.clone();
        let mut faces = vec![0u32; ct.v_table().len()];
        for (c, &v) in ct.v_table().iter().enumerate() {
            let slot = &mut next[v as usize];
            faces[*slot as usize] = (c / 3) as u32;
            *slot += 1;
        }
        VertexFaces { offsets, faces }
    }

    /// Area-weighted unit vertex normals from face normals `fnorm`.
    pub(crate) fn normals_into(&self, fnorm: &[Vec3], out: &mut [Vec3]) {
        out.par_iter_mut().enumerate().with_min_len(8192).for_each(|(v, nrm)| {
            let (a, b) = (self.offsets[v] as usize, self.offsets[v + 1] as usize);
            let s = self.faces[a..b].iter().fold(Vec3::ZERO, |s, &f| s + fnorm[f as usize]);
            *nrm = s.try_normalize().unwrap_or(Vec3::Z);
        });
    }
}

/// Vertices per parallel chunk of [`VertexRings`].
const RING_CHUNK: usize = 2048;

/// Most polygon entries a vertex may have in a [`VertexRings`] (a byte).
const MAX_RING: usize = 255;

/// Every vertex's one-ring as a polygon, packed for per-frame normals.
///
/// The area-weighted normal of `v` (the sum of its faces' cross products,
/// twice their areas) is twice the vector area of the polygon its fan
/// spans: for a closed fan the ring `r_0 .. r_k-1` itself (`v` drops out:
/// `sum (r_i - v) x (r_i+1 - v) = sum r_i x r_i+1`), for a boundary fan
/// `v, r_0 .. r_k`. Twice a polygon's vector area pairs the triangles of the
/// fan from its first point `p_0`: `a x b + b x c = b x (c - a)`, so
///
/// ```text
/// 2A = sum over i = 1, 3, 5, ..   (p_i+1 - p_0) x (p_i+2 - p_i)
///      (+ (p_m-2 - p_0) x (p_m-1 - p_0) when the m - 2 triangles are odd)
/// ```
///
/// two cross products for a valence-6 vertex instead of six, every
/// difference between points of one ring (as well conditioned as the face
/// normals' edges). One header byte per vertex holds the polygon's length
/// and one start offset per chunk lets chunks run in parallel.
#[derive(Clone, Debug, Default)]
pub(crate) struct VertexRings {
    /// Polygon length of every vertex.
    len: Vec<u8>,
    /// The polygons, vertex after vertex.
    ring: Vec<u32>,
    /// Offset into `ring` of vertex `k * RING_CHUNK`.
    chunk_start: Vec<u32>,
}

/// A table whose fans give every vertex's one-ring: triangles (the fan's
/// faces, `(v, a, b)`) or polygons (the fan's edges, `a` leaving `v` in a
/// face and `b` entering it: the ring of edge neighbours, which for a quad
/// mesh gives each vertex the normal of its four neighbours' quadrilateral
/// rather than of the triangles the quads are drawn with).
pub(crate) trait Fans: Sync {
    /// Vertices.
    fn num_vertices(&self) -> usize;
    /// The `(a, b)` of each face around `v` in fan order.
    fn fan_pairs(&self, v: u32, out: &mut Vec<(u32, u32)>);
}

impl Fans for CornerTable {
    fn num_vertices(&self) -> usize {
        CornerTable::num_vertices(self)
    }
    fn fan_pairs(&self, v: u32, out: &mut Vec<(u32, u32)>) {
        use super::{n, p};
        out.clear();
        out.extend(self.fan(v).map(|c| (self.v_table()[n(c) as usize], self.v_table()[p(c) as usize])));
    }
}

impl Fans for super::poly::PolyTable {
    fn num_vertices(&self) -> usize {
        super::poly::PolyTable::num_vertices(self)
    }
    fn fan_pairs(&self, v: u32, out: &mut Vec<(u32, u32)>) {
        out.clear();
        out.extend(self.fan(v).map(|c| (self.vtx(self.next(c)), self.vtx(self.prev(c)))));
    }
}

/// The chained one-ring of `v`, the first entry repeated when it closes,
/// or `None` when the fan's faces do not chain (impossible under the
/// table's invariants) or an id is out of range.
fn chained_ring<T: Fans + ?Sized>(ct: &T, v: u32, pairs: &mut Vec<(u32, u32)>, ring: &mut Vec<u32>) -> Option<()> {
    let nv = ct.num_vertices();
    ring.clear();
    ct.fan_pairs(v, pairs);
    for &(a, b) in pairs.iter() {
        if a as usize >= nv || b as usize >= nv || ring.last().is_some_and(|&l| l != a) {
            return None;
        }
        if ring.is_empty() {
            ring.push(a);
        }
        ring.push(b);
    }
    (ring.len() <= MAX_RING).then_some(())
}

/// The polygon of `v` (see [`VertexRings`]) from its chained ring.
pub(crate) fn fan_polygon(v: u32, ring: &mut Vec<u32>) {
    if ring.len() > 1 && ring.first() == ring.last() {
        ring.pop();
    } else if !ring.is_empty() {
        ring.insert(0, v);
    }
}

/// Every vertex's one-ring as a plain CSR list (`offsets`, `ids`; a closed
/// ring repeats its first neighbour at the end), the faces around `v` being
/// `(v, ids[k], ids[k+1])`: the layout the GPU's normal pass reads. `None`
/// as for [`VertexRings::new`].
pub(crate) fn ring_lists<T: Fans + ?Sized>(ct: &T) -> Option<(Vec<u32>, Vec<u32>)> {
    let nv = ct.num_vertices();
    let (mut offsets, mut ids, mut ring, mut pairs) = (Vec::with_capacity(nv + 1), Vec::new(), Vec::new(), Vec::new());
    offsets.push(0u32);
    for v in 0..nv {
        chained_ring(ct, v as u32, &mut pairs, &mut ring)?;
        ids.extend_from_slice(&ring);
        offsets.push(u32::try_from(ids.len()).ok()?);
    }
    Some((offsets, ids))
}

impl VertexRings {
    /// The polygons of every vertex of `ct`, or `None` when a vertex has
    /// more than 253 neighbours (then use [`VertexFaces`]).
    pub(crate) fn new<T: Fans + ?Sized>(ct: &T) -> Option<VertexRings> {
        let nv = ct.num_vertices();
        let parts: Vec<Option<(Vec<u8>, Vec<u32>)>> = (0..nv.div_ceil(RING_CHUNK))
            .into_par_iter()
            .map(|k| {
                let (mut len, mut ring, mut poly) = (Vec::with_capacity(RING_CHUNK), Vec::new(), Vec::new());
                let mut pairs = Vec::new();
                for v in k * RING_CHUNK..((k + 1) * RING_CHUNK).min(nv) {
                    chained_ring(ct, v as u32, &mut pairs, &mut poly)?;
                    fan_polygon(v as u32, &mut poly);
                    len.push(u8::try_from(poly.len()).ok()?);
                    ring.extend_from_slice(&poly);
                }
                Some((len, ring))
            })
            .collect();
        let mut out = VertexRings { len: Vec::with_capacity(nv), ring: Vec::new(), chunk_start: Vec::new() };
        for part in parts {
            let (len, ring) = part?;
            out.chunk_start.push(u32::try_from(out.ring.len()).ok()?);
            out.len.extend_from_slice(&len);
            out.ring.extend_from_slice(&ring);
        }
        u32::try_from(out.ring.len()).ok()?;
        Some(out)
    }

    /// Area-weighted unit vertex normals of positions `pos` into `out`
    /// (a vertex without faces of non-zero area gets `Vec3::Z`).
    ///
    /// # Panics
    /// If `pos` or `out` does not have one entry per vertex of the table the
    /// rings were built from (a caller bug, not input data).
    pub(crate) fn normals_into(&self, pos: &[Vec3], out: &mut [Vec3]) {
        assert!(pos.len() == self.len.len() && out.len() == self.len.len(), "one position and normal per vertex");
        out.par_chunks_mut(RING_CHUNK)
            .zip(self.len.par_chunks(RING_CHUNK))
            .zip(&self.chunk_start)
            .for_each(|((out, len), &start)| ring_normals(&self.ring, start as usize, len, pos, out));
    }
}

crate::cpu::multiversion! {
    /// The normals of one chunk of vertices: polygon lengths `len`, their
    /// polygons from `ring[start..]`.
    fn ring_normals(ring: &[u32], start: usize, len: &[u8], pos: &[Vec3], out: &mut [Vec3]) {
        let mut o = start;
        for (nrm, &m) in out.iter_mut().zip(len) {
            let m = m as usize;
            let poly = &ring[o..o + m];
            o += m;
            *nrm = polygon_area2(pos, poly).try_normalize().map_or(Vec3::Z, Vec3::from);
        }
    }
}

/// Twice the vector area of the polygon `poly` of positions (see
/// [`VertexRings`]); zero below three points.
#[inline(always)]
fn polygon_area2(pos: &[Vec3], poly: &[u32]) -> Vec3A {
    // SAFETY: every polygon entry is a vertex id of the table the rings were
    // built from (`new` keeps only ids checked against its vertex count, and
    // the fields are private), and `pos.len()` is that count, asserted by
    // `normals_into`, the only caller of `ring_normals`.
    area2_of(|j: u32| load(pos, j as usize), poly)
}

/// The unit normal of the polygon `poly` of a vertex's ring (see
/// [`VertexRings`]; [`fan_polygon`] makes it from the chained ring), as
/// [`VertexRings::normals_into`] makes it bit for bit (`Vec3::Z` without
/// area), its entries checked: for any caller holding its own rings.
///
/// # Panics
/// If an entry of `poly` is not below `pos.len()` (a caller bug).
#[inline(always)]
pub(crate) fn polygon_normal(pos: &[Vec3], poly: &[u32]) -> Vec3 {
    assert!(poly.iter().all(|&j| (j as usize) < pos.len()), "a ring of these points");
    // SAFETY: every entry of `poly` is below `pos.len()` (asserted above),
    // all that `load` needs.
    area2_of(|j: u32| load(pos, j as usize), poly).try_normalize().map_or(Vec3::Z, Vec3::from)
}

/// [`polygon_area2`] with the points loaded by `at`.
#[inline(always)]
fn area2_of(at: impl Fn(u32) -> Vec3A, poly: &[u32]) -> Vec3A {
    if let Some(&[a, b, c, d, e, f]) = poly.first_chunk::<6>().filter(|_| poly.len() == 6) {
        // the closed valence-6 ring, almost every vertex of a refined mesh:
        // the loop below, unrolled (the same sums in the same order)
        let (p0, p3) = (at(a), at(d));
        let mut s = Vec3A::ZERO;
        s += (at(c) - p0).cross(p3 - at(b));
        s += (at(e) - p0).cross(at(f) - p3);
        return s;
    }
    let m = poly.len();
    if m < 3 {
        return Vec3A::ZERO;
    }
    let p0 = at(poly[0]);
    let mut s = Vec3A::ZERO;
    let mut i = 1;
    while i + 2 < m {
        let (a, b, c) = (at(poly[i]), at(poly[i + 1]), at(poly[i + 2]));
        s += (b - p0).cross(c - a);
        i += 2;
    }
    if i + 2 == m {
        // one triangle left: (p_m-2, p_m-1)
        s += (at(poly[m - 2]) - p0).cross(at(poly[m - 1]) - p0);
    }
    s
}

/// `pos[j]` in a register, for `j < pos.len()` (see `polygon_area2`'s
/// SAFETY): one 16-byte load where the next point follows (its x lands in
/// the lane Vec3A ignores), else the three coordinates one by one.
#[inline(always)]
fn load(pos: &[Vec3], j: usize) -> Vec3A {
    #[cfg(target_arch = "x86_64")]
    if j + 1 < pos.len() {
        // SAFETY: points j and j + 1 are in the slice, so the 16 bytes from
        // point j (12 of its own, 4 of the next: `Vec3` is three f32 with no
        // padding) are initialised memory of the slice; `_mm_loadu_ps` needs
        // no alignment, and SSE is part of every x86_64 target.
        return Vec3A::from(unsafe { std::arch::x86_64::_mm_loadu_ps(pos.as_ptr().add(j).cast::<f32>()) });
    }
    // SAFETY: as above, j < pos.len()
    Vec3A::from(unsafe { *pos.get_unchecked(j) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ring_normals_equal_face_normal_gathers() {
        // open and closed fans, valences 3 to 6; a torus-free set of bundled shapes
        for m in [crate::mesh::shapes::icosphere(3), crate::mesh::shapes::grid(5), crate::mesh::shapes::icosphere(0)] {
            let want = vertex_normals(&m.ct, &m.positions);
            let rings = VertexRings::new(&m.ct).expect("small valences pack");
            let mut got = vec![Vec3::ZERO; want.len()];
            rings.normals_into(&m.positions, &mut got);
            for (v, (g, w)) in got.iter().zip(&want).enumerate() {
                assert!((*g - *w).length() < 1e-5, "vertex {v}: {g} vs {w}");
            }
        }
    }

    #[test]
    fn gathered_normals_equal_fan_walks() {
        // the reference walks each vertex's fan through O; icosphere(6) has
        // enough faces for vertex_normals to split them between threads
        for m in [crate::mesh::shapes::icosphere(3), crate::mesh::shapes::grid(5), crate::mesh::shapes::icosphere(6)] {
            let fnorm = face_normals(&m.ct, &m.positions);
            let got = vertex_normals(&m.ct, &m.positions);
            for (v, n) in got.iter().enumerate() {
                let s: Vec3 = m.ct.fan(v as u32).map(|c| fnorm[c as usize / 3]).sum();
                assert!((*n - s.normalize()).length() < 1e-5, "vertex {v}: {n} vs {s}");
            }
        }
    }
}
