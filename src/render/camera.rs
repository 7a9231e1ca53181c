//! An orbit camera: target, distance, yaw and pitch; perspective or
//! orthographic. Pure math, no GPU; the window and the offscreen renderer
//! share it.
//!
//! Clip space is wgpu's (Y up, Z in 0..1), hence glam's `directx` projections.

use glam::{Mat4, Vec2, Vec3};

/// Largest pitch magnitude, so the view never flips over the pole.
const MAX_PITCH: f32 = 1.55;

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
    /// A camera looking at the bounds `(lo, hi)` from the default direction.
    pub fn framing(lo: Vec3, hi: Vec3, aspect: f32) -> Camera {
        let mut c = Camera::default();
        c.fit(lo, hi, aspect);
        c
    }

    /// Unit vector from the target towards the eye.
    pub fn back(&self) -> Vec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        Vec3::new(cp * sy, sp, cp * cy)
    }
    /// Eye position.
    pub fn eye(&self) -> Vec3 {
        self.target + self.distance * self.back()
    }
    /// Unit viewing direction.
    pub fn forward(&self) -> Vec3 {
        -self.back()
    }
    /// Camera right and up unit vectors in world space.
    pub fn right_up(&self) -> (Vec3, Vec3) {
        let f = self.forward();
        let right = f.cross(Vec3::Y).normalize_or(Vec3::X);
        (right, right.cross(f))
    }

    /// World to view matrix.
    pub fn view(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.eye(), self.target, Vec3::Y)
    }
    /// Half height of the view at the target's depth.
    fn half_height(&self) -> f32 {
        self.distance * (0.5 * self.fovy).tan()
    }
    /// View to clip matrix for a viewport of the given aspect (width / height).
    pub fn proj(&self, aspect: f32) -> Mat4 {
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
    pub fn ray(&self, cursor: Vec2, aspect: f32) -> (Vec3, Vec3) {
        let inv = self.view_proj(aspect).inverse();
        let near = inv.project_point3(cursor.extend(0.0));
        let far = inv.project_point3(cursor.extend(1.0));
        (near, (far - near).normalize_or_zero())
    }

    /// Centres the bounds `(lo, hi)` and moves back until their bounding sphere
    /// fits the view, keeping the direction.
    pub fn fit(&mut self, lo: Vec3, hi: Vec3, aspect: f32) {
        let (lo, hi) =
            if lo.is_finite() && hi.is_finite() && lo.cmple(hi).all() { (lo, hi) } else { (-Vec3::ONE, Vec3::ONE) };
        self.target = 0.5 * (lo + hi);
        self.radius = (0.5 * (hi - lo).length()).max(1e-4);
        let aspect = if aspect.is_finite() && aspect > 0.0 { aspect } else { 1.0 };
        let half = (0.5 * self.fovy).tan();
        // The tighter of the vertical and horizontal half-angles.
        let half_min = half.min(half * aspect).atan();
        self.distance = 1.08 * self.radius / half_min.sin();
    }

    /// Orbits by a mouse motion in pixels.
    pub fn orbit(&mut self, delta: Vec2) {
        self.yaw -= delta.x * 0.008;
        self.pitch = (self.pitch + delta.y * 0.008).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Moves the target with the cursor: `delta` in pixels in a viewport
    /// `height` pixels tall, so the point under the cursor follows it.
    pub fn pan(&mut self, delta: Vec2, height: f32) {
        let per_pixel = 2.0 * self.half_height() / height.max(1.0);
        let (right, up) = self.right_up();
        self.target += (-delta.x * right + delta.y * up) * per_pixel;
    }

    /// Scales the distance by `factor` (< 1 zooms in) keeping the point under
    /// the cursor fixed; `cursor` is in NDC of a viewport of the given aspect.
    pub fn zoom_to(&mut self, factor: f32, cursor: Vec2, aspect: f32) {
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

    #[test]
    fn fit_puts_every_corner_inside_the_view() {
        let (lo, hi) = (Vec3::new(-1.0, 2.0, 5.0), Vec3::new(3.0, 2.5, 9.0));
        for aspect in [0.5, 1.0, 2.0] {
            for yaw in [0.0f32, 1.0, 2.5] {
                let mut c = Camera { yaw, ..Camera::default() };
                c.fit(lo, hi, aspect);
                for i in 0..8 {
                    let p = Vec3::new(
                        if i & 1 == 0 { lo.x } else { hi.x },
                        if i & 2 == 0 { lo.y } else { hi.y },
                        if i & 4 == 0 { lo.z } else { hi.z },
                    );
                    let q = c.project(p, aspect);
                    assert!(q.x.abs() < 1.0 && q.y.abs() < 1.0 && q.z > 0.0 && q.z < 1.0, "{p} -> {q}");
                }
            }
        }
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
