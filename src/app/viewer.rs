//! The viewer without its window: the document, the view and the panel's
//! own widget state. A frame of UI is [`Viewer::ui`]: the panel draws and
//! returns commands, [`Viewer::apply`] carries them out, then the camera
//! settles. The headless tests drive exactly this, through egui without a
//! window.

use super::command::Command;
use super::doc::Doc;
use super::panel::{self, PanelState};
use super::view::View;

/// The document, the view and the panel's widget state.
pub(crate) struct Viewer {
    /// What is shown.
    pub(crate) doc: Doc,
    /// Camera and frame statistics.
    pub(crate) view: View,
    /// Text fields, the file browser, export settings.
    pub(crate) panel: PanelState,
}

impl Default for Viewer {
    fn default() -> Self {
        Viewer::new()
    }
}

impl Viewer {
    /// The built-in tetrahedron, nothing running.
    pub(crate) fn new() -> Viewer {
        Viewer { doc: Doc::new(), view: View::default(), panel: PanelState::new() }
    }

    /// Adopts what the workers finished; whether anything arrived.
    pub(crate) fn poll(&mut self) -> bool {
        let finished = self.doc.jobs.poll();
        let any = !finished.is_empty();
        for f in finished {
            self.apply(Command::Finished(Box::new(f)));
        }
        any
    }

    /// Advances the animation clock by `dt` seconds and makes its frame
    /// current (evaluated on the CPU unless the GPU evaluates it): the
    /// document owns time, with or without a window.
    pub(crate) fn advance(&mut self, dt: f64) -> bool {
        self.doc.anim.advance(dt, self.doc.display.normals)
    }

    /// One frame of the panel and the 3D area's input: draws, applies the
    /// commands, settles the camera. Returns the 3D area (points).
    pub(crate) fn ui(&mut self, ui: &mut egui::Ui) -> egui::Rect {
        let (rect, commands) = panel::show(ui, &self.doc, &self.view, &mut self.panel);
        self.view.scene_rect = rect;
        for c in commands {
            self.apply(c);
        }
        self.view.settle_camera(&self.doc);
        let ppp = ui.ctx().pixels_per_point();
        if let Some(view) = super::adaptive::screen_tolerance(&self.view, self.doc.display.side_by_side, ppp) {
            // the page has no worker threads: a tessellation runs in a frame
            // there, so it waits for the camera to be still for a frame
            // (and a frame is asked for to see it still), not at every step
            // of an orbit
            let still = self.doc.model.adaptive.still(view);
            if still || !cfg!(target_arch = "wasm32") {
                self.doc.request_tessellation(view);
            } else if self.doc.display.adaptive {
                ui.ctx().request_repaint_after(std::time::Duration::from_millis(100));
            }
        }
        rect
    }
}
