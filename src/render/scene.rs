//! The 3D pass shared by the window and offscreen rendering
//! (shaders/mesh.wgsl): per-viewport uniforms, then one render pass that
//! clears the targets and draws every viewport.
//!
//! Per viewport, in this order: the faces (shaded; with the wireframe on,
//! the faces and their wireframe in one pass of the `wire` pipeline), the
//! normal segments, the control mesh's edges, the highlighted segments. The
//! wireframe's hidden lines are hidden by the faces of the same pass; the
//! line lists (cage, normals, highlights) are pulled slightly towards the
//! eye so they win against the faces they lie on.

use super::camera::Camera;
use super::pipelines::{Pipelines, uniform_group};
use super::textures::GpuMaterials;
use super::{DEPTH_FORMAT, Look, Surface};
use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec4};
use wgpu::util::DeviceExt;

pub(crate) use super::gpu_mesh::GpuMesh;

/// Background colour (linear RGB) of the window outside the viewports.
pub(crate) const BACKGROUND: [f64; 3] = [0.045, 0.05, 0.065];
/// The quiet vertical gradient behind every viewport (linear RGB): its top
/// and bottom rows (shaders/mesh.wgsl, `fs_background`).
pub(crate) const BACKGROUND_TOP: Vec3 = Vec3::new(0.075, 0.08, 0.1);
/// See [`BACKGROUND_TOP`].
pub(crate) const BACKGROUND_BOTTOM: Vec3 = Vec3::new(0.025, 0.027, 0.036);

/// Linear colour of front faces (the material).
pub const FRONT: Vec4 = Vec4::new(0.32, 0.40, 0.58, 1.0);
/// Linear colours of back faces and lines.
const BACK: Vec4 = Vec4::new(0.62, 0.30, 0.16, 1.0);
const WIRE_DARK: [f32; 4] = [0.015, 0.02, 0.035, 1.0];
const WIRE_LIGHT: [f32; 4] = [0.80, 0.84, 0.92, 1.0];
/// The cage: translucent, so the surface reads through a dense one.
const CONTROL: [f32; 4] = [1.0, 0.38, 0.03, 0.75];
/// A dense cage (over [`CAGE_DETAIL_UP_TO`] vertices): fainter still, so the
/// shaded surface stays the first thing one sees under it.
const CONTROL_DENSE: [f32; 4] = [1.0, 0.38, 0.03, 0.45];
/// Cages with more vertices than this are drawn without dots and without
/// their hidden part: on a dense cage they would cover the surface.
pub(crate) const CAGE_DETAIL_UP_TO: usize = 500;
const NORMALS: [f32; 4] = [0.15, 0.85, 0.25, 1.0];
/// Sharp edges (creases): magenta, apart from the orange cage and green normals.
const SHARP: [f32; 4] = [0.92, 0.12, 0.62, 1.0];

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
pub(crate) fn background_srgb8() -> [u8; 3] {
    BACKGROUND.map(|c| {
        let s = if c <= 0.0031308 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
        (s * 255.0).round().clamp(0.0, 255.0) as u8
    })
}

/// The 8-bit sRGB value of the background gradient in row `y` of a
/// viewport `height` pixels high (what an opaque render shows where nothing
/// is drawn).
pub fn background_srgb8_at(y: u32, height: u32) -> [u8; 3] {
    let t = (y as f32 + 0.5) / height.max(1) as f32;
    let c = BACKGROUND_TOP.lerp(BACKGROUND_BOTTOM, t);
    c.to_array().map(|c| {
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
    wire: [f32; 4],
    viewport: [f32; 4],
    stripes: [f32; 4],
    contour: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<ViewUniform>().is_multiple_of(16), "uniforms are arrays of vec4");

/// Multisampled colour and depth attachments of one size.
pub struct Targets {
    msaa: Option<wgpu::TextureView>,
    /// Without MSAA: the scene before the FXAA pass, and its bind group.
    post: Option<(wgpu::TextureView, wgpu::BindGroup)>,
    depth: wgpu::TextureView,
    /// Size in pixels.
    pub size: (u32, u32),
}

impl Targets {
    /// Attachments for a `width` x `height` target of the renderer's format.
    pub(crate) fn new(device: &wgpu::Device, renderer: &Renderer, width: u32, height: u32) -> Targets {
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
        let post = (renderer.samples == 1).then(|| {
            let view = device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some("before fxaa"),
                    size,
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: renderer.format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
                    view_formats: &[],
                })
                .create_view(&Default::default());
            let group = renderer.fxaa_pass.bind(device, &view);
            (view, group)
        });
        Targets { msaa, post, depth: make(DEPTH_FORMAT, "depth"), size: (size.width, size.height) }
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

/// Line colours, in the order of [`Renderer`]'s style bind groups.
const STYLES: [[f32; 4]; 6] = [WIRE_DARK, WIRE_LIGHT, CONTROL, NORMALS, SHARP, CONTROL_DENSE];
const STYLE_WIRE_DARK: usize = 0;
const STYLE_WIRE_LIGHT: usize = 1;
const STYLE_CONTROL: usize = 2;
const STYLE_NORMALS: usize = 3;
const STYLE_SHARP: usize = 4;
const STYLE_CONTROL_DENSE: usize = 5;

/// Width of wireframe lines in pixels (at [`Renderer::pixel_scale`] 1).
pub(crate) const WIRE_WIDTH: f32 = 1.5;
/// Radius of the control cage's vertex dots in pixels (at scale 1).
pub(crate) const DOT_RADIUS: f32 = 3.0;
/// Width of isolines in pixels (at scale 1); the zero level's is twice it.
pub(crate) const ISOLINE_WIDTH: f32 = 1.25;
/// How strongly a wire line darkens the shading under it (0..1).
pub(crate) const WIRE_STRENGTH: f32 = 0.8;

/// Pipelines and per-viewport uniforms.
pub struct Renderer {
    /// Colour target format.
    pub format: wgpu::TextureFormat,
    /// MSAA sample count of the pipelines.
    pub samples: u32,
    /// Pixels per logical pixel: line widths are multiplied by it (a
    /// screenshot `N` times the window's size sets `N`).
    pub pixel_scale: f32,
    /// Clear the background to alpha 0 (a screenshot for compositing).
    pub transparent: bool,
    /// Without MSAA, smooth edges with the FXAA pass (on by default).
    pub fxaa: bool,
    fxaa_pass: super::blit::Blit,
    pipelines: Pipelines,
    views: Vec<(wgpu::Buffer, wgpu::BindGroup)>,
    styles: [wgpu::BindGroup; 6],
}

impl Renderer {
    /// Pipelines for colour targets of `format` with `samples` MSAA samples.
    pub(crate) fn new(device: &wgpu::Device, format: wgpu::TextureFormat, samples: u32) -> Renderer {
        let pipelines = Pipelines::new(device, format, samples);
        let styles = STYLES.map(|c| {
            let buf = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("line style"),
                contents: bytemuck::cast_slice(&[c]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            uniform_group(device, &pipelines.style_layout, &buf)
        });
        let fxaa_pass = super::blit::Blit::fxaa(device, format);
        Renderer {
            format,
            samples,
            pixel_scale: 1.0,
            transparent: false,
            fxaa: true,
            fxaa_pass,
            pipelines,
            views: Vec::new(),
            styles,
        }
    }

    fn uniform(&self, d: &ViewportDraw) -> ViewUniform {
        let aspect = d.rect[2] / d.rect[3].max(1.0);
        let cam = &d.camera;
        let colors = d.mesh.is_some_and(|m| shown_colors(m, d.look).is_some() || shown_materials(m, d.look).is_some());
        // values only ride in a colour buffer the look shows (never under materials)
        let values = d.look.values
            && d.mesh.is_some_and(|m| shown_colors(m, d.look).is_some() && shown_materials(m, d.look).is_none());
        ViewUniform {
            proj: cam.proj(aspect).to_cols_array_2d(),
            view: cam.view().to_cols_array_2d(),
            eye: cam.eye().extend(1.0).to_array(),
            forward: cam.forward().extend(0.0).to_array(),
            key_light: KEY_LIGHT.normalize().extend(KEY_INTENSITY).to_array(),
            fill_light: FILL_LIGHT.normalize().extend(FILL_INTENSITY).to_array(),
            front_color: FRONT.to_array(),
            back_color: BACK.to_array(),
            params: [
                match d.look.surface {
                    Surface::Flat => 1.0,
                    Surface::Studio => 2.0,
                    Surface::Zebra => 3.0,
                    Surface::Isophotes => 4.0,
                    _ => 0.0,
                },
                f32::from(!self.format.is_srgb()),
                f32::from(cam.orthographic),
                HEADLIGHT_INTENSITY,
            ],
            line: [0.0015, 0.004 * cam.radius, f32::from(d.look.uv_checker), f32::from(colors)],
            wire: [
                WIRE_WIDTH * self.pixel_scale,
                f32::from(d.look.wire_edges.max_generation()),
                f32::from(d.look.surface == Surface::Hidden),
                WIRE_STRENGTH,
            ],
            viewport: [d.rect[2], d.rect[3], DOT_RADIUS * self.pixel_scale, d.rect[1]],
            stripes: [f32::from(d.look.stripes.count.max(1)), f32::from(d.look.stripes.angle).to_radians(), 0.0, 0.0],
            contour: [
                f32::from(values),
                f32::from(d.look.isolines.min(crate::subdiv::eval::color::MAX_ISOLINES)),
                ISOLINE_WIDTH * self.pixel_scale,
                0.0,
            ],
        }
    }

    /// Writes the uniforms of `draws` and records one render pass that clears
    /// `targets` and draws every viewport, resolving into `resolve` (or
    /// drawing straight into it without MSAA).
    pub(crate) fn encode(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        targets: &Targets,
        resolve: &wgpu::TextureView,
        draws: &[ViewportDraw],
    ) {
        self.write_uniforms(device, queue, draws);
        if let Some(wires) = &self.pipelines.wires {
            for m in draws.iter().filter(|d| d.look.wireframe).filter_map(|d| d.mesh) {
                m.data_group(device, &wires.mesh_data_layout);
            }
        }
        for mats in draws.iter().filter_map(|d| d.mesh.and_then(|m| shown_materials(m, d.look))) {
            mats.bind_groups(device, &self.pipelines.material_layout);
        }
        // without MSAA the scene goes through the FXAA pass on its way to `resolve`
        let post = targets.post.as_ref().filter(|_| self.fxaa);
        let scene = post.map_or(resolve, |(view, _)| view);
        let mut pass = self.begin_pass(encoder, targets, scene);
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
            self.draw_viewport(&mut pass, d);
        }
        drop(pass);
        if let Some((_, group)) = post {
            self.fxaa_pass.draw(encoder, group, resolve);
        }
    }

    /// One uniform buffer per viewport (grown on demand), written with its camera and look.
    fn write_uniforms(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, draws: &[ViewportDraw]) {
        while self.views.len() < draws.len() {
            let buf = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("view uniform"),
                size: std::mem::size_of::<ViewUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let group = uniform_group(device, &self.pipelines.view_layout, &buf);
            self.views.push((buf, group));
        }
        for (d, (buf, _)) in draws.iter().zip(&self.views) {
            queue.write_buffer(buf, 0, bytemuck::bytes_of(&self.uniform(d)));
        }
    }

    /// The scene pass: clears colour to the background and depth to 1.
    fn begin_pass<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        targets: &Targets,
        resolve: &wgpu::TextureView,
    ) -> wgpu::RenderPass<'e> {
        let (view, resolve_target) = match &targets.msaa {
            Some(m) => (m, Some(resolve)),
            None => (resolve, None),
        };
        // A non-sRGB target stores what it is given: encode the clear colour like the shader does.
        let [r, g, b] =
            if self.format.is_srgb() { BACKGROUND } else { background_srgb8().map(|c| f64::from(c) / 255.0) };
        encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("scene"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a: if self.transparent { 0.0 } else { 1.0 } }),
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
        })
    }

    /// Everything one viewport shows, in drawing order.
    fn draw_viewport(&self, pass: &mut wgpu::RenderPass, d: &ViewportDraw) {
        if !self.transparent {
            pass.set_pipeline(&self.pipelines.background);
            pass.draw(0..3, 0..1);
        }
        if let Some(m) = d.mesh {
            let wires = self.pipelines.wires.as_ref().filter(|_| d.look.wireframe);
            let wire_group = wires.and_then(|w| Some((w, m.data_group.get()?.as_ref()?)));
            if let Some(mats) = shown_materials(m, d.look) {
                self.draw_materials(pass, m, mats, d.look, wire_group);
            } else if let Some((wires, group)) = wire_group {
                let wire = if shown_colors(m, d.look).is_some() { &wires.wire_colored } else { &wires.wire };
                pass.set_pipeline(&wire[m.cull as usize]);
                pass.set_bind_group(2, group, &[]);
                pass.draw(0..m.triangle_indices, 0..1);
            } else {
                self.draw_faces(pass, m, d.look);
            }
            // a mesh of lines only (a curve), or a device without the one-pass
            // wire (WebGL2): the wireframe is its edges as lines
            let line_wire = m.triangle_indices == 0 || self.pipelines.wires.is_none();
            if let (true, Surface::Hidden, Some(hiding)) = (d.look.wireframe, d.look.surface, &self.pipelines.hiding) {
                // the faces in depth only: the lines behind them stay hidden
                pass.set_pipeline(&hiding[m.cull as usize]);
                bind_faces(pass, m);
                pass.draw_indexed(0..m.triangle_indices, 0, 0..1);
            }
            if d.look.wireframe && line_wire && m.edge_indices > 0 {
                let style = if d.look.surface == Surface::Hidden { STYLE_WIRE_LIGHT } else { STYLE_WIRE_DARK };
                self.draw_edges(pass, m, style);
            }
            if let (true, Some((buf, count))) = (d.look.normals, &m.normal_lines) {
                self.draw_segments(pass, buf, *count, STYLE_NORMALS);
            }
            if let (true, Some(sharp)) = (d.look.sharp, &m.sharp) {
                self.draw_indexed_lines(pass, m, sharp, STYLE_SHARP);
            }
        }
        if let (true, Some(c)) = (d.look.control, d.control)
            && c.edge_indices > 0
        {
            self.draw_cage(pass, c);
            if let (true, Some(sharp)) = (d.look.sharp, &c.sharp) {
                self.draw_indexed_lines(pass, c, sharp, STYLE_SHARP);
            }
        }
        for m in [d.control, d.mesh].into_iter().flatten() {
            if let Some((buf, count)) = &m.highlight {
                self.draw_segments(pass, buf, *count, STYLE_NORMALS);
            }
        }
    }

    /// The shaded faces (material or per-vertex colour); nothing when the
    /// surface is hidden.
    fn draw_faces(&self, pass: &mut wgpu::RenderPass, m: &GpuMesh, look: Look) {
        let shaded = look.surface != Surface::Hidden;
        if m.triangle_indices == 0 || !shaded {
            return;
        }
        let cull = m.cull as usize;
        bind_faces(pass, m);
        if let Some(colors) = shown_colors(m, look) {
            pass.set_pipeline(&self.pipelines.mesh_colored[cull]);
            pass.set_vertex_buffer(2, colors.slice(..));
        } else {
            pass.set_pipeline(&self.pipelines.mesh[cull]);
        }
        pass.draw_indexed(0..m.triangle_indices, 0, 0..1);
    }

    /// The faces one material group at a time, each with its material
    /// bound (and with their wireframe, through `wire`'s storage buffers,
    /// when given); nothing when the surface is hidden without a wire.
    fn draw_materials(
        &self,
        pass: &mut wgpu::RenderPass,
        m: &GpuMesh,
        mats: &GpuMaterials,
        look: Look,
        wire: Option<(&super::pipelines::Wires, &wgpu::BindGroup)>,
    ) {
        let (Some(groups), Some(uv)) = (mats.made_groups(), &m.colors) else { return };
        let cull = m.cull as usize;
        if let Some((wires, wire)) = wire {
            pass.set_pipeline(&wires.wire_textured[cull]);
            pass.set_bind_group(2, wire, &[]);
        } else {
            if m.triangle_indices == 0 || look.surface == Surface::Hidden {
                return;
            }
            pass.set_pipeline(&self.pipelines.mesh_textured[cull]);
            pass.set_vertex_buffer(0, m.positions.slice(..));
            pass.set_vertex_buffer(1, m.normals.slice(..));
            pass.set_vertex_buffer(2, uv.slice(..));
        }
        pass.set_index_buffer(mats.order.slice(..), wgpu::IndexFormat::Uint32);
        for run in &mats.runs {
            let Some(group) = groups.get(run.material) else { continue };
            pass.set_bind_group(3, group, &[]);
            pass.draw_indexed(run.corners.clone(), 0, 0..1);
        }
    }

    /// The control cage: its edges and vertices (dots), faint where the
    /// surface hides them, full where they show.
    fn draw_cage(&self, pass: &mut wgpu::RenderPass, c: &GpuMesh) {
        let p = &self.pipelines;
        let detail = c.vertex_count <= CAGE_DETAIL_UP_TO;
        let style = if detail { STYLE_CONTROL } else { STYLE_CONTROL_DENSE };
        pass.set_bind_group(1, &self.styles[style], &[]);
        pass.set_vertex_buffer(0, c.positions.slice(..));
        pass.set_index_buffer(c.edges.slice(..), wgpu::IndexFormat::Uint32);
        if detail {
            pass.set_pipeline(&p.lines_hidden);
            pass.draw_indexed(0..c.edge_indices, 0, 0..1);
        }
        pass.set_pipeline(&p.lines);
        pass.draw_indexed(0..c.edge_indices, 0, 0..1);
        if detail {
            for dots in [&p.dots_hidden, &p.dots] {
                pass.set_pipeline(dots);
                pass.draw(0..6, 0..c.vertex_count as u32);
            }
        }
    }

    /// A mesh's edge list as lines of one style.
    fn draw_edges(&self, pass: &mut wgpu::RenderPass, m: &GpuMesh, style: usize) {
        pass.set_pipeline(&self.pipelines.lines);
        pass.set_bind_group(1, &self.styles[style], &[]);
        pass.set_vertex_buffer(0, m.positions.slice(..));
        pass.set_index_buffer(m.edges.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..m.edge_indices, 0, 0..1);
    }

    /// Lines between the vertices of `m` that `indices` pairs, in one style.
    fn draw_indexed_lines(
        &self,
        pass: &mut wgpu::RenderPass,
        m: &GpuMesh,
        indices: &(wgpu::Buffer, u32),
        style: usize,
    ) {
        pass.set_pipeline(&self.pipelines.lines);
        pass.set_bind_group(1, &self.styles[style], &[]);
        pass.set_vertex_buffer(0, m.positions.slice(..));
        pass.set_index_buffer(indices.0.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..indices.1, 0, 0..1);
    }

    /// `count` points of `buf`, two per segment, as lines of one style.
    fn draw_segments(&self, pass: &mut wgpu::RenderPass, buf: &wgpu::Buffer, count: u32, style: usize) {
        pass.set_pipeline(&self.pipelines.lines);
        pass.set_bind_group(1, &self.styles[style], &[]);
        pass.set_vertex_buffer(0, buf.slice(..));
        pass.draw(0..count, 0..1);
    }
}

/// The per-vertex colours a mesh is drawn with under `look`: its colour
/// buffer when it has one and the look shows colours. The one place that
/// decides it, for the uniforms, the wire pipeline and the face pipeline.
fn shown_colors(m: &GpuMesh, look: Look) -> Option<&wgpu::Buffer> {
    m.colors.as_ref().filter(|_| look.colors)
}

/// The material groups a mesh is drawn with under `look`: its materials
/// when it has them and the look shows materials.
fn shown_materials(m: &GpuMesh, look: Look) -> Option<&GpuMaterials> {
    m.materials.as_ref().filter(|_| look.materials)
}

/// Binds `m`'s positions, normals and triangles for a draw of its faces.
fn bind_faces(pass: &mut wgpu::RenderPass, m: &GpuMesh) {
    pass.set_vertex_buffer(0, m.positions.slice(..));
    pass.set_vertex_buffer(1, m.normals.slice(..));
    pass.set_index_buffer(m.triangles.slice(..), wgpu::IndexFormat::Uint32);
}
