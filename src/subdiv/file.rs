//! One file refined into another: read (a file or `bundled:NAME`), the
//! caller's [`Flags`] over the options the file states, refined by
//! [`super::subdivide_model`] (a stage whose prims state different options
//! by [`super::subdivide_parts`]) and written by
//! [`crate::io::save_refined`], atomically. The one per-file path of
//! `subdiv subdivide`, of every file of `subdiv batch` and of Python's
//! `subdiv.subdivide_file`.

use super::{LoopBeta, Model, Options, Part, Refinement, Scheme, Stats};
use crate::clock::Instant;
use crate::io::{self, ReadOptions};
use crate::mesh::attributes::Attributes;
use crate::mesh::{
    BoundaryInterpolation, Creasing, FileScheme, Mesh, ShapeOptions, TriangleSubdivision, UvInterpolation,
};
use crate::{Error, Result};
use std::path::Path;

/// What a caller states over the options a file states (the command
/// line's flags): `None` takes the file's tag, else the default.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Flags {
    /// The scheme (over the file's: USD's `subdivisionScheme`).
    pub scheme: Option<Scheme>,
    /// Loop's beta (no file states one).
    pub loop_beta: LoopBeta,
    /// Modified-butterfly tension (0: Zorin's default).
    pub tension: f32,
    /// The memory budget of a refinement (`None`: the library's default).
    pub max_memory: Option<u64>,
    /// Face-varying interpolation of texture coordinates.
    pub uv: Option<UvInterpolation>,
    /// Catmull-Clark's rule on triangles.
    pub triangles: Option<TriangleSubdivision>,
    /// Boundary interpolation.
    pub boundary: Option<BoundaryInterpolation>,
    /// How semi-sharp creases decay.
    pub creasing: Option<Creasing>,
    /// Edges whose faces' normals differ by more than this many degrees
    /// made infinitely sharp.
    pub crease_angle: Option<f32>,
    /// The scheme the file states, where no [`Flags::scheme`] overrides it
    /// (set by [`Flags::over`]).
    pub file_scheme: Option<FileScheme>,
}

impl Flags {
    /// The scheme: [`Flags::scheme`], else the file's, else Loop (a file's
    /// `none` as bilinear: the polygons are the surface, see
    /// [`Flags::subdivides`]).
    pub fn scheme(&self) -> Scheme {
        let file = self.file_scheme.map(|f| Scheme::of_file(f).unwrap_or(Scheme::Bilinear));
        self.scheme.or(file).unwrap_or(Scheme::Loop)
    }

    /// Whether the surface is subdivided: not where the file says
    /// `subdivisionScheme none` (the cage is the surface) and no scheme
    /// is given over it.
    pub fn subdivides(&self) -> bool {
        self.scheme.is_some() || self.file_scheme != Some(FileScheme::None)
    }

    /// The library's options for these flags.
    pub fn options(&self) -> Options {
        Options {
            loop_beta: self.loop_beta,
            tension: self.tension,
            max_memory: self.max_memory,
            creasing: self.creasing.unwrap_or_default(),
            boundary: self.boundary.unwrap_or_default(),
            uv: self.uv.unwrap_or_default(),
            triangles: self.triangles.unwrap_or_default(),
        }
    }

    /// The shape options these flags state (`None` where a flag is absent;
    /// the scheme always, as a file states it).
    pub fn shape(&self) -> ShapeOptions {
        let scheme = self.scheme();
        let stated = match scheme {
            Scheme::CatmullClark => FileScheme::CatmullClark,
            Scheme::Bilinear => FileScheme::Bilinear,
            Scheme::Loop => FileScheme::Loop,
            // the refined triangles are the surface: USD has no other scheme
            _ => FileScheme::None,
        };
        ShapeOptions {
            boundary: self.boundary,
            fvar: self.uv,
            triangles: self.triangles,
            creasing: self.creasing,
            scheme: Some(self.file_scheme.filter(|_| scheme == Scheme::Bilinear).unwrap_or(stated)),
        }
    }

    /// These flags with the options the file states where no flag does
    /// (flags override the file's tags); the file's scheme counts where
    /// no [`Flags::scheme`] is given.
    pub fn over(&self, file: ShapeOptions) -> Flags {
        let o = file.overridden_by(ShapeOptions { scheme: None, ..self.shape() });
        Flags {
            file_scheme: file.scheme.filter(|_| self.scheme.is_none()),
            uv: o.fvar,
            triangles: o.triangles,
            boundary: o.boundary,
            creasing: o.creasing,
            ..*self
        }
    }

    /// `mesh` with the edges sharper than [`Flags::crease_angle`] tagged.
    pub fn apply(&self, mesh: Mesh) -> Mesh {
        let Some(deg) = self.crease_angle else { return mesh };
        let Mesh { ct, positions } = mesh;
        Mesh { ct: ct.with_angle_creases(&positions, deg), positions }
    }
}

/// How [`subdivide_file`] reads, refines and writes a file.
#[derive(Clone, Debug)]
pub struct FileJob {
    /// How the file is read (its attributes are kept where the output's
    /// format keeps them).
    pub read: ReadOptions,
    /// The flags over the file's options.
    pub flags: Flags,
    /// Levels (a file that says `subdivisionScheme none` gets none).
    pub levels: u32,
    /// Compute in f64 from the file's own digits (OBJ's text, PLY's
    /// doubles), written at full precision where the format holds it.
    pub f64: bool,
}

impl Default for FileJob {
    /// The default reading, no flags, one level, f32.
    fn default() -> FileJob {
        FileJob { read: ReadOptions::default(), flags: Flags::default(), levels: 1, f64: false }
    }
}

/// What a file's refinement is predicted to need
/// ([`crate::rules::ControlCounts::peak_bytes`]), told once the file is
/// read and before anything is refined.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Demand {
    /// Peak bytes with every level kept (the most any path takes; twice
    /// that in f64), the parts of a stage together.
    pub peak: u64,
    /// The largest part's peak bytes without the levels kept, as the
    /// library's check counts them: over the budget
    /// ([`Options::max_memory`]), the library refuses the part before it
    /// allocates, whatever its path.
    pub least: u64,
    /// Refinements the file takes (a USD stage of several schemes: one each).
    pub parts: usize,
    /// Triangles the finest level is predicted to have (a quad two).
    pub faces: u64,
}

impl Demand {
    /// The demand of `parts`, each mesh refined by its scheme and levels,
    /// in f64 where `f64` (f64 points take twice the bytes).
    fn of(parts: &[(&Mesh, Scheme, u32)], f64: bool) -> Demand {
        let scale = if f64 { 2 } else { 1 };
        let mut d = Demand { parts: parts.len(), ..Demand::default() };
        for &(mesh, scheme, levels) in parts {
            let counts = super::sizes::ControlCounts::of(&mesh.ct);
            d.peak = d.peak.saturating_add(counts.peak_bytes(scheme, levels, true).saturating_mul(scale));
            d.least = d.least.max(counts.peak_bytes(scheme, levels, false));
            d.faces = d.faces.saturating_add(counts.triangles_at(scheme, levels));
        }
        d
    }
}

/// What [`subdivide_file`] did.
#[derive(Clone, Debug, Default)]
pub struct FileSummary {
    /// The scheme refined by, as a line says it (`loop`; `none (...)`
    /// for a cage kept as it is; `loop and catmull-clark (by prim)`).
    pub scheme: String,
    /// The levels made.
    pub levels: u32,
    /// The control mesh's vertices.
    pub input_vertices: usize,
    /// The control mesh's faces as the file has them (its polygons).
    pub input_faces: usize,
    /// The vertices written.
    pub vertices: usize,
    /// The faces written (a refined level's holes left out).
    pub faces: usize,
    /// What refining took.
    pub stats: Stats,
    /// Milliseconds reading the file (and tagging its features).
    pub load_ms: f64,
    /// Milliseconds writing the output.
    pub save_ms: f64,
    /// The repair's report, where the reading repaired the mesh.
    pub repair: Option<String>,
    /// The attributes the file has that the output's format keeps not
    /// (`texture coordinates`, `colours`, `materials`): left out before
    /// anything is refined.
    pub dropped: Vec<&'static str>,
}

/// Subdivides the model `input` (a file or `bundled:NAME`) into `output`
/// (its format by extension, written atomically) as `job` says: reads it,
/// takes the options it states where `job`'s flags state none, calls
/// `admit` with what the refinement will need (it may wait for memory, or
/// refuse), then refines and writes it.
///
/// # Errors
/// Reading (naming the file), refining (a budget's refusal among them),
/// writing, `admit`'s; f64 for a stage whose prims state different options.
pub fn subdivide_file(
    input: &Path,
    output: &Path,
    job: &FileJob,
    admit: &mut dyn FnMut(&Demand) -> Result<()>,
) -> Result<FileSummary> {
    let t0 = Instant::now();
    let loaded = crate::bundled::read(input, &job.read)?;
    let repair = loaded.notes.repair.as_ref().map(|r| r.to_string());
    let (mesh, attrs, precise) = (loaded.mesh, loaded.attributes, loaded.precise);
    let groups = super::parts_by_options(&mesh, &attrs)?;
    if !groups.is_empty() {
        let s = subdivide_groups(input, output, job, (&mesh, groups), t0, admit)?;
        return Ok(FileSummary { repair, ..s });
    }
    let s = job.flags.over(attrs.options);
    // `subdivisionScheme none`: the cage is the surface at every level
    let levels = if s.subdivides() { job.levels } else { 0 };
    let (attrs, dropped) = kept_by_output(output, attrs);
    let attrs = attrs.with_options(written_options(&s, levels));
    let mesh = s.apply(mesh);
    let load_ms = t0.elapsed().as_secs_f64() * 1e3;
    admit(&Demand::of(&[(&mesh, s.scheme(), levels)], job.f64))?;
    let model = Model { precise: precise.as_deref(), ..Model::new(&mesh, &attrs) };
    let how = Refinement { scheme: s.scheme(), levels, opts: s.options(), f64: job.f64, dest: io::destination(output) };
    let fine = super::subdivide_model(&model, &how)?;
    let t1 = Instant::now();
    io::save_refined(output, &fine)?;
    let input_faces = super::sizes::ControlCounts::of(&mesh.ct).polygons() as usize;
    Ok(FileSummary {
        scheme: match s.subdivides() {
            true => s.scheme().to_string(),
            false => "none (subdivisionScheme none: the cage as it is)".into(),
        },
        levels,
        input_vertices: mesh.positions.len(),
        input_faces,
        vertices: fine.num_vertices(),
        faces: fine.num_faces(),
        stats: fine.stats,
        load_ms,
        save_ms: t1.elapsed().as_secs_f64() * 1e3,
        repair,
        dropped,
    })
}

/// The options a level made with `s` states: the scheme and options it
/// was made with (a refined level's border faces are not holes any more:
/// boundary none is the control mesh's).
fn written_options(s: &Flags, levels: u32) -> ShapeOptions {
    let mut o = s.shape();
    if levels > 0 && o.boundary == Some(BoundaryInterpolation::None) {
        o.boundary = None;
    }
    o
}

/// [`subdivide_file`] of a scene whose prims state different options (a
/// USD stage of a Loop prim and a Catmull-Clark one, or one that says
/// `subdivisionScheme none`): each set of prims refined by its own
/// options under the flags, joined into one output whose faces keep their
/// prims (USD prims, OBJ objects, glTF meshes).
fn subdivide_groups(
    input: &Path,
    output: &Path,
    job: &FileJob,
    (cage, parts): (&Mesh, Vec<(Mesh, Attributes)>),
    t0: Instant,
    admit: &mut dyn FnMut(&Demand) -> Result<()>,
) -> Result<FileSummary> {
    if job.f64 {
        return Err(Error::Usage(format!(
            "{}: its prims state different schemes or options, which --precision f64 does not refine apart: give one --scheme",
            input.display()
        )));
    }
    let mut groups = Vec::with_capacity(parts.len());
    let mut dropped = Vec::new();
    for (mesh, attrs) in parts {
        let s = job.flags.over(attrs.options);
        let levels = if s.subdivides() { job.levels } else { 0 };
        let (attrs, lost) = kept_by_output(output, attrs);
        for what in lost {
            if !dropped.contains(&what) {
                dropped.push(what);
            }
        }
        groups.push((s.apply(mesh), attrs.with_options(written_options(&s, levels)), s, levels));
    }
    let load_ms = t0.elapsed().as_secs_f64() * 1e3;
    let demand: Vec<_> = groups.iter().map(|(mesh, _, s, levels)| (mesh, s.scheme(), *levels)).collect();
    admit(&Demand::of(&demand, false))?;
    let parts: Vec<Part> = groups
        .iter()
        .map(|(mesh, attrs, s, levels)| Part {
            mesh,
            attrs,
            scheme: s.subdivides().then(|| s.scheme()),
            levels: *levels,
            opts: s.options(),
        })
        .collect();
    let (fine, attrs, stats) = super::subdivide_parts(&parts, io::keeps(output).holes)?;
    let t1 = Instant::now();
    io::save_with(output, &fine, &attrs)?;
    let schemes: Vec<String> =
        groups.iter().map(|(_, _, s, _)| if s.subdivides() { s.scheme().to_string() } else { "none".into() }).collect();
    Ok(FileSummary {
        scheme: format!("{} (by prim)", schemes.join(" and ")),
        levels: job.levels,
        input_vertices: cage.positions.len(),
        input_faces: super::sizes::ControlCounts::of(&cage.ct).polygons() as usize,
        vertices: fine.positions.len(),
        faces: fine.pt.num_faces(),
        stats,
        load_ms,
        save_ms: t1.elapsed().as_secs_f64() * 1e3,
        repair: None,
        dropped,
    })
}

/// The attributes `output`'s format keeps, and the names of those dropped
/// (before any is refined).
fn kept_by_output(output: &Path, attrs: Attributes) -> (Attributes, Vec<&'static str>) {
    let keeps = io::keeps(output);
    let dropped: Vec<&'static str> = [
        (attrs.uv.is_some() && !keeps.uv, "texture coordinates"),
        (attrs.colors.is_some() && !keeps.colors, "colours"),
        (attrs.materials.is_some() && !keeps.materials, "materials"),
    ]
    .into_iter()
    .filter_map(|(dropped, what)| dropped.then_some(what))
    .collect();
    let kept = Attributes {
        uv: attrs.uv.filter(|_| keeps.uv),
        colors: attrs.colors.filter(|_| keeps.colors),
        materials: attrs.materials.filter(|_| keeps.materials),
        options: attrs.options,
    };
    (kept, dropped)
}
