//! Time of each phase of reading an OBJ (read, parse, build), the minimum
//! of 20 repeats in one process: for docs/performance.md.
//! `cargo run --release --example load_phases -- MODEL.obj`
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args().nth(1).ok_or("usage: load_phases MODEL.obj")?;
    let mut best = [f64::MAX; 3];
    for _ in 0..20 {
        let t0 = Instant::now();
        let bytes = std::fs::read(&path)?;
        let t1 = Instant::now();
        let opts = subdiv::io::ReadOptions::default();
        let src = subdiv::io::Source::Bytes { bytes: &bytes, name: &path, folder: None };
        let raw = subdiv::io::read_raw(src, &opts)?.raw;
        let t2 = Instant::now();
        let (m, _, _) = raw.build(&path, opts.topology, false)?;
        let t3 = Instant::now();
        std::hint::black_box(m.ct.num_triangles());
        let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
        for (b, x) in best.iter_mut().zip([ms(t0, t1), ms(t1, t2), ms(t2, t3)]) {
            *b = b.min(x);
        }
    }
    println!("read_ms={:.2} parse_ms={:.2} build_ms={:.2} (minimum of 20)", best[0], best[1], best[2]);
    Ok(())
}
