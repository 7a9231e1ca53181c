//! Materials on the GPU: per material a texture (sRGB, with its mipmaps),
//! a sampler with the material's wrap modes and a uniform with its colour
//! factor, bound as group 3 of the textured pipelines (shaders/mesh.wgsl
//! `material_color`), and the mesh's corners ordered by material so each
//! group is one draw of a range of that order.
//!
//! The colour of a fragment is the factor (MTL `Kd`, glTF
//! `baseColorFactor`) times the texture sampled at the interpolated
//! texture coordinate, trilinear: the texture is an `Rgba8UnormSrgb` one,
//! so the hardware decodes to linear light before it filters. A material
//! without a texture (or a mesh without texture coordinates) is its factor
//! alone: a 1 x 1 white texture is bound in its place.

use super::materials::{Run, material_runs, mip_chain};
use crate::mesh::attributes::{Material, MaterialGroups, Texture, Wrap};
use glam::Vec3;
use std::sync::Arc;
use wgpu::util::DeviceExt;

/// The colour of corners whose material id names no material.
const MISSING: Vec3 = Vec3::splat(0.8);

/// One material as bound: its texture, sampler and colour factor.
struct Slot {
    view: Arc<wgpu::TextureView>,
    sampler: wgpu::Sampler,
    uniform: wgpu::Buffer,
}

/// The materials of a mesh on the GPU (see the module's text).
pub struct GpuMaterials {
    /// The corners ordered by material: an index buffer of the mesh's
    /// per-corner vertices.
    pub(super) order: wgpu::Buffer,
    /// The range of `order` each material draws.
    pub(super) runs: Vec<Run>,
    slots: Vec<Slot>,
    /// The textures bound, in the order the materials first use them.
    textures: Vec<Uploaded>,
    /// How many of them were uploaded here.
    #[cfg_attr(not(test), allow(dead_code))]
    uploaded: usize,
    /// The bind group of each slot, made on first draw with the renderer's layout.
    groups: std::sync::OnceLock<Vec<wgpu::BindGroup>>,
}

/// The uniform of a material (see `SurfaceMaterial` in shaders/mesh.wgsl).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct MaterialUniform {
    /// Linear RGB factor, w unused.
    factor: [f32; 4],
    /// x: 1 = sample the texture.
    flags: [f32; 4],
}

/// The sampler address mode of a wrap mode.
fn address(w: Wrap) -> wgpu::AddressMode {
    match w {
        Wrap::Repeat => wgpu::AddressMode::Repeat,
        Wrap::Clamp => wgpu::AddressMode::ClampToEdge,
        Wrap::Mirror => wgpu::AddressMode::MirrorRepeat,
    }
}

/// Uploads `t` with its mipmaps as an sRGB texture.
fn upload_texture(device: &wgpu::Device, queue: &wgpu::Queue, t: &Texture) -> wgpu::Texture {
    let levels = mip_chain(t, device.limits().max_texture_dimension_2d);
    let size = |l: &Texture| wgpu::Extent3d { width: l.width, height: l.height, depth_or_array_layers: 1 };
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("material texture"),
        size: size(&levels[0]),
        mip_level_count: levels.len() as u32,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    for (k, l) in levels.iter().enumerate() {
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: k as u32,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            &l.rgba,
            wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(4 * l.width), rows_per_image: Some(l.height) },
            size(l),
        );
    }
    texture
}

/// Whether `t` has pixels and exactly the bytes its size says.
fn is_whole(t: &Texture) -> bool {
    t.width > 0 && t.height > 0 && t.rgba.len() as u64 == 4 * u64::from(t.width) * u64::from(t.height)
}

/// A trilinear, anisotropic sampler with the wrap modes along `u` and `v`.
fn sampler(device: &wgpu::Device, wrap: [Wrap; 2]) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("material sampler"),
        address_mode_u: address(wrap[0]),
        address_mode_v: address(wrap[1]),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        mipmap_filter: wgpu::MipmapFilterMode::Linear,
        // a face seen at a grazing angle stays sharp along its length (wgpu
        // takes 1 where the device filters only isotropically)
        anisotropy_clamp: 8,
        ..Default::default()
    })
}

/// A texture on the GPU and the pixels it was made from (`None`: the white
/// texel of untextured materials).
struct Uploaded {
    pixels: Option<Arc<Texture>>,
    view: Arc<wgpu::TextureView>,
    mips: u32,
}

/// The textures of a mesh's materials, each uploaded once however many
/// materials share it (or taken from the materials the mesh replaces, when
/// they drew the same pixels), and the white one of the untextured.
struct Uploads<'a> {
    device: &'a wgpu::Device,
    queue: &'a wgpu::Queue,
    reuse: &'a [Uploaded],
    done: Vec<Uploaded>,
    uploaded: usize,
}

impl Uploads<'_> {
    fn view(&mut self, t: Option<&Arc<Texture>>) -> Arc<wgpu::TextureView> {
        let same = |u: &&Uploaded| match (&u.pixels, t) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (a, b) => a.is_none() && b.is_none(),
        };
        if let Some(u) = self.done.iter().find(same) {
            return u.view.clone();
        }
        let u = match self.reuse.iter().find(same) {
            Some(u) => Uploaded { pixels: u.pixels.clone(), view: u.view.clone(), mips: u.mips },
            None => {
                let white = Texture { width: 1, height: 1, rgba: vec![255; 4] };
                let texture = upload_texture(self.device, self.queue, t.map_or(&white, |t| &**t));
                let view = Arc::new(texture.create_view(&Default::default()));
                self.uploaded += 1;
                Uploaded { pixels: t.cloned(), view, mips: texture.mip_level_count() }
            }
        };
        let view = u.view.clone();
        self.done.push(u);
        view
    }
}

/// The materials of a mesh to draw: its groups, its texture coordinates
/// (one per corner) and the materials it replaces, whose textures are
/// taken where they are the same pixels rather than uploaded again (the
/// viewer's next level keeps the model's textures).
#[derive(Clone, Copy)]
pub struct MaterialDraw<'a> {
    /// The groups, one material per triangle.
    pub groups: &'a MaterialGroups,
    /// Texture coordinates, one per corner; `None` (or too few) draws the
    /// flat colours.
    pub uv: Option<&'a [glam::Vec2]>,
    /// The materials of the mesh this one replaces.
    pub reuse: Option<&'a GpuMaterials>,
}

impl GpuMaterials {
    /// The materials of `groups` for a mesh of `groups.face.len()` triangles
    /// drawn one GPU vertex per corner; `textured` false (no texture
    /// coordinates) draws every material in its flat colour.
    pub(crate) fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        groups: &MaterialGroups,
        textured: bool,
        reuse: Option<&GpuMaterials>,
    ) -> GpuMaterials {
        let (order, runs) = material_runs(&groups.face, groups.list.len());
        let reuse = reuse.map_or(&[][..], |r| &r.textures[..]);
        let mut up = Uploads { device, queue, reuse, done: Vec::new(), uploaded: 0 };
        let mut slots = Vec::with_capacity(groups.list.len() + 1);
        // a slot for ids that name no material, when some triangle has one
        let missing = runs
            .last()
            .filter(|r| r.material == groups.list.len())
            .map(|_| Material { diffuse: MISSING, ..Material::named("") });
        for m in groups.list.iter().chain(missing.as_ref()) {
            // (pixels that do not fill the size they claim are not drawn)
            let texture = m.texture.as_ref().filter(|t| textured && is_whole(t));
            let u = MaterialUniform {
                factor: m.diffuse.max(Vec3::ZERO).extend(1.0).to_array(),
                flags: [f32::from(texture.is_some()), 0.0, 0.0, 0.0],
            };
            let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("material"),
                contents: bytemuck::bytes_of(&u),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            slots.push(Slot { view: up.view(texture), sampler: sampler(device, m.wrap), uniform });
        }
        let mut bytes: Vec<u8> = bytemuck::cast_slice(&order).to_vec();
        bytes.resize(bytes.len().max(16), 0);
        let order = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("corners by material"),
            contents: &bytes,
            usage: wgpu::BufferUsages::INDEX,
        });
        GpuMaterials {
            order,
            runs,
            slots,
            textures: up.done,
            uploaded: up.uploaded,
            groups: std::sync::OnceLock::new(),
        }
    }

    /// How many of the textures bound were uploaded for these materials
    /// (the others were taken over from the materials they replace).
    #[cfg(test)]
    pub(crate) fn uploaded(&self) -> usize {
        self.uploaded
    }

    /// The mip level count of each texture bound (the white one of
    /// untextured materials included), in the order the materials first
    /// use them.
    pub fn mip_level_counts(&self) -> Vec<u32> {
        self.textures.iter().map(|u| u.mips).collect()
    }

    /// The bind group of each material (made once) with `layout` (from
    /// [`material_layout`]).
    pub(super) fn bind_groups(&self, device: &wgpu::Device, layout: &wgpu::BindGroupLayout) -> &[wgpu::BindGroup] {
        self.groups.get_or_init(|| {
            let group = |s: &Slot| {
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("material"),
                    layout,
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&s.view) },
                        wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::Sampler(&s.sampler) },
                        wgpu::BindGroupEntry { binding: 2, resource: s.uniform.as_entire_binding() },
                    ],
                })
            };
            self.slots.iter().map(group).collect()
        })
    }

    /// The bind groups when made (see [`GpuMaterials::bind_groups`]).
    pub(super) fn made_groups(&self) -> Option<&[wgpu::BindGroup]> {
        self.groups.get().map(Vec::as_slice)
    }
}

/// The layout of a material's bind group: its texture, sampler and uniform,
/// seen by the fragment stage.
pub(crate) fn material_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let fragment = wgpu::ShaderStages::FRAGMENT;
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("material"),
        entries: &[
            wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: fragment,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: fragment,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: fragment,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
        ],
    })
}
