//! Recording GPU work: compute kernels, one command encoder kept open across operations
//! (submitted only when the host must wait for a result), cached uniform buffers, readbacks.

use std::collections::HashMap;

use super::context::GpuContext;
use crate::backend::{BackendError, Counters};

/// Threads per workgroup of the element-wise and reduction kernels (`WG` in the shaders).
pub const WORKGROUP: u32 = 256;

/// Cached uniform buffers beyond which the cache is emptied (parameters with a varying
/// approach d would otherwise grow it without bound).
const UNIFORM_CACHE_MAX: usize = 512;

/// A compiled compute pipeline and its bind group layout (derived from the shader).
pub struct Kernel {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

impl Kernel {
    /// Compile `entry` of `module`.
    pub fn new(ctx: &GpuContext, module: &wgpu::ShaderModule, entry: &str) -> Kernel {
        let pipeline = ctx
            .device()
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: None,
                module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            });
        let layout = pipeline.get_bind_group_layout(0);
        Kernel { pipeline, layout }
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

/// Workgroups to cover `n` elements, as an (x, y) grid within the per-dimension limit.
pub fn grid_for(ctx: &GpuContext, n: usize) -> (u32, u32) {
    let total = (n as u64).div_ceil(WORKGROUP as u64).max(1) as u32;
    let max_dim = ctx.limits().max_compute_workgroups_per_dimension;
    let x = total.clamp(1, max_dim);
    (x, total.div_ceil(x))
}

/// The open command encoder, the uniform cache and the work counters of one backend.
#[derive(Default)]
pub struct Recorder {
    encoder: Option<wgpu::CommandEncoder>,
    uniforms: HashMap<Vec<u8>, wgpu::Buffer>,
    /// Mappable readback buffers by size, reused (a CG residual check reads one every time).
    staging: HashMap<u64, wgpu::Buffer>,
    /// Work done so far.
    pub counters: Counters,
}

impl Recorder {
    /// The open encoder (a new one if none is open).
    pub fn encoder(&mut self, ctx: &GpuContext) -> &mut wgpu::CommandEncoder {
        self.encoder
            .get_or_insert_with(|| ctx.device().create_command_encoder(&Default::default()))
    }

    /// A uniform buffer holding `params` (cached by content). Fails, rather than panics,
    /// when the device is gone.
    pub fn uniform<T: bytemuck::Pod>(
        &mut self,
        ctx: &GpuContext,
        params: &T,
    ) -> Result<wgpu::Buffer, BackendError> {
        let bytes = bytemuck::bytes_of(params);
        if let Some(b) = self.uniforms.get(bytes) {
            return Ok(b.clone());
        }
        ctx.check()?;
        if self.uniforms.len() >= UNIFORM_CACHE_MAX {
            self.uniforms.clear();
        }
        let buffer = ctx.device().create_buffer(&wgpu::BufferDescriptor {
            label: Some("params"),
            size: (bytes.len() as u64).next_multiple_of(16),
            usage: wgpu::BufferUsages::UNIFORM,
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
        self.uniforms.insert(bytes.to_vec(), buffer.clone());
        Ok(buffer)
    }

    /// Record one dispatch of `kernel` with `entries` (binding, buffer) over `grid` workgroups.
    pub fn dispatch(
        &mut self,
        ctx: &GpuContext,
        kernel: &Kernel,
        entries: &[(u32, &wgpu::Buffer)],
        grid: (u32, u32),
    ) {
        let entries: Vec<wgpu::BindGroupEntry> = entries
            .iter()
            .map(|(binding, buffer)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: buffer.as_entire_binding(),
            })
            .collect();
        let bind = ctx.device().create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &kernel.layout,
            entries: &entries,
        });
        let encoder = self.encoder(ctx);
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&kernel.pipeline);
        pass.set_bind_group(0, &bind, &[]);
        pass.dispatch_workgroups(grid.0, grid.1, 1);
        drop(pass);
        self.counters.dispatches += 1;
    }

    /// Submit what has been recorded (nothing if nothing was).
    pub fn flush(&mut self, ctx: &GpuContext) -> Result<(), BackendError> {
        if let Some(encoder) = self.encoder.take() {
            ctx.queue().submit([encoder.finish()]);
            self.counters.submits += 1;
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
}
