//! An orbit camera: target, distance, yaw and pitch; perspective or
//! orthographic. Pure math, no GPU; the window and the offscreen renderer
//! share it.
//!
//! Clip space is wgpu's (Y up, Z in 0..1), hence glam's `directx` projections.

use glam::{Mat4, Vec2, Vec3};

/// Largest pitch magnitude, so the view never flips over the pole.
const MAX_PITCH: f32 = 1.55;

/// The share of the view's width or height (the tighter of the two) that
/// [`Camera::fit_points`] gives the model.
pub(crate) const FIT_FILL: f32 = 0.9;

/// The eye `(ex, ey, ez)` seeing the points `q` (camera frame) centred
/// with half-angle tangents `s` in perspective ([`Camera::fit_points`]).
fn perspective_eye(q: &[Vec3], s: Vec2) -> (f32, f32, f32) {
    // the planes' touching lines along one axis: (offset, eye depth)
    let touch = |a: &dyn Fn(&Vec3) -> f32, s: f32| {
        let hi = q.iter().map(|p| a(p) + s * p.z).fold(f32::MIN, f32::max);
        let lo = q.iter().map(|p| a(p) - s * p.z).fold(f32::MAX, f32::min);
        (0.5 * (hi + lo), (hi - lo) / (2.0 * s))
    };
    let (ex, ezx) = touch(&|p| p.x, s.x);
    let (ey, ezy) = touch(&|p| p.y, s.y);
    if ezx >= ezy { (ex, centred(q, ezx, |p| p.y), ezx) } else { (centred(q, ezy, |p| p.x), ey, ezy) }
}

/// The offset along `a` that centres the perspective projections
/// `(a(p) - e) / (ez - p.z)` of the points `q` from eye depth `ez`, by
/// bisection (their largest plus their smallest falls as `e` grows).
fn centred(q: &[Vec3], ez: f32, a: impl Fn(&Vec3) -> f32) -> f32 {
    let balance = |e: f32| {
        let (mut lo, mut hi) = (f32::MAX, f32::MIN);
        for p in q {
            let v = (a(p) - e) / (ez - p.z).max(f32::MIN_POSITIVE);
            (lo, hi) = (lo.min(v), hi.max(v));
        }
        lo + hi
    };
    let span = q.iter().map(|p| a(p).abs()).fold(0.0f32, f32::max) + 1.0;
    let (mut a0, mut b0) = (-span, span);
    for _ in 0..60 {
        let m = 0.5 * (a0 + b0);
        if balance(m) > 0.0 {
            a0 = m;
        } else {
            b0 = m;
        }
    }
    0.5 * (a0 + b0)
}

/// The eye seeing the points `q` centred orthographically, its depth the
/// distance whose view half-extents `s * ez` hold them.
fn ortho_eye(q: &[Vec3], s: Vec2) -> (f32, f32, f32) {
    let (lo, hi) = q.iter().fold((Vec3::MAX, Vec3::MIN), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let half = 0.5 * (hi - lo);
    (0.5 * (hi.x + lo.x), 0.5 * (hi.y + lo.y), (half.x / s.x).max(half.y / s.y))
}

/// The bounds of the finite points, `None` if there are none.
fn finite_bounds(points: &[Vec3]) -> Option<(Vec3, Vec3)> {
    let mut it = points.iter().copied().filter(|p| p.is_finite());
    let first = it.next()?;
    Some(it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
}

/// Orbit camera around a target point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Point orbited around and looked at.
    pub target: Vec3,
    /// Distance from the eye to the target.
    pub distance: f32,
    /// Rotation around the world Y axis, radians.
    pub yaw: f32,
    /// Elevation above the XZ plane, radians.
    pub pitch: f32,
    /// Vertical field of view, radians.
    pub fovy: f32,
    /// Orthographic projection (same size at the target as the perspective one).
    pub orthographic: bool,
    /// Radius of the scene's bounding sphere (sets near/far planes).
    pub radius: f32,
}

impl Default for Camera {
    fn default() -> Self {
        Camera {
            target: Vec3::ZERO,
            distance: 3.0,
            yaw: 0.6,
            pitch: 0.35,
            fovy: 40f32.to_radians(),
            orthographic: false,
            radius: 1.0,
        }
    }
}

impl Camera {
    /// A camera looking at the bounds `(lo, hi)` from the default direction
    /// (see [`Camera::fit`]).
    pub fn framing(lo: Vec3, hi: Vec3, aspect: f32) -> Camera {
        let mut c = Camera::default();
        c.fit(lo, hi, aspect);
        c
    }

    /// A camera looking at `points` from the default direction,
    /// orthographic or not (see [`Camera::fit_points`]).
    pub(crate) fn framing_points(points: &[Vec3], aspect: f32, orthographic: bool) -> Camera {
        let mut c = Camera { orthographic, ..Camera::default() };
        c.fit_points(points, aspect);
        c
    }

    /// Unit vector from the target towards the eye.
    pub(crate) fn back(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        Vec3::new(cp * sy, sp, cp * cy)
    }
    /// Eye position.
    pub(crate) fn eye(&self) -> Vec3 {
        self.target + self.distance * self.back()
    }
    /// Unit viewing direction.
    pub fn forward(&self) -> Vec3 {
        -self.back()
    }
    /// Camera right and up unit vectors in world space.
    pub(crate) fn right_up(&self) -> (Vec3, Vec3) {
        let f = self.forward();
        let right = f.cross(Vec3::Y).normalize_or(Vec3::X);
        (right, right.cross(f))
    }

    /// World to view matrix.
    pub(crate) fn view(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye(), self.target, Vec3::Y)
    }
    /// Half height of the view at the target's depth.
    fn half_height(&self) -> f32 {
        self.distance * (0.5 * self.fovy).tan()
    }
    /// View to clip matrix for a viewport of the given aspect (width / height).
    pub(crate) fn proj(&self, aspect: f32) -> Mat4 {
        let aspect = if aspect.is_finite() && aspect > 0.0 { aspect } else { 1.0 };
        let r = self.radius.max(1e-6);
        let far = self.distance + 3.0 * r;
        if self.orthographic {
            let hh = self.half_height();
            let hw = hh * aspect;
            glam::camera::rh::proj::directx::orthographic(-hw, hw, -hh, hh, self.distance - 3.0 * r, far)
        } else {
            let near = (self.distance - 2.0 * r).max(self.distance * 0.01).max(1e-5);
            glam::camera::rh::proj::directx::perspective(self.fovy, aspect, near, far)
        }
    }
    /// World to clip.
    pub fn view_proj(&self, aspect: f32) -> Mat4 {
        self.proj(aspect) * self.view()
    }
    /// Normalised device coordinates (x, y in -1..1, y up) of a world point.
    pub fn project(&self, p: Vec3, aspect: f32) -> Vec3 {
        self.view_proj(aspect).project_point3(p)
    }

    /// The ray through a point of a viewport of the given aspect, given in
    /// its normalised device coordinates (`cursor`, y up): the point on the
    /// near plane and the unit direction away from the eye.
    pub(crate) fn ray(&self, cursor: Vec2, aspect: f32) -> (Vec3, Vec3) {
        let inv = self.view_proj(aspect).inverse();
        let near = inv.project_point3(cursor.extend(0.0));
        let far = inv.project_point3(cursor.extend(1.0));
        (near, (far - near).normalize_or_zero())
    }

    /// `Camera::fit_points` on the eight corners of the box `(lo, hi)`
    /// (a box that is empty or not finite stands for `[-1, 1]^3`).
    pub fn fit(&mut self, lo: Vec3, hi: Vec3, aspect: f32) {
        let (lo, hi) =
            if lo.is_finite() && hi.is_finite() && lo.cmple(hi).all() { (lo, hi) } else { (-Vec3::ONE, Vec3::ONE) };
        let corners: [Vec3; 8] = std::array::from_fn(|i| {
            Vec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        });
        self.fit_points(&corners, aspect);
    }

    /// Keeps the direction and moves the camera so the projection of
    /// `points` is centred in a viewport of the given aspect and fills
    /// [`FIT_FILL`] of it in the tighter of its width and height, in
    /// perspective or orthographically as the camera is. Non-finite points
    /// are skipped; none left frames `[-1, 1]^3`.
    ///
    /// In the camera's frame about the points' box centre (`x`, `y` across
    /// the view, `z` towards the eye), an eye at `(ex, ey, ez)` sees point
    /// `i` within the half-angle tangent `s` across `x` when
    /// `|x_i - ex| <= s (ez - z_i)`: the two planes touch the points when
    /// `ex + s ez = max (x_i + s z_i)` and `ex - s ez = min (x_i - s z_i)`,
    /// which gives `ex` and `ez` in closed form. The tighter axis (the
    /// larger `ez`) is so fitted; the other is then centred by bisection on
    /// its offset (its extreme projections are monotone in it).
    /// Orthographically the extents are the points' own.
    pub(crate) fn fit_points(&mut self, points: &[Vec3], aspect: f32) {
        let aspect = if aspect.is_finite() && aspect > 0.0 { aspect } else { 1.0 };
        let (lo, hi) = finite_bounds(points).unwrap_or((-Vec3::ONE, Vec3::ONE));
        let centre = 0.5 * (lo + hi);
        self.target = centre;
        self.radius = (0.5 * (hi - lo).length()).max(1e-4);
        let t = (0.5 * self.fovy).tan();
        let s = Vec2::new(t * aspect * FIT_FILL, t * FIT_FILL);
        let frame = self.in_frame();
        let q: Vec<Vec3> = points.iter().filter(|p| p.is_finite()).map(|&p| frame(p).into()).collect();
        let q = if q.is_empty() { vec![lo - centre, hi - centre] } else { q };
        let (ex, ey, ez) = if self.orthographic { ortho_eye(&q, s) } else { perspective_eye(&q, s) };
        let zmax = q.iter().fold(f32::MIN, |m, p| m.max(p.z));
        let ez = if self.orthographic { ez } else { ez.max(zmax + 1e-3 * self.radius) };
        let (right, up) = self.right_up();
        self.target = centre + right * ex + up * ey;
        self.distance = ez.max(1e-4 * self.radius);
    }

    /// The map to the camera's frame about the target: `(x, y, z)`
    /// across the view and towards the eye.
    fn in_frame(&self) -> impl Fn(Vec3) -> (f32, f32, f32) + use<> {
        let ((right, up), back, target) = (self.right_up(), self.back(), self.target);
        move |p| {
            let q = p - target;
            (q.dot(right), q.dot(up), q.dot(back))
        }
    }

    /// Orbits by a mouse motion in pixels.
    pub(crate) fn orbit(&mut self, delta: Vec2) {
        self.yaw -= delta.x * 0.008;
        self.pitch = (self.pitch + delta.y * 0.008).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Moves the target with the cursor: `delta` in pixels in a viewport
    /// `height` pixels tall, so the point under the cursor follows it.
    pub(crate) fn pan(&mut self, delta: Vec2, height: f32) {
        let per_pixel = 2.0 * self.half_height() / height.max(1.0);
        let (right, up) = self.right_up();
        self.target += (-delta.x * right + delta.y * up) * per_pixel;
    }

    /// Scales the distance by `factor` (< 1 zooms in) keeping the point under
    /// the cursor fixed; `cursor` is in NDC of a viewport of the given aspect.
    pub(crate) fn zoom_to(&mut self, factor: f32, cursor: Vec2, aspect: f32) {
        if !factor.is_finite() || factor <= 0.0 {
            return;
        }
        let factor = factor.clamp(0.05, 20.0);
        let new_distance = (self.distance * factor).clamp(self.radius * 1e-3, self.radius * 1e3);
        let factor = new_distance / self.distance;
        let hh = self.half_height();
        let (right, up) = self.right_up();
        let under = self.target + right * (cursor.x * hh * aspect) + up * (cursor.y * hh);
        self.target = under + (self.target - under) * factor;
        self.distance = new_distance;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The extents of `points` in normalised device coordinates.
    fn ndc_extents(c: &Camera, points: &[Vec3], aspect: f32) -> (Vec2, Vec2) {
        let mut lo = Vec2::splat(f32::MAX);
        let mut hi = Vec2::splat(f32::MIN);
        for &p in points {
            let q = c.project(p, aspect);
            assert!(q.z > 0.0 && q.z < 1.0, "{p} -> {q}: outside the depth range");
            (lo, hi) = (lo.min(q.truncate()), hi.max(q.truncate()));
        }
        (lo, hi)
    }

    #[test]
    fn fit_centres_the_points_and_fills_the_tighter_side() {
        let mut rng = 0x2545f4914f6cdd1du64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 40) as f32 / (1u64 << 24) as f32
        };
        let blob: Vec<Vec3> =
            (0..500).map(|_| Vec3::new(next() * 4.0 - 1.0, next() * 0.5 + 2.0, next() * 3.0 + 5.0)).collect();
        let tetra = vec![
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(1.0, -1.0, -1.0),
            Vec3::new(-1.0, 1.0, -1.0),
            Vec3::new(-1.0, -1.0, 1.0),
        ];
        for points in [&blob, &tetra] {
            // wide, square, narrow and tall, a phone's portrait
            for aspect in [2.5, 1.33, 1.0, 0.5, 0.3] {
                for yaw in [0.0f32, 1.0, 2.5] {
                    for orthographic in [false, true] {
                        let mut c = Camera { yaw, orthographic, ..Camera::default() };
                        c.fit_points(points, aspect);
                        let (lo, hi) = ndc_extents(&c, points, aspect);
                        let what = format!("aspect {aspect} yaw {yaw} ortho {orthographic}: {lo} .. {hi}");
                        assert!(lo.min_element() >= -FIT_FILL - 1e-4 && hi.max_element() <= FIT_FILL + 1e-4, "{what}");
                        assert!((lo + hi).abs().max_element() < 2e-3, "{what}: not centred");
                        let fill = ((hi - lo) / 2.0).max_element();
                        assert!(fill > FIT_FILL - 2e-3, "{what}: fills {fill}");
                    }
                }
            }
        }
    }

    #[test]
    fn fit_puts_every_corner_of_a_box_inside_the_view() {
        let (lo, hi) = (Vec3::new(-1.0, 2.0, 5.0), Vec3::new(3.0, 2.5, 9.0));
        for aspect in [0.5, 1.0, 2.0] {
            let mut c = Camera::default();
            c.fit(lo, hi, aspect);
            let corners: Vec<Vec3> = (0..8)
                .map(|i| {
                    Vec3::new(
                        if i & 1 == 0 { lo.x } else { hi.x },
                        if i & 2 == 0 { lo.y } else { hi.y },
                        if i & 4 == 0 { lo.z } else { hi.z },
                    )
                })
                .collect();
            let (a, b) = ndc_extents(&c, &corners, aspect);
            assert!(a.min_element() > -1.0 && b.max_element() < 1.0, "{a} {b}");
        }
        // nothing finite: the unit box
        let mut c = Camera::default();
        c.fit_points(&[Vec3::NAN], 1.0);
        assert!(c.view().is_finite() && c.distance > 0.0);
    }

    #[test]
    fn zoom_keeps_the_point_under_the_cursor() {
        for ortho in [false, true] {
            let mut c = Camera { orthographic: ortho, ..Camera::default() };
            c.fit(-Vec3::ONE, Vec3::ONE, 1.5);
            let cursor = Vec2::new(0.4, -0.3);
            let hh = c.distance * (0.5 * c.fovy).tan();
            let (right, up) = c.right_up();
            let p = c.target + right * (cursor.x * hh * 1.5) + up * (cursor.y * hh);
            let before = c.project(p, 1.5);
            c.zoom_to(0.5, cursor, 1.5);
            let after = c.project(p, 1.5);
            assert!((before.truncate() - cursor).length() < 1e-4, "{before}");
            assert!((after.truncate() - cursor).length() < 1e-4, "{after}");
        }
    }

    #[test]
    fn pan_moves_the_scene_with_the_cursor() {
        let mut c = Camera::default();
        c.fit(-Vec3::ONE, Vec3::ONE, 1.0);
        let before = c.project(Vec3::ZERO, 1.0);
        c.pan(Vec2::new(50.0, 0.0), 500.0);
        let after = c.project(Vec3::ZERO, 1.0);
        // 50 px of 500 (NDC spans 2 over the height) is 0.2 in NDC, to the right.
        assert!((after.x - before.x - 0.2).abs() < 1e-3, "{before} {after}");
    }

    #[test]
    fn orbit_keeps_distance_and_clamps_pitch() {
        let mut c = Camera::default();
        let d = (c.eye() - c.target).length();
        c.orbit(Vec2::new(123.0, 10_000.0));
        assert!(((c.eye() - c.target).length() - d).abs() < 1e-4);
        assert!(c.pitch <= MAX_PITCH);
        assert!(c.view().is_finite());
    }
}
