//! Stencil plans of the polygon schemes (Catmull-Clark, bilinear): each
//! level's rows recorded from the same masks the one-shot refinement
//! evaluates ([`crate::subdiv::rules::catmull_clark`], blended at sharp
//! features by [`crate::subdiv::rules::crease`]), in the refinement's vertex
//! order: old vertices, then one point per edge (owner order), then one per
//! face. The rows of the smooth masks name a vertex once per face point it
//! reaches through; [`merge_tail`] folds those into one entry each, so a
//! regular Catmull-Clark vertex row has 9 entries, not 21.

use super::rows::LevelPlan;
use crate::mesh::Creasing;
use crate::mesh::poly::{PolyTable, split};
use crate::subdiv::rules::catmull_clark::{Bilinear, CatmullClark, PolyLevel, PolyOn, PolyRules, face_point};
use crate::subdiv::rules::crease::{edge_stencil, vertex_stencil};
use crate::subdiv::rules::features::Features;
use crate::subdiv::rules::{Record, Weight};
use crate::subdiv::{Options, Scheme};

/// One Catmull-Clark level recorded on `pt` as it is (its boundary corners
/// already applied) and the split table it makes: the local subdivision of
/// exact evaluation runs the very rules the refinement runs.
pub(crate) fn record_one_catmark_level(pt: &PolyTable, opts: &Options) -> (LevelPlan, PolyTable) {
    let r = CatmullClark::new(opts);
    (record_level(&r, pt, opts.creasing, None), split::split(pt, opts.creasing).0)
}

/// The rows of one level of polygon `scheme` on `pt` (its boundary corners
/// already applied), weights of type `W`.
pub(crate) fn record_poly_level<W: Weight + std::ops::AddAssign>(
    pt: &PolyTable,
    scheme: Scheme,
    opts: &Options,
    only: Option<&[u32]>,
) -> LevelPlan<W> {
    match scheme {
        Scheme::Bilinear => record_level(&Bilinear, pt, opts.creasing, only),
        _ => record_level(&CatmullClark::new(opts), pt, opts.creasing, only),
    }
}

/// One level's rows: a vertex row per old vertex (omitted where `R` keeps
/// the old vertices: bilinear), an edge row per edge in owner order, a face
/// row per face.
fn record_level<R: PolyRules, W: Weight + std::ops::AddAssign>(
    r: &R,
    pt: &PolyTable,
    creasing: Creasing,
    only: Option<&[u32]>,
) -> LevelPlan<W> {
    let features = if R::SMOOTH { Features::of(pt, creasing) } else { None };
    let lv = PolyLevel { pt, features: features.as_ref() };
    let on = PolyOn { r, lv: &lv };
    let owners: Vec<u32> = pt.edge_owners().collect();
    let (nv, ne) = (pt.num_vertices(), owners.len());
    let first = if R::SMOOTH { 0 } else { nv };
    let row = |i: usize, rec: &mut Record<W>| {
        let start = rec.idx.len();
        let i = first + i;
        if i < nv {
            vertex_stencil(&on, i as u32, rec);
        } else if i < nv + ne {
            edge_stencil(&on, owners[i - nv], rec);
        } else {
            face_point(pt, (i - nv - ne) as u32, 1.0, rec);
        }
        merge_tail(rec, start);
    };
    let (offsets, indices, weights) = match only {
        // row i is new vertex first + i
        Some(ids) => super::plan::record_rows(ids.len(), |k, rec| row(ids[k] as usize - first, rec)),
        None => super::plan::record_rows(nv + ne + pt.num_faces() - first, row),
    };
    LevelPlan { n_in: nv, copy_vertices: !R::SMOOTH, offsets, indices, weights }
}

/// Folds the entries of `rec` from `start` on that name the same vertex into
/// the first of them (weights summed in the order they were emitted), keeping
/// the order of first appearance.
fn merge_tail<W: Weight + std::ops::AddAssign>(rec: &mut Record<W>, start: usize) {
    let mut end = start;
    for k in start..rec.idx.len() {
        let (v, w) = (rec.idx[k], rec.w[k]);
        match rec.idx[start..end].iter().position(|&u| u == v) {
            Some(j) => rec.w[start + j] += w,
            None => {
                rec.idx[end] = v;
                rec.w[end] = w;
                end += 1;
            }
        }
    }
    rec.idx.truncate(end);
    rec.w.truncate(end);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merge_tail_sums_repeated_vertices_in_emission_order() {
        let mut rec = Record { idx: vec![9, 1, 2, 1, 3, 2, 1], w: vec![5.0, 0.5, 0.25, 0.125, 1.0, 0.25, 0.0625] };
        merge_tail(&mut rec, 1);
        assert_eq!(rec.idx, [9, 1, 2, 3]);
        assert_eq!(rec.w, [5.0, 0.5 + 0.125 + 0.0625, 0.5, 1.0]);
    }
}
