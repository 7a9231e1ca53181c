//! How finely each patch is cut.
//!
//! A flat triangle through three points of a surface `S(u, v)` differs from
//! `S` at the same `(u, v)` by at most `M R^2 / 2`, where `R` is the radius
//! of the smallest circle holding the triangle in `(u, v)` and `M` bounds
//! `|d^2 S / ds^2|` over it along every unit direction `s` of the
//! parameter plane (the error of linear interpolation: Waldron, "The
//! error in linear interpolation at the vertices of a simplex", SIAM J.
//! Numer. Anal. 35, 1998). On the grid of rate `n` every triangle is half
//! a square of side `1/n`, `R^2 = 1 / (2 n^2)`, so `n = ceil(sqrt(M / 4T))`
//! keeps it within `T`. [`initial`] takes `M` from the surface's own
//! second derivatives at a few points of each patch (the largest
//! eigenvalue of `[[|S_uu|, |S_uv|], [|S_uv|, |S_vv|]]`), which samples
//! `M` rather than bounds it; [`measure`] then checks every triangle
//! (against the limit at the same `(u, v)`, or, where that is over `T`,
//! against a nearer point of the limit, [`nearer`]: a distance to a point
//! of the surface either way, so at least the distance to the surface), and
//! [`refine`] makes finer the patches where one is over `T` (by the
//! factor the `n^-2` law asks for), until none is.

use super::domain::{Domain, Patch};
use super::{Built, grid};
use crate::subdiv::eval::{Evaluator, Sample};
use crate::{Error, Result};
use glam::DVec3;

/// The finest interior rate a patch may take.
pub(super) const MAX_RATE: u32 = 1 << 12;

/// Where the second derivatives are sampled: on a triangle its centre,
/// three points towards its corners and its edges' midpoints; on a square
/// a 3 x 3 grid.
const TRI_SAMPLES: [(f64, f64); 7] = [
    (1.0 / 3.0, 1.0 / 3.0),
    (1.0 / 6.0, 1.0 / 6.0),
    (2.0 / 3.0, 1.0 / 6.0),
    (1.0 / 6.0, 2.0 / 3.0),
    (0.5, 0.0),
    (0.5, 0.5),
    (0.0, 0.5),
];
const QUAD_SAMPLES: [f64; 3] = [1.0 / 6.0, 0.5, 5.0 / 6.0];

/// The largest second derivative of `s` along a unit direction, bounded by
/// the matrix of the norms of `S_uu`, `S_uv`, `S_vv` (0 where the surface
/// has none, at an extraordinary vertex itself).
fn second(s: &Sample) -> f64 {
    let (a, b, c) = (s.duu.length(), s.duv.length(), s.dvv.length());
    let m = 0.5 * (a + c) + (0.25 * (a - c) * (a - c) + b * b).sqrt();
    if m.is_finite() { m } else { 0.0 }
}

/// The rate for a second derivative `m` and tolerance `t` (infinite for
/// a patch out of the view: rate 1).
fn rate_for(m: f64, t: f64) -> u32 {
    if t == f64::INFINITY {
        return 1;
    }
    let n = (m / (4.0 * t)).sqrt().ceil();
    if n.is_finite() { (n as u32).clamp(1, MAX_RATE) } else { MAX_RATE }
}

/// The first rates of the patches `which`, from the sampled second
/// derivatives and their tolerances `t` (one per patch of `which`), and
/// the points evaluated for them.
pub(super) fn initial(ev: &Evaluator, domain: &Domain, t: &[f64], which: &[usize]) -> Result<(Vec<u32>, u64)> {
    let mut at = Vec::new();
    let mut starts = Vec::with_capacity(which.len() + 1);
    for p in which.iter().map(|&p| &domain.patches[p]) {
        starts.push(at.len());
        let f = p.face as usize;
        if p.quad {
            for &v in &QUAD_SAMPLES {
                at.extend(QUAD_SAMPLES.iter().map(|&u| (f, u, v)));
            }
        } else {
            at.extend(TRI_SAMPLES.iter().map(|&(u, v)| (f, u, v)));
        }
    }
    starts.push(at.len());
    let m = ev.eval_map(&at, true, second)?;
    let largest = |w: &[usize]| m[w[0]..w[1]].iter().copied().fold(0.0, f64::max);
    let rates = starts.windows(2).zip(t).map(|(w, &t)| rate_for(largest(w), t)).collect();
    Ok((rates, at.len() as u64))
}

/// Each domain edge's rate: the finest its patches ask for (a half side
/// half its patch's rate).
pub(super) fn edge_rates(domain: &Domain, rate: &[u32]) -> Vec<u32> {
    let mut out = vec![1u32; domain.edges.len()];
    for (p, patch) in domain.patches.iter().enumerate() {
        for side in &patch.sides[..patch.sides()] {
            let want = rate[p].div_ceil(u32::from(side.count)).max(1);
            for &(e, _) in &side.parts[..side.count as usize] {
                out[e as usize] = out[e as usize].max(want);
            }
        }
    }
    out
}

/// Whether every side of `patch` has `n` equal segments.
pub(super) fn is_uniform(patch: &Patch, n: u32, edge_rate: &[u32]) -> bool {
    patch.sides[..patch.sides()].iter().all(|side| {
        side.parts[..side.count as usize].iter().all(|&(e, _)| edge_rate[e as usize] * u32::from(side.count) == n)
    })
}

/// Bytes a triangle of the tessellation holds while it is made and
/// measured (its corners with their `(u, v)`, its share of the vertices,
/// their parameters and positions, the measuring points).
const BYTES_PER_TRIANGLE: u64 = 200;

/// Refuses rates whose triangles (the grids' count; the rings add a
/// little) would not fit in `max_memory` (`None`: 80 % of the available
/// memory).
pub(super) fn check_budget(domain: &Domain, rate: &[u32], max_memory: Option<u64>, t: f64) -> Result<()> {
    let count: u64 = domain.patches.iter().zip(rate).map(|(p, &n)| u64::from(n).pow(2) * (1 + u64::from(p.quad))).sum();
    let limit = max_memory.or_else(crate::mem::default_memory_limit).unwrap_or(u64::MAX);
    let bytes = count.saturating_mul(BYTES_PER_TRIANGLE);
    if bytes > limit {
        return Err(Error::Usage(format!(
            "a tessellation within {t:e} needs about {count} triangles ({} MB), more than the memory limit of {} MB: raise the tolerance or --max-memory",
            bytes >> 20,
            limit >> 20
        )));
    }
    Ok(())
}

/// Triangles measured per batch of evaluations.
const BATCH: usize = 1 << 16;

/// The patches whose triangles differ from the round before's (`before`:
/// its patch and edge rates; `None`: every patch).
pub(super) fn changed(
    domain: &Domain,
    (rate, edge_rate): (&[u32], &[u32]),
    before: Option<(&[u32], &[u32])>,
) -> Vec<bool> {
    let Some((old_rate, old_edge)) = before else {
        return vec![true; domain.patches.len()];
    };
    let moved = |e: u32| edge_rate[e as usize] != old_edge[e as usize];
    domain
        .patches
        .iter()
        .enumerate()
        .map(|(p, patch)| {
            rate[p] != old_rate[p]
                || patch.sides[..patch.sides()]
                    .iter()
                    .any(|s| s.parts[..s.count as usize].iter().any(|&(e, _)| moved(e)))
        })
        .collect()
}

/// The largest distance of each `dirty` patch's triangles from the limit
/// surface, into `worst`: at each triangle's centre and its edges'
/// midpoints, the flat triangle's point against the limit at the same
/// `(u, v)`, or, where that is over the patch's tolerance `t`, against a
/// nearer point of the limit ([`nearer`]). Returns the points evaluated.
pub(super) fn measure(
    ev: &Evaluator,
    (domain, t): (&Domain, &[f64]),
    built: &Built,
    dirty: &[bool],
    worst: &mut [f64],
) -> Result<u64> {
    for (p, w) in worst.iter_mut().enumerate() {
        if dirty[p] {
            *w = 0.0;
        }
    }
    let todo: Vec<&(u32, [grid::Pt; 3])> = built.triangles.iter().filter(|(p, _)| dirty[*p as usize]).collect();
    let mut evaluated = 0;
    for chunk in todo.chunks(BATCH) {
        // an edge inside a patch is measured once for its two triangles
        let mut at = Vec::with_capacity(3 * chunk.len());
        // each measured point's patch
        let mut owner = Vec::with_capacity(3 * chunk.len());
        let mut mids = rustc_hash::FxHashMap::default();
        let mut slots = Vec::with_capacity(chunk.len());
        for (p, [a, b, c]) in chunk.iter().copied() {
            let f = domain.patches[*p as usize].face as usize;
            let (third, centre) = (1.0 / 3.0, at.len());
            at.push((f, (a.uv.0 + b.uv.0 + c.uv.0) * third, (a.uv.1 + b.uv.1 + c.uv.1) * third));
            owner.push(*p);
            let mut mid = |x: &grid::Pt, y: &grid::Pt| {
                *mids.entry((*p, x.id.min(y.id), x.id.max(y.id))).or_insert_with(|| {
                    at.push((f, 0.5 * (x.uv.0 + y.uv.0), 0.5 * (x.uv.1 + y.uv.1)));
                    owner.push(*p);
                    at.len() - 1
                })
            };
            let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
            slots.push([centre, ab, bc, ca]);
        }
        let s = ev.eval_map(&at, false, |s| (s.position, s.du, s.dv))?;
        evaluated += at.len() as u64;
        // each measured point's flat point, and its distance from the limit at its (u, v)
        let mut flat = vec![DVec3::ZERO; at.len()];
        for ((_, [a, b, c]), slot) in chunk.iter().copied().zip(&slots) {
            let x = |pt: &grid::Pt| built.positions[pt.id as usize];
            let (xa, xb, xc) = (x(a), x(b), x(c));
            let points = [(xa + xb + xc) / 3.0, 0.5 * (xa + xb), 0.5 * (xb + xc), 0.5 * (xc + xa)];
            for (i, q) in slot.iter().zip(points) {
                flat[*i] = q;
            }
        }
        let mut error: Vec<f64> = flat.iter().zip(&s).map(|(q, (x, _, _))| q.distance(*x)).collect();
        evaluated += nearer(ev, domain, (&at, &s, &owner), (&flat, &mut error), t)?;
        for ((p, _), slot) in chunk.iter().copied().zip(&slots) {
            let e = slot.iter().map(|&i| error[i]).fold(0.0, f64::max);
            let w = &mut worst[*p as usize];
            *w = w.max(e);
        }
    }
    Ok(evaluated)
}

/// A measured point (control face, `u`, `v`) and the limit there: position
/// and first derivatives.
type Point = (usize, f64, f64);
type Frame = (DVec3, DVec3, DVec3);

/// Where a measured point is over its patch's tolerance, its distance to
/// another point of the limit surface, nearer it: one Newton step from
/// the limit at its own `(u, v)` along the tangent plane (the parameter
/// step whose first-order move is the error's tangential part), kept
/// inside the face. Next to an extraordinary vertex the parameterisation
/// stretches (Catmull-Clark's surface goes as `r^1.29` of the parameter at
/// valence 3), so a flat triangle's point and the limit at the same
/// `(u, v)` lie far apart along the surface while the triangle itself lies
/// close to it. The smaller distance is kept: either is the distance to a
/// point of the surface, so both bound the distance to the surface.
/// Returns the points evaluated.
fn nearer(
    ev: &Evaluator,
    domain: &Domain,
    (at, s, owner): (&[Point], &[Frame], &[u32]),
    (flat, error): (&[DVec3], &mut [f64]),
    t: &[f64],
) -> Result<u64> {
    let (mut again, mut which): (Vec<Point>, Vec<usize>) = (Vec::new(), Vec::new());
    for (i, &(f, u, v)) in at.iter().enumerate() {
        let p = owner[i] as usize;
        let (x, du, dv) = s[i];
        let (g00, g01, g11) = (du.dot(du), du.dot(dv), dv.dot(dv));
        let det = g00 * g11 - g01 * g01;
        // within the tolerance already, or no tangent plane (at an extraordinary vertex itself)
        if error[i] <= t[p] || !(det.is_finite() && det > 1e-12 * g00 * g11) {
            continue;
        }
        let e = flat[i] - x;
        let (r0, r1) = (e.dot(du), e.dot(dv));
        let step = ((g11 * r0 - g01 * r1) / det, (g00 * r1 - g01 * r0) / det);
        let (u, v) = inside(domain.patches[p].quad, (u + step.0, v + step.1));
        again.push((f, u, v));
        which.push(i);
    }
    let moved = ev.eval_map(&again, false, |s| s.position)?;
    for (&i, y) in which.iter().zip(moved) {
        error[i] = error[i].min(flat[i].distance(y));
    }
    Ok(again.len() as u64)
}

/// The point of a patch's face nearest `(u, v)` in the parameter: the unit
/// square, or the triangle `u, v >= 0, u + v <= 1`.
fn inside(quad: bool, (u, v): (f64, f64)) -> (f64, f64) {
    let (u, v) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
    if quad || u + v <= 1.0 {
        return (u, v);
    }
    let over = 0.5 * (u + v - 1.0);
    let (u, v) = (u - over, v - over);
    (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0))
}

/// Makes finer each patch with a triangle over its tolerance `t`: by the
/// factor `sqrt(error / t)` the `n^-2` law asks for, and a little more,
/// and by a quarter at least.
pub(super) fn refine(rate: &mut [u32], errors: &[f64], t: &[f64]) {
    for ((n, &e), &t) in rate.iter_mut().zip(errors).zip(t) {
        if e > t {
            // e > t: the factor is over 1 (infinite for an infinite e: MAX_RATE)
            // and by a quarter at least: a distance measured against the nearer
            // point need not follow the law, and a patch just over t would
            // otherwise creep up one step a round
            let factor = ((e / t).sqrt() * 1.1).max(1.25);
            let grown = (f64::from(*n) * factor).ceil().min(f64::from(MAX_RATE)) as u32;
            *n = grown.max(*n + 1).min(MAX_RATE);
        }
    }
}
