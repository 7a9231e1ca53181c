//! Animation evaluated on the GPU (compute passes of shaders/anim.wgsl).
//!
//! A [`GpuAnimator`] holds a recorded [`StencilPlan`] on the device: per
//! level its CSR rows (offsets, indices, weights) and an output buffer, and
//! the finest level's one-rings for the normals. Per frame only the control
//! positions go up ([`GpuAnimator::update`]); one dispatch per level and one
//! for the normals then write the finest positions and normals straight into
//! the [`GpuMesh`]'s vertex buffers, which the renderer draws as they are.
//! The rows are the ones the CPU evaluates, so both agree to rounding (the
//! GPU may fuse multiply-adds).
//!
//! An [`AnimatedMesh`] pairs the drawn mesh with its animator: the one way
//! the viewer, the animation export (`animate --eval gpu`) and
//! `animate --stats --eval gpu` evaluate frames on the GPU.

use super::gpu::Gpu;
use super::gpu_mesh::{GpuMesh, cull_for};
use crate::mesh::normals::ring_lists;
use crate::subdiv::tables::StencilPlan;
use crate::{CornerTable, Error, Result};
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use wgpu::util::DeviceExt;

/// Threads per workgroup (`@workgroup_size` in the shader).
const WORKGROUP: u32 = 64;

/// The shader's `Params`.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Params {
    copied: u32,
    rows: u32,
    _pad: [u32; 2],
}

/// One dispatch: its bind group and thread count.
struct Pass {
    group: wgpu::BindGroup,
    threads: u32,
}

/// A stencil plan and its normal rings on the device (see the module docs).
pub struct GpuAnimator {
    control: wgpu::Buffer,
    n_control: usize,
    /// A plan of no level: the control positions are the finest, copied
    /// into the drawn buffer as they are (no pass writes it).
    copy_to: Option<wgpu::Buffer>,
    level: wgpu::ComputePipeline,
    normals: wgpu::ComputePipeline,
    /// One per level, then the normals.
    passes: Vec<Pass>,
    /// Keeps the intermediate levels' buffers alive.
    _buffers: Vec<wgpu::Buffer>,
}

/// Whether `device` can run the animation passes (compute with six storage
/// buffers per stage; lavapipe can).
pub(crate) fn supports_compute(device: &wgpu::Device) -> bool {
    device.limits().max_storage_buffers_per_shader_stage >= 6
        && device.limits().max_compute_workgroups_per_dimension > 0
}

/// A storage buffer (also a copy source and target) holding `bytes`.
fn storage(device: &wgpu::Device, label: &str, bytes: &[u8]) -> wgpu::Buffer {
    // a binding may not be empty: pad to one word
    let contents: &[u8] = if bytes.is_empty() { &[0; 4] } else { bytes };
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
    })
}

fn layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let entry = |binding: u32, ty: wgpu::BufferBindingType| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
        count: None,
    };
    let ro = wgpu::BufferBindingType::Storage { read_only: true };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("anim"),
        entries: &[
            entry(0, wgpu::BufferBindingType::Uniform),
            entry(1, ro),
            entry(2, ro),
            entry(3, ro),
            entry(4, ro),
            entry(5, wgpu::BufferBindingType::Storage { read_only: false }),
        ],
    })
}

fn pipeline(device: &wgpu::Device, layout: &wgpu::PipelineLayout, entry: &str) -> wgpu::ComputePipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("anim.wgsl"),
        source: wgpu::ShaderSource::Wgsl(include_str!("../../shaders/anim.wgsl").into()),
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(entry),
        layout: Some(layout),
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// The bind group of one dispatch: `params`, then the five buffers.
fn group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    params: Params,
    bufs: [&wgpu::Buffer; 5],
) -> wgpu::BindGroup {
    let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("anim params"),
        contents: bytemuck::bytes_of(&params),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let mut entries = vec![wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() }];
    for (i, b) in bufs.into_iter().enumerate() {
        entries.push(wgpu::BindGroupEntry { binding: i as u32 + 1, resource: b.as_entire_binding() });
    }
    device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some("anim"), layout, entries: &entries })
}

impl GpuAnimator {
    /// Uploads `plan` and the rings of its finest level; the passes write into
    /// `mesh` (built on the plan's finest topology).
    ///
    /// # Errors
    /// [`Error::Gpu`] when the mesh does not match the plan, a buffer exceeds
    /// the device's limits, or a vertex has too many neighbours for a ring.
    pub fn new(device: &wgpu::Device, plan: &StencilPlan, mesh: &GpuMesh) -> Result<GpuAnimator> {
        if mesh.vertex_count() != plan.ct.num_vertices() {
            return Err(Error::Gpu(format!(
                "the GPU mesh has {} vertices, the plan {}",
                mesh.vertex_count(),
                plan.ct.num_vertices()
            )));
        }
        let max = device.limits().max_storage_buffer_binding_size as usize;
        let too_big = |bytes: usize| bytes > max;
        let bgl = layout(device);
        let pl = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("anim"),
            bind_group_layouts: &[Some(&bgl)],
            immediate_size: 0,
        });
        let n_control = plan.n_control();
        let control = storage(device, "anim control", &vec![0u8; n_control * 12]);
        let (mut passes, mut buffers) = (Vec::new(), Vec::new());
        let mut src = control.clone();
        let last = plan.levels.len().saturating_sub(1);
        for (i, lv) in plan.levels.iter().enumerate() {
            if too_big(lv.indices.len() * 4) || too_big(lv.n_out() * 12) {
                return Err(Error::Gpu(format!("level {} does not fit in one GPU buffer ({max} bytes)", i + 1)));
            }
            let offsets = storage(device, "anim offsets", bytemuck::cast_slice(&lv.offsets));
            let indices = storage(device, "anim indices", bytemuck::cast_slice(&lv.indices));
            let weights = storage(device, "anim weights", bytemuck::cast_slice(&lv.weights));
            let dst = if i == last { None } else { Some(storage(device, "anim level", &vec![0u8; lv.n_out() * 12])) };
            let copied = if lv.copy_vertices { lv.n_in as u32 } else { 0 };
            let params = Params { copied, rows: (lv.offsets.len() - 1) as u32, _pad: [0; 2] };
            let out = dst.as_ref().unwrap_or(&mesh.positions);
            let group = group(device, &bgl, params, [&src, &offsets, &indices, &weights, out]);
            passes.push(Pass { group, threads: lv.n_out() as u32 });
            buffers.extend([offsets, indices, weights]);
            if let Some(d) = dst {
                src = d.clone();
                buffers.push(d);
            }
        }
        let rings = match plan.polygons() {
            Some(pt) => ring_lists(pt),
            None => ring_lists(&plan.ct),
        };
        let (offsets, ids) =
            rings.ok_or_else(|| Error::Gpu("a vertex has too many neighbours for the GPU normals".into()))?;
        let offsets = storage(device, "ring offsets", bytemuck::cast_slice(&offsets));
        let ids = storage(device, "rings", bytemuck::cast_slice(&ids));
        let nv = plan.ct.num_vertices() as u32;
        let params = Params { copied: 0, rows: nv, _pad: [0; 2] };
        // binding 4 (weights) is unused by `normals`; any buffer fills it
        let normals_group = group(device, &bgl, params, [&mesh.positions, &offsets, &ids, &ids, &mesh.normals]);
        passes.push(Pass { group: normals_group, threads: nv });
        buffers.extend([offsets, ids]);
        Ok(GpuAnimator {
            copy_to: plan.levels.is_empty().then(|| mesh.positions.clone()),
            control,
            n_control,
            level: pipeline(device, &pl, "level"),
            normals: pipeline(device, &pl, "normals"),
            passes,
            _buffers: buffers,
        })
    }

    /// Uploads the frame's control positions and records the passes; the
    /// caller submits `encoder` (before drawing the mesh).
    ///
    /// # Errors
    /// [`Error::Usage`] when `control` does not have the plan's vertex count.
    pub(crate) fn encode(
        &self,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        control: &[Vec3],
    ) -> Result<()> {
        if control.len() != self.n_control {
            return Err(Error::Usage(format!(
                "{} control positions for a plan of {} vertices",
                control.len(),
                self.n_control
            )));
        }
        queue.write_buffer(&self.control, 0, bytemuck::cast_slice(control));
        if let Some(positions) = &self.copy_to {
            encoder.copy_buffer_to_buffer(&self.control, 0, positions, 0, (control.len() * 12) as u64);
        }
        let mut pass =
            encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("anim"), timestamp_writes: None });
        let n = self.passes.len();
        for (i, p) in self.passes.iter().enumerate() {
            pass.set_pipeline(if i + 1 == n { &self.normals } else { &self.level });
            pass.set_bind_group(0, &p.group, &[]);
            let groups = p.threads.div_ceil(WORKGROUP).max(1);
            let x = groups.min(65535);
            pass.dispatch_workgroups(x, groups.div_ceil(x), 1);
        }
        Ok(())
    }

    /// `GpuAnimator::encode` in its own submission.
    ///
    /// # Errors
    /// As `GpuAnimator::encode`.
    pub fn update(&self, device: &wgpu::Device, queue: &wgpu::Queue, control: &[Vec3]) -> Result<()> {
        let mut encoder = device.create_command_encoder(&Default::default());
        self.encode(queue, &mut encoder, control)?;
        queue.submit([encoder.finish()]);
        Ok(())
    }
}

/// Reads a buffer of packed `Vec3`s back (tests, the export's motion bounds).
///
/// # Errors
/// [`Error::Gpu`] when mapping fails.
pub(crate) fn read_vec3(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    buffer: &wgpu::Buffer,
    n: usize,
) -> Result<Vec<Vec3>> {
    let bytes = (n * 12) as u64;
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("vec3 readback"),
        size: bytes.max(4),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    encoder.copy_buffer_to_buffer(buffer, 0, &staging, 0, bytes);
    queue.submit([encoder.finish()]);
    let slice = staging.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| Error::Gpu(format!("waiting for the GPU: {e}")))?;
    rx.recv().map_err(|e| Error::Gpu(format!("readback: {e}")))?.map_err(|e| Error::Gpu(format!("readback: {e}")))?;
    let out = {
        let data = slice.get_mapped_range().map_err(|e| Error::Gpu(format!("readback: {e}")))?;
        bytemuck::cast_slice::<u8, Vec3>(&data[..bytes as usize]).to_vec()
    };
    staging.unmap();
    Ok(out)
}

impl GpuMesh {
    /// The positions and normals in the mesh's buffers, read back (waits for
    /// the GPU): what a [`GpuAnimator`] wrote, for checking or export.
    ///
    /// # Errors
    /// [`Error::Gpu`] when the copy or the mapping fails.
    pub fn read_back(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<(Vec<Vec3>, Vec<Vec3>)> {
        let n = self.vertex_count();
        Ok((read_vec3(device, queue, &self.positions, n)?, read_vec3(device, queue, &self.normals, n)?))
    }
}

/// Whether `gpu`'s device has the compute passes, as an error naming the
/// adapter when it has not.
///
/// # Errors
/// [`Error::Gpu`] without compute shaders with six storage buffers.
pub(crate) fn require_compute(gpu: &Gpu) -> Result<()> {
    if supports_compute(&gpu.device) {
        Ok(())
    } else {
        Err(Error::Gpu(format!("{} has no compute shaders with six storage buffers", gpu.describe())))
    }
}

/// An animation's finest mesh on the device and the way its frames get
/// there: uploaded from the CPU's evaluation ([`AnimatedMesh::upload`]), or
/// evaluated in place by the compute passes ([`AnimatedMesh::evaluate`]) once
/// they are built ([`AnimatedMesh::start_gpu`], [`AnimatedMesh::on_gpu`]).
/// The viewer, the animation export and `animate --stats --eval gpu` all
/// evaluate frames on the GPU through this one type.
pub(crate) struct AnimatedMesh {
    mesh: GpuMesh,
    /// The compute passes writing `mesh` (`None`: frames come from the CPU).
    animator: Option<GpuAnimator>,
}

impl AnimatedMesh {
    /// The mesh of a frame the CPU evaluated (`ct` the plan's finest topology).
    ///
    /// # Errors
    /// [`Error::Gpu`] when the mesh exceeds the device's buffer limit.
    pub(crate) fn new(
        device: &wgpu::Device,
        ct: &CornerTable,
        positions: &[Vec3],
        normals: &[Vec3],
    ) -> Result<AnimatedMesh> {
        Ok(AnimatedMesh { mesh: GpuMesh::new(device, ct, positions, normals)?, animator: None })
    }

    /// The finest mesh of `plan` with the frame whose control positions are
    /// `control` evaluated by the compute passes from the start: no frame is
    /// evaluated on the CPU (the side to cull is found from the positions
    /// the GPU wrote, read back).
    ///
    /// # Errors
    /// [`Error::Gpu`] without compute shaders, or as [`GpuAnimator::new`];
    /// [`Error::Usage`] as [`GpuAnimator::encode`].
    pub(crate) fn on_gpu(gpu: &Gpu, plan: &StencilPlan, control: &[Vec3]) -> Result<AnimatedMesh> {
        require_compute(gpu)?;
        let zeros = vec![Vec3::ZERO; plan.ct.num_vertices()];
        let mut animated = AnimatedMesh::new(&gpu.device, &plan.ct, &zeros, &zeros)?;
        animated.start_gpu(&gpu.device, plan)?;
        animated.evaluate(&gpu.device, &gpu.queue, control)?;
        let positions = animated.positions(&gpu.device, &gpu.queue)?;
        animated.mesh.cull = cull_for(&plan.ct, &positions);
        Ok(animated)
    }

    /// Builds the compute passes of `plan` (whose finest topology this mesh
    /// has), so that [`AnimatedMesh::evaluate`] can run.
    ///
    /// # Errors
    /// As [`GpuAnimator::new`]; the mesh is then left as it was.
    pub(crate) fn start_gpu(&mut self, device: &wgpu::Device, plan: &StencilPlan) -> Result<()> {
        self.animator = Some(GpuAnimator::new(device, plan, &self.mesh)?);
        Ok(())
    }

    /// Whether the compute passes are built.
    pub(crate) fn gpu_ready(&self) -> bool {
        self.animator.is_some()
    }

    /// Takes a frame the CPU evaluated (the compute passes, if built, stay).
    pub(crate) fn upload(&mut self, queue: &wgpu::Queue, positions: &[Vec3], normals: &[Vec3]) {
        self.mesh.update(queue, positions, normals);
    }

    /// Evaluates the frame whose control positions are `control` with the
    /// compute passes, straight into the drawn buffers (submitted; a later
    /// submission draws it).
    ///
    /// # Errors
    /// [`Error::Gpu`] before [`AnimatedMesh::start_gpu`]; as
    /// [`GpuAnimator::update`].
    pub(crate) fn evaluate(&self, device: &wgpu::Device, queue: &wgpu::Queue, control: &[Vec3]) -> Result<()> {
        let animator =
            self.animator.as_ref().ok_or_else(|| Error::Gpu("the GPU evaluation passes are not built".into()))?;
        animator.update(device, queue, control)
    }

    /// The positions in the drawn buffer, read back (waits for the GPU).
    ///
    /// # Errors
    /// As [`read_vec3`].
    pub(crate) fn positions(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Vec<Vec3>> {
        read_vec3(device, queue, &self.mesh.positions, self.mesh.vertex_count())
    }

    /// The mesh as drawn.
    pub(crate) fn mesh(&self) -> &GpuMesh {
        &self.mesh
    }

    /// The mesh as drawn, to add colours or normal segments to.
    pub(crate) fn mesh_mut(&mut self) -> &mut GpuMesh {
        &mut self.mesh
    }
}

/// Times `frames` evaluations of `anim` on a headless device through
/// `AnimatedMesh`: per frame the upload of the control positions, the
/// passes and the wait for them (ms). Returns the times, the time to upload
/// the plan and evaluate a first frame (ms), and the adapter.
///
/// # Errors
/// [`Error::Gpu`] without an adapter with compute, or when the plan does not
/// fit on the device.
pub fn time_frames(anim: &crate::anim::Animation, frames: usize) -> Result<(Vec<f64>, f64, String)> {
    let gpu = Gpu::headless()?;
    let t0 = crate::clock::Instant::now();
    let animated = AnimatedMesh::on_gpu(&gpu, anim.plan(), anim.control(0))?;
    let upload_ms = t0.elapsed().as_secs_f64() * 1e3;
    let wait = |d: &wgpu::Device| d.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| Error::Gpu(e.to_string()));
    let mut times = Vec::with_capacity(frames);
    for f in 0..frames {
        let t = crate::clock::Instant::now();
        animated.evaluate(&gpu.device, &gpu.queue, anim.control(f))?;
        wait(&gpu.device)?;
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    Ok((times, upload_ms, gpu.describe()))
}
