//! The timer behind the statistics (`Stats`' milliseconds) and the viewer's
//! frame clock: the standard library's `Instant` where the platform has a
//! clock, and on WebAssembly without an operating system
//! (`wasm32-unknown-unknown`, where `std::time::Instant::now` panics) the
//! page's `performance.now()` through `web-time`, the same interface.

#[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
pub(crate) use std::time::Instant;

#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
pub(crate) use web_time::Instant;
