//! Criterion benches: every scheme at levels 1-3 on a generated icosphere
//! (throughput in output faces, so the per-face cost across levels can be
//! compared: it should stay flat), the same on the Stanford bunny when
//! ../shared/models is present, and the animation's per-frame re-evaluation
//! through a stencil plan against a full re-subdivision.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group};
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;
use subdiv::anim::{Animation, Paths, Tweak};
use subdiv::mesh::icosphere;
use subdiv::{Mesh, Options, Scheme, subdivide};

fn per_level(c: &mut Criterion, group: &str, mesh: &Mesh, levels: &[u32]) {
    let mut g = c.benchmark_group(group);
    g.sample_size(10).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(2));
    let opts = Options::default();
    for scheme in Scheme::TRIANGLE {
        for &l in levels {
            let faces = mesh.ct.num_triangles() as u64 * 4u64.pow(l);
            g.throughput(Throughput::Elements(faces));
            g.bench_with_input(BenchmarkId::new(scheme.name(), format!("L{l}")), &l, |b, &l| {
                b.iter(|| black_box(subdivide(mesh, scheme, l, &opts).unwrap().0.positions.len()))
            });
        }
    }
    g.finish();
}

fn schemes(c: &mut Criterion) {
    // 1280 faces: levels 1..5 give 5k .. 1.3M faces
    per_level(c, "icosphere3", &icosphere(3), &[1, 2, 3, 4, 5]);
    let bunny = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/models/stanford-bunny-compact.obj");
    if let Ok(m) = subdiv::bundled::load(&bunny) {
        per_level(c, "bunny", &m, &[1, 2, 3]);
    }
}

fn animation(c: &mut Criterion) {
    let mut g = c.benchmark_group("anim_frame");
    g.sample_size(10).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(3));
    let tet = subdiv::bundled::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models/tetrahedron.obj")).unwrap();
    let mut cases = vec![("tetrahedron_L5", tet, 5)];
    let bunny = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/models/stanford-bunny-compact.obj");
    if let Ok(m) = subdiv::bundled::load(&bunny) {
        cases.push(("bunny_L2", m, 2));
    }
    for (name, mesh, level) in cases {
        let paths = Paths::generated(&mesh, 4);
        let mut anim =
            Animation::new(&mesh, &paths, Tweak::Jarek, 3, Scheme::Loop, level, &Options::default()).unwrap();
        let mut f = 0;
        g.bench_function(BenchmarkId::new("plan_positions_normals", name), |b| {
            b.iter(|| {
                f += 1;
                black_box(anim.evaluate(f).1.len())
            })
        });
        // positions only, as OpenSubdiv's StencilTable::UpdateValues (osd_bench --frames)
        let plan = anim.plan().clone();
        let mut scratch = subdiv::rules::PlanScratch::for_plan(&plan);
        let mut out = Vec::new();
        g.bench_function(BenchmarkId::new("plan_positions", name), |b| {
            b.iter(|| {
                f += 1;
                plan.apply(anim.control(f), &mut scratch, &mut out);
                black_box(out.len())
            })
        });
        let control = Mesh { ct: mesh.ct.clone(), positions: anim.control(3).to_vec() };
        g.bench_function(BenchmarkId::new("full_subdivision_normals", name), |b| {
            b.iter(|| {
                let (m, _) = subdivide(&control, Scheme::Loop, level, &Options::default()).unwrap();
                black_box(m.vertex_normals().len())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, schemes, animation);

/// Makes glibc keep freed blocks up to 32 MiB (its maximum mmap threshold)
/// in the heap instead of unmapping them, so that every level of the
/// per-level group reuses memory between iterations the same way. Without
/// it, the threshold adapts to the first iterations and only the largest
/// level (L5: ~16 MB arrays) gets fresh pages, and the kernel's zeroing of
/// them, on every iteration: a step in the per-face cost that comes from the
/// allocator, not from the algorithm. (The CLI pays first touch at every
/// level; `examples/phases` measures that.)
fn tune_allocator() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only changes allocator parameters; called before any
    // other thread exists.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 32 << 20);
        libc::mallopt(libc::M_TRIM_THRESHOLD, i32::MAX);
    }
}

fn main() {
    tune_allocator();
    benches();
    Criterion::default().configure_from_args().final_summary();
}
