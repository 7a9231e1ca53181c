//! OFF (Object File Format, Geomview) in and out: `OFF`, then vertex, face
//! and edge counts, the vertices, then each face as a count and indices
//! (polygons kept). The keyword's prefixes say what else each vertex line
//! holds (Geomview's `[ST][C][N]OFF`: a normal, a colour of 3 or 4 values,
//! integers 0..255 or floats 0..1, texture coordinates); colours are kept,
//! normals and texture coordinates read past; a 4-D or n-D file is refused.
//! Comments start with `#`. Lines after the counted faces are an error (a
//! header that undercounts would otherwise drop faces silently). Counts
//! are checked against the text that follows before anything is
//! allocated; errors name the file and line.

use super::atomic_write;
use super::raw::{RawMesh, check_count};
use super::text::{LONGEST, Line};
use super::{Format, Input, Keeps};
use crate::mesh::Mesh;
use crate::{Error, Result};
use glam::Vec3;
use std::path::Path;

/// The fewest bytes of a vertex line (`0 0 0` and a newline).
const MIN_VERTEX_BYTES: u64 = 6;
/// The fewest bytes of a face line (`3 0 1 2` and a newline).
const MIN_FACE_BYTES: u64 = 8;

/// The OFF row of [`super::FORMATS`].
pub(crate) const FORMAT: Format = Format {
    name: "OFF",
    extensions: &["off"],
    sniff: |b| {
        let head = b.trim_ascii_start();
        let magic = head.split(|c| c.is_ascii_whitespace()).next().unwrap_or(&[]);
        magic.ends_with(b"OFF") && magic.len() <= 8
    },
    reader: Some(read),
    writer: Some(|path, mesh, attrs| save_with(path, mesh, attrs.colors.as_deref())),
    written_as: &["off"],
    poly_writer: Some(|path, mesh, attrs| save_poly(path, mesh, attrs.colors.as_deref())),
    faces_writer: Some(|path, positions, corners, sides, attrs| {
        save_faces(path, positions, (corners, sides), attrs.colors.as_deref())
    }),
    keeps: Keeps { uv: false, colors: true, materials: false, creases: false, holes: false },
};

/// What the header's keyword says each vertex line holds besides `x y z`
/// (Geomview's `[ST][C][N][4][n]OFF`, in the order the values come:
/// normal, colour, texture coordinates).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Layout {
    normal: bool,
    color: bool,
    texture: bool,
}

/// The layout of the keyword `magic`; a 4-D or n-D file is refused.
fn layout(magic: &str) -> std::result::Result<Layout, String> {
    let mut rest = magic.strip_suffix("OFF").ok_or_else(|| format!("not an OFF file (starts with '{magic}')"))?;
    let mut l = Layout::default();
    for (prefix, flag) in [("ST", 0), ("C", 1), ("N", 2)] {
        if let Some(r) = rest.strip_prefix(prefix) {
            rest = r;
            match flag {
                0 => l.texture = true,
                1 => l.color = true,
                _ => l.normal = true,
            }
        }
    }
    match rest {
        "" => Ok(l),
        "4" | "n" | "4n" => Err(format!("'{magic}': vertices of more than 3 dimensions are not read")),
        _ => Err(format!("'{magic}' is not an OFF keyword ([ST][C][N]OFF)")),
    }
}

/// Reads an OFF file.
///
/// # Errors
/// [`Error::Parse`] naming the file and line; over the budget.
fn read(input: &Input) -> Result<RawMesh> {
    let (file, text) = (input.file, input.text()?);
    // non-empty lines without comments, with their line numbers
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.split('#').next().unwrap_or("").trim()))
        .filter(|(_, l)| !l.is_empty());
    let err = |line: usize, msg: String| Error::Parse { file: file.to_string(), line, msg };
    let (l0, first) = lines.next().ok_or_else(|| err(1, "empty file (no OFF header)".into()))?;
    let mut words: Vec<&str> = first.split_whitespace().collect();
    let magic = words.first().copied().unwrap_or("");
    let layout = layout(magic).map_err(|m| err(l0, m))?;
    words.remove(0);
    let (lc, counts) =
        if words.is_empty() { lines.next().ok_or_else(|| err(l0, "no counts".into()))? } else { (l0, "") };
    let counts: Vec<&str> = if counts.is_empty() { words } else { counts.split_whitespace().collect() };
    let num = |s: Option<&&str>| s.and_then(|s| s.parse::<u64>().ok());
    let (Some(nv), Some(nf)) = (num(counts.first()), num(counts.get(1))) else {
        return Err(err(lc, "expected 'vertices faces edges' counts".into()));
    };
    let rest = text.len();
    let nv = check_count(file, "vertices", nv, MIN_VERTEX_BYTES, rest)?;
    let nf = check_count(file, "faces", nf, MIN_FACE_BYTES, rest)?;
    // the vertices and the faces share the file: together they must fit
    let need = (nv as u64).checked_mul(MIN_VERTEX_BYTES).zip((nf as u64).checked_mul(MIN_FACE_BYTES));
    if need.and_then(|(v, f)| v.checked_add(f)).is_none_or(|n| n > rest as u64) {
        return Err(err(
            lc,
            format!(
                "the header claims {nv} vertices and {nf} faces, but the file has only {rest} bytes \
                 (at least {MIN_VERTEX_BYTES} a vertex and {MIN_FACE_BYTES} a face needed)"
            ),
        ));
    }
    input.budget.take_vertices(nv as u64, file, "header")?;
    input.budget.take_faces(nf as u64, file, "header")?;
    let mut raw = RawMesh { positions: Vec::with_capacity(nv), ..Default::default() };
    let mut colors = layout.color.then(|| Vec::with_capacity(nv));
    for v in 0..nv {
        let (l, line) = lines.next().ok_or_else(|| err(lc, format!("file ends at vertex {v} of {nv}")))?;
        let x: Vec<f32> = line
            .split_whitespace()
            .map(|t| t.parse::<f32>())
            .collect::<std::result::Result<_, _>>()
            .map_err(|_| err(l, format!("vertex {v}: not a number")))?;
        if x.len() < 3 || !x.iter().all(|c| c.is_finite()) {
            return Err(err(l, format!("vertex {v}: needs 3 finite coordinates")));
        }
        raw.positions.push(Vec3::new(x[0], x[1], x[2]));
        if let Some(c) = &mut colors {
            // after the coordinates and the normal, before the texture coordinates
            let from = if layout.normal { 6 } else { 3 };
            let to = x.len().saturating_sub(if layout.texture { 2 } else { 0 });
            let rgb = x.get(from..to).filter(|c| c.len() == 3 || c.len() == 4).ok_or_else(|| {
                err(l, format!("vertex {v}: {} values where '{magic}' needs a colour of 3 or 4", x.len()))
            })?;
            let ints = rgb.iter().any(|&c| c > 1.0);
            let rgb = Vec3::new(rgb[0], rgb[1], rgb[2]);
            c.push(if ints { rgb / 255.0 } else { rgb }.clamp(Vec3::ZERO, Vec3::ONE));
        }
    }
    raw.colors = colors;
    let max_size = input.budget.limits().face_size;
    let mut idx: Vec<u32> = Vec::new();
    for f in 0..nf {
        let (l, line) = lines.next().ok_or_else(|| err(lc, format!("file ends at face {f} of {nf}")))?;
        let mut w = line.split_whitespace().map(|t| t.parse::<u32>());
        let bad = || err(l, format!("face {f}: expected a count and vertex indices"));
        let n = w.next().and_then(|r| r.ok()).ok_or_else(bad)? as usize;
        if n < 3 {
            return Err(err(l, format!("face {f}: {n} vertices (3 or more needed)")));
        }
        input.budget.check("face-size", n as u64, file, &format!("line {l}"))?;
        idx.clear();
        for r in w.take(n.min(max_size as usize)) {
            idx.push(r.map_err(|_| bad())?);
        }
        if idx.len() != n {
            return Err(bad());
        }
        if let Some(&i) = idx.iter().find(|&&i| i as usize >= nv) {
            return Err(err(l, format!("face {f}: vertex index {i}, but there are only {nv} vertices")));
        }
        raw.push_face(&idx);
        raw.sources.face_lines.push(l as u32);
    }
    if let Some((l, _)) = lines.next() {
        return Err(err(l, format!("more lines after the {nf} faces the header counts")));
    }
    Ok(raw)
}

/// Saves `mesh` as OFF text (`COFF` with colours when given, one per vertex).
///
/// # Errors
/// I/O errors naming `path`.
pub(crate) fn save_with(path: &Path, mesh: &Mesh, colors: Option<&[Vec3]>) -> Result<()> {
    save_faces(path, &mesh.positions, (mesh.ct.v_table(), 3), colors)
}

/// [`save_with`] (or [`save_poly`]) of the faces of `sides` corners each
/// (3 or 4) whose vertices are `v`, over the vertices `positions`.
///
/// # Errors
/// I/O errors naming `path`.
pub(crate) fn save_faces(
    path: &Path,
    positions: &[Vec3],
    (v, sides): (&[u32], usize),
    colors: Option<&[Vec3]>,
) -> Result<()> {
    let nf = v.len() / sides;
    let prefix = format!("{sides} ");
    let faces = |first: usize| {
        super::text::row_lines(
            prefix.as_bytes(),
            &v[sides * first..sides * (first + ROWS).min(nf)],
            sides,
            Line::put_u32,
        )
    };
    write_off(path, positions, colors, nf, faces)
}

/// Saves a polygon mesh as OFF text (one `k a b c ...` line per face;
/// `COFF` with colours when given, one per vertex).
///
/// # Errors
/// I/O errors naming `path`.
pub(crate) fn save_poly(path: &Path, mesh: &crate::mesh::poly::PolyMesh, colors: Option<&[Vec3]>) -> Result<()> {
    let nf = mesh.pt.num_faces();
    let faces = |first: usize| {
        let rows = first as u32..(first + ROWS).min(nf) as u32;
        super::text::face_lines(b"", &mesh.pt, rows, true, Line::put_u32)
    };
    write_off(path, &mesh.positions, colors, nf, faces)
}

/// Lines per chunk formatted in parallel.
const ROWS: usize = 1 << 15;

/// The OFF file of `positions` (with `colors`, one per vertex, as `COFF`)
/// and `nf` faces whose lines from face `first` on (`ROWS` of them, or what
/// is left) `faces(first)` formats; chunks formatted in parallel, written
/// in order.
fn write_off(
    path: &Path,
    positions: &[Vec3],
    colors: Option<&[Vec3]>,
    nf: usize,
    faces: impl Fn(usize) -> Vec<u8> + Sync,
) -> Result<()> {
    let colors = colors.filter(|c| c.len() == positions.len());
    let magic = if colors.is_some() { "COFF" } else { "OFF" };
    let nv = positions.len();
    let head = format!("{magic}\n{nv} {nf} 0\n");
    let vertex_chunks = nv.div_ceil(ROWS);
    let text = |k: usize| {
        if k < vertex_chunks {
            let rows = k * ROWS..((k + 1) * ROWS).min(nv);
            vertex_lines(&positions[rows.clone()], colors.map(|c| &c[rows]))
        } else {
            faces((k - vertex_chunks) * ROWS)
        }
    };
    atomic_write(path, |w| {
        let mut sink = |b: &[u8]| w.write_all(b).map_err(|e| Error::io(path, e));
        super::write_formatted(&[head.as_bytes()], vertex_chunks + nf.div_ceil(ROWS), text, &mut sink)
    })
}

/// `x y z [r g b]` lines (colours clamped to [0, 1]), shortest round-trip
/// floats.
fn vertex_lines(positions: &[Vec3], colors: Option<&[Vec3]>) -> Vec<u8> {
    // six numbers of at most 16 characters with their separators
    const CAP: usize = 6 * 17;
    let mut out = Vec::with_capacity(positions.len() * if colors.is_some() { CAP } else { LONGEST } + CAP);
    let mut rb = zmij::Buffer::new();
    let mut line: Line<CAP> = Line::new(b"");
    for (i, p) in positions.iter().enumerate() {
        line.reset();
        for (k, x) in p.to_array().into_iter().enumerate() {
            if k > 0 {
                line.push(b' ');
            }
            line.put(rb.format(x).as_bytes());
        }
        for x in colors.map(|c| c[i].to_array()).into_iter().flatten() {
            line.push(b' ');
            line.put(rb.format(x.clamp(0.0, 1.0)).as_bytes());
        }
        line.push(b'\n');
        line.append_to(&mut out);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_of_lines_read_back_as_the_mesh_with_and_without_colours() {
        // more vertices and faces than one chunk of lines holds
        let m = crate::mesh::shapes::icosphere(6);
        assert!(m.positions.len() > 1 << 15 && m.ct.num_triangles() > 2 << 15);
        let colors: Vec<Vec3> = m.positions.iter().map(|p| (*p * 0.5 + 0.5).clamp(Vec3::ZERO, Vec3::ONE)).collect();
        let dir = crate::io::TestDir::new("off-chunks");
        for c in [None, Some(&colors[..])] {
            let path = dir.0.join("m.off");
            save_with(&path, &m, c).expect("saved");
            let raw = crate::io::raw_of(&std::fs::read(&path).expect("read back"), "m.off").expect("parsed");
            assert!(raw.positions == m.positions, "positions read back to the same bits");
            assert!(raw.corners == m.ct.v_table(), "triangles in order");
            assert_eq!(raw.colors.as_deref(), c, "colours");
        }
    }
}
