//! Writing positions in double precision (`--precision f64`): OBJ with
//! each coordinate's shortest round-trip digits in f64, PLY with `double`
//! properties. The faces, texture coordinates (OBJ), colours (PLY), sharp
//! features and option tags (OBJ) are written as [`super::save_with`]
//! writes them; a hole is left out, or kept as a `t hole` tag where
//! `keep_holes` (a control mesh in OBJ). Not the speed path: the f32
//! writers are.

use super::{Format, atomic_write};
use crate::mesh::attributes::Attributes;
use crate::mesh::poly::{PolyMesh, PolyTable};
use crate::{Error, Mesh, Result};
use glam::DVec3;
use std::path::Path;

/// Saves `mesh` with the positions `positions` (one per vertex, in f64)
/// and its attributes, as OBJ or PLY by extension (atomically); a mesh
/// that stands for polygons is written as polygons.
///
/// # Errors
/// A position count other than the vertex count, another format, or an
/// I/O error naming `path`.
pub fn save_f64(path: &Path, mesh: &Mesh, positions: &[DVec3], attrs: &Attributes, keep_holes: bool) -> Result<()> {
    let (pm, pattrs) = PolyMesh::from_mesh_with_attributes(mesh, attrs);
    save_poly_f64(path, &pm, positions, &pattrs, keep_holes)
}

/// [`save_f64`] of a polygon mesh (texture coordinates per polygon corner).
///
/// # Errors
/// As [`save_f64`].
pub fn save_poly_f64(
    path: &Path,
    mesh: &PolyMesh,
    positions: &[DVec3],
    attrs: &Attributes,
    keep_holes: bool,
) -> Result<()> {
    let usage = |msg: String| Err(Error::Usage(format!("{}: {msg}", path.display())));
    if positions.len() != mesh.pt.num_vertices() {
        return usage(format!("{} positions for {} vertices", positions.len(), mesh.pt.num_vertices()));
    }
    if let Some(f) = (0..mesh.pt.num_faces() as u32).find(|&f| mesh.pt.face_size(f) > 255) {
        return usage(format!("face {f} has {} corners, more than a PLY uchar count holds", mesh.pt.face_size(f)));
    }
    let format = Format::for_output(path).map(|f| f.name);
    let is = |ext: &str| Format::for_output(path).is_some_and(|f| f.extensions.contains(&ext));
    if is("obj") {
        let text = obj_text(mesh, positions, attrs, keep_holes);
        atomic_write(path, |w| w.write_all(&text).map_err(|e| Error::io(path, e)))
    } else if is("ply") {
        let bytes = ply_bytes(&mesh.pt, positions, attrs.colors.as_deref().filter(|c| c.len() == positions.len()));
        atomic_write(path, |w| w.write_all(&bytes).map_err(|e| Error::io(path, e)))
    } else {
        usage(format!("{} holds no double precision: write .obj or .ply", format.unwrap_or("this format")))
    }
}

/// The faces written: every face but the holes, unless they are kept.
fn written_faces(pt: &PolyTable, keep_holes: bool) -> impl Iterator<Item = u32> + '_ {
    (0..pt.num_faces() as u32).filter(move |&f| keep_holes || !pt.is_hole(f))
}

/// The OBJ text: `v` records in f64's shortest digits, `vt` per written
/// corner, `f` records, then the tags.
fn obj_text(mesh: &PolyMesh, positions: &[DVec3], attrs: &Attributes, keep_holes: bool) -> Vec<u8> {
    let pt = &mesh.pt;
    let mut out = Vec::with_capacity(positions.len() * 64 + pt.num_corners() * 12);
    let faces: Vec<u32> = written_faces(pt, keep_holes).collect();
    out.extend(format!("# subdiv (f64): {} vertices, {} faces\n", positions.len(), faces.len()).bytes());
    let mut rb = zmij::Buffer::new();
    let mut put = |out: &mut Vec<u8>, x: f64| {
        out.push(b' ');
        out.extend_from_slice(rb.format_finite(x).as_bytes());
    };
    for p in positions {
        out.push(b'v');
        p.to_array().into_iter().for_each(|x| put(&mut out, x));
        out.push(b'\n');
    }
    let uv = attrs.uv.as_ref().filter(|u| u.len() == pt.num_corners());
    if let Some(uv) = uv {
        for &f in &faces {
            for c in pt.face_corners(f) {
                out.extend_from_slice(b"vt");
                put(&mut out, f64::from(uv[c as usize].x));
                put(&mut out, f64::from(uv[c as usize].y));
                out.push(b'\n');
            }
        }
    }
    let mut vt = 0usize;
    for &f in &faces {
        out.push(b'f');
        for c in pt.face_corners(f) {
            out.extend(format!(" {}", pt.vtx(c) + 1).bytes());
            if uv.is_some() {
                vt += 1;
                out.extend(format!("/{vt}").bytes());
            }
        }
        out.push(b'\n');
    }
    out.extend(super::obj::option_lines(attrs.options));
    if let Some(s) = pt.sharpness() {
        out.extend(super::obj::tag_lines(&s.to_tags(pt)));
    }
    if keep_holes {
        out.extend(super::obj::hole_lines(pt.holes()));
    }
    out
}

/// Binary little-endian PLY with `double` x, y, z (and `uchar` colours).
fn ply_bytes(pt: &PolyTable, positions: &[DVec3], colors: Option<&[glam::Vec3]>) -> Vec<u8> {
    let faces: Vec<u32> = written_faces(pt, false).collect();
    let rgb = if colors.is_some() { "property uchar red\nproperty uchar green\nproperty uchar blue\n" } else { "" };
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\ncomment written by subdiv in double precision\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\n{rgb}element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        positions.len(),
        faces.len()
    )
    .into_bytes();
    for (i, p) in positions.iter().enumerate() {
        p.to_array().iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes()));
        if let Some(c) = colors {
            out.extend(c[i].to_array().map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8));
        }
    }
    for f in faces {
        let r = pt.face_corners(f);
        // at most 255 corners (checked by the caller)
        out.push(r.len() as u8);
        r.for_each(|c| out.extend_from_slice(&(pt.vtx(c) as i32).to_le_bytes()));
    }
    out
}
