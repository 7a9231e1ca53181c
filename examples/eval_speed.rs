//! Exact Loop evaluation speed: random points on a model (default the
//! Stanford bunny from the benchmark models beside the repository), one
//! thread, position and normal, timed as the minimum of interleaved runs.
//!
//! `cargo run --release --example eval_speed [MODEL] [POINTS]`

use std::time::Instant;
use subdiv::Evaluator;
use subdiv::{Options, Scheme};

fn main() -> subdiv::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let path = args.get(1).map_or("../shared/models/stanford-bunny.obj", String::as_str);
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1_000_000);
    let loaded = subdiv::io::read(subdiv::io::Source::File(path.as_ref()), &subdiv::io::ReadOptions::default())?;
    let mesh = loaded.mesh;
    let t = Instant::now();
    let ev = Evaluator::new(&mesh, Scheme::Loop, &Options::default())?;
    let prepare = t.elapsed().as_secs_f64() * 1e3;
    // xorshift points on the faces the evaluator accepts
    let mut x = 0x2545f4914f6cdd1du64;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let faces: Vec<usize> = (0..ev.num_faces()).filter(|&f| ev.accepts(f)).collect();
    let points: Vec<(usize, f64, f64)> = (0..n)
        .map(|_| {
            let f = faces[(next() * faces.len() as f64) as usize % faces.len()];
            let (u, v) = (next(), next());
            if u + v > 1.0 { (f, 1.0 - u, 1.0 - v) } else { (f, u, v) }
        })
        .collect();
    // one at a time in the points' (random) order; then the batch call,
    // which groups them by face, on one thread and on all
    let one =
        rayon::ThreadPoolBuilder::new().num_threads(1).build().map_err(|e| subdiv::Error::Usage(e.to_string()))?;
    let mut best = [f64::INFINITY; 4];
    let mut check = 0.0;
    for _ in 0..5 {
        let t = Instant::now();
        for &(f, u, v) in &points {
            let s = ev.eval_first(f, u, v)?;
            check += s.position.x + s.normal.y;
        }
        best[0] = best[0].min(t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        for &(f, u, v) in &points {
            check += ev.eval(f, u, v)?.mean;
        }
        best[1] = best[1].min(t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        let keep = |s: &subdiv::eval::Sample| [s.position, s.normal];
        let batch = one.install(|| ev.eval_map(&points, false, keep))?;
        best[2] = best[2].min(t.elapsed().as_secs_f64() * 1e3);
        check += batch[n / 2][0].z;
        let t = Instant::now();
        let batch = ev.eval_map(&points, false, keep)?;
        best[3] = best[3].min(t.elapsed().as_secs_f64() * 1e3);
        check += batch[n / 3][0].z;
    }
    let per = |ms: f64| format!("{ms:.1} ms ({:.0} ns/point, {:.2} M/s)", ms * 1e6 / n as f64, n as f64 / ms / 1e3);
    println!(
        "{path}: {} faces ({} evaluated), prepare_ms={prepare:.1}, {n} random points",
        ev.num_faces(),
        faces.len()
    );
    println!("  one thread, one at a time: position+normal {}", per(best[0]));
    println!("  one thread, one at a time: with curvature  {}", per(best[1]));
    println!("  eval_map (grouped by face), one thread:     {}", per(best[2]));
    println!("  eval_map, {} threads:                        {}", rayon::current_num_threads(), per(best[3]));
    println!("  [checksum {check:.3}]");
    Ok(())
}
