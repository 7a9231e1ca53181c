//! PLY (Stanford polygon files): ASCII, binary little endian and binary big
//! endian in; binary little endian out (float `x y z`, `uchar red green blue`
//! when the mesh has colours, faces as `uchar` count + `int` indices).
//!
//! Read: the `vertex` element's `x y z`, colours (`red green blue` or `r g b`,
//! integers scaled by 1/255, floats as they are), per-vertex texture
//! coordinates (`u v`, `s t` or `texture_u texture_v`, carried per corner);
//! the `face` element's `vertex_indices` (or `vertex_index`) lists, polygons
//! kept, and its `texcoord` lists (MeshLab's per-corner texture coordinates,
//! two values a corner). Other elements and properties, lists of floats
//! included, are skipped. A list count must be a whole number. Every
//! count in the header is checked against the bytes that follow before
//! anything is allocated; errors name the file and the element
//! (`vertex 12`, `face 3`, `header line 4`).
//!
//! Hand-written rather than through `ply-rs`: that crate has had no release
//! since 2020, allocates what the header claims and panics on some
//! malformed input; this reader is 300 lines with none of those.

use super::raw::{RawMesh, check_count, format_err};
use super::{Format, Input, Keeps};
use crate::mesh::Mesh;
use crate::{Error, Result};
use glam::{Vec2, Vec3};
use std::borrow::Cow;
use std::path::Path;

/// A scalar type of the header.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Ty {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Ty {
    fn parse(s: &str) -> Option<Ty> {
        Some(match s {
            "char" | "int8" => Ty::I8,
            "uchar" | "uint8" => Ty::U8,
            "short" | "int16" => Ty::I16,
            "ushort" | "uint16" => Ty::U16,
            "int" | "int32" => Ty::I32,
            "uint" | "uint32" => Ty::U32,
            "float" | "float32" => Ty::F32,
            "double" | "float64" => Ty::F64,
            _ => return None,
        })
    }
    fn size(self) -> usize {
        match self {
            Ty::I8 | Ty::U8 => 1,
            Ty::I16 | Ty::U16 => 2,
            Ty::I32 | Ty::U32 | Ty::F32 => 4,
            Ty::F64 => 8,
        }
    }
    fn is_int(self) -> bool {
        !matches!(self, Ty::F32 | Ty::F64)
    }
}

#[derive(Clone, Debug)]
struct Property {
    name: String,
    ty: Ty,
    /// `Some(count type)` for a list property.
    list: Option<Ty>,
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: u64,
    props: Vec<Property>,
}

impl Element {
    /// The fewest bytes one record can take in `enc`: a list's count, and
    /// for the face list (which needs 3 or more) three indices after it.
    fn min_bytes(&self, enc: Encoding) -> u64 {
        let face_list = self.face_list();
        let bytes = self.props.iter().enumerate().map(|(k, p)| {
            let items = if Some(k) == face_list { 3 } else { 0 };
            match (enc, p.list) {
                // a value and a separator each
                (Encoding::Ascii, _) => 2 * (1 + items),
                (_, None) => p.ty.size() as u64,
                (_, Some(ct)) => ct.size() as u64 + items * p.ty.size() as u64,
            }
        });
        bytes.sum::<u64>().max(1)
    }
    /// The `face` element's index list (`vertex_indices` or `vertex_index`).
    fn face_list(&self) -> Option<usize> {
        if self.name != "face" {
            return None;
        }
        self.props.iter().position(|p| p.list.is_some() && p.name.starts_with("vertex_ind"))
    }
    fn index(&self, names: &[&str]) -> Option<usize> {
        self.props.iter().position(|p| p.list.is_none() && names.contains(&p.name.as_str()))
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Encoding {
    Ascii,
    Little,
    Big,
}

/// The parsed header and where the body starts.
struct Header {
    enc: Encoding,
    elements: Vec<Element>,
    body: usize,
}

/// The PLY row of [`super::FORMATS`].
pub(crate) const FORMAT: Format = Format {
    name: "Stanford PLY",
    extensions: &["ply"],
    sniff: |b| b.starts_with(b"ply"),
    reader: Some(read),
    writer: Some(|path, mesh, attrs| save_with(path, mesh, attrs.colors.as_deref())),
    written_as: &["ply"],
    poly_writer: Some(|path, mesh, attrs| save_poly(path, mesh, attrs.colors.as_deref())),
    faces_writer: Some(|path, positions, corners, sides, attrs| {
        write(path, positions, attrs.colors.as_deref(), &Faces::Fixed(corners, sides))
    }),
    keeps: Keeps { uv: false, colors: true, materials: false, creases: false, holes: false },
};

/// The header: lines up to the first line that is `end_header` (a comment
/// that mentions it does not end it).
fn parse_header(bytes: &[u8], file: &str) -> Result<Header> {
    let mut lines = Vec::new();
    let mut at = 0usize;
    let body = loop {
        let Some(rest) = bytes.get(at..).filter(|r| !r.is_empty()) else {
            return Err(format_err(file, "header", "no end_header line"));
        };
        let len = rest.iter().position(|&b| b == b'\n').map_or(rest.len(), |i| i + 1);
        let line = std::str::from_utf8(&rest[..len]).map_err(|_| format_err(file, "header", "not text"))?;
        at += len;
        if line.trim() == "end_header" {
            break at;
        }
        lines.push(line);
    };
    let mut lines = lines.into_iter().enumerate();
    if lines.next().map(|(_, l)| l.trim()) != Some("ply") {
        return Err(format_err(file, "header line 1", "not a PLY file (no 'ply' magic)"));
    }
    let (mut enc, mut elements) = (None, Vec::<Element>::new());
    for (i, line) in lines {
        let at = || format!("header line {}", i + 1);
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.as_slice() {
            [] | ["comment", ..] | ["obj_info", ..] => {}
            ["format", f, _] => {
                enc = Some(match *f {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::Little,
                    "binary_big_endian" => Encoding::Big,
                    other => return Err(format_err(file, at(), format!("unknown format '{other}'"))),
                })
            }
            ["element", name, count] => {
                let count = count.parse().map_err(|_| format_err(file, at(), format!("bad count '{count}'")))?;
                // a second vertex or face element would be read over the first
                if matches!(*name, "vertex" | "face") && elements.iter().any(|e| e.name == *name) {
                    return Err(format_err(file, at(), format!("a second 'element {name}' (only one is allowed)")));
                }
                elements.push(Element { name: name.to_string(), count, props: Vec::new() });
            }
            ["property", "list", ct, ty, name] => {
                let (Some(ct), Some(ty)) = (Ty::parse(ct), Ty::parse(ty)) else {
                    return Err(format_err(file, at(), format!("unknown list types '{ct} {ty}'")));
                };
                if !ct.is_int() {
                    return Err(format_err(file, at(), "a list's count must be an integer type"));
                }
                let el = elements.last_mut().ok_or_else(|| format_err(file, at(), "property before any element"))?;
                if el.name == "face" && name.starts_with("vertex_ind") && !ty.is_int() {
                    return Err(format_err(file, at(), "vertex indices must be integers"));
                }
                el.props.push(Property { name: name.to_string(), ty, list: Some(ct) });
            }
            ["property", ty, name] => {
                let ty = Ty::parse(ty).ok_or_else(|| format_err(file, at(), format!("unknown type '{ty}'")))?;
                let el = elements.last_mut().ok_or_else(|| format_err(file, at(), "property before any element"))?;
                el.props.push(Property { name: name.to_string(), ty, list: None });
            }
            _ => return Err(format_err(file, at(), format!("cannot read '{}'", line.trim()))),
        }
    }
    let enc = enc.ok_or_else(|| format_err(file, "header", "no format line"))?;
    Ok(Header { enc, elements, body })
}

/// Reads values of the body one at a time.
struct Body<'a> {
    bytes: &'a [u8],
    pos: usize,
    enc: Encoding,
}

impl Body<'_> {
    fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    fn value(&mut self, ty: Ty) -> Option<f64> {
        if self.enc == Encoding::Ascii {
            return self.token()?.parse().ok();
        }
        let n = ty.size();
        let b = self.bytes.get(self.pos..self.pos + n)?;
        self.pos += n;
        let mut a = [0u8; 8];
        a[..n].copy_from_slice(b);
        if self.enc == Encoding::Big {
            a[..n].reverse();
        }
        Some(match ty {
            Ty::I8 => f64::from(a[0] as i8),
            Ty::U8 => f64::from(a[0]),
            Ty::I16 => f64::from(i16::from_le_bytes([a[0], a[1]])),
            Ty::U16 => f64::from(u16::from_le_bytes([a[0], a[1]])),
            Ty::I32 => f64::from(i32::from_le_bytes([a[0], a[1], a[2], a[3]])),
            Ty::U32 => f64::from(u32::from_le_bytes([a[0], a[1], a[2], a[3]])),
            Ty::F32 => f64::from(f32::from_le_bytes([a[0], a[1], a[2], a[3]])),
            Ty::F64 => f64::from_le_bytes(a),
        })
    }

    fn token(&mut self) -> Option<&str> {
        let rest = &self.bytes[self.pos..];
        let start = rest.iter().position(|b| !b.is_ascii_whitespace())?;
        let len = rest[start..].iter().position(|b| b.is_ascii_whitespace()).unwrap_or(rest.len() - start);
        self.pos += start + len;
        std::str::from_utf8(&rest[start..start + len]).ok()
    }
}

/// Reads a PLY file's faces with colours and texture coordinates.
///
/// # Errors
/// [`crate::Error::Format`] naming the file and the element: a bad header, a count
/// the file cannot hold, a truncated or unreadable record, a face with fewer
/// than 3 vertices or an index out of range; over the budget.
fn read(input: &Input) -> Result<RawMesh> {
    let (bytes, file) = (input.bytes, input.file);
    let h = parse_header(bytes, file)?;
    let mut body = Body { bytes, pos: h.body, enc: h.enc };
    let mut raw = RawMesh::default();
    let mut vertex_uv: Option<Vec<Vec2>> = None;
    // the last ASCII record needs no separator after it
    let slack = usize::from(h.enc == Encoding::Ascii);
    for el in &h.elements {
        let count = check_count(file, &el.name, el.count, el.min_bytes(h.enc), body.remaining() + slack)?;
        match el.name.as_str() {
            "vertex" => {
                input.budget.take_vertices(count as u64, file, "element vertex")?;
                read_vertices(&mut body, el, count, file, &mut raw, &mut vertex_uv)?;
            }
            "face" => {
                input.budget.take_faces(count as u64, file, "element face")?;
                read_faces(&mut body, el, count, input, &mut raw)?;
            }
            _ => {
                for r in 0..count {
                    record(&mut body, el, file, r, |_, _| Ok(()))?;
                }
            }
        }
    }
    let nv = raw.positions.len();
    if let Some(&bad) = raw.corners.iter().find(|&&i| i as usize >= nv) {
        return Err(format_err(file, "face", format!("vertex index {bad}, but there are only {nv} vertices")));
    }
    if let (Some(uv), None) = (vertex_uv, &raw.uv) {
        raw.uv = Some(raw.corners.iter().map(|&i| uv[i as usize]).collect());
    }
    Ok(raw)
}

/// Reads one record of `el`, calling `f(property index, values)` for each
/// property (one value, or a list's values).
fn record(
    body: &mut Body,
    el: &Element,
    file: &str,
    r: usize,
    mut f: impl FnMut(usize, &[f64]) -> Result<()>,
) -> Result<()> {
    let at = || format!("{} {r}", el.name);
    let mut list = Vec::new();
    for (k, p) in el.props.iter().enumerate() {
        let bad = || format_err(file, at(), format!("property '{}': truncated or not a number", p.name));
        match p.list {
            None => f(k, &[body.value(p.ty).ok_or_else(bad)?])?,
            Some(ct) => {
                let n = body.value(ct).ok_or_else(bad)?;
                if n < 0.0 || n.fract() != 0.0 {
                    let msg = format!("property '{}': list count {n} is not a whole number", p.name);
                    return Err(format_err(file, at(), msg));
                }
                let n = check_count(file, &at(), n as u64, p.ty.size().min(2) as u64, body.remaining())?;
                list.clear();
                for _ in 0..n {
                    list.push(body.value(p.ty).ok_or_else(bad)?);
                }
                f(k, &list)?;
            }
        }
    }
    Ok(())
}

fn read_vertices(
    body: &mut Body,
    el: &Element,
    count: usize,
    file: &str,
    raw: &mut RawMesh,
    uv_out: &mut Option<Vec<Vec2>>,
) -> Result<()> {
    let xyz = [el.index(&["x"]), el.index(&["y"]), el.index(&["z"])];
    let [Some(x), Some(y), Some(z)] = xyz else {
        return Err(format_err(file, "vertex", "needs properties x, y and z"));
    };
    let rgb = [el.index(&["red", "r"]), el.index(&["green", "g"]), el.index(&["blue", "b"])];
    let rgb = match rgb {
        [Some(r), Some(g), Some(b)] => Some([r, g, b]),
        _ => None,
    };
    let scale: Option<f32> = rgb.map(|[r, ..]| if el.props[r].ty.is_int() { 255.0 } else { 1.0 });
    let uv = match [el.index(&["u", "s", "texture_u"]), el.index(&["v", "t", "texture_v"])] {
        [Some(u), Some(v)] => Some([u, v]),
        _ => None,
    };
    raw.positions.reserve_exact(count);
    // double properties are kept in f64 as well (for double precision)
    let doubles = [x, y, z].iter().any(|&k| el.props[k].ty == Ty::F64);
    let mut colors = rgb.map(|_| Vec::with_capacity(count));
    let mut uvs = uv.map(|_| Vec::with_capacity(count));
    let mut vals = vec![0.0f64; el.props.len()];
    for r in 0..count {
        record(body, el, file, r, |k, v| {
            vals[k] = v.first().copied().unwrap_or(0.0);
            Ok(())
        })?;
        let p = Vec3::new(vals[x] as f32, vals[y] as f32, vals[z] as f32);
        if !p.is_finite() {
            return Err(format_err(file, format!("vertex {r}"), "non-finite coordinate"));
        }
        raw.positions.push(p);
        if doubles {
            raw.precise.push(glam::DVec3::new(vals[x], vals[y], vals[z]));
        }
        if let (Some(c), Some([ri, gi, bi]), Some(s)) = (&mut colors, rgb, scale) {
            c.push((Vec3::new(vals[ri] as f32, vals[gi] as f32, vals[bi] as f32) / s).clamp(Vec3::ZERO, Vec3::ONE));
        }
        if let (Some(t), Some([ui, vi])) = (&mut uvs, uv) {
            t.push(Vec2::new(vals[ui] as f32, vals[vi] as f32));
        }
    }
    raw.colors = colors;
    *uv_out = uvs;
    Ok(())
}

fn read_faces(body: &mut Body, el: &Element, count: usize, input: &Input, raw: &mut RawMesh) -> Result<()> {
    let file = input.file;
    let Some(k) = el.face_list() else {
        return Err(format_err(file, "face", "needs a list property vertex_indices"));
    };
    let texcoord = el.props.iter().position(|p| p.list.is_some() && p.name == "texcoord");
    let mut uv: Option<Vec<Vec2>> = texcoord.map(|_| Vec::new());
    raw.corners.reserve(count.saturating_mul(3));
    let (mut idx, mut uv_values) = (Vec::new(), Vec::new());
    for r in 0..count {
        record(body, el, file, r, |j, v| {
            if Some(j) == texcoord {
                uv_values.clear();
                uv_values.extend_from_slice(v);
                return Ok(());
            }
            if j != k {
                return Ok(());
            }
            if v.len() < 3 {
                return Err(format_err(file, format!("face {r}"), format!("{} vertices (3 or more needed)", v.len())));
            }
            input.budget.check("face-size", v.len() as u64, file, &format!("face {r}"))?;
            if let Some(bad) = v.iter().find(|&&i| !(0.0..u32::MAX as f64).contains(&i) || i.fract() != 0.0) {
                return Err(format_err(file, format!("face {r}"), format!("bad vertex index {bad}")));
            }
            idx.clear();
            idx.extend(v.iter().map(|&i| i as u32));
            Ok(())
        })?;
        raw.push_face(&idx);
        if let Some(out) = &mut uv {
            if uv_values.len() != 2 * idx.len() {
                let msg = format!("texcoord has {} values for {} corners (2 each needed)", uv_values.len(), idx.len());
                return Err(format_err(file, format!("face {r}"), msg));
            }
            out.extend(uv_values.chunks_exact(2).map(|c| Vec2::new(c[0] as f32, c[1] as f32)));
        }
    }
    raw.uv = uv;
    Ok(())
}

/// Saves `mesh` as binary PLY, with per-vertex colours when given (one per
/// vertex, linear RGB in [0, 1], stored as `uchar`).
///
/// # Errors
/// I/O errors naming `path`.
pub(crate) fn save_with(path: &Path, mesh: &Mesh, colors: Option<&[Vec3]>) -> Result<()> {
    write(path, &mesh.positions, colors, &Faces::Fixed(mesh.ct.v_table(), 3))
}

/// [`save_with`] of a polygon mesh: one list record per polygon.
///
/// # Errors
/// I/O errors naming `path`; a face of more than 255 corners (a `uchar` count).
pub(crate) fn save_poly(path: &Path, mesh: &crate::mesh::poly::PolyMesh, colors: Option<&[Vec3]>) -> Result<()> {
    let pt = &mesh.pt;
    if let Some(f) = (0..pt.num_faces() as u32).find(|&f| pt.face_size(f) > 255) {
        let msg = format!("face {f} has {} corners, more than a PLY uchar count holds", pt.face_size(f));
        return Err(Error::Usage(format!("{}: {msg}", path.display())));
    }
    // the offset of every chunk of faces: a prefix sum of record sizes
    let chunks = pt.num_faces().div_ceil(FACE_ROWS);
    let mut starts = Vec::with_capacity(chunks + 1);
    let mut at = 0u64;
    for k in 0..chunks {
        starts.push(at);
        let faces = (k * FACE_ROWS) as u32..(((k + 1) * FACE_ROWS).min(pt.num_faces())) as u32;
        at += faces.map(|f| 1 + 4 * u64::from(pt.face_size(f))).sum::<u64>();
    }
    write(path, &mesh.positions, colors, &Faces::Polygons(pt, &starts))
}

/// The faces [`write`] writes: triangles (13-byte records) or polygons
/// (with the byte offset of every chunk of [`FACE_ROWS`] faces).
enum Faces<'a> {
    /// Faces of as many corners each (3: triangles).
    Fixed(&'a [u32], usize),
    Polygons(&'a crate::mesh::poly::PolyTable, &'a [u64]),
}

impl Faces<'_> {
    fn count(&self) -> usize {
        match self {
            Faces::Fixed(v, k) => v.len() / k,
            Faces::Polygons(pt, _) => pt.num_faces(),
        }
    }
    /// Chunk `k`'s offset among the face records, and its records.
    fn chunk(&self, k: usize) -> (u64, Vec<u8>) {
        let first = k * FACE_ROWS;
        let last = (first + FACE_ROWS).min(self.count());
        match self {
            &Faces::Fixed(v, k) => ((1 + 4 * k as u64) * first as u64, face_records(&v[k * first..k * last], k)),
            Faces::Polygons(pt, starts) => {
                let mut out = Vec::new();
                for f in first as u32..last as u32 {
                    let r = pt.face_corners(f);
                    out.push((r.end - r.start) as u8);
                    for c in r {
                        out.extend_from_slice(&pt.vtx(c).to_le_bytes());
                    }
                }
                (starts[k], out)
            }
        }
    }
}

/// Writes positions, colours and `faces` as binary PLY: every piece's
/// offset is known before any is made, so the pieces are made and written
/// in parallel (io::atomic_write_pieces).
fn write(path: &Path, positions: &[Vec3], colors: Option<&[Vec3]>, faces: &Faces) -> Result<()> {
    let colors = colors.filter(|c| c.len() == positions.len());
    let rgb = if colors.is_some() { "property uchar red\nproperty uchar green\nproperty uchar blue\n" } else { "" };
    let (nv, nf) = (positions.len(), faces.count());
    let header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment written by subdiv\nelement vertex {nv}\nproperty float x\nproperty float y\nproperty float z\n{rgb}element face {nf}\nproperty list uchar int vertex_indices\nend_header\n",
    );
    let vertex_size = if colors.is_some() { 15 } else { 12 };
    let (vertex_pieces, face_pieces) = (nv.div_ceil(VERTEX_ROWS), nf.div_ceil(FACE_ROWS));
    let faces_at = (header.len() + nv * vertex_size) as u64;
    let piece = |k: usize| -> (u64, Cow<'_, [u8]>) {
        if k == 0 {
            return (0, Cow::Borrowed(header.as_bytes()));
        }
        if k <= vertex_pieces {
            let first = (k - 1) * VERTEX_ROWS;
            let rows = first..(first + VERTEX_ROWS).min(nv);
            let at = (header.len() + first * vertex_size) as u64;
            return match colors {
                // little-endian f32 triples are the PLY records as they lie in memory
                None if cfg!(target_endian = "little") => (at, Cow::Borrowed(bytemuck::cast_slice(&positions[rows]))),
                _ => (at, Cow::Owned(vertex_records(&positions[rows.clone()], colors.map(|c| &c[rows])))),
            };
        }
        let (at, bytes) = faces.chunk(k - 1 - vertex_pieces);
        (faces_at + at, Cow::Owned(bytes))
    };
    crate::io::atomic_write_pieces(path, 1 + vertex_pieces + face_pieces, piece)
}

/// Vertex records one by one (colours, or a big-endian machine).
fn vertex_records(positions: &[Vec3], colors: Option<&[Vec3]>) -> Vec<u8> {
    let mut buf = Vec::with_capacity(positions.len() * if colors.is_some() { 15 } else { 12 });
    for (i, q) in positions.iter().enumerate() {
        for x in q.to_array() {
            buf.extend_from_slice(&x.to_le_bytes());
        }
        if let Some(c) = colors {
            buf.extend(c[i].to_array().map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8));
        }
    }
    buf
}

/// Vertices per piece of vertex records (about 1 MB).
const VERTEX_ROWS: usize = 1 << 16;

/// Triangles per chunk of face records.
const FACE_ROWS: usize = 1 << 16;

/// Face records (`k a b c ...`, `1 + 4 k` bytes: 13 for triangles) of
/// rows of `k` vertex ids (`k` from 3 to 255).
fn face_records(v: &[u32], k: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(v.len() / k * (1 + 4 * k));
    for face in v.chunks_exact(k) {
        if k <= 4 {
            // one fixed-size copy a record
            let mut rec = [k as u8; 17];
            for (j, &i) in face.iter().enumerate() {
                rec[1 + 4 * j..5 + 4 * j].copy_from_slice(&i.to_le_bytes());
            }
            out.extend_from_slice(&rec[..1 + 4 * k]);
        } else {
            out.push(k as u8);
            face.iter().for_each(|i| out.extend_from_slice(&i.to_le_bytes()));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_written_in_parallel_read_back_as_the_mesh_with_and_without_colours() {
        // more vertices and faces than one piece holds, and a partial last piece
        let m = crate::mesh::shapes::icosphere(7);
        assert!(m.positions.len() > 2 * VERTEX_ROWS && m.ct.num_triangles() > 2 * FACE_ROWS);
        let colors: Vec<Vec3> = m.positions.iter().map(|p| (*p * 0.5 + 0.5).clamp(Vec3::ZERO, Vec3::ONE)).collect();
        let dir = crate::io::TestDir::new("ply-pieces");
        for c in [None, Some(&colors[..])] {
            let path = dir.0.join("m.ply");
            save_with(&path, &m, c).expect("saved");
            let bytes = std::fs::read(&path).expect("read back");
            let raw = crate::io::raw_of(&bytes, "m.ply").expect("parsed");
            assert!(raw.positions == m.positions, "positions, colours {}", c.is_some());
            assert!(raw.corners == m.ct.v_table(), "triangles, colours {}", c.is_some());
            if let (Some(got), Some(want)) = (&raw.colors, c) {
                let byte = |x: f32| (x.clamp(0.0, 1.0) * 255.0).round();
                assert!(got.iter().zip(want).all(|(g, w)| (*g * 255.0).round() == w.to_array().map(byte).into()));
            } else {
                assert_eq!(raw.colors.is_some(), c.is_some());
            }
        }
    }
}
