//! The commands that read a mesh and write one: subdivide, smooth, limit, repair.

use super::args::{InputArgs, LimitArgs, Precision, SubdivArgs};
use super::{logging, print_json, progress};
use serde::Serialize;
use std::path::{Path, PathBuf};
use subdiv::mesh::Attributes;
use subdiv::{Demand, Error, Mesh, Result, bundled, io};

/// `subdiv subdivide` arguments.
#[derive(clap::Args)]
pub struct SubdivideArgs {
    /// Input model: a mesh file or bundled:NAME (see `subdiv models`).
    input: PathBuf,
    /// Output mesh (format by extension; written atomically).
    output: PathBuf,
    #[command(flatten)]
    refine: RefineArgs,
    /// Print timings: `subdivide_ms=<float>` and per-phase times.
    #[arg(long)]
    stats: bool,
    /// Print the result summary as JSON.
    #[arg(long)]
    json: bool,
}

/// The options of `subdivide` besides its files, shared with `subdiv
/// batch`: how a model is read, its subdivision and the precision.
#[derive(clap::Args, Clone)]
pub struct RefineArgs {
    #[command(flatten)]
    pub(crate) from: InputArgs,
    #[command(flatten)]
    pub(crate) sub: SubdivArgs,
    /// Compute in f32 (the default: fast, what the GPU draws) or f64 (from
    /// the file's own digits; written as OBJ's shortest f64 digits or PLY's
    /// double properties).
    #[arg(long, default_value = "f32")]
    pub(crate) precision: Precision,
}

/// What [`subdivide_file`] did: the line of `subdivide`, its `--json`
/// object and its `--stats`.
#[derive(Serialize)]
pub(crate) struct Summary {
    input: String,
    output: String,
    scheme: String,
    levels: u32,
    pub(crate) input_vertices: usize,
    pub(crate) input_faces: usize,
    pub(crate) vertices: usize,
    pub(crate) faces: usize,
    subdivide_ms: f64,
    split_ms: f64,
    edge_ms: f64,
    vertex_ms: f64,
    load_ms: f64,
    save_ms: f64,
    #[serde(skip)]
    numbering_ms: f64,
    #[serde(skip)]
    huge_pages: Option<bool>,
}

/// Output faces above which a subdivision shows a spinner.
const BIG_FACES: u64 = 1 << 20;

/// `subdiv subdivide`.
pub(crate) fn subdivide(a: &SubdivideArgs) -> Result<()> {
    let summary = subdivide_file(&a.input, &a.output, &a.refine, &mut |_| Ok(()))?;
    report(&summary, a.stats, a.json)
}

/// Subdivides the model `input` into `output` as `subdiv subdivide` does
/// (for `subdivide` and every file of `subdiv batch`): the library's
/// [`subdiv::subdivide_file`] with these arguments, `admit` told what the
/// refinement will need (it may wait for memory, or refuse), a spinner
/// for a large one, the repair's report and the attributes the output
/// keeps not on stderr (unless `-q`).
///
/// # Errors
/// The library's (reading, refining, writing; `admit`'s).
pub(crate) fn subdivide_file(
    input: &Path,
    output: &Path,
    o: &RefineArgs,
    admit: &mut dyn FnMut(&Demand) -> Result<()>,
) -> Result<Summary> {
    let job = subdiv::FileJob {
        read: o.from.options(false)?,
        flags: o.sub.scheme.flags(),
        levels: o.sub.levels_or(1),
        f64: o.precision == Precision::F64,
    };
    let mut spin = None;
    let mut admitted = |d: &Demand| {
        admit(d)?;
        if d.faces > BIG_FACES {
            spin = Some(progress::spinner(&format!("subdividing to {} faces", d.faces)));
        }
        Ok(())
    };
    let done = subdiv::subdivide_file(input, output, &job, &mut admitted);
    if let Some(pb) = spin {
        pb.finish_and_clear();
    }
    let s = done?;
    if logging::warnings_shown() {
        if let Some(report) = &s.repair {
            eprint!("{report}");
        }
        if !s.dropped.is_empty() {
            eprintln!("subdiv: note: {} keeps no {}", output.display(), s.dropped.join(" or "));
        }
    }
    let st = &s.stats;
    Ok(Summary {
        input: input.display().to_string(),
        output: output.display().to_string(),
        scheme: s.scheme,
        levels: s.levels,
        input_vertices: s.input_vertices,
        input_faces: s.input_faces,
        vertices: s.vertices,
        faces: s.faces,
        subdivide_ms: st.total_ms,
        split_ms: st.split_ms,
        edge_ms: st.edge_ms,
        vertex_ms: st.vertex_ms,
        load_ms: s.load_ms,
        save_ms: s.save_ms,
        numbering_ms: st.numbering_ms,
        huge_pages: st.huge_pages,
    })
}

/// What `subdivide` prints: `--stats`, `--json` or a line.
fn report(s: &Summary, stats: bool, json: bool) -> Result<()> {
    if stats {
        println!("subdivide_ms={:.3}", s.subdivide_ms);
        println!(
            "phases: split_and_o_ms={:.3} (edge_numbering_ms={:.3}) edge_points_ms={:.3} vertex_points_ms={:.3} load_ms={:.3} save_ms={:.3} threads={}{}",
            s.split_ms,
            s.numbering_ms,
            s.edge_ms,
            s.vertex_ms,
            s.load_ms,
            s.save_ms,
            rayon::current_num_threads(),
            s.huge_pages.map_or("", |huge| if huge { " pages=2MiB" } else { " pages=4KiB" })
        );
    }
    if json {
        print_json(s)?;
    } else if !stats {
        println!(
            "{} -> {}: {} levels of {}, {} vertices, {} faces",
            s.input, s.output, s.levels, s.scheme, s.vertices, s.faces
        );
    }
    Ok(())
}

/// Arguments of the commands that read one mesh and write one.
#[derive(clap::Args)]
pub struct InOut {
    /// Input model: a mesh file or bundled:NAME (see `subdiv models`).
    input: PathBuf,
    /// Output mesh (format by extension; written atomically).
    output: PathBuf,
    #[command(flatten)]
    from: InputArgs,
}

/// `subdiv repair` arguments: no `--repair` (it always repairs) and no
/// subdivision.
#[derive(clap::Args)]
pub struct RepairArgs {
    /// Input model: a mesh file or bundled:NAME (see `subdiv models`).
    input: PathBuf,
    /// Output mesh (format by extension; written atomically).
    output: PathBuf,
    #[command(flatten)]
    limits: LimitArgs,
}

/// `subdiv smooth` arguments.
#[derive(clap::Args)]
pub struct SmoothArgs {
    #[command(flatten)]
    io: InOut,
    /// Number of lambda/mu step pairs.
    #[arg(long, short = 'n', default_value_t = 10)]
    steps: u32,
    /// Shrinking factor lambda (> 0).
    #[arg(long, default_value = "0.6307")]
    lambda: f64,
    /// Inflating factor mu (< -lambda).
    #[arg(long, default_value = "-0.6732", allow_hyphen_values = true)]
    mu: f64,
    /// Plain Laplacian smoothing with lambda only (shrinks; for comparison).
    #[arg(long)]
    laplacian: bool,
    /// f32 (the default) or f64: the passes in double precision from the
    /// file's own digits (OBJ's text, PLY's doubles), written in double
    /// precision (OBJ or PLY).
    #[arg(long, default_value = "f32")]
    precision: Precision,
}

/// `subdiv smooth`.
pub(crate) fn smooth(a: &SmoothArgs) -> Result<()> {
    let (lambda, mu) = (a.lambda, a.mu);
    if !(lambda.is_finite() && mu.is_finite() && lambda > 0.0 && (a.laplacian || mu < -lambda)) {
        return Err(Error::Usage(format!("need lambda > 0 and mu < -lambda (got {lambda}, {mu})")));
    }
    let loaded = a.io.from.read(&a.io.input, false)?;
    let (mesh, precise) = (loaded.mesh, loaded.precise);
    if a.precision == Precision::F64 {
        let control = precise.unwrap_or_else(|| mesh.positions.iter().map(|p| p.as_dvec3()).collect());
        let mu = (!a.laplacian).then_some(mu);
        let pos = subdiv::mesh::smooth_f64(&mesh, &control, a.steps, lambda, mu);
        io::save_f64(&a.io.output, &mesh, &pos, &Attributes::default(), true)?;
    } else {
        let (lambda, mu) = (lambda as f32, mu as f32);
        let positions = match a.laplacian {
            true => subdiv::mesh::laplacian(&mesh, a.steps, lambda),
            false => subdiv::mesh::taubin(&mesh, a.steps, lambda, mu),
        };
        io::save(&a.io.output, &Mesh { ct: mesh.ct, positions })?;
    }
    println!("{} -> {}: {} smoothing steps", a.io.input.display(), a.io.output.display(), a.steps);
    Ok(())
}

/// `subdiv limit` arguments.
#[derive(clap::Args)]
pub struct LimitCmdArgs {
    /// Input model: a mesh file or bundled:NAME (see `subdiv models`).
    input: PathBuf,
    /// Output mesh (format by extension; written atomically; polygons kept where the format keeps them).
    output: PathBuf,
    #[command(flatten)]
    from: InputArgs,
    /// The surface: loop (triangles) or catmull-clark (polygons).
    #[arg(long, short, default_value = "loop")]
    scheme: subdiv::Scheme,
    #[command(flatten)]
    features: super::args::FeatureArgs,
    /// f64 (the default) or f32: the limit from the file's own digits (OBJ's
    /// text, PLY's doubles), computed and written in double precision (OBJ or
    /// PLY); f32 computes from and writes single-precision positions.
    #[arg(long, default_value = "f64")]
    precision: Precision,
}

/// `subdiv limit`.
pub(crate) fn limit(a: &LimitCmdArgs) -> Result<()> {
    let loaded = a.from.read(&a.input, false)?;
    let (mesh, attrs, precise) = (loaded.mesh, loaded.attributes, loaded.precise);
    let features = a.features.over(attrs.options);
    let mesh = features.apply(mesh);
    match a.scheme {
        subdiv::Scheme::Loop if a.precision == Precision::F64 => {
            use subdiv::eval::loop_limit_positions_f64;
            let control = precise.unwrap_or_else(|| mesh.positions.iter().map(|p| p.as_dvec3()).collect());
            let pos = loop_limit_positions_f64(&mesh, &control, subdiv::LoopBeta::Loop);
            io::save_f64(&a.output, &mesh, &pos, &Attributes { options: attrs.options, ..Default::default() }, true)?;
        }
        subdiv::Scheme::Loop => {
            let positions = subdiv::eval::loop_limit_positions(&mesh);
            io::save(&a.output, &Mesh { ct: mesh.ct, positions })?;
        }
        subdiv::Scheme::CatmullClark => {
            let opts = subdiv::Options {
                creasing: features.creasing.unwrap_or_default(),
                boundary: features.sharp.boundary.unwrap_or_default(),
                ..Default::default()
            };
            let mut poly = subdiv::mesh::PolyMesh::from_mesh(&mesh);
            if a.precision == Precision::F64 {
                let control = precise.unwrap_or_else(|| mesh.positions.iter().map(|p| p.as_dvec3()).collect());
                let pos = subdiv::eval::limit_positions_f64(&poly, &control, &opts)?;
                io::save_f64(&a.output, &poly, &pos, &Default::default(), true)?;
            } else {
                let frames = subdiv::eval::limit_frames(&poly, &opts)?;
                poly.positions = frames.iter().map(|f| f.position).collect();
                io::save_with(&a.output, &poly, &Default::default())?;
            }
        }
        s => {
            return Err(Error::Usage(format!(
                "{s} has no limit masks here: `limit` takes --scheme loop or catmull-clark"
            )));
        }
    }
    println!("{} -> {}: {} limit positions", a.input.display(), a.output.display(), a.scheme);
    Ok(())
}

/// `subdiv repair` (always repairs).
pub(crate) fn repair(a: &RepairArgs) -> Result<()> {
    let from = InputArgs { repair: true, limits: a.limits.clone(), time: None };
    let loaded = bundled::read(&a.input, &from.options(false)?)?;
    let mesh = loaded.mesh;
    io::save(&a.output, &mesh)?;
    if let Some(report) = &loaded.notes.repair {
        print!("{report}");
    }
    println!(
        "{} -> {}: {} vertices, {} faces",
        a.input.display(),
        a.output.display(),
        mesh.positions.len(),
        mesh.ct.num_triangles()
    );
    Ok(())
}
