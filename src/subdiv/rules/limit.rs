//! Loop limit positions and exact Loop limit normals ("snap to limit"),
//! docs/schemes.md §6.1-6.3, plus tangent-mask normals for the interpolating
//! butterfly schemes (docs/schemes.md §6.5).
//!
//! Every mask here is a left eigenvector of the local subdivision matrix, so
//! applying it to the control points of ANY level gives the value at the same
//! point of the limit surface (positions: eigenvalue 1) or a vector along the
//! limit tangent (tangents: the subdominant eigenvalues).
//!
//! ## Limit positions (docs/schemes.md §6.1)
//! ```text
//! interior vertex v, valence n, neighbours p_i, Loop's beta(n):
//!     chi   = 1 / (n + 3 / (8 beta))
//!     v_inf = (1 - n chi) v + chi sum p_i
//!     regular (n = 6, beta = 1/16): v_inf = 1/2 v + 1/12 sum p_i
//!     n = 3 (beta = 3/16):          v_inf = 2/5 v + 1/5 sum p_i
//!     Warren's beta: chi = 1/(2n) for every n
//! boundary vertex, boundary neighbours q1, q2 (cubic B-spline limit):
//!     v_inf = 2/3 v + 1/6 (q1 + q2)
//! ```
//! Source: Loop 1987; Hoppe et al. 1994; OpenSubdiv `sdc/loopScheme.h`
//! (`assignSmoothLimitMask`, `assignCreaseLimitMask`, whose comment explains
//! why (1/6, 2/3, 1/6), not (1/5, 3/5, 1/5), matches the (1/2, 1/2) boundary
//! edge rule and (1/8, 3/4, 1/8) boundary vertex rule used by `super::loop_`).
//! Our boundary rule has no corners (a manifold vertex has exactly two border
//! edges; valence-2 vertices are smooth, OpenSubdiv's `EDGE_ONLY`), so every
//! boundary vertex uses the crease mask.
//!
//! ## Limit tangents (docs/schemes.md §6.2-6.3)
//! ```text
//! interior vertex, neighbours p_0 .. p_{n-1} counter-clockwise, centre weight 0:
//!     t1 = sum cos(2 pi i / n) p_i,   t2 = sum sin(2 pi i / n) p_i
//!     normal = normalize(t1 x t2)
//!     regular: t1 = (1, 1/2, -1/2, -1, -1/2, 1/2), t2 = (0, r, r, 0, -r, -r), r = sqrt(3)/2
//! boundary vertex, ring e_0 .. e_m counter-clockwise from one border edge to
//! the other (m faces), centre v:
//!     t_along  = e_0 - e_m                      (OpenSubdiv: 3/2 (e_0 - e_m))
//!     t_across (points into the surface), eigenvalue 3/8 + 1/4 cos(pi/m):
//!       m = 1: e_0 + e_1 - 2 v                  (eigenvalue 1/4)
//!       m >= 2, theta = pi / m, c = cos(theta), s = sin(theta):
//!              v: -s,   e_0 and e_m: -s c,   e_i (0 < i < m): (1 - c)(2c + 1) sin(i theta)
//!       m = 2: e_1 - v;   m = 3: proportional to -2 v - e_0 + 2 e_1 + 2 e_2 - e_3
//!     normal = normalize(t_along x t_across)
//! ```
//! Sources: interior and the boundary cases m = 1, 2, 3 as OpenSubdiv
//! `sdc/loopScheme.h` `assignSmoothLimitTangentMasks` and
//! `assignCreaseLimitTangentMasks` (scaled: only directions matter for a
//! normal). The general boundary formula is **derived here** as the symmetric
//! left eigenvector of the boundary 1-ring subdivision matrix of our rules
//! (v' = 3/4 v + 1/8 (e_0 + e_m), border edges 1/2 (v + e), interior edges
//! 3/8 (v + e_i) + 1/8 (e_{i-1} + e_{i+1})): with `l_i = sin(i theta)` the
//! interior rows give the eigenvalue `3/8 + c/4`, and the rows of `v` and
//! `e_0` fix `l_v` and `l_0` (unit test `boundary_masks_are_left_eigenvectors`).
//! It agrees with the published masks for m = 2, 3. The m >= 4 mask quoted in
//! docs/schemes.md §6.3 (centre weight 0, ends `sin(theta)`, interior
//! `(2 cos(theta) - 2) sin(i theta)`) is NOT an eigenvector of these rules:
//! its normal changes from one level to the next (by about 2 degrees at m = 4
//! on our hemisphere test), so we do not use it.
//! For m >= 7 (boundary valence >= 8) the antisymmetric interior mode
//! `sin(2 i theta)` has eigenvalue `3/8 + cos(2 theta)/4 > 1/2`, larger than
//! the boundary tangent's 1/2, so by our analysis these boundary rules are
//! not C1 there (Biermann, Levin and Zorin, "Piecewise Smooth Subdivision
//! Surfaces with Normal Control", SIGGRAPH 2000, modify the boundary rules
//! for such reasons); the masks do not define a limit normal, and such
//! vertices use the fallback.
//! Every tangent mask sums to 0, so it is translation invariant.
//! Where the cross product vanishes (degenerate geometry) or the vertex is a
//! boundary vertex with m >= 7, the vertex falls back to the area-weighted
//! face normal ([`crate::mesh::normals`], docs/schemes.md §6.6).
//!
//! Ring order: [`CornerTable::ring`] lists the neighbours in swing order,
//! which is counter-clockwise seen from outside for counter-clockwise faces;
//! for a boundary vertex it starts across the border edge of `C[v]` and ends
//! across the other border edge, the interior lying counter-clockwise from
//! `e_0`. So `t1 x t2` (interior) and `t_along x t_across` (boundary) point to
//! the same side as the face normals.

use super::features::Mask;
use super::loop_::LoopBeta;
use crate::mesh::normals::vertex_normals;
use crate::mesh::{CornerTable, Mesh};
use glam::{DVec3, Vec3};
use rayon::prelude::*;
use std::f64::consts::PI;

/// Loop limit positions with Loop's original beta (the default of
/// [`crate::Options`]); one per vertex, same ids as `mesh.positions`.
pub fn loop_limit_positions(mesh: &Mesh) -> Vec<Vec3> {
    loop_limit_positions_with(mesh, LoopBeta::Loop)
}

/// Loop limit positions for the vertex weights `beta` (Loop's or Warren's):
/// the masks of the module docs. The limit of a boundary vertex does not
/// depend on `beta`. On sharp features (docs/sharp-features.md §8; OpenSubdiv
/// `assignCreaseLimitMask`, `assignCornerLimitMask`) a crease vertex takes
/// its crease curve's B-spline limit `2/3 v + 1/6 (a + b)` and a corner
/// stays; the rule is the vertex's at this level, so an edge still
/// semi-sharp here counts as sharp (the limit of a crease that would decay
/// later is neither, OpenSubdiv leaves that choice to the caller too).
pub fn loop_limit_positions_with(mesh: &Mesh, beta: LoopBeta) -> Vec<Vec3> {
    let pos: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    loop_limit_positions_f64(mesh, &pos, beta).iter().map(|p| p.as_vec3()).collect()
}

/// [`loop_limit_positions_with`] of the control positions `pos` (one per
/// vertex of `mesh`, in f64; `mesh.positions` are not read), in f64.
pub fn loop_limit_positions_f64(mesh: &Mesh, pos: &[DVec3], beta: LoopBeta) -> Vec<DVec3> {
    let mut out = smooth_limit_positions(mesh, pos, beta);
    if let Some(f) = super::features::Features::of(&mesh.ct, crate::mesh::Creasing::Uniform) {
        for vf in f.vertices() {
            let v = vf.vertex as usize;
            match vf.parent {
                Mask::Crease(a, b) => {
                    out[v] = pos[v] * (2.0 / 3.0) + (pos[a as usize] + pos[b as usize]) * (1.0 / 6.0);
                }
                Mask::Corner => out[v] = pos[v],
                Mask::Smooth => {}
            }
        }
    }
    out
}

/// [`loop_limit_positions_with`] without sharp features (borders only).
fn smooth_limit_positions(mesh: &Mesh, pos: &[DVec3], beta: LoopBeta) -> Vec<DVec3> {
    let ct = &mesh.ct;
    (0..ct.num_vertices() as u32)
        .into_par_iter()
        .with_min_len(4096)
        .map_init(
            || Vec::with_capacity(16),
            |ring, v| {
                let x = pos[v as usize];
                if let Some((q1, q2)) = ct.boundary_neighbours(v) {
                    let q = pos[q1 as usize] + pos[q2 as usize];
                    return x * (2.0 / 3.0) + q * (1.0 / 6.0);
                }
                ring.clear();
                ring.extend(ct.ring(v));
                let k = ring.len() as u32;
                let chi = 1.0 / (f64::from(k) + 3.0 / (8.0 * beta.beta(k)));
                let sum: DVec3 = ring.iter().map(|&q| pos[q as usize]).sum();
                x * (1.0 - f64::from(k) * chi) + sum * chi
            },
        )
        .collect()
}

/// The two limit tangents of the Loop surface at vertex `v` (interior:
/// `(t1, t2)`; boundary: `(t_along, t_across)`), unnormalised; their cross
/// product points along the limit normal. See the module docs for the masks.
/// Both are zero for a boundary vertex with more than [`MAX_BOUNDARY_FACES`]
/// faces.
pub(crate) fn loop_limit_tangents(ct: &CornerTable, pos: &[Vec3], v: u32) -> (Vec3, Vec3) {
    let ring: Vec<DVec3> = ct.ring(v).map(|q| pos[q as usize].as_dvec3()).collect();
    let x = pos[v as usize].as_dvec3();
    let (t1, t2) = if ct.is_boundary_vertex(v) {
        let m = ring.len() - 1;
        let along = ring[0] - ring[m];
        if m > MAX_BOUNDARY_FACES {
            return (Vec3::ZERO, Vec3::ZERO);
        }
        let across = if m == 1 {
            ring[0] + ring[1] - 2.0 * x
        } else {
            let w = boundary_across_weights(m);
            ring.iter().zip(&w[1..]).fold(x * w[0], |s, (&e, &wi)| s + e * wi)
        };
        (along, across)
    } else {
        let k = ring.len() as f64;
        ring.iter().enumerate().fold((DVec3::ZERO, DVec3::ZERO), |(a, b), (i, &e)| {
            let th = 2.0 * PI * i as f64 / k;
            (a + e * th.cos(), b + e * th.sin())
        })
    };
    (t1.as_vec3(), t2.as_vec3())
}

/// Boundary vertices with more faces than this have no limit normal from the
/// tangent masks (not C1, see the module docs); they get the fallback.
pub(crate) const MAX_BOUNDARY_FACES: usize = 6;

/// The across-boundary tangent mask for a boundary vertex with `m >= 2`
/// faces: `[w_v, w_0, ..., w_m]` (derived here, see the module docs).
pub(crate) fn boundary_across_weights(m: usize) -> Vec<f64> {
    let th = PI / m as f64;
    let (s, c) = th.sin_cos();
    let mut w = vec![-s, -s * c];
    w.extend((1..m).map(|i| (1.0 - c) * (2.0 * c + 1.0) * (i as f64 * th).sin()));
    w.push(-s * c);
    w
}

/// Exact Loop limit normals: unit, one per vertex, oriented like the face
/// normals (counter-clockwise faces seen from outside). Computed from the
/// tangent masks of the module docs; a vertex whose tangents are parallel or
/// zero gets the area-weighted face normal instead.
pub fn loop_limit_normals(mesh: &Mesh) -> Vec<Vec3> {
    tangent_normals(mesh, loop_limit_tangents)
}

/// Normals from a per-vertex tangent pair, with the area-weighted fallback.
fn tangent_normals(mesh: &Mesh, tangents: impl Fn(&CornerTable, &[Vec3], u32) -> (Vec3, Vec3) + Sync) -> Vec<Vec3> {
    let ct = &mesh.ct;
    let mut out: Vec<Vec3> = (0..ct.num_vertices() as u32)
        .into_par_iter()
        .with_min_len(4096)
        .map(|v| {
            let (a, b) = tangents(ct, &mesh.positions, v);
            // relative test: a cross product tiny against |a| |b| means parallel tangents
            let c = a.cross(b);
            if c.length() > 1e-6 * a.length() * b.length() && c.is_finite() { c.normalize() } else { Vec3::ZERO }
        })
        .collect();
    if out.contains(&Vec3::ZERO) {
        let fallback = vertex_normals(ct, &mesh.positions);
        for (o, f) in out.iter_mut().zip(fallback) {
            if *o == Vec3::ZERO {
                *o = f;
            }
        }
    }
    out
}

/// Tangent-mask normals for the interpolating butterfly schemes (docs/schemes.md §6.5;
/// the masks there were derived as left eigenvectors of the butterfly
/// subdivision matrix, eigenvalue 1/2, and are our own result):
/// ```text
/// regular interior vertex (valence 6, its six neighbours interior of valence
/// 6 too: a lattice 2-ring), 19-point mask of §6.5 (a) (8-point butterfly, which is
/// also the modified butterfly's regular rule at tension 0; approximate for
/// other tensions), centre weight 0,
/// neighbour e_i at angle theta_i = 60 i degrees:
///     1-ring e_i (distance 1):                          (8/15) cos(theta_i)
///     straight 2-ring s_i beyond e_i (distance 2):      (1/30) cos(theta_i)
///     diagonal d_i across edge (e_i, e_{i+1}) (sqrt 3): -(4 / (15 sqrt 3)) cos(theta_i + 30 deg)
///     t2: the same with sin
/// other interior vertex, valence k (§6.5 (b); for a regular vertex next to an
/// extraordinary one, the 1-ring part of §6.5 (a), an approximation), centre 0:
///     t1 = sum cos(2 pi j / k) e_j,   t2 = sum sin(2 pi j / k) e_j
/// boundary vertex (§6.5 (c)): along the boundary, the 4-point curve's exact mask
///     t_along = (1/12) (p_{-2} - 8 p_{-1} + 8 p_{+1} - p_{+2})
/// with p_{+1} = e_0, p_{-1} = e_m the boundary neighbours and p_{+2}, p_{-2}
/// the next boundary vertices; across: no verified mask, so (§6.5 (c)) the
/// normal is the area-weighted face normal of the fan with its
/// component along t_along removed: exact along the boundary, approximate
/// across it.
/// ```
/// The vertex positions of an interpolating scheme are already on the limit
/// surface (limit mask = identity), so only normals need masks. Unit normals,
/// oriented like the face normals; degenerate tangents fall back to the
/// area-weighted face normal.
///
/// Accuracy (tests `butterfly_normals_are_exact_on_cubics`,
/// `butterfly_normals_match_finite_differences`): exact for the 8-point
/// butterfly on regular 2-rings (the normal of a cubic's graph is reproduced)
/// and within 0.05 degrees of finite differences at extraordinary vertices
/// with regular neighbours (the modified butterfly from level 1 on); about 2
/// degrees off at a regular vertex next to an extraordinary one (1-ring
/// approximation) and up to about 3.5 degrees at the boundary.
pub fn butterfly_normals(mesh: &Mesh) -> Vec<Vec3> {
    tangent_normals(mesh, butterfly_tangents)
}

/// The 19-point regular tangent pair of [`butterfly_normals`], or `None`
/// when `v` or one of its neighbours `ids` is not an interior vertex of
/// valence 6.
fn regular_butterfly_tangents(ct: &CornerTable, pos: &[Vec3], v: u32, ids: &[u32]) -> Option<(Vec3, Vec3)> {
    let regular = |q: u32| ct.valences()[q as usize] == 6 && !ct.is_boundary_vertex(q);
    if ids.len() != 6 || !ids.iter().all(|&q| regular(q)) {
        return None;
    }
    let p = |q: u32| pos[q as usize].as_dvec3();
    let w1 = 8.0 / 15.0;
    let w2 = 1.0 / 30.0;
    let wd = -4.0 / (15.0 * 3f64.sqrt());
    let (mut t1, mut t2) = (DVec3::ZERO, DVec3::ZERO);
    for (i, c) in ct.fan(v).enumerate() {
        let e = ct.vtx(crate::mesh::n(c));
        // s_i: opposite v in e_i's (valence-6) ring
        let er: Vec<u32> = ct.ring(e).collect();
        let j = er.iter().position(|&q| q == v)?;
        let s = er[(j + 3) % 6];
        // d_i: across the edge (e_i, e_{i+1}) opposite this corner
        let d = ct.vtx(ct.o(c)?);
        let th = (60.0 * i as f64).to_radians();
        let ph = th + 30f64.to_radians();
        t1 += (p(e) * w1 + p(s) * w2) * th.cos() + p(d) * (wd * ph.cos());
        t2 += (p(e) * w1 + p(s) * w2) * th.sin() + p(d) * (wd * ph.sin());
    }
    Some((t1.as_vec3(), t2.as_vec3()))
}

/// The tangent pair of [`butterfly_normals`] at vertex `v`.
fn butterfly_tangents(ct: &CornerTable, pos: &[Vec3], v: u32) -> (Vec3, Vec3) {
    let ids: Vec<u32> = ct.ring(v).collect();
    let ring: Vec<DVec3> = ids.iter().map(|&q| pos[q as usize].as_dvec3()).collect();
    let x = pos[v as usize].as_dvec3();
    if !ct.is_boundary_vertex(v) {
        if let Some(t) = regular_butterfly_tangents(ct, pos, v, &ids) {
            return t;
        }
        let k = ring.len() as f64;
        let (a, b) = ring.iter().enumerate().fold((DVec3::ZERO, DVec3::ZERO), |(a, b), (i, &e)| {
            let th = 2.0 * PI * i as f64 / k;
            (a + e * th.cos(), b + e * th.sin())
        });
        return (a.as_vec3(), b.as_vec3());
    }
    let m = ring.len() - 1;
    let (e0, em) = (ids[0], ids[m]);
    // next boundary vertices: e_0's boundary neighbour other than v, same for e_m
    // (e_0 and e_m lie on v's border edges, so they are boundary vertices)
    let other = |q: u32| match ct.boundary_neighbours(q) {
        Some((a, b)) => {
            if a == v {
                b
            } else {
                a
            }
        }
        None => q,
    };
    let p2 = pos[other(e0) as usize].as_dvec3();
    let m2 = pos[other(em) as usize].as_dvec3();
    let along = (m2 - 8.0 * ring[m] + 8.0 * ring[0] - p2) / 12.0;
    // area-weighted fan normal (2 x area each), made perpendicular to t_along
    let fan_normal = ring.windows(2).map(|w| (w[0] - x).cross(w[1] - x)).sum::<DVec3>();
    let l2 = along.length_squared();
    let nrm = if l2 > 0.0 { fan_normal - along * (fan_normal.dot(along) / l2) } else { fan_normal };
    // along x (nrm x along) = nrm |along|^2: the pair's cross product is nrm
    (along.as_vec3(), nrm.cross(along).as_vec3())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regular_position_mask_is_half_and_twelfths() {
        // chi(6) with beta = 1/16: 1 / (6 + 6) = 1/12; centre 1 - 6/12 = 1/2
        let beta = LoopBeta::Loop.beta(6);
        let chi = 1.0 / (6.0 + 3.0 / (8.0 * beta));
        assert!((chi - 1.0 / 12.0).abs() < 1e-12);
        // n = 3: chi = 1/5
        let chi3 = 1.0 / (3.0 + 3.0 / (8.0 * LoopBeta::Loop.beta(3)));
        assert!((chi3 - 0.2).abs() < 1e-12);
        // Warren: chi = 1/(2n)
        for k in 4..12u32 {
            let c = 1.0 / (f64::from(k) + 3.0 / (8.0 * LoopBeta::Warren.beta(k)));
            assert!((c - 1.0 / (2.0 * f64::from(k))).abs() < 1e-12);
        }
    }

    #[test]
    fn warren_limit_is_the_fixed_point_of_warren_subdivision() {
        // Six levels of Warren-weighted Loop subdivision bring the icosahedron's
        // (valence-5) vertices within 4^-6 of their limit (radial eigenvalue
        // 5/8 - n beta = 1/4); Loop's beta has another limit, 0.016 away.
        let ico = crate::mesh::shapes::icosahedron();
        let warren = crate::Options { loop_beta: LoopBeta::Warren, ..Default::default() };
        let fine = crate::subdivide(&ico, crate::Scheme::Loop, 6, &warren).expect("small mesh").0;
        let (with_warren, with_loop) = (loop_limit_positions_with(&ico, LoopBeta::Warren), loop_limit_positions(&ico));
        for v in 0..ico.positions.len() {
            assert!(fine.positions[v].distance(with_warren[v]) < 1e-4, "vertex {v}");
            assert!(fine.positions[v].distance(with_loop[v]) > 1e-2, "vertex {v}: the betas differ");
        }
    }

    /// The boundary 1-ring subdivision matrix of our Loop rules, rows and
    /// columns ordered `v, e_0, ..., e_m`.
    fn boundary_matrix(m: usize) -> Vec<Vec<f64>> {
        let k = m + 2;
        let mut s = vec![vec![0.0; k]; k];
        s[0][0] = 0.75;
        s[0][1] += 0.125;
        s[0][m + 1] += 0.125;
        for i in 0..=m {
            let r = i + 1;
            if i == 0 || i == m {
                s[r][0] = 0.5;
                s[r][r] = 0.5;
            } else {
                s[r][0] = 0.375;
                s[r][r] = 0.375;
                s[r][r - 1] += 0.125;
                s[r][r + 1] += 0.125;
            }
        }
        s
    }

    #[test]
    fn boundary_masks_are_left_eigenvectors() {
        for m in 1..=12usize {
            let s = boundary_matrix(m);
            let across = if m == 1 { vec![-2.0, 1.0, 1.0] } else { boundary_across_weights(m) };
            let lam = if m == 1 { 0.25 } else { 0.375 + 0.25 * (PI / m as f64).cos() };
            let mut along = vec![0.0; m + 2];
            along[1] = 1.0;
            along[m + 1] = -1.0;
            for (l, lam) in [(across, lam), (along, 0.5)] {
                assert!(l.iter().sum::<f64>().abs() < 1e-12, "m = {m}: mask sum");
                for j in 0..m + 2 {
                    let ls: f64 = (0..m + 2).map(|r| l[r] * s[r][j]).sum();
                    assert!((ls - lam * l[j]).abs() < 1e-12, "m = {m}, column {j}: {ls} vs {}", lam * l[j]);
                }
            }
        }
        // agrees with the published m = 2 and m = 3 masks (up to scale)
        let w2 = boundary_across_weights(2);
        assert!(w2.iter().zip([-1.0, 0.0, 1.0, 0.0]).all(|(a, b)| (a - b).abs() < 1e-12), "{w2:?}");
        let w3 = boundary_across_weights(3);
        let k = w3[0] / -2.0;
        assert!(w3.iter().zip([-2.0, -1.0, 2.0, 2.0, -1.0]).all(|(a, b)| (a - k * b).abs() < 1e-12), "{w3:?}");
    }

    #[test]
    fn published_m4_mask_is_not_an_eigenvector() {
        // the published m >= 4 formula (docs/schemes.md §6.3), for the record
        let m = 4;
        let th = PI / m as f64;
        let mut l = vec![0.0, -th.sin()];
        l.extend((1..m).map(|i| 2.0 * (1.0 - th.cos()) * (i as f64 * th).sin()));
        l.push(-th.sin());
        let s = boundary_matrix(m);
        let ls: Vec<f64> = (0..m + 2).map(|j| (0..m + 2).map(|r| l[r] * s[r][j]).sum()).collect();
        let lam = ls[2] / l[2];
        assert!((0..m + 2).any(|j| (ls[j] - lam * l[j]).abs() > 1e-3), "{ls:?}");
    }

    #[test]
    fn interior_masks_are_left_eigenvectors() {
        // 1-ring matrix of an interior vertex of valence k: v' = (1 - k beta) v + beta sum,
        // e_i' = 3/8 (v + e_i) + 1/8 (e_{i-1} + e_{i+1}); cos/sin masks have eigenvalue
        // 3/8 + 1/4 cos(2 pi / k)
        for k in 3..=12usize {
            let beta = LoopBeta::Loop.beta(k as u32);
            let mut s = vec![vec![0.0; k + 1]; k + 1];
            s[0][0] = 1.0 - k as f64 * beta;
            for i in 0..k {
                s[0][i + 1] = beta;
                s[i + 1][0] = 0.375;
                s[i + 1][i + 1] = 0.375;
                s[i + 1][(i + 1) % k + 1] += 0.125;
                s[i + 1][(i + k - 1) % k + 1] += 0.125;
            }
            let lam = 0.375 + 0.25 * (2.0 * PI / k as f64).cos();
            for f in [f64::cos, f64::sin] {
                let mut l = vec![0.0];
                l.extend((0..k).map(|i| f(2.0 * PI * i as f64 / k as f64)));
                for j in 0..=k {
                    let ls: f64 = (0..=k).map(|r| l[r] * s[r][j]).sum();
                    assert!((ls - lam * l[j]).abs() < 1e-12, "k = {k}, column {j}");
                }
            }
            // and the limit position mask has eigenvalue 1
            let chi = 1.0 / (k as f64 + 3.0 / (8.0 * beta));
            let mut l = vec![1.0 - k as f64 * chi];
            l.extend(std::iter::repeat_n(chi, k));
            for j in 0..=k {
                let ls: f64 = (0..=k).map(|r| l[r] * s[r][j]).sum();
                assert!((ls - l[j]).abs() < 1e-12, "limit mask, k = {k}, column {j}");
            }
        }
    }
}
