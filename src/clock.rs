//! The timer behind the statistics (`Stats`' milliseconds): the standard
//! library's `Instant` where the platform has a clock, and on WebAssembly
//! without an operating system (`wasm32-unknown-unknown`, where
//! `std::time::Instant::now` panics) a timer that reads zero, so that the
//! library runs in a browser with its timings reported as 0 ms.

#[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
pub(crate) use std::time::Instant;

#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
pub(crate) use zero::Instant;

#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
mod zero {
    use std::time::Duration;

    /// A moment of a clock that never advances.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
    pub(crate) struct Instant;

    impl Instant {
        /// Now (always the same moment).
        pub(crate) fn now() -> Instant {
            Instant
        }
        /// The time since this moment: zero.
        pub(crate) fn elapsed(&self) -> Duration {
            Duration::ZERO
        }
    }

    impl std::ops::Sub for Instant {
        type Output = Duration;
        fn sub(self, _: Instant) -> Duration {
            Duration::ZERO
        }
    }
}
