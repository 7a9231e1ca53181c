//! Tolerances: one distance everywhere, or a distance on screen that each
//! patch turns into a distance of its own from where it lies in the view.
//!
//! A point `X` of the surface lands on the screen at pixel
//! `s(X) = (W/2 · x/w, H/2 · y/w)` with `(x, y, z, w) = M (X, 1)` (`M` the
//! world-to-clip matrix). Moving `X` by `d` moves `s` by at most
//! `|J| |d|`, `J = ds/dX`, whose rows are `W/2 (m0 - ndc_x m3) / w` and
//! `H/2 (m1 - ndc_y m3) / w` (`m_i` the rows of `M` without their last
//! entry, `ndc = (x/w, y/w)`); the Frobenius norm of `J` bounds its
//! operator norm. So a triangle within `pixels / |J|` of the limit is
//! within `pixels` on screen. A patch takes `|J|` at its nearest possible
//! depth (the smallest `w` of a sphere holding its corners and centre, no
//! nearer than the near plane) and its samples' screen positions (clamped
//! to the viewport, the largest off-axis term): one tolerance for the whole
//! patch, the smallest any of its points needs. A patch whose sphere lies
//! wholly outside one of the view's clip planes is not seen: it gets no
//! tolerance (rate 1, its corners and sides only).

use super::domain::Domain;
use crate::subdiv::eval::Evaluator;
use crate::{Error, Result};
use glam::{DMat4, DVec3, DVec4};

/// How close [`super::tessellate`] keeps its triangles to the limit
/// surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tolerance {
    /// At most this distance, in the model's units, everywhere.
    Distance(f64),
    /// At most this fraction of the diagonal of the control points'
    /// bounding box, everywhere (`1e-4x` on the command line).
    Fraction(f64),
    /// At most this many pixels on the screen of a view: finer where the
    /// surface is near the eye, coarse out of the view.
    Screen(ScreenTolerance),
}

/// A view and the pixels a triangle may be off the limit surface in it
/// (see [`Tolerance::Screen`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScreenTolerance {
    /// World to clip space: `x` and `y` within `±w`, depth `z` within
    /// `0..w` (wgpu's and Direct3D's convention), perspective or
    /// orthographic.
    pub view_proj: DMat4,
    /// The viewport's width in pixels.
    pub width: f64,
    /// The viewport's height in pixels.
    pub height: f64,
    /// The largest distance on screen, in pixels (half a pixel keeps the
    /// drawn surface on the limit's pixels).
    pub pixels: f64,
}

impl std::str::FromStr for Tolerance {
    type Err = Error;

    /// `1e-3` (a distance) or `1e-4x` (a fraction of the diagonal): a
    /// positive finite number, as the command line and Python take it.
    fn from_str(s: &str) -> Result<Tolerance> {
        let (number, fraction) = s.trim().strip_suffix('x').map_or((s.trim(), false), |n| (n, true));
        let t = number.trim().parse::<f64>().ok().filter(|t| t.is_finite() && *t > 0.0).ok_or_else(|| {
            Error::Usage(format!(
                "tolerance '{s}' is not a positive distance (a number, or a fraction of the diagonal such as 1e-4x)"
            ))
        })?;
        Ok(if fraction { Tolerance::Fraction(t) } else { Tolerance::Distance(t) })
    }
}

impl Tolerance {
    /// The tolerance for the control points `control`: a fraction made a
    /// distance; refused when it is not a positive finite number (or, on
    /// the screen, without pixels).
    pub(super) fn resolve(self, control: &[DVec3]) -> Result<Tolerance> {
        let fine = |x: f64| x.is_finite() && x > 0.0;
        let distance = |t: f64| match fine(t) {
            true => Ok(Tolerance::Distance(t)),
            false => Err(Error::Usage(format!("tolerance {t}: a positive distance is needed"))),
        };
        match self {
            Tolerance::Distance(t) => distance(t),
            Tolerance::Fraction(f) if fine(f) => distance(f * diagonal(control)),
            Tolerance::Fraction(f) => Err(Error::Usage(format!("tolerance {f}x: a positive fraction is needed"))),
            Tolerance::Screen(s) if !fine(s.pixels) => {
                Err(Error::Usage(format!("tolerance of {} pixels: a positive number is needed", s.pixels)))
            }
            Tolerance::Screen(s) if !(fine(s.width) && fine(s.height)) => {
                Err(Error::Usage(format!("a viewport of {} x {} pixels has no pixels", s.width, s.height)))
            }
            Tolerance::Screen(_) => Ok(self),
        }
    }
}

/// The length of the diagonal of the bounding box of `points` (0 for none).
pub(super) fn diagonal(points: &[DVec3]) -> f64 {
    let (lo, hi) = points.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    if points.is_empty() { 0.0 } else { lo.distance(hi) }
}

/// Where each patch's tolerance is sampled: its corners and centre.
const TRI_AT: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0 / 3.0, 1.0 / 3.0)];
const QUAD_AT: [(f64, f64); 5] = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.5, 0.5)];

/// Room around a patch's sampled sphere for the surface between the
/// samples.
const MARGIN: f64 = 1.25;

/// The tolerance in the model's units of each patch of `which` (infinite
/// for a patch out of the view) and the points evaluated for them, from a
/// tolerance [`Tolerance::resolve`] checked (a fraction is taken as a
/// distance).
///
/// # Errors
/// [`Error::Usage`] for a view's matrix that cannot be inverted.
pub(super) fn per_patch(
    ev: &Evaluator,
    domain: &Domain,
    tolerance: &Tolerance,
    which: &[usize],
) -> Result<(Vec<f64>, u64)> {
    let screen = match tolerance {
        Tolerance::Distance(t) | Tolerance::Fraction(t) => return Ok((vec![*t; which.len()], 0)),
        Tolerance::Screen(s) => s,
    };
    let view = View::new(screen)?;
    let samples = |p: &super::domain::Patch| -> &[(f64, f64)] { if p.quad { &QUAD_AT } else { &TRI_AT } };
    let mut at = Vec::with_capacity(5 * which.len());
    for p in which.iter().map(|&p| &domain.patches[p]) {
        at.extend(samples(p).iter().map(|&(u, v)| (p.face as usize, u, v)));
    }
    let points = ev.eval_map(&at, false, |s| s.position)?;
    let mut out = Vec::with_capacity(which.len());
    let mut next = 0;
    for p in which.iter().map(|&p| &domain.patches[p]) {
        let n = samples(p).len();
        out.push(view.tolerance(&points[next..next + n], screen.pixels));
        next += n;
    }
    Ok((out, at.len() as u64))
}

/// A view as the tolerances read it.
struct View {
    /// World to clip.
    m: DMat4,
    /// `w` on the near plane (1 for an orthographic view).
    w_near: f64,
    /// Half the viewport, pixels.
    half: (f64, f64),
}

impl View {
    fn new(s: &ScreenTolerance) -> Result<View> {
        let inverse = s.view_proj.inverse();
        // the near plane's centre, back in the world, and its w
        let near = inverse * DVec4::new(0.0, 0.0, 0.0, 1.0);
        let w_near = s.view_proj.row(3).dot(near / near.w);
        if !(inverse.is_finite() && w_near.is_finite() && w_near > 0.0) {
            return Err(Error::Usage("the view's matrix cannot be inverted".into()));
        }
        Ok(View { m: s.view_proj, w_near, half: (0.5 * s.width, 0.5 * s.height) })
    }

    /// The tolerance of a patch sampled at `points` (its centre last).
    fn tolerance(&self, points: &[DVec3], pixels: f64) -> f64 {
        let centre = points[points.len() - 1];
        let radius = MARGIN * points.iter().map(|p| p.distance(centre)).fold(0.0, f64::max);
        let row = |i: usize| self.m.row(i);
        let plane = |l: DVec4| l.truncate().dot(centre) + l.w < -radius * l.truncate().length();
        let (x, y, z, w) = (row(0), row(1), row(2), row(3));
        // out of the view: wholly beyond a clip plane
        if [w + x, w - x, w + y, w - y, z, w - z].into_iter().any(plane) {
            return f64::INFINITY;
        }
        let (m0, m1, m3) = (x.truncate(), y.truncate(), w.truncate());
        let nearest = (w.truncate().dot(centre) + w.w - radius * m3.length()).max(self.w_near);
        let worst = points
            .iter()
            .map(|p| {
                let c = self.m * p.extend(1.0);
                let ndc = |v: f64| if c.w > 0.0 { (v / c.w).clamp(-1.0, 1.0) } else { 1.0 };
                let jx = self.half.0 * (m0 - ndc(c.x) * m3);
                let jy = self.half.1 * (m1 - ndc(c.y) * m3);
                (jx.length_squared() + jy.length_squared()).sqrt()
            })
            .fold(0.0, f64::max)
            / nearest;
        if worst.is_finite() && worst > 0.0 { pixels / worst } else { f64::INFINITY }
    }
}
