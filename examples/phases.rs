//! Per-phase timing of the subdivision call, input loaded once:
//! `cargo run --release --no-default-features --example phases -- MODEL LEVELS REPEATS [SCHEME...]`
//! prints, per scheme, the minimum over the repeats of every phase (ms), which
//! is what counts on a shared, noisy machine.

use std::path::Path;
use subdiv::{Options, Scheme, subdivide};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model = args.get(1).map_or("../shared/models/stanford-bunny-compact.obj", String::as_str);
    let levels: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    let reps: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(7);
    let schemes: Vec<Scheme> =
        if args.len() > 4 { args[4..].iter().map(|s| s.parse().unwrap()).collect() } else { Scheme::ALL.to_vec() };
    let mesh = subdiv::io::load(Path::new(model)).unwrap();
    for s in schemes {
        let mut best = [f64::MAX; 5];
        for _ in 0..reps {
            let (m, st) = subdivide(&mesh, s, levels, &Options::default()).unwrap();
            std::hint::black_box(m.positions.len());
            for (b, x) in best.iter_mut().zip([st.total_ms, st.split_ms, st.numbering_ms, st.edge_ms, st.vertex_ms]) {
                *b = b.min(x);
            }
        }
        println!(
            "{:<20} total={:7.1} split={:6.1} (numbering={:5.1}) edge={:6.1} vertex={:6.1}",
            s.name(),
            best[0],
            best[1],
            best[2],
            best[3],
            best[4]
        );
    }
}
