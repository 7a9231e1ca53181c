//! The models and animation paths that ship inside the binary (`models/` and
//! `paths/` of the repository, compiled in with `include_bytes!`), shared by
//! the command line and the viewer. An installed `subdiv` needs no checkout:
//! it lists and opens these from memory.
//!
//! On the command line a bundled model is named `bundled:<file name>`
//! (`subdiv info bundled:torus.obj`); `subdiv models` lists them.

use crate::anim::paths::Paths;
use crate::io::{Loaded, ReadOptions};
use crate::{Mesh, Result, io};
use std::path::{Path, PathBuf};

/// One bundled file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Model {
    /// File name, with the extension that says its format (`torus.obj`).
    pub file_name: &'static str,
    /// What it is, for a menu.
    pub what: &'static str,
    /// The file's bytes.
    pub bytes: &'static [u8],
}

impl Model {
    /// Whether this is a `.bzc` curve rather than a mesh.
    pub fn is_curve(&self) -> bool {
        self.file_name.ends_with(".bzc")
    }
    /// The name that opens it on the command line (`bundled:torus.obj`).
    pub fn cli_name(&self) -> String {
        format!("{PREFIX}{}", self.file_name)
    }
    /// Reads it as a mesh (see [`io::read`]), naming it in errors as
    /// [`Model::cli_name`] does.
    ///
    /// # Errors
    /// As [`io::read`] (`teapot.bez` needs [`io::Topology::Repair`]).
    pub(crate) fn read(&self, opts: &ReadOptions) -> Result<Loaded> {
        let name = self.cli_name();
        io::read(io::Source::Bytes { bytes: self.bytes, name: &name, folder: None }, opts)
    }
}

/// Command-line prefix of a bundled model.
pub const PREFIX: &str = "bundled:";

macro_rules! model {
    ($name:literal, $what:literal) => {
        Model { file_name: $name, what: $what, bytes: include_bytes!(concat!("../models/", $name)) }
    };
}

/// Every bundled model, in menu order.
pub const MODELS: &[Model] = &[
    model!("tetrahedron.obj", "tetrahedron (the animation's model)"),
    model!("tetrahedron.ct", "tetrahedron as a corner table"),
    model!("cube.obj", "cube, 12 triangles"),
    model!("cube.ct", "cube as a corner table"),
    model!("cube_uv.obj", "cube with texture charts and vertex colours"),
    model!("lprism.obj", "L-shaped prism"),
    model!("lprism.ct", "L-shaped prism as a corner table"),
    model!("torus.obj", "torus, 1024 triangles"),
    model!("torus.ct", "torus as a corner table"),
    model!("critter.obj", "box-modelled animal, 172 quads (try Catmull-Clark)"),
    model!("teapot.bez", "Newell's teapot, 32 Bezier patches (needs repair)"),
    model!("curve.bzc", "a degree-4 Bezier curve"),
];

/// Bundled `.paths` files by model stem.
const PATHS: &[(&str, &str)] = &[("tetrahedron", include_str!("../paths/tetrahedron.paths"))];

/// The bundled model called `file_name` (`torus.obj`).
pub(crate) fn model(file_name: &str) -> Option<&'static Model> {
    MODELS.iter().find(|m| m.file_name == file_name)
}

/// The bundled model a command-line argument names (`bundled:torus.obj`).
pub(crate) fn from_arg(arg: &Path) -> Option<&'static Model> {
    arg.to_str().and_then(|s| s.strip_prefix(PREFIX)).and_then(model)
}

/// The bytes a model argument names: a bundled model (`bundled:NAME`, from
/// memory) or a file (through [`io::read_file`], within `limits`).
///
/// # Errors
/// As [`io::read_file`]; an unknown `bundled:` name.
pub(crate) fn bytes(arg: &Path, limits: &io::Limits) -> Result<std::borrow::Cow<'static, [u8]>> {
    if let Some(m) = from_arg(arg) {
        return Ok(std::borrow::Cow::Borrowed(m.bytes));
    }
    check_prefix(arg)?;
    io::read_file(arg, limits).map(std::borrow::Cow::Owned)
}

/// An unknown `bundled:` name is an error listing the known ones.
fn check_prefix(arg: &Path) -> Result<()> {
    match arg.to_str().and_then(|s| s.strip_prefix(PREFIX)) {
        Some(name) => {
            let known: Vec<&str> = MODELS.iter().map(|m| m.file_name).collect();
            Err(crate::Error::NoSuchBundled { name: name.to_string(), known: known.join(", ") })
        }
        None => Ok(()),
    }
}

/// The mesh in the file `path`, or the bundled model it names
/// (`bundled:torus.obj`, as the command line takes it), with the default
/// [`ReadOptions`]: a shorthand for [`read`].
///
/// # Errors
/// As [`io::read`]; an unknown `bundled:` name.
pub fn load(path: &Path) -> crate::Result<crate::Mesh> {
    read(path, &ReadOptions::default()).map(|l| l.mesh)
}

/// Reads the mesh a model argument names (a bundled model or a file; see
/// [`io::read`]), telling the log (at info) what it read.
///
/// # Errors
/// As [`io::read`]; an unknown `bundled:` name.
pub fn read(arg: &Path, opts: &ReadOptions) -> Result<Loaded> {
    let loaded = match from_arg(arg) {
        Some(m) => m.read(opts)?,
        None => {
            check_prefix(arg)?;
            io::read(io::Source::File(arg), opts)?
        }
    };
    let (m, a) = (&loaded.mesh, &loaded.attributes);
    log::info!(
        "read {} ({}): {} vertices, {} triangles{}{}{}",
        arg.display(),
        loaded.format.name,
        m.positions.len(),
        m.ct.num_triangles(),
        if loaded.notes.fanned > 0 { format!(" ({} polygons fanned)", loaded.notes.fanned) } else { String::new() },
        if a.uv.is_some() { ", texture coordinates" } else { "" },
        if a.colors.is_some() { ", colours" } else { "" }
    );
    Ok(loaded)
}

/// Loads the `.bzc` curve a model argument names (a file within `limits`).
///
/// # Errors
/// As `bytes` and [`io::bezier::parse_bzc`].
pub fn load_curve(arg: &Path, limits: &io::Limits) -> Result<Vec<glam::Vec2>> {
    let file = arg.display().to_string();
    io::bezier::parse_bzc(io::text(&bytes(arg, limits)?, &file)?, &file)
}

/// The text of the bundled `.paths` for models called `stem`.
pub(crate) fn paths_text(stem: &str) -> Option<&'static str> {
    PATHS.iter().find(|(s, _)| *s == stem).map(|&(_, t)| t)
}

fn stem(file_name: &str) -> &str {
    Path::new(file_name).file_stem().and_then(|s| s.to_str()).unwrap_or(file_name)
}

/// Where a model's animation paths come from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PathsSource {
    /// A `.paths` file beside the model.
    File(PathBuf),
    /// A bundled `.paths`, by model stem.
    Bundled(&'static str),
}

impl PathsSource {
    /// Reads (a file within `limits`) and parses the paths.
    ///
    /// # Errors
    /// Read and parse errors naming the file.
    pub fn load(&self, limits: &io::Limits) -> Result<Paths> {
        match self {
            PathsSource::File(p) => Paths::load(p, limits),
            PathsSource::Bundled(stem) => {
                Paths::parse(paths_text(stem).unwrap_or_default(), &format!("{PREFIX}{stem}.paths"))
            }
        }
    }
    /// How to show it in a panel or message.
    pub fn describe(&self) -> String {
        match self {
            PathsSource::File(p) => p.display().to_string(),
            PathsSource::Bundled(stem) => format!("{PREFIX}{stem}.paths"),
        }
    }
}

/// The paths that go with the model at `model`: `<model>.paths` beside it,
/// else the bundled paths of a model with the same stem.
pub fn paths_for(model: &Path) -> Option<PathsSource> {
    if let Some(m) = from_arg(model) {
        let stem = stem(m.file_name);
        return PATHS.iter().find(|(s, _)| *s == stem).map(|&(s, _)| PathsSource::Bundled(s));
    }
    let beside = model.with_extension("paths");
    if beside.is_file() {
        return Some(PathsSource::File(beside));
    }
    let stem = model.file_stem()?.to_str()?;
    PATHS.iter().find(|(s, _)| *s == stem).map(|&(s, _)| PathsSource::Bundled(s))
}

/// The bundled tetrahedron and its paths: the viewer's first model and the
/// default of `subdiv animate`.
///
/// # Errors
/// None for the files as bundled (a unit test parses them); a parse error
/// would name `bundled:tetrahedron.obj`.
pub fn tetrahedron() -> Result<(Mesh, Paths)> {
    let model = model("tetrahedron.obj").ok_or_else(|| crate::Error::Internal("no bundled tetrahedron".into()))?;
    let mesh = model.read(&ReadOptions::default())?.mesh;
    let paths = PathsSource::Bundled("tetrahedron").load(&io::Limits::default())?;
    paths.check_model(&mesh, "bundled:tetrahedron.paths")?;
    Ok((mesh, paths))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_bundled_model_opens() {
        for m in MODELS {
            if m.is_curve() {
                let text = io::text(m.bytes, m.file_name).unwrap();
                assert!(io::bezier::parse_bzc(text, m.file_name).unwrap().len() >= 2, "{}", m.file_name);
            } else {
                let repair = ReadOptions { topology: io::Topology::Repair, ..Default::default() };
                let mesh = m.read(&repair).unwrap_or_else(|e| panic!("{}: {e}", m.file_name)).mesh;
                assert!(mesh.ct.num_triangles() > 0, "{}", m.file_name);
                if m.file_name != "teapot.bez" {
                    m.read(&ReadOptions::default()).unwrap_or_else(|e| panic!("{}: {e}", m.file_name));
                }
            }
        }
        let (tet, paths) = tetrahedron().unwrap();
        assert_eq!(paths.vertex_count(), tet.positions.len());
        assert_eq!(from_arg(Path::new("bundled:torus.obj")).map(|m| m.file_name), Some("torus.obj"));
        assert_eq!(from_arg(Path::new("torus.obj")), None);
        assert_eq!(from_arg(Path::new("bundled:nothing.obj")), None);
    }
}
