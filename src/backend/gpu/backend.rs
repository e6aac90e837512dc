//! The GPU backend: f32 fields in wgpu storage buffers, the padded FFT convolution and CG's
//! vector operations as WGSL kernels, CG's scalars in a device-side slot buffer.
//!
//! Work is recorded into one open command encoder and submitted only when the host needs a
//! result (a CG residual every `check_every` iterations, a contact sweep's counts, a state).

use super::context::GpuContext;
use super::fft::GpuFft;
use super::recorder::{grid_for, module, storage, Kernel, Recorder, WORKGROUP};
use super::spectral::{largest_buffer_bytes, GpuSpectralFilter, SpectralKernels};
use crate::backend::cpu::spectral::SpectralFilter;
use crate::backend::cpu::GridSetup;
use crate::backend::kernel::{padded_kernel, stiffness_spectrum};
use crate::backend::{
    Backend, BackendError, ContactChange, Counters, Preconditioner, Slot, N_SLOTS,
};
use wgpu::util::DeviceExt;

/// Device slot receiving sums for the host (after the solver's [`N_SLOTS`]).
const SUM_SLOT: u32 = N_SLOTS as u32;
/// Device slot receiving the first-crossing fraction.
const MIN_SLOT: u32 = N_SLOTS as u32 + 1;
/// Slots on the device: the solver's and the two above.
const DEVICE_SLOTS: u64 = N_SLOTS as u64 + 2;
/// Most workgroups of a reduction's first pass.
const MAX_REDUCE_GROUPS: usize = 1024;
/// Elements each reduction thread adds at least (before the workgroup tree).
const REDUCE_PER_THREAD: usize = 8;

/// A real field of nx × ny f32 values in a storage buffer.
pub struct GpuField {
    buffer: wgpu::Buffer,
}

/// Uniform parameters of shaders/vector.wgsl (`struct Params`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct VectorParams {
    n: u32,
    num: u32,
    den: u32,
    pad0: u32,
    sign: f32,
    scalar: f32,
    pad1: [u32; 2],
}

/// Uniform parameters of shaders/reduce.wgsl (`struct Params`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ReduceParams {
    n: u32,
    groups: u32,
    out: u32,
    pad0: u32,
    sigma: f32,
    pad1: [u32; 3],
}

/// Uniform parameters of shaders/contact.wgsl (`struct Params`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ContactParams {
    nx: u32,
    ny: u32,
    d: f32,
    sigma: f32,
}

/// Which reduction of reduce.wgsl to run.
#[derive(Debug, Clone, Copy)]
enum Reduction {
    /// Σ_C a·b.
    Dot,
    /// Σ_C a and |C|.
    Sum,
    /// The first-crossing fraction (a minimum).
    Crossing,
}

/// The compiled kernels of vector.wgsl, reduce.wgsl and contact.wgsl.
struct Kernels {
    residual: Kernel,
    axpy_ratio: Kernel,
    xpay_ratio: Kernel,
    lerp: Kernel,
    copy_slot: Kernel,
    dot_partials: Kernel,
    sum_partials: Kernel,
    crossing_partials: Kernel,
    finish_sum: Kernel,
    finish_min: Kernel,
    update_contact: Kernel,
    spectral: SpectralKernels,
}

impl Kernels {
    fn new(ctx: &GpuContext) -> Kernels {
        let v = module(
            ctx,
            "vector.wgsl",
            include_str!("../../../shaders/vector.wgsl"),
        );
        let r = module(
            ctx,
            "reduce.wgsl",
            include_str!("../../../shaders/reduce.wgsl"),
        );
        let c = module(
            ctx,
            "contact.wgsl",
            include_str!("../../../shaders/contact.wgsl"),
        );
        Kernels {
            residual: Kernel::new(ctx, &v, "residual"),
            axpy_ratio: Kernel::new(ctx, &v, "axpy_ratio"),
            xpay_ratio: Kernel::new(ctx, &v, "xpay_ratio"),
            lerp: Kernel::new(ctx, &v, "lerp"),
            copy_slot: Kernel::new(ctx, &v, "copy_slot"),
            dot_partials: Kernel::new(ctx, &r, "dot_partials"),
            sum_partials: Kernel::new(ctx, &r, "sum_partials"),
            crossing_partials: Kernel::new(ctx, &r, "crossing_partials"),
            finish_sum: Kernel::new(ctx, &r, "finish_sum"),
            finish_min: Kernel::new(ctx, &r, "finish_min"),
            update_contact: Kernel::new(ctx, &c, "update_contact"),
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
    fft: GpuFft,
    convolution: GpuSpectralFilter,
    preconditioner: Option<GpuSpectralFilter>,
    profile: wgpu::Buffer,
    mask: wgpu::Buffer,
    slots: wgpu::Buffer,
    partials: wgpu::Buffer,
    counts: wgpu::Buffer,
    contact_counters: wgpu::Buffer,
    reduce_groups: u32,
    rec: Recorder,
}

/// What a grid of nx × ny needs of an adapter: the largest single buffer (bytes), checked
/// against the adapter's storage-binding and buffer-size limits. On failure, the message says
/// which limit and the largest square grid that fits.
pub fn check_fits(limits: &wgpu::Limits, nx: usize, ny: usize) -> Result<(), BackendError> {
    let limit = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    let which = if limits.max_storage_buffer_binding_size <= limits.max_buffer_size {
        "max_storage_buffer_binding_size"
    } else {
        "max_buffer_size"
    };
    let need = largest_buffer_bytes(2 * nx, 2 * ny);
    if need <= limit && nx * ny <= u32::MAX as usize / 4 {
        return Ok(());
    }
    let n = largest_square_grid(limits);
    Err(BackendError::GridTooLarge {
        nx,
        ny,
        backend: "gpu",
        reason: format!(
            "the padded spectrum needs one buffer of {} MiB but the adapter's {which} is {} MiB; \
             the largest square grid that fits is {n}×{n} (or use --backend cpu)",
            need >> 20,
            limit >> 20
        ),
    })
}

/// The largest square power-of-two grid N × N whose buffers the adapter's limits allow
/// (its padded column spectrum, (N + 1)·2N complex f32 values, in one binding).
pub fn largest_square_grid(limits: &wgpu::Limits) -> usize {
    let limit = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    let mut n = 4usize;
    while largest_buffer_bytes(4 * n, 4 * n) <= limit && n < 1 << 20 {
        n *= 2;
    }
    n
}

impl GpuBackend {
    /// Build the backend on an opened device: compile the kernels, upload the profile and
    /// the kernel spectra (computed in f64 on the CPU). Refuses, before allocating anything,
    /// a grid whose buffers exceed the adapter's limits.
    pub fn new(ctx: GpuContext, setup: &GridSetup) -> Result<Self, BackendError> {
        let (nx, ny) = (setup.nx, setup.ny);
        if setup.profile.len() != nx * ny {
            return Err(BackendError::Unavailable(format!(
                "profile has {} values, grid needs {}",
                setup.profile.len(),
                nx * ny
            )));
        }
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
        let fft = GpuFft::new(&ctx, nx.max(2 * ny))?;
        let mut conv = SpectralFilter::new(nx, ny, 2 * nx, 2 * ny);
        conv.set_symbol_from_kernel(&padded_kernel(nx, ny, dx, e));
        let convolution = GpuSpectralFilter::new(&ctx, &fft, &conv, nx, ny)?;
        drop(conv);
        let preconditioner = match setup.preconditioner {
            Preconditioner::None => None,
            Preconditioner::Stiffness => {
                let mut f = SpectralFilter::new(nx, ny, nx, ny);
                f.set_symbol(&stiffness_spectrum(nx, ny, dx, e));
                Some(GpuSpectralFilter::new(&ctx, &fft, &f, nx, ny)?)
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
        let reduce_groups = n
            .div_ceil(WORKGROUP as usize * REDUCE_PER_THREAD)
            .clamp(1, MAX_REDUCE_GROUPS) as u32;
        let backend = GpuBackend {
            nx,
            ny,
            kernels: Kernels::new(&ctx),
            fft,
            convolution,
            preconditioner,
            profile,
            mask: storage(&ctx, "contact mask", n as u64 * 4),
            slots: storage(&ctx, "slots", DEVICE_SLOTS * 4),
            partials: storage(&ctx, "partials", reduce_groups as u64 * 4),
            counts: storage(&ctx, "partial counts", (reduce_groups as u64 + 1) * 4),
            contact_counters: storage(&ctx, "contact counters", 16),
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

    fn n(&self) -> usize {
        self.nx * self.ny
    }

    /// Record an element-wise kernel of vector.wgsl over the grid; the parameters (binding 0)
    /// and the contact mask (binding 4) are bound here, the fields by `entries`.
    fn vector(
        &mut self,
        kernel: fn(&Kernels) -> &Kernel,
        params: VectorParams,
        entries: &[(u32, &wgpu::Buffer)],
    ) -> Result<(), BackendError> {
        let p = self.rec.uniform(&self.ctx, &params)?;
        let mut all = vec![(0, &p), (4, &self.mask)];
        all.extend_from_slice(entries);
        let grid = grid_for(&self.ctx, self.n());
        self.rec
            .dispatch(&self.ctx, kernel(&self.kernels), &all, grid);
        Ok(())
    }

    /// y ← kernel(y, x, slots[num] / slots[den], sign) for axpy_ratio and xpay_ratio.
    fn ratio_update(
        &mut self,
        kernel: fn(&Kernels) -> &Kernel,
        y: &mut GpuField,
        x: &GpuField,
        (num, den): (Slot, Slot),
        sign: f64,
    ) -> Result<(), BackendError> {
        let params = VectorParams {
            num: num.0 as u32,
            den: den.0 as u32,
            sign: sign as f32,
            ..self.vector_params()
        };
        let slots = self.slots.clone();
        self.vector(
            kernel,
            params,
            &[(1, &x.buffer), (3, &y.buffer), (6, &slots)],
        )
    }

    fn vector_params(&self) -> VectorParams {
        VectorParams {
            n: self.n() as u32,
            num: 0,
            den: 0,
            pad0: 0,
            sign: 1.0,
            scalar: 0.0,
            pad1: [0; 2],
        }
    }

    /// Two-pass reduction of `kind` over the fields a, b: partials per workgroup, then one
    /// workgroup into slot `out`.
    fn reduce(
        &mut self,
        kind: Reduction,
        a: &wgpu::Buffer,
        b: &wgpu::Buffer,
        out: u32,
        sigma: f32,
    ) -> Result<(), BackendError> {
        let params = ReduceParams {
            n: self.n() as u32,
            groups: self.reduce_groups,
            out,
            pad0: 0,
            sigma,
            pad1: [0; 3],
        };
        let p = self.rec.uniform(&self.ctx, &params)?;
        let k = &self.kernels;
        let (first, finish, counted) = match kind {
            Reduction::Dot => (&k.dot_partials, &k.finish_sum, true),
            Reduction::Sum => (&k.sum_partials, &k.finish_sum, true),
            Reduction::Crossing => (&k.crossing_partials, &k.finish_min, false),
        };
        // Every first pass reads b (sum_partials statically, with b = a); sums also count.
        let mut entries = vec![
            (0, &p),
            (1, a),
            (2, b),
            (3, &self.mask),
            (4, &self.partials),
        ];
        let mut finishing = vec![(0, &p), (4, &self.partials), (6, &self.slots)];
        if counted {
            entries.push((5, &self.counts));
            finishing.push((5, &self.counts));
        }
        self.rec
            .dispatch(&self.ctx, first, &entries, (self.reduce_groups, 1));
        self.rec.dispatch(&self.ctx, finish, &finishing, (1, 1));
        Ok(())
    }

    fn read_f32(&mut self, slot: u32) -> Result<f32, BackendError> {
        let v: Vec<f32> = self.rec.read(&self.ctx, &self.slots, slot as u64 * 4, 4)?;
        Ok(v[0])
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

impl Backend for GpuBackend {
    type Field = GpuField;

    fn name(&self) -> &'static str {
        "gpu"
    }
    fn precision(&self) -> &'static str {
        "f32"
    }
    fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }
    fn sibling(&self, setup: &GridSetup) -> Result<Self, BackendError> {
        GpuBackend::new(self.ctx.clone(), setup)
    }

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

    fn set_contact(&mut self, mask: &[bool]) -> Result<(), BackendError> {
        self.check_len(mask.len())?;
        self.rec.flush(&self.ctx)?;
        let v: Vec<u32> = mask.iter().map(|&m| m as u32).collect();
        self.ctx
            .queue()
            .write_buffer(&self.mask, 0, bytemuck::cast_slice(&v));
        Ok(())
    }

    fn contact(&mut self, mask: &mut [bool]) -> Result<(), BackendError> {
        self.check_len(mask.len())?;
        let v: Vec<u32> = self
            .rec
            .read(&self.ctx, &self.mask, 0, self.n() as u64 * 4)?;
        for (m, x) in mask.iter_mut().zip(v) {
            *m = x != 0;
        }
        Ok(())
    }

    fn convolve(&mut self, src: &GpuField, dst: &mut GpuField) -> Result<(), BackendError> {
        self.convolution.encode(
            &self.ctx,
            &mut self.rec,
            &self.kernels.spectral,
            &self.fft,
            &src.buffer,
            &dst.buffer,
            &self.mask,
            false,
        )
    }

    fn precondition(&mut self, src: &GpuField, dst: &mut GpuField) -> Result<(), BackendError> {
        match &self.preconditioner {
            None => self.copy(src, dst),
            Some(f) => f.encode(
                &self.ctx,
                &mut self.rec,
                &self.kernels.spectral,
                &self.fft,
                &src.buffer,
                &dst.buffer,
                &self.mask,
                true,
            ),
        }
    }

    fn residual(&mut self, u: &GpuField, d: f64, r: &mut GpuField) -> Result<(), BackendError> {
        let params = VectorParams {
            scalar: d as f32,
            ..self.vector_params()
        };
        let profile = self.profile.clone();
        self.vector(
            |k| &k.residual,
            params,
            &[(1, &u.buffer), (3, &r.buffer), (5, &profile)],
        )
    }

    fn dot(&mut self, a: &GpuField, b: &GpuField, out: Slot) -> Result<(), BackendError> {
        self.reduce(Reduction::Dot, &a.buffer, &b.buffer, out.0 as u32, 0.0)
    }

    fn axpy_ratio(
        &mut self,
        y: &mut GpuField,
        x: &GpuField,
        num: Slot,
        den: Slot,
        sign: f64,
    ) -> Result<(), BackendError> {
        self.ratio_update(|k| &k.axpy_ratio, y, x, (num, den), sign)
    }

    fn xpay_ratio(
        &mut self,
        y: &mut GpuField,
        x: &GpuField,
        num: Slot,
        den: Slot,
    ) -> Result<(), BackendError> {
        self.ratio_update(|k| &k.xpay_ratio, y, x, (num, den), 1.0)
    }

    fn copy_slot(&mut self, src: Slot, dst: Slot) -> Result<(), BackendError> {
        let params = VectorParams {
            num: src.0 as u32,
            den: dst.0 as u32,
            ..self.vector_params()
        };
        let p = self.rec.uniform(&self.ctx, &params)?;
        self.rec.dispatch(
            &self.ctx,
            &self.kernels.copy_slot,
            &[(0, &p), (6, &self.slots)],
            (1, 1),
        );
        Ok(())
    }

    fn read_slots(&mut self, slots: &[Slot], out: &mut [f64]) -> Result<(), BackendError> {
        let v: Vec<f32> = self
            .rec
            .read(&self.ctx, &self.slots, 0, N_SLOTS as u64 * 4)?;
        for (o, s) in out.iter_mut().zip(slots) {
            *o = v[s.0] as f64;
        }
        Ok(())
    }

    fn update_contact(
        &mut self,
        p: &mut GpuField,
        u: &GpuField,
        d: f64,
        sigma_c: f64,
    ) -> Result<ContactChange, BackendError> {
        let params = ContactParams {
            nx: self.nx as u32,
            ny: self.ny as u32,
            d: d as f32,
            sigma: sigma_c as f32,
        };
        let prm = self.rec.uniform(&self.ctx, &params)?;
        self.rec
            .encoder(&self.ctx)
            .clear_buffer(&self.contact_counters, 0, None);
        let grid = grid_for(&self.ctx, self.n());
        self.rec.dispatch(
            &self.ctx,
            &self.kernels.update_contact,
            &[
                (0, &prm),
                (1, &p.buffer),
                (2, &u.buffer),
                (3, &self.mask),
                (4, &self.profile),
                (5, &self.contact_counters),
            ],
            grid,
        );
        let c: Vec<u32> = self.rec.read(&self.ctx, &self.contact_counters, 0, 16)?;
        Ok(ContactChange {
            detached: c[0] as usize,
            attached: c[1] as usize,
            n_contact: c[2] as usize,
            at_edge: c[3] as usize,
        })
    }

    fn first_crossing(
        &mut self,
        p_old: &GpuField,
        p_new: &GpuField,
        sigma_c: f64,
    ) -> Result<f64, BackendError> {
        self.reduce(
            Reduction::Crossing,
            &p_old.buffer,
            &p_new.buffer,
            MIN_SLOT,
            sigma_c as f32,
        )?;
        Ok(self.read_f32(MIN_SLOT)? as f64)
    }

    fn lerp(
        &mut self,
        a: &GpuField,
        b: &GpuField,
        t: f64,
        dst: &mut GpuField,
    ) -> Result<(), BackendError> {
        let params = VectorParams {
            scalar: t as f32,
            ..self.vector_params()
        };
        self.vector(
            |k| &k.lerp,
            params,
            &[(1, &a.buffer), (2, &b.buffer), (3, &dst.buffer)],
        )
    }

    fn copy(&mut self, src: &GpuField, dst: &mut GpuField) -> Result<(), BackendError> {
        let bytes = self.n() as u64 * 4;
        self.rec
            .encoder(&self.ctx)
            .copy_buffer_to_buffer(&src.buffer, 0, &dst.buffer, 0, bytes);
        Ok(())
    }

    fn sum_and_count(&mut self, p: &GpuField) -> Result<(f64, usize), BackendError> {
        self.reduce(Reduction::Sum, &p.buffer, &p.buffer, SUM_SLOT, 0.0)?;
        let sum = self.read_f32(SUM_SLOT)? as f64;
        let c: Vec<u32> =
            self.rec
                .read(&self.ctx, &self.counts, self.reduce_groups as u64 * 4, 4)?;
        Ok((sum, c[0] as usize))
    }

    fn counters(&self) -> Counters {
        self.rec.counters
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
            ..wgpu::Limits::default()
        };
        assert!(check_fits(&limits, 2048, 2048).is_ok());
        assert_eq!(largest_square_grid(&limits), 2048);
        let err = check_fits(&limits, 4096, 4096).unwrap_err().to_string();
        assert!(err.contains("max_storage_buffer_binding_size"), "{err}");
        assert!(err.contains("2048×2048"), "{err}");
        assert!(check_fits(&limits, 4096, 1024).is_ok());
    }
}
