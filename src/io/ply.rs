//! Binary little-endian PLY output (vertices as float xyz, faces as uchar
//! count + int indices), written atomically.

use super::atomic_write;
use crate::mesh::Mesh;
use crate::{Error, Result};
use std::path::Path;

/// Saves `mesh` as binary PLY.
///
/// # Errors
/// I/O errors naming `path`.
pub fn save(path: &Path, mesh: &Mesh) -> Result<()> {
    atomic_write(path, |w| {
        let io = |e| Error::io(path, e);
        let header = format!(
            "ply\nformat binary_little_endian 1.0\ncomment written by subdiv\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
            mesh.positions.len(),
            mesh.ct.num_triangles()
        );
        w.write_all(header.as_bytes()).map_err(io)?;
        let mut buf = Vec::with_capacity(1 << 20);
        for q in &mesh.positions {
            for x in q.to_array() {
                buf.extend_from_slice(&x.to_le_bytes());
            }
            if buf.len() > (1 << 20) - 64 {
                w.write_all(&buf).map_err(io)?;
                buf.clear();
            }
        }
        for tri in mesh.ct.v_table().chunks_exact(3) {
            buf.push(3);
            for &i in tri {
                buf.extend_from_slice(&i.to_le_bytes());
            }
            if buf.len() > (1 << 20) - 64 {
                w.write_all(&buf).map_err(io)?;
                buf.clear();
            }
        }
        w.write_all(&buf).map_err(io)
    })
}
