//! `subdiv eval`: the exact Loop or Catmull-Clark limit surface at given
//! parameter points.

use super::args::{InputArgs, LimitInput, Precision, SchemeArgs};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use subdiv::Evaluator;
use subdiv::Result;
use subdiv::eval::parse_points_in;
use subdiv::io::write_rows;

/// `subdiv eval` arguments.
#[derive(clap::Args)]
#[command(mut_arg("scheme_flag", |a| a.help("Scheme: loop (triangles, the default) or catmull-clark (polygons): the schemes with an exact evaluation")))]
pub struct EvalArgs {
    /// Input model: a mesh file or bundled:NAME (see `subdiv models`).
    input: PathBuf,
    /// Points, one per line: `f u v`. Loop: control triangle f, 0-based in
    /// the file's face order, the point (1-u-v) c0 + u c1 + v c2 of its
    /// corners in the order the face lists them. Catmull-Clark: ptex face f
    /// (a quad is one, an n-gon n, one per corner, in file order) and (u, v)
    /// in its unit square, corner 0 at (0,0), 1 at (1,0), 2 at (1,1).
    points: PathBuf,
    /// Output: one line per point, `x y z nx ny nz` (limit position, unit
    /// normal), with --curvature also `H K`.
    output: PathBuf,
    #[command(flatten)]
    from: InputArgs,
    #[command(flatten)]
    scheme: SchemeArgs,
    /// Also write the mean and Gaussian curvature (H > 0 on a convex
    /// surface with outward normals; NaN at an extraordinary or sharp vertex
    /// itself, where the surface has none). Positions and normals are always
    /// finite.
    #[arg(long)]
    curvature: bool,
    /// Print the times of preparing and evaluating on stderr.
    #[arg(long)]
    stats: bool,
    /// The control points' precision: f64 (the default: the file's own
    /// digits, OBJ's text or PLY's doubles) or f32 (rounded as the viewer
    /// draws them). The evaluation is in f64 either way.
    #[arg(long, default_value = "f64")]
    precision: Precision,
}

/// `subdiv eval`.
pub(crate) fn eval(a: &EvalArgs) -> Result<()> {
    let LimitInput { mesh, scheme, control, .. } = LimitInput::read(&a.input, &a.from, &a.scheme, a.precision)?;
    let limits = a.from.limits.limits()?;
    let max_points = limits.get("vertices").unwrap_or(u64::MAX);
    let shown = a.points.display().to_string();
    let text = subdiv::io::read_text_file(&a.points, &limits)?;
    let start = Instant::now();
    let ev = Evaluator::new_f64(&mesh, &control, scheme.scheme(), &scheme.options())?;
    let prepared = start.elapsed();
    // every point is checked before any is evaluated
    let points = parse_points_in(&text, &shown, ev.domain(), usize::try_from(max_points).unwrap_or(usize::MAX))?;
    // only what is written is kept (a million points: 48 or 64 MB)
    let evaluated = if a.curvature {
        eval_and_write::<8>(&ev, &points, &a.output)?
    } else {
        eval_and_write::<6>(&ev, &points, &a.output)?
    };
    if a.stats {
        eprintln!(
            "prepare_ms={:.3} eval_ms={:.3} points={} per_point_ns={:.1}",
            prepared.as_secs_f64() * 1e3,
            evaluated.as_secs_f64() * 1e3,
            points.len(),
            evaluated.as_secs_f64() * 1e9 / points.len().max(1) as f64
        );
    }
    println!("{} at {} points -> {}", a.input.display(), points.len(), a.output.display());
    Ok(())
}

/// The first `N` columns of every point's row (with the curvatures when
/// `N` is 8) written to `out`; returns the time of the evaluation alone.
fn eval_and_write<const N: usize>(ev: &Evaluator, points: &[(usize, f64, f64)], out: &Path) -> Result<Duration> {
    let start = Instant::now();
    let rows = ev.eval_rows::<N>(points, N > 6)?;
    let evaluated = start.elapsed();
    write_rows(out, &rows)?;
    Ok(evaluated)
}
