//! The exact limit at the vertices of a Loop refinement: each vertex of
//! level `L` lies at a dyadic parameter point of a control face, found by
//! following the split's layout down from the control faces (see
//! `src/mesh/split.rs`: the central child keeps its parent's id and has the
//! midpoints of the opposite edges at its corners; the corner child of
//! corner `j` of triangle `t` is triangle `nt (j + 1) + t`, corners
//! `(v_j, mid(j, j+1), mid(j, j+2))`).

use super::{Evaluator, Sample};
use crate::mesh::{CornerTable, Mesh};
use crate::subdiv::{Options, Scheme};
use crate::{Error, Result};

/// The control face and `(u, v)` of every vertex of the level-`levels`
/// table `fine` made from a control mesh of `control_faces` triangles.
pub fn vertex_params(control_faces: usize, fine: &CornerTable, levels: u32) -> Result<Vec<(usize, f64, f64)>> {
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

/// The exact Loop limit (with curvature) at every vertex of `fine`, the
/// Loop refinement of `control` by `levels`; NaN samples where the control
/// face is refused (an interior vertex of valence 2), NaN curvature where
/// it is not defined (an extraordinary vertex itself).
///
/// # Errors
/// A `fine` that is not such a refinement, or the evaluator's errors.
pub fn vertex_samples(control: &Mesh, fine: &Mesh, levels: u32, opts: &Options) -> Result<Vec<Sample>> {
    let ev = Evaluator::new(control, Scheme::Loop, opts)?;
    let params = vertex_params(control.ct.num_triangles(), &fine.ct, levels)?;
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
