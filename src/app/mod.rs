//! The desktop viewer: winit window, wgpu surface, egui side panel.

use crate::{Result, Scheme};
use std::path::PathBuf;

/// What `subdiv view` (and `subdiv` with no arguments) was asked to show.
#[derive(Clone, Debug, Default)]
pub struct ViewOptions {
    /// Model to open (`None`: the bundled tetrahedron).
    pub model: Option<PathBuf>,
    /// Initial scheme.
    pub scheme: Scheme,
    /// Initial level.
    pub level: u32,
    /// Start with the wireframe on.
    pub wireframe: bool,
    /// Render this many frames and exit (CI smoke test).
    pub frames: Option<u32>,
    /// Save the last frame here (with `frames`).
    pub screenshot: Option<PathBuf>,
    /// A `.paths` file for the animation.
    pub paths: Option<PathBuf>,
}

/// Opens the viewer window and runs until it is closed.
///
/// # Errors
/// When no window or GPU adapter can be created.
pub fn run(_opts: ViewOptions) -> Result<()> {
    Err(crate::Error::Usage("the viewer is not built yet".into()))
}
