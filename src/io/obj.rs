//! Wavefront OBJ.
//!
//! Reading: our own streaming parser (`v`, `vt`, `f`, `usemtl`, `mtllib`
//! and OpenSubdiv's `t` tags), with vertex ids global across `o`/`g` groups,
//! negative (relative) indices, polygons kept as polygons, and the line of
//! every record remembered so that every error names it. The `mtllib`
//! libraries are read through the `Resolver`
//! (OBJ practice lets them lie anywhere; only regular files, each read
//! once, within the budget) and parsed by `io/mtl.rs`; their textures
//! are decoded when the read asks for them. A library that cannot be read
//! or a material it lacks is a warning: those faces are drawn grey.
//!
//! Writing formats chunks of lines in parallel (shortest round-trip floats).

use super::raw::RawMesh;
use super::resolve::Scope;
use super::text::{self, Line};
use super::{Format, Input, Keeps, atomic_write};
use crate::mesh::Mesh;
use crate::mesh::attributes::weld_uvs;
use crate::mesh::attributes::{Attributes, Material};
use crate::mesh::options::{ShapeOptions, TriangleSubdivision};
use crate::mesh::sharpness::Creasing;
use crate::mesh::sharpness::{CornerTag, CreaseTag};
use crate::{Error, MeshError, Result};
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The OBJ row of [`super::FORMATS`] (any text is taken for OBJ last).
pub(crate) const FORMAT: Format = Format {
    name: "Wavefront OBJ",
    extensions: &["obj"],
    sniff: |_| true,
    reader: Some(read),
    writer: Some(save_with),
    written_as: &["obj"],
    poly_writer: Some(save_poly),
    faces_writer: Some(save_faces),
    keeps: Keeps { uv: true, colors: true, materials: true, creases: true, holes: false },
};

/// A corner without a texture coordinate.
const NO_UV: u32 = u32::MAX;

/// A face before any `usemtl`.
const NO_MATERIAL: u32 = u32::MAX;

/// What the parser gathers besides the [`RawMesh`].
#[derive(Default)]
struct Parsed {
    raw: RawMesh,
    /// Texture coordinates of the `vt` records.
    uvs: Vec<Vec2>,
    /// Per face corner, the `vt` record used there ([`NO_UV`] when none).
    corner_uv: Vec<u32>,
    /// `v x y z r g b` colours, in record order (only while every record has one).
    colors: Vec<Vec3>,
    /// The material names of `usemtl` records, in order of first use.
    names: Vec<String>,
    /// Where each name is in `names`.
    name_ids: HashMap<String, u32>,
    /// Index into `names` of every face ([`NO_MATERIAL`] before any `usemtl`).
    face_material: Vec<u32>,
    /// The files of `mtllib` records, as written, each once.
    mtllibs: Vec<String>,
    /// The corners of the face record being read (reused between records):
    /// vertex ids and `vt` ids.
    poly: (Vec<u32>, Vec<u32>),
    /// How many vertices and faces may be read, and corners per face.
    max: (usize, usize, usize),
}

/// The next `N` tokens as numbers; `what` names the record in errors.
fn floats<'a, const N: usize, F: std::str::FromStr + Copy + Default>(
    toks: &mut impl Iterator<Item = &'a str>,
    file: &str,
    ln: usize,
    what: &str,
) -> Result<[F; N]> {
    let mut out = [F::default(); N];
    for (i, slot) in out.iter_mut().enumerate() {
        let t = toks.next().ok_or_else(|| parse_err(file, ln, format!("{what} has {i} values, expected {N}")))?;
        *slot = t.parse().map_err(|_| parse_err(file, ln, format!("{what} '{t}' is not a number")))?;
    }
    Ok(out)
}

fn parse_err(file: &str, line: usize, msg: impl Into<String>) -> Error {
    Error::Parse { file: file.to_string(), line, msg: msg.into() }
}

/// Reads an OBJ file with its materials.
///
/// # Errors
/// [`Error::Parse`] or [`Error::Mesh`] with the line of the record; over
/// the budget.
fn read(input: &Input) -> Result<RawMesh> {
    let mut p = parse(input)?;
    let file = input.file;
    input.budget.take_vertices(p.raw.positions.len() as u64, file, "v records")?;
    input.budget.take_faces(p.raw.num_faces() as u64, file, "f records")?;
    let corners = p.raw.corners.len();
    if corners > 0 && p.corner_uv.iter().all(|&j| j != NO_UV) {
        p.raw.uv = Some(p.corner_uv.iter().map(|&j| p.uvs[j as usize]).collect());
    } else if p.corner_uv.iter().any(|&j| j != NO_UV) {
        let without = p.corner_uv.iter().filter(|&&j| j == NO_UV).count();
        input.warnings.warn(
            "texture coordinate notes",
            format!("{file}: texture coordinates dropped: {without} of {corners} face corners have none"),
        );
    }
    if !p.colors.is_empty() && p.colors.len() == p.raw.positions.len() {
        p.raw.colors = Some(std::mem::take(&mut p.colors));
    }
    if !p.names.is_empty() {
        materials(&mut p, input)?;
    }
    p.raw.libraries = p.mtllibs;
    Ok(p.raw)
}

/// Parses OBJ text into [`Parsed`].
///
/// # Errors
/// [`Error::Parse`] with the line number for anything that is not valid OBJ.
fn parse(input: &Input) -> Result<Parsed> {
    let (bytes, file) = (input.bytes, input.file);
    let l = input.budget.limits();
    let max = (l.vertices.min(u32::MAX as u64) as usize, l.faces as usize, l.face_size as usize);
    // one check of the whole text (fast); where a byte is bad, the lines
    // before it are read first, so that an earlier error is the one reported
    match std::str::from_utf8(bytes) {
        Ok(text) => parse_text(text, file, max, l.materials),
        Err(e) => {
            let good = &bytes[..e.valid_up_to()];
            let start = good.iter().rposition(|&b| b == b'\n').map_or(0, |k| k + 1);
            let ln = good.iter().filter(|&&b| b == b'\n').count() + 1;
            // the bytes before the bad line's start are valid UTF-8
            let before = std::str::from_utf8(&bytes[..start]).unwrap_or_default();
            parse_text(before, file, max, l.materials)?;
            Err(parse_err(file, ln, "not text (invalid UTF-8): is this an OBJ file?"))
        }
    }
}

/// [`parse`] of text.
fn parse_text(text: &str, file: &str, max: (usize, usize, usize), max_materials: u64) -> Result<Parsed> {
    let mut p = Parsed { max, ..Default::default() };
    p.raw.sources.id_base = 1;
    let mut material = NO_MATERIAL;
    for (lineno, line) in text.split('\n').enumerate() {
        let ln = lineno + 1;
        // `#` and `\r` are ASCII: cutting at them keeps the text valid
        let line = match line.bytes().position(|b| b == b'#') {
            Some(k) => &line[..k],
            None => line.strip_suffix('\r').unwrap_or(line),
        };
        let mut toks = line.split_ascii_whitespace();
        let Some(key) = toks.next() else { continue };
        let at = Loc { file, ln };
        match key {
            "v" => vertex_record(&mut p, toks, at)?,
            "vt" => texture_record(&mut p, toks, at)?,
            "f" => {
                face_record(&mut p, toks, at)?;
                p.face_material.push(material);
            }
            "usemtl" => {
                let name = line.trim_start().strip_prefix("usemtl").unwrap_or("").trim();
                material = match p.name_ids.get(name) {
                    Some(&i) => i,
                    None => {
                        if p.names.len() as u64 >= max_materials {
                            return Err(over(file, ln, "materials", p.names.len() as u64 + 1, max_materials));
                        }
                        p.names.push(name.to_string());
                        p.name_ids.insert(name.to_string(), p.names.len() as u32 - 1);
                        p.names.len() as u32 - 1
                    }
                };
            }
            "mtllib" => {
                for lib in toks {
                    if !p.mtllibs.iter().any(|l| l == lib) {
                        p.mtllibs.push(lib.to_string());
                    }
                }
            }
            "t" => parse_tag(&mut toks, file, ln, &mut p.raw)?,
            other if is_ignored_keyword(other) => {}
            other => {
                let shown: String = other.chars().take(20).collect();
                return Err(parse_err(file, ln, format!("unexpected '{shown}': is this an OBJ file?")));
            }
        }
    }
    Ok(p)
}

/// [`Error::OverBudget`] at line `ln`.
fn over(file: &str, ln: usize, limit: &'static str, value: u64, max: u64) -> Error {
    Error::OverBudget { file: file.to_string(), element: format!("line {ln}"), limit, value, max }
}

/// `t hole N/0/0 f1 .. fN`: the 0-based ids of faces that are holes.
fn parse_hole<'a>(
    toks: &mut impl Iterator<Item = &'a str>,
    counts: &str,
    file: &str,
    ln: usize,
    raw: &mut RawMesh,
) -> Result<()> {
    let n = counts.split('/').next().and_then(|x| x.parse::<usize>().ok());
    let Some(n) = n.filter(|&n| n > 0) else {
        return Err(parse_err(file, ln, format!("hole tag: '{counts}' is not a count like 1/0/0")));
    };
    let ids: Option<Vec<u32>> = toks.take(n).map(|t| t.parse().ok()).collect();
    match ids.filter(|v| v.len() == n) {
        Some(ids) => {
            raw.holes.extend(ids.into_iter().map(|f| (f, ln as u32)));
            Ok(())
        }
        None => Err(parse_err(file, ln, format!("hole tag: needs {n} face ids (0-based)"))),
    }
}

/// The tags that state a subdivision option (see [`ShapeOptions`]).
const OPTION_TAGS: [&str; 4] =
    ["interpolateboundary", "facevaryinginterpolateboundary", "smoothtriangles", "creasemethod"];

/// An option tag: `t interpolateboundary 1/0/0 k` (0 none, 1
/// edge-and-corner, 2 edge), `t facevaryinginterpolateboundary 1/0/0 k` (0
/// none .. 5 all), `t smoothtriangles 0/0/1 catmark|smooth`, `t
/// creasemethod 0/0/1 normal|chaikin` (OpenSubdiv's regression shapes).
fn parse_option<'a>(
    name: &str,
    toks: &mut impl Iterator<Item = &'a str>,
    counts: &str,
    at: Loc,
    options: &mut ShapeOptions,
) -> Result<()> {
    let value = toks.next().unwrap_or("");
    let bad = |want: &str| parse_err(at.file, at.ln, format!("{name} tag: '{counts} {value}' is not {want}"));
    let int = |max: u32| value.parse::<u32>().ok().filter(|&k| k <= max);
    match name {
        "interpolateboundary" => {
            let k = int(2).filter(|_| counts == "1/0/0").ok_or_else(|| bad("1/0/0 and 0, 1 or 2"))?;
            options.boundary = ShapeOptions::boundary_of(k);
        }
        "facevaryinginterpolateboundary" => {
            let k = int(5).filter(|_| counts == "1/0/0").ok_or_else(|| bad("1/0/0 and 0 to 5"))?;
            options.fvar = ShapeOptions::fvar_of(k);
        }
        "smoothtriangles" => {
            options.triangles = Some(match (counts, value) {
                ("0/0/1", "catmark") => TriangleSubdivision::Catmark,
                ("0/0/1", "smooth") => TriangleSubdivision::Smooth,
                _ => return Err(bad("0/0/1 and catmark or smooth")),
            })
        }
        _ => {
            options.creasing = Some(match (counts, value) {
                ("0/0/1", "normal") => Creasing::Uniform,
                ("0/0/1", "chaikin") => Creasing::Chaikin,
                _ => return Err(bad("0/0/1 and normal or chaikin")),
            })
        }
    }
    Ok(())
}

/// Parses a tag record (OpenSubdiv's `t name nint/nfloat/nstring ints
/// floats strings`): `t crease 2/1/0 v0 v1 s` (also a chain `t crease
/// k/1/0 v0 .. vk-1 s`, or one sharpness per edge), `t corner 1/1/0 v s`
/// (also several vertices), `t hole N/0/0 f1 .. fN` (faces); ids are
/// 0-based; the options of [`OPTION_TAGS`]. Other tags are read and
/// ignored.
fn parse_tag<'a>(toks: &mut impl Iterator<Item = &'a str>, file: &str, ln: usize, raw: &mut RawMesh) -> Result<()> {
    let name = toks.next().unwrap_or("");
    let counts = toks.next().unwrap_or("");
    if name == "hole" {
        return parse_hole(toks, counts, file, ln, raw);
    }
    if OPTION_TAGS.contains(&name) {
        return parse_option(name, toks, counts, Loc { file, ln }, &mut raw.options);
    }
    if name != "crease" && name != "corner" {
        return Ok(());
    }
    let mut cs = counts.split('/').map(|x| x.parse::<usize>());
    let (Some(Ok(ni)), Some(Ok(nf))) = (cs.next(), cs.next()) else {
        return Err(parse_err(file, ln, format!("{name} tag: '{counts}' is not a count like 2/1/0")));
    };
    let ints: Vec<u32> = toks
        .by_ref()
        .take(ni)
        .map(|t| t.parse().ok())
        .collect::<Option<_>>()
        .filter(|v: &Vec<u32>| v.len() == ni)
        .ok_or_else(|| parse_err(file, ln, format!("{name} tag: needs {ni} vertex ids (0-based)")))?;
    let floats: Vec<f32> = toks
        .take(nf)
        .map(|t| t.parse().ok())
        .collect::<Option<_>>()
        .filter(|v: &Vec<f32>| v.len() == nf)
        .ok_or_else(|| parse_err(file, ln, format!("{name} tag: needs {nf} sharpness values")))?;
    let per = |k: usize, n: usize| -> Result<f32> {
        match floats.len() {
            1 => Ok(floats[0]),
            m if m == n => Ok(floats[k]),
            m => Err(parse_err(file, ln, format!("{name} tag: {m} sharpness values for {n} elements"))),
        }
    };
    let lines = &mut raw.sources.tag_lines;
    if name == "crease" {
        if ints.len() < 2 {
            return Err(parse_err(file, ln, "crease tag: needs two vertex ids (0-based) and a sharpness"));
        }
        for k in 0..ints.len() - 1 {
            let s = per(k, ints.len() - 1)?;
            raw.tags.creases.push(CreaseTag { v0: ints[k], v1: ints[k + 1], sharpness: s });
            // crease lines come before corner lines: insert before the corners'
            lines.insert(raw.tags.creases.len() - 1, ln as u32);
        }
    } else {
        if ints.is_empty() {
            return Err(parse_err(file, ln, "corner tag: needs a vertex id (0-based) and a sharpness"));
        }
        for (k, &v) in ints.iter().enumerate() {
            raw.tags.corners.push(CornerTag { vertex: v, sharpness: per(k, ints.len())? });
            lines.push(ln as u32);
        }
    }
    Ok(())
}

/// Where a record is: the file (for messages) and its 1-based line.
#[derive(Clone, Copy)]
struct Loc<'a> {
    file: &'a str,
    ln: usize,
}

/// Records we read past: the rest of the OBJ keywords (normals, groups,
/// materials, free-form geometry), and any other short identifier, which is
/// taken for an extension.
fn is_ignored_keyword(key: &str) -> bool {
    matches!(
        key,
        "vn" | "vp"
            | "o"
            | "g"
            | "s"
            | "l"
            | "p"
            | "cstype"
            | "deg"
            | "curv"
            | "curv2"
            | "surf"
            | "parm"
            | "trim"
            | "hole"
            | "end"
            | "bmat"
            | "step"
            | "mg"
            | "lod"
            | "usemap"
            | "maplib"
            | "shadow_obj"
            | "trace_obj"
            | "ctech"
            | "stech"
            | "con"
            | "sp"
    ) || (key.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') && key.len() < 32)
}

/// A `v x y z [r g b]` record.
fn vertex_record<'a>(p: &mut Parsed, mut toks: impl Iterator<Item = &'a str>, at: Loc) -> Result<()> {
    let Loc { file, ln } = at;
    if p.raw.positions.len() >= p.max.0 {
        return Err(over(file, ln, "vertices", p.raw.positions.len() as u64 + 1, p.max.0 as u64));
    }
    // read in f64 (kept for double precision), drawn in f32; a decimal
    // exactly halfway between two f32 values (ten or more digits) may
    // round to the other one of the two
    let xyz: [f64; 3] = floats(&mut toks, file, ln, "vertex")?;
    if xyz.iter().any(|x| !(*x as f32).is_finite()) {
        return Err(Error::Mesh {
            file: file.into(),
            line: Some(ln),
            source: MeshError::NonFinite { vertex: p.raw.positions.len() + 1 },
        });
    }
    // Optional per-vertex colour `v x y z r g b` (a common extension); a
    // lone fourth value is the homogeneous w and is ignored.
    if let (Some(r), Some(g)) = (toks.next(), toks.next()) {
        let rgb: [f32; 3] = floats(&mut [r, g].into_iter().chain(toks), file, ln, "colour")?;
        if rgb.iter().any(|x| !x.is_finite()) {
            return Err(parse_err(file, ln, "vertex colour is not finite"));
        }
        // kept only while every vertex so far has one
        if p.colors.len() == p.raw.positions.len() {
            p.colors.push(Vec3::from_array(rgb).clamp(Vec3::ZERO, Vec3::ONE));
        }
    }
    let precise = glam::DVec3::from_array(xyz);
    p.raw.positions.push(precise.as_vec3());
    p.raw.precise.push(precise);
    p.raw.sources.vertex_lines.push(ln as u32);
    Ok(())
}

/// A `vt u v [w]` record.
fn texture_record<'a>(p: &mut Parsed, mut toks: impl Iterator<Item = &'a str>, at: Loc) -> Result<()> {
    let uv: [f32; 2] = floats(&mut toks, at.file, at.ln, "texture coordinate")?;
    if uv.iter().any(|x| !x.is_finite()) {
        return Err(parse_err(at.file, at.ln, "texture coordinate is not finite"));
    }
    if p.uvs.len() >= p.max.0 {
        return Err(over(at.file, at.ln, "vertices", p.uvs.len() as u64 + 1, p.max.0 as u64));
    }
    p.uvs.push(Vec2::from_array(uv));
    Ok(())
}

/// An `f v[/vt[/vn]] ...` record, kept as a polygon.
fn face_record<'a>(p: &mut Parsed, toks: impl Iterator<Item = &'a str>, at: Loc) -> Result<()> {
    let Loc { file, ln } = at;
    if p.raw.num_faces() >= p.max.1 {
        return Err(over(file, ln, "faces", p.raw.num_faces() as u64 + 1, p.max.1 as u64));
    }
    let (mut pv, mut puv) = std::mem::take(&mut p.poly);
    pv.clear();
    puv.clear();
    for t in toks {
        if pv.len() >= p.max.2 {
            return Err(over(file, ln, "face-size", pv.len() as u64 + 1, p.max.2 as u64));
        }
        let mut parts = t.split('/');
        let idx = parts.next().unwrap_or("");
        puv.push(match parts.next().filter(|x| !x.is_empty()) {
            None => NO_UV,
            Some(vt) => texture_index(vt, t, p.uvs.len(), at)?,
        });
        pv.push(vertex_index(idx, t, p, at)?);
    }
    if pv.len() < 3 {
        return Err(parse_err(file, ln, format!("face has {} vertices, needs at least 3", pv.len())));
    }
    p.raw.push_face(&pv);
    p.corner_uv.extend_from_slice(&puv);
    p.raw.sources.face_lines.push(ln as u32);
    p.poly = (pv, puv);
    Ok(())
}

/// The 0-based id of the `vt` index `vt` of face corner `t`, with `m` `vt`
/// records so far (1-based, or negative = relative to the last one).
fn texture_index(vt: &str, t: &str, m: usize, at: Loc) -> Result<u32> {
    let j: i64 = vt.parse().map_err(|_| parse_err(at.file, at.ln, format!("'{t}' has a bad texture index")))?;
    let m = m as i64;
    let abs = if j < 0 { m + j } else { j - 1 };
    if j == 0 || abs < 0 || abs >= m {
        return Err(parse_err(at.file, at.ln, format!("texture index {j} out of range ({m} vt records so far)")));
    }
    Ok(abs as u32)
}

/// The 0-based id of the vertex index `idx` of face corner `t` (1-based, or
/// negative = relative to the last vertex so far). An index past the
/// vertices read so far is accepted here and checked when the mesh is built.
fn vertex_index(idx: &str, t: &str, p: &Parsed, at: Loc) -> Result<u32> {
    let i: i64 = idx.parse().map_err(|_| parse_err(at.file, at.ln, format!("'{t}' is not a vertex index")))?;
    let n = p.raw.positions.len() as i64;
    let abs = if i < 0 { n + i } else { i - 1 };
    if i == 0 || abs < 0 || abs >= u32::MAX as i64 {
        return Err(Error::Mesh {
            file: at.file.into(),
            line: Some(at.ln),
            source: MeshError::IndexOutOfRange { face: p.raw.num_faces(), index: i, len: n as usize },
        });
    }
    Ok(abs as u32)
}

/// The material groups of an OBJ with `usemtl` records: `Kd` and `map_Kd`
/// of each material from its `mtllib` libraries (the first library that
/// has a name wins), with the textures decoded when the read asks for
/// them. Faces before the first `usemtl` get a material `default`.
///
/// # Errors
/// Over the budget (libraries, bytes); a library that cannot be read is a
/// warning.
fn materials(p: &mut Parsed, input: &Input) -> Result<()> {
    let file = input.file;
    let mut face = std::mem::take(&mut p.face_material);
    let mut names = std::mem::take(&mut p.names);
    if face.contains(&NO_MATERIAL) {
        names.push("default".into());
        let d = names.len() as u32 - 1;
        face.iter_mut().filter(|m| **m == NO_MATERIAL).for_each(|m| *m = d);
    }
    let entries = read_libraries(&p.mtllibs, input)?;
    let mut list = Vec::with_capacity(names.len());
    for n in &names {
        let Some((e, folder)) = entries.get(n.as_str()) else {
            if n != "default" {
                input.warnings.warn(
                    "materials missing from the libraries",
                    format!("{file}: material '{n}' is in no mtllib that could be read; drawn grey"),
                );
            }
            list.push(Material::named(n));
            continue;
        };
        let mut m =
            Material { diffuse: e.diffuse.unwrap_or(Vec3::splat(0.8)), wrap: [e.wrap; 2], ..Material::named(n) };
        if let Some(t) = &e.texture {
            let at = format!("material '{n}' map_Kd");
            match input.refs.resolve_in(folder, t, Scope::Anywhere, &at) {
                Ok(path) => {
                    if input.textures {
                        m.texture = super::texture::load(input, &path, &at);
                    }
                    m.diffuse_texture = Some(path);
                }
                Err(e) => input.warnings.warn("textures that cannot be read", e),
            }
        }
        list.push(m);
    }
    p.raw.materials = Some(face);
    p.raw.material_list = list;
    Ok(())
}

/// The entries of the libraries `libs` by material name (the first library
/// naming one wins), each with the folder its textures are found in. Each
/// library is read once, through the resolver; one that cannot be read is
/// a warning.
///
/// # Errors
/// Over the `libraries` or byte budget.
fn read_libraries(libs: &[String], input: &Input) -> Result<HashMap<String, (super::mtl::Entry, PathBuf)>> {
    let mut out = HashMap::new();
    let mut seen: Vec<PathBuf> = Vec::new();
    for lib in libs {
        let at = format!("mtllib {lib}");
        let path = match input.refs.resolve(lib, Scope::Anywhere, &at) {
            Ok(p) => p,
            Err(e) => {
                input.warnings.warn("libraries that cannot be read", e);
                continue;
            }
        };
        let real = path.canonicalize().unwrap_or_else(|_| path.clone());
        if seen.contains(&real) {
            continue;
        }
        seen.push(real);
        input.budget.take_library(input.file, &at)?;
        let bytes = match input.refs.read(&path, None, &at) {
            Ok(b) => b,
            Err(e @ Error::OverBudget { .. }) => return Err(e),
            Err(e) => {
                input.warnings.warn("libraries that cannot be read", e);
                continue;
            }
        };
        let shown = format!("{} ({})", input.file, crate::error::clean(lib, 60));
        let text = String::from_utf8_lossy(&bytes);
        let folder = path.parent().map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        for e in super::mtl::parse(&text, &shown, input.warnings) {
            out.entry(e.name.clone()).or_insert_with(|| (e, folder.clone()));
        }
    }
    Ok(out)
}

/// [`put_f32`] appended to `out` (the records written one by one).
fn push_f32(out: &mut Vec<u8>, buf: &mut zmij::Buffer, x: f32) {
    let mut line: Line = Line::new(b"");
    put_f32(&mut line, buf, x);
    line.append_to(out);
}

/// Whether `x` is a whole number below 10^7 in magnitude, and not -0:
/// written without ".0" (shorter and still exact; -0 would lose its sign).
/// The conversion to an integer and back is two instructions, where
/// `x.trunc()` is a call into libm on the baseline x86_64.
#[inline(always)]
fn is_small_whole(x: f32) -> bool {
    x.abs() < 1e7 && (x as i32) as f32 == x && !(x == 0.0 && x.is_sign_negative())
}

/// OBJ text of the faces of `sides` corners each whose vertices are `v`
/// over the vertices `pos`, with their attributes and the tag records
/// `tags` (see [`write_obj_with`]).
///
/// # Errors
/// The first error of `sink`.
fn write_faces(
    (pos, v, sides): (&[Vec3], &[u32], usize),
    attrs: &Attributes,
    tags: &[u8],
    sink: &mut dyn FnMut(&[u8]) -> Result<()>,
) -> Result<()> {
    let tags = &[option_lines(attrs.options), tags.to_vec()].concat();
    if !attrs.is_empty() {
        let face = |f: usize| sides * f..sides * f + sides;
        let faces = FaceSource { corners: v, count: v.len() / sides, face: &face };
        return write_records(pos, &faces, attrs, tags, sink);
    }
    const ROWS: usize = 1 << 15;
    let noun = if sides == 3 { "triangles" } else { "faces" };
    let header = format!("# subdiv: {} vertices, {} {noun}\n", pos.len(), v.len() / sides);
    let vchunks: Vec<&[Vec3]> = pos.chunks(ROWS).collect();
    let tchunks: Vec<&[u32]> = v.chunks(sides * ROWS).collect();
    let nv = vchunks.len();
    let text = |k: usize| if k < nv { vertex_text(vchunks[k]) } else { face_text(tchunks[k - nv], sides) };
    crate::io::write_formatted(&[header.as_bytes()], nv + tchunks.len(), text, sink)?;
    sink(tags)
}

/// `v x y z` lines. Each line is put together in a small array and
/// appended whole (see [`Line`]).
fn vertex_text(ch: &[Vec3]) -> Vec<u8> {
    // room for the longest lines (and the whole Line copied past the last),
    // so that the buffer is never moved while it grows
    let mut out = Vec::with_capacity(ch.len() * text::LONGEST + 64);
    let mut rb = zmij::Buffer::new();
    let mut line: Line = Line::new(b"v ");
    for q in ch {
        line.reset();
        for (k, x) in q.to_array().into_iter().enumerate() {
            if k > 0 {
                line.push(b' ');
            }
            put_f32(&mut line, &mut rb, x);
        }
        line.push(b'\n');
        line.append_to(&mut out);
    }
    out
}

/// The shortest text that reads back as `x` (zmij: Schubfach's shortest
/// round-trip digits, the same text as ryu's and faster); whole numbers
/// below 10^7 without ".0" (see [`is_small_whole`]).
#[inline(always)]
fn put_f32(line: &mut Line, rb: &mut zmij::Buffer, x: f32) {
    if is_small_whole(x) {
        if x < 0.0 {
            line.push(b'-');
        }
        line.put_u32(x.abs() as u32);
    } else {
        line.put(rb.format_finite(x).as_bytes());
    }
}

/// `f a b c` lines (1-based) of rows of `sides` vertex ids.
fn face_text(ch: &[u32], sides: usize) -> Vec<u8> {
    text::row_lines(b"f ", ch, sides, |line, v| line.put_u32(v.wrapping_add(1)))
}

/// The mesh's sharpness as OBJ tag records (OpenSubdiv's `t crease 2/1/0 a b
/// s` and `t corner 1/1/0 v s`, 0-based ids), so a file round-trips.
pub(crate) fn tag_records(mesh: &Mesh) -> Vec<u8> {
    let mut out = mesh.ct.sharpness().map_or_else(Vec::new, |s| tag_lines(&s.to_tags(&mesh.ct)));
    out.extend(hole_lines(mesh.ct.holes()));
    out
}

/// The option tags (see [`parse_option`]) of the options that are not the
/// defaults.
pub(crate) fn option_lines(options: ShapeOptions) -> Vec<u8> {
    let o = options.not_default();
    let mut out = String::new();
    if let Some(b) = o.boundary {
        out += &format!("t interpolateboundary 1/0/0 {}\n", ShapeOptions::boundary_code(b));
    }
    if let Some(m) = o.fvar {
        out += &format!("t facevaryinginterpolateboundary 1/0/0 {}\n", ShapeOptions::fvar_code(m));
    }
    if o.triangles.is_some() {
        out += "t smoothtriangles 0/0/1 smooth\n";
    }
    if o.creasing.is_some() {
        out += "t creasemethod 0/0/1 chaikin\n";
    }
    out.into_bytes()
}

/// `t hole N/0/0 f1 .. fN` (0-based face ids) for the faces `holes`.
pub(crate) fn hole_lines(holes: &[u32]) -> Vec<u8> {
    if holes.is_empty() {
        return Vec::new();
    }
    let ids: Vec<String> = holes.iter().map(u32::to_string).collect();
    format!("t hole {}/0/0 {}\n", holes.len(), ids.join(" ")).into_bytes()
}

/// OBJ tag records of `tags`.
pub(crate) fn tag_lines(tags: &crate::mesh::sharpness::Tags) -> Vec<u8> {
    let mut out = Vec::new();
    let mut rb = zmij::Buffer::new();
    for t in &tags.creases {
        out.extend_from_slice(format!("t crease 2/1/0 {} {} ", t.v0, t.v1).as_bytes());
        push_f32(&mut out, &mut rb, t.sharpness);
        out.push(b'\n');
    }
    for t in &tags.corners {
        out.extend_from_slice(format!("t corner 1/1/0 {} ", t.vertex).as_bytes());
        push_f32(&mut out, &mut rb, t.sharpness);
        out.push(b'\n');
    }
    out
}

/// The faces an OBJ writer writes: a triangle table's or a polygon table's,
/// each face with the index of its first corner (the corners of all faces
/// in order are the `vt` records when there are texture coordinates).
pub(crate) struct FaceSource<'a> {
    /// The vertex of every corner, face after face.
    pub corners: &'a [u32],
    /// Faces.
    pub count: usize,
    /// The first corner of face `f`, and one past its last.
    pub face: &'a (dyn Fn(usize) -> std::ops::Range<usize> + Sync),
}

/// Formats OBJ text for `mesh` with its attributes: `v x y z r g b` when
/// there are colours, one `vt` per corner and `f a/ta b/tb c/tc` when there
/// are texture coordinates, the `mtllib` records and a `usemtl` wherever the
/// material changes when there are material groups. Without attributes this
/// is the plain `v`/`f` text.
///
/// # Errors
/// The first error of `sink`.
pub fn write_obj_with(mesh: &Mesh, attrs: &Attributes, sink: &mut dyn FnMut(&[u8]) -> Result<()>) -> Result<()> {
    write_faces((&mesh.positions, mesh.ct.v_table(), 3), attrs, &tag_records(mesh), sink)
}

/// [`write_obj_with`] of a polygon mesh: one `f` line per polygon (texture
/// coordinates per polygon corner, a material per face).
///
/// # Errors
/// The first error of `sink`.
pub(crate) fn write_poly(
    mesh: &crate::mesh::poly::PolyMesh,
    attrs: &Attributes,
    sink: &mut dyn FnMut(&[u8]) -> Result<()>,
) -> Result<()> {
    let pt = &mesh.pt;
    let tags = [option_lines(attrs.options), poly_tag_records(pt)].concat();
    if attrs.is_empty() {
        const ROWS: usize = 1 << 15;
        let pos = &mesh.positions;
        let header = format!("# subdiv: {} vertices, {} faces\n", pos.len(), pt.num_faces());
        let vchunks: Vec<&[Vec3]> = pos.chunks(ROWS).collect();
        let (nv, nf) = (vchunks.len(), pt.num_faces().div_ceil(ROWS));
        let text = |k: usize| {
            if k < nv {
                return vertex_text(vchunks[k]);
            }
            let first = ((k - nv) * ROWS) as u32;
            let last = (first + ROWS as u32).min(pt.num_faces() as u32);
            text::face_lines(b"f ", pt, first..last, false, |line, v| line.put_u32(v.wrapping_add(1)))
        };
        crate::io::write_formatted(&[header.as_bytes()], nv + nf, text, sink)?;
        return sink(&tags);
    }
    let face = |f: usize| {
        let r = pt.face_corners(f as u32);
        r.start as usize..r.end as usize
    };
    let faces = FaceSource { corners: pt.v_table(), count: pt.num_faces(), face: &face };
    write_records(&mesh.positions, &faces, attrs, &tags, sink)
}

/// The OBJ records of positions and `faces` with attributes (see
/// [`write_obj_with`]), then `tags`.
fn write_records(
    positions: &[Vec3],
    faces: &FaceSource,
    attrs: &Attributes,
    tags: &[u8],
    sink: &mut dyn FnMut(&[u8]) -> Result<()>,
) -> Result<()> {
    let mut out = Vec::with_capacity(1 << 20);
    // appends one record, handing the text to `sink` every megabyte
    let mut record = |out: &mut Vec<u8>, write: &mut dyn FnMut(&mut Vec<u8>)| -> Result<()> {
        write(out);
        if out.len() > 1 << 20 {
            sink(out)?;
            out.clear();
        }
        Ok(())
    };
    let (mut rb, mut ib) = (zmij::Buffer::new(), itoa::Buffer::new());
    let noun = if faces.corners.len() == 3 * faces.count { "triangles" } else { "faces" };
    let header = format!("# subdiv: {} vertices, {} {noun}\n", positions.len(), faces.count);
    record(&mut out, &mut |o| o.extend_from_slice(header.as_bytes()))?;
    let colors = attrs.colors.as_ref().filter(|c| c.len() == positions.len());
    for (i, q) in positions.iter().enumerate() {
        let rgb = colors.map(|c| c[i].to_array());
        record(&mut out, &mut |o| {
            o.push(b'v');
            for x in q.to_array().into_iter().chain(rgb.into_iter().flatten()) {
                o.push(b' ');
                push_f32(o, &mut rb, x);
            }
            o.push(b'\n');
        })?;
    }
    let mats = attrs.materials.as_ref().filter(|m| m.face.len() == faces.count);
    for lib in mats.map(|m| m.libraries.as_slice()).unwrap_or_default() {
        record(&mut out, &mut |o| o.extend_from_slice(format!("mtllib {lib}\n").as_bytes()))?;
    }
    // one vt per vertex and coordinate: the seams stay seams, the rest is shared
    let uv = attrs.uv.as_ref().filter(|u| u.len() == faces.corners.len()).map(|u| weld_uvs(faces.corners, u));
    for t in uv.iter().flat_map(|(values, _)| values) {
        record(&mut out, &mut |o| {
            o.extend_from_slice(b"vt");
            for x in [t.x, t.y] {
                o.push(b' ');
                push_f32(o, &mut rb, x);
            }
            o.push(b'\n');
        })?;
    }
    // a scene's prims are objects (`o`), other groups materials (`usemtl`)
    let scene = mats.and_then(|m| m.scene.as_deref()).filter(|s| mats.is_some_and(|m| s.prim_of.len() == m.list.len()));
    let (mut current, mut prim) = (u32::MAX, u32::MAX);
    for f in 0..faces.count {
        if let Some(m) = mats
            && m.face[f] != current
        {
            current = m.face[f];
            match scene {
                Some(s) if s.prim_of[current as usize] != prim => {
                    prim = s.prim_of[current as usize];
                    let name = s.prims.get(prim as usize).map_or("/Mesh", |p| p.path.as_str());
                    record(&mut out, &mut |o| o.extend_from_slice(format!("o {name}\n").as_bytes()))?;
                }
                Some(_) => {}
                None => {
                    let name = m.list.get(current as usize).map_or("default", |x| x.name.as_str());
                    record(&mut out, &mut |o| o.extend_from_slice(format!("usemtl {name}\n").as_bytes()))?;
                }
            }
        }
        record(&mut out, &mut |o| {
            o.push(b'f');
            for c in (faces.face)(f) {
                o.push(b' ');
                o.extend_from_slice(ib.format(faces.corners[c] + 1).as_bytes());
                if let Some((_, index)) = &uv {
                    o.push(b'/');
                    o.extend_from_slice(ib.format(index[c] + 1).as_bytes());
                }
            }
            o.push(b'\n');
        })?;
    }
    out.extend_from_slice(tags);
    sink(&out)
}

/// The sharpness of a polygon table as OBJ tag records.
fn poly_tag_records(pt: &crate::mesh::poly::PolyTable) -> Vec<u8> {
    let mut out = pt.sharpness().map_or_else(Vec::new, |s| tag_lines(&s.to_tags(pt)));
    out.extend(hole_lines(pt.holes()));
    out
}

/// Saves a polygon mesh with its attributes as OBJ (atomically).
///
/// # Errors
/// I/O errors naming `path`.
pub(crate) fn save_poly(path: &Path, mesh: &crate::mesh::poly::PolyMesh, attrs: &Attributes) -> Result<()> {
    atomic_write(path, |w| write_poly(mesh, attrs, &mut |b| w.write_all(b).map_err(|e| Error::io(path, e))))
}

/// Saves `mesh` with its attributes as OBJ (atomically).
///
/// # Errors
/// I/O errors naming `path`.
pub(crate) fn save_with(path: &Path, mesh: &Mesh, attrs: &Attributes) -> Result<()> {
    crate::io::atomic_write(path, |w| {
        write_obj_with(mesh, attrs, &mut |b| w.write_all(b).map_err(|e| Error::io(path, e)))
    })
}

/// Saves the faces of `sides` corners each whose vertices are `v` over the
/// vertices `positions`, with their attributes, as OBJ (atomically):
/// [`save_with`] of a mesh with these triangles, or [`save_poly`] of a mesh
/// with these quads, and no sharp features.
///
/// # Errors
/// I/O errors naming `path`.
pub(crate) fn save_faces(path: &Path, positions: &[Vec3], v: &[u32], sides: usize, attrs: &Attributes) -> Result<()> {
    crate::io::atomic_write(path, |w| {
        write_faces((positions, v, sides), attrs, &[], &mut |b| w.write_all(b).map_err(|e| Error::io(path, e)))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn face_lines_match_the_standard_formatting() {
        // every digit count, both sides of each power of ten, and the largest id
        let mut ids: Vec<u32> = (0..=9).flat_map(|k| [10u32.pow(k) - 1, 10u32.pow(k)]).collect();
        ids.extend([0, 7, 42, 65_535, u32::MAX - 1]);
        let v: Vec<u32> = ids.iter().flat_map(|&a| [a, a / 3, a / 7]).collect();
        let expected: String =
            v.chunks_exact(3).map(|t| format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1)).collect();
        assert_eq!(String::from_utf8(face_text(&v, 3)).unwrap(), expected);
    }

    #[test]
    fn the_first_error_in_the_file_is_reported_invalid_utf8_included() {
        let read = |bytes: &[u8]| {
            let src = crate::io::Source::Bytes { bytes, name: "m.obj", folder: None };
            crate::io::read(src, &Default::default())
        };
        let line_of = |bytes: &[u8]| match read(bytes) {
            Err(Error::Parse { line, msg, .. }) => (line, msg),
            other => panic!("expected a parse error, got {other:?}"),
        };
        let (line, msg) = line_of(b"v 0 0 0\nv 1 0 0\n# \xff\xfe\nf 1 2 3\n");
        assert_eq!(line, 3);
        assert!(msg.contains("UTF-8"), "{msg}");
        // a bad record before the bad byte is the error reported
        let (line, msg) = line_of(b"v 0 0 0\nv 1 zero 0\nv 0 1 0\n\xff\n");
        assert_eq!(line, 2);
        assert!(msg.contains("not a number"), "{msg}");
        // comments and carriage returns are cut before the tokens
        let m = read(b"v 0 0 0 # a comment\r\nv 1 0 0\r\nv 0 1 0#x\nf 1 2 3\r\n").expect("valid").mesh;
        assert_eq!((m.positions.len(), m.ct.num_triangles()), (3, 1));
    }

    #[test]
    fn coordinates_read_back_to_the_same_bits() {
        let mut xs =
            vec![0.0f32, -0.0, 1.0, -3.0, 0.1, 1.0 / 3.0, 1e-7, 3.4e38, f32::MIN_POSITIVE, 1e-45, 16_777_216.0];
        // a spread of magnitudes and mantissas
        xs.extend((0..2000u32).map(|i| f32::from_bits(i.wrapping_mul(2_654_435_761) & 0x7f7f_ffff)));
        xs.extend(xs.clone().iter().map(|x| -x));
        xs.extend([-1e6, -9_999_999.0, 9_999_999.0, 1e7, -1.5e7]);
        let mut b = zmij::Buffer::new();
        for &x in &xs {
            let mut out = Vec::new();
            push_f32(&mut out, &mut b, x);
            let text = std::str::from_utf8(&out).unwrap();
            let back: f32 = text.parse().unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{x:e} written as {text}");
            // with its prefix and separators in a vertex line
            let line = vertex_text(&[Vec3::new(x, 1.0, x)]);
            assert_eq!(String::from_utf8(line).unwrap(), format!("v {text} 1 {text}\n"));
        }
    }
}
