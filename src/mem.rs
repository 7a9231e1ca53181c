//! Allocation of the large per-level arrays.
//!
//! A subdivision level writes hundreds of megabytes into fresh memory, and
//! with 4 KiB pages the first touch of every page (a fault plus the kernel
//! zeroing it) costs more than the arithmetic. Arrays are therefore taken
//! from `calloc` (fresh zero pages, no user-space memset).
//!
//! By default every large array is pre-faulted at allocation
//! (`MADV_POPULATE_WRITE`), in 1 MiB pieces spread over rayon's threads:
//! the kernel fills the page tables in one call per piece instead of taking
//! one fault per page inside the passes that write the array (which fault
//! in scattered order where they write through `O`). Measured in cold runs
//! (one process each, as a user runs a command; docs/performance.md, "Page
//! policy"), interleaved, on 2 threads: bunny Loop L3 median 117 against
//! 119 ms without advice (21 runs each), nefertiti L4 575-636 against
//! 665-669 ms, with fewer slow outliers. Pre-faulting in one call on one
//! thread, as an earlier version did, was slower than no advice.
//! `MADV_HUGEPAGE` gives the fastest single runs and the slowest ones (runs
//! vary 2x to 4x: bunny Loop L3 83-166 ms, nefertiti L4 405-1664 ms); the
//! first run is the one a user sees, so steadiness wins.
//! `SUBDIV_MEM=plain|huge|populate|huge-populate` selects a policy for such
//! measurements (`plain`: no advice); anything else means `populate`.
//!
//! Why huge pages are unsteady here: the machines we measure on are virtual
//! machines whose balloon device reports free memory to the host in 2 MiB
//! blocks (virtio-balloon free page reporting, `page_reporting_order` 9);
//! the host discards them, so the first touch of a reported block faults on
//! the host as well. A huge page is always such a block (`scripts/page-cost.c`): 256 MiB of huge
//! pages took 25 ms to touch right after a previous run and 540-670 ms after
//! six idle seconds, while 4 KiB pages took 100-110 ms either way.
//!
//! Within one process the cheapest page is one already faulted in:
//! [`keep_freed_memory`] lets glibc hand the arrays a level frees (the level
//! before, the split's scratch) to the ones allocated next, instead of
//! unmapping them and faulting fresh pages in.

use bytemuck::Zeroable;

/// Arrays smaller than this are left to the allocator's defaults (no advice).
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
        advise(ptr as *mut u8, layout.size());
        Vec::from_raw_parts(ptr, n, n)
    }
}

/// Makes the allocator keep freed memory for later allocations of this
/// process instead of giving it back to the kernel: glibc's mmap threshold
/// (large blocks from `mmap`, unmapped on `free`) and trim threshold
/// (the top of the heap returned to the kernel) raised to 1 GiB. For short
/// batch commands, where it saves the unmapping of every freed level and the
/// page faults of reusing that memory (docs/performance.md, "Page policy",
/// has the figures); the peak resident memory grows by the freed blocks
/// that could not be reused (bunny L3: 212 to 245 MB). A long-running
/// process (the viewer) should not call it. Other platforms and C
/// libraries: does nothing.
pub fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only sets two of glibc's tuning parameters (it takes
    // the allocator's lock itself); every value is valid for both.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 1 << 30);
        libc::mallopt(libc::M_TRIM_THRESHOLD, 1 << 30);
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
        Ok("plain") => Policy::Plain,
        Ok("huge-populate") => Policy::HugePopulate,
        _ => Policy::Populate,
    })
}

#[cfg(target_os = "linux")]
fn advise(ptr: *mut u8, len: usize) {
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
            use rayon::prelude::*;
            const STEP: usize = 1 << 20;
            (start..end).into_par_iter().step_by(STEP).for_each(|a| {
                let b = (a + STEP).min(end);
                // SAFETY: [a, b) lies inside the allocation just made and
                // owned by the caller; MADV_POPULATE_WRITE only faults its pages
                // in (writable, still zero), changing no contents.
                unsafe {
                    libc::madvise(a as *mut libc::c_void, b - a, libc::MADV_POPULATE_WRITE);
                }
            });
        }
    }
}

#[cfg(not(target_os = "linux"))]
fn advise(_ptr: *mut u8, _len: usize) {}

/// Bytes this process can still be given: 80% of the machine's
/// `MemAvailable`, and no more than half the process's address-space limit
/// (`ulimit -v`) where one is set; `None` when neither is known.
pub fn default_memory_limit() -> Option<u64> {
    let available = || -> Option<u64> {
        let s = std::fs::read_to_string("/proc/meminfo").ok()?;
        let line = s.lines().find(|l| l.starts_with("MemAvailable:"))?;
        let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
        Some(kb * 1024 / 5 * 4)
    };
    match (available(), address_space_limit().map(|l| l / 2)) {
        (Some(a), Some(l)) => Some(a.min(l)),
        (a, l) => a.or(l),
    }
}

/// The process's address-space limit (`RLIMIT_AS`), when one is set.
fn address_space_limit() -> Option<u64> {
    #[cfg(unix)]
    {
        let mut r = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
        // SAFETY: getrlimit writes the limit into the struct we own and
        // reads nothing else of ours.
        let ok = unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut r) } == 0;
        // rlim_t is u64 on Linux but not everywhere
        #[allow(clippy::unnecessary_cast)]
        (ok && r.rlim_cur != libc::RLIM_INFINITY).then_some(r.rlim_cur as u64)
    }
    #[cfg(not(unix))]
    None
}

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
