//! Run-time choice of instruction sets for the per-frame kernels.
//!
//! The binary is built for the baseline x86_64 (SSE2) so that it runs on any
//! machine; the animation's hot loops (the stencil levels, the ring normals)
//! are compiled a second time with AVX2 and FMA enabled and chosen at run
//! time with [`avx2_fma`]. The second copy is the same Rust code: LLVM only
//! gets three-operand (VEX) encodings and SSE4.1 shuffles, and since Rust
//! never fuses a multiply and an add unless asked (`mul_add`), both copies
//! compute bit-identical results.

use std::sync::atomic::{AtomicBool, Ordering};

static BASELINE: AtomicBool = AtomicBool::new(false);

/// Makes every kernel run its baseline copy (`true`) or the fastest one the
/// CPU has (`false`, the default): for comparing the two.
pub fn force_baseline(on: bool) {
    BASELINE.store(on, Ordering::Relaxed);
}

/// Whether this CPU has AVX2 and FMA (detected once, then cached by std)
/// and [`force_baseline`] is off.
#[inline]
pub fn avx2_fma() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        !BASELINE.load(Ordering::Relaxed)
            && std::arch::is_x86_feature_detected!("avx2")
            && std::arch::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Defines `$name`, which runs `$body` (a closure-free function body over
/// the given arguments) compiled with AVX2 and FMA where the CPU has them,
/// else compiled for the baseline.
macro_rules! multiversion {
    ($(#[$m:meta])* $vis:vis fn $name:ident $(<$($g:ident: $b:path),*>)? ($($a:ident: $t:ty),* $(,)?) $body:block) => {
        $(#[$m])* $vis fn $name $(<$($g: $b),*>)? ($($a: $t),*) {
            #[inline(always)]
            fn body $(<$($g: $b),*>)? ($($a: $t),*) $body
            #[cfg(target_arch = "x86_64")]
            #[target_feature(enable = "avx2,fma")]
            fn fast $(<$($g: $b),*>)? ($($a: $t),*) { body($($a),*) }
            #[cfg(target_arch = "x86_64")]
            if $crate::cpu::avx2_fma() {
                // SAFETY: `fast` only needs AVX2 and FMA, which this CPU was
                // just found to have.
                return unsafe { fast($($a),*) };
            }
            body($($a),*)
        }
    };
}
pub(crate) use multiversion;

/// Asks the CPU to bring `slice[i]` into its caches (nothing when `i` is out
/// of bounds, or on other architectures): for passes that gather from large
/// arrays in an order they know a few iterations ahead, so that the misses
/// of many iterations overlap instead of each stalling its own.
#[inline(always)]
pub(crate) fn prefetch<T>(slice: &[T], i: usize) {
    #[cfg(target_arch = "x86_64")]
    if let Some(x) = slice.get(i) {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        // SAFETY: SSE, which `_mm_prefetch` needs, is part of the x86_64
        // baseline; a prefetch reads nothing into the program and cannot
        // fault, and the address is an element of the slice besides.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(std::ptr::from_ref(x).cast()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (slice, i);
}
