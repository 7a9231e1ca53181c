//! A point in the caller's precision: `Vec3` (f32, what the GPU draws) or
//! `DVec3` (f64). The subdivision rules and the smoothing passes are
//! written once over it; a weight is rounded to the point's precision as
//! it is taken.

use glam::{DVec3, Vec3};

/// A point in f32 or f64 (see the module's documentation).
pub(crate) trait Coord:
    Copy
    + Send
    + Sync
    + PartialEq
    + bytemuck::Zeroable
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::AddAssign
    + 'static
{
    /// The origin.
    const ZERO: Self;
    /// `self` times the weight `w` (rounded to this precision first).
    fn times(self, w: f64) -> Self;
    /// `self` divided by `k` (in this precision).
    fn over(self, k: f64) -> Self;
}

impl Coord for Vec3 {
    const ZERO: Self = Vec3::ZERO;
    #[inline(always)]
    fn times(self, w: f64) -> Self {
        self * w as f32
    }
    #[inline(always)]
    fn over(self, k: f64) -> Self {
        self / k as f32
    }
}

impl Coord for DVec3 {
    const ZERO: Self = DVec3::ZERO;
    #[inline(always)]
    fn times(self, w: f64) -> Self {
        self * w
    }
    #[inline(always)]
    fn over(self, k: f64) -> Self {
        self / k
    }
}
