//! Offscreen rendering to a PNG without a window (feature `viewer`):
//! `cargo run --release --example render_png -- [IN] [OUT.png] [LEVELS]`
//! (defaults: the bundled torus, `torus.png` in the temp directory, 2).
//! Needs a GPU adapter; Mesa's lavapipe is enough.

use std::path::PathBuf;
use subdiv::render::{RenderOptions, Shading, save_png};
use subdiv::{Scheme, subdivide};

fn main() -> subdiv::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let input = PathBuf::from(args.first().map_or("bundled:torus.obj", String::as_str));
    let output = args.get(1).map_or_else(|| std::env::temp_dir().join("torus.png"), PathBuf::from);
    let levels: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2);

    let control = subdiv::bundled::load(&input)?;
    let (fine, _) = subdivide(&control, Scheme::ModifiedButterfly, levels, &Default::default())?;
    let opts = RenderOptions { shading: Shading::PhongWire, width: 640, height: 480, ..Default::default() };
    // the control mesh overlaid, the camera framed on it
    save_png(&subdiv::render_image(&fine, Some(&control), &opts)?, &output)?;
    let img = image::open(&output).map_err(|e| subdiv::Error::Usage(format!("{}: {e}", output.display())))?;
    println!("{} -> {} ({}x{})", input.display(), output.display(), img.width(), img.height());
    Ok(())
}
