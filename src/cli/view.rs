//! `subdiv view`: the window.

use super::args::{ColorArgs, InputArgs, SubdivArgs};
use std::path::PathBuf;
use subdiv::{Error, Result};

/// `subdiv view` arguments (parsed the same with and without the viewer feature).
#[derive(clap::Args, Default)]
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
pub struct ViewArgs {
    /// A mesh file, .bez (patches) or .bzc (curve), or bundled:NAME (default: the bundled tetrahedron).
    model: Option<PathBuf>,
    #[command(flatten)]
    from: InputArgs,
    #[command(flatten)]
    sub: SubdivArgs,
    #[command(flatten)]
    color: ColorArgs,
    /// Start with the wireframe shown.
    #[arg(long)]
    wireframe: bool,
    /// Start with the control mesh (cage) shown.
    #[arg(long)]
    control: bool,
    /// Start with the adaptive display: the exact limit tessellated for the
    /// view, within half a pixel (Loop and Catmull-Clark).
    #[arg(long)]
    adaptive: bool,
    /// Render N frames, then exit (for CI).
    #[arg(long)]
    frames: Option<u32>,
    /// Save the last frame to this PNG (with --frames).
    #[arg(long)]
    screenshot: Option<PathBuf>,
    /// Animation paths (.paths) for the model.
    #[arg(long)]
    paths: Option<PathBuf>,
    /// Start playing the animation.
    #[arg(long)]
    play: bool,
    /// Start with the camera turning around the model.
    #[arg(long)]
    turntable: bool,
}

/// `subdiv view`.
#[cfg(feature = "viewer")]
pub(crate) fn view(a: ViewArgs) -> Result<()> {
    if a.screenshot.is_some() && a.frames.is_none() {
        return Err(Error::Usage("--screenshot needs --frames N (or press P in the window)".into()));
    }
    let s = &a.sub.scheme;
    let coloring = a.color.asked()?;
    subdiv::app::run(subdiv::app::ViewOptions {
        model: a.model,
        scheme: s.scheme(),
        opts: s.options(),
        // a scheme given on the command line is pinned; else a file's is adopted
        flags: subdiv::mesh::ShapeOptions { scheme: s.shape().scheme.filter(|_| s.scheme_flag.is_some()), ..s.shape() },
        level: a.sub.levels_or(0),
        wireframe: a.wireframe,
        frames: a.frames,
        screenshot: a.screenshot,
        paths: a.paths,
        play: a.play,
        turntable: a.turntable,
        repair: a.from.repair,
        time: a.from.time,
        // auto: the viewer shows a model's materials when it has them; none stays none
        coloring,
        isolines: a.color.isolines(coloring)?,
        range: a.color.range(coloring)?,
        crease_angle: s.features.sharp.crease_angle,
        control: a.control,
        adaptive: a.adaptive,
    })
}

/// `subdiv` alone: the viewer with something worth seeing (see `ViewOptions::first_launch`).
#[cfg(feature = "viewer")]
pub(crate) fn first_launch() -> Result<()> {
    subdiv::app::run(subdiv::app::ViewOptions::first_launch())
}

/// `subdiv` alone without the viewer: the same refusal as `view`.
#[cfg(not(feature = "viewer"))]
pub(crate) fn first_launch() -> Result<()> {
    view(ViewArgs::default())
}

/// `subdiv view` without the viewer.
#[cfg(not(feature = "viewer"))]
pub(crate) fn view(_a: ViewArgs) -> Result<()> {
    Err(Error::Usage(
        "built without the 'viewer' feature: use subdivide / info, or rebuild with default features".into(),
    ))
}
