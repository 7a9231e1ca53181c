//! Time of each phase of reading an OBJ (read, parse, build): for
//! docs/performance.md. `cargo run --release --example load_phases -- MODEL.obj`
use std::time::Instant;
fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args().nth(1).ok_or("usage: load_phases MODEL.obj")?;
    for _ in 0..3 {
        let t0 = Instant::now();
        let bytes = std::fs::read(&path)?;
        let t1 = Instant::now();
        let raw = subdiv::io::obj::parse(&bytes, &path)?;
        let t2 = Instant::now();
        let (m, _) = subdiv::Mesh::from_triangles_report(raw.positions.clone(), &raw.triangles)?;
        let t3 = Instant::now();
        let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
        println!(
            "read_ms={:.2} parse_ms={:.2} build_ms={:.2} faces={}",
            ms(t0, t1),
            ms(t1, t2),
            ms(t2, t3),
            m.ct.num_triangles()
        );
    }
    Ok(())
}
