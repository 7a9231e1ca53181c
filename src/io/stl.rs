//! STL (stereolithography) in, ASCII and binary; binary out.
//!
//! An STL file is a soup: every triangle carries its own three corners. On
//! reading, corners at exactly the same position are welded into one vertex
//! ([`RawMesh::weld`]) so the mesh is connected and can be subdivided. Which
//! of the two encodings a file uses is told by its content, not its name:
//! a binary file's size is `84 + 50 * n` for the `n` in its header, and many
//! binary files begin with `solid` too, so that size is checked first.
//! Hand-written (the format is a page long): `stl_io` allocates the count a
//! binary header claims before reading it.

use super::raw::{RawMesh, check_count, format_err};
use super::{Format, Input, Keeps};
use crate::mesh::Mesh;
use crate::{Error, Result};
use glam::Vec3;
use std::path::Path;

/// The STL row of [`super::FORMATS`].
pub(crate) const FORMAT: Format = Format {
    name: "STL",
    extensions: &["stl"],
    sniff: |b| is_binary(b) || b.trim_ascii_start().starts_with(b"solid"),
    reader: Some(read),
    writer: Some(|path, mesh, _| save(path, mesh)),
    written_as: &["stl"],
    poly_writer: None,
    faces_writer: Some(|path, positions, corners, _, _| save_faces(path, positions, corners)),
    keeps: Keeps { uv: false, colors: false, materials: false, creases: false, holes: false },
};

/// Whether `bytes` are a binary STL file (its size matches its triangle count).
pub(crate) fn is_binary(bytes: &[u8]) -> bool {
    match bytes.get(80..84) {
        Some(n) => 84 + 50 * u64::from(u32::from_le_bytes([n[0], n[1], n[2], n[3]])) == bytes.len() as u64,
        None => false,
    }
}

/// Whether `bytes` read as ASCII STL: they start with `solid`, are text,
/// and have a facet (or none at all: `solid x` then `endsolid`), where
/// many binary files start with `solid` too.
fn is_ascii(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(1024)];
    let text = match std::str::from_utf8(head) {
        Ok(t) => t,
        // a multi-byte character cut at 1024 bytes
        Err(e) if e.valid_up_to() + 4 > head.len() => std::str::from_utf8(&head[..e.valid_up_to()]).unwrap_or(""),
        Err(_) => return false,
    };
    text.trim_start().starts_with("solid") && (text.contains("facet") || text.contains("endsolid"))
}

/// Reads an STL file (either encoding), welded.
///
/// # Errors
/// [`Error::Format`] naming the file and the facet or line; over the
/// budget.
fn read(input: &Input) -> Result<RawMesh> {
    let (bytes, file) = (input.bytes, input.file);
    let mut raw = if !is_binary(bytes) && is_ascii(bytes) { parse_ascii(bytes, file)? } else { parse_binary(input)? };
    input.budget.take_vertices(raw.positions.len() as u64, file, "facets")?;
    raw.weld();
    Ok(raw)
}

/// A binary STL: its size must be the one its facet count gives (a count
/// smaller than the data would drop facets silently).
fn parse_binary(input: &Input) -> Result<RawMesh> {
    let (bytes, file) = (input.bytes, input.file);
    let Some(n) = bytes.get(80..84) else {
        return Err(format_err(file, "header", format!("{} bytes: a binary STL has at least 84", bytes.len())));
    };
    let n = u64::from(u32::from_le_bytes([n[0], n[1], n[2], n[3]]));
    let n = check_count(file, "facets", n, 50, bytes.len() - 84)?;
    if bytes.len() != 84 + 50 * n {
        let msg = format!(
            "the header counts {n} facets ({} bytes), but the file has {} (not ASCII STL either)",
            84 + 50 * n,
            bytes.len()
        );
        return Err(format_err(file, "header", msg));
    }
    input.budget.take_faces(n as u64, file, "header")?;
    let mut positions = Vec::with_capacity(3 * n);
    for (f, rec) in bytes[84..].chunks_exact(50).take(n).enumerate() {
        for k in 0..3 {
            let at = 12 + 12 * k;
            let c = |i: usize| f32::from_le_bytes([rec[at + i], rec[at + i + 1], rec[at + i + 2], rec[at + i + 3]]);
            let p = Vec3::new(c(0), c(4), c(8));
            if !p.is_finite() {
                return Err(format_err(file, format!("facet {f}"), "non-finite coordinate"));
            }
            positions.push(p);
        }
    }
    let triangles = (0..positions.len() as u32).collect();
    Ok(RawMesh::from_triangles(positions, triangles))
}

fn parse_ascii(bytes: &[u8], file: &str) -> Result<RawMesh> {
    let text = super::text(bytes, file)?;
    let mut positions = Vec::new();
    let mut in_loop = 0usize;
    for (i, line) in text.lines().enumerate() {
        let err = |msg: String| Error::Parse { file: file.to_string(), line: i + 1, msg };
        let mut w = line.split_whitespace();
        match w.next() {
            Some("vertex") => {
                let mut c = [0f32; 3];
                for x in &mut c {
                    let t = w.next().ok_or_else(|| err("vertex needs 3 coordinates".into()))?;
                    *x = t.parse().map_err(|_| err(format!("bad coordinate '{t}'")))?;
                }
                let p = Vec3::from(c);
                if !p.is_finite() {
                    return Err(err("non-finite coordinate".into()));
                }
                in_loop += 1;
                if in_loop > 3 {
                    return Err(err("more than 3 vertices in a facet".into()));
                }
                positions.push(p);
            }
            Some("endloop") => {
                if in_loop != 3 {
                    return Err(err(format!("a facet with {in_loop} vertices (3 needed)")));
                }
                in_loop = 0;
            }
            Some("solid" | "endsolid" | "facet" | "endfacet" | "outer") | None => {}
            Some(other) => return Err(err(format!("unknown keyword '{other}'"))),
        }
    }
    if in_loop != 0 {
        return Err(format_err(file, "last facet", "file ends inside a facet"));
    }
    let triangles = (0..positions.len() as u32).collect();
    Ok(RawMesh::from_triangles(positions, triangles))
}

/// Saves `mesh` as binary STL (face normals from the positions).
///
/// # Errors
/// I/O errors naming `path`; a mesh of more than 2^32 - 1 triangles.
pub(crate) fn save(path: &Path, mesh: &Mesh) -> Result<()> {
    save_faces(path, &mesh.positions, mesh.ct.v_table())
}

/// [`save`] of the triangles `v` (a V table) over the vertices `positions`.
///
/// # Errors
/// As [`save`].
pub(crate) fn save_faces(path: &Path, positions: &[Vec3], v: &[u32]) -> Result<()> {
    let nt = u32::try_from(v.len() / 3)
        .map_err(|_| Error::Usage(format!("{}: too many triangles for STL", path.display())))?;
    let mut header = [b' '; 84];
    header[..20].copy_from_slice(b"binary STL by subdiv");
    header[80..].copy_from_slice(&nt.to_le_bytes());
    // 50 bytes a triangle: every piece's offset is known, so the pieces are
    // made and written in parallel (io::atomic_write_pieces)
    const ROWS: usize = 1 << 14;
    let pieces = (nt as usize).div_ceil(ROWS);
    crate::io::atomic_write_pieces(path, 1 + pieces, |k| {
        if k == 0 {
            return (0, std::borrow::Cow::Borrowed(&header[..]));
        }
        let first = (k - 1) * ROWS;
        let tris = &v[3 * first..3 * (first + ROWS).min(nt as usize)];
        (84 + 50 * first as u64, std::borrow::Cow::Owned(facets(positions, tris)))
    })
}

/// Facet records (normal, three corners, a zero attribute count) of
/// V-table triples.
fn facets(positions: &[Vec3], tris: &[u32]) -> Vec<u8> {
    let mut buf = Vec::with_capacity(tris.len() / 3 * 50);
    for tri in tris.chunks_exact(3) {
        let [a, b, c] = [0, 1, 2].map(|k| positions[tri[k] as usize]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        for p in [n, a, b, c] {
            for x in p.to_array() {
                buf.extend_from_slice(&x.to_le_bytes());
            }
        }
        buf.extend_from_slice(&[0, 0]);
    }
    buf
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn facets_written_in_parallel_pieces_read_back_in_order() {
        let m = crate::mesh::shapes::icosphere(6);
        assert!(m.ct.num_triangles() > 2 * (1 << 14), "several pieces and a partial last one");
        let dir = crate::io::TestDir::new("stl-pieces");
        let path = dir.0.join("m.stl");
        save(&path, &m).expect("saved");
        let bytes = std::fs::read(&path).expect("read back");
        assert_eq!(bytes.len(), 84 + 50 * m.ct.num_triangles());
        // every facet's corners, in triangle order
        for (t, tri) in m.ct.v_table().chunks_exact(3).enumerate() {
            let rec = &bytes[84 + 50 * t..84 + 50 * (t + 1)];
            for (k, &v) in tri.iter().enumerate() {
                let at = 12 + 12 * k;
                let p: Vec<f32> =
                    rec[at..at + 12].chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect();
                assert_eq!(p, m.positions[v as usize].to_array(), "triangle {t} corner {k}");
            }
        }
    }
}
