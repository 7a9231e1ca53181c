//! The render pipelines of shaders/mesh.wgsl, built once per colour format
//! and sample count.
//!
//! | pipeline      | vertex shader       | buffers               | colour | depth      | per cull mode |
//! |---------------|---------------------|-----------------------|--------|------------|---------------|
//! | `mesh`        | `vs_mesh`           | position, normal      | yes    | write, <   | yes           |
//! | `mesh_colored`| `vs_mesh_colored`   | position, normal, rgb | yes    | write, <   | yes           |
//! | `wire`        | `vs_wire`, `fs_wire`| none: storage, group 2| blend  | write, <   | yes           |
//! | `wire_colored`| `vs_wire_colored`, `fs_wire_colored` | none: storage, group 2 | blend | write, < | yes |
//! | `mesh_textured` | `vs_mesh_colored`, `fs_mesh_textured` | position, normal, uv; group 3 | yes | write, < | yes |
//! | `wire_textured` | `vs_wire_colored`, `fs_wire_textured` | none: storage, group 2; group 3 | blend | write, < | yes |
//! | `lines`       | `vs_line`           | position              | yes    | write, <=  | no            |
//! | `background`  | `vs_background`     | none                  | yes    | always     | no            |
//! | `lines_hidden`| `vs_line`, `fs_line_hidden` | position      | blend  | always     | no            |
//! | `dots`        | `vs_dot`, `fs_dot`  | position per instance | blend  | <=         | no            |
//! | `dots_hidden` | `vs_dot`, `fs_dot_hidden` | position per instance | blend | always | no            |
//!
//! The `_hidden` pipelines draw the control cage faintly where the surface
//! hides it (translucent cage); the dots are its vertices.
//!
//! `wire` draws the faces and their wireframe in one pass, without an index
//! buffer: it reads the mesh from the storage buffers of group 2 by the
//! vertex index (one vertex per corner, see shaders/mesh.wgsl).
//!
//! The `_textured` pipelines draw one material group at a time: group 3
//! binds its texture, sampler and colour ([`super::textures`]), the
//! colour attribute holds the texture coordinates, and the draw is indexed
//! by the mesh's corners ordered by material (for `wire_textured` the
//! index is the corner its storage buffers are read at).
//!
//! The per-cull arrays are indexed by [`super::gpu_mesh::Cull`] `as usize`:
//! closed meshes skip the faces turned away from the eye.

use super::DEPTH_FORMAT;

/// Vertex buffer 0: positions (`@location(0)`).
pub(crate) const POS_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
};
/// Vertex buffer 1: normals (`@location(1)`).
pub(crate) const NRM_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![1 => Float32x3],
};
/// Vertex buffer 2: per-vertex colours or texture coordinates (`@location(2)`).
pub(crate) const COLOR_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![2 => Float32x3],
};

/// Vertex buffer 0 stepped per instance: one point per dot (`@location(0)`).
pub(crate) const POS_INSTANCE_LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Instance,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
};

/// Cull modes in the order of [`super::gpu_mesh::Cull`].
const CULLS: [Option<wgpu::Face>; 3] = [None, Some(wgpu::Face::Back), Some(wgpu::Face::Front)];

/// The pipelines and the bind group layouts they were made with.
pub(crate) struct Pipelines {
    /// Shaded faces, material colour.
    pub mesh: [wgpu::RenderPipeline; 3],
    /// Shaded faces, per-vertex colour.
    pub mesh_colored: [wgpu::RenderPipeline; 3],
    /// The one-pass wireframe, where the device reads storage buffers in
    /// the vertex stage (not WebGL2: there the wireframe is a line list
    /// over the faces).
    pub wires: Option<Wires>,
    /// Where there is no one-pass wireframe: faces that write depth only,
    /// drawn before the line list of the wire shading so that the faces
    /// hide the lines behind them.
    pub hiding: Option<[wgpu::RenderPipeline; 3]>,
    /// Shaded faces of one material group, its texture sampled per pixel.
    pub mesh_textured: [wgpu::RenderPipeline; 3],
    /// Line lists (wireframe, control mesh, normals, highlights).
    pub lines: wgpu::RenderPipeline,
    /// The viewport's background gradient (one full-viewport triangle).
    pub background: wgpu::RenderPipeline,
    /// Line lists where they are hidden: faint, no depth test or write.
    pub lines_hidden: wgpu::RenderPipeline,
    /// Round dots of a constant size in pixels, one per point (instanced quads).
    pub dots: wgpu::RenderPipeline,
    /// The dots where they are hidden: faint.
    pub dots_hidden: wgpu::RenderPipeline,
    /// Group 0: the per-viewport `View` uniform.
    pub view_layout: wgpu::BindGroupLayout,
    /// Group 1 of the line pipeline: the `LineStyle` uniform.
    pub style_layout: wgpu::BindGroupLayout,
    /// Group 3 of the textured pipelines: a material's texture, sampler and colour.
    pub material_layout: wgpu::BindGroupLayout,
}

/// The pipelines that draw faces and their wireframe in one pass, from the
/// mesh's storage buffers (group 2).
pub(crate) struct Wires {
    /// Faces with their wireframe, one pass (also wire only: faces that
    /// only hide the lines behind them), blended over the target.
    pub wire: [wgpu::RenderPipeline; 3],
    /// `wire` with per-vertex colours (or texture coordinates) from group 2.
    pub wire_colored: [wgpu::RenderPipeline; 3],
    /// `wire` for one material group, its texture sampled per pixel.
    pub wire_textured: [wgpu::RenderPipeline; 3],
    /// Group 2: the mesh's storage buffers.
    pub mesh_data_layout: wgpu::BindGroupLayout,
}

impl Wires {
    /// The wire pipelines, where `factory`'s device has the storage
    /// buffers they read in the vertex stage.
    fn new(
        factory: &Factory,
        view_layout: &wgpu::BindGroupLayout,
        material_layout: &wgpu::BindGroupLayout,
    ) -> Option<Wires> {
        let device = factory.device;
        if device.limits().max_storage_buffers_per_shader_stage < MESH_DATA_BINDINGS {
            return None;
        }
        let mesh_data_layout = mesh_data_layout(device);
        let wire_layout = pipeline_layout(device, "wire", &[Some(view_layout), None, Some(&mesh_data_layout)]);
        let wire_spec = |label, vertex_shader, fragment_shader| Spec {
            label,
            layout: &wire_layout,
            vertex_shader,
            buffers: &[],
            topology: wgpu::PrimitiveTopology::TriangleList,
            fragment_shader,
            depth_write: true,
            depth_compare: wgpu::CompareFunction::Less,
            cull_mode: None,
            blend: Some(wgpu::BlendState::ALPHA_BLENDING),
        };
        let wire = factory.per_cull(wire_spec("wire", "vs_wire", "fs_wire"));
        let wire_colored = factory.per_cull(wire_spec("wire colored", "vs_wire_colored", "fs_wire_colored"));
        let wire_textured = textured_wire(factory, [view_layout, &mesh_data_layout, material_layout]);
        Some(Wires { wire, wire_colored, wire_textured, mesh_data_layout })
    }
}

/// The storage buffers of the wire pipeline, in binding order (see
/// shaders/mesh.wgsl): positions, normals, corner vertices, generations,
/// colours.
pub(crate) const MESH_DATA_BINDINGS: u32 = 5;

/// The bind group layout of [`MESH_DATA_BINDINGS`] read-only storage buffers,
/// seen by the vertex stage.
fn mesh_data_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let entries: Vec<wgpu::BindGroupLayoutEntry> = (0..MESH_DATA_BINDINGS)
        .map(|binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::VERTEX,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        })
        .collect();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some("mesh data"), entries: &entries })
}

/// What varies between the pipelines.
struct Spec<'a> {
    label: &'a str,
    layout: &'a wgpu::PipelineLayout,
    vertex_shader: &'a str,
    buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    topology: wgpu::PrimitiveTopology,
    fragment_shader: &'a str,
    depth_write: bool,
    depth_compare: wgpu::CompareFunction,
    cull_mode: Option<wgpu::Face>,
    blend: Option<wgpu::BlendState>,
}

/// What every pipeline shares.
struct Factory<'a> {
    device: &'a wgpu::Device,
    shader: wgpu::ShaderModule,
    format: wgpu::TextureFormat,
    samples: u32,
}

impl Factory<'_> {
    fn build(&self, spec: &Spec) -> wgpu::RenderPipeline {
        self.build_writing(spec, wgpu::ColorWrites::ALL)
    }

    /// [`Factory::build`] writing only the colour channels `write_mask`
    /// (none: depth only).
    fn build_writing(&self, spec: &Spec, write_mask: wgpu::ColorWrites) -> wgpu::RenderPipeline {
        let fragment_shader = spec.fragment_shader;
        self.device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(spec.label),
            layout: Some(spec.layout),
            vertex: wgpu::VertexState {
                module: &self.shader,
                entry_point: Some(spec.vertex_shader),
                compilation_options: Default::default(),
                buffers: spec.buffers,
            },
            primitive: wgpu::PrimitiveState {
                topology: spec.topology,
                cull_mode: spec.cull_mode,
                ..Default::default()
            },
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(spec.depth_write),
                depth_compare: Some(spec.depth_compare),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: wgpu::MultisampleState { count: self.samples, mask: !0, alpha_to_coverage_enabled: false },
            fragment: Some(wgpu::FragmentState {
                module: &self.shader,
                entry_point: Some(fragment_shader),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState { format: self.format, blend: spec.blend, write_mask })],
            }),
            multiview_mask: None,
            cache: None,
        })
    }

    /// One triangle pipeline per cull mode.
    fn per_cull(&self, spec: Spec) -> [wgpu::RenderPipeline; 3] {
        CULLS.map(|cull_mode| self.build(&Spec { cull_mode, ..spec }))
    }
}

/// The line list and dot pipelines (with `layout`: view and line style):
/// lines, lines where hidden, dots, dots where hidden.
fn lines_and_dots(factory: &Factory, layout: &wgpu::PipelineLayout) -> [wgpu::RenderPipeline; 4] {
    let line_spec = Spec {
        label: "lines",
        layout,
        vertex_shader: "vs_line",
        buffers: &[Some(POS_LAYOUT)],
        topology: wgpu::PrimitiveTopology::LineList,
        fragment_shader: "fs_line",
        depth_write: true,
        depth_compare: wgpu::CompareFunction::LessEqual,
        cull_mode: None,
        blend: Some(wgpu::BlendState::ALPHA_BLENDING),
    };
    let blend = Some(wgpu::BlendState::ALPHA_BLENDING);
    let always = wgpu::CompareFunction::Always;
    let hidden =
        Spec { fragment_shader: "fs_line_hidden", depth_write: false, depth_compare: always, blend, ..line_spec };
    let dot_spec = Spec {
        label: "dots",
        vertex_shader: "vs_dot",
        buffers: &[Some(POS_INSTANCE_LAYOUT)],
        topology: wgpu::PrimitiveTopology::TriangleList,
        fragment_shader: "fs_dot",
        depth_write: false,
        blend,
        ..line_spec
    };
    let dots_hidden = Spec { fragment_shader: "fs_dot_hidden", depth_compare: always, ..dot_spec };
    [&line_spec, &hidden, &dot_spec, &dots_hidden].map(|spec| factory.build(spec))
}

/// The textured faces' pipelines (group 3 the material).
fn textured(factory: &Factory, [view, material]: [&wgpu::BindGroupLayout; 2]) -> [wgpu::RenderPipeline; 3] {
    let faces = pipeline_layout(factory.device, "mesh textured", &[Some(view), None, None, Some(material)]);
    factory.per_cull(textured_spec(&faces))
}

/// The textured faces' pipeline description, on `layout`.
fn textured_spec(layout: &wgpu::PipelineLayout) -> Spec<'_> {
    Spec {
        label: "mesh textured",
        layout,
        vertex_shader: "vs_mesh_colored",
        buffers: &[Some(POS_LAYOUT), Some(NRM_LAYOUT), Some(COLOR_LAYOUT)],
        topology: wgpu::PrimitiveTopology::TriangleList,
        fragment_shader: "fs_mesh_textured",
        depth_write: true,
        depth_compare: wgpu::CompareFunction::Less,
        cull_mode: None,
        blend: None,
    }
}

/// The textured faces with their wire (group 3 the material, group 2 the
/// wire's storage buffers).
fn textured_wire(
    factory: &Factory,
    [view, mesh_data, material]: [&wgpu::BindGroupLayout; 3],
) -> [wgpu::RenderPipeline; 3] {
    let wire = pipeline_layout(factory.device, "wire textured", &[Some(view), None, Some(mesh_data), Some(material)]);
    factory.per_cull(Spec {
        label: "wire textured",
        vertex_shader: "vs_wire_colored",
        buffers: &[],
        fragment_shader: "fs_wire_textured",
        blend: Some(wgpu::BlendState::ALPHA_BLENDING),
        ..textured_spec(&wire)
    })
}

/// A bind group layout with one uniform buffer at binding 0.
pub(crate) fn uniform_layout(device: &wgpu::Device, label: &str) -> wgpu::BindGroupLayout {
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

/// A bind group of `layout` (from [`uniform_layout`]) holding `buf`.
pub(crate) fn uniform_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    buf: &wgpu::Buffer,
) -> wgpu::BindGroup {
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout,
        entries: &[wgpu::BindGroupEntry { binding: 0, resource: buf.as_entire_binding() }],
    })
}

fn pipeline_layout(
    device: &wgpu::Device,
    label: &str,
    groups: &[Option<&wgpu::BindGroupLayout>],
) -> wgpu::PipelineLayout {
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: groups,
        immediate_size: 0,
    })
}

impl Pipelines {
    /// Every pipeline for colour targets of `format` with `samples` MSAA samples.
    pub(crate) fn new(device: &wgpu::Device, format: wgpu::TextureFormat, samples: u32) -> Pipelines {
        let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("mesh.wgsl"),
            source: wgpu::ShaderSource::Wgsl(include_str!("../../shaders/mesh.wgsl").into()),
        });
        let factory = Factory { device, shader, format, samples };
        let view_layout = uniform_layout(device, "view");
        let style_layout = uniform_layout(device, "line style");
        let mesh_layout = pipeline_layout(device, "mesh", &[Some(&view_layout)]);
        let line_layout = pipeline_layout(device, "lines", &[Some(&view_layout), Some(&style_layout)]);
        let shaded = [Some(POS_LAYOUT), Some(NRM_LAYOUT)];
        let colored = [Some(POS_LAYOUT), Some(NRM_LAYOUT), Some(COLOR_LAYOUT)];
        let faces = |label, vertex_shader, buffers, fragment_shader| Spec {
            label,
            layout: &mesh_layout,
            vertex_shader,
            buffers,
            topology: wgpu::PrimitiveTopology::TriangleList,
            fragment_shader,
            depth_write: true,
            depth_compare: wgpu::CompareFunction::Less,
            cull_mode: None,
            blend: None,
        };
        let mesh = factory.per_cull(faces("mesh", "vs_mesh", &shaded, "fs_mesh"));
        let mesh_colored = factory.per_cull(faces("mesh colored", "vs_mesh_colored", &colored, "fs_mesh"));
        let [lines, lines_hidden, dots, dots_hidden] = lines_and_dots(&factory, &line_layout);
        let material_layout = super::textures::material_layout(device);
        let mesh_textured = textured(&factory, [&view_layout, &material_layout]);
        let wires = Wires::new(&factory, &view_layout, &material_layout);
        let hiding = wires.is_none().then(|| {
            let spec = faces("faces hiding lines", "vs_mesh", &shaded, "fs_mesh");
            CULLS.map(|cull_mode| factory.build_writing(&Spec { cull_mode, ..spec }, wgpu::ColorWrites::empty()))
        });
        let background = factory.build(&Spec {
            label: "background",
            layout: &mesh_layout,
            blend: None,
            depth_write: false,
            depth_compare: wgpu::CompareFunction::Always,
            ..faces("background", "vs_background", &[], "fs_background")
        });
        Pipelines {
            mesh,
            mesh_colored,
            wires,
            hiding,
            mesh_textured,
            lines,
            background,
            lines_hidden,
            dots,
            dots_hidden,
            view_layout,
            style_layout,
            material_layout,
        }
    }
}
