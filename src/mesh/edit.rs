//! Local edits of a corner table that keep V, O, C and the valences
//! consistent without a rebuild: edge flip and edge split. Each touches O(1)
//! corners plus the fans of the four or five vertices involved.
//!
//! Labels (corner `c`, its triangle `(c, n(c), p(c))` with vertices
//! `(w, a, b)`; the edge `(a, b)` opposite `c`; `x = o(c)` with vertex `d`):
//! ```text
//!          w                       flip: edge (a, b) -> edge (w, d)
//!        /   \                       triangle of c: (c:w, n(c):a, p(c):d)
//!       a --- b                      triangle of x: (x:d, n(x):b, p(x):w)
//!        \   /                     split at m = a + t (b - a):
//!          d                         (w, a, m) (w, m, b) [+ (d, b, m) (d, m, a)]
//! ```
//! Corners keep their ids where their triangle survives; a split appends its
//! new triangles (and one vertex) at the end.

use super::{BORDER, CornerTable, Mesh, n, p};

/// Why an edge cannot be flipped.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum EditError {
    /// The corner id is not in the table.
    #[error("corner {corner} does not exist ({corners} corners)")]
    NoSuchCorner { corner: u32, corners: usize },
    /// The edge is on the border (one triangle only).
    #[error("the edge opposite corner {corner} is a border edge")]
    BorderEdge { corner: u32 },
    /// The new diagonal already exists elsewhere in the mesh (or would be a
    /// loop `w == d`): flipping would create a duplicate or degenerate edge.
    #[error("flipping would create edge ({v0}, {v1}), which already exists")]
    DuplicateEdge { v0: u32, v1: u32 },
    /// An endpoint of the edge would be left with fewer than 3 edges
    /// (interior) and its two triangles would fold onto each other.
    #[error("flipping would leave vertex {vertex} with fewer than 3 edges")]
    LowValence { vertex: u32 },
}

/// Flips the edge opposite corner `c`: the two triangles `(w, a, b)` and
/// `(d, b, a)` become `(w, a, d)` and `(d, b, w)`. Corner ids stay; `V[p(c)]`
/// becomes `d` and `V[p(x)]` becomes `w`.
///
/// O update (`x = o(c)`, primes = after):
/// `O'[c] = O[n(x)]`, `O'[x] = O[n(c)]`, `O'[n(c)] = n(x)`, `O'[n(x)] = n(c)`
/// (and the outer corners point back); `O[p(c)]`, `O[p(x)]` are unchanged.
/// Valences: `a`, `b` lose one edge, `w`, `d` gain one; `C` of the four
/// vertices is recomputed from their fans.
///
/// # Errors
/// [`EditError`]: no such corner, a border edge, a diagonal that already
/// exists (or `w == d`), or an interior endpoint of valence 3.
pub fn flip_edge(ct: &mut CornerTable, c: u32) -> Result<(), EditError> {
    // sharpness is kept by vertex pairs: a flipped sharp edge is gone
    let tags = ct.sharpness.take().map(|s| s.to_tags(ct));
    // an edited table is a new control table: its edges are generation 0
    ct.clear_generations();
    let done = flip_topology(ct, c);
    restore_tags(ct, tags, None);
    done
}

/// Sharpness tags re-applied after an edit; a tag on `split = (a, b, m)`'s
/// edge goes to both halves, a tag whose edge is gone is dropped.
fn restore_tags(ct: &mut CornerTable, tags: Option<super::Tags>, split: Option<(u32, u32, u32)>) {
    let Some(mut tags) = tags else { return };
    if let Some((a, b, m)) = split {
        let halves: Vec<_> = tags
            .creases
            .iter()
            .filter(|t| (t.v0, t.v1) == (a, b) || (t.v0, t.v1) == (b, a))
            .flat_map(|t| [super::sharpness::CreaseTag { v1: m, ..*t }, super::sharpness::CreaseTag { v0: m, ..*t }])
            .collect();
        tags.creases.extend(halves);
    }
    tags.creases.retain(|t| ct.corner_opposite(t.v0, t.v1).is_some());
    tags.corners.retain(|t| (t.vertex as usize) < ct.num_vertices());
    // every tag names an existing edge or vertex now, with a value checked
    // when it was first made
    ct.sharpness = super::Sharpness::from_tags(ct, &tags).ok().flatten().map(Box::new);
}

fn flip_topology(ct: &mut CornerTable, c: u32) -> Result<(), EditError> {
    if c as usize >= ct.num_corners() {
        return Err(EditError::NoSuchCorner { corner: c, corners: ct.num_corners() });
    }
    let x = ct.o(c).ok_or(EditError::BorderEdge { corner: c })?;
    let (w, a, b, d) = (ct.vtx(c), ct.vtx(n(c)), ct.vtx(p(c)), ct.vtx(x));
    if w == d || ct.ring(w).any(|q| q == d) {
        return Err(EditError::DuplicateEdge { v0: w.min(d), v1: w.max(d) });
    }
    for v in [a, b] {
        if !ct.is_boundary_vertex(v) && ct.valence[v as usize] <= 3 {
            return Err(EditError::LowValence { vertex: v });
        }
    }
    let (e_bw, e_ad) = (ct.o[n(c) as usize], ct.o[n(x) as usize]);
    ct.v[p(c) as usize] = d;
    ct.v[p(x) as usize] = w;
    ct.o[c as usize] = e_ad;
    ct.o[x as usize] = e_bw;
    if e_ad != BORDER {
        ct.o[e_ad as usize] = c;
    }
    if e_bw != BORDER {
        ct.o[e_bw as usize] = x;
    }
    ct.o[n(c) as usize] = n(x);
    ct.o[n(x) as usize] = n(c);
    for (v, corner) in [(w, c), (a, n(c)), (b, n(x)), (d, x)] {
        refresh_vertex(ct, v, corner);
    }
    Ok(())
}

/// Splits the edge opposite corner `c` at `a + t (b - a)` (`a = v(n(c))`,
/// `b = v(p(c))`; `t` is not clamped): the new vertex `m` (returned; id =
/// the old vertex count) joins `w = v(c)` and, for an interior edge, `d =
/// v(o(c))`. Interior edge: 2 triangles become 4, +1 vertex, +3 edges;
/// border edge: 1 becomes 2, +1 vertex, +2 edges (Euler characteristic kept).
///
/// Triangle of `c` becomes `(c:w, n(c):a, p(c):m)`, a new triangle `k` is
/// `(k0:w, k1:m, k2:b)`; on an interior edge the triangle of `x = o(c)`
/// becomes `(x:d, n(x):b, p(x):m)` and a new triangle `j` is
/// `(j0:d, j1:m, j2:a)`. New opposites:
/// ```text
/// O[c] = j0 (BORDER)    O[n(c)] = k2    O[p(c)] unchanged
/// O[k0] = x (BORDER)    O[k1] = old O[n(c)]
/// O[n(x)] = j2          O[p(x)] unchanged
/// O[j1] = old O[n(x)]
/// ```
/// (in brackets: a border edge, where there is no `x` and no `j`).
///
/// # Panics
/// If `c` is not a corner of `mesh` or the table would exceed 32-bit ids.
pub fn split_edge(mesh: &mut Mesh, c: u32, t: f32) -> u32 {
    let tags = mesh.ct.sharpness.take().map(|s| s.to_tags(&mesh.ct));
    mesh.ct.clear_generations();
    let ends = (mesh.ct.vtx(n(c)), mesh.ct.vtx(p(c)));
    let m = split_topology(mesh, c, t);
    restore_tags(&mut mesh.ct, tags, Some((ends.0, ends.1, m)));
    m
}

fn split_topology(mesh: &mut Mesh, c: u32, t: f32) -> u32 {
    let ct = &mut mesh.ct;
    assert!((c as usize) < ct.num_corners(), "split_edge: corner {c} does not exist");
    assert!(ct.num_corners() + 6 < BORDER as usize, "split_edge: too many corners");
    let (w, a, b) = (ct.vtx(c), ct.vtx(n(c)), ct.vtx(p(c)));
    let m = mesh.positions.len() as u32;
    let (pa, pb) = (mesh.positions[a as usize], mesh.positions[b as usize]);
    mesh.positions.push(pa + (pb - pa) * t);
    ct.vc.push(p(c));
    ct.valence.push(0);
    let e_bw = ct.o[n(c) as usize];
    let x = ct.o(c);
    let k0 = ct.num_corners() as u32;
    let (k1, k2) = (k0 + 1, k0 + 2);
    ct.v.extend_from_slice(&[w, m, b]);
    ct.o.extend_from_slice(&[BORDER, e_bw, n(c)]);
    ct.v[p(c) as usize] = m;
    ct.o[n(c) as usize] = k2;
    if e_bw != BORDER {
        ct.o[e_bw as usize] = k1;
    }
    let mut touched = vec![(w, c), (a, n(c)), (b, k2), (m, p(c))];
    if let Some(x) = x {
        let d = ct.vtx(x);
        let e_ad = ct.o[n(x) as usize];
        let j0 = ct.num_corners() as u32;
        let (j1, j2) = (j0 + 1, j0 + 2);
        ct.v.extend_from_slice(&[d, m, a]);
        ct.o.extend_from_slice(&[c, e_ad, n(x)]);
        ct.v[p(x) as usize] = m;
        ct.o[c as usize] = j0;
        ct.o[k0 as usize] = x;
        ct.o[x as usize] = k0;
        ct.o[n(x) as usize] = j2;
        if e_ad != BORDER {
            ct.o[e_ad as usize] = j1;
        }
        touched.push((d, x));
    }
    for (v, corner) in touched {
        refresh_vertex(ct, v, corner);
    }
    m
}

/// Recomputes `C[v]` and the valence of `v` from its fan, given any corner
/// of `v`: unswing to the border (boundary vertex: that corner starts the
/// fan) or all the way round (interior: `corner` itself), then count.
fn refresh_vertex(ct: &mut CornerTable, v: u32, corner: u32) {
    debug_assert_eq!(ct.vtx(corner), v);
    let mut start = corner;
    let mut closed = false;
    while let Some(y) = ct.u(start) {
        if y == corner {
            closed = true;
            break;
        }
        start = y;
    }
    if closed {
        start = corner;
    }
    let mut count = 1u32;
    let mut cur = start;
    while let Some(y) = ct.s(cur) {
        if y == start {
            break;
        }
        count += 1;
        cur = y;
    }
    ct.vc[v as usize] = start;
    ct.valence[v as usize] = count + u32::from(!closed);
}
