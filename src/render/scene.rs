//! Pipelines, GPU meshes and the 3D pass shared by the window and offscreen
//! rendering (shaders/mesh.wgsl).
//!
//! The wireframe is a line list of the mesh's edges (each edge once, taken
//! from the corner table), drawn with the same vertex buffer: no polygon-mode
//! feature is needed. Hidden lines are removed by a depth-only pass of the
//! faces; lines are pulled slightly towards the eye so they win against the
//! faces they lie on.

use super::camera::Camera;
use super::{DEPTH_FORMAT, Look, Surface};
use crate::mesh::{BORDER, n, p};
use crate::{CornerTable, Error, Result};
use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec4};
use wgpu::util::DeviceExt;

/// Background colour (linear RGB) of every view.
pub const BACKGROUND: [f64; 3] = [0.045, 0.05, 0.065];

/// Linear colour of front faces (the material).
pub const FRONT: Vec4 = Vec4::new(0.32, 0.40, 0.58, 1.0);
/// Linear colours of back faces and lines.
const BACK: Vec4 = Vec4::new(0.62, 0.30, 0.16, 1.0);
const WIRE_DARK: [f32; 4] = [0.015, 0.02, 0.035, 1.0];
const WIRE_LIGHT: [f32; 4] = [0.80, 0.84, 0.92, 1.0];
const CONTROL: [f32; 4] = [1.0, 0.38, 0.03, 1.0];
const NORMALS: [f32; 4] = [0.15, 0.85, 0.25, 1.0];

/// Direction towards the key light (world, not normalised): upper left front.
pub const KEY_LIGHT: Vec3 = Vec3::new(-0.45, 0.75, 0.5);
/// Intensity of the key light.
pub const KEY_INTENSITY: f32 = 0.5;
/// Direction towards the weak fill light (world, not normalised): from below.
pub const FILL_LIGHT: Vec3 = Vec3::new(0.35, -0.8, -0.45);
/// Intensity of the fill light.
pub const FILL_INTENSITY: f32 = 0.15;
/// Intensity of the headlight, which shines from the eye along the view direction.
pub const HEADLIGHT_INTENSITY: f32 = 0.6;

/// The 8-bit sRGB value the background has in a rendered image.
pub fn background_srgb8() -> [u8; 3] {
    BACKGROUND.map(|c| {
        let s = if c <= 0.0031308 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
        (s * 255.0).round().clamp(0.0, 255.0) as u8
    })
}

/// Per-viewport uniforms (see `View` in shaders/mesh.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct ViewUniform {
    proj: [[f32; 4]; 4],
    view: [[f32; 4]; 4],
    eye: [f32; 4],
    forward: [f32; 4],
    key_light: [f32; 4],
    fill_light: [f32; 4],
    front_color: [f32; 4],
    back_color: [f32; 4],
    params: [f32; 4],
    line: [f32; 4],
}

/// A mesh on the GPU: positions and normals (separate buffers, so per-frame
/// animation updates copy the slices as they are), triangle and edge indices.
pub struct GpuMesh {
    positions: wgpu::Buffer,
    normals: wgpu::Buffer,
    triangles: wgpu::Buffer,
    edges: wgpu::Buffer,
    vertex_count: usize,
    triangle_indices: u32,
    edge_indices: u32,
    normal_lines: Option<(wgpu::Buffer, u32)>,
    normal_length: f32,
    /// Which faces may be skipped (closed meshes only).
    pub cull: Cull,
    colors: Option<wgpu::Buffer>,
    highlight: Option<(wgpu::Buffer, u32)>,
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
pub fn cull_for(ct: &CornerTable, positions: &[Vec3]) -> Cull {
    if ct.o_table().contains(&BORDER) {
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

/// Each edge once as a pair of vertex ids (see [`CornerTable::edge_owners`]).
pub fn edge_indices(ct: &CornerTable) -> Vec<u32> {
    ct.edge_owners().flat_map(|c| [ct.v_table()[n(c) as usize], ct.v_table()[p(c) as usize]]).collect()
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
        let vertex = wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST;
        Ok(GpuMesh {
            positions: buffer(device, "positions", bytemuck::cast_slice(positions), vertex),
            normals: buffer(device, "normals", bytemuck::cast_slice(normals), vertex),
            triangles: buffer(device, "triangles", bytemuck::cast_slice(ct.v_table()), wgpu::BufferUsages::INDEX),
            edges: buffer(device, "edges", bytemuck::cast_slice(&edges), wgpu::BufferUsages::INDEX),
            vertex_count: positions.len(),
            triangle_indices: ct.v_table().len() as u32,
            edge_indices: edges.len() as u32,
            normal_lines: None,
            normal_length: 0.05,
            cull: cull_for(ct, positions),
            colors: None,
            highlight: None,
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
        let pos: Vec<Vec3> = ct.v_table().iter().map(|&v| positions[v as usize]).collect();
        let nrm: Vec<Vec3> = ct.v_table().iter().map(|&v| normals[v as usize]).collect();
        let identity: Vec<u32> = (0..ct.v_table().len() as u32).collect();
        // the same edges, between the corners' own GPU vertices
        let edges: Vec<u32> = ct.edge_owners().flat_map(|c| [n(c), p(c)]).collect();
        let limit = device.limits().max_buffer_size;
        if (pos.len() * 12) as u64 > limit {
            return Err(Error::Gpu(format!(
                "the mesh needs {} per buffer, the device allows {}",
                crate::error::human_bytes((pos.len() * 12) as u64),
                crate::error::human_bytes(limit)
            )));
        }
        let vertex = wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST;
        let mut attr = corner_attr.to_vec();
        attr.resize(pos.len(), Vec3::ZERO);
        Ok(GpuMesh {
            positions: buffer(device, "corner positions", bytemuck::cast_slice(&pos), vertex),
            normals: buffer(device, "corner normals", bytemuck::cast_slice(&nrm), vertex),
            triangles: buffer(device, "corner triangles", bytemuck::cast_slice(&identity), wgpu::BufferUsages::INDEX),
            edges: buffer(device, "corner edges", bytemuck::cast_slice(&edges), wgpu::BufferUsages::INDEX),
            vertex_count: pos.len(),
            triangle_indices: identity.len() as u32,
            edge_indices: edges.len() as u32,
            normal_lines: None,
            normal_length: 0.05,
            cull: cull_for(ct, positions),
            colors: Some(buffer(device, "corner uv", bytemuck::cast_slice(&attr), wgpu::BufferUsages::VERTEX)),
            highlight: None,
        })
    }

    /// Lines only (no faces): `points` joined by the index pairs in `pairs`
    /// (a curve and its control polygon).
    pub fn lines(device: &wgpu::Device, points: &[Vec3], pairs: &[u32]) -> GpuMesh {
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
        }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }
    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
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

    /// Builds the segments, `length` long, that display the vertex normals.
    pub fn set_normal_lines(&mut self, device: &wgpu::Device, positions: &[Vec3], normals: &[Vec3], length: f32) {
        self.normal_length = length;
        let v = normal_segments(positions, normals, length);
        let usage = wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST;
        self.normal_lines = Some((buffer(device, "normal lines", bytemuck::cast_slice(&v), usage), v.len() as u32));
    }

    /// Whether the normal segments are built.
    pub fn has_normal_lines(&self) -> bool {
        self.normal_lines.is_some()
    }

    /// Sets per-vertex colours (linear RGB, one per vertex), shown when the
    /// look asks for colours.
    pub fn set_colors(&mut self, device: &wgpu::Device, colors: &[Vec3]) {
        let mut c = colors.to_vec();
        c.resize(self.vertex_count, Vec3::ONE);
        self.colors = Some(buffer(device, "colors", bytemuck::cast_slice(&c), wgpu::BufferUsages::VERTEX));
    }

    /// Segments (point pairs) drawn highlighted over this mesh, e.g. a
    /// picked edge; empty clears them.
    pub fn set_highlight(&mut self, device: &wgpu::Device, segments: &[Vec3]) {
        self.highlight = (!segments.is_empty()).then(|| {
            (
                buffer(device, "highlight", bytemuck::cast_slice(segments), wgpu::BufferUsages::VERTEX),
                segments.len() as u32,
            )
        });
    }

    /// Drops the normal segments.
    pub fn clear_normal_lines(&mut self) {
        self.normal_lines = None;
    }
}

/// Multisampled colour and depth attachments of one size.
pub struct Targets {
    msaa: Option<wgpu::TextureView>,
    depth: wgpu::TextureView,
    /// Size in pixels.
    pub size: (u32, u32),
}

impl Targets {
    /// Attachments for a `width` x `height` target of the renderer's format.
    pub fn new(device: &wgpu::Device, renderer: &Renderer, width: u32, height: u32) -> Targets {
        let size = wgpu::Extent3d { width: width.max(1), height: height.max(1), depth_or_array_layers: 1 };
        let make = |format, label| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size,
                    mip_level_count: 1,
                    sample_count: renderer.samples,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                    view_formats: &[],
                })
                .create_view(&Default::default())
        };
        let msaa = (renderer.samples > 1).then(|| make(renderer.format, "msaa colour"));
        Targets { msaa, depth: make(DEPTH_FORMAT, "depth"), size: (size.width, size.height) }
    }
}

/// One viewport's worth of drawing.
pub struct ViewportDraw<'a> {
    /// Pixel rectangle `[x, y, width, height]` in the target.
    pub rect: [f32; 4],
    /// Camera (its aspect is taken from `rect`).
    pub camera: Camera,
    /// The surface to draw.
    pub mesh: Option<&'a GpuMesh>,
    /// The control mesh to overlay as lines (when `look.control`).
    pub control: Option<&'a GpuMesh>,
    /// How to draw it.
    pub look: Look,
}

/// Pipelines and per-viewport uniforms.
pub struct Renderer {
    /// Colour target format.
    pub format: wgpu::TextureFormat,
    /// MSAA sample count of the pipelines.
    pub samples: u32,
    mesh: [wgpu::RenderPipeline; 3],
    mesh_colored: [wgpu::RenderPipeline; 3],
    depth_only: [wgpu::RenderPipeline; 3],
    lines: wgpu::RenderPipeline,
    view_layout: wgpu::BindGroupLayout,
    views: Vec<(wgpu::Buffer, wgpu::BindGroup)>,
    styles: [wgpu::BindGroup; 4],
}

const POS_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
};
const NRM_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![1 => Float32x3],
};
const COLOR_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![2 => Float32x3],
};

fn uniform_layout(device: &wgpu::Device, label: &str) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    })
}

fn uniform_group(device: &wgpu::Device, layout: &wgpu::BindGroupLayout, buf: &wgpu::Buffer) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout,
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: buf.as_entire_binding() }],
    })
}

impl Renderer {
    /// Pipelines for colour targets of `format` with `samples` MSAA samples.
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat, samples: u32) -> Renderer {
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("mesh.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../../shaders/mesh.wgsl").into()),
        });
        let view_layout = uniform_layout(device, "view");
        let style_layout = uniform_layout(device, "line style");
        let mesh_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("mesh"),
            bind_group_layouts: &[Some(&view_layout)],
            immediate_size: 0,
        });
        let line_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("lines"),
            bind_group_layouts: &[Some(&view_layout), Some(&style_layout)],
            immediate_size: 0,
        });
        let multisample = wgpu::MultisampleState { count: samples, mask: !0, alpha_to_coverage_enabled: false };
        let depth = |write: bool, compare| {
            Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(write),
                depth_compare: Some(compare),
                stencil: Default::default(),
                bias: Default::default(),
            })
        };
        let pipeline = |label: &str,
                        layout: &wgpu::PipelineLayout,
                        vs: &str,
                        buffers: &[Option<wgpu::VertexBufferLayout>],
                        topology,
                        write_color: bool,
                        depth_state,
                        cull_mode: Option<wgpu::Face>| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(vs),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState { topology, cull_mode, ..Default::default() },
                depth_stencil: depth_state,
                multisample,
                fragment: Some(wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(if vs == "vs_line" { "fs_line" } else { "fs_mesh" }),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format,
                        blend: None,
                        write_mask: if write_color { wgpu::ColorWrites::ALL } else { wgpu::ColorWrites::empty() },
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let tri = wgpu::PrimitiveTopology::TriangleList;
        let mesh_buffers = [Some(POS_LAYOUT), Some(NRM_LAYOUT)];
        // Index by `Cull as usize`: closed meshes skip their back faces.
        let culls = [None, Some(wgpu::Face::Back), Some(wgpu::Face::Front)];
        let mesh = culls.map(|c| {
            pipeline(
                "mesh",
                &mesh_layout,
                "vs_mesh",
                &mesh_buffers,
                tri,
                true,
                depth(true, wgpu::CompareFunction::Less),
                c,
            )
        });
        let colored_buffers = [Some(POS_LAYOUT), Some(NRM_LAYOUT), Some(COLOR_LAYOUT)];
        let mesh_colored = culls.map(|c| {
            pipeline(
                "mesh colored",
                &mesh_layout,
                "vs_mesh_colored",
                &colored_buffers,
                tri,
                true,
                depth(true, wgpu::CompareFunction::Less),
                c,
            )
        });
        let depth_only = culls.map(|c| {
            pipeline(
                "depth only",
                &mesh_layout,
                "vs_mesh",
                &mesh_buffers,
                tri,
                false,
                depth(true, wgpu::CompareFunction::Less),
                c,
            )
        });
        let lines = pipeline(
            "lines",
            &line_layout,
            "vs_line",
            &[Some(POS_LAYOUT)],
            wgpu::PrimitiveTopology::LineList,
            true,
            depth(true, wgpu::CompareFunction::LessEqual),
            None,
        );
        let style = |c: [f32; 4]| {
            let buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("line style"),
                contents: bytemuck::cast_slice(&[c]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            uniform_group(device, &style_layout, &buf)
        };
        let styles = [style(WIRE_DARK), style(WIRE_LIGHT), style(CONTROL), style(NORMALS)];
        Renderer { format, samples, mesh, mesh_colored, depth_only, lines, view_layout, views: Vec::new(), styles }
    }

    fn uniform(&self, d: &ViewportDraw) -> ViewUniform {
        let aspect = d.rect[2] / d.rect[3].max(1.0);
        let cam = &d.camera;
        let key_world = KEY_LIGHT.normalize();
        let fill_world = FILL_LIGHT.normalize();
        ViewUniform {
            proj: cam.proj(aspect).to_cols_array_2d(),
            view: cam.view().to_cols_array_2d(),
            eye: cam.eye().extend(1.0).to_array(),
            forward: cam.forward().extend(0.0).to_array(),
            key_light: key_world.extend(KEY_INTENSITY).to_array(),
            fill_light: fill_world.extend(FILL_INTENSITY).to_array(),
            front_color: FRONT.to_array(),
            back_color: BACK.to_array(),
            params: [
                f32::from(d.look.surface == Surface::Flat),
                f32::from(!self.format.is_srgb()),
                f32::from(cam.orthographic),
                HEADLIGHT_INTENSITY,
            ],
            line: [0.0015, 0.004 * cam.radius, f32::from(d.look.uv_checker), 0.0],
        }
    }

    /// Writes the uniforms of `draws` and records one render pass that clears
    /// `targets` and draws every viewport, resolving into `resolve` (or
    /// drawing straight into it without MSAA).
    pub fn encode(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        targets: &Targets,
        resolve: &wgpu::TextureView,
        draws: &[ViewportDraw],
    ) {
        while self.views.len() < draws.len() {
            let buf = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("view uniform"),
                size: std::mem::size_of::<ViewUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let group = uniform_group(device, &self.view_layout, &buf);
            self.views.push((buf, group));
        }
        for (d, (buf, _)) in draws.iter().zip(&self.views) {
            queue.write_buffer(buf, 0, bytemuck::bytes_of(&self.uniform(d)));
        }
        let (view, resolve_target) = match &targets.msaa {
            Some(m) => (m, Some(resolve)),
            None => (resolve, None),
        };
        // A non-sRGB target stores what it is given: encode the clear colour like the shader does.
        let [r, g, b] =
            if self.format.is_srgb() { BACKGROUND } else { background_srgb8().map(|c| f64::from(c) / 255.0) };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("scene"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a: 1.0 }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &targets.depth,
                depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Discard }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        let (tw, th) = (targets.size.0 as f32, targets.size.1 as f32);
        for (d, (_, group)) in draws.iter().zip(&self.views) {
            let [x, y, w, h] = d.rect;
            let (x0, y0) = (x.clamp(0.0, tw), y.clamp(0.0, th));
            let (x1, y1) = ((x + w).clamp(0.0, tw), (y + h).clamp(0.0, th));
            if x1 - x0 < 1.0 || y1 - y0 < 1.0 {
                continue;
            }
            // The viewport keeps the full rectangle (so the aspect is right); the scissor clips it.
            pass.set_viewport(x, y, w.max(1.0), h.max(1.0), 0.0, 1.0);
            pass.set_scissor_rect(x0 as u32, y0 as u32, (x1 - x0) as u32, (y1 - y0) as u32);
            pass.set_bind_group(0, group, &[]);
            if let Some(m) = d.mesh {
                let cull = m.cull as usize;
                let shaded = matches!(d.look.surface, Surface::Smooth | Surface::Flat);
                if m.triangle_indices > 0 && (shaded || d.look.wireframe) {
                    pass.set_vertex_buffer(0, m.positions.slice(..));
                    pass.set_vertex_buffer(1, m.normals.slice(..));
                    pass.set_index_buffer(m.triangles.slice(..), wgpu::IndexFormat::Uint32);
                    if !shaded {
                        // Hidden-line wireframe: the faces only fill the depth buffer.
                        pass.set_pipeline(&self.depth_only[cull]);
                        pass.draw_indexed(0..m.triangle_indices, 0, 0..1);
                    }
                    if shaded {
                        match (&m.colors, d.look.colors) {
                            (Some(colors), true) => {
                                pass.set_pipeline(&self.mesh_colored[cull]);
                                pass.set_vertex_buffer(2, colors.slice(..));
                            }
                            _ => pass.set_pipeline(&self.mesh[cull]),
                        }
                        pass.draw_indexed(0..m.triangle_indices, 0, 0..1);
                    }
                }
                pass.set_pipeline(&self.lines);
                if d.look.wireframe && m.edge_indices > 0 {
                    let style = if d.look.surface == Surface::Hidden { 1 } else { 0 };
                    pass.set_bind_group(1, &self.styles[style], &[]);
                    pass.set_vertex_buffer(0, m.positions.slice(..));
                    pass.set_index_buffer(m.edges.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(0..m.edge_indices, 0, 0..1);
                }
                if let (true, Some((buf, count))) = (d.look.normals, &m.normal_lines) {
                    pass.set_bind_group(1, &self.styles[3], &[]);
                    pass.set_vertex_buffer(0, buf.slice(..));
                    pass.draw(0..*count, 0..1);
                }
            }
            if let (true, Some(c)) = (d.look.control, d.control)
                && c.edge_indices > 0
            {
                pass.set_pipeline(&self.lines);
                pass.set_bind_group(1, &self.styles[2], &[]);
                pass.set_vertex_buffer(0, c.positions.slice(..));
                pass.set_index_buffer(c.edges.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..c.edge_indices, 0, 0..1);
            }
            for m in [d.control, d.mesh].into_iter().flatten() {
                if let Some((buf, count)) = &m.highlight {
                    pass.set_pipeline(&self.lines);
                    pass.set_bind_group(1, &self.styles[3], &[]);
                    pass.set_vertex_buffer(0, buf.slice(..));
                    pass.draw(0..*count, 0..1);
                }
            }
        }
    }
}
