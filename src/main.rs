//! The `subdiv` command line: view | animate | subdivide | smooth | limit |
//! repair | info | render | models. Every command that reads a model takes a
//! file or `bundled:NAME`, a model compiled into the binary (`subdiv models`
//! lists them), through `subdiv::bundled`.

use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;
use subdiv::mesh::topology::topology;
use subdiv::{Error, LoopBeta, Mesh, MeshError, Options, Result, Scheme, bundled, io};

#[derive(Parser)]
#[command(name = "subdiv", version, about = "Triangle-mesh subdivision: viewer and command line", long_about = None)]
struct Cli {
    #[command(subcommand)]
    cmd: Option<Cmd>,
    /// Worker threads (default: all cores).
    #[arg(long, global = true)]
    threads: Option<usize>,
}

#[derive(clap::Args, Clone, Default)]
struct SchemeArgs {
    /// Scheme: midpoint, loop, butterfly, modified-butterfly, jarek.
    #[arg(long, short, default_value = "loop")]
    scheme: Scheme,
    /// Use Warren's beta for Loop instead of Loop's.
    #[arg(long)]
    warren: bool,
    /// Modified-butterfly tension w (0 = Zorin's default).
    #[arg(long, default_value_t = 0.0)]
    tension: f32,
    /// Refuse levels predicted to need more than this (e.g. 2G, 500M; default: 80% of available memory).
    #[arg(long, value_parser = parse_bytes)]
    max_memory: Option<u64>,
    #[command(flatten)]
    features: FeatureArgs,
}

impl SchemeArgs {
    fn options(&self) -> Options {
        Options {
            loop_beta: if self.warren { LoopBeta::Warren } else { LoopBeta::Loop },
            tension: self.tension,
            max_memory: self.max_memory,
            creasing: self.features.creasing,
            boundary: self.features.boundary,
        }
    }
}

/// Sharp features: the model's own tags (OBJ `t crease` / `t corner`, .ct
/// `creases` / `corners`) plus these options (OpenSubdiv's names).
#[derive(clap::Args, Clone, Default)]
struct FeatureArgs {
    /// Make every edge whose two faces' normals differ by more than DEG degrees infinitely sharp.
    #[arg(long, value_name = "DEG")]
    crease_angle: Option<f32>,
    /// Boundary interpolation: edge (boundary edges sharp) or edge-and-corner (also one-face corners).
    #[arg(long, default_value = "edge")]
    boundary: subdiv::mesh::BoundaryInterpolation,
    /// How semi-sharp creases decay: uniform (s - 1 per level) or chaikin.
    #[arg(long, default_value = "uniform")]
    creasing: subdiv::mesh::Creasing,
}

impl FeatureArgs {
    /// `mesh` with the edges sharper than `--crease-angle` tagged.
    fn apply(&self, mesh: Mesh) -> Result<Mesh> {
        let Some(deg) = self.crease_angle else { return Ok(mesh) };
        if !(0.0..=180.0).contains(&deg) {
            return Err(Error::Usage(format!("--crease-angle {deg}: give an angle from 0 to 180 degrees")));
        }
        let Mesh { ct, positions } = mesh;
        Ok(Mesh { ct: ct.with_angle_creases(&positions, deg), positions })
    }
}

#[derive(Subcommand)]
enum Cmd {
    /// Open the viewer (the default when no command is given).
    View(ViewArgs),
    /// Render the split-and-tweak animation to a GIF or numbered PNGs.
    Animate(AnimateArgs),
    /// Subdivide a mesh and write the result (.obj, .ply or .ct by extension).
    Subdivide {
        /// Input model: .obj, .ct, .bez or bundled:NAME (see `subdiv models`).
        input: PathBuf,
        /// Output .obj, .ply or .ct.
        output: PathBuf,
        #[command(flatten)]
        scheme: SchemeArgs,
        /// Number of levels.
        #[arg(long, short = 'n', default_value_t = 1)]
        levels: u32,
        /// Print timings: `subdivide_ms=<float>` and per-phase times.
        #[arg(long)]
        stats: bool,
        /// Print the result summary as JSON.
        #[arg(long)]
        json: bool,
        /// Repair the input first (cut non-manifold edges, split non-manifold
        /// vertices, fix orientation, drop degenerate and duplicate faces)
        /// instead of refusing it; the repair report goes to stderr.
        #[arg(long)]
        repair: bool,
    },
    /// Repair a mesh into a valid manifold one and write it (.obj, .ply or .ct by extension).
    ///
    /// Drops degenerate and duplicate faces, cuts non-manifold edges, makes the
    /// orientation consistent, gives every fan of a non-manifold vertex its own
    /// copy and drops unreferenced vertices; prints what changed.
    /// Taubin lambda/mu smoothing (no shrinkage), or plain Laplacian with --laplacian.
    Smooth {
        /// Input model: .obj, .ct, .bez or bundled:NAME (see `subdiv models`).
        input: PathBuf,
        /// Output .obj, .ply or .ct (written atomically).
        output: PathBuf,
        /// Number of lambda/mu step pairs.
        #[arg(long, short = 'n', default_value_t = 10)]
        steps: u32,
        /// Shrinking factor lambda (> 0).
        #[arg(long, default_value_t = subdiv::mesh::smooth::TAUBIN_LAMBDA)]
        lambda: f32,
        /// Inflating factor mu (< -lambda).
        #[arg(long, default_value_t = subdiv::mesh::smooth::TAUBIN_MU, allow_hyphen_values = true)]
        mu: f32,
        /// Plain Laplacian smoothing with lambda only (shrinks; for comparison).
        #[arg(long)]
        laplacian: bool,
    },
    /// Move every vertex to its limit position on the Loop surface (after `subdivide --scheme loop`).
    Limit {
        /// Input model: .obj, .ct, .bez or bundled:NAME (see `subdiv models`).
        input: PathBuf,
        /// Output .obj, .ply or .ct (written atomically).
        output: PathBuf,
    },
    Repair {
        /// Input model: .obj, .ct, .bez or bundled:NAME (see `subdiv models`).
        input: PathBuf,
        /// Output .obj, .ply or .ct (written atomically).
        output: PathBuf,
    },
    /// Print counts, boundary, components, genus, valences and problems.
    ///
    /// A mesh that does not build (non-manifold, inconsistent orientation,
    /// degenerate faces) is analysed instead: every non-manifold edge and
    /// vertex is listed, and the counts are those of the repaired mesh. A
    /// .bzc Bezier curve is described as a curve (control points, degree).
    Info {
        /// Input model: .obj, .ct, .bez or bundled:NAME (see `subdiv models`).
        input: PathBuf,
        /// Print as JSON.
        #[arg(long)]
        json: bool,
        /// Always analyse and describe the repaired mesh, even when the input is valid.
        #[arg(long)]
        repair: bool,
        #[command(flatten)]
        features: FeatureArgs,
    },
    /// List the bundled models (open any of them as bundled:NAME).
    Models,
    /// Render a mesh offscreen to a PNG.
    Render {
        /// Input model: .obj, .ct, .bez or bundled:NAME (see `subdiv models`).
        input: PathBuf,
        /// Output PNG.
        output: PathBuf,
        #[command(flatten)]
        scheme: SchemeArgs,
        /// Number of levels.
        #[arg(long, short = 'n', default_value_t = 0)]
        levels: u32,
        /// phong, flat, studio (matcap), wire or phong+wire.
        #[arg(long, default_value = "phong")]
        shading: String,
        /// Image size WxH.
        #[arg(long, default_value = "800x600", value_parser = parse_size)]
        size: (u32, u32),
        /// Orthographic projection.
        #[arg(long)]
        ortho: bool,
        /// Overlay the control mesh.
        #[arg(long)]
        control: bool,
        #[command(flatten)]
        look: RenderLook,
    },
}

/// The wireframe and picture options of `render`.
#[derive(clap::Args)]
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
struct RenderLook {
    /// Wireframe edges drawn (with --shading wire or phong+wire): all, control
    /// (the control mesh's edges on the surface) or K (the edges made up to level K).
    #[arg(long, default_value = "all")]
    wire_level: String,
    /// Transparent background (alpha 0; the object stays opaque).
    #[arg(long)]
    transparent: bool,
    /// Render N times the size (lines N times as wide: the same picture, sharper).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=8))]
    scale: u32,
}

fn parse_size(s: &str) -> std::result::Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("'{s}' is not WxH"))?;
    let w: u32 = w.parse().map_err(|_| format!("bad width in '{s}'"))?;
    let h: u32 = h.parse().map_err(|_| format!("bad height in '{s}'"))?;
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(format!("size {w}x{h} out of range (1..16384)"));
    }
    Ok((w, h))
}

fn parse_bytes(s: &str) -> std::result::Result<u64, String> {
    let s = s.trim();
    let (num, mult) = match s.chars().last().map(|c| c.to_ascii_uppercase()) {
        Some('K') => (&s[..s.len() - 1], 1u64 << 10),
        Some('M') => (&s[..s.len() - 1], 1 << 20),
        Some('G') => (&s[..s.len() - 1], 1 << 30),
        Some('T') => (&s[..s.len() - 1], 1 << 40),
        _ => (s, 1),
    };
    let x: f64 = num.parse().map_err(|_| format!("'{s}' is not a size (e.g. 512M, 2G)"))?;
    if !(x.is_finite() && x >= 0.0) {
        return Err(format!("'{s}' is not a size"));
    }
    Ok((x * mult as f64) as u64)
}

fn main() -> ExitCode {
    // Like other Unix tools, end quietly when the reader of our output goes away
    // (`subdiv info big.obj | head`) instead of panicking on a broken pipe.
    // SAFETY: setting a signal disposition to the default before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    if let Some(n) = cli.threads
        && let Err(e) = rayon::ThreadPoolBuilder::new().num_threads(n.max(1)).build_global()
    {
        eprintln!("subdiv: cannot set {n} threads: {e}");
        return ExitCode::from(2);
    }
    match run(cli.cmd) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("subdiv: error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(cmd: Option<Cmd>) -> Result<()> {
    match cmd {
        None => first_launch(),
        Some(Cmd::View(args)) => view(args),
        Some(Cmd::Animate(args)) => animate_cmd(args),
        Some(Cmd::Subdivide { input, output, scheme, levels, stats, json, repair }) => {
            subdivide_cmd(&input, &output, &scheme, levels, stats, json, repair)
        }
        Some(Cmd::Repair { input, output }) => repair_cmd(&input, &output),
        Some(Cmd::Smooth { input, output, steps, lambda, mu, laplacian }) => {
            let mesh = bundled::load(&input)?;
            if !(lambda.is_finite() && mu.is_finite() && lambda > 0.0 && (laplacian || mu < -lambda)) {
                return Err(Error::Usage(format!("need lambda > 0 and mu < -lambda (got {lambda}, {mu})")));
            }
            let positions = if laplacian {
                subdiv::mesh::smooth::laplacian(&mesh, steps, lambda)
            } else {
                subdiv::mesh::smooth::taubin(&mesh, steps, lambda, mu)
            };
            let out = Mesh { ct: mesh.ct, positions };
            io::save(&output, &out)?;
            println!("{} -> {}: {steps} smoothing steps", input.display(), output.display());
            Ok(())
        }
        Some(Cmd::Limit { input, output }) => {
            let mesh = bundled::load(&input)?;
            let positions = subdiv::subdiv::limit::loop_limit_positions(&mesh);
            io::save(&output, &Mesh { ct: mesh.ct, positions })?;
            println!("{} -> {}: Loop limit positions", input.display(), output.display());
            Ok(())
        }
        Some(Cmd::Info { input, json, repair, features }) => info_cmd(&input, json, repair, &features),
        Some(Cmd::Models) => {
            models_cmd();
            Ok(())
        }
        Some(Cmd::Render { input, output, scheme, levels, shading, size, ortho, control, look }) => {
            render_cmd(&input, &output, &scheme, levels, &shading, size, ortho, control, &look)
        }
    }
}

/// `subdiv view` arguments (parsed the same with and without the viewer feature).
#[derive(clap::Args, Default)]
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
struct ViewArgs {
    /// OBJ, .ct, .bez (patches) or .bzc (curve) file, or bundled:NAME (default: the bundled tetrahedron).
    model: Option<PathBuf>,
    #[command(flatten)]
    scheme: SchemeArgs,
    /// Initial subdivision level.
    #[arg(long, short, default_value_t = 0)]
    level: u32,
    /// Start with the wireframe shown.
    #[arg(long)]
    wireframe: bool,
    /// Start with the control mesh (cage) shown.
    #[arg(long)]
    control: bool,
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
    /// Repair the model's topology when opening it (see `subdiv repair`).
    #[arg(long)]
    repair: bool,
    /// Colouring: none, shells, displacement, file (OBJ vertex colours) or checker (OBJ vt).
    #[arg(long, default_value = "none")]
    color: String,
}

#[cfg(feature = "viewer")]
fn view(a: ViewArgs) -> Result<()> {
    if a.screenshot.is_some() && a.frames.is_none() {
        return Err(Error::Usage("--screenshot needs --frames N (or press P in the window)".into()));
    }
    subdiv::app::run(subdiv::app::ViewOptions {
        model: a.model,
        scheme: a.scheme.scheme,
        opts: a.scheme.options(),
        level: a.level,
        wireframe: a.wireframe,
        frames: a.frames,
        screenshot: a.screenshot,
        paths: a.paths,
        play: a.play,
        turntable: a.turntable,
        repair: a.repair,
        coloring: a.color.parse().map_err(Error::Usage)?,
        crease_angle: a.scheme.features.crease_angle,
        control: a.control,
    })
}

/// `subdiv` alone: the viewer with something worth seeing (see `ViewOptions::first_launch`).
#[cfg(feature = "viewer")]
fn first_launch() -> Result<()> {
    subdiv::app::run(subdiv::app::ViewOptions::first_launch())
}

#[cfg(not(feature = "viewer"))]
fn first_launch() -> Result<()> {
    view(ViewArgs::default())
}

/// `subdiv animate` arguments.
#[derive(clap::Args)]
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
struct AnimateArgs {
    /// Model: a file or bundled:NAME (default: the bundled tetrahedron).
    #[arg(long)]
    model: Option<PathBuf>,
    /// Key paths (.paths; default: beside the model or in paths/, else generated loops).
    #[arg(long)]
    paths: Option<PathBuf>,
    #[command(flatten)]
    scheme: SchemeArgs,
    /// Subdivision level of every frame.
    #[arg(long, short, default_value_t = 5)]
    level: u32,
    /// Path refinements n: K keys give K * 2^n frames.
    #[arg(long, default_value_t = 5)]
    refine: u32,
    /// Path tweak: bspline, four-point or jarek.
    #[arg(long, default_value = "jarek")]
    tweak: String,
    /// Write one looping GIF here.
    #[arg(long, conflicts_with = "frames_dir", required_unless_present = "frames_dir")]
    gif: Option<PathBuf>,
    /// Write frame_0000.png, ... into this directory.
    #[arg(long)]
    frames_dir: Option<PathBuf>,
    /// Image size WxH.
    #[arg(long, default_value = "480x480", value_parser = parse_size)]
    size: (u32, u32),
    /// phong, flat, wire or phong+wire.
    #[arg(long, default_value = "phong")]
    shading: String,
    /// Overlay the moving control mesh.
    #[arg(long)]
    control: bool,
    /// Frames per second stored in the GIF.
    #[arg(long, default_value_t = 30.0)]
    fps: f32,
}

#[cfg(feature = "viewer")]
fn animate_cmd(a: AnimateArgs) -> Result<()> {
    use subdiv::anim::{paths::Paths, player::Animation, tweak::Tweak};
    use subdiv::render::export::{ExportStyle, ExportTarget, export_animation};
    let shading: subdiv::render::Shading = a.shading.parse().map_err(Error::Usage)?;
    let tweak: Tweak = a.tweak.parse().map_err(Error::Usage)?;
    let (mesh, default_paths) = match &a.model {
        Some(m) => {
            let mesh = bundled::load(m)?;
            let beside = match bundled::paths_for(m) {
                Some(src) => {
                    let paths = src.load()?;
                    paths.check_model(&mesh, &src.describe())?;
                    Some(paths)
                }
                None => None,
            };
            (mesh, beside)
        }
        None => {
            let (mesh, paths) = bundled::tetrahedron()?;
            (mesh, Some(paths))
        }
    };
    let mesh = a.scheme.features.apply(mesh)?;
    let paths = match (&a.paths, default_paths) {
        (Some(p), _) => {
            let paths = Paths::load(p)?;
            paths.check_model(&mesh, &p.display().to_string())?;
            paths
        }
        (None, Some(paths)) => paths,
        (None, None) => Paths::generated(&mesh, 4),
    };
    let mut anim = Animation::new(&mesh, &paths, tweak, a.refine, a.scheme.scheme, a.level, &a.scheme.options())?;
    let target = match (a.gif, a.frames_dir) {
        (Some(g), _) => ExportTarget::Gif(g),
        (None, Some(d)) => ExportTarget::Frames(d),
        (None, None) => return Err(Error::Usage("give --gif FILE or --frames-dir DIR".into())),
    };
    let look = subdiv::render::Look { control: a.control, ..shading.look() };
    let style = ExportStyle { size: a.size, look, fps: a.fps };
    let t0 = Instant::now();
    let total = anim.frame_count();
    let n = export_animation(&mut anim, &mesh, &target, &style, |d, t| {
        if d == t || d % 16 == 0 {
            eprint!("\rsubdiv: frame {d}/{t}");
        }
        true
    })?;
    eprintln!();
    let out = match &target {
        ExportTarget::Gif(p) | ExportTarget::Frames(p) => p.display().to_string(),
    };
    println!(
        "wrote {n} frames ({} keys x 2^{}, {} triangles each) to {out} in {:.2} s",
        paths.keys_per_vertex,
        a.refine,
        anim.topology().num_triangles(),
        t0.elapsed().as_secs_f64()
    );
    debug_assert_eq!(n, total);
    Ok(())
}

#[cfg(not(feature = "viewer"))]
fn animate_cmd(_a: AnimateArgs) -> Result<()> {
    Err(Error::Usage("built without the 'viewer' feature: animation export is not available".into()))
}

#[cfg(not(feature = "viewer"))]
fn view(_a: ViewArgs) -> Result<()> {
    Err(Error::Usage(
        "built without the 'viewer' feature: use subdivide / info, or rebuild with default features".into(),
    ))
}

#[cfg(feature = "viewer")]
#[allow(clippy::too_many_arguments)]
fn render_cmd(
    input: &Path,
    output: &Path,
    scheme: &SchemeArgs,
    levels: u32,
    shading: &str,
    size: (u32, u32),
    ortho: bool,
    control: bool,
    look: &RenderLook,
) -> Result<()> {
    let shading: subdiv::render::Shading = shading.parse().map_err(Error::Usage)?;
    let wire_edges = look.wire_level.parse().map_err(Error::Usage)?;
    let mesh = scheme.features.apply(bundled::load(input)?)?;
    let (fine, _) = subdiv::subdivide(&mesh, scheme.scheme, levels, &scheme.options())?;
    let shot = subdiv::render::Shot { scale: look.scale, transparent: look.transparent };
    let (width, height) = size;
    let opts = subdiv::render::RenderOptions { shading, width, height, orthographic: ortho, wire_edges, shot };
    subdiv::render::render_png(&fine, control.then_some(&mesh), &opts, output)
}

#[cfg(not(feature = "viewer"))]
#[allow(clippy::too_many_arguments)]
fn render_cmd(
    _: &Path,
    _: &Path,
    _: &SchemeArgs,
    _: u32,
    _: &str,
    _: (u32, u32),
    _: bool,
    _: bool,
    _: &RenderLook,
) -> Result<()> {
    Err(Error::Usage("built without the 'viewer' feature: rendering is not available".into()))
}

fn subdivide_cmd(
    input: &Path,
    output: &Path,
    s: &SchemeArgs,
    levels: u32,
    stats: bool,
    json: bool,
    repair: bool,
) -> Result<()> {
    let t0 = Instant::now();
    let is_obj = |p: &Path| p.extension().is_none_or(|e| e.eq_ignore_ascii_case("obj"));
    let (mesh, attrs) = if repair {
        let (m, report) = bundled::load_repaired(input)?;
        eprint!("{report}");
        (m, Default::default())
    } else if is_obj(input) {
        bundled::load_with_attributes(input)?
    } else {
        (bundled::load(input)?, Default::default())
    };
    let mesh = s.features.apply(mesh)?;
    let load_ms = t0.elapsed().as_secs_f64() * 1e3;
    let (fine, st) = subdiv::subdivide(&mesh, s.scheme, levels, &s.options())?;
    // Texture coordinates and colours ride along (OBJ in and out; see subdiv::attributes).
    let fine_attrs = if attrs.is_empty() {
        attrs
    } else if is_obj(output) {
        subdiv::subdiv::attributes::refine(&mesh.ct, &attrs, s.scheme, levels, &s.options())?
    } else {
        eprintln!("subdiv: note: texture coordinates and colours are written to .obj outputs only");
        Default::default()
    };
    let t1 = Instant::now();
    if fine_attrs.is_empty() {
        io::save(output, &fine)?;
    } else {
        io::obj::save_with(output, &fine, &fine_attrs)?;
    }
    let save_ms = t1.elapsed().as_secs_f64() * 1e3;
    if stats {
        println!("subdivide_ms={:.3}", st.total_ms);
        println!(
            "phases: split_and_o_ms={:.3} (edge_numbering_ms={:.3}) edge_points_ms={:.3} vertex_points_ms={:.3} load_ms={load_ms:.3} save_ms={save_ms:.3} threads={}",
            st.split_ms,
            st.numbering_ms,
            st.edge_ms,
            st.vertex_ms,
            rayon::current_num_threads()
        );
    }
    if json {
        println!(
            "{{\"scheme\":\"{}\",\"levels\":{levels},\"input_vertices\":{},\"input_faces\":{},\"vertices\":{},\"faces\":{},\"subdivide_ms\":{:.3},\"split_ms\":{:.3},\"edge_ms\":{:.3},\"vertex_ms\":{:.3},\"load_ms\":{load_ms:.3},\"save_ms\":{save_ms:.3}}}",
            s.scheme,
            mesh.positions.len(),
            mesh.ct.num_triangles(),
            fine.positions.len(),
            fine.ct.num_triangles(),
            st.total_ms,
            st.split_ms,
            st.edge_ms,
            st.vertex_ms
        );
    } else if !stats {
        println!(
            "{} -> {}: {} levels of {}, {} vertices, {} faces",
            input.display(),
            output.display(),
            levels,
            s.scheme,
            fine.positions.len(),
            fine.ct.num_triangles()
        );
    }
    Ok(())
}

fn repair_cmd(input: &Path, output: &Path) -> Result<()> {
    let (mesh, report) = bundled::load_repaired(input)?;
    io::save(output, &mesh)?;
    print!("{report}");
    println!(
        "{} -> {}: {} vertices, {} faces",
        input.display(),
        output.display(),
        mesh.positions.len(),
        mesh.ct.num_triangles()
    );
    Ok(())
}

/// Is this load error a topology problem that the repair analysis can describe?
fn is_topology_error(e: &Error) -> bool {
    let source = match e {
        Error::Mesh { source, .. } | Error::Invalid(source) => source,
        _ => return false,
    };
    matches!(
        source,
        MeshError::NonManifoldEdge { .. }
            | MeshError::NonManifoldVertex { .. }
            | MeshError::InconsistentOrientation { .. }
            | MeshError::DegenerateFace { .. }
    )
}

/// `subdiv models`: one line per bundled model, its command-line name and what it is.
fn models_cmd() {
    let width = bundled::MODELS.iter().map(|m| m.cli_name().len()).max().unwrap_or(0);
    for m in bundled::MODELS {
        println!("{:<width$}  {}", m.cli_name(), m.what);
    }
}

/// Is this model argument a `.bzc` curve (a file or a bundled one)?
fn is_curve(input: &Path) -> bool {
    input.extension().is_some_and(|e| e.eq_ignore_ascii_case("bzc"))
}

/// `subdiv info` of a `.bzc` Bezier curve: control points, degree, ends,
/// the point at t = 1/2 and the polyline length.
fn curve_info(input: &Path, json: bool) -> Result<()> {
    let control = bundled::load_curve(input)?;
    let at = |t: f32| subdiv::io::bezier::de_casteljau(&control, t).unwrap_or_default();
    let (first, mid, last) = (at(0.0), at(0.5), at(1.0));
    let length: f32 =
        subdiv::io::bezier::curve_polyline(&control, 256).windows(2).map(|w| (w[1] - w[0]).length()).sum();
    let degree = control.len().saturating_sub(1);
    if json {
        println!(
            "{{\"file\":\"{}\",\"kind\":\"bezier_curve\",\"control_points\":{},\"degree\":{degree},\"length\":{length}}}",
            json_escape(&input.display().to_string()),
            control.len()
        );
        return Ok(());
    }
    println!("file:            {}", input.display());
    println!("kind:            Bezier curve (.bzc), not a mesh: no faces to subdivide (`subdiv view` draws it)");
    println!("control points:  {} (degree {degree})", control.len());
    println!("ends:            ({:.4}, {:.4}) .. ({:.4}, {:.4})", first.x, first.y, last.x, last.y);
    println!("point at t=1/2:  ({:.4}, {:.4})", mid.x, mid.y);
    println!("length:          {length:.4}");
    Ok(())
}

fn json_escape(s: &str) -> String {
    s.replace('\\', "\\\\").replace('"', "\\\"")
}

fn info_cmd(input: &Path, json: bool, repair: bool, features: &FeatureArgs) -> Result<()> {
    if is_curve(input) {
        return curve_info(input, json);
    }
    let loaded = if repair { None } else { Some(load_for_info(input)) };
    let (mesh, dropped, records, report) = match loaded {
        Some(Ok((m, dropped, records))) => (m, dropped, records, None),
        Some(Err(e)) if !is_topology_error(&e) => return Err(e),
        // invalid topology (or --repair): analyse and describe the repaired mesh
        _ => {
            let (m, r) = bundled::analyze(input)?;
            (m, r.unreferenced_vertices.count, r.vertices_in, Some(r))
        }
    };
    let mesh = features.apply(mesh)?;
    let sharp = subdiv::subdiv::features::summary(&mesh.ct, features.boundary);
    let (nm_edges, nm_vertices) =
        report.as_ref().map_or((0, 0), |r| (r.non_manifold_edges.count, r.non_manifold_vertices.count));
    let t = topology(&mesh.ct);
    let (lo, hi) = mesh.bounds();
    let hist: Vec<String> =
        t.valence_histogram.iter().enumerate().filter(|&(_, &c)| c > 0).map(|(k, c)| format!("{k}:{c}")).collect();
    if json {
        println!(
            "{{\"file\":\"{}\",\"vertices\":{},\"edges\":{},\"faces\":{},\"closed\":{},\"boundary_loops\":{},\"border_edges\":{},\"components\":{},\"euler\":{},\"genus\":{},\"unreferenced_dropped\":{dropped},\"non_manifold_edges\":{nm_edges},\"non_manifold_vertices\":{nm_vertices},\"repaired\":{},\"sharp_edges\":{},\"infinitely_sharp_edges\":{},\"sharp_vertices\":{},\"corners\":{},\"darts\":{},\"crease_vertices\":{},\"valence\":{{{}}}}}",
            json_escape(&input.display().to_string()),
            t.vertices,
            t.edges,
            t.faces,
            t.is_closed(),
            t.boundary_loops,
            t.border_edges,
            t.components,
            t.euler,
            t.genus,
            report.is_some(),
            sharp.sharp_edges,
            sharp.infinite_edges,
            sharp.sharp_vertices,
            sharp.corners,
            sharp.darts,
            sharp.crease_vertices,
            hist.iter()
                .map(|h| {
                    let (k, c) = h.split_once(':').unwrap_or(("0", "0"));
                    format!("\"{k}\":{c}")
                })
                .collect::<Vec<_>>()
                .join(",")
        );
        return Ok(());
    }
    println!("file:            {}", input.display());
    println!("vertices:        {} ({records} records, {dropped} unreferenced dropped)", t.vertices);
    println!("edges:           {}", t.edges);
    println!("faces:           {}", t.faces);
    println!("closed:          {}", if t.is_closed() { "yes" } else { "no" });
    println!("boundary loops:  {} ({} border edges)", t.boundary_loops, t.border_edges);
    println!("components:      {}", t.components);
    println!("euler:           {}", t.euler);
    println!("genus:           {}", t.genus);
    match &report {
        None => println!("manifold:        yes (0 non-manifold edges, 0 non-manifold vertices)"),
        Some(r) => {
            let b = r.id_base;
            println!(
                "manifold:        {} ({nm_edges} non-manifold edges, {nm_vertices} non-manifold vertices; counts above are of the repaired mesh)",
                if nm_edges + nm_vertices == 0 { "yes" } else { "no" }
            );
            if nm_edges > 0 {
                let ids: Vec<String> =
                    r.non_manifold_edges.examples.iter().map(|e| format!("{}-{}", e[0] + b, e[1] + b)).collect();
                println!("non-manifold edges:    {}", ids.join(" "));
            }
            if nm_vertices > 0 {
                let ids: Vec<String> = r.non_manifold_vertices.examples.iter().map(|v| (v + b).to_string()).collect();
                println!("non-manifold vertices: {}", ids.join(" "));
            }
        }
    }
    println!(
        "sharp features:  {} sharp edges ({} infinitely sharp), {} sharp vertices; {} corners, {} darts, {} crease vertices",
        sharp.sharp_edges,
        sharp.infinite_edges,
        sharp.sharp_vertices,
        sharp.corners,
        sharp.darts,
        sharp.crease_vertices
    );
    println!("valence:         {}", hist.join(" "));
    println!("bounds:          [{:.4} {:.4} {:.4}] .. [{:.4} {:.4} {:.4}]", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    if let Some(r) = &report {
        print!("{r}");
    }
    Ok(())
}

/// Loads for `info`: the mesh, unreferenced vertices dropped, vertex records.
fn load_for_info(input: &Path) -> Result<(Mesh, usize, usize)> {
    if input.extension().is_some_and(|e| e == "ct" || e == "bez") {
        let m = bundled::load(input)?;
        let n = m.positions.len();
        Ok((m, 0, n))
    } else {
        // a file or a bundled model: bundled::read gives the bytes of either
        let bytes = bundled::read(input)?;
        let (m, inf) = io::obj::from_bytes(&bytes, &input.display().to_string())?;
        Ok((m, inf.unreferenced, inf.vertex_records))
    }
}
