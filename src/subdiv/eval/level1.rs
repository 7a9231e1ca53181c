//! One Loop step of the whole control mesh in f64, so that every face of
//! level 1 has at most one extraordinary vertex (Stam 1998 §3 assumes
//! it). Control face `f` has the children `4f + k`:
//!
//! ```text
//!            v2                 k = 0: (v0, e01, e20)   (s, t) = (2u, 2v)
//!           /  \                k = 1: (e01, v1, e12)   (s, t) = (2u - 1, 2v)
//!        e20 -- e12             k = 2: (e20, e12, v2)   (s, t) = (2u, 2v - 1)
//!        / \    / \             k = 3: (e01, e12, e20)  (s, t) = (2u + 2v - 1, 1 - 2u)
//!      v0 -- e01 -- v1
//! ```
//!
//! Vertex points use Loop's interior rule with the chosen beta (boundary
//! vertices the boundary rule), edge points `3/8, 3/8, 1/8, 1/8` (border
//! edges the midpoint), as [`crate::subdiv::rules::loop_`] does; only the
//! faces whose three control vertices are interior and free of sharp
//! features are evaluated, and their level-1 neighbourhoods use nothing
//! else.

use crate::mesh::{CornerTable, Mesh, n, p};
use crate::subdiv::LoopBeta;
use crate::{Error, Result};
use glam::DVec3;

/// The level-1 table and its f64 points.
pub(crate) struct Level1 {
    pub(crate) ct: CornerTable,
    pub(crate) pos: Vec<DVec3>,
}

/// No extraordinary corner.
pub(crate) const REGULAR: u8 = u8::MAX;

/// Appends the support of the triangle of corner `c` in walk order (the
/// patch module docs): `c0`, the ring of `c0` from `c1`, the outer
/// neighbours of `c1` (its ring from `c2`: `c2 c0 z o1 o2 o3`) and of `c2`
/// (from `c0`: `c0 c1 o3 o4 o5`).
pub(crate) fn walk(ct: &CornerTable, c: u32, mut out: impl FnMut(u32)) {
    out(ct.vtx(c));
    let mut x = c;
    loop {
        out(ct.vtx(n(x)));
        match ct.s(x) {
            Some(next) if next != c => x = next,
            _ => break,
        }
    }
    for (start, take) in [(n(c), 3), (p(c), 2)] {
        let mut x = start;
        for i in 0..3 + take {
            if i >= 3 {
                out(ct.vtx(n(x)));
            }
            x = ct.s(x).unwrap_or(x);
        }
    }
}

/// The edge id of every corner (the edge opposite it) and their count.
fn edge_ids(ct: &CornerTable) -> (Vec<u32>, u32) {
    let nc = ct.num_corners() as u32;
    let mut ids = vec![u32::MAX; nc as usize];
    let mut ne = 0;
    for c in 0..nc {
        match ct.o(c) {
            Some(x) if x < c => ids[c as usize] = ids[x as usize],
            _ => {
                ids[c as usize] = ne;
                ne += 1;
            }
        }
    }
    (ids, ne)
}

fn vertex_points(ct: &CornerTable, pos: &[DVec3], beta: LoopBeta, out: &mut [DVec3]) {
    for v in 0..ct.num_vertices() as u32 {
        let x = pos[v as usize];
        out[v as usize] = match ct.boundary_neighbours(v) {
            Some((a, b)) => x * 0.75 + (pos[a as usize] + pos[b as usize]) * 0.125,
            None => {
                let k = ct.valence(v);
                let b = beta.beta(k);
                let sum: DVec3 = ct.ring(v).map(|w| pos[w as usize]).sum();
                x * (1.0 - f64::from(k) * b) + sum * b
            }
        };
    }
}

impl Level1 {
    /// Level 1 of `mesh` under Loop's rules with `beta`.
    pub(crate) fn new(mesh: &Mesh, beta: LoopBeta) -> Result<Level1> {
        let ct = &mesh.ct;
        let nv = ct.num_vertices();
        let pos: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
        let (ids, ne) = edge_ids(ct);
        let mut out = vec![DVec3::ZERO; nv + ne as usize];
        vertex_points(ct, &pos, beta, &mut out[..nv]);
        for c in 0..ct.num_corners() as u32 {
            let (a, b) = (pos[ct.vtx(n(c)) as usize], pos[ct.vtx(p(c)) as usize]);
            out[nv + ids[c as usize] as usize] = match ct.o(c) {
                Some(x) => (a + b) * 0.375 + (pos[ct.vtx(c) as usize] + pos[ct.vtx(x) as usize]) * 0.125,
                None => (a + b) * 0.5,
            };
        }
        let mut tris = Vec::with_capacity(12 * ct.num_triangles());
        for f in 0..ct.num_triangles() as u32 {
            let c = 3 * f;
            let [v0, v1, v2] = [ct.vtx(c), ct.vtx(c + 1), ct.vtx(c + 2)];
            let e = |corner: u32| nv as u32 + ids[corner as usize];
            let (e01, e12, e20) = (e(c + 2), e(c), e(c + 1));
            tris.extend([v0, e01, e20, e01, v1, e12, e20, e12, v2, e01, e12, e20]);
        }
        let (ct1, _, remap) = CornerTable::build(out.len(), &tris, None).map_err(Error::from)?;
        // every level-1 vertex is used (level 0 has no unused vertex), so
        // the ids stay; a remap would only reorder, and is applied if given
        let pos = match remap {
            Some(map) => map.iter().map(|&old| out[old as usize]).collect(),
            None => out,
        };
        Ok(Level1 { ct: ct1, pos })
    }

    /// Face `g`'s extraordinary corner ([`REGULAR`] if none) and the size
    /// of its support (valence + 6).
    #[inline]
    pub(crate) fn shape(&self, g: u32) -> (u8, usize) {
        let ct = &self.ct;
        for i in 0..3 {
            let k = ct.valence(ct.vtx(3 * g + i));
            if k != 6 {
                return (i as u8, k as usize + 6);
            }
        }
        (REGULAR, 12)
    }
}

/// The level-1 neighbourhood of every control face, stored face after face
/// so that one point reads one contiguous block: the points of control
/// face `f`'s four children's supports (the vertex points of its corners
/// and the edge points of their edges), and per child its support as
/// indices into the block (walk order from its extraordinary corner).
#[derive(Default)]
pub(crate) struct Blocks {
    pos: Vec<DVec3>,
    /// Control face `f`'s points are `pos[face_start[f]..face_start[f + 1]]`.
    face_start: Vec<u32>,
    /// Level-1 face `g`'s support is `index[child_start[g]..child_start[g + 1]]`.
    index: Vec<u16>,
    child_start: Vec<u32>,
    /// Level-1 face `g`'s extraordinary corner, [`REGULAR`] if none.
    corner: Vec<u8>,
}

impl Blocks {
    /// The blocks of the control faces not `refused`.
    pub(crate) fn new(l1: &Level1, refused: &[bool]) -> Result<Blocks> {
        let nf = refused.len();
        let mut b = Blocks {
            pos: Vec::new(),
            face_start: Vec::with_capacity(nf + 1),
            index: Vec::new(),
            child_start: Vec::with_capacity(4 * nf + 1),
            corner: Vec::with_capacity(4 * nf),
        };
        b.face_start.push(0);
        b.child_start.push(0);
        let too_big = || Error::Usage("the mesh is too large to evaluate (over 2^32 block entries)".into());
        let mut local: Vec<u32> = Vec::new();
        for (f, &refused) in refused.iter().enumerate() {
            local.clear();
            for g in 4 * f as u32..4 * f as u32 + 4 {
                let (corner, _) = l1.shape(g);
                if !refused {
                    let start = if corner == REGULAR { 0 } else { u32::from(corner) };
                    walk(&l1.ct, 3 * g + start, |v| {
                        let i = local.iter().position(|&x| x == v).unwrap_or_else(|| {
                            local.push(v);
                            local.len() - 1
                        });
                        // a block holds the rings of three vertices: far
                        // fewer than 2^16 points for any valence a corner
                        // table allows
                        b.index.push(u16::try_from(i).unwrap_or(u16::MAX));
                    });
                }
                b.child_start.push(u32::try_from(b.index.len()).map_err(|_| too_big())?);
                b.corner.push(corner);
            }
            b.pos.extend(local.iter().map(|&v| l1.pos[v as usize]));
            b.face_start.push(u32::try_from(b.pos.len()).map_err(|_| too_big())?);
        }
        Ok(b)
    }

    /// Level-1 face `g`'s extraordinary corner ([`REGULAR`] if none) and its
    /// support size.
    #[inline]
    pub(crate) fn shape(&self, g: u32) -> (u8, usize) {
        let g = g as usize;
        (self.corner[g], (self.child_start[g + 1] - self.child_start[g]) as usize)
    }

    /// Writes the support of level-1 face `g` (a child of control face `g /
    /// 4`) to `out`.
    #[inline]
    pub(crate) fn support(&self, g: u32, out: &mut [DVec3]) {
        let g = g as usize;
        let block = &self.pos[self.face_start[g / 4] as usize..self.face_start[g / 4 + 1] as usize];
        let index = &self.index[self.child_start[g] as usize..self.child_start[g + 1] as usize];
        for (o, &i) in out.iter_mut().zip(index) {
            *o = block[usize::from(i)];
        }
    }
}
