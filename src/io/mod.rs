//! Reading and writing meshes.
//!
//! **Reading** is one pipeline, [`read`]: the bytes of a file (or of memory)
//! go to the reader its format's row of [`FORMATS`] names (by extension, by
//! content where the extension says nothing), which produces one
//! [`RawMesh`] (polygons kept as polygons, optional per-corner texture
//! coordinates, per-vertex colours, per-face materials, sharpness tags);
//! the [`ReadOptions`] then say what becomes of it (validated, repaired or
//! analysed; polygons fanned into triangles for the triangle schemes; which
//! attributes come along) and [`Loaded`] holds the mesh, its attributes and
//! what was found on the way. Everything a file can make us read or
//! allocate is counted against one [`Limits`], and every file a file names
//! goes through one `resolve::Resolver`. No reader panics, hangs or
//! allocates more than the budget allows (`tests/io.rs` fuzzes them all).
//!
//! A format is one module here and one row of [`FORMATS`]: its
//! extensions, a test of its content, its reader and its writer.
//!
//! **Writing**: [`save`] by extension; every writer goes through
//! `atomic_write`, so a failure never leaves a truncated file behind.

pub mod bezier;
pub(crate) mod ct;
pub(crate) mod dae;
pub(crate) mod gltf;
pub(crate) mod limits;
mod mtl;
pub(crate) mod obj;
pub(crate) mod off;
pub(crate) mod ply;
mod precise;
pub(crate) mod raw;
pub(crate) mod resolve;
pub(crate) mod stl;
mod text;
pub(crate) mod texture;
pub(crate) mod usd;
mod write;

// What the library's users reach; the format modules are the crate's own
// (Bézier patches, a format with an API of its own, stay a module).
pub use ct::write as write_ct;
pub use limits::{Budget, LIMIT_NAMES, Limits};
pub use obj::write_obj_with;
pub use save::{Save, SaveF64, save_f64, save_refined, save_with};
mod save;
pub use raw::{BuildNotes, RawMesh, Topology};
pub use texture::load_file as load_texture;
pub(crate) use write::atomic_write;
pub(crate) use write::{atomic_write_pieces, write_formatted};
pub use write::{write_points, write_rows};

use crate::mesh::Mesh;
use crate::mesh::attributes::Attributes;
use crate::mesh::poly::PolyMesh;
use crate::{Error, Result};
use resolve::Resolver;
use std::cell::RefCell;
use std::path::{Path, PathBuf};

/// One file format: a row of [`FORMATS`].
pub struct Format {
    /// Its name ("Wavefront OBJ").
    pub name: &'static str,
    /// File extensions, lower case, without the dot; the first is the usual one.
    pub extensions: &'static [&'static str],
    /// Whether bytes look like this format (asked in table order, for a file
    /// whose extension names no format).
    sniff: fn(&[u8]) -> bool,
    /// Its reader; `None` for a file that is not a mesh (a `.bzc` curve).
    reader: Option<fn(&Input) -> Result<RawMesh>>,
    /// Its writer, when the format is written.
    writer: Option<Writer>,
    /// The extensions the writer writes (glTF: `.glb` only).
    written_as: &'static [&'static str],
    /// Its writer of polygon meshes (`None`: polygons are written fanned
    /// into triangles).
    poly_writer: Option<PolyWriter>,
    /// Its writer of faces alone, without adjacency or sharpness (`None`:
    /// the format needs the corner table: `.ct`).
    faces_writer: Option<FacesWriter>,
    /// What its writer keeps of a mesh's attributes.
    pub keeps: Keeps,
}

/// A format's writer: the mesh with its attributes into a file.
type Writer = fn(&Path, &Mesh, &Attributes) -> Result<()>;

/// A format's writer of polygon meshes (attributes per polygon corner and face).
type PolyWriter = fn(&Path, &PolyMesh, &Attributes) -> Result<()>;

/// A format's writer of faces alone: positions, the vertex of every corner,
/// the corners per face (3 or 4; always 3 for a format without polygons)
/// and attributes.
type FacesWriter = fn(&Path, &[glam::Vec3], &[u32], usize, &Attributes) -> Result<()>;

/// What a format's writer keeps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Keeps {
    /// Texture coordinates.
    pub uv: bool,
    /// Vertex colours.
    pub colors: bool,
    /// Material groups.
    pub materials: bool,
    /// Sharp edges and vertices (creases and corners).
    pub creases: bool,
    /// The holes of a refined level (USD's `holeIndices`; elsewhere a
    /// refined level's holes are left out).
    pub holes: bool,
}

impl std::fmt::Debug for Format {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

impl PartialEq for Format {
    fn eq(&self, other: &Format) -> bool {
        self.name == other.name
    }
}

/// Every format, in the order content is sniffed (OBJ, which takes any
/// text, last).
pub static FORMATS: &[Format] = &[
    ply::FORMAT,
    gltf::FORMAT,
    dae::FORMAT,
    stl::FORMAT,
    off::FORMAT,
    usd::FORMAT,
    ct::FORMAT,
    bezier::BEZ_FORMAT,
    bezier::BZC_FORMAT,
    obj::FORMAT,
];

impl Format {
    /// The format of `file` by its extension; without a known one, by the
    /// first bytes of its content, else OBJ.
    pub(crate) fn of(file: &str, bytes: &[u8]) -> &'static Format {
        Format::by_extension(Path::new(file))
            .or_else(|| FORMATS.iter().find(|f| (f.sniff)(bytes)))
            .unwrap_or(&obj::FORMAT)
    }

    /// The format `path`'s extension names.
    pub(crate) fn by_extension(path: &Path) -> Option<&'static Format> {
        let e = ext(path);
        FORMATS.iter().find(|f| f.extensions.contains(&e.as_str()))
    }

    /// The format [`save`] writes for `path`'s extension.
    pub(crate) fn for_output(path: &Path) -> Option<&'static Format> {
        let e = ext(path);
        FORMATS.iter().find(|f| f.writer.is_some() && f.written_as.contains(&e.as_str()))
    }
}

/// The extensions that are read (lower case, no dot): what file dialogs
/// and drag and drop offer.
pub fn read_extensions() -> impl Iterator<Item = &'static str> {
    FORMATS.iter().flat_map(|f| f.extensions.iter().copied())
}

/// The extensions [`save`] writes.
pub fn write_extensions() -> impl Iterator<Item = &'static str> {
    FORMATS.iter().flat_map(|f| f.written_as.iter().copied())
}

/// What a reader is given: the bytes, the file's name for messages, the
/// budget, the resolver for the files it names, and where warnings go.
pub struct Input<'a> {
    /// The file's bytes.
    pub bytes: &'a [u8],
    /// The file as messages name it.
    pub file: &'a str,
    /// The read's budget.
    pub budget: &'a Budget,
    /// Finds the files the file names.
    pub refs: &'a Resolver<'a>,
    /// Warnings of the read.
    pub warnings: &'a Warnings,
    /// Whether material textures are decoded.
    pub textures: bool,
    /// The time code to read a stage's sampled points at (`None`: where
    /// the stage opens).
    pub time: Option<f64>,
}

impl Input<'_> {
    /// The bytes as text; invalid UTF-8 is a parse error at its line.
    ///
    /// # Errors
    /// [`Error::Parse`] at the line of the first invalid byte.
    pub(crate) fn text(&self) -> Result<&str> {
        text(self.bytes, self.file)
    }
}

/// The warnings of one read, each one printable line; after the first few
/// of a kind the rest are only counted ("... and 99,999 more").
#[derive(Debug, Default)]
pub struct Warnings {
    /// The file the summary lines name.
    file: String,
    chars: usize,
    lines: RefCell<Vec<String>>,
    /// Per kind: how many were given.
    kinds: RefCell<Vec<(&'static str, usize)>>,
}

/// Warnings of one kind shown before the rest are counted.
const SHOWN_PER_KIND: usize = 3;

impl Warnings {
    /// Warnings of at most `chars` characters a line, about `file`.
    pub(crate) fn new(file: &str, chars: u64) -> Warnings {
        let file = crate::error::clean(file, 80).into_owned();
        Warnings { file, chars: chars.clamp(40, 100_000) as usize, ..Default::default() }
    }

    /// Adds a warning of `kind` (a short phrase naming what is counted).
    pub(crate) fn warn(&self, kind: &'static str, msg: impl std::fmt::Display) {
        let mut kinds = self.kinds.borrow_mut();
        let n = match kinds.iter_mut().find(|(k, _)| *k == kind) {
            Some((_, n)) => {
                *n += 1;
                *n
            }
            None => {
                kinds.push((kind, 1));
                1
            }
        };
        if n <= SHOWN_PER_KIND {
            self.lines.borrow_mut().push(crate::error::clean(&msg.to_string(), self.chars).into_owned());
        }
    }

    /// The warnings, with a line counting those not shown of each kind.
    pub(crate) fn finish(self) -> Vec<String> {
        let mut lines = self.lines.take();
        for (kind, n) in self.kinds.take() {
            if n > SHOWN_PER_KIND {
                lines.push(format!("{}: ... and {} more {kind}", self.file, group_digits(n - SHOWN_PER_KIND)));
            }
        }
        lines
    }
}

/// `99999` as `99,999`.
fn group_digits(n: usize) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// Where a read takes its bytes from.
#[derive(Clone, Copy, Debug)]
pub enum Source<'a> {
    /// A file; the files it names are found beside it.
    File(&'a Path),
    /// Bytes in memory, called `name` in messages (its extension chooses
    /// the format); the files it names are found in `folder`, and without
    /// one they cannot be read.
    Bytes {
        /// The content.
        bytes: &'a [u8],
        /// Its name.
        name: &'a str,
        /// Where the files it names are.
        folder: Option<&'a Path>,
    },
}

/// What [`read`] does with what it reads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReadOptions {
    /// The budget.
    pub limits: Limits,
    /// What becomes of a mesh that is not a valid manifold.
    pub topology: Topology,
    /// Whether texture coordinates, colours and materials come along.
    pub attributes: bool,
    /// Whether material textures are decoded (for drawing).
    pub textures: bool,
    /// The time code a stage's sampled points are read at (`None`: its
    /// `startTimeCode`, else its first sample; unsampled values are read
    /// whatever the time).
    pub time: Option<f64>,
}

impl Default for ReadOptions {
    /// The default budget, refusing invalid topology, with attributes and
    /// without decoding textures.
    fn default() -> ReadOptions {
        ReadOptions {
            limits: Limits::default(),
            topology: Topology::Refuse,
            attributes: true,
            textures: false,
            time: None,
        }
    }
}

/// What [`read`] gives back.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The mesh (polygons fanned into triangles).
    pub mesh: Mesh,
    /// Its attributes (empty unless asked for, and after a repair).
    pub attributes: Attributes,
    /// The format it was read as.
    pub format: &'static Format,
    /// What the build found: faces and their sizes, polygons fanned,
    /// unreferenced vertices, the repair's report.
    pub notes: BuildNotes,
    /// Warnings, one line each, also sent to the log.
    pub warnings: Vec<String>,
    /// The positions in f64 where the file holds more than f32 (OBJ's text,
    /// PLY's `double` properties) and no repair renumbered them; `None`:
    /// `mesh.positions` are what the file holds.
    pub precise: Option<Vec<glam::DVec3>>,
}

/// Reads a mesh from `source` as `opts` say: the one way in. The stages
/// are [`read_raw`] (the bytes through the format's reader) and
/// [`RawMesh::build`] (validated, repaired or analysed, polygons fanned).
///
/// # Errors
/// I/O, parse and validation errors, each one line naming the file and the
/// line or element; a read over the budget names the limit;
/// [`Error::NotAMesh`] for a `.bzc` curve.
pub fn read(source: Source, opts: &ReadOptions) -> Result<Loaded> {
    let Raw { raw, format, file, warnings } = read_raw(source, opts)?;
    let precise = raw.kept_precise(opts.topology);
    let (mesh, attributes, notes) = raw.build(&file, opts.topology, opts.attributes)?;
    for w in &warnings {
        log::warn!("{w}");
    }
    Ok(Loaded { mesh, attributes, format, notes, warnings, precise })
}

/// What [`read_raw`] gives back: the polygons as read, before the build.
#[derive(Clone, Debug)]
pub struct Raw {
    /// The mesh as read.
    pub raw: RawMesh,
    /// The format it was read as.
    pub format: &'static Format,
    /// The file as messages name it.
    pub file: String,
    /// Warnings of the read (not yet logged).
    pub warnings: Vec<String>,
}

/// The first stage of [`read`]: the bytes of `source` (within the budget
/// of `opts`) through its format's reader, polygons kept as polygons.
///
/// # Errors
/// As [`read`], but for the mesh's validity.
pub fn read_raw(source: Source, opts: &ReadOptions) -> Result<Raw> {
    let budget = Budget::new(opts.limits);
    let (owned, bytes, file, folder): (Vec<u8>, &[u8], String, Option<PathBuf>) = match source {
        Source::File(path) => {
            let file = path.display().to_string();
            let folder = path.parent().map(|p| if p.as_os_str().is_empty() { Path::new(".") } else { p });
            (resolve::read_model(path, &budget, &file)?, &[], file, folder.map(Path::to_path_buf))
        }
        Source::Bytes { bytes, name, folder } => {
            budget.take_bytes(bytes.len() as u64, name, "file")?;
            (Vec::new(), bytes, name.to_string(), folder.map(Path::to_path_buf))
        }
    };
    let bytes = if owned.is_empty() { bytes } else { &owned };
    let format = Format::of(&file, bytes);
    let reader = format.reader.ok_or_else(|| Error::NotAMesh { file: file.clone(), what: format.name })?;
    let refs = Resolver::new(&file, folder, &budget);
    let warnings = Warnings::new(&file, opts.limits.message_chars);
    let input = Input {
        bytes,
        file: &file,
        budget: &budget,
        refs: &refs,
        warnings: &warnings,
        textures: opts.textures,
        time: opts.time,
    };
    let raw = reader(&input)?;
    Ok(Raw { raw, format, file, warnings: warnings.finish() })
}

/// The bytes of a file the user names besides a model (key paths, a
/// curve, evaluation points), read as models are: a regular file only,
/// opened without blocking, within `limits` (`file-bytes`).
///
/// # Errors
/// One line naming the file: not a regular file (a device, a pipe or a
/// folder), an I/O error, or over the budget.
pub(crate) fn read_file(path: &Path, limits: &Limits) -> Result<Vec<u8>> {
    let budget = Budget::new(*limits);
    resolve::read_model(path, &budget, &path.display().to_string())
}

/// `read_file` as text; invalid UTF-8 is a parse error at its line.
///
/// # Errors
/// As `read_file` and `text`.
pub fn read_text_file(path: &Path, limits: &Limits) -> Result<String> {
    let bytes = read_file(path, limits)?;
    text(&bytes, &path.display().to_string())?;
    // valid UTF-8, checked above
    Ok(String::from_utf8(bytes).unwrap_or_default())
}

/// The bytes of `file` as text; invalid UTF-8 is a parse error at its line.
///
/// # Errors
/// [`Error::Parse`] at the line of the first invalid byte.
pub(crate) fn text<'a>(bytes: &'a [u8], file: &str) -> Result<&'a str> {
    std::str::from_utf8(bytes).map_err(|e| Error::Parse {
        file: file.to_string(),
        line: bytes[..e.valid_up_to()].iter().filter(|&&b| b == b'\n').count() + 1,
        msg: "not text (invalid UTF-8)".into(),
    })
}

/// Saves a mesh by extension (see [`write_extensions`]).
///
/// # Errors
/// An unknown extension or an I/O error.
pub fn save(path: &Path, mesh: &impl Save) -> Result<()> {
    mesh.save_to(save::sealed::Token::NEW, path, &Attributes::default())
}

/// What [`save_with`] writes of a mesh's attributes to `path`'s format
/// (nothing for an unknown extension): a caller refines only those.
pub fn keeps(path: &Path) -> Keeps {
    Format::for_output(path).map_or_else(Keeps::default, |f| f.keeps)
}

/// [`save`] with the mesh's attributes where the format keeps them (see
/// [`Format::keeps`]); elsewhere they are dropped. A mesh that stands for
/// polygons (fanned faces, triangulated quads: its diagonals hidden) is
/// written as polygons by the formats that keep them (OBJ, PLY, OFF, `.ct`).
///
/// # Errors
/// As [`save`].
pub(crate) fn save_mesh(path: &Path, mesh: &Mesh, attrs: &Attributes) -> Result<()> {
    // a refined level's holes are not written; a control mesh keeps them as
    // tags where the format holds them (OBJ's `t hole`), else they go too
    let control = mesh.ct.generations().is_none_or(|g| g.level() == 0);
    // (USD's holeIndices keep them at every level)
    let keeps_holes = Format::for_output(path)
        .is_some_and(|f| (control && f.extensions.contains(&"obj")) || f.extensions.contains(&"usda"));
    if !mesh.ct.holes().is_empty() && !keeps_holes {
        return save_without_holes(path, mesh, attrs);
    }
    if let Some(write) = Format::for_output(path).and_then(|f| f.poly_writer)
        && PolyMesh::is_polygonal(mesh)
    {
        let (pm, pattrs) = PolyMesh::from_mesh_with_attributes(mesh, attrs);
        return write(path, &pm, &pattrs);
    }
    match Format::for_output(path).and_then(|f| f.writer) {
        Some(write) => write(path, mesh, attrs),
        None => Err(Error::UnknownFormat {
            path: path.display().to_string(),
            ext: ext(path),
            direction: "output",
            known: ".obj, .ply, .ct, .stl, .off, .glb, .usda, .usdc or .usdz",
        }),
    }
}

/// [`save_with`] of a mesh with holes, the holes left out (every vertex
/// kept, as OpenSubdiv writes them): its quads when it stands for quads,
/// else its triangles, through [`save_faces`] (`.ct`, which needs a corner
/// table, gets the whole table).
fn save_without_holes(path: &Path, mesh: &Mesh, attrs: &Attributes) -> Result<()> {
    if Format::for_output(path).is_some_and(|f| f.faces_writer.is_none()) {
        let whole = Mesh { ct: mesh.ct.clone().with_holes(Vec::new()), positions: mesh.positions.clone() };
        return save_with(path, &whole, attrs);
    }
    let keep_corners = |sides: usize, hole: &dyn Fn(u32) -> bool, n: usize| -> Vec<usize> {
        (0..n as u32).filter(|&f| !hole(f)).flat_map(|f| (0..sides).map(move |k| sides * f as usize + k)).collect()
    };
    let (pm, pattrs) = PolyMesh::from_mesh_with_attributes(mesh, attrs);
    let (positions, v, sides, kept_faces, corners, a) = if PolyMesh::is_polygonal(mesh) && pm.pt.is_quads() {
        let keep = keep_corners(4, &|f| pm.pt.is_hole(f), pm.pt.num_faces());
        (&pm.positions, pm.pt.v_table(), 4, pm.pt.num_faces(), keep, &pattrs)
    } else {
        let keep = keep_corners(3, &|t| mesh.ct.is_hole(t), mesh.ct.num_triangles());
        (&mesh.positions, mesh.ct.v_table(), 3, mesh.ct.num_triangles(), keep, attrs)
    };
    let kept: Vec<u32> = corners.iter().map(|&c| v[c]).collect();
    let attrs = Attributes {
        uv: a.uv.as_ref().filter(|u| u.len() == v.len()).map(|u| corners.iter().map(|&c| u[c]).collect()),
        colors: a.colors.clone(),
        options: a.options,
        materials: a.materials.as_ref().filter(|m| m.face.len() == kept_faces).map(|m| {
            let face = corners.chunks_exact(sides).map(|f| m.face[f[0] / sides]).collect();
            crate::mesh::attributes::MaterialGroups { face, ..m.clone() }
        }),
    };
    let faces = crate::mesh::Faces { positions: positions.clone(), corners: kept, sides };
    save_faces(path, &faces, &attrs)
}

/// Whether `save_faces` writes `path`'s format, and writes in it all that
/// [`save_with`] would write of a mesh (`sharp`: whether the mesh has sharp
/// features, which only the formats that keep creases write): then a
/// caller that writes a subdivision needs only its faces
/// ([`crate::subdiv::subdivide_faces`]).
pub fn writes_faces(path: &Path, sharp: bool) -> bool {
    Format::for_output(path).is_some_and(|f| f.faces_writer.is_some() && !(sharp && f.keeps.creases))
}

/// What a file of `path`'s format keeps of a refinement, for
/// [`crate::subdivide_model`]: faces alone where [`writes_faces`] says
/// they are written as the tables would be, its sharp features and its
/// refined holes as [`keeps`] says.
pub fn destination(path: &Path) -> crate::Destination {
    use crate::subdiv::FacesOnly;
    let faces = match Format::for_output(path).is_some_and(|f| f.faces_writer.is_some()) {
        true => FacesOnly::Written,
        false => FacesOnly::Never,
    };
    let keeps = keeps(path);
    crate::Destination { faces, creases: keeps.creases, holes: keeps.holes }
}

/// Saves faces alone (triangles or quads, with their attributes) by
/// extension: the bytes [`save_with`] writes for a mesh with these
/// triangles, or [`save_poly`] for a mesh with these quads, and no sharp
/// features. A format without polygons gets the quads fanned into
/// triangles, as [`save_poly`] does.
///
/// # Errors
/// Faces of other than 3 or 4 corners, a corner naming no vertex, an
/// extension whose format needs the corner table (`.ct`, see
/// [`writes_faces`]), an unknown one, or an I/O error.
pub(crate) fn save_faces(path: &Path, faces: &crate::mesh::Faces, attrs: &Attributes) -> Result<()> {
    use rayon::prelude::*;
    let (v, sides, nv) = (&faces.corners, faces.sides, faces.positions.len());
    let bad = |msg: String| Err(Error::Usage(format!("{}: {msg}", path.display())));
    if !(3..=4).contains(&sides) || v.len() % sides != 0 {
        return bad(format!(
            "{} corners in faces of {sides}: only triangles and quads are written from faces",
            v.len()
        ));
    }
    if let Some(c) = v.par_iter().position_any(|&x| x as usize >= nv) {
        return bad(format!("corner {c} names vertex {}, beyond the {nv} vertices", v[c]));
    }
    match Format::for_output(path) {
        Some(f @ Format { faces_writer: Some(write), .. }) if sides == 3 || f.poly_writer.is_some() => {
            write(path, &faces.positions, v, sides, attrs)
        }
        Some(Format { faces_writer: Some(write), .. }) => {
            // quads into a format without polygons: each fanned as save_poly does
            let fan: Vec<u32> = (0..v.len() as u32 / 4)
                .flat_map(|f| [4 * f, 4 * f + 1, 4 * f + 2, 4 * f, 4 * f + 2, 4 * f + 3])
                .collect();
            let tri_attrs = Attributes {
                uv: attrs
                    .uv
                    .as_ref()
                    .filter(|u| u.len() == v.len())
                    .map(|u| fan.iter().map(|&c| u[c as usize]).collect()),
                colors: attrs.colors.clone(),
                options: attrs.options,
                materials: attrs.materials.as_ref().map(|m| crate::mesh::attributes::MaterialGroups {
                    face: (0..2 * m.face.len()).map(|t| m.face[t / 2]).collect(),
                    ..m.clone()
                }),
            };
            let tris: Vec<u32> = fan.iter().map(|&c| v[c as usize]).collect();
            write(path, &faces.positions, &tris, 3, &tri_attrs)
        }
        Some(f) => Err(Error::Usage(format!("{}: {} needs a corner table, not faces alone", path.display(), f.name))),
        None => Err(Error::UnknownFormat {
            path: path.display().to_string(),
            ext: ext(path),
            direction: "output",
            known: ".obj, .ply, .ct, .stl, .off, .glb, .usda, .usdc or .usdz",
        }),
    }
}

/// Saves a polygon mesh by extension, its attributes per polygon corner
/// (texture coordinates) and face (materials) where the format keeps them;
/// STL and `.glb` get its faces fanned into triangles.
///
/// # Errors
/// An unknown extension or an I/O error.
pub(crate) fn save_poly(path: &Path, mesh: &PolyMesh, attrs: &Attributes) -> Result<()> {
    if !mesh.pt.holes().is_empty() {
        // through the mesh of its triangles, which leaves the holes out (or
        // keeps them as tags) as save_with does
        let fan = mesh.pt.fan_corners();
        let tri_attrs = Attributes {
            uv: attrs
                .uv
                .as_ref()
                .filter(|u| u.len() == mesh.pt.num_corners())
                .map(|u| fan.iter().map(|&c| u[c as usize]).collect()),
            colors: attrs.colors.clone(),
            options: attrs.options,
            materials: attrs.materials.as_ref().filter(|m| m.face.len() == mesh.pt.num_faces()).map(|m| {
                crate::mesh::attributes::MaterialGroups {
                    face: fan.chunks_exact(3).map(|t| m.face[mesh.pt.face(t[0]) as usize]).collect(),
                    ..m.clone()
                }
            }),
        };
        return save_with(path, &mesh.triangulated(), &tri_attrs);
    }
    match Format::for_output(path) {
        Some(Format { poly_writer: Some(write), .. }) => write(path, mesh, attrs),
        Some(_) => {
            let fan = mesh.pt.fan_corners();
            let tri_attrs = Attributes {
                uv: attrs.uv.as_ref().map(|u| fan.iter().map(|&c| u[c as usize]).collect()),
                colors: attrs.colors.clone(),
                options: attrs.options,
                materials: attrs.materials.as_ref().map(|m| crate::mesh::attributes::MaterialGroups {
                    face: fan.chunks_exact(3).map(|t| m.face[mesh.pt.face(t[0]) as usize]).collect(),
                    ..m.clone()
                }),
            };
            save_with(path, &mesh.triangulated(), &tri_attrs)
        }
        None => save_with(path, &mesh.triangulated(), attrs),
    }
}

pub(crate) fn ext(path: &Path) -> String {
    path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase()
}

/// The [`RawMesh`] the reader of `name`'s format makes of `bytes`, with the
/// default budget (for the readers' unit tests).
#[cfg(test)]
pub(crate) fn raw_of(bytes: &[u8], name: &str) -> Result<RawMesh> {
    read_raw(Source::Bytes { bytes, name, folder: None }, &ReadOptions::default()).map(|r| r.raw)
}

/// A fresh directory for one unit test's files, removed when dropped.
#[cfg(test)]
pub(crate) struct TestDir(pub(crate) PathBuf);

#[cfg(test)]
impl TestDir {
    pub(crate) fn new(name: &str) -> TestDir {
        let dir = std::env::temp_dir().join(format!("subdiv-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temporary directory");
        TestDir(dir)
    }
}

#[cfg(test)]
impl Drop for TestDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeated_warnings_are_summarised() {
        let w = Warnings::new("m.obj", 300);
        for i in 0..100_002 {
            w.warn("unknown materials", format!("material 'm{i}' is in no library\n"));
        }
        w.warn("other", "one");
        let lines = w.finish();
        assert_eq!(lines.len(), 5, "{lines:?}");
        assert!(lines.iter().all(|l| !l.contains('\n')));
        assert_eq!(lines[4], "m.obj: ... and 99,999 more unknown materials");
    }

    #[test]
    fn extensions_and_content_choose_the_format() {
        assert_eq!(Format::of("a.PLY", b"").name, ply::FORMAT.name);
        for (bytes, f) in [
            (&b"ply\nformat ascii 1.0\n"[..], &ply::FORMAT),
            (b"  {\"asset\":{}}", &gltf::FORMAT),
            (b"glTF\x02\0\0\0", &gltf::FORMAT),
            (b"<?xml version=\"1.0\"?><COLLADA>", &dae::FORMAT),
            (b"solid x\nfacet normal 0 0 1\n", &stl::FORMAT),
            (b"OFF\n3 1 0\n", &off::FORMAT),
            (b"COFF\n", &off::FORMAT),
            (b"v 0 0 0\n", &obj::FORMAT),
        ] {
            assert_eq!(Format::of("noextension", bytes), f, "{}", String::from_utf8_lossy(bytes));
        }
        let mut stl = vec![0u8; 84 + 50];
        stl[80] = 1;
        assert_eq!(Format::of("x", &stl), &stl::FORMAT);
    }
}
