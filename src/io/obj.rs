//! Wavefront OBJ.
//!
//! Reading uses our own streaming parser rather than `tobj`: it keeps vertex
//! ids global across `o`/`g` groups (tobj renumbers per group, which would cut
//! a mesh apart at group borders and silently drop unused vertices), supports
//! negative indices, triangulates polygons as fans, and remembers the line of
//! every `v` and `f` record so that every error names the line. [`load_tobj`]
//! reads the same file through tobj; the tests use it as an independent
//! reference for our parser.
//!
//! Writing formats chunks of lines in parallel (shortest round-trip floats).

use super::atomic_write;
use super::text::{self, Line};
use crate::mesh::Mesh;
use crate::mesh::attributes::{Attributes, Material, MaterialGroups};
use crate::mesh::repair::{RepairReport, repair};
use crate::mesh::sharpness::{CornerTag, CreaseTag, Tags};
use crate::{Error, MeshError, Result};
use glam::{Vec2, Vec3};
use std::path::{Path, PathBuf};

/// What the parser read besides the mesh.
#[derive(Clone, Debug, Default)]
pub struct ObjInfo {
    /// `v` records in the file.
    pub vertex_records: usize,
    /// Vertices dropped because no face uses them.
    pub unreferenced: usize,
    /// Polygons with more than 3 corners that were split into triangles.
    pub polygons_triangulated: usize,
}

/// Raw OBJ content: positions, triangles, and the source line of each.
#[derive(Clone, Debug, Default)]
pub struct RawObj {
    /// Positions of every `v` record.
    pub positions: Vec<Vec3>,
    /// Triangles (0-based, global).
    pub triangles: Vec<u32>,
    /// Line (1-based) of every `v` record.
    pub vertex_lines: Vec<u32>,
    /// Line of the face record of every triangle.
    pub triangle_lines: Vec<u32>,
    /// Polygons triangulated.
    pub polygons: usize,
    /// Texture coordinates of the `vt` records.
    pub uvs: Vec<Vec2>,
    /// Per triangle corner, the `vt` index used there ([`NO_UV`] when none).
    pub corner_uv: Vec<u32>,
    /// `v x y z r g b` colours, in record order (only the records that had one).
    pub colors: Vec<Vec3>,
    /// Sharpness tags (`t crease`, `t corner`; vertex ids 0-based records).
    pub tags: Tags,
    /// Line of every crease tag.
    pub crease_lines: Vec<u32>,
    /// Line of every corner tag.
    pub corner_lines: Vec<u32>,
    /// The material names of `usemtl` records, in order of first use.
    pub material_names: Vec<String>,
    /// Index into `material_names` of every triangle ([`NO_MATERIAL`] before any `usemtl`).
    pub face_material: Vec<u32>,
    /// The files of `mtllib` records, as written.
    pub mtllibs: Vec<String>,
}

/// A triangle before any `usemtl` in [`RawObj::face_material`].
pub const NO_MATERIAL: u32 = u32::MAX;

/// A corner without a texture coordinate in [`RawObj::corner_uv`].
pub const NO_UV: u32 = u32::MAX;

/// The next `N` tokens as numbers; `what` names the record in errors.
fn floats<'a, const N: usize>(
    toks: &mut impl Iterator<Item = &'a str>,
    file: &str,
    ln: usize,
    what: &str,
) -> Result<[f32; N]> {
    let mut out = [0f32; N];
    for (i, slot) in out.iter_mut().enumerate() {
        let t = toks.next().ok_or_else(|| parse_err(file, ln, format!("{what} has {i} values, expected {N}")))?;
        *slot = t.parse().map_err(|_| parse_err(file, ln, format!("{what} '{t}' is not a number")))?;
    }
    Ok(out)
}

fn parse_err(file: &str, line: usize, msg: impl Into<String>) -> Error {
    Error::Parse { file: file.to_string(), line, msg: msg.into() }
}

/// Parses OBJ text. `file` is only used in error messages.
///
/// # Errors
/// [`Error::Parse`] with the line number for anything that is not valid OBJ.
pub fn parse(bytes: &[u8], file: &str) -> Result<RawObj> {
    // one check of the whole text (fast); where a byte is bad, the lines
    // before it are read first, so that an earlier error is the one reported
    match std::str::from_utf8(bytes) {
        Ok(text) => parse_text(text, file),
        Err(e) => {
            let good = &bytes[..e.valid_up_to()];
            let start = good.iter().rposition(|&b| b == b'\n').map_or(0, |k| k + 1);
            let ln = good.iter().filter(|&&b| b == b'\n').count() + 1;
            // the bytes before the bad line's start are valid UTF-8
            let before = std::str::from_utf8(&bytes[..start]).unwrap_or_default();
            parse_text(before, file)?;
            Err(parse_err(file, ln, "not text (invalid UTF-8): is this an OBJ file?"))
        }
    }
}

/// [`parse`] of text.
fn parse_text(text: &str, file: &str) -> Result<RawObj> {
    let mut raw = RawObj::default();
    let mut poly = Polygon::default();
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
            "v" => vertex_record(&mut raw, toks, at)?,
            "vt" => texture_record(&mut raw, toks, at)?,
            "f" => {
                face_record(&mut raw, &mut poly, toks, at)?;
                raw.face_material.resize(raw.triangle_lines.len(), material);
            }
            "usemtl" => {
                let name = line.trim_start().strip_prefix("usemtl").unwrap_or("").trim();
                material = match raw.material_names.iter().position(|n| n == name) {
                    Some(i) => i as u32,
                    None => {
                        raw.material_names.push(name.to_string());
                        raw.material_names.len() as u32 - 1
                    }
                };
            }
            "mtllib" => raw.mtllibs.extend(toks.map(str::to_string)),
            "t" => parse_tag(&mut toks, file, ln, &mut raw)?,
            other if is_ignored_keyword(other) => {}
            other => {
                let shown: String = other.chars().take(20).collect();
                return Err(parse_err(file, ln, format!("unexpected '{shown}': is this an OBJ file?")));
            }
        }
    }
    Ok(raw)
}

/// Parses a tag record (OpenSubdiv's `t name nint/nfloat/nstring ints
/// floats strings`): `t crease 2/1/0 v0 v1 s` (also a chain `t crease
/// k/1/0 v0 .. vk-1 s`, or one sharpness per edge), `t corner 1/1/0 v s`
/// (also several vertices); vertex ids are 0-based. Other tags (such as
/// `interpolateboundary`) are read and ignored.
fn parse_tag<'a>(toks: &mut impl Iterator<Item = &'a str>, file: &str, ln: usize, raw: &mut RawObj) -> Result<()> {
    let name = toks.next().unwrap_or("");
    let counts = toks.next().unwrap_or("");
    if name != "crease" && name != "corner" {
        return Ok(());
    }
    let mut cs = counts.split('/').map(|x| x.parse::<usize>());
    let (Some(Ok(ni)), Some(Ok(nf))) = (cs.next(), cs.next()) else {
        return Err(parse_err(file, ln, format!("{name} tag: '{counts}' is not a count like 2/1/0")));
    };
    let ints: Vec<u32> = (0..ni)
        .map(|_| toks.next().and_then(|t| t.parse().ok()))
        .collect::<Option<_>>()
        .ok_or_else(|| parse_err(file, ln, format!("{name} tag: needs {ni} vertex ids (0-based)")))?;
    let floats: Vec<f32> = (0..nf)
        .map(|_| toks.next().and_then(|t| t.parse().ok()))
        .collect::<Option<_>>()
        .ok_or_else(|| parse_err(file, ln, format!("{name} tag: needs {nf} sharpness values")))?;
    let per = |k: usize, n: usize| -> Result<f32> {
        match floats.len() {
            1 => Ok(floats[0]),
            m if m == n => Ok(floats[k]),
            m => Err(parse_err(file, ln, format!("{name} tag: {m} sharpness values for {n} elements"))),
        }
    };
    if name == "crease" {
        if ints.len() < 2 {
            return Err(parse_err(file, ln, "crease tag: needs two vertex ids (0-based) and a sharpness"));
        }
        for k in 0..ints.len() - 1 {
            let s = per(k, ints.len() - 1)?;
            raw.tags.creases.push(CreaseTag { v0: ints[k], v1: ints[k + 1], sharpness: s });
            raw.crease_lines.push(ln as u32);
        }
    } else {
        if ints.is_empty() {
            return Err(parse_err(file, ln, "corner tag: needs a vertex id (0-based) and a sharpness"));
        }
        for (k, &v) in ints.iter().enumerate() {
            raw.tags.corners.push(CornerTag { vertex: v, sharpness: per(k, ints.len())? });
            raw.corner_lines.push(ln as u32);
        }
    }
    Ok(())
}

/// The tags of `raw` applied to `mesh` (built from `raw` with `used`
/// records kept in order), errors at the tag's line.
fn apply_tags(mesh: Mesh, raw_tags: &Tags, lines: (&[u32], &[u32]), used: &[bool], file: &str) -> Result<Mesh> {
    if raw_tags.is_empty() {
        return Ok(mesh);
    }
    let (crease_lines, corner_lines) = lines;
    let line_of = |i: usize| {
        (if i < crease_lines.len() { crease_lines[i] } else { corner_lines[i - crease_lines.len()] }) as usize
    };
    // record id -> vertex id (the build keeps the used records in order)
    let mut new_id = vec![u32::MAX; used.len()];
    let mut next = 0;
    for (i, &u) in used.iter().enumerate() {
        if u {
            new_id[i] = next;
            next += 1;
        }
    }
    let map = |i: usize, v: u32| -> Result<u32> {
        match new_id.get(v as usize) {
            Some(&x) if x != u32::MAX => Ok(x),
            Some(_) => Err(parse_err(file, line_of(i), format!("tag: vertex {v} is used by no face"))),
            None => Err(parse_err(
                file,
                line_of(i),
                format!("tag: vertex {v} does not exist ({} vertices, ids are 0-based)", used.len()),
            )),
        }
    };
    let mut tags = Tags::default();
    for (i, t) in raw_tags.creases.iter().enumerate() {
        tags.creases.push(CreaseTag { v0: map(i, t.v0)?, v1: map(i, t.v1)?, ..*t });
    }
    for (j, t) in raw_tags.corners.iter().enumerate() {
        tags.corners.push(CornerTag { vertex: map(crease_lines.len() + j, t.vertex)?, ..*t });
    }
    let Mesh { ct, positions } = mesh;
    let ct = ct.with_tags(&tags).map_err(|e| match e {
        MeshError::BadTag { index, msg } => parse_err(file, line_of(index), msg),
        other => Error::Mesh { file: file.to_string(), line: None, source: other },
    })?;
    Ok(Mesh { ct, positions })
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
fn vertex_record<'a>(raw: &mut RawObj, mut toks: impl Iterator<Item = &'a str>, at: Loc) -> Result<()> {
    let Loc { file, ln } = at;
    let xyz: [f32; 3] = floats(&mut toks, file, ln, "vertex")?;
    if xyz.iter().any(|x| !x.is_finite()) {
        return Err(Error::Mesh {
            file: file.into(),
            line: Some(ln),
            source: MeshError::NonFinite { vertex: raw.positions.len() + 1 },
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
        if raw.colors.len() == raw.positions.len() {
            raw.colors.push(Vec3::from_array(rgb).clamp(Vec3::ZERO, Vec3::ONE));
        }
    }
    raw.positions.push(Vec3::from_array(xyz));
    raw.vertex_lines.push(ln as u32);
    Ok(())
}

/// A `vt u v [w]` record.
fn texture_record<'a>(raw: &mut RawObj, mut toks: impl Iterator<Item = &'a str>, at: Loc) -> Result<()> {
    let uv: [f32; 2] = floats(&mut toks, at.file, at.ln, "texture coordinate")?;
    if uv.iter().any(|x| !x.is_finite()) {
        return Err(parse_err(at.file, at.ln, "texture coordinate is not finite"));
    }
    raw.uvs.push(Vec2::from_array(uv));
    Ok(())
}

/// The corners of the face record being read (reused between records).
#[derive(Default)]
struct Polygon {
    /// Vertex ids, 0-based.
    v: Vec<u32>,
    /// `vt` ids, [`NO_UV`] where a corner has none.
    uv: Vec<u32>,
}

/// An `f v[/vt[/vn]] ...` record, triangulated as a fan.
fn face_record<'a>(raw: &mut RawObj, poly: &mut Polygon, toks: impl Iterator<Item = &'a str>, at: Loc) -> Result<()> {
    let Loc { file, ln } = at;
    poly.v.clear();
    poly.uv.clear();
    for t in toks {
        let mut parts = t.split('/');
        let idx = parts.next().unwrap_or("");
        poly.uv.push(match parts.next().filter(|x| !x.is_empty()) {
            None => NO_UV,
            Some(vt) => texture_index(vt, t, raw.uvs.len(), at)?,
        });
        poly.v.push(vertex_index(idx, t, raw, at)?);
    }
    if poly.v.len() < 3 {
        return Err(parse_err(file, ln, format!("face has {} vertices, needs at least 3", poly.v.len())));
    }
    if poly.v.len() > 3 {
        raw.polygons += 1;
    }
    let (pv, puv) = (&poly.v, &poly.uv);
    for k in 1..pv.len() - 1 {
        raw.triangles.extend_from_slice(&[pv[0], pv[k], pv[k + 1]]);
        raw.corner_uv.extend_from_slice(&[puv[0], puv[k], puv[k + 1]]);
        raw.triangle_lines.push(ln as u32);
    }
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
fn vertex_index(idx: &str, t: &str, raw: &RawObj, at: Loc) -> Result<u32> {
    let i: i64 = idx.parse().map_err(|_| parse_err(at.file, at.ln, format!("'{t}' is not a vertex index")))?;
    let n = raw.positions.len() as i64;
    let abs = if i < 0 { n + i } else { i - 1 };
    if i == 0 || abs < 0 || abs >= u32::MAX as i64 {
        return Err(Error::Mesh {
            file: at.file.into(),
            line: Some(at.ln),
            source: MeshError::IndexOutOfRange { face: raw.triangle_lines.len(), index: i, len: n as usize },
        });
    }
    Ok(abs as u32)
}

/// Loads and validates an OBJ file.
///
/// # Errors
/// I/O errors, [`Error::Parse`], and [`Error::Mesh`] with the line of the
/// offending face or vertex record.
pub fn load(path: &Path) -> Result<(Mesh, ObjInfo)> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    from_bytes(&bytes, &path.display().to_string())
}

/// Parses and validates OBJ bytes (see [`load`]); `file` names the source in errors.
///
/// # Errors
/// See [`load`].
pub fn from_bytes(bytes: &[u8], file: &str) -> Result<(Mesh, ObjInfo)> {
    let raw = parse(bytes, file)?;
    build(raw, file)
}

/// Loads an OBJ file and repairs it instead of refusing bad topology (see
/// [`crate::mesh::repair`](mod@crate::mesh::repair)). The report shows vertex ids 1-based, as the file
/// numbers them (`id_base` 1), and triangles 0-based, as error messages do.
///
/// # Errors
/// I/O errors and [`Error::Parse`] as [`load`]; [`Error::Mesh`] for an index
/// out of range, a non-finite coordinate, or no face left after repair.
pub fn load_repaired(path: &Path) -> Result<(Mesh, RepairReport)> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    from_bytes_repaired(&bytes, &path.display().to_string())
}

/// Parses and repairs OBJ bytes (see [`load_repaired`]).
///
/// # Errors
/// See [`load_repaired`].
pub fn from_bytes_repaired(bytes: &[u8], file: &str) -> Result<(Mesh, RepairReport)> {
    let raw = parse(bytes, file)?;
    let lines = raw.triangle_lines;
    let (mesh, mut report) = repair(raw.positions, &raw.triangles).map_err(|e| Error::Mesh {
        file: file.to_string(),
        line: e.face().and_then(|f| lines.get(f)).map(|&l| l as usize),
        source: e.shift_vertices(1),
    })?;
    report.id_base = 1;
    Ok((mesh, report))
}

/// Loads an OBJ with its attributes: per-corner texture coordinates (when
/// every face corner has a `vt`) and per-vertex colours (when every `v`
/// record has one), following the vertex renumbering of the build.
///
/// # Errors
/// See [`load`].
pub fn load_with_attributes(path: &Path) -> Result<(Mesh, Attributes)> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    from_bytes_with_attributes(&bytes, &path.display().to_string())
}

/// [`load_with_attributes`] on bytes; `file` names the source in errors.
///
/// # Errors
/// See [`load`].
pub fn from_bytes_with_attributes(bytes: &[u8], file: &str) -> Result<(Mesh, Attributes)> {
    let mut raw = parse(bytes, file)?;
    let uv = (!raw.corner_uv.is_empty() && raw.corner_uv.iter().all(|&j| j != NO_UV))
        .then(|| raw.corner_uv.iter().map(|&j| raw.uvs[j as usize]).collect::<Vec<_>>());
    let colors =
        (raw.colors.len() == raw.positions.len() && !raw.colors.is_empty()).then(|| std::mem::take(&mut raw.colors));
    let used = used_records(raw.positions.len(), &raw.triangles);
    let materials = material_groups(&mut raw, file);
    let (mesh, _) = build(raw, file)?;
    // the build keeps used vertices in record order
    let colors = colors.map(|c| c.into_iter().zip(&used).filter(|(_, u)| **u).map(|(c, _)| c).collect());
    Ok((mesh, Attributes { uv, colors, materials }))
}

/// The material groups of an OBJ that has `usemtl` records: `Kd` and
/// `map_Kd` of each material read from its `mtllib` files through tobj
/// (relative to the OBJ's directory). A library that cannot be read, or a
/// material it lacks, is a warning in the log, not an error: that material
/// is drawn grey. Faces before the first `usemtl` get a material `default`.
fn material_groups(raw: &mut RawObj, file: &str) -> Option<MaterialGroups> {
    if raw.material_names.is_empty() {
        return None;
    }
    let mut face = std::mem::take(&mut raw.face_material);
    let mut names = std::mem::take(&mut raw.material_names);
    if face.contains(&NO_MATERIAL) {
        names.push("default".into());
        let d = names.len() as u32 - 1;
        face.iter_mut().filter(|m| **m == NO_MATERIAL).for_each(|m| *m = d);
    }
    let dir = Path::new(file).parent().unwrap_or(Path::new("."));
    let mut found: Vec<(tobj::Material, PathBuf)> = Vec::new();
    for lib in &raw.mtllibs {
        let path = dir.join(lib);
        match tobj::load_mtl(&path) {
            Ok((mats, _)) => found.extend(mats.into_iter().map(|m| (m, path.clone()))),
            Err(e) => log::warn!("{file}: mtllib {}: {e}", path.display()),
        }
    }
    let list = names
        .iter()
        .map(|n| match found.iter().find(|(m, _)| &m.name == n) {
            Some((m, lib)) => Material {
                name: n.clone(),
                diffuse: m.diffuse.map_or(Vec3::splat(0.8), Vec3::from),
                diffuse_texture: m
                    .diffuse_texture
                    .as_ref()
                    .map(|t| lib.parent().unwrap_or(Path::new(".")).join(t.trim())),
            },
            None => {
                if n != "default" {
                    log::warn!("{file}: material '{n}' is in no mtllib that could be read; drawn grey");
                }
                Material::named(n)
            }
        })
        .collect();
    Some(MaterialGroups { face, list, libraries: std::mem::take(&mut raw.mtllibs) })
}

/// Which of `n` vertex records some triangle uses.
fn used_records(n: usize, triangles: &[u32]) -> Vec<bool> {
    let mut u = vec![false; n];
    for &i in triangles {
        if let Some(slot) = u.get_mut(i as usize) {
            *slot = true;
        }
    }
    u
}

/// Validates parsed OBJ content into a mesh, mapping errors to source lines.
///
/// # Errors
/// [`Error::Mesh`] naming the file and line.
pub fn build(raw: RawObj, file: &str) -> Result<(Mesh, ObjInfo)> {
    let nrec = raw.positions.len();
    let polygons = raw.polygons;
    let used = if raw.tags.is_empty() { Vec::new() } else { used_records(nrec, &raw.triangles) };
    match Mesh::from_triangles_report(raw.positions, &raw.triangles) {
        Ok((mesh, rep)) => Ok((
            apply_tags(mesh, &raw.tags, (&raw.crease_lines, &raw.corner_lines), &used, file)?,
            ObjInfo { vertex_records: nrec, unreferenced: rep.unreferenced, polygons_triangulated: polygons },
        )),
        Err(e) => {
            let line = e
                .face()
                .and_then(|f| raw.triangle_lines.get(f))
                .or_else(|| e.vertex().and_then(|v| raw.vertex_lines.get(v)))
                .map(|&l| l as usize);
            Err(Error::Mesh {
                file: file.to_string(),
                line,
                // messages use the file's own 1-based vertex numbering
                source: e.shift_vertices(1),
            })
        }
    }
}

/// Reads an OBJ through `tobj` (one model per group, renumbered per group),
/// returning every model's positions and triangles concatenated. Used as an
/// independent reference for [`parse`] in tests.
///
/// # Errors
/// tobj's load error as [`Error::Parse`] (without a line: tobj has none).
pub fn load_tobj(path: &Path) -> Result<(Vec<Vec3>, Vec<u32>)> {
    let opts = tobj::LoadOptions { triangulate: true, single_index: false, ..Default::default() };
    let (models, _) =
        tobj::load_obj(path, &opts).map_err(|e| parse_err(&path.display().to_string(), 0, e.to_string()))?;
    let mut pos = Vec::new();
    let mut tris = Vec::new();
    for m in models {
        let base = pos.len() as u32;
        pos.extend(m.mesh.positions.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])));
        tris.extend(m.mesh.indices.iter().map(|&i| i + base));
    }
    Ok((pos, tris))
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

/// Formats OBJ text for `mesh` in parallel chunks and passes them, in order,
/// to `sink`: a helper thread formats the next chunks while this one writes.
///
/// # Errors
/// The first error of `sink`.
pub fn write_obj(mesh: &Mesh, sink: &mut dyn FnMut(&[u8]) -> Result<()>) -> Result<()> {
    const ROWS: usize = 1 << 15;
    let pos = &mesh.positions;
    let header = format!("# subdiv: {} vertices, {} triangles\n", pos.len(), mesh.ct.num_triangles());
    let vchunks: Vec<&[Vec3]> = pos.chunks(ROWS).collect();
    let tchunks: Vec<&[u32]> = mesh.ct.v_table().chunks(3 * ROWS).collect();
    let nv = vchunks.len();
    let text = |k: usize| if k < nv { vertex_text(vchunks[k]) } else { face_text(tchunks[k - nv]) };
    crate::io::write_formatted(&[header.as_bytes()], nv + tchunks.len(), text, sink)?;
    sink(&tag_records(mesh))
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

/// `f a b c` lines (1-based) of V-table triples.
fn face_text(ch: &[u32]) -> Vec<u8> {
    text::triple_lines(b"f ", ch, |line, v| line.put_u32(v.wrapping_add(1)))
}

/// The mesh's sharpness as OBJ tag records (OpenSubdiv's `t crease 2/1/0 a b
/// s` and `t corner 1/1/0 v s`, 0-based ids), so a file round-trips.
pub fn tag_records(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::new();
    let Some(s) = mesh.ct.sharpness() else { return out };
    let tags = s.to_tags(&mesh.ct);
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

/// Formats OBJ text for `mesh` with its attributes: `v x y z r g b` when
/// there are colours, one `vt` per corner and `f a/ta b/tb c/tc` when there
/// are texture coordinates, the `mtllib` records and a `usemtl` wherever the
/// material changes when there are material groups. Without attributes this
/// is [`write_obj`].
///
/// # Errors
/// The first error of `sink`.
pub fn write_obj_with(mesh: &Mesh, attrs: &Attributes, sink: &mut dyn FnMut(&[u8]) -> Result<()>) -> Result<()> {
    if attrs.is_empty() {
        return write_obj(mesh, sink);
    }
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
    let header = format!("# subdiv: {} vertices, {} triangles\n", mesh.positions.len(), mesh.ct.num_triangles());
    record(&mut out, &mut |o| o.extend_from_slice(header.as_bytes()))?;
    let colors = attrs.colors.as_ref().filter(|c| c.len() == mesh.positions.len());
    for (i, q) in mesh.positions.iter().enumerate() {
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
    let mats = attrs.materials.as_ref().filter(|m| m.face.len() == mesh.ct.num_triangles());
    for lib in mats.map(|m| m.libraries.as_slice()).unwrap_or_default() {
        record(&mut out, &mut |o| o.extend_from_slice(format!("mtllib {lib}\n").as_bytes()))?;
    }
    let uv = attrs.uv.as_ref().filter(|u| u.len() == mesh.ct.v_table().len());
    for t in uv.into_iter().flatten() {
        record(&mut out, &mut |o| {
            o.extend_from_slice(b"vt");
            for x in [t.x, t.y] {
                o.push(b' ');
                push_f32(o, &mut rb, x);
            }
            o.push(b'\n');
        })?;
    }
    let mut current = u32::MAX;
    for (t, tri) in mesh.ct.v_table().chunks_exact(3).enumerate() {
        if let Some(m) = mats
            && m.face[t] != current
        {
            current = m.face[t];
            let name = m.list.get(current as usize).map_or("default", |x| x.name.as_str());
            record(&mut out, &mut |o| o.extend_from_slice(format!("usemtl {name}\n").as_bytes()))?;
        }
        record(&mut out, &mut |o| {
            o.push(b'f');
            for (k, v) in tri.iter().enumerate() {
                o.push(b' ');
                o.extend_from_slice(ib.format(v + 1).as_bytes());
                if uv.is_some() {
                    // one vt per corner, in corner order
                    o.push(b'/');
                    o.extend_from_slice(ib.format(3 * t + k + 1).as_bytes());
                }
            }
            o.push(b'\n');
        })?;
    }
    out.extend_from_slice(&tag_records(mesh));
    sink(&out)
}

/// Saves `mesh` with its attributes as OBJ (atomically).
///
/// # Errors
/// I/O errors naming `path`.
pub fn save_with(path: &Path, mesh: &Mesh, attrs: &Attributes) -> Result<()> {
    crate::io::atomic_write(path, |w| {
        write_obj_with(mesh, attrs, &mut |b| w.write_all(b).map_err(|e| Error::io(path, e)))
    })
}

/// Saves `mesh` as OBJ (atomically).
///
/// # Errors
/// I/O errors naming `path`.
pub fn save(path: &Path, mesh: &Mesh) -> Result<()> {
    atomic_write(path, |w| write_obj(mesh, &mut |b| w.write_all(b).map_err(|e| Error::io(path, e))))
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
        assert_eq!(String::from_utf8(face_text(&v)).unwrap(), expected);
    }

    #[test]
    fn the_first_error_in_the_file_is_reported_invalid_utf8_included() {
        let line_of = |bytes: &[u8]| match parse(bytes, "m.obj") {
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
        let raw = parse(b"v 0 0 0 # a comment\r\nv 1 0 0\r\nv 0 1 0#x\nf 1 2 3\r\n", "m.obj").expect("valid");
        assert_eq!((raw.positions.len(), raw.triangles.len()), (3, 3));
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
