//! What an edit of the cage costs on the refiner (the figures in
//! docs/performance.md), minima over repetitions in one process:
//!
//! - `one_vertex_us`: one random control vertex moved (its support's rows
//!   at every level and the normals around them);
//! - `hundred_us`: a proportional edit of the 100 control vertices nearest
//!   a random one (smooth falloff);
//! - `sharpness_ms`: one edge made semi-sharp (2.5), the stencils recorded
//!   again;
//! - `full_ms`: every row and normal of every level evaluated again
//!   ([`Refiner::set_control`] once the normals are made);
//! - `positions_ms`: the same on a refiner whose normals were never asked
//!   for (the rows alone), and `normals_ms` the difference;
//! - `build_ms`: `Refiner::new` (the one-shot passes, every level kept);
//! - `first_ms`: the first move, which records the stencils of every level
//!   on the kept tables and evaluates every level by them once.
//!
//! ```text
//! cargo run --release --example edit_latency -- MODEL LEVELS [SCHEME]
//! ```
use glam::Vec3;
use std::time::Instant;
use subdiv::{Options, Refiner, Scheme};

/// xorshift64: reproducible vertex choices.
struct Rng(u64);
impl Rng {
    fn below(&mut self, n: usize) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % n as u64) as u32
    }
}

fn min_us(reps: usize, mut f: impl FnMut(usize)) -> f64 {
    (0..reps)
        .map(|k| {
            let t = Instant::now();
            f(k);
            t.elapsed().as_secs_f64() * 1e6
        })
        .fold(f64::MAX, f64::min)
}

/// The `k` control vertices nearest `v` and their falloff weights.
fn proportional(control: &[Vec3], v: u32, k: usize) -> (Vec<u32>, Vec<f32>) {
    let c = control[v as usize];
    let mut ids: Vec<u32> = (0..control.len() as u32).collect();
    ids.sort_by(|&a, &b| c.distance_squared(control[a as usize]).total_cmp(&c.distance_squared(control[b as usize])));
    ids.truncate(k);
    let radius = ids.last().map_or(1.0, |&f| c.distance(control[f as usize])).max(1e-12);
    let w = ids.iter().map(|&i| 1.0 - (c.distance(control[i as usize]) / radius).powi(2)).collect();
    (ids, w)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (Some(model), Some(levels)) = (args.get(1), args.get(2)) else {
        return Err("usage: edit_latency MODEL LEVELS [SCHEME]".into());
    };
    let scheme: Scheme = args.get(3).map_or(Ok(Scheme::Loop), |s| s.parse()).map_err(|e: String| e)?;
    // repaired where it is not a manifold (some scans and sculpts are not)
    let opts = subdiv::io::ReadOptions { topology: subdiv::io::Topology::Repair, ..Default::default() };
    let mesh = subdiv::io::read(subdiv::io::Source::File(std::path::Path::new(model)), &opts)?.mesh;
    let t = Instant::now();
    let mut r = Refiner::new(&mesh, scheme, levels.parse()?, &Options::default())?;
    let build_ms = t.elapsed().as_secs_f64() * 1e3;
    let t = Instant::now();
    r.move_vertices(&[0], &[mesh.positions[0]])?;
    let first_ms = t.elapsed().as_secs_f64() * 1e3;
    // as a viewer draws them: every edit below keeps the normals up to date
    let _ = r.normals();
    let n = mesh.positions.len();
    let (lo, hi) = mesh.positions.iter().fold((Vec3::MAX, Vec3::MIN), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let step = lo.distance(hi) * 1e-3;
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let one = min_us(200, |k| {
        let v = rng.below(n);
        let to = r.control()[v as usize] + Vec3::splat(if k % 2 == 0 { step } else { -step });
        r.move_vertices(&[v], &[to]).expect("a control vertex");
    });
    // the selections are made before the clock runs (a viewer makes them on click)
    let picks: Vec<(Vec<u32>, Vec<f32>)> = (0..50).map(|_| proportional(r.control(), rng.below(n), 100)).collect();
    let hundred = min_us(50, |k| {
        let (ids, w) = &picks[k];
        let d = Vec3::new(0.0, 0.0, if k % 2 == 0 { step } else { -step });
        let to: Vec<Vec3> = ids.iter().zip(w).map(|(&i, &w)| r.control()[i as usize] + d * w).collect();
        r.move_vertices(ids, &to).expect("control vertices");
    });
    let (a, b) = (mesh.ct.v_table()[0], mesh.ct.v_table()[1]);
    let sharp = min_us(5, |k| r.set_edge_sharpness(a, b, if k % 2 == 0 { 2.5 } else { 0.0 }).expect("an edge")) / 1e3;
    let control = r.control().to_vec();
    let full = min_us(20, |_| r.set_control(&control)) / 1e3;
    drop(r);
    // the rows alone: a refiner whose normals were never made
    let mut bare = Refiner::new(&mesh, scheme, levels.parse()?, &Options::default())?;
    let positions = min_us(20, |_| bare.set_control(&control)) / 1e3;
    let r = bare;
    println!(
        "one_vertex_us={one:.1} hundred_us={hundred:.1} sharpness_ms={sharp:.2} full_ms={full:.2} \
         positions_ms={positions:.2} normals_ms={:.2} build_ms={build_ms:.1} first_ms={first_ms:.1} faces={} threads={}",
        full - positions,
        r.topology().num_triangles(),
        rayon::current_num_threads()
    );
    Ok(())
}
