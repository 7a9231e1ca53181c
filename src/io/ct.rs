//! The corner-table text format `.ct` (from the original corner-table
//! assignment; docs/formats.md):
//!
//! ```text
//! k                 vertex count
//! x y z             k lines
//! t                 triangle count
//! a b c             t lines of 0-based vertex ids
//! o0 o1 o2          optional: t lines of opposite corners, -1 = border
//! creases m         optional (our extension): m sharp edges,
//! v0 v1 s           m lines: vertex ids and sharpness (>= 10 infinite)
//! corners m         optional (our extension): m sharp vertices,
//! v s               m lines
//! ```
//! `#` starts a comment. O is always built from the faces as for OBJ (expected
//! O(n), no hashing; it also validates the faces); when the O lines are
//! present they must equal that table entry by entry, else the file is
//! refused at the line of the first O row that differs. (A stored O can be a
//! perfectly valid involution and still not be the faces' table: an interior
//! edge marked as border on both sides is a slit the faces do not have.)
//! Counts in the header are checked against the file size before anything
//! is allocated.

use super::atomic_write;
use super::raw::{RawMesh, Sources};
use super::text::triple_lines;
use super::{Format, Input, Keeps};
use crate::mesh::sharpness::{CornerTag, CreaseTag, Tags};
use crate::mesh::{BORDER, Mesh};
use crate::{Error, MeshError, Result};
use glam::Vec3;
use std::io::Write;
use std::path::Path;

struct Tokens<'a> {
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
    cur: std::str::SplitAsciiWhitespace<'a>,
    line: usize,
    file: &'a str,
}

impl<'a> Tokens<'a> {
    fn new(text: &'a str, file: &'a str) -> Self {
        Tokens { lines: text.lines().enumerate(), cur: "".split_ascii_whitespace(), line: 0, file }
    }
    fn next_tok(&mut self) -> Option<&'a str> {
        loop {
            if let Some(t) = self.cur.next() {
                return Some(t);
            }
            let (i, l) = self.lines.next()?;
            self.line = i + 1;
            self.cur = l.split('#').next().unwrap_or("").split_ascii_whitespace();
        }
    }
    fn err(&self, msg: impl Into<String>) -> Error {
        Error::Parse { file: self.file.to_string(), line: self.line.max(1), msg: msg.into() }
    }
    /// The next token without taking it.
    fn peek(&self) -> Option<&'a str> {
        let mut copy = Tokens { lines: self.lines.clone(), cur: self.cur.clone(), line: self.line, file: self.file };
        copy.next_tok()
    }
    fn num<T: std::str::FromStr>(&mut self, what: &str) -> Result<T> {
        let t = self.next_tok().ok_or_else(|| self.err(format!("file ends where {what} was expected")))?;
        t.parse().map_err(|_| self.err(format!("'{t}' is not a valid {what}")))
    }
}

/// The `.ct` row of [`super::FORMATS`].
pub(crate) const FORMAT: Format = Format {
    name: "corner table",
    extensions: &["ct"],
    sniff: |_| false,
    reader: Some(read),
    writer: Some(|path, mesh, _| save(path, mesh)),
    written_as: &["ct"],
    poly_writer: Some(|path, mesh, _| save_poly(path, mesh)),
    faces_writer: None,
    keeps: Keeps { uv: false, colors: false, materials: false, creases: true, holes: false },
};

/// Reads `.ct` text into a [`RawMesh`] with its stored opposite table and
/// tags, checking syntax, counts, index ranges and finite coordinates; the
/// build checks the topology and that the stored O is the faces' own.
///
/// # Errors
/// [`Error::Parse`] with the line, or [`Error::Mesh`] for an index out of
/// range or a non-finite coordinate; over the budget.
fn read(input: &Input) -> Result<RawMesh> {
    let (text, file) = (input.text()?, input.file);
    let mut tk = Tokens::new(text, file);
    let k: u64 = tk.num("vertex count")?;
    // every vertex needs at least "0 0 0\n" (6 bytes): refuse absurd headers before allocating
    if k > text.len() as u64 / 6 + 1 {
        return Err(tk.err(format!("header claims {k} vertices but the file has only {} bytes", text.len())));
    }
    input.budget.take_vertices(k, file, "vertex count")?;
    let mut raw = RawMesh { positions: Vec::with_capacity(k as usize), ..Default::default() };
    for i in 0..k {
        let x: f32 = tk.num("coordinate")?;
        let y: f32 = tk.num("coordinate")?;
        let z: f32 = tk.num("coordinate")?;
        if !(x.is_finite() && y.is_finite() && z.is_finite()) {
            return Err(Error::Mesh {
                file: file.into(),
                line: Some(tk.line),
                source: MeshError::NonFinite { vertex: i as usize },
            });
        }
        raw.positions.push(Vec3::new(x, y, z));
        raw.sources.vertex_lines.push(tk.line as u32);
    }
    let peek = tk.peek();
    if peek == Some("polygons") {
        tk.next_tok();
        return read_polygons(&mut tk, raw, k, text.len(), input);
    }
    let t: u64 = tk.num("triangle count")?;
    if t > text.len() as u64 / 6 + 1 {
        return Err(tk.err(format!("header claims {t} triangles but the file has only {} bytes", text.len())));
    }
    input.budget.take_faces(t, file, "triangle count")?;
    let mut tris = Vec::with_capacity(3 * t as usize);
    for _ in 0..3 * t {
        let i: i64 = tk.num("vertex id")?;
        if i < 0 || i as u64 >= k {
            return Err(Error::Mesh {
                file: file.into(),
                line: Some(tk.line),
                source: MeshError::IndexOutOfRange { face: tris.len() / 3, index: i, len: k as usize },
            });
        }
        tris.push(i as u32);
        if tris.len() % 3 == 0 {
            raw.sources.face_lines.push(tk.line as u32);
        }
    }
    let mut next = tk.next_tok();
    if let Some(first) = next.filter(|s| !is_section(s)) {
        raw.opposite = Some(opposite_table(&mut tk, first, t, &mut raw.sources.opposite_lines)?);
        next = tk.next_tok();
    }
    let (tags, tag_lines) = parse_sections(&mut tk, next, text.len())?;
    let mut out = RawMesh::from_triangles(std::mem::take(&mut raw.positions), tris);
    out.opposite = raw.opposite;
    out.tags = tags;
    out.sources = Sources { tag_lines, ..raw.sources };
    Ok(out)
}

/// The optional opposite table (`3 t` corner ids, -1 for a border) whose
/// first token is `first`; the line of each row goes to `lines`.
fn opposite_table<'a>(tk: &mut Tokens<'a>, first: &'a str, t: u64, lines: &mut Vec<u32>) -> Result<Vec<u32>> {
    corner_ids(tk, first, 3 * t, lines, "opposite", &|n| n % 3 == 0)
}

/// `h` corner ids (`-1`: [`BORDER`]) of a table, the first token `first`;
/// the line of each row goes to `lines`, a row ending after `n` ids where
/// `row_end(n)` (a face's corners).
fn corner_ids<'a>(
    tk: &mut Tokens<'a>,
    first: &'a str,
    h: u64,
    lines: &mut Vec<u32>,
    what: &str,
    row_end: &dyn Fn(usize) -> bool,
) -> Result<Vec<u32>> {
    let mut stored = Vec::with_capacity(h as usize);
    let mut tok = Some(first);
    for _ in 0..h {
        let s = match tok.take() {
            Some(s) => s,
            None => tk.next_tok().ok_or_else(|| tk.err(format!("the {what} table ends early")))?,
        };
        let x: i64 = s.parse().map_err(|_| tk.err(format!("'{s}' is not a corner id")))?;
        if x < -1 || x >= h as i64 {
            return Err(tk.err(format!("{what} corner {x} out of range")));
        }
        stored.push(if x < 0 { BORDER } else { x as u32 });
        if row_end(stored.len()) {
            lines.push(tk.line as u32);
        }
    }
    Ok(stored)
}

/// The polygon extension: after the vertices, `polygons F`, then `F` lines
/// of a corner count and that many vertex ids, then optionally `F` lines of
/// the corners' twins (the corner across the edge leaving each corner, in
/// the order the faces list their corners, `-1` on the border), then the
/// sections.
fn read_polygons(tk: &mut Tokens, mut raw: RawMesh, k: u64, bytes: usize, input: &Input) -> Result<RawMesh> {
    let file = input.file;
    let f: u64 = tk.num("polygon count")?;
    // every face needs at least "3 0 1 2\n" (8 bytes)
    if f > bytes as u64 / 8 + 1 {
        return Err(tk.err(format!("header claims {f} polygons but the file has only {bytes} bytes")));
    }
    input.budget.take_faces(f, file, "polygon count")?;
    let mut ids = Vec::new();
    for face in 0..f as usize {
        let n: u64 = tk.num("corner count")?;
        input.budget.check("face-size", n, file, &format!("line {}", tk.line))?;
        if n < 3 || n > bytes as u64 / 2 {
            return Err(tk.err(format!("polygon {face} has {n} corners (3 or more, as many as the file holds)")));
        }
        ids.clear();
        for _ in 0..n {
            let i: i64 = tk.num("vertex id")?;
            if i < 0 || i as u64 >= k {
                let source = MeshError::IndexOutOfRange { face, index: i, len: k as usize };
                return Err(Error::Mesh { file: file.into(), line: Some(tk.line), source });
            }
            ids.push(i as u32);
        }
        raw.push_face(&ids);
        raw.sources.face_lines.push(tk.line as u32);
    }
    let mut next = tk.next_tok();
    if let Some(first) = next.filter(|s| !is_section(s)) {
        let h = raw.corners.len() as u64;
        let starts = &raw.face_starts;
        let row_end = |n: usize| starts.binary_search(&(n as u32)).is_ok();
        raw.twins = Some(corner_ids(tk, first, h, &mut raw.sources.opposite_lines, "twin", &row_end)?);
        next = tk.next_tok();
    }
    let (tags, tag_lines) = parse_sections(tk, next, bytes)?;
    raw.tags = tags;
    raw.sources.tag_lines = tag_lines;
    Ok(raw)
}

fn is_section(tok: &str) -> bool {
    tok == "creases" || tok == "corners"
}

/// The optional `creases` and `corners` sections after the tables.
fn parse_sections<'a>(tk: &mut Tokens<'a>, mut next: Option<&'a str>, bytes: usize) -> Result<(Tags, Vec<u32>)> {
    let (mut tags, mut creases, mut corners) = (Tags::default(), Vec::new(), Vec::new());
    while let Some(key) = next {
        if !is_section(key) {
            return Err(tk.err(format!("unexpected '{key}' after the tables (expected creases or corners)")));
        }
        let m: u64 = tk.num(&format!("{key} count"))?;
        if m > bytes as u64 / 4 + 1 {
            return Err(tk.err(format!("{key} count {m} is larger than the file")));
        }
        for _ in 0..m {
            if key == "creases" {
                let (v0, v1): (u32, u32) = (tk.num("vertex id")?, tk.num("vertex id")?);
                tags.creases.push(CreaseTag { v0, v1, sharpness: tk.num("sharpness")? });
                creases.push(tk.line as u32);
            } else {
                let vertex: u32 = tk.num("vertex id")?;
                tags.corners.push(CornerTag { vertex, sharpness: tk.num("sharpness")? });
                corners.push(tk.line as u32);
            }
        }
        next = tk.next_tok();
    }
    creases.extend(corners);
    Ok((tags, creases))
}

/// Writes `.ct` text including the O table.
///
/// # Errors
/// I/O errors.
pub fn write(w: &mut dyn Write, mesh: &Mesh) -> std::io::Result<()> {
    let text = Text::of(mesh);
    for k in 0..text.chunks() {
        w.write_all(&text.chunk(k))?;
    }
    w.write_all(&text.tags())
}

/// Saves `mesh` as `.ct` (atomically), its chunks of lines formatted in
/// parallel and written in order (`io::write_formatted`).
///
/// # Errors
/// I/O errors naming `path`.
pub(crate) fn save(path: &Path, mesh: &Mesh) -> Result<()> {
    let text = Text::of(mesh);
    atomic_write(path, |w| {
        let mut sink = |b: &[u8]| w.write_all(b).map_err(|e| Error::io(path, e));
        super::write_formatted(&[], text.chunks(), |k| text.chunk(k), &mut sink)?;
        sink(&text.tags())
    })
}

/// Saves a polygon mesh as `.ct` with the polygon extension (`polygons F`,
/// the faces, their twins, the sharpness), in one buffer.
///
/// # Errors
/// I/O errors naming `path`.
pub(crate) fn save_poly(path: &Path, mesh: &crate::mesh::poly::PolyMesh) -> Result<()> {
    let pt = &mesh.pt;
    let mut out = Vec::new();
    let _ = writeln!(out, "{}", mesh.positions.len());
    for q in &mesh.positions {
        let _ = writeln!(out, "{} {} {}", q.x, q.y, q.z);
    }
    let _ = writeln!(out, "polygons {}", pt.num_faces());
    let rows = |out: &mut Vec<u8>, value: &dyn Fn(u32) -> String| {
        for f in 0..pt.num_faces() as u32 {
            let r = pt.face_corners(f);
            let line: Vec<String> = r.map(value).collect();
            let _ = writeln!(out, "{}", line.join(" "));
        }
    };
    let count_and_vertex = |c: u32| {
        let v = pt.vtx(c).to_string();
        if c == pt.face_corners(pt.face(c)).start { format!("{} {v}", pt.face_size(pt.face(c))) } else { v }
    };
    rows(&mut out, &count_and_vertex);
    rows(&mut out, &|c| if pt.twin_entry(c) == BORDER { "-1".into() } else { pt.twin_entry(c).to_string() });
    if let Some(s) = pt.sharpness() {
        section_lines(&mut out, &s.to_tags(pt));
    }
    atomic_write(path, |w| w.write_all(&out).map_err(|e| Error::io(path, e)))
}

/// The `creases` and `corners` sections of `tags`.
fn section_lines(out: &mut Vec<u8>, tags: &Tags) {
    if !tags.creases.is_empty() {
        let _ = writeln!(out, "creases {}", tags.creases.len());
        for t in &tags.creases {
            let _ = writeln!(out, "{} {} {}", t.v0, t.v1, t.sharpness);
        }
    }
    if !tags.corners.is_empty() {
        let _ = writeln!(out, "corners {}", tags.corners.len());
        for t in &tags.corners {
            let _ = writeln!(out, "{} {}", t.vertex, t.sharpness);
        }
    }
}

/// The text of a `.ct` file in chunks of lines: the vertex count and the
/// positions (shortest strings that read back to the same f32, as `Display`
/// prints them), the triangle count and the V table, the O table (`-1` on
/// the border), then the sharpness tags.
struct Text<'a> {
    mesh: &'a Mesh,
    vertex_chunks: usize,
    triangle_chunks: usize,
}

impl<'a> Text<'a> {
    /// Lines per chunk.
    const ROWS: usize = 1 << 15;

    fn of(mesh: &'a Mesh) -> Self {
        let (nv, nt) = (mesh.positions.len(), mesh.ct.num_triangles());
        Text { mesh, vertex_chunks: nv.div_ceil(Self::ROWS).max(1), triangle_chunks: nt.div_ceil(Self::ROWS).max(1) }
    }

    fn chunks(&self) -> usize {
        self.vertex_chunks + 2 * self.triangle_chunks
    }

    /// Chunk `k`: vertex lines, then V lines, then O lines.
    fn chunk(&self, k: usize) -> Vec<u8> {
        let mut out = Vec::new();
        let rows = |j: usize, n: usize| j * Self::ROWS..((j + 1) * Self::ROWS).min(n);
        if k < self.vertex_chunks {
            if k == 0 {
                out.extend_from_slice(format!("{}\n", self.mesh.positions.len()).as_bytes());
            }
            for q in &self.mesh.positions[rows(k, self.mesh.positions.len())] {
                // Display prints the shortest string that reads back to the same f32
                let _ = writeln!(out, "{} {} {}", q.x, q.y, q.z);
            }
            return out;
        }
        let nt = self.mesh.ct.num_triangles();
        let (j, table) = match k - self.vertex_chunks {
            j if j < self.triangle_chunks => (j, self.mesh.ct.v_table()),
            j => (j - self.triangle_chunks, self.mesh.ct.o_table()),
        };
        let r = rows(j, nt);
        let lines = triple_lines(b"", &table[3 * r.start..3 * r.end], |line, x| {
            if x == BORDER {
                line.push(b'-');
                line.push(b'1');
            } else {
                line.put_u32(x);
            }
        });
        if k != self.vertex_chunks {
            return lines;
        }
        // the triangle count heads the first chunk of the V table
        out.extend_from_slice(format!("{nt}\n").as_bytes());
        out.extend_from_slice(&lines);
        out
    }

    /// The `creases` and `corners` sections, when there are sharp features.
    fn tags(&self) -> Vec<u8> {
        let mut w = Vec::new();
        if let Some(s) = self.mesh.ct.sharpness() {
            section_lines(&mut w, &s.to_tags(&self.mesh.ct));
        }
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_of_lines_read_back_as_the_table() {
        // several chunks of each section, and an open mesh for the -1 entries
        for m in [crate::mesh::shapes::icosphere(6), crate::mesh::shapes::grid(200)] {
            assert!(m.ct.num_triangles() > 1 << 15);
            let mut text = Vec::new();
            write(&mut text, &m).expect("written");
            let raw = crate::io::raw_of(&text, "m.ct").expect("parsed");
            assert!(raw.positions == m.positions, "positions read back to the same bits");
            assert!(raw.corners == m.ct.v_table(), "V");
            assert!(raw.opposite.as_deref() == Some(m.ct.o_table()), "O, border entries included");
        }
    }
}
