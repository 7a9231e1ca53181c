use std::time::Instant;
use subdiv::subdiv::rules::{Level, ring_sums};
fn main() {
    let m = subdiv::io::load(std::path::Path::new("/work/shared/models/stanford-bunny-compact.obj")).unwrap();
    let (m, _) = subdiv::subdivide(&m, subdiv::Scheme::Midpoint, 2, &Default::default()).unwrap();
    let mut out = vec![glam::Vec3::ZERO; m.positions.len()];
    for _ in 0..3 {
        let t = Instant::now();
        let lv = Level::new(&m.ct);
        let t1 = t.elapsed();
        ring_sums(&lv, &m.positions, &mut out);
        println!("level {:?} ring_sums {:?} (nv={})", t1, t.elapsed() - t1, m.positions.len());
    }
    // sequential walk for comparison
    let t = Instant::now();
    let mut acc = glam::Vec3::ZERO;
    for v in 0..m.positions.len() as u32 {
        for c in m.ct.fan(v) {
            acc += m.positions[m.ct.v[subdiv::mesh::n(c) as usize] as usize];
        }
    }
    println!("1-thread naive fan walk {:?} {acc}", t.elapsed());
}
