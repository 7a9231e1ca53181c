//! What the wireframe costs: renders `MODEL` at Loop level `LEVEL` offscreen
//! (640x480, the default camera) `FRAMES` times in each look, alternating,
//! and prints the median frame time (submit to image read back) of each.
//!
//! `cargo run --release --example wire_cost -- MODEL LEVEL [FRAMES]`

use std::time::Instant;
use subdiv::render::{Offscreen, RenderOptions, Shading, default_camera};
use subdiv::{Options, Scheme};

fn main() -> subdiv::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let model = args.first().map_or("bundled:torus.obj", String::as_str);
    let levels: u32 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(3);
    let frames: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(30);
    let control = subdiv::bundled::load(std::path::Path::new(model))?;
    let fine = subdiv::subdivide(&control, Scheme::Loop, levels, &Options::default())?.0;
    let opts = RenderOptions { width: 640, height: 480, ..Default::default() };
    let mut off = Offscreen::new(opts.width, opts.height)?;
    let gm = off.upload(&fine)?;
    let cam = default_camera(&control, &opts);
    let shadings = [Shading::Phong, Shading::PhongWire, Shading::Wire];
    let mut times = vec![Vec::with_capacity(frames); shadings.len()];
    for i in 0..frames + 2 {
        for (k, s) in shadings.iter().enumerate() {
            let t = Instant::now();
            off.render_one(cam, &gm, None, s.look())?;
            // the first two rounds warm up (pipelines, bind groups, caches)
            if i >= 2 {
                times[k].push(t.elapsed().as_secs_f64() * 1000.0);
            }
        }
    }
    println!(
        "{model} L{levels}: {} triangles, {frames} frames each, samples {}",
        fine.ct.num_triangles(),
        off.renderer.samples
    );
    let base = median(&mut times[0]);
    for (s, t) in shadings.iter().zip(&mut times) {
        let m = median(t);
        println!("  {s:?}: median {m:.1} ms ({:+.1}%)", 100.0 * (m / base - 1.0));
    }
    Ok(())
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}
