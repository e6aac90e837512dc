//! The GPU backend: f32 fields in wgpu storage buffers, the padded FFT convolution and CG's
//! vector operations as WGSL kernels, CG's scalars in device-side slots (pending as partial
//! sums until a kernel that needs them adds them up).
//!
//! Work is recorded into one open command encoder and submitted only when the host needs a
//! result (a CG residual every `check_every` iterations, a contact sweep's counts, a state).
//! A preconditioned CG iteration is eight dispatches: the convolution with s·Ks fused in (3),
//! the update of p and r with r·r (1), the preconditioner with r·z (3) and the new direction
//! (1).

use std::collections::BTreeMap;

use super::context::GpuContext;
use super::profile::{KernelTime, Profiler};
use super::recorder::{grid_for, module, storage, Kernel, Recorder, WORKGROUP};
use super::shaders;
use super::slots::{self, scalars_bytes, SLOTS};
use super::spectral::{largest_buffer_bytes, GpuSpectralFilter, SpectralKernels};
use super::traffic;
use crate::backend::cpu::spectral::SpectralFilter;
use crate::backend::kernel::stiffness_spectrum;
use crate::backend::{
    BackendError, CgKernels, CgStop, ChordAxes, ContactChange, ContactKernels, ContactMeasure,
    Counters, Device, ElasticOperator, FieldStore, GridSetup, MaskStore, Preconditioner, Scalars,
    Slot,
};
use crate::params::BACKEND;
use wgpu::util::DeviceExt;

/// Most workgroups of a reduction's first pass.
const MAX_REDUCE_GROUPS: usize = 1024;
/// Elements each reduction thread adds at least (before the workgroup tree).
const REDUCE_PER_THREAD: usize = 8;

/// A real field of nx × ny f32 values in a storage buffer.
pub struct GpuField {
    buffer: wgpu::Buffer,
}

/// A contact set on the device: one u32 per element (1 = in contact), read by every kernel
/// that works on C.
pub struct GpuMask {
    buffer: wgpu::Buffer,
}

/// Uniform parameters of shaders/vector.wgsl (`struct Params`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct VectorParams {
    n: u32,
    num: u32,
    den: u32,
    out: u32,
    sign: f32,
    scalar: f32,
    guarded: u32,
    aux: u32,
}

/// Uniform parameters of shaders/reduce.wgsl (`struct Params`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ReduceParams {
    n: u32,
    groups: u32,
    out: u32,
    nx: u32,
    sigma: f32,
    ny: u32,
    cos: f32,
    sin: f32,
}

/// The relative CG residual below which f32 arithmetic cannot bring the true residual: the
/// solver's tolerance is raised to it on this backend, so that a GPU run makes no more CG
/// iterations than a CPU run of the same states. Measured on lavapipe, sphere 64², whole
/// curve: with no floor (the 1e-8 tolerance) 2526 iterations against the CPU's 2093, with
/// 1e-7 2096, with 2e-7 1973 (worst true residual 2.4e-7, |min F̄| within 1.1e-6 of f64's).
pub const F32_RESIDUAL_FLOOR: f64 = 2e-7;

/// Uniform parameters of shaders/contact.wgsl (`struct Params`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ContactParams {
    nx: u32,
    ny: u32,
    d: f32,
    sigma: f32,
    /// 1: attach elements off C with a negative gap; 0: detach only.
    attach: u32,
    _pad: [u32; 3],
}

/// Uniform parameters of shaders/spread.wgsl (`struct Params`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SpreadParams {
    nx: u32,
    ny: u32,
    radius: u32,
    _pad: u32,
}

/// Uniform parameters of shaders/certify.wgsl (`struct Params`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct CertifyParams {
    nx: u32,
    ny: u32,
    generation: u32,
    truncation: u32,
    hole_reach: u32,
    candidate_reach: u32,
    /// −σ_c − 3ε (stress).
    limit: f32,
    safety: f32,
    /// The count slot of this generation within its batch.
    slot: u32,
    /// The slot of the generation before it in the batch ([`NO_GUARD`]: none).
    guard: u32,
    /// Tiles of [`CERTIFY_TILE`]² along x.
    tiles_x: u32,
    _pad: u32,
}

/// `CertifyParams::guard` of a batch's first generation: it runs whatever came before.
const NO_GUARD: u32 = u32::MAX;

/// The most generations of the certification recorded before the host reads their counts.
const MAX_GENERATION_BATCH: usize = 16;

/// Side of the tiles of shaders/certify.wgsl's `jacobi` and `certify` (elements; `TILE`).
const CERTIFY_TILE: usize = 16;

/// The largest truncation of G those tiles hold (elements; `HALO` in the shader).
const CERTIFY_HALO: i64 = 12;

/// The device fields of the certified detachments (shaders/certify.wgsl), made at the first
/// cascade that takes them: each element's generation and role, the hole's Jacobi iterate
/// (two buffers, ping-pong), G's table, the counts of a batch's generations with the list of
/// the tiles the hole and the candidates touch, whether each tile is listed, and the indirect
/// dispatch over the list.
struct CertifyBuffers {
    gen: wgpu::Buffer,
    role: wgpu::Buffer,
    v: [wgpu::Buffer; 2],
    g: wgpu::Buffer,
    count: wgpu::Buffer,
    listed: wgpu::Buffer,
    dispatch: wgpu::Buffer,
}

impl CertifyBuffers {
    fn new(ctx: &GpuContext, n: usize, tiles: usize) -> CertifyBuffers {
        let g = crate::backend::certify::off_diagonal();
        let field = |label| storage(ctx, label, n as u64 * 4);
        CertifyBuffers {
            gen: field("certify generation"),
            role: field("certify role"),
            v: [field("certify v (a)"), field("certify v (b)")],
            g: ctx
                .device()
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("inverse influence off the diagonal"),
                    contents: bytemuck::cast_slice(g),
                    usage: wgpu::BufferUsages::STORAGE,
                }),
            // The batch's counts, the tiles listed and their list (LISTED and LIST in
            // shaders/certify.wgsl).
            count: storage(
                ctx,
                "certified counts and listed tiles",
                4 * (MAX_GENERATION_BATCH + 1 + tiles) as u64,
            ),
            listed: storage(ctx, "tile listed", 4 * tiles as u64),
            dispatch: ctx.device().create_buffer(&wgpu::BufferDescriptor {
                label: Some("certify dispatch"),
                size: 16,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT,
                mapped_at_creation: false,
            }),
        }
    }
}

/// Which reduction of reduce.wgsl to run.
#[derive(Debug, Clone, Copy)]
enum Reduction {
    /// A state's measurement ([`ContactMeasure`]) with the chords along these axes.
    Measure(ChordAxes),
    /// The first-crossing fraction (a minimum).
    Crossing,
    /// −max |a| on C (a minimum).
    MaxAbs,
}

/// Which of the backend's two spectral filters to apply.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Filter {
    /// The influence operator u = K p.
    Convolution,
    /// The preconditioner's stiffness.
    Preconditioner,
}

/// The compiled kernels of vector.wgsl, reduce.wgsl and contact.wgsl.
struct Kernels {
    residual: Kernel,
    lerp: Kernel,
    cg_update: Kernel,
    axpy_ratio: Kernel,
    xpay_ratio: Kernel,
    dot: Kernel,
    finish_slots: Kernel,
    copy_slot: Kernel,
    measure_partials: Kernel,
    crossing_partials: Kernel,
    max_abs_partials: Kernel,
    finish_measure: Kernel,
    finish_min: Kernel,
    update_contact: Kernel,
    spread_detached: Kernel,
    certify_seed: Kernel,
    certify_mark: Kernel,
    certify_tiles: Kernel,
    certify_jacobi: Kernel,
    certify: Kernel,
    spectral: SpectralKernels,
}

impl Kernels {
    fn new(ctx: &GpuContext) -> Kernels {
        let v = module(ctx, "vector.wgsl", shaders::VECTOR);
        let r = module(ctx, "reduce.wgsl", shaders::REDUCE);
        let c = module(ctx, "contact.wgsl", shaders::CONTACT);
        let s = module(ctx, "spread.wgsl", shaders::SPREAD);
        let cf = module(ctx, "certify.wgsl", shaders::CERTIFY);
        let k = |m: &wgpu::ShaderModule, table, entry| {
            Kernel::new(ctx, m, entry, shaders::bindings(table, entry))
        };
        let vector = |entry| k(&v, shaders::VECTOR_KERNELS, entry);
        let reduce = |entry| k(&r, shaders::REDUCE_KERNELS, entry);
        Kernels {
            residual: vector("residual"),
            lerp: vector("lerp"),
            cg_update: vector("cg_update"),
            axpy_ratio: vector("axpy_ratio"),
            xpay_ratio: vector("xpay_ratio"),
            dot: vector("dot_masked"),
            finish_slots: vector("finish_slots"),
            copy_slot: vector("copy_slot"),
            measure_partials: reduce("measure_partials"),
            crossing_partials: reduce("crossing_partials"),
            max_abs_partials: reduce("max_abs_partials"),
            finish_measure: reduce("finish_measure"),
            finish_min: reduce("finish_min"),
            update_contact: k(&c, shaders::CONTACT_KERNELS, "update_contact"),
            spread_detached: k(&s, shaders::SPREAD_KERNELS, "spread_detached"),
            certify_seed: k(&cf, shaders::CERTIFY_KERNELS, "seed"),
            certify_mark: k(&cf, shaders::CERTIFY_KERNELS, "mark"),
            certify_tiles: k(&cf, shaders::CERTIFY_KERNELS, "tiles"),
            certify_jacobi: k(&cf, shaders::CERTIFY_KERNELS, "jacobi"),
            certify: k(&cf, shaders::CERTIFY_KERNELS, "certify"),
            spectral: SpectralKernels::new(ctx),
        }
    }
}

/// The wgpu backend (f32 on the device).
pub struct GpuBackend {
    ctx: GpuContext,
    nx: usize,
    ny: usize,
    kernels: Kernels,
    convolution: GpuSpectralFilter,
    /// Whether the convolution is the periodic one (unpadded, images summed).
    periodic: bool,
    preconditioner: Option<GpuSpectralFilter>,
    profile: wgpu::Buffer,
    /// The detachment shares (f32, `backend::shares::detachment_shares`).
    shares: wgpu::Buffer,
    /// Bound to the mask binding of a kernel that does not read it (the unmasked
    /// convolution): the kernels' layouts share that binding.
    no_mask: wgpu::Buffer,
    /// CG's scalar slots with their pending partials (shaders/shared/slots.wgsl).
    scalars: wgpu::Buffer,
    /// Partials of each slot as last produced (for the byte counts of their consumers).
    pending: [u32; SLOTS],
    /// The stop condition of the guarded CG batch being recorded, if any.
    guard: Option<CgStop>,
    /// Slots handed out so far (the next one's index).
    next_slot: usize,
    /// The slot receiving the per-state sums for the host.
    sum_slot: Slot,
    /// The slot receiving the first-crossing fraction.
    min_slot: Slot,
    partials: wgpu::Buffer,
    counts: wgpu::Buffer,
    contact_counters: wgpu::Buffer,
    /// Made at the first certification.
    certify: Option<CertifyBuffers>,
    /// Generations the last certification took (its last, which certifies nothing,
    /// included): the next one records as many before it first reads their counts.
    certify_generations: usize,
    reduce_groups: u32,
    rec: Recorder,
}

/// What a grid of nx × ny needs of an adapter: its largest buffer (the padded half spectrum)
/// within the storage-binding and buffer-size limits, and its FFT lines (its longer side)
/// within what one workgroup's memory holds. On failure, the message says which limit and the
/// largest square grid that fits.
pub fn check_fits(limits: &wgpu::Limits, nx: usize, ny: usize) -> Result<(), BackendError> {
    let limit = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    let which = if limits.max_storage_buffer_binding_size <= limits.max_buffer_size {
        "max_storage_buffer_binding_size"
    } else {
        "max_buffer_size"
    };
    let need = largest_buffer_bytes(nx, ny);
    let side = super::spectral::points_max(limits);
    let n = largest_square_grid(limits);
    let reason = if nx.max(ny) > side {
        format!(
            "its FFT lines of {} values exceed the {side} that the adapter's {} KiB of workgroup \
             memory holds; the largest square grid that fits is {n}×{n} (or use {BACKEND} cpu)",
            nx.max(ny),
            limits.max_compute_workgroup_storage_size >> 10
        )
    } else if need > limit || nx * ny > u32::MAX as usize / 4 {
        format!(
            "the padded half spectrum needs one buffer of {} MiB but the adapter's {which} is {} \
             MiB; the largest square grid that fits is {n}×{n} (or use {BACKEND} cpu)",
            need >> 20,
            limit >> 20
        )
    } else {
        return Ok(());
    };
    Err(BackendError::GridTooLarge {
        nx,
        ny,
        backend: "gpu",
        reason,
    })
}

/// The largest square power-of-two grid N × N the adapter's limits allow: its half spectrum,
/// (N + 1)·N complex f32 values, in one binding, and lines of N values in one workgroup.
pub fn largest_square_grid(limits: &wgpu::Limits) -> usize {
    let limit = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    let side = super::spectral::points_max(limits);
    let mut n = 4usize;
    while 2 * n <= side && largest_buffer_bytes(2 * n, 2 * n) <= limit {
        n *= 2;
    }
    n
}

impl GpuBackend {
    /// Build the backend on an opened device: compile the kernels, upload the profile and
    /// the kernel spectra (computed in f64 on the CPU). Refuses, before allocating anything,
    /// a grid whose buffers exceed the adapter's limits.
    pub fn new(ctx: GpuContext, setup: &GridSetup) -> Result<Self, BackendError> {
        Self::with_convolution(ctx, setup, false)
    }

    /// Like [`GpuBackend::new`] but with the periodic convolution of
    /// [`crate::backend::cpu::CpuBackend::new_periodic`] (the same symbol,
    /// [`crate::backend::kernel::periodic_symbol`], on the unpadded nx × ny transform that the
    /// preconditioner also uses), for a surface periodic over the domain. As there, the
    /// certified detachments are not taken and no contact is reported at the edge.
    pub fn new_periodic(ctx: GpuContext, setup: &GridSetup) -> Result<Self, BackendError> {
        Self::with_convolution(ctx, setup, true)
    }

    /// [`GpuBackend::new`] with the padded (`periodic` false) or periodic convolution.
    fn with_convolution(
        ctx: GpuContext,
        setup: &GridSetup,
        periodic: bool,
    ) -> Result<Self, BackendError> {
        crate::backend::check_profile(setup)?;
        let (nx, ny) = (setup.nx, setup.ny);
        if !nx.is_power_of_two() || !ny.is_power_of_two() || nx < 4 || ny < 4 {
            return Err(BackendError::GridTooLarge {
                nx,
                ny,
                backend: "gpu",
                reason: "the GPU FFT needs power-of-two grids of at least 4×4".into(),
            });
        }
        check_fits(ctx.limits(), nx, ny)?;
        let (dx, e) = (setup.dx, setup.e_star);
        let kernels = Kernels::new(&ctx);
        let conv = SpectralFilter::influence(nx, ny, dx, e, periodic);
        let convolution = GpuSpectralFilter::new(&ctx, &kernels.spectral, &conv, nx, ny)?;
        drop(conv);
        let preconditioner = match setup.preconditioner {
            Preconditioner::None => None,
            Preconditioner::Stiffness => {
                let mut f = SpectralFilter::new(nx, ny, nx, ny);
                f.set_symbol(&stiffness_spectrum(nx, ny, dx, e));
                Some(GpuSpectralFilter::new(&ctx, &kernels.spectral, &f, nx, ny)?)
            }
        };
        let n = nx * ny;
        let profile: Vec<f32> = setup.profile.iter().map(|&v| v as f32).collect();
        let profile = ctx
            .device()
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("profile"),
                contents: bytemuck::cast_slice(&profile),
                usage: wgpu::BufferUsages::STORAGE,
            });
        let shares: Vec<f32> = crate::backend::shares::detachment_shares()
            .iter()
            .map(|&v| v as f32)
            .collect();
        let shares = ctx
            .device()
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("detachment shares"),
                contents: bytemuck::cast_slice(&shares),
                usage: wgpu::BufferUsages::STORAGE,
            });
        let reduce_groups = n
            .div_ceil(WORKGROUP as usize * REDUCE_PER_THREAD)
            .clamp(1, MAX_REDUCE_GROUPS) as u32;
        let backend = GpuBackend {
            nx,
            ny,
            periodic,
            kernels,
            convolution,
            preconditioner,
            profile,
            shares,
            no_mask: storage(&ctx, "unread mask", n as u64 * 4),
            scalars: storage(&ctx, "scalars", scalars_bytes()),
            pending: [0; SLOTS],
            guard: None,
            next_slot: 2,
            sum_slot: Slot::new(0),
            min_slot: Slot::new(1),
            partials: storage(&ctx, "partials", 3 * reduce_groups as u64 * 4),
            counts: storage(&ctx, "partial counts", (5 * reduce_groups as u64 + 8) * 4),
            contact_counters: storage(&ctx, "contact counters", 16),
            certify: None,
            certify_generations: 2,
            reduce_groups,
            rec: Recorder::default(),
            ctx,
        };
        backend.ctx.check()?;
        Ok(backend)
    }

    /// The adapter in use, in words.
    pub fn adapter_summary(&self) -> String {
        self.ctx.adapter_summary()
    }

    /// The device context (for tests that provoke a device loss).
    pub fn context(&self) -> &GpuContext {
        &self.ctx
    }

    /// Start or stop timing every kernel with timestamp queries (pending work is submitted
    /// first). Fails where the adapter cannot write timestamps.
    pub fn set_profiling(&mut self, on: bool) -> Result<(), BackendError> {
        let profiler = if on {
            Some(Profiler::new(&self.ctx)?)
        } else {
            None
        };
        self.rec.set_profiler(&self.ctx, profiler)
    }

    /// The per-kernel profile gathered since profiling started (after submitting pending
    /// work), or `None` when not profiling.
    pub fn profile(&mut self) -> Result<Option<BTreeMap<&'static str, KernelTime>>, BackendError> {
        self.rec.flush(&self.ctx)?;
        Ok(self.rec.profiler().map(|p| p.totals().clone()))
    }

    /// The longest FFT line (complex values) this device's kernels transform in workgroup
    /// memory: the longest grid side it accepts.
    pub fn longest_line(&self) -> usize {
        self.kernels.spectral.points_max()
    }

    fn n(&self) -> usize {
        self.nx * self.ny
    }

    fn vector_params(&self) -> VectorParams {
        VectorParams {
            n: self.n() as u32,
            num: 0,
            den: 0,
            out: slots::NO_SLOT,
            sign: 1.0,
            scalar: 0.0,
            guarded: 0,
            aux: 0,
        }
    }

    /// dst = F src with F the convolution or the preconditioner (a copy where there is none)
    /// and, with `dot`, slots\[dot\] = Σ_C src·dst fused into the filter's last pass (which a
    /// CG guard then guards).
    fn filter(
        &mut self,
        which: Filter,
        mask: &wgpu::Buffer,
        src: &GpuField,
        dst: &GpuField,
        dot: Option<Slot>,
    ) -> Result<(), BackendError> {
        let filter = match which {
            Filter::Convolution => &mut self.convolution,
            Filter::Preconditioner => match &mut self.preconditioner {
                Some(f) => f,
                None => {
                    self.copy_grid(&src.buffer, &dst.buffer);
                    return match dot {
                        Some(out) => self.dot_on(mask, src, dst, out),
                        None => Ok(()),
                    };
                }
            },
        };
        filter.set_guarded(dot.is_some() && self.guard.is_some());
        let result = filter.encode(
            &self.ctx,
            &mut self.rec,
            &self.kernels.spectral,
            &self.scalars,
            &src.buffer,
            &dst.buffer,
            mask,
            which == Filter::Preconditioner,
            dot.map(|out| (out, &src.buffer)),
        );
        filter.set_guarded(false);
        result?;
        if let Some(out) = dot {
            self.pending[out.index()] = filter.row_groups();
        }
        Ok(())
    }

    /// slots\[out\] = Σ over the mask `mask` of a·b.
    fn dot_on(
        &mut self,
        mask: &wgpu::Buffer,
        a: &GpuField,
        b: &GpuField,
        out: Slot,
    ) -> Result<(), BackendError> {
        let params = VectorParams {
            out: out.index() as u32,
            ..self.vector_params()
        };
        let mask = mask.clone();
        let bytes = traffic::dot(self.n());
        self.pending[out.index()] = self.strided(
            |k| &k.dot,
            params,
            &[(1, &a.buffer), (2, &b.buffer), (4, &mask)],
            bytes,
        )?;
        Ok(())
    }

    /// Record a copy of one grid of 4-byte values from `src` to `dst` (a field or the mask).
    fn copy_grid(&mut self, src: &wgpu::Buffer, dst: &wgpu::Buffer) {
        let bytes = self.n() as u64 * 4;
        self.rec.counters.bytes += 2 * bytes;
        self.rec
            .encoder(&self.ctx)
            .copy_buffer_to_buffer(src, 0, dst, 0, bytes);
    }

    /// Partials a consumer of slots `a` and `b` adds (for its byte count): the larger.
    fn partials_of(&self, a: Slot, b: Slot) -> u32 {
        self.pending[a.0].max(self.pending[b.0])
    }

    /// Record an element-wise kernel of vector.wgsl with one thread per element.
    fn elementwise(
        &mut self,
        kernel: fn(&Kernels) -> &Kernel,
        params: VectorParams,
        entries: &[(u32, &wgpu::Buffer)],
        fields: u64,
    ) -> Result<(), BackendError> {
        let p = self.rec.uniform(&self.ctx, &params)?;
        let mut all = vec![(0, &p)];
        all.extend_from_slice(entries);
        let grid = grid_for(&self.ctx, self.n());
        let bytes = traffic::elementwise(self.n(), fields);
        self.rec
            .dispatch(&self.ctx, kernel(&self.kernels), &all, grid, bytes)
    }

    /// Record a grid-stride kernel of vector.wgsl (the ones that read or produce slots);
    /// returns its workgroups (the partials of a slot it produces).
    fn strided(
        &mut self,
        kernel: fn(&Kernels) -> &Kernel,
        params: VectorParams,
        entries: &[(u32, &wgpu::Buffer)],
        bytes: u64,
    ) -> Result<u32, BackendError> {
        let p = self.rec.uniform(&self.ctx, &params)?;
        let mut all = vec![(0, &p), (8, &self.scalars)];
        all.extend_from_slice(entries);
        let groups = traffic::stride_groups(self.n());
        self.rec
            .dispatch(&self.ctx, kernel(&self.kernels), &all, (groups, 1), bytes)?;
        Ok(groups)
    }

    /// Two-pass reduction of `kind` over the fields a, b: partials per workgroup, then one
    /// workgroup into slot `out`.
    fn reduce(
        &mut self,
        kind: Reduction,
        mask: &wgpu::Buffer,
        a: &wgpu::Buffer,
        b: &wgpu::Buffer,
        out: u32,
        sigma: f32,
    ) -> Result<(), BackendError> {
        let axes = match kind {
            Reduction::Measure(axes) => axes,
            Reduction::Crossing | Reduction::MaxAbs => ChordAxes::ALIGNED,
        };
        let params = ReduceParams {
            n: self.n() as u32,
            groups: self.reduce_groups,
            out,
            nx: self.nx as u32,
            sigma,
            ny: self.ny as u32,
            cos: axes.cos as f32,
            sin: axes.sin as f32,
        };
        let p = self.rec.uniform(&self.ctx, &params)?;
        let k = &self.kernels;
        let n = self.n();
        let (first, finish, bytes) = match kind {
            Reduction::Measure(_) => (
                k.measure_partials.clone(),
                k.finish_measure.clone(),
                8 * n as u64,
            ),
            Reduction::Crossing => (
                k.crossing_partials.clone(),
                k.finish_min.clone(),
                12 * n as u64,
            ),
            Reduction::MaxAbs => (
                k.max_abs_partials.clone(),
                k.finish_min.clone(),
                8 * n as u64,
            ),
        };
        let (first, finish) = (&first, &finish);
        let g = self.reduce_groups as u64;
        match kind {
            Reduction::Measure(_) => {
                self.rec.dispatch(
                    &self.ctx,
                    first,
                    &[
                        (0, &p),
                        (1, a),
                        (3, mask),
                        (4, &self.partials),
                        (5, &self.counts),
                    ],
                    (self.reduce_groups, 1),
                    bytes + 32 * g,
                )?;
                self.rec.dispatch(
                    &self.ctx,
                    finish,
                    &[
                        (0, &p),
                        (4, &self.partials),
                        (5, &self.counts),
                        (8, &self.scalars),
                    ],
                    (1, 1),
                    32 * g + 44,
                )?;
            }
            Reduction::Crossing | Reduction::MaxAbs => {
                let fields: &[(u32, &wgpu::Buffer)] = if matches!(kind, Reduction::Crossing) {
                    &[(0, &p), (1, a), (2, b), (3, mask), (4, &self.partials)]
                } else {
                    &[(0, &p), (1, a), (3, mask), (4, &self.partials)]
                };
                self.rec.dispatch(
                    &self.ctx,
                    first,
                    fields,
                    (self.reduce_groups, 1),
                    bytes + 4 * g,
                )?;
                self.rec.dispatch(
                    &self.ctx,
                    finish,
                    &[(0, &p), (4, &self.partials), (8, &self.scalars)],
                    (1, 1),
                    4 * g + 8,
                )?;
            }
        }
        self.pending[out as usize] = 0;
        Ok(())
    }

    /// Give every pending slot its value (one dispatch), then read slots `first..first+count`.
    fn read_values(&mut self, first: usize, count: usize) -> Result<Vec<f32>, BackendError> {
        if self.pending.iter().any(|&p| p > 0) {
            let reads: u64 = self.pending.iter().map(|&p| 4 * p as u64).sum();
            self.rec.dispatch(
                &self.ctx,
                &self.kernels.finish_slots,
                &[(8, &self.scalars)],
                (SLOTS as u32, 1),
                reads + 8 * SLOTS as u64,
            )?;
            self.pending = [0; SLOTS];
        }
        self.rec.read(
            &self.ctx,
            &self.scalars,
            slots::value_offset(first),
            4 * count as u64,
        )
    }

    fn check_len(&self, len: usize) -> Result<(), BackendError> {
        if len != self.n() {
            return Err(BackendError::Unavailable(format!(
                "a host field of {len} values for a grid of {}",
                self.n()
            )));
        }
        Ok(())
    }
}

impl Device for GpuBackend {
    type Field = GpuField;
    type Mask = GpuMask;
    fn name(&self) -> &'static str {
        if self.periodic {
            "gpu-periodic"
        } else {
            "gpu"
        }
    }
    fn precision(&self) -> &'static str {
        "f32"
    }
    fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }
    fn sibling(&self, setup: &GridSetup) -> Result<Self, BackendError> {
        GpuBackend::with_convolution(self.ctx.clone(), setup, self.periodic)
    }
    fn counters(&self) -> Counters {
        self.rec.counters
    }
}

impl FieldStore for GpuBackend {
    fn field(&mut self) -> Result<GpuField, BackendError> {
        let buffer = storage(&self.ctx, "field", self.n() as u64 * 4);
        self.ctx.check()?;
        Ok(GpuField { buffer })
    }
    fn upload(&mut self, dst: &mut GpuField, host: &[f64]) -> Result<(), BackendError> {
        self.check_len(host.len())?;
        self.rec.flush(&self.ctx)?;
        let v: Vec<f32> = host.iter().map(|&x| x as f32).collect();
        self.ctx
            .queue()
            .write_buffer(&dst.buffer, 0, bytemuck::cast_slice(&v));
        Ok(())
    }
    fn download(&mut self, src: &GpuField, host: &mut [f64]) -> Result<(), BackendError> {
        self.check_len(host.len())?;
        let v: Vec<f32> = self
            .rec
            .read(&self.ctx, &src.buffer, 0, self.n() as u64 * 4)?;
        for (h, x) in host.iter_mut().zip(v) {
            *h = x as f64;
        }
        Ok(())
    }
    fn copy(&mut self, src: &GpuField, dst: &mut GpuField) -> Result<(), BackendError> {
        self.copy_grid(&src.buffer, &dst.buffer);
        Ok(())
    }
}

impl MaskStore for GpuBackend {
    fn mask(&mut self) -> Result<GpuMask, BackendError> {
        let buffer = storage(&self.ctx, "contact mask", self.n() as u64 * 4);
        self.ctx.check()?;
        Ok(GpuMask { buffer })
    }
    fn upload_mask(&mut self, dst: &mut GpuMask, host: &[bool]) -> Result<(), BackendError> {
        self.check_len(host.len())?;
        self.rec.flush(&self.ctx)?;
        let v: Vec<u32> = host.iter().map(|&m| m as u32).collect();
        self.ctx
            .queue()
            .write_buffer(&dst.buffer, 0, bytemuck::cast_slice(&v));
        Ok(())
    }
    fn download_mask(&mut self, src: &GpuMask, host: &mut [bool]) -> Result<(), BackendError> {
        self.check_len(host.len())?;
        let v: Vec<u32> = self
            .rec
            .read(&self.ctx, &src.buffer, 0, self.n() as u64 * 4)?;
        for (m, x) in host.iter_mut().zip(v) {
            *m = x != 0;
        }
        Ok(())
    }
    fn copy_mask(&mut self, src: &GpuMask, dst: &mut GpuMask) -> Result<(), BackendError> {
        self.copy_grid(&src.buffer, &dst.buffer);
        Ok(())
    }
}

impl Scalars for GpuBackend {
    fn slot(&mut self) -> Result<Slot, BackendError> {
        if self.next_slot >= slots::HALT_SLOT {
            return Err(BackendError::Unavailable(format!(
                "the GPU backend has no more than {} scalar slots",
                slots::HALT_SLOT
            )));
        }
        self.next_slot += 1;
        Ok(Slot::new(self.next_slot - 1))
    }
    fn copy_slot(&mut self, src: Slot, dst: Slot) -> Result<(), BackendError> {
        let params = VectorParams {
            num: src.index() as u32,
            den: dst.index() as u32,
            ..self.vector_params()
        };
        let p = self.rec.uniform(&self.ctx, &params)?;
        let bytes = 4 * self.pending[src.index()] as u64 + 8;
        self.rec.dispatch(
            &self.ctx,
            &self.kernels.copy_slot,
            &[(0, &p), (8, &self.scalars)],
            (1, 1),
            bytes,
        )?;
        self.pending[dst.index()] = 0;
        Ok(())
    }
    fn read_slots(&mut self, slots: &[Slot], out: &mut [f64]) -> Result<(), BackendError> {
        let v = self.read_values(0, self.next_slot)?;
        for (o, s) in out.iter_mut().zip(slots) {
            *o = v[s.index()] as f64;
        }
        Ok(())
    }
}

impl ElasticOperator for GpuBackend {
    fn convolve(&mut self, src: &GpuField, dst: &mut GpuField) -> Result<(), BackendError> {
        let unread = self.no_mask.clone();
        self.filter(Filter::Convolution, &unread, src, dst, None)
    }
    fn precondition(
        &mut self,
        c: &GpuMask,
        src: &GpuField,
        dst: &mut GpuField,
    ) -> Result<(), BackendError> {
        self.filter(Filter::Preconditioner, &c.buffer, src, dst, None)
    }
}

impl CgKernels for GpuBackend {
    fn residual_floor(&self) -> f64 {
        F32_RESIDUAL_FLOOR
    }
    /// 8: the device stops the iterations queued past convergence itself, so reading rarely
    /// costs only their launches.
    fn check_every(&self) -> usize {
        8
    }
    fn convolve_dot(
        &mut self,
        c: &GpuMask,
        src: &GpuField,
        dst: &mut GpuField,
        out: Slot,
    ) -> Result<(), BackendError> {
        self.filter(Filter::Convolution, &c.buffer, src, dst, Some(out))
    }
    fn precondition_dot(
        &mut self,
        c: &GpuMask,
        src: &GpuField,
        dst: &mut GpuField,
        out: Slot,
    ) -> Result<(), BackendError> {
        self.filter(Filter::Preconditioner, &c.buffer, src, dst, Some(out))
    }
    fn residual(
        &mut self,
        c: &GpuMask,
        u: &GpuField,
        d: f64,
        r: &mut GpuField,
    ) -> Result<(), BackendError> {
        let params = VectorParams {
            scalar: d as f32,
            ..self.vector_params()
        };
        let (mask, profile) = (c.buffer.clone(), self.profile.clone());
        self.elementwise(
            |k| &k.residual,
            params,
            &[(1, &u.buffer), (3, &r.buffer), (4, &mask), (5, &profile)],
            4,
        )
    }
    fn dot(
        &mut self,
        c: &GpuMask,
        a: &GpuField,
        b: &GpuField,
        out: Slot,
    ) -> Result<(), BackendError> {
        self.dot_on(&c.buffer, a, b, out)
    }
    fn axpy_ratio(
        &mut self,
        c: &GpuMask,
        y: &mut GpuField,
        x: &GpuField,
        num: Slot,
        den: Slot,
        sign: f64,
    ) -> Result<(), BackendError> {
        let params = VectorParams {
            num: num.index() as u32,
            den: den.index() as u32,
            sign: sign as f32,
            ..self.vector_params()
        };
        let mask = c.buffer.clone();
        let bytes = traffic::axpy_ratio(self.n(), self.partials_of(num, den));
        self.strided(
            |k| &k.axpy_ratio,
            params,
            &[(1, &x.buffer), (3, &y.buffer), (4, &mask)],
            bytes,
        )?;
        Ok(())
    }
    fn xpay_ratio(
        &mut self,
        c: &GpuMask,
        y: &mut GpuField,
        x: &GpuField,
        num: Slot,
        den: Slot,
    ) -> Result<(), BackendError> {
        let params = match self.guard {
            Some(g) => VectorParams {
                num: num.index() as u32,
                den: den.index() as u32,
                out: g.rr.index() as u32,
                aux: g.bb.index() as u32,
                scalar: (g.tolerance * g.tolerance) as f32,
                guarded: 1,
                ..self.vector_params()
            },
            None => VectorParams {
                num: num.index() as u32,
                den: den.index() as u32,
                ..self.vector_params()
            },
        };
        let mask = c.buffer.clone();
        let bytes = traffic::xpay_ratio(self.n(), self.partials_of(num, den));
        self.strided(
            |k| &k.xpay_ratio,
            params,
            &[(1, &x.buffer), (3, &y.buffer), (4, &mask)],
            bytes,
        )?;
        Ok(())
    }
    fn cg_update(
        &mut self,
        c: &GpuMask,
        x: &mut GpuField,
        r: &mut GpuField,
        s: &GpuField,
        q: &GpuField,
        num: Slot,
        den: Slot,
        rr: Slot,
    ) -> Result<(), BackendError> {
        let params = VectorParams {
            num: num.index() as u32,
            den: den.index() as u32,
            out: rr.index() as u32,
            guarded: self.guard.is_some() as u32,
            ..self.vector_params()
        };
        let mask = c.buffer.clone();
        let bytes = traffic::cg_update(self.n(), self.partials_of(num, den));
        self.pending[rr.index()] = self.strided(
            |k| &k.cg_update,
            params,
            &[
                (1, &s.buffer),
                (2, &q.buffer),
                (3, &x.buffer),
                (4, &mask),
                (6, &r.buffer),
            ],
            bytes,
        )?;
        Ok(())
    }
    fn guard_cg(&mut self, stop: Option<CgStop>) -> Result<(), BackendError> {
        if stop.is_some() {
            // HALT_SLOT and STEPS_SLOT back to 0.0.
            self.rec.encoder(&self.ctx).clear_buffer(
                &self.scalars,
                slots::value_offset(slots::HALT_SLOT),
                Some(8),
            );
            self.pending[slots::HALT_SLOT] = 0;
            self.pending[slots::STEPS_SLOT] = 0;
        }
        self.guard = stop;
        Ok(())
    }
    fn defers_cg_start(&self) -> bool {
        true
    }
    fn max_abs_to(&mut self, c: &GpuMask, f: &GpuField, out: Slot) -> Result<(), BackendError> {
        // The reduction leaves −max |f| (a minimum); the copy turns its sign in place.
        let out = out.index() as u32;
        self.reduce(Reduction::MaxAbs, &c.buffer, &f.buffer, &f.buffer, out, 0.0)?;
        let params = VectorParams {
            num: out,
            den: out,
            sign: -1.0,
            ..self.vector_params()
        };
        let p = self.rec.uniform(&self.ctx, &params)?;
        self.rec.dispatch(
            &self.ctx,
            &self.kernels.copy_slot,
            &[(0, &p), (8, &self.scalars)],
            (1, 1),
            8,
        )
    }
    fn read_cg_status(
        &mut self,
        slots: &[Slot],
        out: &mut [f64],
    ) -> Result<Option<usize>, BackendError> {
        let v = self.read_values(0, SLOTS)?;
        for (o, s) in out.iter_mut().zip(slots) {
            *o = v[s.index()] as f64;
        }
        Ok(self.guard.map(|_| v[slots::STEPS_SLOT] as usize))
    }
}

impl ContactKernels for GpuBackend {
    fn update_contact(
        &mut self,
        c: &mut GpuMask,
        p: &mut GpuField,
        u: &GpuField,
        attach_at: Option<f64>,
        sigma_c: f64,
    ) -> Result<ContactChange, BackendError> {
        let params = ContactParams {
            nx: self.nx as u32,
            ny: self.ny as u32,
            d: attach_at.unwrap_or(0.0) as f32,
            sigma: sigma_c as f32,
            attach: attach_at.is_some() as u32,
            _pad: [0; 3],
        };
        let prm = self.rec.uniform(&self.ctx, &params)?;
        self.rec
            .encoder(&self.ctx)
            .clear_buffer(&self.contact_counters, 0, None);
        let grid = grid_for(&self.ctx, self.n());
        let bytes = traffic::elementwise(self.n(), 6) + 16;
        self.rec.dispatch(
            &self.ctx,
            &self.kernels.update_contact,
            &[
                (0, &prm),
                (1, &p.buffer),
                (2, &u.buffer),
                (3, &c.buffer),
                (4, &self.profile),
                (5, &self.contact_counters),
            ],
            grid,
            bytes,
        )?;
        let n: Vec<u32> = self.rec.read(&self.ctx, &self.contact_counters, 0, 16)?;
        Ok(ContactChange {
            detached: n[0] as usize,
            attached: n[1] as usize,
            n_contact: n[2] as usize,
            // A periodic domain has no edge: a contact there meets its own images.
            at_edge: if self.periodic { 0 } else { n[3] as usize },
        })
    }
    fn spread_detached(
        &mut self,
        c: &GpuMask,
        before: &GpuField,
        p: &mut GpuField,
    ) -> Result<(), BackendError> {
        let params = SpreadParams {
            nx: self.nx as u32,
            ny: self.ny as u32,
            radius: crate::backend::shares::SHARE_RADIUS as u32,
            _pad: 0,
        };
        let prm = self.rec.uniform(&self.ctx, &params)?;
        let grid = grid_for(&self.ctx, self.n());
        // p read and written, the mask and `before` read; the neighbours' reads hit the cache.
        let bytes = traffic::elementwise(self.n(), 4);
        self.rec.dispatch(
            &self.ctx,
            &self.kernels.spread_detached,
            &[
                (0, &prm),
                (1, &p.buffer),
                (2, &before.buffer),
                (3, &c.buffer),
                (4, &self.shares),
            ],
            grid,
            bytes,
        )
    }
    fn certify_detached(
        &mut self,
        c: &mut GpuMask,
        before: &GpuField,
        p: &mut GpuField,
        sigma_c: f64,
        eps: f64,
    ) -> Result<Option<usize>, BackendError> {
        use crate::backend::certify::{
            CANDIDATE_REACH, ERROR_MARGIN, HOLE_REACH, JACOBI_STEPS, ROUNDING_SAFETY, TRUNCATION,
        };
        if self.periodic {
            // The bound is the plane's (backend::certify), not proven for the periodic
            // operator: not taken, as on the CPU backend.
            return Ok(None);
        }
        let n = self.n();
        const _: () = assert!(TRUNCATION <= CERTIFY_HALO, "the tiles' halo must hold G");
        let tiles = (
            self.nx.div_ceil(CERTIFY_TILE) as u32,
            self.ny.div_ceil(CERTIFY_TILE) as u32,
        );
        let bufs = self
            .certify
            .get_or_insert_with(|| CertifyBuffers::new(&self.ctx, n, (tiles.0 * tiles.1) as usize));
        let enc = self.rec.encoder(&self.ctx);
        for b in [
            &bufs.gen,
            &bufs.role,
            &bufs.v[0],
            &bufs.v[1],
            &bufs.count,
            &bufs.listed,
        ] {
            enc.clear_buffer(b, 0, None);
        }
        let grid = grid_for(&self.ctx, n);
        let mut params = CertifyParams {
            nx: self.nx as u32,
            ny: self.ny as u32,
            generation: 1,
            truncation: TRUNCATION as u32,
            hole_reach: HOLE_REACH as u32,
            candidate_reach: CANDIDATE_REACH as u32,
            limit: (-sigma_c - ERROR_MARGIN * eps) as f32,
            safety: ROUNDING_SAFETY as f32,
            slot: 0,
            guard: NO_GUARD,
            tiles_x: tiles.0,
            _pad: 0,
        };
        let prm = self.rec.uniform(&self.ctx, &params)?;
        self.rec.dispatch(
            &self.ctx,
            &self.kernels.certify_seed,
            &[
                (0, &prm),
                (2, &before.buffer),
                (3, &c.buffer),
                (4, &bufs.gen),
            ],
            grid,
            traffic::elementwise(n, 3),
        )?;
        // Generations are recorded in batches, as many as the last certification took, and
        // their counts read once a batch: a generation after one that certified nothing does
        // nothing on the device (its guard), so the batch ends where a loop of one generation
        // a read would. The stencils' neighbour reads hit the cache or workgroup memory: each
        // kernel moves about its own elements' fields.
        let batch = self.certify_generations.clamp(2, MAX_GENERATION_BATCH);
        let mut certified = 0;
        let mut first = 1u32;
        loop {
            // The batch's counts (the list of tiles after them stays).
            self.rec.encoder(&self.ctx).clear_buffer(
                &bufs.count,
                0,
                Some(4 * MAX_GENERATION_BATCH as u64),
            );
            for k in 0..batch {
                params.generation = first + k as u32;
                params.slot = k as u32;
                params.guard = if k == 0 { NO_GUARD } else { k as u32 - 1 };
                let prm = self.rec.uniform(&self.ctx, &params)?;
                self.rec.dispatch(
                    &self.ctx,
                    &self.kernels.certify_mark,
                    &[
                        (0, &prm),
                        (3, &c.buffer),
                        (4, &bufs.gen),
                        (5, &bufs.role),
                        (9, &bufs.count),
                        (10, &bufs.listed),
                    ],
                    grid,
                    traffic::elementwise(n, 1),
                )?;
                self.rec.dispatch(
                    &self.ctx,
                    &self.kernels.certify_tiles,
                    &[(0, &prm), (9, &bufs.count), (11, &bufs.dispatch)],
                    (1, 1),
                    16,
                )?;
                for step in 0..JACOBI_STEPS {
                    let (from, to) = (&bufs.v[step % 2], &bufs.v[(step + 1) % 2]);
                    self.rec.dispatch_indirect(
                        &self.ctx,
                        &self.kernels.certify_jacobi,
                        &[
                            (0, &prm),
                            (2, &before.buffer),
                            (4, &bufs.gen),
                            (5, &bufs.role),
                            (6, from),
                            (7, to),
                            (8, &bufs.g),
                            (9, &bufs.count),
                        ],
                        &bufs.dispatch,
                        traffic::elementwise(n, 2),
                    )?;
                }
                self.rec.dispatch_indirect(
                    &self.ctx,
                    &self.kernels.certify,
                    &[
                        (0, &prm),
                        (1, &p.buffer),
                        (2, &before.buffer),
                        (3, &c.buffer),
                        (4, &bufs.gen),
                        (5, &bufs.role),
                        (6, &bufs.v[JACOBI_STEPS % 2]),
                        (8, &bufs.g),
                        (9, &bufs.count),
                    ],
                    &bufs.dispatch,
                    traffic::elementwise(n, 2),
                )?;
            }
            let counts: Vec<u32> = self.rec.read(&self.ctx, &bufs.count, 0, 4 * batch as u64)?;
            match counts.iter().position(|&k| k == 0) {
                Some(last) => {
                    certified += counts[..last].iter().map(|&k| k as usize).sum::<usize>();
                    self.certify_generations = first as usize + last;
                    break;
                }
                None => {
                    certified += counts.iter().map(|&k| k as usize).sum::<usize>();
                    first += batch as u32;
                }
            }
        }
        Ok(Some(certified))
    }
    fn first_crossing(
        &mut self,
        c: &GpuMask,
        p_old: &GpuField,
        p_new: &GpuField,
        sigma_c: f64,
    ) -> Result<f64, BackendError> {
        let min_slot = self.min_slot.index() as u32;
        self.reduce(
            Reduction::Crossing,
            &c.buffer,
            &p_old.buffer,
            &p_new.buffer,
            min_slot,
            sigma_c as f32,
        )?;
        Ok(self.read_values(min_slot as usize, 1)?[0] as f64)
    }
    fn max_abs(&mut self, c: &GpuMask, f: &GpuField) -> Result<f64, BackendError> {
        let min_slot = self.min_slot.index() as u32;
        self.reduce(
            Reduction::MaxAbs,
            &c.buffer,
            &f.buffer,
            &f.buffer,
            min_slot,
            0.0,
        )?;
        Ok(-(self.read_values(min_slot as usize, 1)?[0] as f64))
    }
    fn lerp(
        &mut self,
        c: &GpuMask,
        a: &GpuField,
        b: &GpuField,
        t: f64,
        dst: &mut GpuField,
    ) -> Result<(), BackendError> {
        let params = VectorParams {
            scalar: t as f32,
            ..self.vector_params()
        };
        let mask = c.buffer.clone();
        self.elementwise(
            |k| &k.lerp,
            params,
            &[(1, &a.buffer), (2, &b.buffer), (3, &dst.buffer), (4, &mask)],
            4,
        )
    }
    fn measure(
        &mut self,
        c: &GpuMask,
        p: &GpuField,
        axes: ChordAxes,
    ) -> Result<ContactMeasure, BackendError> {
        let sum_slot = self.sum_slot.index() as u32;
        self.reduce(
            Reduction::Measure(axes),
            &c.buffer,
            &p.buffer,
            &p.buffer,
            sum_slot,
            0.0,
        )?;
        let at = 5 * self.reduce_groups as u64 * 4;
        let v: Vec<u32> = self.rec.read(&self.ctx, &self.counts, at, 8 * 4)?;
        let value = |k: usize| f32::from_bits(v[k]) as f64;
        let count = v[0] as usize;
        Ok(ContactMeasure {
            sum: value(5),
            count,
            half_lengths: (value(6) / 2.0, value(7) / 2.0),
            bounds: (count > 0).then(|| [1, 2, 3, 4].map(|k| v[k] as usize)),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_limits_name_the_limit_and_what_fits() {
        let limits = wgpu::Limits {
            max_storage_buffer_binding_size: 128 << 20,
            max_buffer_size: 256 << 20,
            max_compute_workgroup_storage_size: 48 << 10,
            ..wgpu::Limits::default()
        };
        assert!(check_fits(&limits, 2048, 2048).is_ok());
        assert_eq!(largest_square_grid(&limits), 2048);
        let err = check_fits(&limits, 4096, 4096).unwrap_err().to_string();
        assert!(err.contains("max_storage_buffer_binding_size"), "{err}");
        assert!(err.contains("2048×2048"), "{err}");
        assert!(check_fits(&limits, 4096, 1024).is_ok());
        // 32 KiB of workgroup memory (lavapipe's) hold FFT lines of 2048 values.
        let small = wgpu::Limits {
            max_compute_workgroup_storage_size: 32 << 10,
            ..limits
        };
        assert_eq!(largest_square_grid(&small), 2048);
        let err = check_fits(&small, 4096, 1024).unwrap_err().to_string();
        assert!(
            err.contains("workgroup memory") && err.contains("2048×2048"),
            "{err}"
        );
    }
}
