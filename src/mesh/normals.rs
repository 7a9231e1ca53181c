//! Vertex normals: the area-weighted average of the incident face normals
//! (schemes.md 4.4), computed per triangle and gathered per vertex in parallel.

use super::CornerTable;
use glam::Vec3;
use rayon::prelude::*;

/// Unnormalised face normals (cross product of two edges: length = 2 x area).
pub fn face_normals(ct: &CornerTable, pos: &[Vec3]) -> Vec<Vec3> {
    let mut out = vec![Vec3::ZERO; ct.num_triangles()];
    face_normals_into(ct, pos, &mut out);
    out
}

/// [`face_normals`] into a caller-owned buffer (no allocation per frame).
pub fn face_normals_into(ct: &CornerTable, pos: &[Vec3], out: &mut [Vec3]) {
    out.par_iter_mut().zip(ct.v_table().par_chunks_exact(3)).with_min_len(4096).for_each(|(f, tri)| {
        let a = pos[tri[0] as usize];
        *f = (pos[tri[1] as usize] - a).cross(pos[tri[2] as usize] - a);
    });
}

/// Area-weighted unit vertex normals: face normals gathered per vertex
/// through a [`VertexFaces`] list (sequential reads, faster than walking each
/// fan through O). A vertex whose faces all have zero area gets `Vec3::Z`.
/// For a fixed topology evaluated many times, keep the [`VertexFaces`].
pub fn vertex_normals(ct: &CornerTable, pos: &[Vec3]) -> Vec<Vec3> {
    let mut out = vec![Vec3::ZERO; ct.num_vertices()];
    VertexFaces::new(ct).normals_into(&face_normals(ct, pos), &mut out);
    out
}

/// The faces around every vertex as one compressed list (CSR): built once
/// for a fixed topology, it turns the per-frame normal gather into
/// sequential reads instead of a fan walk through the O table.
#[derive(Clone, Debug, Default)]
pub struct VertexFaces {
    /// `faces[offsets[v]..offsets[v + 1]]` are the triangles around `v`.
    offsets: Vec<u32>,
    faces: Vec<u32>,
}

impl VertexFaces {
    /// Counting sort of the corners by vertex (O(corners)).
    pub fn new(ct: &CornerTable) -> VertexFaces {
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
    pub fn normals_into(&self, fnorm: &[Vec3], out: &mut [Vec3]) {
        out.par_iter_mut().enumerate().with_min_len(8192).for_each(|(v, nrm)| {
            let (a, b) = (self.offsets[v] as usize, self.offsets[v + 1] as usize);
            let s = self.faces[a..b].iter().fold(Vec3::ZERO, |s, &f| s + fnorm[f as usize]);
            *nrm = s.try_normalize().unwrap_or(Vec3::Z);
        });
    }
}

/// Vertices evaluated together, one per lane (two SSE registers).
const LANES: usize = 8;

/// Groups of [`LANES`] vertices per parallel chunk.
const GROUPS_PER_CHUNK: usize = 256;

/// Most ring entries a vertex may have in a [`VertexRings`].
const MAX_RING: usize = 255;

/// Every vertex's one-ring in fan order, packed for per-frame normals.
///
/// The faces around `v` are `(v, r_i, r_i+1)`, so the sum of their
/// (unnormalised, area-weighted) normals is `sum (r_i - v) x (r_i+1 - v)`:
/// normals straight from the positions, with no face-normal array written
/// and gathered back. A boundary fan stores its `k + 1` neighbours, a closed
/// fan its `k` and the first again. Vertices go in groups of [`LANES`]
/// consecutive ones, their rings interleaved entry by entry and padded to
/// the group's longest by repeating a ring's last entry (the pair then
/// adds `d x d = 0` exactly): the sums of a group are computed lane by lane
/// in arrays the compiler vectorises, one cross product per ring entry.
#[derive(Clone, Debug, Default)]
pub struct VertexRings {
    vertices: usize,
    /// Entries per lane of every group (at least 1).
    len: Vec<u8>,
    /// Group after group: `len * LANES` vertex ids, entry-major.
    ring: Vec<u32>,
    /// Offset into `ring` of group `k * GROUPS_PER_CHUNK`.
    chunk_start: Vec<u32>,
}

/// The chained one-ring of `v`, the first entry repeated when it closes,
/// or `None` when the fan's faces do not chain (impossible under the
/// table's invariants) or an id is out of range.
fn chained_ring(ct: &CornerTable, v: u32, ring: &mut Vec<u32>) -> Option<()> {
    use super::{n, p};
    let nv = ct.num_vertices();
    let v_of = |c: u32| ct.v_table()[c as usize];
    ring.clear();
    for c in ct.fan(v) {
        let (a, b) = (v_of(n(c)), v_of(p(c)));
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

/// Every vertex's one-ring as a plain CSR list (`offsets`, `ids`; a closed
/// ring repeats its first neighbour at the end), the faces around `v` being
/// `(v, ids[k], ids[k+1])`: the layout the GPU's normal pass reads. `None`
/// as for [`VertexRings::new`].
pub fn ring_lists(ct: &CornerTable) -> Option<(Vec<u32>, Vec<u32>)> {
    let nv = ct.num_vertices();
    let (mut offsets, mut ids, mut ring) = (Vec::with_capacity(nv + 1), Vec::new(), Vec::new());
    offsets.push(0u32);
    for v in 0..nv {
        chained_ring(ct, v as u32, &mut ring)?;
        ids.extend_from_slice(&ring);
        offsets.push(u32::try_from(ids.len()).ok()?);
    }
    Some((offsets, ids))
}

impl VertexRings {
    /// The rings of every vertex of `ct`, or `None` when a vertex has more
    /// than 254 neighbours (then use [`VertexFaces`]).
    pub fn new(ct: &CornerTable) -> Option<VertexRings> {
        let nv = ct.num_vertices();
        let groups = nv.div_ceil(LANES);
        let parts: Vec<Option<(Vec<u8>, Vec<u32>)>> = (0..groups.div_ceil(GROUPS_PER_CHUNK))
            .into_par_iter()
            .map(|k| {
                let (mut len, mut ring) = (Vec::with_capacity(GROUPS_PER_CHUNK), Vec::new());
                let mut lanes: [Vec<u32>; LANES] = Default::default();
                for g in k * GROUPS_PER_CHUNK..((k + 1) * GROUPS_PER_CHUNK).min(groups) {
                    for (l, lane) in lanes.iter_mut().enumerate() {
                        let v = g * LANES + l;
                        if v < nv {
                            chained_ring(ct, v as u32, lane)?;
                        } else {
                            lane.clear();
                        }
                        if lane.is_empty() {
                            // no faces (or past the end): d = 0, normal Z
                            lane.push(v.min(nv - 1) as u32);
                        }
                    }
                    let m = lanes.iter().map(Vec::len).max().unwrap_or(1);
                    len.push(m as u8);
                    for e in 0..m {
                        ring.extend(lanes.iter().map(|lane| lane[e.min(lane.len() - 1)]));
                    }
                }
                Some((len, ring))
            })
            .collect();
        let mut out =
            VertexRings { vertices: nv, len: Vec::with_capacity(groups), ring: Vec::new(), chunk_start: Vec::new() };
        for part in parts {
            let (len, ring) = part?;
            out.chunk_start.push(out.ring.len() as u32);
            out.len.extend_from_slice(&len);
            out.ring.extend_from_slice(&ring);
        }
        Some(out)
    }

    /// Area-weighted unit vertex normals of positions `pos` into `out`
    /// (a vertex without faces of non-zero area gets `Vec3::Z`).
    ///
    /// # Panics
    /// If `pos` or `out` does not have one entry per vertex of the table the
    /// rings were built from (a caller bug, not input data).
    pub fn normals_into(&self, pos: &[Vec3], out: &mut [Vec3]) {
        assert!(pos.len() == self.vertices && out.len() == self.vertices, "one position and normal per vertex");
        out.par_chunks_mut(GROUPS_PER_CHUNK * LANES)
            .zip(self.len.par_chunks(GROUPS_PER_CHUNK))
            .zip(&self.chunk_start)
            .enumerate()
            .for_each(|(k, ((out, len), &start))| {
                let mut o = start as usize;
                for (g, (out, &m)) in out.chunks_mut(LANES).zip(len).enumerate() {
                    let m = m as usize;
                    let ring = &self.ring[o..o + m * LANES];
                    prefetch(pos, self.ring.get(o + PREFETCH..o + PREFETCH + m * LANES).unwrap_or(&[]));
                    o += m * LANES;
                    let base = (k * GROUPS_PER_CHUNK + g) * LANES;
                    let sum = group_normals(pos, base, ring);
                    for (l, nrm) in out.iter_mut().enumerate() {
                        let s = Vec3::new(sum[0][l], sum[1][l], sum[2][l]);
                        *nrm = s.try_normalize().unwrap_or(Vec3::Z);
                    }
                }
            });
    }
}

/// Ring entries ahead of the current group whose positions are prefetched.
const PREFETCH: usize = 4 * 7 * LANES;

/// Asks the cache for the positions of vertices `ids` (the rings a few
/// groups ahead): the gathers are scattered over the whole position array,
/// and loading them early hides the latency of the outer caches.
#[inline(always)]
fn prefetch(pos: &[Vec3], ids: &[u32]) {
    #[cfg(target_arch = "x86_64")]
    for &j in ids {
        if let Some(p) = pos.get(j as usize) {
            // SAFETY: SSE is part of every x86_64 target; a prefetch is a
            // hint that reads nothing architecturally and cannot fault, and
            // the pointer is to an element of `pos` anyway.
            unsafe {
                std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>((p as *const Vec3).cast());
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (pos, ids);
}

/// The unnormalised normals of the [`LANES`] vertices from `base` (x, y, z
/// lanes), from their interleaved padded rings.
#[inline(always)]
fn group_normals(pos: &[Vec3], base: usize, ring: &[u32]) -> [[f32; LANES]; 3] {
    // SAFETY (both closures): every ring entry is a vertex id of the table the
    // rings were built from (`new` checks each against the vertex count and
    // pads with ids below it; the fields are private), and `pos.len()` is
    // that count, asserted by the only caller.
    let get = |j: u32| unsafe { *pos.get_unchecked(j as usize) };
    let v: [Vec3; LANES] = std::array::from_fn(|l| pos[(base + l).min(pos.len() - 1)]);
    let (mut px, mut py, mut pz) = ([0f32; LANES], [0f32; LANES], [0f32; LANES]);
    for l in 0..LANES {
        let d = get(ring[l]) - v[l];
        (px[l], py[l], pz[l]) = (d.x, d.y, d.z);
    }
    let (mut sx, mut sy, mut sz) = ([0f32; LANES], [0f32; LANES], [0f32; LANES]);
    for entry in ring.chunks_exact(LANES).skip(1) {
        let (mut dx, mut dy, mut dz) = ([0f32; LANES], [0f32; LANES], [0f32; LANES]);
        for l in 0..LANES {
            let d = get(entry[l]) - v[l];
            (dx[l], dy[l], dz[l]) = (d.x, d.y, d.z);
        }
        for l in 0..LANES {
            // (px, py, pz) x (dx, dy, dz), as glam's Vec3::cross
            sx[l] += py[l] * dz[l] - dy[l] * pz[l];
            sy[l] += pz[l] * dx[l] - dz[l] * px[l];
            sz[l] += px[l] * dy[l] - dx[l] * py[l];
        }
        (px, py, pz) = (dx, dy, dz);
    }
    [sx, sy, sz]
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
        // the reference walks each vertex's fan through O
        for m in [crate::mesh::shapes::icosphere(3), crate::mesh::shapes::grid(5)] {
            let fnorm = face_normals(&m.ct, &m.positions);
            let got = vertex_normals(&m.ct, &m.positions);
            for (v, n) in got.iter().enumerate() {
                let s: Vec3 = m.ct.fan(v as u32).map(|c| fnorm[c as usize / 3]).sum();
                assert!((*n - s.normalize()).length() < 1e-5, "vertex {v}: {n} vs {s}");
            }
        }
    }
}
