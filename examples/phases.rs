//! Per-phase timing of the subdivision call that `subdiv subdivide` makes
//! (`subdivide_faces`, `subdivide_faces`: the last level without its
//! adjacency), input loaded once:
//! `cargo run --release --no-default-features --example phases -- MODEL LEVELS REPEATS [SCHEME...]`
//! prints, per scheme, the minimum over the repeats of every phase (ms), which
//! is what counts on a shared, noisy machine. Repeats after the first reuse
//! the memory the one before freed, as the command line's levels do, so the
//! minimum is the subdivision without fresh pages (`minflt=0`); a cold
//! process is `subdiv subdivide --stats`.

use std::path::Path;
use subdiv::{Options, Scheme, subdivide_faces};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model = args.get(1).map_or("../shared/models/stanford-bunny-compact.obj", String::as_str);
    let levels: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    let reps: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(7);
    let schemes: Vec<Scheme> =
        if args.len() > 4 { args[4..].iter().map(|s| s.parse().unwrap()).collect() } else { Scheme::ALL.to_vec() };
    // as the command line does: freed levels serve the next allocations, so
    // that repeats after the first measure the work without fresh pages
    subdiv::mem::keep_freed_memory();
    let mesh = subdiv::bundled::load(Path::new(model)).unwrap();
    let poly = subdiv::mesh::PolyMesh::from_mesh(&mesh);
    for s in schemes {
        let mut best = [f64::MAX; 8];
        for _ in 0..reps {
            let r0 = usage();
            let (m, st) = match s.is_polygonal() {
                // the polygons the file holds, as `subdiv subdivide` takes them
                true => subdivide_faces(&poly, s, levels, &Options::default(), |j| j).unwrap(),
                false => subdivide_faces(&mesh, s, levels, &Options::default(), |j| j).unwrap(),
            };
            let r1 = usage();
            std::hint::black_box(m.positions.len());
            let cpu = [r1[0] - r0[0], r1[1] - r0[1], r1[2] - r0[2]];
            for (b, x) in best.iter_mut().zip([
                st.total_ms,
                st.split_ms,
                st.numbering_ms,
                st.edge_ms,
                st.vertex_ms,
                cpu[0],
                cpu[1],
                cpu[2],
            ]) {
                *b = b.min(x);
            }
        }
        println!(
            "{:<20} total={:7.1} split={:6.1} (numbering={:5.1}) edge={:6.1} vertex={:6.1} user={:6.1} sys={:6.1} minflt={}",
            s.name(),
            best[0],
            best[1],
            best[2],
            best[3],
            best[4],
            best[5],
            best[6],
            best[7]
        );
    }
}

/// (user ms, system ms, minor faults) of this process so far.
fn usage() -> [f64; 3] {
    // SAFETY: getrusage fills the struct it is given.
    let r = unsafe {
        let mut r: libc::rusage = std::mem::zeroed();
        libc::getrusage(libc::RUSAGE_SELF, &mut r);
        r
    };
    let ms = |t: libc::timeval| t.tv_sec as f64 * 1e3 + t.tv_usec as f64 / 1e3;
    [ms(r.ru_utime), ms(r.ru_stime), r.ru_minflt as f64]
}
