//! The view: the camera of the 3D viewports and what the window measures.
//! Kept apart from the document: it changes with every mouse drag and says
//! nothing about the model.

use super::doc::Doc;
use crate::render::Camera;
use glam::Vec2;

/// What the window measures, shown in the statistics.
#[derive(Clone, Debug, Default)]
pub(crate) struct FrameStats {
    /// Smoothed frame time, ms.
    pub(crate) frame_ms: f64,
    /// Time of the last GPU upload, ms.
    pub(crate) upload_ms: f64,
    /// Bytes the last GPU upload sent (buffers made or written).
    pub(crate) upload_bytes: u64,
    /// CPU time to record the last 3D render, ms.
    pub(crate) encode_ms: f64,
    /// How many times the 3D viewports were rendered (they are cached between changes).
    pub(crate) scene_renders: u64,
    /// Adapter description.
    pub(crate) adapter: String,
    /// The adapter offers multisampling.
    pub(crate) msaa_available: bool,
}

/// Camera and window state of the 3D area.
pub(crate) struct View {
    /// Shared camera of the viewports.
    pub(crate) camera: Camera,
    /// Frame what is shown on the next frame.
    pub(crate) fit: bool,
    /// Look at a newly opened curve from the front and frame it.
    pub(crate) fit_curve: bool,
    /// Reset the camera direction (then fit).
    pub(crate) reset: bool,
    /// The 3D area (points), set each frame by the panel.
    pub(crate) scene_rect: egui::Rect,
    /// A screenshot was asked for (P).
    pub(crate) screenshot: bool,
    /// How P and the panel's button take it (scale, transparency).
    pub(crate) shot: crate::render::Shot,
    /// A file is hovering over the window.
    pub(crate) hovering_file: bool,
    /// Frame times and counters.
    pub(crate) stats: FrameStats,
    /// The window is to close (after the unsaved changes were answered).
    pub(crate) quit: bool,
}

impl Default for View {
    fn default() -> Self {
        View {
            camera: Camera::default(),
            fit: true,
            fit_curve: false,
            reset: false,
            scene_rect: egui::Rect::NOTHING,
            screenshot: false,
            shot: crate::render::Shot::default(),
            hovering_file: false,
            stats: FrameStats::default(),
            quit: false,
        }
    }
}

/// Aspect of one viewport of the 3D area.
pub(crate) fn viewport_aspect(rect: egui::Rect, side_by_side: bool) -> f32 {
    let w = if side_by_side { rect.width() / 2.0 } else { rect.width() };
    w / rect.height().max(1.0)
}

/// The cursor in the normalised device coordinates of the viewport under it
/// (the left or right half in side-by-side mode).
pub(crate) fn cursor_ndc(rect: egui::Rect, side_by_side: bool, pos: egui::Pos2) -> Vec2 {
    let mut vp = rect;
    if side_by_side {
        vp.set_width(rect.width() / 2.0);
        if pos.x > vp.right() {
            vp = vp.translate(egui::vec2(vp.width(), 0.0));
        }
    }
    Vec2::new((pos.x - vp.left()) / vp.width() * 2.0 - 1.0, 1.0 - (pos.y - vp.top()) / vp.height() * 2.0)
}

impl View {
    /// Carries out the pending reset and fits, once the 3D area is known:
    /// a mesh is framed by its shown result (a Loop surface can be much
    /// smaller than its control mesh), a curve by its control points, seen
    /// from the front, orthographically, in its single viewport.
    pub(crate) fn settle_camera(&mut self, doc: &Doc) {
        let rect = self.scene_rect;
        if self.reset {
            let orthographic = self.camera.orthographic;
            self.camera = Camera { orthographic, ..Default::default() };
            self.fit = true;
            self.reset = false;
        }
        if !rect.is_positive() {
            return;
        }
        match &*doc.model.curve {
            Some(curve) if self.fit_curve => {
                let points: Vec<glam::Vec3> = curve.control.iter().map(|p| p.extend(0.0)).collect();
                let (lo, hi) = crate::mesh::bounds_of(&points);
                self.camera = Camera { yaw: 0.0, pitch: 0.0, orthographic: true, ..Default::default() };
                // a curve has one viewport, side by side or not
                self.camera.fit(lo, hi, viewport_aspect(rect, false));
                self.fit_curve = false;
            }
            Some(_) => {}
            None => {
                self.fit_curve = false;
                if self.fit {
                    let points = &doc.model.result.shown.mesh.positions;
                    self.camera.fit_points(points, viewport_aspect(rect, doc.display.side_by_side));
                    self.fit = false;
                }
            }
        }
    }
}
