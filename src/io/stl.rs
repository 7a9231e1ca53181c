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

use super::atomic_write;
use super::raw::{RawMesh, check_count, format_err};
use crate::mesh::Mesh;
use crate::{Error, Result};
use glam::Vec3;
use std::path::Path;

/// Whether `bytes` are a binary STL file (its size matches its triangle count).
pub fn is_binary(bytes: &[u8]) -> bool {
    match bytes.get(80..84) {
        Some(n) => 84 + 50 * u64::from(u32::from_le_bytes([n[0], n[1], n[2], n[3]])) == bytes.len() as u64,
        None => false,
    }
}

/// Reads an STL file (either encoding), welded.
///
/// # Errors
/// [`Error::Format`] naming the file and the facet or line.
pub fn parse(bytes: &[u8], file: &str) -> Result<RawMesh> {
    let trimmed = bytes.iter().position(|b| !b.is_ascii_whitespace()).map_or(&[][..], |i| &bytes[i..]);
    let mut raw = if !is_binary(bytes) && trimmed.starts_with(b"solid") {
        parse_ascii(bytes, file)?
    } else {
        parse_binary(bytes, file)?
    };
    raw.weld();
    Ok(raw)
}

fn parse_binary(bytes: &[u8], file: &str) -> Result<RawMesh> {
    let Some(n) = bytes.get(80..84) else {
        return Err(format_err(file, "header", format!("{} bytes: a binary STL has at least 84", bytes.len())));
    };
    let n = u64::from(u32::from_le_bytes([n[0], n[1], n[2], n[3]]));
    let n = check_count(file, "facets", n, 50, bytes.len() - 84)?;
    let mut raw =
        RawMesh { positions: Vec::with_capacity(3 * n), triangles: Vec::with_capacity(3 * n), ..Default::default() };
    for (f, rec) in bytes[84..].chunks_exact(50).take(n).enumerate() {
        for k in 0..3 {
            let at = 12 + 12 * k;
            let c = |i: usize| f32::from_le_bytes([rec[at + i], rec[at + i + 1], rec[at + i + 2], rec[at + i + 3]]);
            let p = Vec3::new(c(0), c(4), c(8));
            if !p.is_finite() {
                return Err(format_err(file, format!("facet {f}"), "non-finite coordinate"));
            }
            raw.triangles.push(raw.positions.len() as u32);
            raw.positions.push(p);
        }
    }
    Ok(raw)
}

fn parse_ascii(bytes: &[u8], file: &str) -> Result<RawMesh> {
    let text = super::text(bytes, file)?;
    let mut raw = RawMesh::default();
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
                raw.triangles.push(raw.positions.len() as u32);
                raw.positions.push(p);
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
    Ok(raw)
}

/// Saves `mesh` as binary STL (face normals from the positions).
///
/// # Errors
/// I/O errors naming `path`; a mesh of more than 2^32 - 1 triangles.
pub fn save(path: &Path, mesh: &Mesh) -> Result<()> {
    let nt = u32::try_from(mesh.ct.num_triangles())
        .map_err(|_| Error::Usage(format!("{}: too many triangles for STL", path.display())))?;
    atomic_write(path, |w| {
        let io = |e| Error::io(path, e);
        let mut header = [b' '; 80];
        header[..20].copy_from_slice(b"binary STL by subdiv");
        w.write_all(&header).map_err(io)?;
        w.write_all(&nt.to_le_bytes()).map_err(io)?;
        let mut buf = Vec::with_capacity(1 << 20);
        for tri in mesh.ct.v_table().chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[tri[k] as usize]);
            let n = (b - a).cross(c - a).normalize_or_zero();
            for p in [n, a, b, c] {
                for x in p.to_array() {
                    buf.extend_from_slice(&x.to_le_bytes());
                }
            }
            buf.extend_from_slice(&[0, 0]);
            if buf.len() > (1 << 20) - 64 {
                w.write_all(&buf).map_err(io)?;
                buf.clear();
            }
        }
        w.write_all(&buf).map_err(io)
    })
}
