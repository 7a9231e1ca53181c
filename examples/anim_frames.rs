//! Minimum per-frame time of the CPU animation over 100 frames, split into
//! stencils and normals (the figures in docs/performance.md; the median is
//! `subdiv animate --stats`):
//!
//! ```text
//! cargo run --release --example anim_frames -- MODEL.obj LEVEL [SCHEME]
//! ```
use std::time::Instant;
use subdiv::anim::{Animation, Paths, Tweak};
use subdiv::{Options, Scheme};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (Some(model), Some(level)) = (args.get(1), args.get(2)) else {
        return Err("usage: anim_frames MODEL LEVEL [SCHEME]".into());
    };
    let scheme: Scheme = args.get(3).map_or(Ok(Scheme::Loop), |s| s.parse()).map_err(|e: String| e)?;
    let m = subdiv::bundled::load(std::path::Path::new(model))?;
    let paths = Paths::generated(&m, 4);
    let mut anim = Animation::new(&m, &paths, Tweak::Jarek, 3, scheme, level.parse()?, &Options::default())?;
    let (mut total, mut stencils, mut normals) = (f64::MAX, f64::MAX, f64::MAX);
    for f in 0..100 {
        let t = Instant::now();
        anim.evaluate(f);
        total = total.min(t.elapsed().as_secs_f64() * 1e3);
        stencils = stencils.min(anim.last_timing.0.as_secs_f64() * 1e3);
        normals = normals.min(anim.last_timing.1.as_secs_f64() * 1e3);
    }
    println!(
        "frame_min_ms={total:.3} stencils_min_ms={stencils:.3} normals_min_ms={normals:.3} plan_ms={:.1} threads={}",
        anim.plan_ms(),
        rayon::current_num_threads()
    );
    Ok(())
}
