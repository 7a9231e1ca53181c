//! The commands that read a mesh and write one: subdivide, smooth, limit, repair.

use super::args::{InputArgs, LimitArgs, Precision, SchemeArgs, SubdivArgs};
use super::{logging, print_json, progress};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;
use subdiv::mesh::Attributes;
use subdiv::{Error, Mesh, Result, bundled, io};

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

/// One file's subdivision: its input, its output and the options.
struct Job<'a> {
    input: &'a Path,
    output: &'a Path,
    from: &'a InputArgs,
    sub: &'a SubdivArgs,
    precision: Precision,
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

/// What a file's refinement is predicted to need (the library's
/// prediction, [`subdiv::rules::ControlCounts::peak_bytes`]), told once the
/// file is read and before anything is refined.
pub(crate) struct Demand {
    /// Peak bytes with every level kept (the most any path takes; twice
    /// that in f64), the parts of a stage together.
    pub(crate) peak: u64,
    /// The largest part's peak bytes without the levels kept, as the
    /// library's check counts them: over `--max-memory`, the library
    /// refuses the part before it allocates, whatever its path.
    pub(crate) least: u64,
    /// Refinements the file takes (a USD stage of several schemes: one each).
    pub(crate) parts: usize,
}

impl Demand {
    /// The demand of `parts`, each mesh refined by its scheme and levels,
    /// in `precision` (f64 points take twice the bytes).
    fn of(parts: &[(&Mesh, subdiv::Scheme, u32)], precision: Precision) -> Demand {
        let scale = if precision == Precision::F64 { 2 } else { 1 };
        let (mut peak, mut least) = (0u64, 0u64);
        for &(mesh, scheme, levels) in parts {
            let counts = subdiv::rules::ControlCounts::of(&mesh.ct);
            peak = peak.saturating_add(counts.peak_bytes(scheme, levels, true).saturating_mul(scale));
            least = least.max(counts.peak_bytes(scheme, levels, false));
        }
        Demand { peak, least, parts: parts.len() }
    }
}

/// Output faces above which a subdivision shows a spinner.
const BIG_FACES: u64 = 1 << 20;

/// `subdiv subdivide`.
pub(crate) fn subdivide(a: &SubdivideArgs) -> Result<()> {
    let summary = subdivide_file(&a.input, &a.output, &a.refine, &mut |_| Ok(()))?;
    report(&summary, a.stats, a.json)
}

/// Subdivides the model `input` into `output` as `subdiv subdivide` does
/// (for `subdivide` and every file of `subdiv batch`): reads it, calls
/// `admit` with what the refinement will need (it may wait for memory, or
/// refuse), then refines and writes it.
///
/// # Errors
/// The library's (reading, refining, writing; `admit`'s).
pub(crate) fn subdivide_file(
    input: &Path,
    output: &Path,
    o: &RefineArgs,
    admit: &mut dyn FnMut(&Demand) -> Result<()>,
) -> Result<Summary> {
    let a = &Job { input, output, from: &o.from, sub: &o.sub, precision: o.precision };
    let t0 = Instant::now();
    let loaded = a.from.read(a.input, false)?;
    let (mesh, attrs, precise) = (loaded.mesh, loaded.attributes, loaded.precise);
    let groups = subdiv::parts_by_options(&mesh, &attrs)?;
    if !groups.is_empty() {
        return subdivide_groups(a, (&mesh, groups), t0, admit);
    }
    // the file's option tags where no flag is given
    let s = &a.sub.scheme.over(attrs.options);
    // `subdivisionScheme none`: the cage is the surface at every level
    let levels = if s.subdivides() { a.sub.levels_or(1) } else { 0 };
    let attrs = attrs.with_options(written_options(s, levels));
    let mesh = s.features.apply(mesh);
    let load_ms = t0.elapsed().as_secs_f64() * 1e3;
    admit(&Demand::of(&[(&mesh, s.scheme(), levels)], a.precision))?;
    let faces = (mesh.ct.num_triangles() as u64).saturating_mul(1u64 << (2 * levels.min(30)));
    let spin = (faces > BIG_FACES).then(|| progress::spinner(&format!("subdividing to {faces} faces")));
    let attrs = kept_by_output(a.output, attrs);
    let model = subdiv::Model { precise: precise.as_deref(), ..subdiv::Model::new(&mesh, &attrs) };
    let how = subdiv::Refinement {
        scheme: s.scheme(),
        levels,
        opts: s.options(),
        f64: a.precision == Precision::F64,
        dest: io::destination(a.output),
    };
    let fine = subdiv::subdivide_model(&model, &how)?;
    let t1 = Instant::now();
    io::save_refined(a.output, &fine)?;
    let save_ms = t1.elapsed().as_secs_f64() * 1e3;
    let (vertices, out_faces, st) = (fine.num_vertices(), fine.num_faces(), &fine.stats);
    if let Some(pb) = spin {
        pb.finish_and_clear();
    }
    let file_faces = match subdiv::mesh::PolyMesh::is_polygonal(&mesh) {
        true => subdiv::mesh::PolyMesh::from_mesh(&mesh).pt.num_faces(),
        false => mesh.ct.num_triangles(),
    };
    let what = match s.subdivides() {
        true => s.scheme().to_string(),
        false => "none (subdivisionScheme none: the cage as it is)".into(),
    };
    Ok(summary((a, levels, &what), (mesh.positions.len(), file_faces), (vertices, out_faces), st, (load_ms, save_ms)))
}

/// The options a level made with `s` states: the scheme and options it
/// was made with (a refined level's border faces are not holes any more:
/// boundary none is the control mesh's).
fn written_options(s: &SchemeArgs, levels: u32) -> subdiv::mesh::ShapeOptions {
    let mut o = s.shape();
    if levels > 0 && o.boundary == Some(subdiv::mesh::BoundaryInterpolation::None) {
        o.boundary = None;
    }
    o
}

/// `subdivide` of a scene whose prims state different options (a USD
/// stage of a Loop prim and a Catmull-Clark one, or one that says
/// `subdivisionScheme none`): each set of prims refined by its own
/// options under the flags, joined into one output whose faces keep their
/// prims (USD prims, OBJ objects, glTF meshes).
fn subdivide_groups(
    a: &Job,
    (cage, parts): (&Mesh, Vec<(Mesh, Attributes)>),
    t0: Instant,
    admit: &mut dyn FnMut(&Demand) -> Result<()>,
) -> Result<Summary> {
    if a.precision == Precision::F64 {
        return Err(Error::Usage(format!(
            "{}: its prims state different schemes or options, which --precision f64 does not refine apart: give one --scheme",
            a.input.display()
        )));
    }
    let mut groups = Vec::with_capacity(parts.len());
    for (mesh, attrs) in parts {
        let s = a.sub.scheme.over(attrs.options);
        let levels = if s.subdivides() { a.sub.levels_or(1) } else { 0 };
        let attrs = kept_by_output(a.output, attrs).with_options(written_options(&s, levels));
        groups.push((s.features.apply(mesh), attrs, s, levels));
    }
    let load_ms = t0.elapsed().as_secs_f64() * 1e3;
    let demand: Vec<_> = groups.iter().map(|(mesh, _, s, levels)| (mesh, s.scheme(), *levels)).collect();
    admit(&Demand::of(&demand, a.precision))?;
    let parts: Vec<subdiv::Part> = groups
        .iter()
        .map(|(mesh, attrs, s, levels)| subdiv::Part {
            mesh,
            attrs,
            scheme: s.subdivides().then(|| s.scheme()),
            levels: *levels,
            opts: s.options(),
        })
        .collect();
    let (fine, attrs, st) = subdiv::subdivide_parts(&parts, io::keeps(a.output).holes)?;
    let t1 = Instant::now();
    io::save_with(a.output, &fine, &attrs)?;
    let save_ms = t1.elapsed().as_secs_f64() * 1e3;
    let cage = (cage.positions.len(), subdiv::mesh::PolyMesh::from_mesh(cage).pt.num_faces());
    let schemes: Vec<String> =
        groups.iter().map(|(_, _, s, _)| if s.subdivides() { s.scheme().to_string() } else { "none".into() }).collect();
    let what = format!("{} (by prim)", schemes.join(" and "));
    let levels = a.sub.levels_or(1);
    Ok(summary((a, levels, &what), cage, (fine.positions.len(), fine.pt.num_faces()), &st, (load_ms, save_ms)))
}

/// The attributes `output`'s format keeps, the others dropped (with a
/// note) before any is refined.
fn kept_by_output(output: &std::path::Path, attrs: Attributes) -> Attributes {
    let keeps = io::keeps(output);
    let dropped: Vec<&str> = [
        (attrs.uv.is_some() && !keeps.uv, "texture coordinates"),
        (attrs.colors.is_some() && !keeps.colors, "colours"),
        (attrs.materials.is_some() && !keeps.materials, "materials"),
    ]
    .into_iter()
    .filter_map(|(dropped, what)| dropped.then_some(what))
    .collect();
    if !dropped.is_empty() && logging::warnings_shown() {
        eprintln!("subdiv: note: {} keeps no {}", output.display(), dropped.join(" or "));
    }
    Attributes {
        uv: attrs.uv.filter(|_| keeps.uv),
        colors: attrs.colors.filter(|_| keeps.colors),
        materials: attrs.materials.filter(|_| keeps.materials),
        options: attrs.options,
    }
}

/// The summary of a subdivision.
fn summary(
    (a, levels, scheme): (&Job, u32, &str),
    (input_vertices, input_faces): (usize, usize),
    (vertices, faces): (usize, usize),
    st: &subdiv::Stats,
    (load_ms, save_ms): (f64, f64),
) -> Summary {
    Summary {
        input: a.input.display().to_string(),
        output: a.output.display().to_string(),
        scheme: scheme.to_string(),
        levels,
        input_vertices,
        input_faces,
        vertices,
        faces,
        subdivide_ms: st.total_ms,
        split_ms: st.split_ms,
        edge_ms: st.edge_ms,
        vertex_ms: st.vertex_ms,
        load_ms,
        save_ms,
        numbering_ms: st.numbering_ms,
        huge_pages: st.huge_pages,
    }
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
