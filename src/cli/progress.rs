//! Progress on long work (big subdivisions, animation export) as an
//! indicatif bar on stderr, drawn only when stderr is a terminal and `-q` was
//! not given: piped or captured output never sees it.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Set by `subdiv batch`'s bar: the spinners of single files are not drawn.
static SPINNERS_OFF: AtomicBool = AtomicBool::new(false);

/// Whether bars are drawn here.
fn shown() -> bool {
    super::logging::warnings_shown() && std::io::stderr().is_terminal()
}

/// A bar over `total` steps named `what` (hidden where bars are not shown).
#[cfg(feature = "viewer")]
pub(crate) fn bar(total: u64, what: &str) -> ProgressBar {
    if !shown() {
        return ProgressBar::hidden();
    }
    let style = ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} ({eta})")
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> ");
    ProgressBar::new(total).with_style(style).with_message(what.to_string())
}

/// A spinner for work of unknown length (one big library call), ticking by
/// itself until finished.
pub(crate) fn spinner(what: &str) -> ProgressBar {
    if !shown() || SPINNERS_OFF.load(Ordering::Relaxed) {
        return ProgressBar::hidden();
    }
    let style =
        ProgressStyle::with_template("{spinner} {msg} {elapsed}").unwrap_or_else(|_| ProgressStyle::default_spinner());
    let pb = ProgressBar::new_spinner().with_style(style).with_message(what.to_string());
    pb.enable_steady_tick(Duration::from_millis(120));
    pb
}

/// The bar of `subdiv batch` over its `total` files (its message: the
/// failures and faces per second, set by the batch), or `None` where bars
/// are not shown (the batch logs a line per file instead). From then on
/// the spinners of single files are not drawn: the bar stands for them.
pub(crate) fn files(total: u64) -> Option<ProgressBar> {
    if !shown() {
        return None;
    }
    SPINNERS_OFF.store(true, Ordering::Relaxed);
    let style = ProgressStyle::with_template("[{bar:40}] {pos}/{len} files, {msg} ({eta} left)")
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> ");
    let pb = ProgressBar::new(total).with_style(style).with_message("0 failed");
    pb.enable_steady_tick(Duration::from_millis(500));
    Some(pb)
}
