//! Batched complex-to-complex FFT on the GPU (`shaders/fft.wgsl`), with its CPU twin.
//!
//! Lines of n complex values (n a power of two, 2 ≤ n ≤ `n_max`) lie contiguously in a
//! storage buffer of `vec2<f32>`. Lines with n ≤ [`GpuFft::shared_max`] are transformed by one
//! workgroup each, entirely in workgroup memory; longer lines first run log2(n / shared_max)
//! radix-2 Stockham stages in global memory (one dispatch each) and then finish in workgroup
//! memory. Twiddles e^{-2πik/n_max} are computed on the host in f64 and uploaded as f32.

use rustfft::num_complex::Complex;
use wgpu::util::DeviceExt;

use super::context::GpuContext;
use crate::backend::BackendError;

/// Threads per workgroup; must equal `WG` in shaders/fft.wgsl.
const WORKGROUP: u32 = 256;
/// Longest line the shared-memory kernel will hold, whatever the adapter allows.
const SHARED_CAP: u32 = 2048;
/// Bytes of one complex f32 value (vec2<f32>).
const COMPLEX_BYTES: u64 = 8;

/// Uniform parameters of one dispatch. Must stay in sync with `struct Params` in
/// shaders/fft.wgsl.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FftParams {
    n: u32,
    batch: u32,
    stride: u32,
    n_max: u32,
    inverse: u32,
    pad: [u32; 3],
}

/// Which kernel a dispatch of a plan runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum PassKind {
    /// One radix-2 stage in global memory.
    Global,
    /// The workgroup-memory finish, in place.
    Shared,
    /// The workgroup-memory finish, from the scratch buffer into the data buffer.
    SharedOutOfPlace,
}

/// One dispatch of a plan.
struct FftPass {
    kind: PassKind,
    bind: wgpu::BindGroup,
    grid: (u32, u32),
}

/// The dispatches of one batched transform of a fixed buffer (see [`GpuFft::plan`]).
pub struct FftPlan {
    passes: Vec<FftPass>,
    /// Uniform buffers the bind groups refer to.
    _params: Vec<wgpu::Buffer>,
}

/// Compiled FFT pipelines and the twiddle table, built once per device.
pub struct GpuFft {
    global_stage: wgpu::ComputePipeline,
    shared: wgpu::ComputePipeline,
    shared_oop: wgpu::ComputePipeline,
    twiddles: wgpu::Buffer,
    n_max: u32,
    shared_max: u32,
}

impl std::fmt::Debug for GpuFft {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuFft")
            .field("n_max", &self.n_max)
            .field("shared_max", &self.shared_max)
            .finish_non_exhaustive()
    }
}

/// Largest power of two m ≤ `SHARED_CAP`, ≤ `n_max`, whose two ping-pong buffers
/// (2 · m · 8 bytes) fit in `workgroup_bytes` of workgroup memory.
fn shared_line_max(workgroup_bytes: u32, n_max: u32) -> u32 {
    let mut m = SHARED_CAP.min(n_max);
    while m > 2 && 2 * m as u64 * COMPLEX_BYTES > workgroup_bytes as u64 {
        m /= 2;
    }
    m
}

/// Splits `total` workgroups into an (x, y) grid with x within the per-dimension limit.
fn dispatch_grid(total: u32, max_dim: u32) -> (u32, u32) {
    let x = total.clamp(1, max_dim);
    (x, total.div_ceil(x))
}

/// The WGSL of shaders/fft.wgsl with SMEM substituted and `fft_shared_oop` appended: a copy of
/// `fft_shared` (the file's last function) that loads from `src` and stores to `dst`.
fn fft_source(shared_max: u32) -> String {
    let base =
        include_str!("../../../shaders/fft.wgsl").replace("__SMEM__", &shared_max.to_string());
    let start = base
        .rfind("@compute @workgroup_size(WG)\nfn fft_shared(")
        .expect("fft.wgsl ends with fft_shared");
    let oop = base[start..]
        .replace("fn fft_shared(", "fn fft_shared_oop(")
        .replace("= data[at]", "= src[at]")
        .replace("data[at] =", "dst[at] =");
    format!("{base}\n{oop}")
}

/// The twiddle table e^{-2πik/n_max}, k in [0, n_max/2), evaluated in f64, stored as f32.
fn twiddle_table(n_max: u32) -> Vec<[f32; 2]> {
    (0..n_max / 2)
        .map(|k| {
            let angle = -2.0 * std::f64::consts::PI * k as f64 / n_max as f64;
            [angle.cos() as f32, angle.sin() as f32]
        })
        .collect()
}

impl GpuFft {
    /// Compiles the pipelines for lines of up to `n_max` complex values (a power of two ≥ 2)
    /// and uploads the twiddle table.
    pub fn new(ctx: &GpuContext, n_max: usize) -> Result<GpuFft, BackendError> {
        Self::with_shared_max(ctx, n_max, SHARED_CAP as usize)
    }

    /// As [`GpuFft::new`], but lines longer than `shared_max` (a power of two ≥ 2; lowered to
    /// what the adapter's workgroup memory holds) start with global-memory stages. Lets tests
    /// exercise the global-memory path on short lines.
    pub fn with_shared_max(
        ctx: &GpuContext,
        n_max: usize,
        shared_max: usize,
    ) -> Result<GpuFft, BackendError> {
        if !shared_max.is_power_of_two() || shared_max < 2 {
            return Err(BackendError::Unavailable(format!(
                "GPU FFT shared-memory line length {shared_max} must be a power of two ≥ 2"
            )));
        }
        if !n_max.is_power_of_two() || n_max < 2 || n_max > u32::MAX as usize / 2 {
            return Err(BackendError::Unavailable(format!(
                "GPU FFT length limit {n_max} must be a power of two ≥ 2"
            )));
        }
        let n_max = n_max as u32;
        let limits = ctx.limits();
        if limits.max_compute_invocations_per_workgroup < WORKGROUP
            || limits.max_compute_workgroup_size_x < WORKGROUP
            || limits.max_compute_workgroup_storage_size < 32
        {
            return Err(BackendError::Unavailable(format!(
                "the GPU adapter allows {} threads and {} bytes of memory per workgroup; \
                 the FFT needs {WORKGROUP} threads: use `--backend cpu`",
                limits.max_compute_invocations_per_workgroup,
                limits.max_compute_workgroup_storage_size
            )));
        }
        let shared_max = shared_line_max(limits.max_compute_workgroup_storage_size, n_max)
            .min(shared_max.min(SHARED_CAP as usize) as u32);
        let source = fft_source(shared_max);
        let device = ctx.device();
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("fft.wgsl"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pipeline = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: None,
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        let twiddles = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("fft twiddles"),
            contents: bytemuck::cast_slice(&twiddle_table(n_max)),
            usage: wgpu::BufferUsages::STORAGE,
        });
        Ok(GpuFft {
            global_stage: pipeline("fft_global_stage"),
            shared: pipeline("fft_shared"),
            shared_oop: pipeline("fft_shared_oop"),
            twiddles,
            n_max,
            shared_max,
        })
    }

    /// Longest line (complex values) transformed entirely in workgroup memory.
    pub fn shared_max(&self) -> usize {
        self.shared_max as usize
    }

    /// Longest line (complex values) these pipelines accept.
    pub fn n_max(&self) -> usize {
        self.n_max as usize
    }

    fn params(
        &self,
        ctx: &GpuContext,
        n: u32,
        batch: u32,
        stride: u32,
        inverse: bool,
    ) -> wgpu::Buffer {
        let p = FftParams {
            n,
            batch,
            stride,
            n_max: self.n_max,
            inverse: inverse as u32,
            pad: [0; 3],
        };
        ctx.device()
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("fft params"),
                contents: bytemuck::bytes_of(&p),
                usage: wgpu::BufferUsages::UNIFORM,
            })
    }

    /// Records the dispatches that transform, in place, `batch` contiguous lines of `n`
    /// complex values held in `buffer` (`vec2<f32>`; usages STORAGE | COPY_SRC | COPY_DST).
    /// The inverse is unnormalised. Run the plan with [`GpuFft::encode`] as often as needed.
    pub fn plan(
        &self,
        ctx: &GpuContext,
        buffer: &wgpu::Buffer,
        n: usize,
        batch: usize,
        inverse: bool,
    ) -> Result<FftPlan, BackendError> {
        let too_large = |reason: String| BackendError::GridTooLarge {
            nx: n,
            ny: batch,
            backend: "gpu",
            reason,
        };
        if !n.is_power_of_two() || n < 2 || n > self.n_max as usize {
            return Err(too_large(format!(
                "FFT lines must have a power-of-two length in [2, {}]",
                self.n_max
            )));
        }
        let bytes = (n as u64)
            .checked_mul(batch as u64)
            .and_then(|c| c.checked_mul(COMPLEX_BYTES))
            .filter(|&b| b < u32::MAX as u64)
            .ok_or_else(|| too_large("more than 2³² bytes of FFT data".into()))?;
        let limits = ctx.limits();
        if bytes > limits.max_storage_buffer_binding_size || bytes > buffer.size() {
            return Err(too_large(format!(
                "{bytes} bytes of FFT data; the buffer holds {} and one binding sees at most {}",
                buffer.size(),
                limits.max_storage_buffer_binding_size
            )));
        }
        let mut plan = FftPlan {
            passes: Vec::new(),
            _params: Vec::new(),
        };
        if batch == 0 {
            return Ok(plan);
        }
        let (n32, batch32) = (n as u32, batch as u32);
        let device = ctx.device();
        let max_dim = limits.max_compute_workgroups_per_dimension;
        let shared_max = self.shared_max.min(n32);
        let global_stages = (n32 / shared_max).trailing_zeros();
        let mut scratch_in = None;
        if global_stages > 0 {
            let scratch = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("fft scratch"),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let layout = self.global_stage.get_bind_group_layout(0);
            for k in 0..global_stages {
                let (src, dst) = if k % 2 == 0 {
                    (buffer, &scratch)
                } else {
                    (&scratch, buffer)
                };
                let params = self.params(ctx, n32, batch32, 1 << k, inverse);
                let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("fft global stage"),
                    layout: &layout,
                    entries: &[
                        bind(0, &params),
                        bind(1, &self.twiddles),
                        bind(3, src),
                        bind(4, dst),
                    ],
                });
                let groups = (batch32 * (n32 / 2)).div_ceil(WORKGROUP);
                plan.passes.push(FftPass {
                    kind: PassKind::Global,
                    bind,
                    grid: dispatch_grid(groups, max_dim),
                });
                plan._params.push(params);
            }
            if global_stages % 2 == 1 {
                scratch_in = Some(scratch);
            }
        }
        let stride = 1u32 << global_stages;
        let params = self.params(ctx, n32, batch32, stride, inverse);
        let (kind, bind) = match &scratch_in {
            None => (
                PassKind::Shared,
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("fft shared"),
                    layout: &self.shared.get_bind_group_layout(0),
                    entries: &[bind(0, &params), bind(1, &self.twiddles), bind(2, buffer)],
                }),
            ),
            Some(scratch) => (
                PassKind::SharedOutOfPlace,
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("fft shared out of place"),
                    layout: &self.shared_oop.get_bind_group_layout(0),
                    entries: &[
                        bind(0, &params),
                        bind(1, &self.twiddles),
                        bind(3, scratch),
                        bind(4, buffer),
                    ],
                }),
            ),
        };
        // Sub-lines per workgroup: must equal `lpg` in fft_shared.
        let len = n32 / stride;
        let lines_per_group = ((2 * WORKGROUP).min(self.shared_max) / len).max(1);
        plan.passes.push(FftPass {
            kind,
            bind,
            grid: dispatch_grid((batch32 * stride).div_ceil(lines_per_group), max_dim),
        });
        plan._params.push(params);
        Ok(plan)
    }

    /// Appends a plan's dispatches to `encoder`; returns the number of dispatches.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder, plan: &FftPlan) -> u64 {
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            for p in &plan.passes {
                pass.set_pipeline(match p.kind {
                    PassKind::Global => &self.global_stage,
                    PassKind::Shared => &self.shared,
                    PassKind::SharedOutOfPlace => &self.shared_oop,
                });
                pass.set_bind_group(0, &p.bind, &[]);
                pass.dispatch_workgroups(p.grid.0, p.grid.1, 1);
            }
        }
        plan.passes.len() as u64
    }

    /// Transforms, in place, `batch` contiguous lines of `n` complex values held in `buffer`
    /// (`vec2<f32>`; usages STORAGE | COPY_SRC | COPY_DST). The inverse is unnormalised.
    /// The work is submitted, not waited for.
    pub fn run(
        &self,
        ctx: &GpuContext,
        buffer: &wgpu::Buffer,
        n: usize,
        batch: usize,
        inverse: bool,
    ) -> Result<(), BackendError> {
        let plan = self.plan(ctx, buffer, n, batch, inverse)?;
        let mut encoder = ctx.device().create_command_encoder(&Default::default());
        self.encode(&mut encoder, &plan);
        ctx.queue().submit([encoder.finish()]);
        Ok(())
    }

    /// Uploads `data` (whole lines of `n` values), transforms every line, waits and reads the
    /// result back. For tests and debugging; the solver keeps its fields on the device.
    ///
    /// Panics if `data` does not hold whole lines of `n` values.
    pub fn fft_lines(
        &self,
        ctx: &GpuContext,
        data: &[Complex<f32>],
        n: usize,
        inverse: bool,
    ) -> Result<Vec<Complex<f32>>, BackendError> {
        assert!(
            n > 0 && data.len().is_multiple_of(n),
            "data must hold whole lines of {n} values"
        );
        let host: Vec<[f32; 2]> = data.iter().map(|c| [c.re, c.im]).collect();
        let device = ctx.device();
        let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("fft lines"),
            contents: bytemuck::cast_slice(&host),
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
        });
        self.run(ctx, &buffer, n, data.len() / n, inverse)?;
        let out: Vec<[f32; 2]> = read_buffer(ctx, &buffer)?;
        Ok(out
            .into_iter()
            .map(|[re, im]| Complex::new(re, im))
            .collect())
    }
}

fn bind(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

/// Copies a whole buffer (usage COPY_SRC) back to the host, waiting for the GPU.
pub fn read_buffer<T: bytemuck::Pod>(
    ctx: &GpuContext,
    buffer: &wgpu::Buffer,
) -> Result<Vec<T>, BackendError> {
    super::recorder::Recorder::default().read(ctx, buffer, 0, buffer.size())
}

/// CPU twin of `shaders/fft.wgsl`, in f64: the same radix-2 Stockham stages in the same order
/// (`shared_max` plays the role of the shader's SMEM), for every line of `n` values in `data`.
/// The inverse is unnormalised. Panics unless n is a power of two ≥ 2 dividing `data.len()`.
pub fn stockham_twin(data: &mut [Complex<f64>], n: usize, inverse: bool, shared_max: usize) {
    assert!(n.is_power_of_two() && n >= 2 && data.len().is_multiple_of(n));
    let sign = if inverse { 1.0 } else { -1.0 };
    let twiddle = |p: usize, len: usize| {
        Complex::from_polar(
            1.0,
            sign * 2.0 * std::f64::consts::PI * p as f64 / len as f64,
        )
    };
    let half = n / 2;
    let shared_max = shared_max.min(n);
    for line in data.chunks_exact_mut(n) {
        // fft_global_stage: stages with stride s until the sub-lines fit in shared memory.
        let mut s = 1;
        while n / s > shared_max {
            let src = line.to_vec();
            for j in 0..half {
                let (p, q) = (j / s, j % s);
                let (a, b) = (src[j], src[j + half]);
                line[q + 2 * s * p] = a + b;
                line[q + 2 * s * p + s] = (a - b) * twiddle(p, n / s);
            }
            s *= 2;
        }
        // fft_shared: each residue q mod s is a line of length n/s, stride s.
        let (stride, len) = (s, n / s);
        for q in 0..stride {
            let mut cur: Vec<Complex<f64>> = (0..len).map(|i| line[q + i * stride]).collect();
            let mut t = 1;
            while t < len {
                let mut nxt = vec![Complex::default(); len];
                for j in 0..len / 2 {
                    let (p, r) = (j / t, j % t);
                    let (a, b) = (cur[j], cur[j + len / 2]);
                    nxt[r + 2 * t * p] = a + b;
                    nxt[r + 2 * t * p + t] = (a - b) * twiddle(p, len / t);
                }
                cur = nxt;
                t *= 2;
            }
            for (i, v) in cur.into_iter().enumerate() {
                line[q + i * stride] = v;
            }
        }
    }
}
