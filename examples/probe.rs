use std::time::Instant;
use subdiv::render::{Look, Offscreen, RenderOptions, Surface, default_camera};
fn main() {
    let m = subdiv::io::load(std::path::Path::new("../shared/models/stanford-bunny-compact.obj")).unwrap();
    let (f, _) = subdiv::subdivide(&m, subdiv::Scheme::Loop, 2, &Default::default()).unwrap();
    let mut off = Offscreen::new(960, 800).unwrap();
    println!("{} samples {}", off.gpu.describe(), off.renderer.samples);
    let cam = default_camera(&m, &RenderOptions { width: 960, height: 800, ..Default::default() });
    let g = off.upload(&f).unwrap();
    for (name, look) in [
        ("smooth", Look::default()),
        ("flat", Look { surface: Surface::Flat, ..Look::default() }),
        ("hidden", Look { surface: Surface::Hidden, wireframe: false, ..Look::default() }),
    ] {
        let mut ts = vec![];
        for _ in 0..6 {
            let t = Instant::now();
            off.render_one(cam, &g, None, look).unwrap();
            ts.push(t.elapsed().as_secs_f64() * 1e3);
        }
        println!("{name}: {:?}", ts.iter().map(|t| format!("{t:.0}")).collect::<Vec<_>>());
    }
}
