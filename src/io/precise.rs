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
pub(crate) fn save_mesh_f64(
    path: &Path,
    mesh: &Mesh,
    positions: &[DVec3],
    attrs: &Attributes,
    keep_holes: bool,
) -> Result<()> {
    if PolyMesh::is_polygonal(mesh) {
        let (pm, pattrs) = PolyMesh::from_mesh_with_attributes(mesh, attrs);
        return save_poly_f64(path, &pm, positions, &pattrs, keep_holes);
    }
    save_table(path, &mesh.ct, positions, attrs, keep_holes)
}

/// [`save_f64`] of a polygon mesh (texture coordinates per polygon corner).
///
/// # Errors
/// As [`save_f64`].
pub(crate) fn save_poly_f64(
    path: &Path,
    mesh: &PolyMesh,
    positions: &[DVec3],
    attrs: &Attributes,
    keep_holes: bool,
) -> Result<()> {
    save_table(path, &mesh.pt, positions, attrs, keep_holes)
}

/// The faces of a triangle or a polygon table, as the writers read them.
trait Table {
    fn num_vertices(&self) -> usize;
    fn num_faces(&self) -> usize;
    /// The corners of face `f` (texture coordinates are per corner).
    fn corners(&self, f: u32) -> std::ops::Range<u32>;
    fn vtx(&self, c: u32) -> u32;
    fn is_hole(&self, f: u32) -> bool;
    fn holes(&self) -> &[u32];
    fn tags(&self) -> Option<crate::mesh::Tags>;
}

impl Table for crate::CornerTable {
    fn num_vertices(&self) -> usize {
        crate::CornerTable::num_vertices(self)
    }
    fn num_faces(&self) -> usize {
        self.num_triangles()
    }
    fn corners(&self, f: u32) -> std::ops::Range<u32> {
        3 * f..3 * f + 3
    }
    fn vtx(&self, c: u32) -> u32 {
        crate::CornerTable::vtx(self, c)
    }
    fn is_hole(&self, f: u32) -> bool {
        crate::CornerTable::is_hole(self, f)
    }
    fn holes(&self) -> &[u32] {
        crate::CornerTable::holes(self)
    }
    fn tags(&self) -> Option<crate::mesh::Tags> {
        self.sharpness().map(|s| s.to_tags(self))
    }
}

impl Table for PolyTable {
    fn num_vertices(&self) -> usize {
        PolyTable::num_vertices(self)
    }
    fn num_faces(&self) -> usize {
        PolyTable::num_faces(self)
    }
    fn corners(&self, f: u32) -> std::ops::Range<u32> {
        self.face_corners(f)
    }
    fn vtx(&self, c: u32) -> u32 {
        PolyTable::vtx(self, c)
    }
    fn is_hole(&self, f: u32) -> bool {
        PolyTable::is_hole(self, f)
    }
    fn holes(&self) -> &[u32] {
        PolyTable::holes(self)
    }
    fn tags(&self) -> Option<crate::mesh::Tags> {
        self.sharpness().map(|s| s.to_tags(self))
    }
}

/// [`save_poly_f64`] of either table.
fn save_table(path: &Path, t: &dyn Table, positions: &[DVec3], attrs: &Attributes, keep_holes: bool) -> Result<()> {
    let usage = |msg: String| Err(Error::Usage(format!("{}: {msg}", path.display())));
    if positions.len() != t.num_vertices() {
        return usage(format!("{} positions for {} vertices", positions.len(), t.num_vertices()));
    }
    if let Some(f) = (0..t.num_faces() as u32).find(|&f| t.corners(f).len() > 255) {
        return usage(format!("face {f} has {} corners, more than a PLY uchar count holds", t.corners(f).len()));
    }
    let format = Format::for_output(path).map(|f| f.name);
    let is = |ext: &str| Format::for_output(path).is_some_and(|f| f.extensions.contains(&ext));
    if is("obj") {
        let text = obj_text(t, positions, attrs, keep_holes);
        atomic_write(path, |w| w.write_all(&text).map_err(|e| Error::io(path, e)))
    } else if is("ply") {
        let bytes = ply_bytes(t, positions, attrs.colors.as_deref().filter(|c| c.len() == positions.len()));
        atomic_write(path, |w| w.write_all(&bytes).map_err(|e| Error::io(path, e)))
    } else {
        usage(format!("{} holds no double precision: write .obj or .ply", format.unwrap_or("this format")))
    }
}

/// The faces written: every face but the holes, unless they are kept.
fn written_faces(t: &dyn Table, keep_holes: bool) -> impl Iterator<Item = u32> + '_ {
    (0..t.num_faces() as u32).filter(move |&f| keep_holes || !t.is_hole(f))
}

/// The OBJ text: `v` records in f64's shortest digits, `vt` per written
/// corner, `f` records, then the tags.
fn obj_text(pt: &dyn Table, positions: &[DVec3], attrs: &Attributes, keep_holes: bool) -> Vec<u8> {
    let corners = (0..pt.num_faces() as u32).map(|f| pt.corners(f).len()).sum::<usize>();
    let mut out = Vec::with_capacity(positions.len() * 64 + corners * 12);
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
    let uv = attrs.uv.as_ref().filter(|u| u.len() == corners);
    if let Some(uv) = uv {
        for &f in &faces {
            for c in pt.corners(f) {
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
        for c in pt.corners(f) {
            out.extend(format!(" {}", pt.vtx(c) + 1).bytes());
            if uv.is_some() {
                vt += 1;
                out.extend(format!("/{vt}").bytes());
            }
        }
        out.push(b'\n');
    }
    out.extend(super::obj::option_lines(attrs.options));
    if let Some(tags) = pt.tags() {
        out.extend(super::obj::tag_lines(&tags));
    }
    if keep_holes {
        out.extend(super::obj::hole_lines(pt.holes()));
    }
    out
}

/// Binary little-endian PLY with `double` x, y, z (and `uchar` colours).
fn ply_bytes(pt: &dyn Table, positions: &[DVec3], colors: Option<&[glam::Vec3]>) -> Vec<u8> {
    let faces: Vec<u32> = written_faces(pt, false).collect();
    let rgb = if colors.is_some() { "property uchar red\nproperty uchar green\nproperty uchar blue\n" } else { "" };
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\ncomment written by subdiv in double precision\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\n{rgb}element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        positions.len(),
        faces.len()
    )
    .into_bytes();
    out.reserve(positions.len() * 27 + faces.iter().map(|&f| 1 + 4 * pt.corners(f).len()).sum::<usize>());
    for (i, p) in positions.iter().enumerate() {
        p.to_array().iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes()));
        if let Some(c) = colors {
            out.extend(c[i].to_array().map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8));
        }
    }
    for f in faces {
        let r = pt.corners(f);
        // at most 255 corners (checked by the caller)
        out.push(r.len() as u8);
        r.for_each(|c| out.extend_from_slice(&(pt.vtx(c) as i32).to_le_bytes()));
    }
    out
}
