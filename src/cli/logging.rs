//! The log backend of the command line: records of the library and of its
//! dependencies (wgpu's validation and adapter warnings) on stderr, as
//! `subdiv: warning: [target] message`. `-q` keeps errors only, the default
//! shows warnings, `-v` info, `-vv` debug, `-vvv` trace; `RUST_LOG=LEVEL`
//! (error, warn, info, debug, trace or off) sets the level when neither flag
//! is given.

use log::{Level, LevelFilter, Log, Metadata, Record};

struct Stderr;

impl Log for Stderr {
    fn enabled(&self, m: &Metadata) -> bool {
        m.level() <= log::max_level()
    }

    fn log(&self, r: &Record) {
        if !self.enabled(r.metadata()) {
            return;
        }
        let level = match r.level() {
            Level::Error => "error",
            Level::Warn => "warning",
            Level::Info => "info",
            Level::Debug => "debug",
            Level::Trace => "trace",
        };
        eprintln!("subdiv: {level}: [{}] {}", r.target(), r.args());
    }

    fn flush(&self) {}
}

static LOGGER: Stderr = Stderr;

/// The level for the flags (and `RUST_LOG` when neither is given).
pub(crate) fn level(quiet: bool, verbose: u8, env: Option<&str>) -> LevelFilter {
    if quiet {
        return LevelFilter::Error;
    }
    match verbose {
        0 => env.and_then(|s| s.trim().parse().ok()).unwrap_or(LevelFilter::Warn),
        1 => LevelFilter::Info,
        2 => LevelFilter::Debug,
        _ => LevelFilter::Trace,
    }
}

/// Installs the backend at the level the flags ask for.
pub(crate) fn init(quiet: bool, verbose: u8) {
    let env = std::env::var("RUST_LOG").ok();
    log::set_max_level(level(quiet, verbose, env.as_deref()));
    // a second init (none happens) would keep the first backend
    let _ = log::set_logger(&LOGGER);
}

/// Whether warnings and notes are shown (not `-q`).
pub(crate) fn warnings_shown() -> bool {
    log::max_level() >= LevelFilter::Warn
}
