//! The option groups shared by the commands (flattened into each with
//! `#[command(flatten)]`), so one option has one name, one meaning and one
//! help text everywhere: [`InputArgs`] on every command that reads a mesh,
//! [`SubdivArgs`] (scheme, sharp features, levels) on every command that
//! subdivides, [`ColorArgs`] on every command that draws.

use std::path::Path;
use subdiv::eval::color::CurvatureKind;
use subdiv::io::{Limits, Loaded, ReadOptions, Topology};
use subdiv::mesh::{FileScheme, ShapeOptions};
use subdiv::{LoopBeta, Mesh, Options, Result, Scheme, bundled};

/// How a mesh is read.
#[derive(clap::Args, Clone, Default)]
pub struct InputArgs {
    /// Repair the input first (cut non-manifold edges, split non-manifold
    /// vertices, fix orientation, drop degenerate and duplicate faces)
    /// instead of refusing it; the repair report goes to stderr.
    #[arg(long)]
    pub repair: bool,
    /// Read a USD stage's sampled points (and transforms) at time code T
    /// (default: the stage's startTimeCode, else its first sample).
    #[arg(long, value_name = "T", allow_hyphen_values = true, value_parser = parse_time)]
    pub time: Option<f64>,
    #[command(flatten)]
    pub limits: LimitArgs,
}

/// A finite time code.
fn parse_time(s: &str) -> std::result::Result<f64, String> {
    s.parse::<f64>().ok().filter(|t| t.is_finite()).ok_or_else(|| format!("'{s}' is not a finite time code"))
}

/// The reading budget.
#[derive(clap::Args, Clone, Default)]
pub struct LimitArgs {
    // the help lists subdiv::io::LIMIT_NAMES, the names parse_limit takes
    #[arg(long = "limit", value_name = "NAME=VALUE", value_parser = parse_limit, help = limit_help())]
    pub limit: Vec<(String, u64)>,
}

/// The help of `--limit`: every name [`parse_limit`] takes.
fn limit_help() -> String {
    let names: Vec<&str> = subdiv::io::LIMIT_NAMES.iter().map(|(n, _)| *n).collect();
    format!(
        "Set a reading limit, NAME=VALUE (repeatable; sizes take K, M, G): {}. The defaults scale with the free memory",
        names.join(", ")
    )
}

impl LimitArgs {
    /// The default limits with these set.
    pub(crate) fn limits(&self) -> Result<Limits> {
        let mut limits = Limits::default();
        for (name, value) in &self.limit {
            limits.set(name, *value)?;
        }
        Ok(limits)
    }
}

impl InputArgs {
    /// The read options for these arguments (attributes kept; textures
    /// decoded when `textures`, for drawing).
    pub(crate) fn options(&self, textures: bool) -> Result<ReadOptions> {
        let topology = if self.repair { Topology::Repair } else { Topology::Refuse };
        Ok(ReadOptions { limits: self.limits.limits()?, topology, attributes: true, textures, time: self.time })
    }

    /// Reads the mesh `input` names (a file or `bundled:NAME`), repaired
    /// when asked (the report on stderr unless `-q`; warnings through the log).
    pub(crate) fn read(&self, input: &Path, textures: bool) -> Result<Loaded> {
        let loaded = bundled::read(input, &self.options(textures)?)?;
        if let Some(report) = &loaded.notes.repair
            && super::logging::warnings_shown()
        {
            eprint!("{report}");
        }
        Ok(loaded)
    }
}

/// `NAME=VALUE` of `--limit`: a known limit and a count or size.
pub(crate) fn parse_limit(s: &str) -> std::result::Result<(String, u64), String> {
    let (name, value) = s.split_once('=').ok_or_else(|| format!("'{s}' is not NAME=VALUE"))?;
    let name = name.trim();
    if Limits::default().get(name).is_none() {
        let known: Vec<&str> = subdiv::io::LIMIT_NAMES.iter().map(|(n, _)| *n).collect();
        return Err(format!("unknown limit '{name}' (known: {})", known.join(", ")));
    }
    Ok((name.to_string(), parse_bytes(value)?))
}

/// The subdivision: scheme, its options, sharp features and the number of levels.
#[derive(clap::Args, Clone, Default)]
pub struct SubdivArgs {
    #[command(flatten)]
    pub scheme: SchemeArgs,
    /// Subdivision levels (default: 1 for subdivide and batch, 0 for render and view, 5 for animate).
    #[arg(long, short = 'n', visible_alias = "level", short_alias = 'l', value_name = "N")]
    pub levels: Option<u32>,
}

impl SubdivArgs {
    /// The levels asked for, or this command's `default`.
    pub(crate) fn levels_or(&self, default: u32) -> u32 {
        self.levels.unwrap_or(default)
    }
}

/// A scheme and its options.
#[derive(clap::Args, Clone, Default)]
pub struct SchemeArgs {
    // the help lists Scheme::TRIANGLE and Scheme::POLYGON by their names
    #[arg(long = "scheme", short = 's', value_name = "SCHEME", help = scheme_help())]
    pub scheme_flag: Option<Scheme>,
    /// Use Warren's beta for Loop instead of Loop's.
    #[arg(long)]
    pub warren: bool,
    /// Modified-butterfly tension w (0 = Zorin's default).
    #[arg(long, default_value_t = 0.0)]
    pub tension: f32,
    /// Refuse levels predicted to need more than this (e.g. 2G, 500M; default: 80% of available memory).
    #[arg(long, value_parser = parse_bytes)]
    pub max_memory: Option<u64>,
    /// Texture coordinates through Catmull-Clark and Loop (OpenSubdiv's face-varying interpolation): none (the scheme on the UV charts, nothing kept), corners-only (their one-face corners kept), corners-plus1 (and junctions of three or more charts), corners-plus2 (and darts and the other side of a chart corner), boundaries (linear along the charts' borders) or all (bilinear in every face); smooth and linear name corners-only and all.
    /// Default: the file's `t facevaryinginterpolateboundary` tag, else corners-only.
    #[arg(long = "fvar", visible_alias = "uv", value_name = "MODE")]
    pub uv: Option<subdiv::mesh::UvInterpolation>,
    /// Triangles in Catmull-Clark meshes: catmark (Catmull-Clark's own rules) or smooth (OpenSubdiv's smooth triangle rule, TRI_SUB_SMOOTH). Default: the file's `t smoothtriangles` tag, else catmark.
    #[arg(long, value_name = "RULE")]
    pub triangles: Option<subdiv::mesh::TriangleSubdivision>,
    #[command(flatten)]
    pub features: FeatureArgs,
    /// The scheme the file states, when it chose `scheme` (see `over`).
    #[arg(skip)]
    pub file_scheme: Option<FileScheme>,
}

/// The help of `--scheme`: every scheme by its command-line name.
fn scheme_help() -> String {
    let names = |schemes: &[Scheme]| schemes.iter().map(|s| s.name()).collect::<Vec<_>>().join(", ");
    format!(
        "Scheme: {} (triangles); {} (polygons; catmark is catmull-clark)",
        names(&Scheme::TRIANGLE),
        names(&Scheme::POLYGON)
    )
}

impl SchemeArgs {
    /// These flags as the library takes them, over a file's options.
    pub(crate) fn flags(&self) -> subdiv::Flags {
        subdiv::Flags {
            scheme: self.scheme_flag,
            loop_beta: if self.warren { LoopBeta::Warren } else { LoopBeta::Loop },
            tension: self.tension,
            max_memory: self.max_memory,
            uv: self.uv,
            triangles: self.triangles,
            boundary: self.features.sharp.boundary,
            creasing: self.features.creasing,
            crease_angle: self.features.sharp.crease_angle,
            file_scheme: self.file_scheme,
        }
    }

    /// The arguments that stand for the library's `flags`.
    fn of_flags(f: subdiv::Flags) -> SchemeArgs {
        SchemeArgs {
            scheme_flag: f.scheme,
            warren: f.loop_beta == LoopBeta::Warren,
            tension: f.tension,
            max_memory: f.max_memory,
            uv: f.uv,
            triangles: f.triangles,
            features: FeatureArgs {
                sharp: SharpArgs { crease_angle: f.crease_angle, boundary: f.boundary },
                creasing: f.creasing,
            },
            file_scheme: f.file_scheme,
        }
    }

    /// The scheme: `--scheme`, else the file's (after [`SchemeArgs::over`]),
    /// else Loop ([`subdiv::Flags::scheme`]).
    pub(crate) fn scheme(&self) -> Scheme {
        self.flags().scheme()
    }

    /// The library's options for these arguments.
    pub(crate) fn options(&self) -> Options {
        self.flags().options()
    }

    /// The shape options these flags state (`None` where a flag is absent).
    pub(crate) fn shape(&self) -> ShapeOptions {
        self.flags().shape()
    }

    /// These arguments with the options a file states where no flag does
    /// (flags override the file's tags; [`subdiv::Flags::over`]).
    /// A file's scheme (USD's `subdivisionScheme`) applies where `--scheme`
    /// is left at its default (`none` as bilinear: the polygons are the surface).
    pub(crate) fn over(&self, file: ShapeOptions) -> SchemeArgs {
        SchemeArgs::of_flags(self.flags().over(file))
    }
}

/// Sharp features: the model's own tags (OBJ `t crease` / `t corner`, .ct
/// `creases` / `corners`) plus these options (OpenSubdiv's names), and how
/// semi-sharp ones decay as the levels refine.
#[derive(clap::Args, Clone, Default)]
pub struct FeatureArgs {
    #[command(flatten)]
    pub sharp: SharpArgs,
    /// How semi-sharp creases decay: uniform (s - 1 per level) or chaikin. Default: the file's `t creasemethod` tag, else uniform.
    #[arg(long, value_name = "METHOD")]
    pub creasing: Option<subdiv::mesh::Creasing>,
}

impl FeatureArgs {
    /// `mesh` with the edges sharper than `--crease-angle` tagged.
    pub(crate) fn apply(&self, mesh: Mesh) -> Mesh {
        self.sharp.apply(mesh)
    }

    /// These arguments with the boundary and creasing a file states where
    /// no flag does.
    pub(crate) fn over(&self, file: ShapeOptions) -> FeatureArgs {
        SchemeArgs { features: self.clone(), ..SchemeArgs::default() }.over(file).features
    }
}

/// Which features of the control mesh are sharp: what `info` counts (it
/// refines nothing, so the decay of [`FeatureArgs::creasing`] has no meaning
/// there and `info` does not take it).
#[derive(clap::Args, Clone, Default)]
pub struct SharpArgs {
    /// Make every edge whose two faces' normals differ by more than DEG degrees (0 to 180) infinitely sharp.
    #[arg(long, value_name = "DEG", value_parser = parse_angle, allow_hyphen_values = true)]
    pub crease_angle: Option<f32>,
    /// Boundary interpolation: edge (boundary edges sharp), edge-and-corner (also one-face corners) or none (the faces at the border left out, their vertices still shaping the rest). Default: the file's `t interpolateboundary` tag, else edge.
    #[arg(long, value_name = "MODE")]
    pub boundary: Option<subdiv::mesh::BoundaryInterpolation>,
}

impl SharpArgs {
    /// `mesh` with the edges sharper than `--crease-angle` tagged.
    pub(crate) fn apply(&self, mesh: Mesh) -> Mesh {
        subdiv::Flags { crease_angle: self.crease_angle, ..subdiv::Flags::default() }.apply(mesh)
    }
}

/// A dihedral angle in degrees, 0..=180 (NaN and infinities refused).
pub(crate) fn parse_angle(s: &str) -> std::result::Result<f32, String> {
    let bad = || format!("'{s}' is not an angle from 0 to 180 degrees");
    let deg: f32 = s.trim().parse().map_err(|_| bad())?;
    if (0.0..=180.0).contains(&deg) { Ok(deg) } else { Err(bad()) }
}

/// How a drawing command colours the surface.
#[derive(clap::Args, Clone)]
pub struct ColorArgs {
    // the help lists COLORINGS and the curvatures by CurvatureKind::name
    #[arg(long, default_value = "auto", help = color_help())]
    pub color: String,
    /// Draw isolines (contour lines) over a curvature colouring: the zero
    /// level (wider, darker) and N levels on each side, evenly spaced
    /// between 0 and the ends of the colour range (every 1/(N+1) of it).
    /// 1..=50.
    // a string checked by `isolines` (like --color), so a bad count is one
    // line of error like every other refusal of the command
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub isolines: Option<String>,
    /// With a curvature colouring: the colours span [-R, R] (beyond, they
    /// saturate). Default: R is the 90th percentile of |curvature| by area,
    /// so 90% of the surface lies inside the range. The colour bar says
    /// which.
    // a string checked by `range`, as --isolines
    #[arg(long, value_name = "R", allow_hyphen_values = true)]
    pub range: Option<String>,
}

/// The colourings `--color` takes besides the curvatures, each with what it
/// draws (the viewer's `Coloring` parses them; `auto` is decided by the
/// model). A unit test below checks that these and [`CURVATURES`] parse and
/// name every `Coloring`.
const COLORINGS: [(&str, &str); 7] = [
    ("auto", "the OBJ's MTL materials when it has usemtl groups, else none"),
    ("none", ""),
    ("shells", "the level that made each vertex"),
    ("displacement", "from the control mesh"),
    ("file", "the file's vertex colours"),
    ("checker", "a checker through the file's texture coordinates"),
    ("material", "Kd and map_Kd of the MTL per group, through the refined UVs"),
];

/// The curvature colourings, named by [`CurvatureKind::name`].
const CURVATURES: [CurvatureKind; 4] =
    [CurvatureKind::Mean, CurvatureKind::Gaussian, CurvatureKind::Min, CurvatureKind::Max];

/// The help of `--color`: every colouring it takes.
fn color_help() -> String {
    let plain: Vec<String> = COLORINGS
        .iter()
        .map(|(name, what)| if what.is_empty() { name.to_string() } else { format!("{name} ({what})") })
        .collect();
    let curvatures: Vec<&str> = CURVATURES.iter().map(|k| k.name()).collect();
    format!(
        "Colouring: {}, or a curvature of the exact limit at each drawn vertex (with -s {}): {}",
        plain.join(", "),
        subdiv::eval::color::SCHEMES.map(|s| s.name()).join(" or -s "),
        curvatures.join(", ")
    )
}

impl ColorArgs {
    /// The colouring asked for: `None` for `auto` (decided by the model, see
    /// `Coloring::initial`), every other name its colouring (`none` the
    /// plain front colour, even on a model with materials).
    #[cfg(feature = "viewer")]
    pub(crate) fn asked(&self) -> Result<Option<subdiv::render::Coloring>> {
        match self.color.as_str() {
            "auto" => Ok(None),
            c => c.parse().map(Some).map_err(subdiv::Error::Usage),
        }
    }

    /// The isolines asked for, refused unless `coloring` is a curvature
    /// (the lines are contours of its value).
    #[cfg(feature = "viewer")]
    pub(crate) fn isolines(&self, coloring: Option<subdiv::render::Coloring>) -> Result<Option<u8>> {
        use subdiv::render::Coloring;
        let n = self.isolines.as_deref().map(parse_isolines).transpose().map_err(subdiv::Error::Usage)?;
        match (n, coloring) {
            (Some(_), Some(Coloring::Curvature(_))) | (None, _) => Ok(n),
            (Some(_), _) => Err(subdiv::Error::Usage(
                "--isolines draws contours of a curvature: add --color mean-curvature (or gaussian-, min-, max-curvature)"
                    .into(),
            )),
        }
    }

    /// The half-width of the curvature colours asked for (`None`: the
    /// default percentile), refused unless `coloring` is a curvature.
    #[cfg(feature = "viewer")]
    pub(crate) fn range(
        &self,
        coloring: Option<subdiv::render::Coloring>,
    ) -> Result<Option<subdiv::eval::color::HalfWidth>> {
        use subdiv::render::Coloring;
        let r = self.range.as_deref().map(parse_range).transpose().map_err(subdiv::Error::Usage)?;
        match (r, coloring) {
            (Some(_), Some(Coloring::Curvature(_))) | (None, _) => Ok(r),
            (Some(_), _) => Err(subdiv::Error::Usage(
                "--range sets the span of a curvature's colours: add --color mean-curvature (or gaussian-, min-, max-curvature)"
                    .into(),
            )),
        }
    }
}

/// A half-width of the curvature colours (`--range`): a number above 0.
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
pub(crate) fn parse_range(s: &str) -> std::result::Result<subdiv::eval::color::HalfWidth, String> {
    s.parse().map_err(|_| format!("--range '{s}': expected the half-width of the colour range, a number above 0"))
}

/// An isoline count, 1..=50 (`--isolines`).
#[cfg_attr(not(feature = "viewer"), allow(dead_code))]
pub(crate) fn parse_isolines(s: &str) -> std::result::Result<u8, String> {
    let most = subdiv::eval::color::MAX_ISOLINES;
    let bad = || format!("--isolines '{s}': expected a count of levels per side from 1 to {most}");
    let n: u8 = s.trim().parse().map_err(|_| bad())?;
    if (1..=most).contains(&n) { Ok(n) } else { Err(bad()) }
}

impl Default for ColorArgs {
    fn default() -> Self {
        ColorArgs { color: "auto".into(), isolines: None, range: None }
    }
}

/// `WxH`, each side 1..=16384.
pub(crate) fn parse_size(s: &str) -> std::result::Result<(u32, u32), String> {
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| format!("'{s}' is not WxH"))?;
    let w: u32 = w.parse().map_err(|_| format!("bad width in '{s}'"))?;
    let h: u32 = h.parse().map_err(|_| format!("bad height in '{s}'"))?;
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err(format!("size {w}x{h} out of range (1..16384)"));
    }
    Ok((w, h))
}

/// A byte count with an optional K, M, G or T suffix.
pub(crate) fn parse_bytes(s: &str) -> std::result::Result<u64, String> {
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

#[cfg(all(test, feature = "viewer"))]
mod tests {
    use super::{COLORINGS, CURVATURES, ColorArgs};
    use subdiv::render::Coloring;

    #[test]
    fn the_help_of_color_names_every_coloring() {
        let mut named = Vec::new();
        for name in COLORINGS.iter().map(|(n, _)| *n).filter(|&n| n != "auto").chain(CURVATURES.map(|k| k.name())) {
            let c: Coloring = name.parse().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert!(!named.contains(&c), "{name}: {c:?} named twice");
            named.push(c);
        }
        for c in Coloring::ALL {
            assert!(named.contains(&c), "--color's help leaves out {c:?} ({})", c.name());
        }
    }

    #[test]
    fn color_none_is_asked_for_and_auto_is_not() {
        let asked = |c: &str| ColorArgs { color: c.into(), ..ColorArgs::default() }.asked();
        assert_eq!(asked("none").unwrap(), Some(Coloring::None));
        assert_eq!(asked("auto").unwrap(), None);
        assert_eq!(asked("material").unwrap(), Some(Coloring::Material));
        assert!(asked("plaid").unwrap_err().to_string().contains("unknown colouring 'plaid'"));
        // what view and render open with, on a model with MTL materials
        assert_eq!(Coloring::initial(asked("none").unwrap(), true), Coloring::None);
        assert_eq!(Coloring::initial(asked("auto").unwrap(), true), Coloring::Material);
    }
}

#[cfg(test)]
mod angle_tests {
    #[test]
    fn crease_angles_outside_0_to_180_and_nan_are_refused() {
        for ok in ["0", "40", "180", " 90.5 "] {
            assert!(super::parse_angle(ok).is_ok(), "{ok}");
        }
        for bad in ["-1", "180.5", "400", "nan", "NaN", "inf", "-inf", "forty", ""] {
            let e = super::parse_angle(bad).unwrap_err();
            assert!(e.contains("not an angle from 0 to 180"), "{bad}: {e}");
        }
    }
}

/// The precision of a computation: `--precision f32|f64`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Precision {
    /// Single precision.
    #[default]
    F32,
    /// Double precision.
    F64,
}

/// A model read for its exact limit surface (`eval`, `tessellate`): the
/// mesh with the sharp features the flags and the file state, the scheme
/// and options over the file's, and the control points in `precision`
/// (f64: the file's own digits where it has them).
pub(crate) struct LimitInput {
    pub mesh: Mesh,
    pub scheme: SchemeArgs,
    pub control: Vec<glam::DVec3>,
    /// The file's texture coordinates (one per corner), if it has them.
    pub uv: Option<Vec<glam::Vec2>>,
    /// The file's colours (one per vertex), if it has them.
    pub colors: Option<Vec<glam::Vec3>>,
}

impl LimitInput {
    /// Reads `input` as `from` and `scheme` say.
    pub(crate) fn read(
        input: &Path,
        from: &InputArgs,
        scheme: &SchemeArgs,
        precision: Precision,
    ) -> Result<LimitInput> {
        let loaded = from.read(input, false)?;
        let scheme = scheme.over(loaded.attributes.options);
        let mesh = scheme.features.apply(loaded.mesh);
        let control = match (precision, loaded.precise) {
            (Precision::F64, Some(p)) => p,
            _ => mesh.positions.iter().map(|p| p.as_dvec3()).collect(),
        };
        let (uv, colors) = (loaded.attributes.uv, loaded.attributes.colors);
        Ok(LimitInput { mesh, scheme, control, uv, colors })
    }
}
