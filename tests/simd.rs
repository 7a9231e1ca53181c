//! The per-frame kernels compiled for AVX2 and FMA give the same bits as
//! their baseline (SSE2) copies: Rust fuses no multiply-add unless asked, so
//! only the encodings differ (src/cpu.rs). Alone in its binary because it
//! flips the process-wide switch.

use subdiv::anim::{Animation, Paths, Tweak};
use subdiv::{Options, Scheme};

#[test]
fn avx2_kernels_equal_the_baseline_bit_for_bit() {
    if !subdiv::cpu::avx2_fma() {
        eprintln!("this CPU has no AVX2 and FMA: only the baseline kernels exist here");
    }
    let control = subdiv::bundled::load(std::path::Path::new("bundled:torus.obj")).unwrap();
    let paths = Paths::generated(&control, 4);
    for scheme in [Scheme::Loop, Scheme::ModifiedButterfly] {
        let mut anim = Animation::new(&control, &paths, Tweak::Jarek, 2, scheme, 3, &Options::default()).unwrap();
        for f in [0, 5] {
            subdiv::cpu::force_baseline(false);
            let (p, n) = anim.evaluate(f);
            let (fast_p, fast_n) = (p.to_vec(), n.to_vec());
            subdiv::cpu::force_baseline(true);
            let (p, n) = anim.evaluate(f);
            let bits = |v: &[glam::Vec3]| v.iter().flat_map(|q| q.to_array().map(f32::to_bits)).collect::<Vec<_>>();
            assert_eq!(bits(&fast_p), bits(p), "{scheme:?} frame {f}: positions");
            assert_eq!(bits(&fast_n), bits(n), "{scheme:?} frame {f}: normals");
            assert!(fast_p.len() > control.positions.len() * 16, "level 3 refines");
        }
    }
    subdiv::cpu::force_baseline(false);
}
