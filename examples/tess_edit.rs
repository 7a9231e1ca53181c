//! What a tessellation to a tolerance costs again after an edit (the
//! figures in docs/tessellation.md), minima over repetitions in one
//! process:
//!
//! - `fresh_ms`: [`subdiv::tessellate`] of the cage;
//! - `again_ms`: [`subdiv::Tessellator::tessellate`] after one random
//!   control vertex moved by a thousandth of the diagonal, from the
//!   tessellation before the move (each repetition moves another vertex);
//! - the evaluations of each, and the triangles.
//!
//! ```text
//! cargo run --release --example tess_edit -- MODEL SCHEME TOLERANCE [REPS]
//! ```
//! (`TOLERANCE` as `subdiv tessellate` takes it: `1e-3`, `1e-4x`.)
use glam::DVec3;
use std::time::Instant;
use subdiv::{Options, Scheme, Tessellator, Tolerance};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [path, scheme, tolerance, rest @ ..] = &args[..] else {
        return Err("usage: tess_edit MODEL SCHEME TOLERANCE [REPS]".into());
    };
    let reps: usize = rest.first().map_or(Ok(5), |r| r.parse())?;
    let source = subdiv::io::Source::File(std::path::Path::new(path));
    let mesh = subdiv::io::read(source, &subdiv::io::ReadOptions::default())?.mesh;
    let scheme: Scheme = scheme.parse()?;
    let opts = Options::default();
    let control: Vec<DVec3> = mesh.positions.iter().map(|p| p.as_dvec3()).collect();
    // a fraction of the diagonal as a distance: a moved point must not move the tolerance
    let diagonal = {
        let (lo, hi) = control.iter().fold((DVec3::MAX, DVec3::MIN), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        lo.distance(hi)
    };
    let tolerance = match tolerance.parse::<Tolerance>()? {
        Tolerance::Fraction(f) => Tolerance::Distance(f * diagonal),
        t => t,
    };
    let (mut fresh_ms, mut again_ms) = (f64::INFINITY, f64::INFINITY);
    let (mut fresh, mut again) = (None, None);
    let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
    for _ in 0..reps {
        let t = Instant::now();
        let out = subdiv::tessellate(&mesh, &control, scheme, &opts, tolerance)?;
        fresh_ms = fresh_ms.min(t.elapsed().as_secs_f64() * 1e3);
        fresh = Some(out.stats);
        let mut tessellator = Tessellator::new();
        tessellator.tessellate(&mesh, &control, scheme, &opts, tolerance)?;
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        let mut moved = control.clone();
        moved[(seed % control.len() as u64) as usize] += DVec3::new(1.0, 0.5, -0.7).normalize() * (1e-3 * diagonal);
        let t = Instant::now();
        let out = tessellator.tessellate(&mesh, &moved, scheme, &opts, tolerance)?;
        again_ms = again_ms.min(t.elapsed().as_secs_f64() * 1e3);
        again = Some((out.stats, out.triangles.len()));
    }
    let (Some(fresh), Some((again, triangles))) = (fresh, again) else {
        return Err("no repetitions".into());
    };
    println!(
        "fresh_ms {fresh_ms:.1} again_ms {again_ms:.1} triangles {triangles} fresh_evaluations {} again_evaluations {} met {}",
        fresh.evaluations, again.evaluations, again.met
    );
    Ok(())
}
