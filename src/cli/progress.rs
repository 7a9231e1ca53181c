//! Progress on long work (big subdivisions, animation export) as an
//! indicatif bar on stderr, drawn only when stderr is a terminal and `-q` was
//! not given: piped or captured output never sees it.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::time::Duration;

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
    if !shown() {
        return ProgressBar::hidden();
    }
    let style =
        ProgressStyle::with_template("{spinner} {msg} {elapsed}").unwrap_or_else(|_| ProgressStyle::default_spinner());
    let pb = ProgressBar::new_spinner().with_style(style).with_message(what.to_string());
    pb.enable_steady_tick(Duration::from_millis(120));
    pb
}
