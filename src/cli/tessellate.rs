//! `subdiv tessellate`: the exact limit surface as a crack-free triangle
//! mesh within a tolerance (docs/tessellation.md).

use super::args::{InputArgs, LimitInput, Precision, SchemeArgs};
use std::path::PathBuf;
use subdiv::Result;
use subdiv::mesh::Faces;

/// `subdiv tessellate` arguments.
#[derive(clap::Args)]
#[command(mut_arg("scheme_flag", |a| a.help("Scheme: loop (triangles, the default) or catmull-clark (polygons): the schemes with an exact limit surface")))]
pub struct TessellateArgs {
    /// Input model: a mesh file or bundled:NAME (see `subdiv models`).
    input: PathBuf,
    /// Output mesh (format by extension).
    output: PathBuf,
    /// The largest distance a triangle may be from the limit surface: a
    /// length in the model's units, or a fraction of the bounding box's
    /// diagonal with an `x` after it (`1e-4x`).
    #[arg(long, short = 't', value_name = "T", default_value = "1e-4x", allow_hyphen_values = true, value_parser = parse_tolerance)]
    tolerance: subdiv::Tolerance,
    /// Also write each output vertex's control face and `(u, v)`, one `f u
    /// v` line per vertex (a points file `subdiv eval` reads: attributes
    /// evaluated later without refining).
    #[arg(long, value_name = "FILE")]
    params: Option<PathBuf>,
    #[command(flatten)]
    from: InputArgs,
    #[command(flatten)]
    scheme: SchemeArgs,
    /// Print the triangles, the distance measured, rounds and times on
    /// stderr.
    #[arg(long)]
    stats: bool,
    /// The control points' precision: f64 (the file's own digits, the
    /// default) or f32.
    #[arg(long, default_value = "f64")]
    precision: Precision,
}

/// `1e-3` or `1e-4x`, as the library reads it.
fn parse_tolerance(s: &str) -> std::result::Result<subdiv::Tolerance, String> {
    s.parse().map_err(|e: subdiv::Error| e.to_string())
}

/// `subdiv tessellate`.
pub(crate) fn tessellate(a: &TessellateArgs) -> Result<()> {
    let LimitInput { mesh, scheme, control, uv, colors } = LimitInput::read(&a.input, &a.from, &a.scheme, a.precision)?;
    let out = subdiv::tessellate(&mesh, &control, scheme.scheme(), &scheme.options(), a.tolerance)?;
    let faces = Faces {
        positions: out.positions.iter().map(|p| p.as_vec3()).collect(),
        corners: out.triangles.iter().flatten().copied().collect(),
        sides: 3,
    };
    // the file's texture coordinates come along (linear over each control face)
    if uv.is_some() && scheme.options().uv != subdiv::mesh::UvInterpolation::Linear {
        log::info!(
            "{}: texture coordinates interpolated linearly over each control face (--fvar all)",
            a.input.display()
        );
    }
    // and its colours, as the points: their limit at each vertex
    let colors = colors
        .map(|c| {
            let c: Vec<glam::DVec3> = c.iter().map(|c| c.as_dvec3()).collect();
            let at = out.vertex_values(&mesh, &c)?;
            Ok::<_, subdiv::Error>(at.iter().map(|c| c.as_vec3().clamp(glam::Vec3::ZERO, glam::Vec3::ONE)).collect())
        })
        .transpose()?;
    let uv = uv.map(|uv| out.uvs(&mesh, &uv)).transpose()?;
    let attrs = subdiv::mesh::Attributes { uv, colors, ..Default::default() };
    subdiv::io::save_with(&a.output, &faces, &attrs)?;
    if let Some(path) = &a.params {
        subdiv::io::write_points(path, &out.params)?;
    }
    let s = out.stats;
    if a.stats {
        eprintln!(
            "triangles={} vertices={} tolerance={:e} measured={:e} met={} rounds={} max_rate={} evaluations={} tessellate_ms={:.1} per_triangle_ns={:.0}",
            out.triangles.len(),
            out.positions.len(),
            s.tolerance,
            s.measured,
            s.met,
            s.rounds,
            s.max_rate,
            s.evaluations,
            s.seconds * 1e3,
            s.seconds * 1e9 / out.triangles.len().max(1) as f64
        );
    }
    if !s.met {
        log::warn!(
            "{}: the largest distance measured, {:e}, is over the tolerance {:e} after {} rounds",
            a.input.display(),
            s.measured,
            s.tolerance,
            s.rounds
        );
    }
    println!(
        "{} -> {} ({} triangles within {:e})",
        a.input.display(),
        a.output.display(),
        out.triangles.len(),
        s.tolerance
    );
    Ok(())
}
