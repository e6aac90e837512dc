//! Recording GPU work: compute kernels with explicit layouts, bind groups built once per
//! (kernel, buffers) and reused, one command encoder with one compute pass kept open across
//! dispatches (submitted only when the host must wait for a result), cached uniform buffers,
//! readbacks, the work counters (dispatches, bytes moved), and an optional per-kernel profile.

use std::collections::HashMap;

use super::context::GpuContext;
use super::profile::Profiler;
use crate::backend::{BackendError, Counters};

/// Threads per workgroup of every kernel (`WG` in shaders/shared/common.wgsl).
pub const WORKGROUP: u32 = 256;

/// Cached uniform buffers beyond which the cache is emptied (parameters with a varying
/// approach d would otherwise grow it without bound).
const UNIFORM_CACHE_MAX: usize = 512;
/// Cached bind groups beyond which the cache is emptied (they keep their buffers alive).
const BIND_CACHE_MAX: usize = 4096;

/// What one binding of a kernel holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Binding {
    /// A uniform buffer (the kernel's parameters).
    Uniform,
    /// A storage buffer the kernel only reads.
    Read,
    /// A storage buffer the kernel writes (and may read).
    ReadWrite,
}

/// A compiled compute pipeline with its explicit bind group layout (clones share them).
#[derive(Clone)]
pub struct Kernel {
    /// The entry point's name (the profiler's key).
    pub label: &'static str,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl Kernel {
    /// Compile `entry` of `module` with the bindings of group 0 it uses (see
    /// [`super::shaders::KernelLayout`]). Workgroup memory is not zeroed first: every kernel
    /// writes what it reads.
    pub fn new(
        ctx: &GpuContext,
        module: &wgpu::ShaderModule,
        entry: &'static str,
        bindings: &[(u32, Binding)],
    ) -> Kernel {
        let device = ctx.device();
        let entries: Vec<wgpu::BindGroupLayoutEntry> = bindings
            .iter()
            .map(|&(binding, kind)| wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: match kind {
                        Binding::Uniform => wgpu::BufferBindingType::Uniform,
                        Binding::Read => wgpu::BufferBindingType::Storage { read_only: true },
                        Binding::ReadWrite => wgpu::BufferBindingType::Storage { read_only: false },
                    },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            })
            .collect();
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(entry),
            entries: &entries,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(entry),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(entry),
            layout: Some(&pipeline_layout),
            module,
            entry_point: Some(entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &[],
                zero_initialize_workgroup_memory: false,
            },
            cache: None,
        });
        Kernel {
            label: entry,
            pipeline,
            layout,
        }
    }
}

/// Compile a WGSL source.
pub fn module(ctx: &GpuContext, label: &str, source: &str) -> wgpu::ShaderModule {
    ctx.device()
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        })
}

/// A zeroed storage buffer of `bytes` bytes (at least 4) that can be copied from and to.
pub fn storage(ctx: &GpuContext, label: &str, bytes: u64) -> wgpu::Buffer {
    ctx.device().create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes.max(4),
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// `total` workgroups as an (x, y) grid within the per-dimension limit.
pub fn groups_grid(ctx: &GpuContext, total: u32) -> (u32, u32) {
    let max_dim = ctx.limits().max_compute_workgroups_per_dimension;
    let x = total.clamp(1, max_dim);
    (x, total.max(1).div_ceil(x))
}

/// Workgroups to cover `n` elements with one thread each, as an (x, y) grid.
pub fn grid_for(ctx: &GpuContext, n: usize) -> (u32, u32) {
    groups_grid(ctx, (n as u64).div_ceil(WORKGROUP as u64).max(1) as u32)
}

/// The workgroups of one dispatch: a grid given now, or one a buffer holds when it runs.
enum Workgroups<'a> {
    /// (x, y) workgroups.
    Direct((u32, u32)),
    /// x, y, z workgroups read from the buffer's start on the device.
    Indirect(&'a wgpu::Buffer),
}

impl Workgroups<'_> {
    fn dispatch(&self, pass: &mut wgpu::ComputePass<'_>) {
        match self {
            Workgroups::Direct((x, y)) => pass.dispatch_workgroups(*x, *y, 1),
            Workgroups::Indirect(args) => pass.dispatch_workgroups_indirect(args, 0),
        }
    }
}

/// A bind group's identity: the kernel (by its layout) and the buffer at each binding.
type BindKey = (wgpu::BindGroupLayout, Vec<(u32, wgpu::Buffer)>);

/// The open command encoder and compute pass, the caches and the work counters of one backend.
#[derive(Default)]
pub struct Recorder {
    encoder: Option<wgpu::CommandEncoder>,
    pass: Option<wgpu::ComputePass<'static>>,
    uniforms: HashMap<Vec<u8>, wgpu::Buffer>,
    binds: HashMap<BindKey, wgpu::BindGroup>,
    /// Mappable readback buffers by size, reused (a CG residual check reads one every time).
    staging: HashMap<u64, wgpu::Buffer>,
    /// Per-kernel timestamps, when profiling.
    profiler: Option<Profiler>,
    /// Work done so far.
    pub counters: Counters,
}

impl Recorder {
    /// The open encoder (a new one if none is open), with no compute pass open on it: for
    /// copies and clears between dispatches.
    pub fn encoder(&mut self, ctx: &GpuContext) -> &mut wgpu::CommandEncoder {
        self.pass = None;
        self.encoder
            .get_or_insert_with(|| ctx.device().create_command_encoder(&Default::default()))
    }

    /// Start (or stop, with `None`) timing every dispatch. Pending work is submitted first.
    pub fn set_profiler(
        &mut self,
        ctx: &GpuContext,
        profiler: Option<Profiler>,
    ) -> Result<(), BackendError> {
        self.flush(ctx)?;
        self.profiler = profiler;
        Ok(())
    }

    /// The profile so far, if profiling.
    pub fn profiler(&self) -> Option<&Profiler> {
        self.profiler.as_ref()
    }

    /// A uniform buffer holding `params` (cached by content). Fails, rather than panics,
    /// when the device is gone.
    pub fn uniform<T: bytemuck::Pod>(
        &mut self,
        ctx: &GpuContext,
        params: &T,
    ) -> Result<wgpu::Buffer, BackendError> {
        self.params_buffer(ctx, params, wgpu::BufferUsages::UNIFORM)
    }

    /// A read-only storage buffer holding `params` (cached by content), for kernels that take
    /// their parameters from storage rather than uniform memory.
    pub fn storage_params<T: bytemuck::Pod>(
        &mut self,
        ctx: &GpuContext,
        params: &T,
    ) -> Result<wgpu::Buffer, BackendError> {
        self.params_buffer(ctx, params, wgpu::BufferUsages::STORAGE)
    }

    fn params_buffer<T: bytemuck::Pod>(
        &mut self,
        ctx: &GpuContext,
        params: &T,
        usage: wgpu::BufferUsages,
    ) -> Result<wgpu::Buffer, BackendError> {
        let mut key = bytemuck::bytes_of(params).to_vec();
        key.push((usage == wgpu::BufferUsages::STORAGE) as u8);
        let bytes = bytemuck::bytes_of(params);
        if let Some(b) = self.uniforms.get(&key) {
            return Ok(b.clone());
        }
        ctx.check()?;
        if self.uniforms.len() >= UNIFORM_CACHE_MAX {
            self.uniforms.clear();
            self.binds.clear();
        }
        let buffer = ctx.device().create_buffer(&wgpu::BufferDescriptor {
            label: Some("params"),
            size: (bytes.len() as u64).next_multiple_of(16),
            usage,
            mapped_at_creation: true,
        });
        buffer
            .get_mapped_range_mut(..)
            .map_err(|e| {
                // Prefer what the driver said about the device over the buffer's symptom.
                ctx.check().err().unwrap_or(BackendError::DeviceLost {
                    backend: "gpu",
                    reason: e.to_string(),
                })
            })?
            .slice(..bytes.len())
            .copy_from_slice(bytes);
        buffer.unmap();
        self.uniforms.insert(key, buffer.clone());
        Ok(buffer)
    }

    /// The bind group of `kernel` over `entries` (binding, buffer), built once and reused.
    fn bind_group(
        &mut self,
        ctx: &GpuContext,
        kernel: &Kernel,
        entries: &[(u32, &wgpu::Buffer)],
    ) -> wgpu::BindGroup {
        let key: BindKey = (
            kernel.layout.clone(),
            entries
                .iter()
                .map(|(b, buf)| (*b, (*buf).clone()))
                .collect(),
        );
        if let Some(g) = self.binds.get(&key) {
            return g.clone();
        }
        if self.binds.len() >= BIND_CACHE_MAX {
            self.binds.clear();
        }
        let group_entries: Vec<wgpu::BindGroupEntry> = entries
            .iter()
            .map(|(binding, buffer)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: buffer.as_entire_binding(),
            })
            .collect();
        let group = ctx.device().create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(kernel.label),
            layout: &kernel.layout,
            entries: &group_entries,
        });
        self.binds.insert(key, group.clone());
        group
    }

    /// Record one dispatch of `kernel` with `entries` (binding, buffer) over `grid`
    /// workgroups; `bytes` is what the kernel reads and writes in device memory (counted).
    pub fn dispatch(
        &mut self,
        ctx: &GpuContext,
        kernel: &Kernel,
        entries: &[(u32, &wgpu::Buffer)],
        grid: (u32, u32),
        bytes: u64,
    ) -> Result<(), BackendError> {
        self.record(ctx, kernel, entries, Workgroups::Direct(grid), bytes)
    }

    /// Record one dispatch of `kernel` over the workgroups that `args` (x, y, z: three u32 at
    /// its start, written on the device; a buffer with the INDIRECT usage) holds when it runs.
    pub fn dispatch_indirect(
        &mut self,
        ctx: &GpuContext,
        kernel: &Kernel,
        entries: &[(u32, &wgpu::Buffer)],
        args: &wgpu::Buffer,
        bytes: u64,
    ) -> Result<(), BackendError> {
        self.record(ctx, kernel, entries, Workgroups::Indirect(args), bytes)
    }

    fn record(
        &mut self,
        ctx: &GpuContext,
        kernel: &Kernel,
        entries: &[(u32, &wgpu::Buffer)],
        groups: Workgroups,
        bytes: u64,
    ) -> Result<(), BackendError> {
        let bind = self.bind_group(ctx, kernel, entries);
        self.counters.dispatches += 1;
        self.counters.bytes += bytes;
        if self.profiler.as_ref().is_some_and(|p| p.is_full()) {
            self.flush(ctx)?;
        }
        if let Some(profiler) = self.profiler.as_mut() {
            // One pass per dispatch, with timestamps at its start and end.
            let writes = profiler.next(kernel.label, bytes);
            let encoder = self
                .encoder
                .get_or_insert_with(|| ctx.device().create_command_encoder(&Default::default()));
            self.pass = None;
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(kernel.label),
                timestamp_writes: Some(writes),
            });
            pass.set_pipeline(&kernel.pipeline);
            pass.set_bind_group(0, &bind, &[]);
            groups.dispatch(&mut pass);
            return Ok(());
        }
        if self.pass.is_none() {
            let encoder = self
                .encoder
                .get_or_insert_with(|| ctx.device().create_command_encoder(&Default::default()));
            self.pass = Some(
                encoder
                    .begin_compute_pass(&Default::default())
                    .forget_lifetime(),
            );
        }
        let pass = self.pass.as_mut().expect("a pass was opened above");
        pass.set_pipeline(&kernel.pipeline);
        pass.set_bind_group(0, &bind, &[]);
        groups.dispatch(pass);
        Ok(())
    }

    /// Submit what has been recorded (nothing if nothing was); when profiling, wait for it and
    /// collect its timestamps.
    pub fn flush(&mut self, ctx: &GpuContext) -> Result<(), BackendError> {
        self.pass = None;
        if let Some(mut encoder) = self.encoder.take() {
            if let Some(p) = self.profiler.as_mut() {
                p.resolve(&mut encoder);
            }
            let t0 = std::time::Instant::now();
            ctx.queue().submit([encoder.finish()]);
            self.counters.submit_ns += t0.elapsed().as_nanos() as u64;
            self.counters.submits += 1;
            if let Some(p) = self.profiler.as_mut() {
                p.collect(ctx)?;
            }
        }
        ctx.check()
    }

    /// Submit, wait, and read `bytes` bytes of `buffer` from `offset` (multiples of 4).
    pub fn read<T: bytemuck::Pod>(
        &mut self,
        ctx: &GpuContext,
        buffer: &wgpu::Buffer,
        offset: u64,
        bytes: u64,
    ) -> Result<Vec<T>, BackendError> {
        let staging = self
            .staging
            .entry(bytes)
            .or_insert_with(|| {
                ctx.device().create_buffer(&wgpu::BufferDescriptor {
                    label: Some("readback"),
                    size: bytes,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            })
            .clone();
        self.encoder(ctx)
            .copy_buffer_to_buffer(buffer, offset, &staging, 0, bytes);
        self.flush(ctx)?;
        self.counters.readbacks += 1;
        self.counters.readback_bytes += bytes;
        let t0 = std::time::Instant::now();
        let out = map_read(ctx, &staging);
        self.counters.wait_ns += t0.elapsed().as_nanos() as u64;
        out
    }
}

/// Map `staging` (MAP_READ, its copy already submitted), wait, and read it whole.
pub fn map_read<T: bytemuck::Pod>(
    ctx: &GpuContext,
    staging: &wgpu::Buffer,
) -> Result<Vec<T>, BackendError> {
    let (tx, rx) = std::sync::mpsc::channel();
    staging.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = tx.send(r);
    });
    ctx.wait()?;
    let lost = |reason: String| BackendError::DeviceLost {
        backend: "gpu",
        reason,
    };
    rx.recv()
        .map_err(|e| lost(e.to_string()))?
        .map_err(|e| lost(e.to_string()))?;
    let out = {
        let view = staging
            .get_mapped_range(..)
            .map_err(|e| lost(e.to_string()))?;
        bytemuck::pod_collect_to_vec(&view)
    };
    staging.unmap();
    Ok(out)
}
