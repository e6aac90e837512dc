//! The 2-D real spectral filter on the GPU (`shaders/spectral.wgsl` around `shaders/fft.wgsl`):
//! dst = crop(IFFT(symbol · FFT(pad(src)))) for data nx × ny and a transform mx × my.
//!
//! A real row costs a half-size complex FFT (hx = mx/2 values); the padding rows are never
//! transformed along x and the cropped rows never transformed back; the column FFTs run on a
//! transposed (column-major) spectrum. Its CPU twin is
//! [`crate::backend::cpu::spectral::SpectralFilter`], whose f64 symbol this filter uploads.

use super::context::GpuContext;
use super::fft::{FftPlan, GpuFft};
use super::recorder::{grid_for, module, storage, Kernel, Recorder};
use crate::backend::cpu::spectral::SpectralFilter;
use crate::backend::BackendError;
use wgpu::util::DeviceExt;

/// Uniform parameters; must stay in sync with `struct Params` in shaders/spectral.wgsl.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SpectralParams {
    nx: u32,
    ny: u32,
    mx: u32,
    my: u32,
    hx: u32,
    masked: u32,
    pad: [u32; 2],
}

/// The compiled kernels of shaders/spectral.wgsl, shared by every filter of a device.
pub struct SpectralKernels {
    pack_rows: Kernel,
    split_rows: Kernel,
    multiply_symbol: Kernel,
    merge_cols: Kernel,
    unpack_rows: Kernel,
}

impl SpectralKernels {
    /// Compile the kernels.
    pub fn new(ctx: &GpuContext) -> SpectralKernels {
        let m = module(
            ctx,
            "spectral.wgsl",
            include_str!("../../../shaders/spectral.wgsl"),
        );
        SpectralKernels {
            pack_rows: Kernel::new(ctx, &m, "pack_rows"),
            split_rows: Kernel::new(ctx, &m, "split_rows"),
            multiply_symbol: Kernel::new(ctx, &m, "multiply_symbol"),
            merge_cols: Kernel::new(ctx, &m, "merge_cols"),
            unpack_rows: Kernel::new(ctx, &m, "unpack_rows"),
        }
    }
}

/// Bytes the largest buffer of a filter of transform size mx × my needs (the column spectra:
/// (mx/2 + 1)·my complex f32 values).
pub fn largest_buffer_bytes(mx: usize, my: usize) -> u64 {
    (mx as u64 / 2 + 1) * my as u64 * 8
}

/// A planned filter with its device buffers.
pub struct GpuSpectralFilter {
    nx: usize,
    ny: usize,
    hx: usize,
    my: usize,
    rows: wgpu::Buffer,
    cols: wgpu::Buffer,
    twiddle: wgpu::Buffer,
    symbol: wgpu::Buffer,
    plain: SpectralParams,
    row_fwd: FftPlan,
    row_inv: FftPlan,
    col_fwd: FftPlan,
    col_inv: FftPlan,
}

impl GpuSpectralFilter {
    /// Plan the GPU twin of `cpu` (same shapes, same symbol) on `fft`'s device.
    pub fn new(
        ctx: &GpuContext,
        fft: &GpuFft,
        cpu: &SpectralFilter,
        nx: usize,
        ny: usize,
    ) -> Result<GpuSpectralFilter, BackendError> {
        let (mx, my) = cpu.transform_shape();
        let hx = mx / 2;
        let device = ctx.device();
        let rows = storage(ctx, "spectral rows", (ny * hx * 8) as u64);
        let cols = storage(ctx, "spectral columns", largest_buffer_bytes(mx, my));
        let twiddle: Vec<[f32; 2]> = (0..=hx)
            .map(|k| {
                let a = -2.0 * std::f64::consts::PI * k as f64 / mx as f64;
                [a.cos() as f32, a.sin() as f32]
            })
            .collect();
        let twiddle = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("r2c twiddles"),
            contents: bytemuck::cast_slice(&twiddle),
            usage: wgpu::BufferUsages::STORAGE,
        });
        // The CPU symbol carries 1/(mx·my); the GPU round trip needs 1/(hx·my) = 2/(mx·my).
        let symbol: Vec<f32> = cpu.symbol().iter().map(|&v| (2.0 * v) as f32).collect();
        let symbol = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("spectral symbol"),
            contents: bytemuck::cast_slice(&symbol),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let plain = SpectralParams {
            nx: nx as u32,
            ny: ny as u32,
            mx: mx as u32,
            my: my as u32,
            hx: hx as u32,
            masked: 0,
            pad: [0; 2],
        };
        Ok(GpuSpectralFilter {
            nx,
            ny,
            hx,
            my,
            row_fwd: fft.plan(ctx, &rows, hx, ny, false)?,
            row_inv: fft.plan(ctx, &rows, hx, ny, true)?,
            col_fwd: fft.plan(ctx, &cols, my, hx + 1, false)?,
            col_inv: fft.plan(ctx, &cols, my, hx + 1, true)?,
            rows,
            cols,
            twiddle,
            symbol,
            plain,
        })
    }

    /// Record dst = crop(IFFT(symbol · FFT(pad(src)))); with `masked`, src is read as zero
    /// off the contact mask and dst is written as zero off it.
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        ctx: &GpuContext,
        rec: &mut Recorder,
        kernels: &SpectralKernels,
        fft: &GpuFft,
        src: &wgpu::Buffer,
        dst: &wgpu::Buffer,
        mask: &wgpu::Buffer,
        masked: bool,
    ) -> Result<(), BackendError> {
        let params = rec.uniform(
            ctx,
            &SpectralParams {
                masked: masked as u32,
                ..self.plain
            },
        )?;
        let (n_rows, n_cols, n_out) = (
            self.ny * self.hx,
            (self.hx + 1) * self.my,
            self.nx * self.ny,
        );
        rec.dispatch(
            ctx,
            &kernels.pack_rows,
            &[(0, &params), (1, src), (3, &self.rows), (7, mask)],
            grid_for(ctx, n_rows),
        );
        self.fft(ctx, rec, fft, &self.row_fwd);
        rec.dispatch(
            ctx,
            &kernels.split_rows,
            &[
                (0, &params),
                (3, &self.rows),
                (4, &self.cols),
                (5, &self.twiddle),
            ],
            grid_for(ctx, n_cols),
        );
        self.fft(ctx, rec, fft, &self.col_fwd);
        rec.dispatch(
            ctx,
            &kernels.multiply_symbol,
            &[(0, &params), (4, &self.cols), (6, &self.symbol)],
            grid_for(ctx, n_cols),
        );
        self.fft(ctx, rec, fft, &self.col_inv);
        rec.dispatch(
            ctx,
            &kernels.merge_cols,
            &[
                (0, &params),
                (3, &self.rows),
                (4, &self.cols),
                (5, &self.twiddle),
            ],
            grid_for(ctx, n_rows),
        );
        self.fft(ctx, rec, fft, &self.row_inv);
        rec.dispatch(
            ctx,
            &kernels.unpack_rows,
            &[(0, &params), (2, dst), (3, &self.rows), (7, mask)],
            grid_for(ctx, n_out),
        );
        Ok(())
    }

    fn fft(&self, ctx: &GpuContext, rec: &mut Recorder, fft: &GpuFft, plan: &FftPlan) {
        let n = fft.encode(rec.encoder(ctx), plan);
        rec.counters.dispatches += n;
    }
}
