//! A per-kernel GPU profile from timestamp queries: while profiling, every dispatch runs in a
//! compute pass of its own with a timestamp written at its start and end, and the recorder
//! collects the times at each submission. The totals per kernel (dispatches, seconds, bytes
//! moved) give each kernel's achieved bandwidth.

use std::collections::BTreeMap;

use super::context::GpuContext;
use super::recorder::map_read;
use crate::backend::BackendError;

/// Dispatches timed between two collections (two timestamps each; wgpu allows 4096 queries
/// per set).
const CAPACITY: u32 = 1024;

/// What one kernel did over the profile.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct KernelTime {
    /// Dispatches of the kernel.
    pub dispatches: u64,
    /// GPU time between each dispatch's start and end timestamps, summed (s).
    pub seconds: f64,
    /// Bytes the kernel read and wrote in device memory, summed (as counted by
    /// `traffic`).
    pub bytes: u64,
}

impl KernelTime {
    /// Achieved bandwidth (bytes/s); 0 when no time was measured.
    pub fn bandwidth(&self) -> f64 {
        if self.seconds > 0.0 {
            self.bytes as f64 / self.seconds
        } else {
            0.0
        }
    }
}

/// Timestamps around every dispatch, gathered per kernel.
pub struct Profiler {
    queries: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    staging: wgpu::Buffer,
    /// Kernel and bytes of each dispatch recorded since the last collection.
    recorded: Vec<(&'static str, u64)>,
    /// Nanoseconds per timestamp tick.
    period_ns: f64,
    totals: BTreeMap<&'static str, KernelTime>,
}

impl Profiler {
    /// A profiler on `ctx`'s device; fails where the adapter cannot write timestamps.
    pub fn new(ctx: &GpuContext) -> Result<Profiler, BackendError> {
        if !ctx.has_timestamps() {
            return Err(BackendError::Unavailable(format!(
                "the GPU adapter {} cannot write timestamps (no TIMESTAMP_QUERY feature), so \
                 kernels cannot be profiled on it",
                ctx.adapter_summary()
            )));
        }
        let device = ctx.device();
        let bytes = 16 * CAPACITY as u64;
        Ok(Profiler {
            queries: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("kernel timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2 * CAPACITY,
            }),
            resolve: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: bytes,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            staging: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps readback"),
                size: bytes,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            recorded: Vec::new(),
            period_ns: ctx.queue().get_timestamp_period() as f64,
            totals: BTreeMap::new(),
        })
    }

    /// Whether the query set is full (the recorder must submit and collect first).
    pub fn is_full(&self) -> bool {
        self.recorded.len() as u32 >= CAPACITY
    }

    /// The timestamp writes for the next dispatch, of `kernel`, moving `bytes`.
    pub fn next(
        &mut self,
        kernel: &'static str,
        bytes: u64,
    ) -> wgpu::ComputePassTimestampWrites<'_> {
        let i = self.recorded.len() as u32;
        self.recorded.push((kernel, bytes));
        wgpu::ComputePassTimestampWrites {
            query_set: &self.queries,
            beginning_of_pass_write_index: Some(2 * i),
            end_of_pass_write_index: Some(2 * i + 1),
        }
    }

    /// Record the resolution of this submission's timestamps at the end of `encoder`.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        let n = 2 * self.recorded.len() as u32;
        if n == 0 {
            return;
        }
        encoder.resolve_query_set(&self.queries, 0..n, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.staging, 0, 8 * n as u64);
    }

    /// After the submission that [`Profiler::resolve`] ended: wait, read the timestamps and
    /// add them to the totals.
    pub fn collect(&mut self, ctx: &GpuContext) -> Result<(), BackendError> {
        if self.recorded.is_empty() {
            return Ok(());
        }
        let ticks: Vec<u64> = map_read(ctx, &self.staging)?;
        for (i, (kernel, bytes)) in self.recorded.drain(..).enumerate() {
            let (start, end) = (ticks[2 * i], ticks[2 * i + 1]);
            let t = self.totals.entry(kernel).or_default();
            t.dispatches += 1;
            t.seconds += end.saturating_sub(start) as f64 * self.period_ns * 1e-9;
            t.bytes += bytes;
        }
        Ok(())
    }

    /// The totals per kernel so far, by kernel name.
    pub fn totals(&self) -> &BTreeMap<&'static str, KernelTime> {
        &self.totals
    }

    /// Forget the totals (to profile a new measurement).
    pub fn reset(&mut self) {
        self.totals.clear();
    }
}
