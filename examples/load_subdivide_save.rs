//! Load a mesh in any format, subdivide it, save it in any format:
//! `cargo run --release --example load_subdivide_save -- [IN] [OUT] [LEVELS] [SCHEME]`
//! (defaults: the bundled cube, `cube-loop2.glb` in the temp directory, 2, loop).
//! The formats follow the extensions; texture coordinates, colours and
//! material groups ride along where the output keeps them.

use std::path::PathBuf;
use subdiv::{Options, Refiner, Scheme, bundled, io};

fn main() -> subdiv::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let input = PathBuf::from(args.first().map_or("bundled:cube_uv.obj", String::as_str));
    let output = args.get(1).map_or_else(|| std::env::temp_dir().join("cube-loop2.glb"), PathBuf::from);
    let levels: u32 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2);
    let scheme: Scheme = args.get(3).map_or(Ok(Scheme::Loop), |s| s.parse()).map_err(subdiv::Error::Usage)?;

    // a file, or a model compiled into the library (bundled:NAME), through
    // the one reading pipeline (its budget, its warnings in the result)
    let loaded = bundled::read(&input, &io::ReadOptions::default())?;
    let (mesh, attrs) = (loaded.mesh, loaded.attributes);
    let opts = Options::default();
    let t0 = std::time::Instant::now();
    // the levels refined once; the attributes served on them (colours with
    // the scheme's weights, texture coordinates on their own charts)
    let r = Refiner::new(&mesh, scheme, levels, &opts)?;
    let (fine, fine_attrs) = (r.mesh(), r.attributes(&attrs)?);
    let ms = t0.elapsed().as_secs_f64() * 1e3;
    io::save_with(&output, &fine, &fine_attrs)?;

    // read it back: the same triangles
    let back = subdiv::bundled::load(&output)?;
    assert_eq!(back.ct.num_triangles(), fine.ct.num_triangles());
    println!(
        "{} -> {}: {levels} levels of {scheme}, {} -> {} triangles in {:.2} ms",
        input.display(),
        output.display(),
        mesh.ct.num_triangles(),
        fine.ct.num_triangles(),
        ms
    );
    Ok(())
}
