//! An animation loop through a stencil plan: the subdivision of one topology
//! is recorded once (`StencilPlan::build`, CSR weights per level) and every
//! frame only re-applies those weights to new control positions, which is
//! how split-and-tweak animation stays cheap.
//! `cargo run --release --example animation_loop -- [IN] [LEVELS] [FRAMES]`
//! (defaults: the bundled tetrahedron, 5, 120). No GPU needed.

use glam::Vec3;
use std::path::PathBuf;
use std::time::Instant;
use subdiv::StencilPlan;
use subdiv::rules::PlanScratch;
use subdiv::{Options, Scheme, subdivide};

fn main() -> subdiv::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let input = PathBuf::from(args.first().map_or("bundled:tetrahedron.obj", String::as_str));
    let levels: u32 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(5);
    let frames: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(120);

    let mesh = subdiv::bundled::load(&input)?;
    let opts = Options::default();
    let t0 = Instant::now();
    let plan = StencilPlan::build(&mesh.ct, Scheme::Loop, levels, &opts)?;
    let build_ms = t0.elapsed().as_secs_f64() * 1e3;

    let (mut scratch, mut fine) = (PlanScratch::default(), Vec::new());
    let t1 = Instant::now();
    let mut extent = 0.0f32;
    for f in 0..frames {
        // the control points breathe: each moves along its own direction
        let phase = std::f32::consts::TAU * f as f32 / frames as f32;
        let control: Vec<Vec3> =
            mesh.positions.iter().enumerate().map(|(i, p)| *p * (1.0 + 0.2 * (phase + i as f32).sin())).collect();
        plan.apply(&control, &mut scratch, &mut fine);
        extent = extent.max(fine.iter().map(|p| p.length()).fold(0.0, f32::max));
    }
    let per_frame = t1.elapsed().as_secs_f64() * 1e3 / frames.max(1) as f64;

    // the plan gives exactly what subdividing the last frame's control points gives
    let phase = std::f32::consts::TAU * (frames - 1) as f32 / frames as f32;
    let last: Vec<Vec3> =
        mesh.positions.iter().enumerate().map(|(i, p)| *p * (1.0 + 0.2 * (phase + i as f32).sin())).collect();
    let (direct, _) = subdivide(&subdiv::Mesh { ct: mesh.ct.clone(), positions: last }, Scheme::Loop, levels, &opts)?;
    let diff = direct.positions.iter().zip(&fine).map(|(a, b)| (*a - *b).length()).fold(0.0, f32::max);
    assert!(diff < 1e-4, "plan and direct subdivision differ by {diff}");
    println!(
        "{}: plan of {levels} levels built in {build_ms:.2} ms, {frames} frames of {} points at {per_frame:.3} ms each; extent {extent:.3}, plan vs direct {diff:.1e}",
        input.display(),
        fine.len()
    );
    Ok(())
}
