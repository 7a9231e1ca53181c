//! Allocation of the large per-level arrays.
//!
//! A subdivision level writes hundreds of megabytes into fresh memory, and
//! with 4 KiB pages the first touch of every page (a fault plus the kernel
//! zeroing it) costs more than the arithmetic. Arrays are therefore taken
//! from `calloc` (fresh zero pages, no user-space memset).
//!
//! No page advice by default. The policy was chosen by measuring cold runs
//! (one process each, as a user runs a command; docs/performance.md, "Page
//! policy"): `MADV_HUGEPAGE` has the fastest single runs, but with the
//! kernel's `defrag = madvise` a fault in an advised region may wait for
//! memory compaction, so runs vary 2x to 4x (bunny Loop L3 83-166 ms,
//! nefertiti L4 405-1664 ms on a quiet machine), while plain 4 KiB pages
//! stay within 7-17% run to run (113-127 ms and 663-775 ms) and have the
//! better median at nefertiti L4. Pre-faulting (`MADV_POPULATE_WRITE`) was
//! steady but slower, and with huge pages worst by far (the kernel compacts
//! memory for every 2 MiB page in one synchronous call). The first run is
//! the one a user sees, so steadiness wins.
//! `SUBDIV_MEM=plain|huge|populate|huge-populate` selects a policy for such
//! measurements; anything else means `plain`.

use bytemuck::Zeroable;

/// Arrays smaller than this are left to the allocator's defaults.
const HUGE_MIN: usize = 4 << 20;

/// A vector of `n` zeroed elements, backed as the page policy says.
pub fn zeroed<T: Zeroable + Clone>(n: usize) -> Vec<T> {
    // vec![zeroed; n] of a Zeroable type would memset page by page; calloc
    // gives untouched zero pages instead.
    let Ok(layout) = std::alloc::Layout::array::<T>(n) else {
        return vec![T::zeroed(); n];
    };
    if layout.size() == 0 {
        return vec![T::zeroed(); n];
    }
    // SAFETY: layout has non-zero size; an all-zero bit pattern is a valid T
    // (Zeroable), so every element is initialised; the Vec takes ownership of
    // a block allocated by the global allocator with exactly this layout.
    unsafe {
        let ptr = std::alloc::alloc_zeroed(layout) as *mut T;
        if ptr.is_null() {
            std::alloc::handle_alloc_error(layout);
        }
        advise_huge(ptr as *mut u8, layout.size());
        Vec::from_raw_parts(ptr, n, n)
    }
}

/// How fresh large arrays are backed (`SUBDIV_MEM`, for measuring).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Policy {
    /// No advice: 4 KiB pages faulted on first touch.
    Plain,
    /// `MADV_HUGEPAGE`.
    Huge,
    /// `MADV_POPULATE_WRITE`: every page faulted in one call, up front.
    Populate,
    /// Both.
    HugePopulate,
}

fn policy() -> Policy {
    static P: std::sync::OnceLock<Policy> = std::sync::OnceLock::new();
    *P.get_or_init(|| match std::env::var("SUBDIV_MEM").as_deref() {
        Ok("huge") => Policy::Huge,
        Ok("populate") => Policy::Populate,
        Ok("huge-populate") => Policy::HugePopulate,
        _ => Policy::Plain,
    })
}

#[cfg(target_os = "linux")]
fn advise_huge(ptr: *mut u8, len: usize) {
    if len < HUGE_MIN {
        return;
    }
    // only whole 2 MiB-aligned stretches can become huge pages
    const HP: usize = 2 << 20;
    let start = (ptr as usize).div_ceil(HP) * HP;
    let end = (ptr as usize + len) / HP * HP;
    let p = policy();
    if end > start && matches!(p, Policy::Huge | Policy::HugePopulate) {
        // SAFETY: [start, end) lies inside the allocation just made; madvise
        // with MADV_HUGEPAGE changes no contents, only how pages are backed.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_HUGEPAGE);
        }
    }
    if matches!(p, Policy::Populate | Policy::HugePopulate) {
        const PAGE: usize = 4096;
        let start = (ptr as usize).div_ceil(PAGE) * PAGE;
        let end = (ptr as usize + len) / PAGE * PAGE;
        if end > start {
            // SAFETY: [start, end) lies inside the allocation just made and
            // owned by the caller; MADV_POPULATE_WRITE only faults its pages
            // in (writable, still zero), changing no contents.
            unsafe {
                libc::madvise(start as *mut libc::c_void, end - start, libc::MADV_POPULATE_WRITE);
            }
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise_huge(_ptr: *mut u8, _len: usize) {}

#[cfg(test)]
mod tests {
    #[test]
    fn zeroed_vectors_are_zero_and_owned() {
        for n in [0, 1, 1000, 3 << 20] {
            let mut v: Vec<u32> = super::zeroed(n);
            assert_eq!(v.len(), n);
            assert!(v.iter().all(|&x| x == 0));
            v.push(7);
            assert_eq!(v[n], 7);
        }
        let p: Vec<glam::Vec3> = super::zeroed(5 << 20);
        assert!(p.iter().all(|x| *x == glam::Vec3::ZERO));
    }
}
