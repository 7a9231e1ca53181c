//! `subdiv animate --stats` without an output: every frame evaluated (at
//! least 32 evaluations, cycling), on the CPU or through the GPU's compute
//! passes, and the plan and per-frame times printed.

use std::time::Instant;
use subdiv::Result;
use subdiv::anim::Animation;

/// Evaluates and prints `plan_ms=.. frame_ms=..` (medians).
pub fn run(anim: &mut Animation, gpu: bool) -> Result<()> {
    if gpu { on_gpu(anim) } else { on_cpu(anim) }
}

fn median(t: &mut [f64]) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn on_cpu(anim: &mut Animation) -> Result<()> {
    let n = anim.frame_count().max(32);
    let (mut times, mut stencils, mut normals) = (Vec::with_capacity(n), Vec::with_capacity(n), Vec::with_capacity(n));
    for f in 0..n {
        let t = Instant::now();
        std::hint::black_box(anim.evaluate(f).1.len());
        times.push(t.elapsed().as_secs_f64() * 1e3);
        stencils.push(anim.last_timing.0.as_secs_f64() * 1e3);
        normals.push(anim.last_timing.1.as_secs_f64() * 1e3);
    }
    println!(
        "plan_ms={:.3} frame_ms={:.3} frame_min_ms={:.3} (stencils_ms={:.3} normals_ms={:.3}) evaluations={n} frames={} triangles={} threads={}",
        anim.plan_ms(),
        median(&mut times),
        times[0],
        median(&mut stencils),
        median(&mut normals),
        anim.frame_count(),
        anim.topology().num_triangles(),
        rayon::current_num_threads()
    );
    Ok(())
}

fn on_gpu(anim: &mut Animation) -> Result<()> {
    let n = anim.frame_count().max(32);
    let (mut times, upload_ms, adapter) = subdiv::render::gpu_anim::time_frames(anim, n)?;
    println!(
        "plan_ms={:.3} frame_ms={:.3} frame_min_ms={:.3} (gpu upload_ms={upload_ms:.3}) evaluations={n} frames={} triangles={} adapter=\"{adapter}\"",
        anim.plan_ms(),
        median(&mut times),
        times[0],
        anim.frame_count(),
        anim.topology().num_triangles(),
    );
    Ok(())
}
