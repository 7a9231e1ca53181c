//! The exact limit at the vertices of a refinement: each vertex of level
//! `L` lies at a dyadic parameter point of a control face, found by
//! following the split's layout down from the control faces.
//!
//! Loop (`src/mesh/split.rs`): the central child keeps its parent's id and
//! has the midpoints of the opposite edges at its corners; the corner child
//! of corner `j` of triangle `t` is triangle `nt (j + 1) + t`, corners
//! `(v_j, mid(j, j+1), mid(j, j+2))`.
//!
//! Catmull-Clark (`src/mesh/poly/split.rs`): corner `c` of a level becomes
//! quad `c` of the next, corners `(V[c], the edge leaving c, the face
//! point, the edge entering c)`. A control quad is one ptex face, the unit
//! square with its corners `0 1 2 3` at `(0,0) (1,0) (1,1) (0,1)`; corner
//! `k` of a face of another size is the ptex face of its level-1 quad, whose
//! corners are the square's in that order (`catmark.rs`). From level 1 on
//! every face is a quad: quad `q` of level `L` came from corner `q % 4` of
//! quad `q / 4` of level `L - 1`, so the base-4 digits of `q` are its path
//! down from the level-1 quad of control corner `q / 4^(L-1)`.

use super::{Evaluator, Sample};
use crate::mesh::poly::{PolyMesh, PolyTable};
use crate::mesh::{CornerTable, Mesh};
use crate::subdiv::{Options, Scheme};
use crate::{Error, Result};
use rayon::prelude::*;

/// The control face and `(u, v)` of every vertex of the level-`levels`
/// table `fine` made from a control mesh of `control_faces` triangles.
pub(crate) fn vertex_params(control_faces: usize, fine: &CornerTable, levels: u32) -> Result<Vec<(usize, f64, f64)>> {
    let expect = control_faces.saturating_mul(1usize << (2 * levels.min(30)));
    if fine.num_triangles() != expect {
        return Err(Error::Usage(format!(
            "{} triangles are not {levels} levels of {control_faces} control faces",
            fine.num_triangles()
        )));
    }
    let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    let mut tris: Vec<(u32, [[f64; 2]; 3])> =
        (0..control_faces as u32).map(|f| (f, [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])).collect();
    for _ in 0..levels {
        let nt = tris.len();
        let mut next = vec![(0, [[0.0; 2]; 3]); 4 * nt];
        for (t, &(f, c)) in tris.iter().enumerate() {
            next[t] = (f, [mid(c[1], c[2]), mid(c[2], c[0]), mid(c[0], c[1])]);
            for j in 0..3 {
                next[nt * (j + 1) + t] = (f, [c[j], mid(c[j], c[(j + 1) % 3]), mid(c[j], c[(j + 2) % 3])]);
            }
        }
        tris = next;
    }
    let mut out = vec![(usize::MAX, 0.0, 0.0); fine.num_vertices()];
    for (t, &(f, c)) in tris.iter().enumerate() {
        for (j, uv) in c.iter().enumerate() {
            let v = fine.vtx(3 * t as u32 + j as u32) as usize;
            if out[v].0 == usize::MAX {
                out[v] = (f as usize, uv[0], uv[1]);
            }
        }
    }
    Ok(out)
}

/// The unit square's corners in a quad's corner order.
const SQUARE: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

/// The corners of the child quad of corner `k` of the quad `a` (module
/// docs): its corner, the midpoint of the edge leaving it, the centre, the
/// midpoint of the edge entering it.
fn child(a: &[[f64; 2]; 4], k: usize) -> [[f64; 2]; 4] {
    let mid = |p: [f64; 2], q: [f64; 2]| [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
    let centre = mid(mid(a[0], a[2]), mid(a[1], a[3]));
    [a[k], mid(a[k], a[(k + 1) % 4]), centre, mid(a[(k + 3) % 4], a[k])]
}

/// The ptex face and `(u, v)` of every vertex of `fine`, the
/// triangulated level `levels` of the Catmull-Clark (or bilinear) quad
/// split of the control polygons `control` (module docs); the ptex faces
/// are [`super::catmark::ptex_faces`]'s. `fine` from level 1 on lists quad
/// `q` as its triangles `2q` (corners 0, 1, 2) and `2q + 1` (0, 2, 3), as
/// [`PolyTable::triangulated`] writes them; at level 0 its vertices are the
/// control polygons'.
///
/// # Errors
/// A `fine` that is not such a level.
pub fn poly_vertex_params(control: &PolyTable, fine: &CornerTable, levels: u32) -> Result<Vec<(usize, f64, f64)>> {
    let mismatch = || {
        Error::Usage(format!(
            "{} triangles of {} vertices are not {levels} quad splits of {} polygons",
            fine.num_triangles(),
            fine.num_vertices(),
            control.num_faces()
        ))
    };
    // each face's first ptex face
    let mut first = Vec::with_capacity(control.num_faces());
    let mut p = 0usize;
    for f in 0..control.num_faces() as u32 {
        first.push(p);
        p += match control.face_size(f) {
            4 => 1,
            n => n as usize,
        };
    }
    // the ptex face and corners of the level-1 quad of control corner c,
    // or at level 0 the corner's own ptex face and point
    let of_corner = |c: u32| {
        let f = control.face(c);
        let k = (c - control.face_corners(f).start) as usize;
        match control.face_size(f) {
            4 => (first[f as usize], k, child(&SQUARE, k)),
            _ => (first[f as usize] + k, 0, SQUARE),
        }
    };
    if levels == 0 {
        if fine.num_vertices() != control.num_vertices() {
            return Err(mismatch());
        }
        return Ok((0..control.num_vertices() as u32)
            .map(|v| {
                let (p, k, _) = of_corner(control.corner_of(v));
                (p, SQUARE[k][0], SQUARE[k][1])
            })
            .collect());
    }
    let quads = control.num_corners().checked_mul(1usize.checked_shl(2 * (levels - 1)).unwrap_or(0));
    if quads.is_none_or(|q| q == 0 || fine.num_triangles() != 2 * q) {
        return Err(mismatch());
    }
    let quads = quads.unwrap_or(0);
    // every quad's ptex face and corners, from its path (in parallel),
    // then its four vertices in quad order
    let params: Vec<(usize, [[f64; 2]; 4])> = (0..quads)
        .into_par_iter()
        .with_min_len(4096)
        .map(|q| {
            let depth = 2 * (levels - 1);
            let (p, _, mut a) = of_corner((q >> depth) as u32);
            for level in (0..levels - 1).rev() {
                a = child(&a, (q >> (2 * level)) & 3);
            }
            (p, a)
        })
        .collect();
    let mut out = vec![(usize::MAX, 0.0, 0.0); fine.num_vertices()];
    for (q, &(p, a)) in params.iter().enumerate() {
        let t = 6 * q as u32;
        for (corner, uv) in [t, t + 1, t + 2, t + 5].into_iter().zip(a) {
            let v = fine.vtx(corner) as usize;
            if out[v].0 == usize::MAX {
                out[v] = (p, uv[0], uv[1]);
            }
        }
    }
    if out.iter().any(|x| x.0 == usize::MAX) {
        return Err(mismatch());
    }
    Ok(out)
}

/// The exact limit (with curvature) at every vertex of `fine`, the
/// refinement of `control` by `levels` of `scheme`: Loop's (its triangle
/// split, `fine` as [`crate::subdivide`] makes it) or Catmull-Clark's (the
/// quad split of the polygons `control` stands for, triangulated as
/// [`crate::subdivide`] gives it). NaN samples where the control face is
/// refused (Loop: an interior vertex of valence 2), NaN curvature where it
/// is not defined (an extraordinary vertex itself, an irregular vertex on a
/// sharp feature).
///
/// # Errors
/// A `fine` that is not such a refinement, a scheme without an exact limit
/// (the evaluator's refusal), or the evaluator's errors.
pub fn vertex_samples(control: &Mesh, fine: &Mesh, scheme: Scheme, levels: u32, opts: &Options) -> Result<Vec<Sample>> {
    let (ev, params) = match scheme {
        Scheme::CatmullClark => {
            let poly = PolyMesh::from_mesh(control);
            let params = poly_vertex_params(&poly.pt, &fine.ct, levels)?;
            (Evaluator::new_poly(&poly, scheme, opts)?, params)
        }
        _ => {
            let ev = Evaluator::new(control, scheme, opts)?;
            (ev, vertex_params(control.ct.num_triangles(), &fine.ct, levels)?)
        }
    };
    // the batch call, which shares each child's patch between its points,
    // on the accepted ones
    let (kept, points): (Vec<usize>, Vec<(usize, f64, f64)>) =
        params.iter().enumerate().filter(|(_, p)| ev.accepts(p.0)).map(|(i, &p)| (i, p)).unzip();
    let samples = ev.eval_all(&points, true)?;
    let mut out = vec![Sample::NAN; params.len()];
    for (i, s) in kept.into_iter().zip(samples) {
        out[i] = s;
    }
    Ok(out)
}
