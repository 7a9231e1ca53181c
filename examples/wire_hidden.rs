//! How much of a shaded model the wireframe hides: renders `MODEL` at Loop
//! level `LEVEL` offscreen (640x480, the default camera) in Phong and in
//! Phong+wire and prints the share of the object's pixels whose luminance
//! changes by more than 60 (the measure of tests/wire.rs), and by more than 8.
//!
//! `cargo run --release --example wire_hidden -- MODEL LEVEL [WIRE_LEVEL]`

use subdiv::render::{Look, Offscreen, RenderOptions, Shading, WireEdges, default_camera};
use subdiv::{Options, Scheme};

fn luminance(p: &image::Rgba<u8>) -> f64 {
    0.2126 * f64::from(p.0[0]) + 0.7152 * f64::from(p.0[1]) + 0.0722 * f64::from(p.0[2])
}

fn main() -> subdiv::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let model = args.first().map_or("bundled:torus.obj", String::as_str);
    let levels: u32 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(3);
    let edges: WireEdges = args.get(2).map_or(Ok(WireEdges::All), |s| s.parse()).map_err(subdiv::Error::Usage)?;
    let control = subdiv::bundled::load(std::path::Path::new(model))?;
    let fine = subdiv::subdivide(&control, Scheme::Loop, levels, &Options::default())?.0;
    let opts = RenderOptions { width: 640, height: 480, ..Default::default() };
    let mut off = Offscreen::new(opts.width, opts.height)?;
    let gm = off.upload(&fine)?;
    let cam = default_camera(&control, &opts);
    let phong = off.render_one(cam, &gm, None, Shading::Phong.look())?;
    let wired = off.render_one(cam, &gm, None, Look { wire_edges: edges, ..Shading::PhongWire.look() })?;
    // the background is a vertical gradient: compare with the row's first pixel
    let object: Vec<bool> = phong
        .enumerate_pixels()
        .map(|(_, y, p)| (0..3).any(|i| p.0[i].abs_diff(phong.get_pixel(0, y).0[i]) > 2))
        .collect();
    let total = object.iter().filter(|&&o| o).count().max(1) as f64;
    let share = |by: f64| {
        phong
            .pixels()
            .zip(wired.pixels())
            .zip(&object)
            .filter(|&((p, q), &o)| o && (luminance(p) - luminance(q)).abs() > by)
            .count() as f64
            / total
    };
    println!(
        "{model} L{levels} {} triangles: hidden (>60) {:.1}%, touched (>8) {:.1}%",
        fine.ct.num_triangles(),
        100.0 * share(60.0),
        100.0 * share(8.0)
    );
    Ok(())
}
