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
}
