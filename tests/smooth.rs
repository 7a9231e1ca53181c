//! Taubin lambda/mu smoothing (schemes.md 9): planes stay planes, noise is
//! removed without the shrinkage of plain Laplacian smoothing, affine
//! invariance, boundary vertices move along the boundary only.

mod common;
use common::*;
use glam::{Mat3, Vec3};
use subdiv::Mesh;
use subdiv::mesh::{TAUBIN_LAMBDA, TAUBIN_MU, laplacian, smooth_f64, taubin};

fn radii(p: &[Vec3]) -> (f32, f32) {
    let n = p.len() as f32;
    let mean = p.iter().map(|q| q.length()).sum::<f32>() / n;
    let var = p.iter().map(|q| (q.length() - mean).powi(2)).sum::<f32>() / n;
    (mean, var.sqrt())
}

fn noisy_sphere() -> Mesh {
    let mut m = icosphere(3);
    let mut rng = Rng(11);
    for q in &mut m.positions {
        *q *= 1.0 + 0.05 * rng.next_f32();
    }
    m
}

#[test]
fn a_plane_stays_a_plane() {
    let (o, a, b) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.8, 0.1, -0.3), Vec3::new(-0.2, 0.5, 0.9));
    let nrm = a.cross(b).normalize();
    let mut rng = Rng(3);
    let m = grid(8, 7, |i, j| o + a * i + b * j);
    let mut noisy = m.clone();
    for q in &mut noisy.positions {
        *q += a * 0.3 * rng.next_f32() + b * 0.3 * rng.next_f32();
    }
    for out in [taubin(&noisy, 10, TAUBIN_LAMBDA, TAUBIN_MU), laplacian(&noisy, 10, 0.5)] {
        for (i, q) in out.iter().enumerate() {
            assert!((*q - o).dot(nrm).abs() < 1e-4, "vertex {i} left the plane: {q}");
        }
    }
}

/// Taubin's point: the noise goes, the size stays. Plain Laplacian smoothing
/// with the same lambda and the same number of passes shrinks the sphere.
#[test]
fn noisy_sphere_is_smoothed_without_shrinking() {
    let m = noisy_sphere();
    let (mean0, sd0) = radii(&m.positions);
    let t = taubin(&m, 10, TAUBIN_LAMBDA, TAUBIN_MU);
    let (mean_t, sd_t) = radii(&t);
    assert!(sd_t < sd0 / 2.5, "Taubin left the noise: {sd0} -> {sd_t}");
    // no shrinkage (the pass band is even amplified a little: +0.4% here)
    assert!((mean_t - mean0).abs() < 0.01 * mean0, "Taubin changed the size: {mean0} -> {mean_t}");
    // 20 Laplacian passes = the same number of umbrella passes as 10 Taubin steps
    let l = laplacian(&m, 20, TAUBIN_LAMBDA);
    let (mean_l, sd_l) = radii(&l);
    assert!(sd_l < sd0 / 2.5, "Laplacian left the noise: {sd0} -> {sd_l}");
    assert!(mean_l < 0.9 * mean0, "Laplacian should shrink: {mean0} -> {mean_l}");
    assert!(mean0 - mean_l > 10.0 * (mean_t - mean0).abs());
}

/// Uniform umbrella weights sum to zero: smoothing commutes with affine maps.
#[test]
fn smoothing_is_affine_invariant() {
    let a = Mat3::from_cols(Vec3::new(1.2, 0.3, -0.4), Vec3::new(0.1, 0.9, 0.5), Vec3::new(-0.3, 0.2, 1.4));
    let b = Vec3::new(-1.0, 0.5, 2.0);
    for (name, m) in all_meshes() {
        let mut t = m.clone();
        for q in &mut t.positions {
            *q = a * *q + b;
        }
        let (s, st) = (taubin(&m, 5, TAUBIN_LAMBDA, TAUBIN_MU), taubin(&t, 5, TAUBIN_LAMBDA, TAUBIN_MU));
        for i in 0..s.len() {
            assert!((a * s[i] + b).distance(st[i]) < 2e-4 * (1.0 + s[i].length()), "{name}: vertex {i}");
        }
    }
}

/// An open tube (k vertices around, `rings + 1` circles).
fn tube(k: u32, rings: u32) -> Mesh {
    let mut pos = Vec::new();
    for r in 0..=rings {
        for i in 0..k {
            let a = std::f32::consts::TAU * i as f32 / k as f32;
            pos.push(Vec3::new(a.cos(), a.sin(), r as f32 / rings as f32));
        }
    }
    let id = |r: u32, i: u32| r * k + i % k;
    let mut tris = Vec::new();
    for r in 0..rings {
        for i in 0..k {
            tris.extend([id(r, i), id(r, i + 1), id(r + 1, i + 1), id(r, i), id(r + 1, i + 1), id(r + 1, i)]);
        }
    }
    Mesh::from_triangles(pos, &tris).unwrap()
}

/// Boundary vertices are smoothed along the boundary only (1-D umbrella of
/// their two boundary neighbours): on an open tube the two boundary circles
/// stay exactly in their planes whatever the interior does, and their noise
/// is removed without shrinking them.
#[test]
fn boundary_moves_along_the_boundary_only() {
    let (k, rings) = (48, 6);
    let mut m = tube(k, rings);
    let mut rng = Rng(5);
    let mut boundary = Vec::new();
    for (i, q) in m.positions.iter_mut().enumerate() {
        let r = i as u32 / k;
        if r == 0 || r == rings {
            boundary.push(i);
            *q = Vec3::new(q.x * (1.0 + 0.05 * rng.next_f32()), q.y * (1.0 + 0.05 * rng.next_f32()), q.z);
        } else {
            *q += rng.vec3() * 0.1;
        }
    }
    let ring_radii = |p: &[Vec3]| radii(&boundary.iter().map(|&i| p[i].truncate().extend(0.0)).collect::<Vec<_>>());
    let (mean0, sd0) = ring_radii(&m.positions);
    let out = taubin(&m, 30, TAUBIN_LAMBDA, TAUBIN_MU);
    for &i in &boundary {
        assert_eq!(out[i].z, m.positions[i].z, "boundary vertex {i} left its plane");
    }
    let (mean1, sd1) = ring_radii(&out);
    assert!(sd1 < sd0 / 2.0, "boundary noise left: {sd0} -> {sd1}");
    // the circle is the lowest mode of the boundary polygon's umbrella operator,
    // eigenvalue -kf with kf = 1 - cos(2 pi / k): each Taubin step scales it by
    // (1 - lambda kf)(1 - mu kf), slightly above 1 (pass band), never below
    let kf = 1.0 - (std::f64::consts::TAU / f64::from(k)).cos();
    let gain = ((1.0 - f64::from(TAUBIN_LAMBDA) * kf) * (1.0 - f64::from(TAUBIN_MU) * kf)).powi(30);
    let ratio = f64::from(mean1 / mean0);
    assert!((ratio - gain).abs() < 2e-3, "boundary circles scaled by {ratio}, theory {gain}");
}

#[test]
fn zero_steps_is_the_identity() {
    let m = noisy_sphere();
    assert_eq!(taubin(&m, 0, TAUBIN_LAMBDA, TAUBIN_MU), m.positions);
}

/// Smoothing in f64: the f32 passes' result within f32's rounding, and a
/// million units from the origin the same result moved, where f32's
/// spacing (0.06) would swamp it (the umbrella's weights sum to zero).
#[test]
fn f64_smoothing_keeps_its_digits_far_from_the_origin() {
    let m = noisy_sphere();
    let exact: Vec<glam::DVec3> = m.positions.iter().map(|p| p.as_dvec3()).collect();
    let (l, mu) = (TAUBIN_LAMBDA as f64, TAUBIN_MU as f64);
    for (name, f64s, f32s) in [
        ("taubin", smooth_f64(&m, &exact, 10, l, Some(mu)), taubin(&m, 10, TAUBIN_LAMBDA, TAUBIN_MU)),
        ("laplacian", smooth_f64(&m, &exact, 10, 0.5, None), laplacian(&m, 10, 0.5)),
    ] {
        let near = f64s.iter().zip(&f32s).map(|(a, b)| (*a - b.as_dvec3()).abs().max_element()).fold(0.0, f64::max);
        assert!(near < 1e-5, "{name}: f64 and f32 agree to f32's rounding ({near})");
        let shift = glam::DVec3::splat(1e6);
        let far: Vec<glam::DVec3> = exact.iter().map(|p| *p + shift).collect();
        let taubin_case = name == "taubin";
        let moved = smooth_f64(&m, &far, 10, if taubin_case { l } else { 0.5 }, taubin_case.then_some(mu));
        let worst = moved.iter().zip(&f64s).map(|(a, b)| (*a - shift - *b).abs().max_element()).fold(0.0, f64::max);
        assert!(worst < 1e-8, "{name}: a million units out ({worst})");
    }
}
