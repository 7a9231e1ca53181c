//! Catmull-Clark limit positions and tangents (OpenSubdiv 3.5
//! `sdc/catmarkScheme.h`, `assign*LimitMask` and `assign*LimitTangentMasks`;
//! docs/schemes.md §12.4).
//!
//! The masks read a vertex's 1-ring on an all-quad level: its edges'
//! other ends `e_i` and, for each face, the vertex opposite it `f_i`, in
//! fan order (counter-clockwise about the normal, face `i` between edges `i`
//! and `i + 1`; on the boundary edge 0 and the last edge are the border).
//!
//! ```text
//! smooth, valence n:
//!   position  v (1 - n (e + f)) + e sum e_i + f sum f_i,   f = 1/(n(n+5)), e = 4f
//!             regular: 4/9 v + 1/9 sum e_i + 1/36 sum f_i
//!   tan1      e_i: 4 cos(i t),  f_i: (cos(i t) + cos((i+1) t)) / (4 l - 1),  v: 0
//!             t = 2 pi / n,  l = 5/16 + (cos t + cos(t/2) sqrt(2 (9 + cos t))) / 16
//!             regular: 4 (e_0 - e_2) + f_0 - f_1 - f_2 + f_3
//!   tan2      tan1's weights moved one place on (e_i takes tan1's e_{i-1})
//!   valence 2: the corner masks
//! crease through e_a, e_b (a < b in fan order; the border's two edges on
//! the boundary):
//!   position  2/3 v + 1/6 (e_a + e_b)
//!   tan1      (e_a - e_b) / 2
//!   tan2      across the faces from a to b, k = b - a:
//!             k = 1: -6 v + 3 e_a + 3 e_b
//!             k = 2: -4/6 v - 1/6 (e_a + e_b) + 4/6 e_{a+1} + 1/6 (f_a + f_{a+1})
//!             k > 2 (Biermann, Levin, Zorin 2000), s = pi / k, d = 1/(k (3 + cos s)),
//!               R = (cos s + 1) / sin s:
//!               v: 4 R (cos s - 1) d,  e_a, e_b: -R (1 + 2 cos s) d,
//!               e_{a+i}: 4 sin(i s) d,  f_{a+i}: (sin(i s) + sin((i+1) s)) d
//! corner:
//!   position  v;   tan1 = e_0 - v,   tan2 = e_1 - v
//! dart (one infinitely sharp edge): the smooth tangents (as OpenSubdiv);
//!   the position by the dart's own eigenvector (`dart_position`), where
//!   OpenSubdiv takes the smooth mask (8e-4 off on the dart fixture)
//! ```
//! The rule is the vertex's at the level the masks read (an edge still
//! semi-sharp there counts as sharp, as in OpenSubdiv's `Limit`; a dart
//! whose edge is semi-sharp takes the smooth mask); [`limit_frames`]
//! refines first until every face is a quad and no semi-sharp feature is
//! left, so its positions are the limit surface's.
//! `tan1 x tan2` points to the side the faces' normals do.

use crate::mesh::Creasing;
use crate::mesh::edges::EdgeTable;
use crate::mesh::poly::{PolyMesh, PolyTable};
use crate::mesh::sharpness::INFINITE;
use crate::subdiv::rules::features::{Features, Mask, Rule};
use crate::subdiv::{Options, Scheme};
use crate::{Error, Result};
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use std::f64::consts::PI;

/// A point of the limit surface and two tangents there (scaled as
/// OpenSubdiv scales them; `tan1 x tan2` is along the normal).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LimitFrame {
    /// The limit position.
    pub position: Vec3,
    /// The first tangent.
    pub tan1: Vec3,
    /// The second tangent.
    pub tan2: Vec3,
}

impl LimitFrame {
    /// The unit normal `tan1 x tan2` (zero where the tangents are parallel).
    pub fn normal(&self) -> Vec3 {
        self.tan1.cross(self.tan2).normalize_or_zero()
    }
}

/// The limit frames of every vertex of `mesh` (same ids), through as many
/// Catmull-Clark levels as it takes for every face to be a quad and every
/// semi-sharp feature to have decayed (at most 8; beyond, and where a
/// level does not fit in memory, what is left counts as sharp).
///
/// # Errors
/// None in practice: levels that do not fit are skipped, not refused.
pub fn limit_frames(mesh: &PolyMesh, opts: &Options) -> Result<Vec<LimitFrame>> {
    let nv = mesh.positions.len();
    // old vertices keep their ids through the levels; with none, the control
    // level's one-face corners are tagged as the option says
    let (fine, points) = refined_for_limit(mesh, &mesh.positions, opts)?;
    let frames = frames_at(&fine, &points, opts.creasing);
    Ok(frames.into_iter().take(nv).collect())
}

/// The limit positions of [`limit_frames`] from the f64 control points
/// `control` (one per vertex of `mesh`, e.g. a file's own digits): the
/// levels refined with the rules' f64 weights, the masks applied in f64.
///
/// # Errors
/// `control` not one point per vertex of `mesh`.
pub fn limit_positions_f64(mesh: &PolyMesh, control: &[DVec3], opts: &Options) -> Result<Vec<DVec3>> {
    let nv = mesh.positions.len();
    if control.len() != nv {
        return Err(Error::Usage(format!("{} control points for {nv} vertices", control.len())));
    }
    let (fine, pos) = refined_for_limit(mesh, control, opts)?;
    let masks = masks_at(&fine, opts.creasing, &|i| pos[i as usize]);
    Ok(masks.into_iter().take(nv).map(|m| m.map_or(DVec3::ZERO, |(p, _, _)| p)).collect())
}

/// The levels the limit masks need on `mesh` (every face a quad, every
/// semi-sharp feature decayed, at most 8; fewer where they do not fit in
/// memory), made by the level builder from the points `control`: the
/// finest table (the tagged control table for none) and its points.
///
/// # Errors
/// As the builder's.
fn refined_for_limit<P: crate::subdiv::rules::Coord>(
    mesh: &PolyMesh,
    control: &[P],
    opts: &Options,
) -> Result<(PolyTable, Vec<P>)> {
    use crate::subdiv::refine::build::{Keep, Table, build, check};
    let mut levels = semi_sharp_levels(&mesh.pt).min(8);
    if !mesh.pt.is_quads() {
        levels = levels.max(1);
    }
    let limit = opts.max_memory.or_else(crate::mem::default_memory_limit);
    while levels > 0 && check(mesh.pt.counts(), true, levels, limit, false).is_err() {
        levels -= 1;
    }
    let mut b = build(&mesh.pt, control, (Scheme::CatmullClark, levels, opts), Keep::Finest, &mut |_, _| true)?;
    Ok((b.fine, b.points.pop().unwrap_or_default()))
}

/// Levels until the sharpest semi-sharp edge or vertex has decayed.
fn semi_sharp_levels(pt: &PolyTable) -> u32 {
    let Some(s) = pt.sharpness() else { return 0 };
    let semi = s.sharp_corners().iter().chain(s.sharp_vertices()).map(|&(_, x)| x).filter(|&x| x < INFINITE);
    semi.fold(0.0f32, f32::max).ceil() as u32
}

/// The masks' frames of every vertex of an all-quad level, its rules taken
/// at this level. Vertices on a face of another size get zeros.
pub fn frames_at(pt: &PolyTable, pos: &[Vec3], creasing: Creasing) -> Vec<LimitFrame> {
    let masks = masks_at(pt, creasing, &|i| pos[i as usize].as_dvec3());
    masks.into_iter().map(|m| m.map_or_else(LimitFrame::default, to_frame)).collect()
}

/// The masks' position and tangents in f64 at every vertex of an all-quad
/// level whose points `p` gives; `None` at a vertex with a face of another
/// size.
fn masks_at(pt: &PolyTable, creasing: Creasing, p: &(dyn Fn(u32) -> DVec3 + Sync)) -> Vec<Option<Masks>> {
    let features = Features::of(pt, creasing);
    (0..pt.num_vertices() as u32)
        .into_par_iter()
        .with_min_len(2048)
        .map_init(Ring::default, |ring, v| {
            ring.gather(pt, v, pt.corner_of(v)).then(|| ring.masks(pt, p, rule(pt, features.as_ref(), v)))
        })
        .collect()
}

/// A limit position and its two tangents, in f64.
type Masks = (DVec3, DVec3, DVec3);

/// The f32 frame of `masks`.
fn to_frame((position, tan1, tan2): Masks) -> LimitFrame {
    LimitFrame { position: position.as_vec3(), tan1: tan1.as_vec3(), tan2: tan2.as_vec3() }
}

/// The frame of vertex `v` with its fan started at corner `first` (one of
/// `v`'s corners; on the boundary the fan always starts at the border):
/// where edge 0 falls decides the tangents' frame, as in OpenSubdiv,
/// though not the normal. `None` when a face at `v` is not a quad.
pub fn frame_from(pt: &PolyTable, pos: &[Vec3], creasing: Creasing, v: u32, first: u32) -> Option<LimitFrame> {
    let features = Features::of(pt, creasing);
    let mut ring = Ring::default();
    let start = if pt.is_boundary_vertex(v) { pt.corner_of(v) } else { first };
    let p = |i: u32| pos[i as usize].as_dvec3();
    ring.gather(pt, v, start).then(|| to_frame(ring.masks(pt, &p, rule(pt, features.as_ref(), v))))
}

/// The limit rule of a vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
enum LimitRule {
    /// The smooth masks.
    Smooth,
    /// One sharp edge: the smooth tangents, the position by the dart's
    /// own eigenvector ([`dart_position`]).
    Dart,
    /// The crease through these two neighbours.
    Crease(u32, u32),
    /// The corner masks.
    Corner,
}

/// The limit rule of `v`: its features' at this level, else the border's
/// crease, else smooth.
fn rule(pt: &PolyTable, f: Option<&Features>, v: u32) -> LimitRule {
    match f.and_then(|f| f.vertex(v)) {
        Some(vf) if vf.rule == Rule::Dart => LimitRule::Dart,
        Some(vf) => match vf.parent {
            Mask::Smooth => LimitRule::Smooth,
            Mask::Crease(a, b) => LimitRule::Crease(a, b),
            Mask::Corner => LimitRule::Corner,
        },
        None if pt.is_boundary_vertex(v) => {
            let first = pt.corner_of(v);
            let last = pt.fan(v).last().unwrap_or(first);
            LimitRule::Crease(pt.vtx(pt.next(first)), pt.vtx(pt.prev(last)))
        }
        None => LimitRule::Smooth,
    }
}

/// A vertex's 1-ring in fan order.
#[derive(Default)]
struct Ring {
    v: u32,
    boundary: bool,
    /// Other ends of the edges (one more than the faces on the boundary).
    e: Vec<u32>,
    /// The vertex across each face.
    f: Vec<u32>,
}

impl Ring {
    /// Fills the ring of `v` from corner `start`; false where a face at `v`
    /// is not a quad.
    fn gather(&mut self, pt: &PolyTable, v: u32, start: u32) -> bool {
        self.v = v;
        self.e.clear();
        self.f.clear();
        let mut c = start;
        loop {
            if pt.face_size(pt.face(c)) != 4 {
                return false;
            }
            self.e.push(pt.vtx(pt.next(c)));
            self.f.push(pt.vtx(pt.next(pt.next(c))));
            match pt.swing(c) {
                Some(x) if x != start => c = x,
                Some(_) => break,
                None => {
                    // the border edge entering the last corner
                    self.e.push(pt.vtx(pt.prev(c)));
                    break;
                }
            }
        }
        self.boundary = self.e.len() > self.f.len();
        true
    }

    /// The masks for `rule` (the vertex's), the level's points from `p`.
    fn masks(&self, pt: &PolyTable, p: &(dyn Fn(u32) -> DVec3 + Sync), rule: LimitRule) -> Masks {
        let v = p(self.v);
        let e: Vec<DVec3> = self.e.iter().map(|&i| p(i)).collect();
        let f: Vec<DVec3> = self.f.iter().map(|&i| p(i)).collect();
        let smooth_like = self.f.len() > 2 && !self.boundary;
        match rule {
            LimitRule::Smooth if smooth_like => smooth(v, &e, &f),
            LimitRule::Dart if smooth_like => {
                let (_, tan1, tan2) = smooth(v, &e, &f);
                // a semi-sharp dart edge decays: the smooth mask is nearer
                let sharp = |x: &u32| pt.edge_between(self.v, *x).is_some_and(|c| pt.edge_sharpness(c) >= INFINITE);
                let d = self.e.iter().position(sharp);
                (d.map_or_else(|| smooth(v, &e, &f).0, |d| dart_position(v, &e, &f, d)), tan1, tan2)
            }
            LimitRule::Crease(a, b) => {
                let ia = self.e.iter().position(|&x| x == a);
                let ib = self.e.iter().position(|&x| x == b);
                match (ia, ib) {
                    (Some(ia), Some(ib)) => crease_frame(v, &e, &f, ia.min(ib), ia.max(ib)),
                    _ => corner(v, &e),
                }
            }
            _ => corner(v, &e),
        }
    }
}

/// The limit position of a dart: the left eigenvector of eigenvalue 1 of
/// its 1-ring's subdivision matrix, found by iterating the rules on the
/// weights. OpenSubdiv gives a dart the smooth mask, which is not this
/// eigenvector (the dart's edge takes the crease rule, so the ring
/// refines differently): off by 8e-4 on a unit grid. The ring `(v, e_i,
/// f_i)` maps to itself under one level: `v' = (n-2)/n v + 1/n^2 sum e_j +
/// 1/n^2 sum F_j`, `e_i' = (v + e_i + F_{i-1} + F_i) / 4` (the dart's edge
/// `d`: `(v + e_d) / 2`), `f_i' = F_i`, with the face points
/// `F_i = (v + e_i + f_i + e_{i+1}) / 4`.
fn dart_position(v: DVec3, e: &[DVec3], f: &[DVec3], d: usize) -> DVec3 {
    let n = e.len();
    let nf = n as f64;
    // rows of S: index 0 = v, 1 + i = e_i, 1 + n + i = f_i
    let mut s = vec![vec![0.0f64; 1 + 2 * n]; 1 + 2 * n];
    let face = |row: &mut [f64], i: usize, w: f64| {
        row[0] += w / 4.0;
        row[1 + i] += w / 4.0;
        row[1 + (i + 1) % n] += w / 4.0;
        row[1 + n + i] += w / 4.0;
    };
    s[0][0] = (nf - 2.0) / nf;
    for j in 0..n {
        s[0][1 + j] += 1.0 / (nf * nf);
        let row = &mut s[0];
        face(row, j, 1.0 / (nf * nf));
    }
    for i in 0..n {
        let row = &mut s[1 + i];
        row[0] += if i == d { 0.5 } else { 0.25 };
        row[1 + i] += if i == d { 0.5 } else { 0.25 };
        if i != d {
            face(row, (i + n - 1) % n, 0.25);
            face(row, i, 0.25);
        }
        face(&mut s[1 + n + i], i, 1.0);
    }
    // l S = l from the smooth mask on: the other eigenvalues are below 1
    let (fw, ew) = (1.0 / (nf * (nf + 5.0)), 4.0 / (nf * (nf + 5.0)));
    let mut l: Vec<f64> = std::iter::once(1.0 - nf * (ew + fw))
        .chain(std::iter::repeat_n(ew, n))
        .chain(std::iter::repeat_n(fw, n))
        .collect();
    let mut next = vec![0.0; l.len()];
    for _ in 0..400 {
        next.iter_mut().for_each(|x| *x = 0.0);
        for (r, row) in s.iter().enumerate() {
            for (c, &w) in row.iter().enumerate() {
                next[c] += l[r] * w;
            }
        }
        let change = l.iter().zip(&next).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        std::mem::swap(&mut l, &mut next);
        if change < 1e-15 {
            break;
        }
    }
    v * l[0]
        + e.iter().zip(&l[1..=n]).map(|(p, w)| *p * *w).sum::<DVec3>()
        + f.iter().zip(&l[1 + n..]).map(|(p, w)| *p * *w).sum::<DVec3>()
}

/// The corner masks: the vertex, and its first two edges.
fn corner(v: DVec3, e: &[DVec3]) -> (DVec3, DVec3, DVec3) {
    (v, e[0] - v, e[1 % e.len()] - v)
}

/// The smooth masks at an interior vertex of valence `n = e.len() >= 3`.
fn smooth(v: DVec3, e: &[DVec3], f: &[DVec3]) -> (DVec3, DVec3, DVec3) {
    let n = e.len();
    let nf = n as f64;
    let (fw, ew) = if n == 4 { (1.0 / 36.0, 1.0 / 9.0) } else { (1.0 / (nf * (nf + 5.0)), 4.0 / (nf * (nf + 5.0))) };
    let sum_e: DVec3 = e.iter().sum();
    let sum_f: DVec3 = f.iter().sum();
    let position = v * (1.0 - nf * (ew + fw)) + sum_e * ew + sum_f * fw;
    let (we, wf) = smooth_tangent_weights(n);
    let mut tan1 = DVec3::ZERO;
    let mut tan2 = DVec3::ZERO;
    for i in 0..n {
        tan1 += e[i] * we[i] + f[i] * wf[i];
        // tan2's weight at i is tan1's at i - 1
        let j = (i + n - 1) % n;
        tan2 += e[i] * we[j] + f[i] * wf[j];
    }
    (position, tan1, tan2)
}

/// tan1's edge and face weights at an interior vertex of valence `n`.
pub(crate) fn smooth_tangent_weights(n: usize) -> (Vec<f64>, Vec<f64>) {
    if n == 4 {
        return (vec![4.0, 0.0, -4.0, 0.0], vec![1.0, -1.0, -1.0, 1.0]);
    }
    let t = 2.0 * PI / n as f64;
    let lambda = 5.0 / 16.0 + (t.cos() + (t * 0.5).cos() * (2.0 * (9.0 + t.cos())).sqrt()) / 16.0;
    let face_scale = 1.0 / (4.0 * lambda - 1.0);
    let we = (0..n).map(|i| 4.0 * (i as f64 * t).cos()).collect();
    let wf = (0..n).map(|i| face_scale * ((i as f64 * t).cos() + ((i + 1) as f64 * t).cos())).collect();
    (we, wf)
}

/// The crease masks for the crease through edges `a < b`.
pub(crate) fn crease_frame(v: DVec3, e: &[DVec3], f: &[DVec3], a: usize, b: usize) -> (DVec3, DVec3, DVec3) {
    let position = v * (2.0 / 3.0) + (e[a] + e[b]) * (1.0 / 6.0);
    let tan1 = (e[a] - e[b]) * 0.5;
    let (wv, we, wf) = crease_across_weights(b - a);
    let mut tan2 = v * wv;
    for (i, &w) in we.iter().enumerate() {
        tan2 += e[a + i] * w;
    }
    for (i, &w) in wf.iter().enumerate() {
        tan2 += f[a + i] * w;
    }
    (position, tan1, tan2)
}

/// The across-crease tangent's weights for a span of `k` faces: the
/// vertex's, the edges' `a ..= a + k`, the faces' `a .. a + k`.
pub(crate) fn crease_across_weights(k: usize) -> (f64, Vec<f64>, Vec<f64>) {
    match k {
        0 | 1 => (-6.0, vec![3.0, 3.0], vec![0.0]),
        2 => (-4.0 / 6.0, vec![-1.0 / 6.0, 4.0 / 6.0, -1.0 / 6.0], vec![1.0 / 6.0, 1.0 / 6.0]),
        _ => {
            let kf = k as f64;
            let s = PI / kf;
            let d = 1.0 / (kf * (3.0 + s.cos()));
            let r = (s.cos() + 1.0) / s.sin();
            let mut we = vec![0.0; k + 1];
            we[0] = -r * (1.0 + 2.0 * s.cos()) * d;
            we[k] = we[0];
            for (i, w) in we.iter_mut().enumerate().take(k).skip(1) {
                *w = 4.0 * (i as f64 * s).sin() * d;
            }
            let wf = (0..k).map(|i| ((i as f64 * s).sin() + ((i + 1) as f64 * s).sin()) * d).collect();
            (4.0 * r * (s.cos() - 1.0) * d, we, wf)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every position mask sums to 1 and every tangent mask to 0 (affine
    /// invariance), for valences 3 to 12 and crease spans 1 to 8.
    #[test]
    fn masks_sum_to_one_and_zero() {
        for n in 3..=12 {
            let (we, wf) = smooth_tangent_weights(n);
            let total: f64 = we.iter().chain(&wf).sum();
            assert!(total.abs() < 1e-12, "valence {n}: tan1 sums to {total}");
        }
        for k in 1..=8 {
            let (wv, we, wf) = crease_across_weights(k);
            let total: f64 = wv + we.iter().chain(&wf).sum::<f64>();
            assert!(total.abs() < 1e-12, "span {k}: tan2 sums to {total}");
        }
    }
}
