//! Meshes on the GPU: vertex buffers (positions, normals, optional colours),
//! triangle and edge index buffers, normal segments and highlighted
//! segments. Built from the corner table's flat arrays; the renderer
//! ([`super::scene`]) only reads them.
//!
//! The wireframe is drawn by the faces themselves (the `wire` pipeline,
//! shaders/mesh.wgsl), which read positions, normals, the V table, the edge
//! generations and the colours as storage buffers, one vertex per corner:
//! the buffers double as vertex, index and storage buffers, nothing is
//! copied. The edge list (a line list, each edge once) remains for meshes
//! drawn as lines: the control cage and curves.

use crate::mesh::draw::{edge_corner_pairs, edge_indices, packed_generations, sharp_corner_pairs, sharp_edge_indices};
use crate::{CornerTable, Error, Result};
use glam::Vec3;
use wgpu::util::DeviceExt;

/// A mesh on the GPU: positions and normals (separate buffers, so per-frame
/// animation updates copy the slices as they are), triangle and edge indices.
pub struct GpuMesh {
    pub(super) positions: wgpu::Buffer,
    pub(super) normals: wgpu::Buffer,
    pub(super) triangles: wgpu::Buffer,
    pub(super) edges: wgpu::Buffer,
    pub(super) vertex_count: usize,
    pub(super) triangle_indices: u32,
    pub(super) edge_indices: u32,
    pub(super) normal_lines: Option<(wgpu::Buffer, u32)>,
    pub(super) normal_length: f32,
    /// Which faces may be skipped (closed meshes only).
    pub cull: Cull,
    pub(super) colors: Option<wgpu::Buffer>,
    pub(super) highlight: Option<(wgpu::Buffer, u32)>,
    /// The sharp edges (sharpness > 0) as vertex pairs into `positions`.
    pub(super) sharp: Option<(wgpu::Buffer, u32)>,
    /// Edge generation of every corner, four bytes to a word.
    pub(super) generations: wgpu::Buffer,
    /// The storage bind group of the wire pipeline, made on first use
    /// (`None` inside: a buffer exceeds the device's storage binding size).
    pub(super) data_group: std::sync::OnceLock<Option<wgpu::BindGroup>>,
    /// The material groups with their textures (a mesh made by
    /// [`GpuMesh::textured`]), drawn when the look asks for materials.
    pub(super) materials: Option<super::textures::GpuMaterials>,
}

/// Face culling of a mesh.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cull {
    /// Draw both sides (open meshes: their inside can be seen).
    None = 0,
    /// Closed, outward oriented: skip back faces.
    Back = 1,
    /// Closed, inward oriented: skip front faces.
    Front = 2,
}

/// Closed meshes skip the faces turned away from the eye; which side is
/// "away" follows the sign of the enclosed volume (the corner table makes the
/// orientation consistent, not necessarily outward).
pub(crate) fn cull_for(ct: &CornerTable, positions: &[Vec3]) -> Cull {
    if !ct.is_closed() {
        return Cull::None;
    }
    let volume: f64 = ct
        .v_table()
        .chunks_exact(3)
        .map(|t| {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| positions[i as usize].as_dvec3());
            a.dot(b.cross(c))
        })
        .sum();
    if volume >= 0.0 { Cull::Back } else { Cull::Front }
}

/// Segments from each point along its normal, `length` long.
fn normal_segments(positions: &[Vec3], normals: &[Vec3], length: f32) -> Vec<Vec3> {
    positions.iter().zip(normals).flat_map(|(q, n)| [*q, *q + *n * length]).collect()
}

/// An index buffer of `indices`, `None` when there are none.
fn index_buffer(device: &wgpu::Device, label: &str, indices: &[u32]) -> Option<(wgpu::Buffer, u32)> {
    (!indices.is_empty()).then(|| {
        (buffer(device, label, bytemuck::cast_slice(indices), wgpu::BufferUsages::INDEX), indices.len() as u32)
    })
}

/// Vertex attributes, also read as storage by the wire pipeline and
/// rewritten by animation.
const VERTEX_STORAGE: wgpu::BufferUsages =
    wgpu::BufferUsages::VERTEX.union(wgpu::BufferUsages::STORAGE).union(wgpu::BufferUsages::COPY_DST);
/// The V table: an index buffer, also read as storage by the wire pipeline.
const INDEX_STORAGE: wgpu::BufferUsages = wgpu::BufferUsages::INDEX.union(wgpu::BufferUsages::STORAGE);

fn generation_buffer(device: &wgpu::Device, ct: &CornerTable) -> wgpu::Buffer {
    buffer(device, "generations", bytemuck::cast_slice(&packed_generations(ct)), wgpu::BufferUsages::STORAGE)
}

fn buffer(device: &wgpu::Device, label: &str, bytes: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
    // wgpu rejects nothing of size 0, but some backends dislike it: keep 16 bytes at least.
    let mut padded;
    let contents = if bytes.len() < 16 {
        padded = bytes.to_vec();
        padded.resize(16, 0);
        &padded[..]
    } else {
        bytes
    };
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor { label: Some(label), contents, usage })
}

impl GpuMesh {
    /// Uploads a mesh with its vertex normals.
    ///
    /// # Errors
    /// [`Error::Gpu`] when a buffer would exceed the device's limit.
    pub fn new(device: &wgpu::Device, ct: &CornerTable, positions: &[Vec3], normals: &[Vec3]) -> Result<GpuMesh> {
        let edges = edge_indices(ct);
        let limit = device.limits().max_buffer_size;
        let biggest = (ct.v_table().len().max(edges.len()) * 4).max(positions.len() * 12) as u64;
        if biggest > limit {
            return Err(Error::Gpu(format!(
                "the mesh needs a {} buffer but the graphics device allows {}",
                crate::error::human_bytes(biggest),
                crate::error::human_bytes(limit)
            )));
        }
        // also a copy source: the animation's compute passes write the
        // positions and normals (render::gpu_anim) and tests read them back
        let vertex = VERTEX_STORAGE | wgpu::BufferUsages::COPY_SRC;
        Ok(GpuMesh {
            positions: buffer(device, "positions", bytemuck::cast_slice(positions), vertex),
            normals: buffer(device, "normals", bytemuck::cast_slice(normals), vertex),
            triangles: buffer(
                device,
                "triangles",
                bytemuck::cast_slice(&crate::mesh::draw::drawn_triangles(ct)),
                INDEX_STORAGE,
            ),
            edges: buffer(device, "edges", bytemuck::cast_slice(&edges), wgpu::BufferUsages::INDEX),
            vertex_count: positions.len(),
            triangle_indices: ct.v_table().len() as u32,
            edge_indices: edges.len() as u32,
            normal_lines: None,
            normal_length: 0.05,
            cull: cull_for(ct, positions),
            colors: None,
            highlight: None,
            sharp: index_buffer(device, "sharp edges", &sharp_edge_indices(ct)),
            generations: generation_buffer(device, ct),
            data_group: std::sync::OnceLock::new(),
            materials: None,
        })
    }

    /// One GPU vertex per corner, carrying a per-corner attribute in the
    /// colour slot (texture coordinates for the checker, `(u, v, 0)`), so
    /// seams between charts stay sharp. Edges are the corner table's.
    pub fn unwelded(
        device: &wgpu::Device,
        ct: &CornerTable,
        positions: &[Vec3],
        normals: &[Vec3],
        corner_attr: &[Vec3],
    ) -> Result<GpuMesh> {
        let drawn = crate::mesh::draw::drawn_triangles(ct);
        let pos: Vec<Vec3> = drawn.iter().map(|&v| positions[v as usize]).collect();
        let nrm: Vec<Vec3> = drawn.iter().map(|&v| normals[v as usize]).collect();
        let identity: Vec<u32> = (0..ct.v_table().len() as u32).collect();
        // the same edges, between the corners' own GPU vertices
        let edges = edge_corner_pairs(ct);
        let limit = device.limits().max_buffer_size;
        if (pos.len() * 12) as u64 > limit {
            return Err(Error::Gpu(format!(
                "the mesh needs {} per buffer, the device allows {}",
                crate::error::human_bytes((pos.len() * 12) as u64),
                crate::error::human_bytes(limit)
            )));
        }
        let vertex = VERTEX_STORAGE;
        let mut attr = corner_attr.to_vec();
        attr.resize(pos.len(), Vec3::ZERO);
        Ok(GpuMesh {
            positions: buffer(device, "corner positions", bytemuck::cast_slice(&pos), vertex),
            normals: buffer(device, "corner normals", bytemuck::cast_slice(&nrm), vertex),
            triangles: buffer(device, "corner triangles", bytemuck::cast_slice(&identity), INDEX_STORAGE),
            edges: buffer(device, "corner edges", bytemuck::cast_slice(&edges), wgpu::BufferUsages::INDEX),
            vertex_count: pos.len(),
            triangle_indices: identity.len() as u32,
            edge_indices: edges.len() as u32,
            normal_lines: None,
            normal_length: 0.05,
            cull: cull_for(ct, positions),
            colors: Some(buffer(device, "corner uv", bytemuck::cast_slice(&attr), VERTEX_STORAGE)),
            highlight: None,
            sharp: index_buffer(device, "sharp edges", &sharp_corner_pairs(ct)),
            generations: generation_buffer(device, ct),
            data_group: std::sync::OnceLock::new(),
            materials: None,
        })
    }

    /// One GPU vertex per corner ([`GpuMesh::unwelded`]) carrying its
    /// texture coordinate (`materials.uv`; without them every material is
    /// drawn in its flat colour), with the material groups bound for
    /// drawing: each group's texture sampled per pixel (see
    /// `super::textures`).
    ///
    /// # Errors
    /// As [`GpuMesh::unwelded`].
    pub fn textured(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        ct: &CornerTable,
        positions: &[Vec3],
        normals: &[Vec3],
        materials: super::textures::MaterialDraw,
    ) -> Result<GpuMesh> {
        let corners = ct.v_table().len();
        let uv = materials.uv.filter(|u| u.len() == corners);
        let attr: Vec<Vec3> = uv.map_or_else(Vec::new, |u| u.iter().map(|t| t.extend(0.0)).collect());
        let mut mesh = GpuMesh::unwelded(device, ct, positions, normals, &attr)?;
        let groups = materials.groups;
        if groups.face.len() == ct.num_triangles() {
            let reuse = materials.reuse;
            mesh.materials = Some(super::textures::GpuMaterials::new(device, queue, groups, uv.is_some(), reuse));
        }
        Ok(mesh)
    }

    /// The materials bound by [`GpuMesh::textured`].
    pub fn materials(&self) -> Option<&super::textures::GpuMaterials> {
        self.materials.as_ref()
    }

    /// Lines only (no faces): `points` joined by the index pairs in `pairs`
    /// (a curve and its control polygon).
    pub(crate) fn lines(device: &wgpu::Device, points: &[Vec3], pairs: &[u32]) -> GpuMesh {
        let vertex = wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST;
        let normals = vec![Vec3::Z; points.len()];
        GpuMesh {
            positions: buffer(device, "line points", bytemuck::cast_slice(points), vertex),
            normals: buffer(device, "line normals", bytemuck::cast_slice(&normals), vertex),
            triangles: buffer(device, "no triangles", &[], wgpu::BufferUsages::INDEX),
            edges: buffer(device, "line pairs", bytemuck::cast_slice(pairs), wgpu::BufferUsages::INDEX),
            vertex_count: points.len(),
            triangle_indices: 0,
            edge_indices: pairs.len() as u32,
            normal_lines: None,
            normal_length: 0.05,
            cull: Cull::None,
            colors: None,
            highlight: None,
            sharp: None,
            generations: buffer(device, "no generations", &[], wgpu::BufferUsages::STORAGE),
            data_group: std::sync::OnceLock::new(),
            materials: None,
        }
    }

    /// The bytes of its buffers (what uploading it whole sent; a material
    /// mesh's textures left out).
    pub(crate) fn byte_size(&self) -> u64 {
        let optional = [&self.normal_lines, &self.highlight, &self.sharp];
        let fixed = [&self.positions, &self.normals, &self.triangles, &self.edges, &self.generations];
        fixed.iter().map(|b| b.size()).sum::<u64>()
            + self.colors.as_ref().map_or(0, wgpu::Buffer::size)
            + optional.iter().filter_map(|b| b.as_ref()).map(|(b, _)| b.size()).sum::<u64>()
    }

    /// Its normal segments as the GPU holds them (a test's readback).
    #[cfg(test)]
    pub(crate) fn read_normal_lines(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Vec<Vec3>> {
        match &self.normal_lines {
            Some((buf, count)) => super::gpu_anim::read_vec3(device, queue, buf, *count as usize),
            None => Ok(Vec::new()),
        }
    }

    /// Number of vertices.
    pub(crate) fn vertex_count(&self) -> usize {
        self.vertex_count
    }
    /// Number of triangles.
    pub(crate) fn triangle_count(&self) -> usize {
        self.triangle_indices as usize / 3
    }

    /// Replaces positions and normals (same vertex count, same topology):
    /// the per-frame path of the animation; nothing is reallocated.
    pub fn update(&mut self, queue: &wgpu::Queue, positions: &[Vec3], normals: &[Vec3]) {
        let k = self.vertex_count.min(positions.len()).min(normals.len());
        queue.write_buffer(&self.positions, 0, bytemuck::cast_slice(&positions[..k]));
        queue.write_buffer(&self.normals, 0, bytemuck::cast_slice(&normals[..k]));
        if let Some((buf, count)) = &self.normal_lines {
            let segs = normal_segments(&positions[..k], &normals[..k], self.normal_length);
            if segs.len() as u32 == *count {
                queue.write_buffer(buf, 0, bytemuck::cast_slice(&segs));
            }
        }
    }

    /// Writes the positions and normals of the vertices in `ranges` (and
    /// their normal segments) from `positions` and `normals`, the whole
    /// arrays of the same vertices as drawn (an edit that moved some of
    /// them): nothing is reallocated, the rest stays. Returns the bytes
    /// written.
    pub(crate) fn write_ranges(
        &mut self,
        queue: &wgpu::Queue,
        (positions, normals): (&[Vec3], &[Vec3]),
        ranges: &[std::ops::Range<usize>],
    ) -> u64 {
        let k = self.vertex_count.min(positions.len()).min(normals.len());
        let lines = self.normal_lines.as_ref().filter(|(_, count)| *count as usize == 2 * k);
        let mut bytes = 0;
        for r in ranges.iter().map(|r| r.start.min(k)..r.end.min(k)).filter(|r| !r.is_empty()) {
            let at = (r.start * 12) as u64;
            queue.write_buffer(&self.positions, at, bytemuck::cast_slice(&positions[r.clone()]));
            queue.write_buffer(&self.normals, at, bytemuck::cast_slice(&normals[r.clone()]));
            bytes += 24 * r.len() as u64;
            if let Some((buf, _)) = lines {
                let segs = normal_segments(&positions[r.clone()], &normals[r.clone()], self.normal_length);
                queue.write_buffer(buf, 2 * at, bytemuck::cast_slice(&segs));
                bytes += 24 * r.len() as u64;
            }
        }
        bytes
    }

    /// Builds the segments, `length` long, that display the vertex normals.
    pub(crate) fn set_normal_lines(
        &mut self,
        device: &wgpu::Device,
        positions: &[Vec3],
        normals: &[Vec3],
        length: f32,
    ) {
        self.normal_length = length;
        let v = normal_segments(positions, normals, length);
        // a copy source for tests' readback
        let usage = wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC;
        self.normal_lines = Some((buffer(device, "normal lines", bytemuck::cast_slice(&v), usage), v.len() as u32));
    }

    /// Whether the normal segments are built.
    pub(crate) fn has_normal_lines(&self) -> bool {
        self.normal_lines.is_some()
    }

    /// Sets per-vertex colours (linear RGB, one per vertex), shown when the
    /// look asks for colours.
    pub fn set_colors(&mut self, device: &wgpu::Device, colors: &[Vec3]) {
        let mut c = colors.to_vec();
        c.resize(self.vertex_count, Vec3::ONE);
        self.colors = Some(buffer(device, "colors", bytemuck::cast_slice(&c), VERTEX_STORAGE));
        // the wire pipeline's bind group held the old colours
        self.data_group = std::sync::OnceLock::new();
    }

    /// Sets per-vertex values shown on the curvature colours' diverging map
    /// (with [`super::Look::values`]): each value over the colour range's
    /// half-width, NaN where not evaluated (grey). They ride in the colour
    /// slot as `(t, 1, 0)`, or `(0, 0, 0)` for NaN, so the shader can blend
    /// the grey in and draw isolines only where every corner has a value.
    pub(crate) fn set_values(&mut self, device: &wgpu::Device, t: &[f32]) {
        let attr: Vec<Vec3> =
            t.iter().map(|&t| if t.is_finite() { Vec3::new(t, 1.0, 0.0) } else { Vec3::ZERO }).collect();
        self.set_colors(device, &attr);
    }

    /// The storage bind group of the wire pipeline (made once), `None` when a
    /// buffer exceeds the device's storage binding size (the wire is then
    /// not drawn) or the mesh has no faces.
    pub(super) fn data_group(&self, device: &wgpu::Device, layout: &wgpu::BindGroupLayout) -> Option<&wgpu::BindGroup> {
        self.data_group
            .get_or_init(|| {
                let colors = self.colors.as_ref().unwrap_or(&self.normals);
                let buffers = [&self.positions, &self.normals, &self.triangles, &self.generations, colors];
                let limit = device.limits().max_storage_buffer_binding_size;
                if self.triangle_indices == 0 {
                    return None;
                }
                if let Some(big) = buffers.iter().find(|b| b.size() > limit) {
                    log::warn!(
                        "wireframe not drawn: a {} buffer is over the device's storage binding limit of {}",
                        crate::error::human_bytes(big.size()),
                        crate::error::human_bytes(limit)
                    );
                    return None;
                }
                let entries: Vec<wgpu::BindGroupEntry> = buffers
                    .iter()
                    .enumerate()
                    .map(|(i, b)| wgpu::BindGroupEntry { binding: i as u32, resource: b.as_entire_binding() })
                    .collect();
                Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("mesh data"),
                    layout,
                    entries: &entries,
                }))
            })
            .as_ref()
    }

    /// Segments (point pairs) drawn highlighted over this mesh, e.g. a
    /// picked edge; empty clears them.
    pub(crate) fn set_highlight(&mut self, device: &wgpu::Device, segments: &[Vec3]) {
        self.highlight = (!segments.is_empty()).then(|| {
            (
                buffer(device, "highlight", bytemuck::cast_slice(segments), wgpu::BufferUsages::VERTEX),
                segments.len() as u32,
            )
        });
    }

    /// Drops the normal segments.
    pub(crate) fn clear_normal_lines(&mut self) {
        self.normal_lines = None;
    }
}
