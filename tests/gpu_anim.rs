//! The animation's compute passes (render::gpu_anim) against the CPU plan:
//! the same positions within 1e-5 relative and the same normals, on the
//! bundled tetrahedron animation and a creased model, for several schemes,
//! frames drawn from either the same image, and exports evaluated on the GPU
//! (no frame on the CPU) the CPU's exports. Runs on any wgpu adapter
//! (lavapipe in CI); skips only when no adapter exists and
//! SUBDIV_REQUIRE_GPU is unset.
#![cfg(feature = "viewer")]

mod common;

use common::{bundled, offscreen, scratch_dir, share_within};
use subdiv::anim::{Animation, Paths, Tweak};
use subdiv::render::GpuAnimator;
use subdiv::render::{Camera, GpuMesh, Look, Offscreen};
use subdiv::render::{Evaluation, ExportStyle, ExportTarget, export_animation, frame_path};
use subdiv::{Mesh, Options, Scheme};

fn tetrahedron() -> (Mesh, Paths) {
    let paths = Paths::load(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("paths/tetrahedron.paths"),
        &Default::default(),
    )
    .unwrap();
    (bundled("tetrahedron.obj"), paths)
}

/// A polygon fixture (faces of 3 to 6 corners, or creased quads) with
/// generated paths.
fn polygons(name: &str) -> (Mesh, Paths) {
    let m = subdiv::bundled::load(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/catmark").join(name),
    )
    .unwrap();
    let p = Paths::generated(&m, 4);
    (m, p)
}

fn creased() -> (Mesh, Paths) {
    let m = subdiv::bundled::load(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/creases/ico_crease.obj"),
    )
    .unwrap();
    assert!(m.ct.sharpness().is_some(), "the fixture has creases");
    let p = Paths::generated(&m, 4);
    (m, p)
}

/// The GPU mesh and animator of `anim`, first filled with frame 0 from the CPU.
fn gpu_of(off: &Offscreen, anim: &mut Animation) -> (GpuMesh, GpuAnimator) {
    let (ct, p, n) = anim.evaluate_with_topology(0);
    let mesh = GpuMesh::new(&off.gpu.device, ct, p, n).unwrap();
    let a = GpuAnimator::new(&off.gpu.device, anim.plan(), &mesh).unwrap();
    (mesh, a)
}

#[test]
fn gpu_positions_and_normals_equal_the_cpu_plan() {
    let Some(off) = offscreen(16, 16) else { return };
    let (dev, queue) = (&off.gpu.device, &off.gpu.queue);
    let cases = [
        ("tetrahedron", tetrahedron(), Scheme::Loop, 4),
        // no level: the control positions are drawn as they are
        ("tetrahedron", tetrahedron(), Scheme::Loop, 0),
        ("tetrahedron", tetrahedron(), Scheme::ModifiedButterfly, 3),
        ("ico_crease", creased(), Scheme::Loop, 2),
        ("ico_crease", creased(), Scheme::Butterfly, 2),
        ("ico_crease", creased(), Scheme::Jarek, 2),
        ("ngons", polygons("ngons.obj"), Scheme::CatmullClark, 3),
        ("cube_creases", polygons("cube_creases.obj"), Scheme::CatmullClark, 2),
        ("ngons", polygons("ngons.obj"), Scheme::Bilinear, 2),
    ];
    for (name, (m, paths), scheme, level) in cases {
        let mut anim = Animation::new(&m, &paths, Tweak::Jarek, 3, scheme, level, &Options::default()).unwrap();
        let (mesh, gpu) = gpu_of(&off, &mut anim);
        // the fine positions the buffers were filled with (frame 0, on the CPU)
        let first = anim.evaluate(0).0.to_vec();
        for f in [5, 17, anim.frame_count() - 1] {
            gpu.update(dev, queue, anim.control(f)).unwrap();
            let n = anim.topology().num_vertices();
            let (gp, gn) = mesh.read_back(dev, queue).unwrap();
            let (cp, cn) = anim.evaluate(f);
            assert_eq!((gp.len(), gn.len(), cp.len(), cn.len(), first.len()), (n, n, n, n, n), "{name} {scheme}");
            let scale = cp.iter().fold(1.0f32, |s, p| s.max(p.abs().max_element()));
            for (i, (g, c)) in gp.iter().zip(cp).enumerate() {
                assert!(
                    (*g - *c).abs().max_element() <= 1e-5 * scale,
                    "{name} {scheme} frame {f} vertex {i}: {g} vs {c}"
                );
            }
            for (i, (g, c)) in gn.iter().zip(cn).enumerate() {
                assert!(g.distance(*c) < 1e-3, "{name} {scheme} frame {f} normal {i}: {g} vs {c}");
            }
            // the update really moved the buffers away from frame 0: the same
            // fine vertices, not fine ones against control points
            let moved = gp.iter().zip(&first).filter(|(g, p)| g.distance(**p) > 1e-3).count();
            assert!(moved > 0, "{name} {scheme} frame {f}: no fine vertex moved from frame 0");
        }
    }
}

#[test]
fn frames_evaluated_on_the_gpu_draw_the_cpu_image() {
    let Some(mut off) = offscreen(128, 128) else { return };
    let (m, paths) = tetrahedron();
    let mut anim = Animation::new(&m, &paths, Tweak::Jarek, 3, Scheme::Loop, 3, &Options::default()).unwrap();
    let (lo, hi) = subdiv::render::motion_bounds(&anim);
    let cam = Camera::framing(lo, hi, 1.0);
    let (gpu_mesh, gpu) = gpu_of(&off, &mut anim);
    let (ct, p, n) = anim.evaluate_with_topology(0);
    let mut cpu_mesh = GpuMesh::new(&off.gpu.device, ct, p, n).unwrap();
    let first = off.render_one(cam, &cpu_mesh, None, Look::default()).unwrap();
    for f in [7, anim.frame_count() / 2] {
        gpu.update(&off.gpu.device, &off.gpu.queue, anim.control(f)).unwrap();
        let (p, n) = anim.evaluate(f);
        cpu_mesh.update(&off.gpu.queue, p, n);
        let by_cpu = off.render_one(cam, &cpu_mesh, None, Look::default()).unwrap();
        let by_gpu = off.render_one(cam, &gpu_mesh, None, Look::default()).unwrap();
        let differ = |a: &image::RgbaImage, b: &image::RgbaImage, tol: u8| {
            a.pixels().zip(b.pixels()).filter(|(p, q)| (0..3).any(|i| p.0[i].abs_diff(q.0[i]) > tol)).count()
        };
        assert!(differ(&first, &by_cpu, 8) > 50, "frame {f} moves");
        assert!(differ(&by_cpu, &by_gpu, 2) <= 3, "frame {f}: {} pixels differ", differ(&by_cpu, &by_gpu, 2));
    }
}

/// The PNG frames of `anim` exported with `look`, evaluated where `eval`
/// says, and whether the CPU evaluated any frame of it.
fn exported(
    name: &str,
    (m, paths): &(Mesh, Paths),
    (scheme, level): (Scheme, u32),
    look: Look,
    eval: Evaluation,
) -> (Vec<image::RgbaImage>, bool) {
    let mut anim = Animation::new(m, paths, Tweak::Jarek, 1, scheme, level, &Options::default()).unwrap();
    assert!(anim.frame_ms().is_none(), "recording the plan evaluates no frame");
    let dir = scratch_dir(&format!("gpu-export-{name}-{eval:?}"));
    let style = ExportStyle { size: (96, 96), look, fps: 30.0, eval };
    let n = export_animation(&mut anim, m, &ExportTarget::Frames(dir.clone()), &style, None, |_, _| true).unwrap();
    assert_eq!(n, anim.frame_count());
    let frames = (0..n).map(|f| image::open(frame_path(&dir, f, n)).unwrap().to_rgba8()).collect();
    let _ = std::fs::remove_dir_all(&dir);
    (frames, anim.frame_ms().is_some())
}

#[test]
fn exports_evaluated_on_the_gpu_are_the_cpus_without_a_frame_evaluated_on_the_cpu() {
    if offscreen(8, 8).is_none() {
        return;
    }
    let overlay = Look { control: true, wireframe: true, ..Look::default() };
    let cases = [
        ("tetrahedron", tetrahedron(), (Scheme::Loop, 3), Look::default()),
        ("cube_creases", polygons("cube_creases.obj"), (Scheme::CatmullClark, 2), overlay),
        ("ico_crease", creased(), (Scheme::ModifiedButterfly, 2), Look::default()),
    ];
    for (name, model, sub, look) in cases {
        let (cpu, on_cpu) = exported(name, &model, sub, look, Evaluation::Cpu);
        let (gpu, gpu_on_cpu) = exported(name, &model, sub, look, Evaluation::Gpu);
        assert!(on_cpu, "{name}: the CPU export evaluates its frames on the CPU");
        assert!(!gpu_on_cpu, "{name}: the GPU export evaluated a frame on the CPU");
        assert_eq!(cpu.len(), gpu.len());
        for (f, (c, g)) in cpu.iter().zip(&gpu).enumerate() {
            let share = share_within(c, g, 8);
            assert!(share >= 0.995, "{name} frame {f}: only {:.2}% of the pixels within 8 levels", share * 100.0);
        }
        // every frame of the GPU's moves from the one before: the passes ran on each frame's control points
        for f in 1..gpu.len() {
            let moved = 1.0 - share_within(&gpu[f - 1], &gpu[f], 8);
            assert!(
                moved > 0.01,
                "{name}: GPU frame {f} is frame {} ({:.3}% of the pixels moved)",
                f - 1,
                moved * 100.0
            );
        }
    }
}
