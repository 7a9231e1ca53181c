//! Allocation of the large per-level arrays.
//!
//! A subdivision level writes hundreds of megabytes into fresh memory, and
//! with 4 KiB pages the first touch of every page (a fault plus the kernel
//! zeroing it) costs more than the arithmetic. Arrays are therefore taken
//! from `calloc` (fresh zero pages, no user-space memset) and, by default,
//! given 2 MiB pages (`MADV_HUGEPAGE`, 512 times fewer faults) and
//! pre-faulted at allocation (`MADV_POPULATE_WRITE`), in 2 MiB pieces
//! spread over rayon's threads: the kernel fills the page tables in one call
//! per piece instead of taking one fault per page inside the passes that
//! write the array (which fault in scattered order where they write through
//! `O`).
//!
//! Huge pages are not always cheap. On a virtual machine whose balloon
//! device reports free memory to the host in 2 MiB blocks (virtio-balloon
//! free page reporting, `page_reporting_order` 9), a host that discards the
//! reported blocks makes the first touch of one fault on the host as well,
//! and a huge page is always such a block: on one such host 256 MiB of huge
//! pages took 25 ms to touch right after a previous run and 540-670 ms after
//! six idle seconds, while 4 KiB pages took 100-110 ms either way
//! (`scripts/page-cost.c`). A kernel short of free 2 MiB blocks compacts
//! memory in the fault, which is slow too. So every whole 2 MiB piece is
//! timed as it is faulted in, and the second one slower than
//! `SlowHugePages::LIMIT` turns the rest of the process to 4 KiB pages,
//! still pre-faulted (`huge_pages` tells which are in use). Measured in
//! cold runs, interleaved (docs/performance.md, "Page policy"): bunny Loop L3
//! on one thread 70.8 against 84.4 ms with 4 KiB pages pre-faulted.
//!
//! `SUBDIV_MEM=plain|huge|populate|huge-populate` selects a fixed policy for
//! measuring (`plain`: no advice; `populate`: 4 KiB pages pre-faulted in
//! 1 MiB pieces; `huge-populate`: both, untimed); anything else means the
//! default.
//!
//! Within one process the cheapest page is one already faulted in:
//! [`keep_freed_memory`] lets glibc hand the arrays a level frees (the level
//! before, the split's scratch) to the ones allocated next, instead of
//! unmapping them and faulting fresh pages in.

use bytemuck::Zeroable;

/// Arrays smaller than this are left to the allocator's defaults (no advice).
#[cfg_attr(not(target_os = "linux"), allow(dead_code))]
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

/// How fresh large arrays are backed (`SUBDIV_MEM`, for measuring; Linux
/// only).
#[cfg_attr(not(target_os = "linux"), allow(dead_code))]
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Policy {
    /// No advice: 4 KiB pages faulted on first touch.
    Plain,
    /// `MADV_HUGEPAGE`.
    Huge,
    /// `MADV_POPULATE_WRITE`: every page faulted in up front.
    Populate,
    /// Both.
    HugePopulate,
    /// Both while huge pages come cheap, then 4 KiB pages pre-faulted
    /// (the default; [`SlowHugePages`]).
    Adaptive,
}

#[cfg_attr(not(target_os = "linux"), allow(dead_code))]
fn policy() -> Policy {
    static P: std::sync::OnceLock<Policy> = std::sync::OnceLock::new();
    *P.get_or_init(|| match std::env::var("SUBDIV_MEM").as_deref() {
        Ok("huge") => Policy::Huge,
        Ok("plain") => Policy::Plain,
        Ok("populate") => Policy::Populate,
        Ok("huge-populate") => Policy::HugePopulate,
        _ => Policy::Adaptive,
    })
}

/// Whether the large arrays this process allocates now get huge pages: by
/// the policy, and for the default one, while no slow huge page was met.
pub(crate) fn huge_pages() -> bool {
    #[cfg(target_os = "linux")]
    return match policy() {
        Policy::Huge | Policy::HugePopulate => true,
        Policy::Adaptive => !SlowHugePages::met(),
        Policy::Plain | Policy::Populate => false,
    };
    #[cfg(not(target_os = "linux"))]
    false
}

/// Whether this process has met slow huge pages: two 2 MiB blocks whose
/// pre-faulting took longer than [`SlowHugePages::LIMIT`] each. A fresh huge
/// page costs the kernel's zeroing of 2 MiB (0.2-0.46 ms on the machines we
/// measure on); one the hypervisor took back (free page reporting) costs
/// 4-5.5 ms, a fault on the host too, and so does one the kernel had to
/// compact memory for. Two, not one, so that a single block whose thread
/// was descheduled on a busy host does not decide for the whole process;
/// after the second every later array of the process gets 4 KiB pages.
#[cfg(target_os = "linux")]
struct SlowHugePages;

#[cfg(target_os = "linux")]
impl SlowHugePages {
    /// Three to seven times a fresh block's cost, a third of a reclaimed
    /// one's; a block of 4 KiB pages pre-faulted takes 0.7-0.9 ms.
    const LIMIT: std::time::Duration = std::time::Duration::from_micros(1500);
    /// Slow blocks that turn the process to 4 KiB pages.
    const TRIP: u32 = 2;

    fn count() -> &'static std::sync::atomic::AtomicU32 {
        static SLOW: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
        &SLOW
    }

    fn met() -> bool {
        Self::count().load(std::sync::atomic::Ordering::Relaxed) >= Self::TRIP
    }

    /// Records the time a whole 2 MiB block took to fault in.
    fn record(took: std::time::Duration) {
        if took > Self::LIMIT {
            Self::count().fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
    }
}

/// 2 MiB: the huge page size, and the piece the adaptive policy times.
#[cfg(target_os = "linux")]
const HP: usize = 2 << 20;

#[cfg(target_os = "linux")]
fn advise(ptr: *mut u8, len: usize) {
    if len < HUGE_MIN {
        return;
    }
    // only whole 2 MiB-aligned stretches can become huge pages
    let start = (ptr as usize).div_ceil(HP) * HP;
    let end = (ptr as usize + len) / HP * HP;
    let p = policy();
    let huge = huge_pages();
    // after slow huge pages, the default policy says so explicitly: with
    // transparent huge pages `always`, no advice would still mean huge ones
    let advice = match (huge, p) {
        (true, _) => Some(libc::MADV_HUGEPAGE),
        (false, Policy::Adaptive) => Some(libc::MADV_NOHUGEPAGE),
        (false, _) => None,
    };
    if let Some(advice) = advice.filter(|_| end > start) {
        // SAFETY: [start, end) lies inside the allocation just made; madvise
        // with MADV_(NO)HUGEPAGE changes no contents, only how pages are
        // backed.
        unsafe {
            libc::madvise(start as *mut libc::c_void, end - start, advice);
        }
    }
    if matches!(p, Policy::Populate | Policy::HugePopulate | Policy::Adaptive) {
        populate(ptr as usize, len, huge, p == Policy::Adaptive);
    }
}

/// Faults in the pages of `[ptr, ptr + len)` with `MADV_POPULATE_WRITE`,
/// in pieces spread over rayon's threads: 1 MiB pieces of 4 KiB pages, or
/// 2 MiB-aligned pieces where the range was advised `huge`. With `timed`,
/// each whole 2 MiB piece is timed ([`SlowHugePages`]), and once slow ones
/// are met the pieces not yet faulted are advised back to 4 KiB pages.
#[cfg(target_os = "linux")]
fn populate(ptr: usize, len: usize, huge: bool, timed: bool) {
    use rayon::prelude::*;
    const PAGE: usize = 4096;
    let start = ptr.div_ceil(PAGE) * PAGE;
    let end = (ptr + len) / PAGE * PAGE;
    if end <= start {
        return;
    }
    let step = if huge { HP } else { 1 << 20 };
    let first = start / step * step;
    (first..end).into_par_iter().step_by(step).for_each(|a| {
        let (a, b) = (a.max(start), (a + step).min(end));
        let whole = huge && b - a == HP;
        if timed && whole && SlowHugePages::met() {
            // SAFETY: [a, b) lies inside the allocation just made and owned
            // by the caller; MADV_NOHUGEPAGE changes no contents.
            unsafe {
                libc::madvise(a as *mut libc::c_void, b - a, libc::MADV_NOHUGEPAGE);
            }
        }
        let t0 = crate::clock::Instant::now();
        // SAFETY: [a, b) lies inside the allocation just made and owned by
        // the caller; MADV_POPULATE_WRITE only faults its pages in
        // (writable, still zero), changing no contents.
        unsafe {
            libc::madvise(a as *mut libc::c_void, b - a, libc::MADV_POPULATE_WRITE);
        }
        if timed && whole {
            SlowHugePages::record(t0.elapsed());
        }
    });
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

/// The process's address-space limit (`RLIMIT_AS`), when one is set; on
/// `wasm32` the 4 GiB a 32-bit linear memory can grow to (a browser's
/// page or node: past it an allocation traps instead of failing).
fn address_space_limit() -> Option<u64> {
    #[cfg(target_arch = "wasm32")]
    return Some(4 << 30);
    #[cfg(all(unix, not(target_arch = "wasm32")))]
    {
        let mut r = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
        // SAFETY: getrlimit writes the limit into the struct we own and
        // reads nothing else of ours.
        let ok = unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut r) } == 0;
        // rlim_t is u64 on Linux but not everywhere
        #[allow(clippy::unnecessary_cast)]
        (ok && r.rlim_cur != libc::RLIM_INFINITY).then_some(r.rlim_cur as u64)
    }
    #[cfg(not(any(unix, target_arch = "wasm32")))]
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

    /// The mappings of this process wholly inside `[a, b)`, from
    /// `/proc/self/smaps`: each one's `VmFlags` and `AnonHugePages` (kB).
    #[cfg(target_os = "linux")]
    fn mappings_within(a: usize, b: usize) -> Vec<(String, u64)> {
        let smaps = std::fs::read_to_string("/proc/self/smaps").expect("smaps");
        let mut out = Vec::new();
        let mut inside = false;
        let mut huge_kb = 0;
        for line in smaps.lines() {
            let first = line.split_whitespace().next().unwrap_or("");
            if let Some((lo, hi)) = first.split_once('-')
                && let (Ok(lo), Ok(hi)) = (usize::from_str_radix(lo, 16), usize::from_str_radix(hi, 16))
            {
                inside = a <= lo && hi <= b;
            } else if let Some(kb) = line.strip_prefix("AnonHugePages:") {
                huge_kb = kb.trim().trim_end_matches("kB").trim().parse().unwrap_or(0);
            } else if let Some(flags) = line.strip_prefix("VmFlags:")
                && inside
            {
                out.push((flags.to_string(), huge_kb));
            }
        }
        out
    }

    /// Once slow huge pages are met, later arrays are advised 4 KiB pages
    /// (`MADV_NOHUGEPAGE`, which holds under transparent huge pages
    /// `always` too) and still come zeroed and writable.
    #[cfg(target_os = "linux")]
    #[test]
    fn slow_huge_pages_turn_later_arrays_to_small_pages() {
        use super::{HP, SlowHugePages};
        for _ in 0..SlowHugePages::TRIP {
            SlowHugePages::record(SlowHugePages::LIMIT * 2);
        }
        assert!(SlowHugePages::met());
        let n = 3 << 20;
        let mut v: Vec<u64> = super::zeroed(n);
        assert!(v.iter().all(|&x| x == 0));
        v[n - 1] = 9;
        assert_eq!(v.iter().sum::<u64>(), 9);
        // the whole 2 MiB blocks of the array: advised, and no huge page
        let p = v.as_ptr() as usize;
        let (a, b) = (p.div_ceil(HP) * HP, (p + 8 * n) / HP * HP);
        let maps = mappings_within(a, b);
        assert!(!maps.is_empty(), "the advice splits the array's blocks into mappings of their own");
        for (flags, huge_kb) in maps {
            assert!(flags.split_whitespace().any(|f| f == "nh"), "not advised MADV_NOHUGEPAGE: {flags}");
            assert_eq!(huge_kb, 0, "huge pages after slow ones");
        }
    }
}
