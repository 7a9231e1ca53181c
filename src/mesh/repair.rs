//! Repairing a triangle soup into a mesh that [`CornerTable::build`](super::CornerTable::build) accepts:
//! the documented alternative to refusing non-manifold input (docs/design.md §3).
//!
//! [`repair`] takes the raw positions and triangles (indices already checked by
//! the caller or reported as [`MeshError::IndexOutOfRange`]) and runs, in order:
//!
//! 1. **Degenerate faces** are dropped (`drop_degenerate_faces`): a face that uses
//!    one vertex twice, or two of whose corners have bit-identical positions (zero
//!    area by construction; collinear faces with distinct positions are kept, they
//!    are topologically valid).
//! 2. **Duplicate faces** are dropped (`drop_duplicate_faces`): faces with the same
//!    vertex set, in any rotation or orientation; the first one is kept.
//! 3. **Edge classification** (`classify_edges`). Every corner owns the edge
//!    opposite it. Corners are sorted by undirected edge: an edge with one face is
//!    a border, with two faces it is *glued* (a candidate for O), with three or
//!    more it is a **non-manifold edge and cut**: none of its faces is glued across
//!    it, so each of them ends up with a border edge there.
//! 4. **Orientation** (`orient_faces`). A breadth-first search over faces across
//!    glued edges gives every face a flip bit so that both faces of a glued edge
//!    run along it in opposite directions. Where the search meets a face again with
//!    the other bit (a Möbius-like, non-orientable component) that edge is cut
//!    instead. In each component the smaller set of faces is flipped (`(a, b, c)`
//!    becomes `(a, c, b)`), so a mostly-consistent mesh keeps its own orientation.
//! 5. **Vertex fans** (`number_fans`). Union-find over corners: the two corners of
//!    each vertex of a glued edge are joined. Each class is one fan, and every fan
//!    of a vertex gets its own copy of the vertex, which separates bowtie vertices
//!    and the faces of cut edges. Copies are numbered vertex by vertex, fans in
//!    order of their first corner, so an already valid mesh keeps its ids.
//! 6. **Re-gluing** (`reglue_or_cut`; `separate_fans` repeats 5 and 6). Two faces
//!    of a cut edge can still share both its vertex copies: the fan of each
//!    endpoint goes around and reaches the other face (two tetrahedra sharing an
//!    edge: each one's two faces on it). They are glued again, which merges no fans
//!    and changes no ids, so each tetrahedron comes out closed. Such a pair is
//!    always oppositely oriented: the glued edges around one vertex are all
//!    consistent after step 4, and faces around a vertex cannot be inconsistent
//!    across exactly one edge. Three faces cannot share both copies either (a fan
//!    has two ends). The code still handles the impossible case defensively, by
//!    cutting one more edge at the shared endpoint and redoing step 5 (cuts only
//!    split fans, so that would end, at worst with separate triangles).
//! 7. **Unreferenced vertices** (used by no remaining face) are dropped
//!    (`count_copies` reports them, with the split ones).
//!
//! The result is then built by [`Mesh::from_triangles`], which validates it
//! once more. Everything is O(n log n) (two sorts by edge key) and
//! allocation-per-element free.
//!
//! The [`RepairReport`] counts each kind of change and keeps the first
//! [`EXAMPLES`] ids of each (input numbering, 0-based; its `Display` shifts
//! vertex ids by [`RepairReport::id_base`], 1 for OBJ files, as the error
//! messages do, and shows at most
//! [`EXAMPLES`] of each). [`analyze`] keeps every id, for `subdiv info`.

use super::{BORDER, Mesh, n, p};
use crate::MeshError;
use glam::Vec3;
use std::fmt;

/// How many example ids a [`RepairReport`] keeps per kind of change.
pub(crate) const EXAMPLES: usize = 10;

/// A count and its first few examples.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tally<T> {
    /// How many were found.
    pub count: usize,
    /// The first ones found (at most the cap given to the analysis).
    pub examples: Vec<T>,
    cap: usize,
}

impl<T> Default for Tally<T> {
    fn default() -> Self {
        Tally { count: 0, examples: Vec::new(), cap: EXAMPLES }
    }
}

impl<T> Tally<T> {
    fn with_cap(cap: usize) -> Self {
        Tally { count: 0, examples: Vec::new(), cap }
    }
    fn push(&mut self, x: T) {
        self.count += 1;
        if self.examples.len() < self.cap {
            self.examples.push(x);
        }
    }
    /// Nothing found?
    pub(crate) fn is_empty(&self) -> bool {
        self.count == 0
    }
}

/// What [`repair`] changed. Face ids are indices into the input triangle list
/// and vertex ids indices into the input positions, both 0-based.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RepairReport {
    /// Added to every vertex id when the report is displayed (1 for OBJ
    /// files, whose vertices are numbered from 1). Face ids are shown 0-based,
    /// as in [`MeshError`] messages.
    pub id_base: u32,
    /// Triangles in the input.
    pub faces_in: usize,
    /// Vertices in the input.
    pub vertices_in: usize,
    /// Triangles in the result.
    pub faces_out: usize,
    /// Vertices in the result.
    pub vertices_out: usize,
    /// Faces dropped for using a vertex twice or having two identical corner positions.
    pub degenerate_faces: Tally<usize>,
    /// Faces dropped because an earlier face has the same vertex set.
    pub duplicate_faces: Tally<usize>,
    /// Edges shared by three or more faces, cut (as input vertex pairs, smaller id first).
    pub non_manifold_edges: Tally<[u32; 2]>,
    /// Glued edges cut to make a component orientable, or to separate faces of
    /// a cut edge that still shared both its vertices.
    pub extra_cuts: Tally<[u32; 2]>,
    /// Faces whose orientation was reversed.
    pub flipped_faces: Tally<usize>,
    /// Vertices of the input whose faces form two or more separate fans even
    /// with every shared edge joined (bowties).
    pub non_manifold_vertices: Tally<u32>,
    /// Input vertices that were given more than one copy.
    pub split_vertices: Tally<u32>,
    /// Vertex copies added by splitting.
    pub added_vertices: usize,
    /// Input vertices that no remaining face uses; dropped.
    pub unreferenced_vertices: Tally<u32>,
}

impl RepairReport {
    /// Did the repair change the connectivity (anything besides dropping
    /// unreferenced vertices)?
    pub fn changed_faces(&self) -> bool {
        !(self.degenerate_faces.is_empty()
            && self.duplicate_faces.is_empty()
            && self.non_manifold_edges.is_empty()
            && self.extra_cuts.is_empty()
            && self.flipped_faces.is_empty()
            && self.split_vertices.is_empty())
    }
    /// Did the repair change anything at all?
    pub fn is_empty(&self) -> bool {
        !self.changed_faces() && self.unreferenced_vertices.is_empty()
    }
}

fn list<T>(t: &Tally<T>, f: impl Fn(&T) -> String) -> String {
    if t.examples.is_empty() {
        return String::new();
    }
    let shown: Vec<String> = t.examples.iter().take(EXAMPLES).map(f).collect();
    let more = if t.count > shown.len() { ", ..." } else { "" };
    format!(" ({}{more})", shown.join(", "))
}

impl fmt::Display for RepairReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = self.id_base;
        let base = if b == 1 { "vertex ids 1-based as in the file" } else { "vertex ids 0-based" };
        writeln!(
            f,
            "repair: {} -> {} faces, {} -> {} vertices ({base}; faces are 0-based triangle indices)",
            self.faces_in, self.faces_out, self.vertices_in, self.vertices_out
        )?;
        if self.is_empty() {
            return writeln!(f, "  nothing to repair");
        }
        // faces as in MeshError: 0-based triangle indices (OBJ polygons are
        // split into triangles, so the file has no triangle numbering of its own)
        let face = |x: &usize| x.to_string();
        let vert = |x: &u32| (x + b).to_string();
        let edge = |e: &[u32; 2]| format!("{}-{}", e[0] + b, e[1] + b);
        writeln!(
            f,
            "  degenerate faces dropped:       {}{}",
            self.degenerate_faces.count,
            list(&self.degenerate_faces, face)
        )?;
        writeln!(
            f,
            "  duplicate faces dropped:        {}{}",
            self.duplicate_faces.count,
            list(&self.duplicate_faces, face)
        )?;
        writeln!(
            f,
            "  non-manifold edges cut:         {}{}",
            self.non_manifold_edges.count,
            list(&self.non_manifold_edges, edge)
        )?;
        writeln!(f, "  edges cut to orient/separate:   {}{}", self.extra_cuts.count, list(&self.extra_cuts, edge))?;
        writeln!(
            f,
            "  faces flipped:                  {}{}",
            self.flipped_faces.count,
            list(&self.flipped_faces, face)
        )?;
        writeln!(
            f,
            "  non-manifold (bowtie) vertices: {}{}",
            self.non_manifold_vertices.count,
            list(&self.non_manifold_vertices, vert)
        )?;
        writeln!(
            f,
            "  vertices split:                 {}{}, {} copies added",
            self.split_vertices.count,
            list(&self.split_vertices, vert),
            self.added_vertices
        )?;
        writeln!(
            f,
            "  unreferenced vertices dropped:  {}{}",
            self.unreferenced_vertices.count,
            list(&self.unreferenced_vertices, vert)
        )
    }
}

/// Union-find over corner ids with path halving.
struct Dsu(Vec<u32>);

impl Dsu {
    fn new(n: usize) -> Self {
        Dsu((0..n as u32).collect())
    }
    fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let g = self.0[self.0[x as usize] as usize];
            self.0[x as usize] = g;
            x = g;
        }
        x
    }
    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            // the smaller root wins: classes are then named by their first corner
            let (lo, hi) = (ra.min(rb), ra.max(rb));
            self.0[hi as usize] = lo;
        }
    }
}

#[inline]
fn edge_key(a: u32, b: u32) -> u64 {
    (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
}

/// Corners sorted by the undirected edge opposite them, as `(key, corner)`.
fn corners_by_edge(v: &[u32]) -> Vec<(u64, u32)> {
    let mut e: Vec<(u64, u32)> =
        (0..v.len() as u32).map(|c| (edge_key(v[n(c) as usize], v[p(c) as usize]), c)).collect();
    e.sort_unstable();
    e
}

/// Runs of equal keys in a sorted `(key, corner)` list.
fn runs(e: &[(u64, u32)]) -> impl Iterator<Item = &[(u64, u32)]> {
    e.chunk_by(|x, y| x.0 == y.0)
}

/// The corner of vertex `x` in the triangle of corner `c`.
#[inline]
fn corner_of(v: &[u32], c: u32, x: u32) -> u32 {
    let t0 = c - c % 3;
    (t0..t0 + 3).find(|&k| v[k as usize] == x).unwrap_or(c)
}

/// Repairs a triangle soup into a valid mesh (see the module docs for the
/// steps) and reports what changed, keeping `EXAMPLES` ids per kind.
///
/// # Errors
/// [`MeshError::IndexOutOfRange`] for an index past `positions`,
/// [`MeshError::NonFinite`] for a used vertex with a NaN or infinite
/// coordinate, [`MeshError::Empty`] when no face is left, and
/// [`MeshError::TooManyElements`] past 32-bit corner ids.
pub fn repair(positions: Vec<Vec3>, triangles: &[u32]) -> Result<(Mesh, RepairReport), MeshError> {
    repair_with_cap(positions, triangles, EXAMPLES)
}

#[cfg(test)]
/// Runs the repair analysis and returns only its report, keeping every id
/// (no cap): what `subdiv info` lists for a mesh that does not build.
///
/// # Errors
/// As [`repair`].
pub(crate) fn analyze(positions: &[Vec3], triangles: &[u32]) -> Result<RepairReport, MeshError> {
    repair_with_cap(positions.to_vec(), triangles, usize::MAX).map(|(_, r)| r)
}

/// [`repair`] keeping up to `cap` example ids per kind of change.
///
/// # Errors
/// As [`repair`].
pub(crate) fn repair_with_cap(
    positions: Vec<Vec3>,
    triangles: &[u32],
    cap: usize,
) -> Result<(Mesh, RepairReport), MeshError> {
    let mut rep = check_input(&positions, triangles, cap)?;
    let nv = positions.len();
    // 1. and 2.: the kept faces; `orig[t]` is the input id of face t
    let mut keep = drop_degenerate_faces(&positions, triangles, &mut rep);
    drop_duplicate_faces(triangles, &mut keep, &mut rep);
    let orig: Vec<u32> = (0..keep.len() as u32).filter(|&f| keep[f as usize]).collect();
    if orig.is_empty() {
        return Err(MeshError::Empty);
    }
    let mut v: Vec<u32> =
        orig.iter().flat_map(|&f| triangles[3 * f as usize..3 * f as usize + 3].iter().copied()).collect();
    // 3. edge classification: mate[c] is the glued corner across the edge opposite c
    let mut mate = classify_edges(&v, nv, &mut rep);
    // 4. orientation
    orient_faces(&mut v, &mut mate, &orig, &mut rep);
    // 5. and 6. fans -> vertex copies, re-gluing
    let (new_v, origin) = separate_fans(&v, &mut mate, nv, &mut rep);
    // 7. splits and unreferenced vertices
    count_copies(&origin, nv, &mut rep);
    let out_pos: Vec<Vec3> = origin.iter().map(|&x| positions[x as usize]).collect();
    drop(positions);
    let mesh = Mesh::from_triangles(out_pos, &new_v)?;
    rep.faces_out = mesh.ct.num_triangles();
    rep.vertices_out = mesh.positions.len();
    Ok((mesh, rep))
}

/// The size, range and finiteness checks (not repairable: these are errors
/// in the data) and an empty report with `cap` examples per kind.
fn check_input(positions: &[Vec3], triangles: &[u32], cap: usize) -> Result<RepairReport, MeshError> {
    let nv = positions.len();
    let nt = triangles.len() / 3;
    if 3 * nt >= (u32::MAX as usize) / 4 || nv >= u32::MAX as usize {
        return Err(MeshError::TooManyElements { what: format!("{nt} triangles, {nv} vertices") });
    }
    for (f, tri) in triangles.chunks_exact(3).enumerate() {
        for &i in tri {
            if i as usize >= nv {
                return Err(MeshError::IndexOutOfRange { face: f, index: i64::from(i), len: nv });
            }
            if !positions[i as usize].is_finite() {
                return Err(MeshError::NonFinite { vertex: i as usize });
            }
        }
    }
    Ok(RepairReport {
        faces_in: nt,
        vertices_in: nv,
        degenerate_faces: Tally::with_cap(cap),
        duplicate_faces: Tally::with_cap(cap),
        non_manifold_edges: Tally::with_cap(cap),
        extra_cuts: Tally::with_cap(cap),
        flipped_faces: Tally::with_cap(cap),
        non_manifold_vertices: Tally::with_cap(cap),
        split_vertices: Tally::with_cap(cap),
        unreferenced_vertices: Tally::with_cap(cap),
        ..Default::default()
    })
}

/// Step 1: which faces to keep, dropping those that use a vertex twice or
/// have two bit-identical corner positions.
fn drop_degenerate_faces(positions: &[Vec3], triangles: &[u32], rep: &mut RepairReport) -> Vec<bool> {
    let mut keep = vec![true; triangles.len() / 3];
    for (f, tri) in triangles.chunks_exact(3).enumerate() {
        let [a, b, c] = [tri[0], tri[1], tri[2]];
        let (pa, pb, pc) = (positions[a as usize], positions[b as usize], positions[c as usize]);
        if a == b || b == c || a == c || pa == pb || pb == pc || pa == pc {
            keep[f] = false;
            rep.degenerate_faces.push(f);
        }
    }
    keep
}

/// Step 2: drops every kept face whose vertex set an earlier kept face has
/// (a sort by the sorted triple).
fn drop_duplicate_faces(triangles: &[u32], keep: &mut [bool], rep: &mut RepairReport) {
    let mut keys: Vec<([u32; 3], u32)> = (0..keep.len() as u32)
        .filter(|&f| keep[f as usize])
        .map(|f| {
            let mut k = [triangles[3 * f as usize], triangles[3 * f as usize + 1], triangles[3 * f as usize + 2]];
            k.sort_unstable();
            (k, f)
        })
        .collect();
    keys.sort_unstable();
    let mut dups = Vec::new();
    for run in keys.chunk_by(|x, y| x.0 == y.0) {
        dups.extend(run[1..].iter().map(|&(_, f)| f as usize));
    }
    dups.sort_unstable();
    for f in dups {
        keep[f] = false;
        rep.duplicate_faces.push(f);
    }
}

/// Step 3: glues the two corners of every edge with exactly two faces
/// (`mate`, returned; [`BORDER`] elsewhere), reports edges with three or
/// more as non-manifold (cut), and vertices whose faces form two or more
/// fans even with every shared edge joined as bowties.
fn classify_edges(v: &[u32], nv: usize, rep: &mut RepairReport) -> Vec<u32> {
    let nc = v.len();
    let mut mate = vec![BORDER; nc];
    let mut all_edges = Dsu::new(nc); // fans with every shared edge joined (bowtie detection)
    for run in runs(&corners_by_edge(v)) {
        let key = run[0].0;
        let edge = [(key >> 32) as u32, key as u32];
        if run.len() == 2 {
            let (c1, c2) = (run[0].1, run[1].1);
            mate[c1 as usize] = c2;
            mate[c2 as usize] = c1;
        } else if run.len() > 2 {
            rep.non_manifold_edges.push(edge);
        }
        // join the corners of both endpoints across every face of the edge
        for w in run.windows(2) {
            for x in edge {
                all_edges.union(corner_of(v, w[0].1, x), corner_of(v, w[1].1, x));
            }
        }
    }
    // bowties: vertices with two or more classes even with all edges joined
    let mut fans = vec![0u32; nv];
    for c in 0..nc as u32 {
        // count distinct roots per vertex: a root is counted at its own corner
        if all_edges.find(c) == c {
            fans[v[c as usize] as usize] += 1;
        }
    }
    for (x, &k) in fans.iter().enumerate() {
        if k > 1 {
            rep.non_manifold_vertices.push(x as u32);
        }
    }
    mate
}

/// Step 4: a flip bit per face from a breadth-first search across glued
/// edges (an edge where the search meets a face again with the other bit is
/// cut), the smaller part of each component flipped, then applied to `v`
/// and `mate`: `(a, b, c)` becomes `(a, c, b)`.
fn orient_faces(v: &mut Vec<u32>, mate: &mut Vec<u32>, orig: &[u32], rep: &mut RepairReport) {
    let flip = flip_bits(v, mate, rep);
    if flip.contains(&1) {
        apply_flips(v, mate, &flip, orig, rep);
    }
    debug_assert!((0..v.len() as u32).all(|c| {
        let m = mate[c as usize];
        m == BORDER || (v[n(c) as usize] == v[p(m) as usize] && v[p(c) as usize] == v[n(m) as usize])
    }));
}

/// Reverses the faces whose `flip` bit is set, in `v` and `mate`.
fn apply_flips(v: &mut Vec<u32>, mate: &mut Vec<u32>, flip: &[u8], orig: &[u32], rep: &mut RepairReport) {
    // (a, b, c) -> (a, c, b) swaps corners 1 and 2 of the face
    let perm = |c: u32| -> u32 {
        if flip[(c / 3) as usize] == 1 && !c.is_multiple_of(3) { if c % 3 == 1 { c + 1 } else { c - 1 } } else { c }
    };
    let nc = v.len();
    let mut v2 = vec![0u32; nc];
    let mut m2 = vec![BORDER; nc];
    for c in 0..nc as u32 {
        v2[perm(c) as usize] = v[c as usize];
        let m = mate[c as usize];
        m2[perm(c) as usize] = if m == BORDER { BORDER } else { perm(m) };
    }
    *v = v2;
    *mate = m2;
    for (t, &fl) in flip.iter().enumerate() {
        if fl == 1 {
            rep.flipped_faces.push(orig[t] as usize);
        }
    }
}

/// The flip bit of every face (step 4's search), cutting the glued edges
/// where a component turns out non-orientable.
fn flip_bits(v: &[u32], mate: &mut [u32], rep: &mut RepairReport) -> Vec<u8> {
    let nf = v.len() / 3;
    let mut flip = vec![u8::MAX; nf];
    let mut queue: Vec<u32> = Vec::with_capacity(nf);
    for seed in 0..nf as u32 {
        if flip[seed as usize] != u8::MAX {
            continue;
        }
        let start = queue.len();
        flip[seed as usize] = 0;
        queue.push(seed);
        let mut head = start;
        while head < queue.len() {
            let f = queue[head];
            head += 1;
            for c in 3 * f..3 * f + 3 {
                let m = mate[c as usize];
                if m == BORDER {
                    continue;
                }
                let g = (m / 3) as usize;
                // same direction: both corners see the edge start at the same vertex
                let same = u8::from(v[n(c) as usize] == v[n(m) as usize]);
                let want = flip[f as usize] ^ same;
                if flip[g] == u8::MAX {
                    flip[g] = want;
                    queue.push(g as u32);
                } else if flip[g] != want {
                    let (a, b) = (v[n(c) as usize], v[p(c) as usize]);
                    rep.extra_cuts.push([a.min(b), a.max(b)]);
                    mate[c as usize] = BORDER;
                    mate[m as usize] = BORDER;
                }
            }
        }
        // flip the smaller part of the component
        let comp = &queue[start..];
        let flipped = comp.iter().filter(|&&f| flip[f as usize] == 1).count();
        if 2 * flipped > comp.len() {
            for &f in comp {
                flip[f as usize] ^= 1;
            }
        }
    }
    flip
}

/// Rounds of step 5 (numbering the fans) and step 6 (re-gluing or cutting
/// faces of a cut edge that still share its copies) until nothing is cut:
/// the new V and, per new vertex, its input vertex.
fn separate_fans(v: &[u32], mate: &mut [u32], nv: usize, rep: &mut RepairReport) -> (Vec<u32>, Vec<u32>) {
    const MAX_ROUNDS: u32 = 64;
    let mut rounds = 0u32;
    loop {
        let (new_v, origin) = number_fans(v, mate, nv);
        if !reglue_or_cut(v, &new_v, mate, rounds >= MAX_ROUNDS, rep) {
            return (new_v, origin);
        }
        rounds += 1;
        if rounds >= MAX_ROUNDS {
            // safety net, not expected to be reached: separate triangles are always valid
            debug_assert!(false, "repair: separation did not converge");
            for c in 0..mate.len() {
                if mate[c] != BORDER && (c as u32) < mate[c] {
                    let (a, b) = (v[n(c as u32) as usize], v[p(c as u32) as usize]);
                    rep.extra_cuts.push([a.min(b), a.max(b)]);
                }
            }
            mate.fill(BORDER);
        }
    }
}

/// Step 5: union-find over corners joined across glued edges; every class
/// (fan) gets its own vertex, numbered vertex by vertex, fans in order of
/// their first corner. Returns the new V and the input vertex of each new one.
fn number_fans(v: &[u32], mate: &[u32], nv: usize) -> (Vec<u32>, Vec<u32>) {
    let nc = v.len();
    let mut dsu = Dsu::new(nc);
    for c in 0..nc as u32 {
        let m = mate[c as usize];
        if m != BORDER && c < m {
            // c's edge runs a -> b, m's runs b -> a
            dsu.union(n(c), p(m));
            dsu.union(p(c), n(m));
        }
    }
    // number the classes vertex by vertex (counting sort of corners by vertex)
    let mut start = vec![0u32; nv + 1];
    for &x in v {
        start[x as usize + 1] += 1;
    }
    for i in 0..nv {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut by_vertex = vec![0u32; nc];
    for c in 0..nc as u32 {
        let x = v[c as usize] as usize;
        by_vertex[fill[x] as usize] = c;
        fill[x] += 1;
    }
    let mut id_of_root = vec![BORDER; nc];
    let mut origin: Vec<u32> = Vec::with_capacity(nv);
    for x in 0..nv {
        for &c in &by_vertex[start[x] as usize..start[x + 1] as usize] {
            let r = dsu.find(c) as usize;
            if id_of_root[r] == BORDER {
                id_of_root[r] = origin.len() as u32;
                origin.push(x as u32);
            }
        }
    }
    let new_v: Vec<u32> = (0..nc as u32).map(|c| id_of_root[dsu.find(c) as usize]).collect();
    (new_v, origin)
}

/// Step 6, on the new ids: an edge whose copies are shared by faces that are
/// not glued across it is glued again when the two run oppositely (this
/// merges no fans), otherwise (or when `exhausted`) each face but the first
/// gets one more glued edge cut at that edge's endpoint. Returns whether
/// anything was cut (step 5 must then be redone).
fn reglue_or_cut(v: &[u32], new_v: &[u32], mate: &mut [u32], exhausted: bool, rep: &mut RepairReport) -> bool {
    let mut cut_any = false;
    for run in runs(&corners_by_edge(new_v)) {
        if run.len() == 1 || (run.len() == 2 && mate[run[0].1 as usize] == run[1].1) {
            continue;
        }
        let (c0, c1) = (run[0].1, run[1].1);
        if run.len() == 2 && new_v[n(c0) as usize] == new_v[p(c1) as usize] && !exhausted {
            // a consistent pair: both corners are already in one fan at
            // each end, so gluing merges no fans and changes no ids
            mate[c0 as usize] = c1;
            mate[c1 as usize] = c0;
            continue;
        }
        for &(_, c) in &run[1..] {
            // cut the face's other glued edge at one endpoint of this edge
            for k in [p(c), n(c)] {
                let m = mate[k as usize];
                if m != BORDER {
                    let (a, b) = (v[n(k) as usize], v[p(k) as usize]);
                    rep.extra_cuts.push([a.min(b), a.max(b)]);
                    mate[k as usize] = BORDER;
                    mate[m as usize] = BORDER;
                    cut_any = true;
                    break;
                }
            }
        }
    }
    cut_any
}

/// Step 7 (and the split counts): input vertices with no copy are
/// unreferenced, those with several were split.
fn count_copies(origin: &[u32], nv: usize, rep: &mut RepairReport) {
    let mut copies = vec![0u32; nv];
    for &x in origin {
        copies[x as usize] += 1;
    }
    for (x, &k) in copies.iter().enumerate() {
        match k {
            0 => rep.unreferenced_vertices.push(x as u32),
            1 => {}
            _ => {
                rep.split_vertices.push(x as u32);
                rep.added_vertices += k as usize - 1;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::icosphere;
    use crate::mesh::topology::{check_invariants, topology};

    fn check(mesh: &Mesh) {
        check_invariants(&mesh.ct).unwrap();
        Mesh::from_triangles(mesh.positions.clone(), mesh.ct.v_table()).unwrap();
    }

    #[test]
    fn good_mesh_is_unchanged() {
        let s = icosphere(2);
        let (m, rep) = repair(s.positions.clone(), s.ct.v_table()).unwrap();
        assert!(rep.is_empty(), "{rep}");
        assert_eq!(m.ct.v_table(), s.ct.v_table());
        assert_eq!(m.positions, s.positions);
        assert_eq!((rep.faces_in, rep.faces_out), (320, 320));
        assert!(rep.to_string().contains("nothing to repair"));
    }

    #[test]
    fn flipped_faces_are_reoriented() {
        let s = icosphere(1);
        let mut tris = s.ct.v_table().to_vec();
        // flip faces 3 and 17
        for f in [3, 17] {
            tris.swap(3 * f + 1, 3 * f + 2);
        }
        assert!(matches!(
            Mesh::from_triangles(s.positions.clone(), &tris).unwrap_err(),
            MeshError::InconsistentOrientation { .. }
        ));
        let (m, rep) = repair(s.positions.clone(), &tris).unwrap();
        check(&m);
        assert_eq!(rep.flipped_faces.count, 2);
        assert_eq!(rep.flipped_faces.examples, vec![3, 17]);
        // flipped back to exactly the original faces
        assert_eq!(m.ct.v_table(), s.ct.v_table());
        let t = topology(&m.ct);
        assert_eq!((t.euler, t.border_edges, t.components), (2, 0, 1));
    }

    #[test]
    fn majority_orientation_wins() {
        // a strip of 4 triangles where the first one is flipped
        let pos: Vec<Vec3> = (0..6).map(|i| Vec3::new((i / 2) as f32, (i % 2) as f32, 0.0)).collect();
        let tris = [0, 1, 2, 1, 3, 2, 2, 3, 4, 3, 5, 4];
        let mut bad = tris;
        bad.swap(1, 2);
        let (m, rep) = repair(pos, &bad).unwrap();
        check(&m);
        assert_eq!(rep.flipped_faces.examples, vec![0]);
        assert_eq!(m.ct.v_table(), tris.to_vec());
    }

    #[test]
    fn bowtie_gets_one_extra_vertex() {
        let pos =
            vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::new(2.0, 1.0, 0.0), Vec3::new(2.0, 2.0, 0.0)];
        let tris = [0, 1, 2, 2, 3, 4];
        let (m, rep) = repair(pos, &tris).unwrap();
        check(&m);
        assert_eq!(m.positions.len(), 6);
        assert_eq!(rep.added_vertices, 1);
        assert_eq!(rep.split_vertices.examples, vec![2]);
        assert_eq!(rep.non_manifold_vertices.examples, vec![2]);
        assert!(rep.non_manifold_edges.is_empty() && rep.flipped_faces.is_empty());
    }

    fn fin(k: usize) -> (Vec<Vec3>, Vec<u32>) {
        // k triangles on the edge (0, 1), alternating orientation
        let mut pos = vec![Vec3::ZERO, Vec3::X];
        let mut tris = Vec::new();
        for i in 0..k {
            let a = std::f32::consts::TAU * i as f32 / k as f32;
            pos.push(Vec3::new(0.5, a.cos(), a.sin()));
            let w = 2 + i as u32;
            if i % 2 == 0 { tris.extend([0, 1, w]) } else { tris.extend([1, 0, w]) }
        }
        (pos, tris)
    }

    #[test]
    fn fin_is_cut_into_separate_triangles() {
        for k in [3, 4] {
            let (pos, tris) = fin(k);
            let (m, rep) = repair(pos, &tris).unwrap();
            check(&m);
            assert_eq!(rep.non_manifold_edges.count, 1);
            assert_eq!(rep.non_manifold_edges.examples, vec![[0, 1]]);
            // every face keeps all three of its edges as borders
            let t = topology(&m.ct);
            assert_eq!(t.faces, k);
            assert_eq!(t.border_edges, 3 * k);
            assert_eq!(t.components, k);
            assert_eq!(m.positions.len(), 3 * k);
            assert_eq!(rep.added_vertices, 2 * (k - 1));
            assert!(rep.non_manifold_vertices.is_empty(), "endpoints of a cut edge are not bowties");
        }
    }

    #[test]
    fn two_tetrahedra_on_one_edge_become_two_closed_tetrahedra() {
        // two tetrahedra sharing the edge (0, 1): four faces on it. Cutting it
        // leaves each tetrahedron's two faces sharing both vertex copies with
        // opposite directions, so they are glued again: two closed surfaces.
        let pos = vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::new(0.5, 1.0, 0.2),
            Vec3::new(0.5, 0.5, 1.0),
            Vec3::new(0.5, -1.0, 0.2),
            Vec3::new(0.5, -0.5, -1.0),
        ];
        let tet = |a: u32, b: u32, c: u32, d: u32| [a, c, b, a, d, c, a, b, d, b, c, d];
        let mut tris = tet(0, 1, 2, 3).to_vec();
        tris.extend(tet(0, 1, 4, 5));
        assert!(matches!(
            Mesh::from_triangles(pos.clone(), &tris).unwrap_err(),
            MeshError::NonManifoldEdge { faces: 4, .. }
        ));
        let (m, rep) = repair(pos, &tris).unwrap();
        check(&m);
        assert_eq!(rep.non_manifold_edges.count, 1);
        assert_eq!(rep.added_vertices, 2);
        assert!(rep.extra_cuts.is_empty(), "{rep}");
        let t = topology(&m.ct);
        assert_eq!((t.faces, t.components, t.border_edges, t.euler), (8, 2, 0, 4));
    }

    #[test]
    fn mobius_strip_is_cut_once() {
        // a strip of 5 quads whose ends are glued with a half twist
        let k = 5u32;
        let mut pos = Vec::new();
        for i in 0..k {
            let a = std::f32::consts::TAU * i as f32 / k as f32;
            let tw = a / 2.0;
            let (r, h) = (1.0 + 0.3 * tw.cos(), 0.3 * tw.sin());
            pos.push(Vec3::new(r * a.cos(), r * a.sin(), h));
            let (r, h) = (1.0 - 0.3 * tw.cos(), -0.3 * tw.sin());
            pos.push(Vec3::new(r * a.cos(), r * a.sin(), h));
        }
        let mut tris = Vec::new();
        for i in 0..k {
            let (a, b) = (2 * i, 2 * i + 1);
            let (c, d) = if i + 1 < k { (2 * i + 2, 2 * i + 3) } else { (1, 0) }; // the twist
            tris.extend([a, c, b, b, c, d]);
        }
        let (m, rep) = repair(pos, &tris).unwrap();
        check(&m);
        assert!(rep.extra_cuts.count >= 1, "{rep}");
        let t = topology(&m.ct);
        assert_eq!(t.faces, 2 * k as usize);
        assert_eq!(t.components, 1);
    }

    #[test]
    fn degenerate_duplicate_and_unreferenced_are_dropped() {
        let pos = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::ONE, Vec3::X];
        // face 1 repeats a vertex, face 2 duplicates face 0 reversed, face 3 has
        // two corners at the same position (vertices 1 and 4)
        let tris = [0, 1, 2, 0, 0, 2, 2, 1, 0, 0, 1, 4];
        let (m, rep) = repair(pos, &tris).unwrap();
        check(&m);
        assert_eq!(rep.degenerate_faces.examples, vec![1, 3]);
        assert_eq!(rep.duplicate_faces.examples, vec![2]);
        assert_eq!(rep.unreferenced_vertices.examples, vec![3, 4]);
        assert_eq!(m.ct.v_table(), vec![0, 1, 2]);
        let s = rep.to_string();
        assert!(s.contains("degenerate faces dropped:       2 (1, 3)"), "{s}");
    }

    #[test]
    fn examples_are_capped_but_analyze_keeps_all() {
        // 15 repeated-index faces next to one good one
        let pos = vec![Vec3::ZERO, Vec3::X, Vec3::Y];
        let mut tris = vec![0, 1, 2];
        for _ in 0..15 {
            tris.extend([0, 1, 1]);
        }
        let (_, rep) = repair(pos.clone(), &tris).unwrap();
        assert_eq!(rep.degenerate_faces.count, 15);
        assert_eq!(rep.degenerate_faces.examples, (1..=EXAMPLES).collect::<Vec<_>>());
        let all = analyze(&pos, &tris).unwrap();
        assert_eq!(all.degenerate_faces.examples, (1..=15).collect::<Vec<_>>());
        // the display shows the first EXAMPLES and says there are more
        let s = all.to_string();
        assert!(s.contains("15 (1, 2, 3, 4, 5, 6, 7, 8, 9, 10, ...)"), "{s}");
    }

    #[test]
    fn errors_stay_errors() {
        assert_eq!(repair(vec![Vec3::ZERO; 3], &[0, 0, 1]).unwrap_err(), MeshError::Empty);
        assert!(matches!(repair(vec![Vec3::ZERO; 3], &[0, 1, 3]).unwrap_err(), MeshError::IndexOutOfRange { .. }));
        let nan = vec![Vec3::ZERO, Vec3::X, Vec3::NAN];
        assert_eq!(repair(nan, &[0, 1, 2]).unwrap_err(), MeshError::NonFinite { vertex: 2 });
    }

    #[test]
    fn display_lists_one_based_examples() {
        let (pos, tris) = fin(3);
        let (_, mut rep) = repair(pos, &tris).unwrap();
        rep.id_base = 1;
        let s = rep.to_string();
        assert!(s.contains("non-manifold edges cut:         1 (1-2)"), "{s}");
        assert!(s.contains("vertex ids 1-based"), "{s}");
    }
}
