//! The 2-D real spectral filter on the GPU (`shaders/spectral.wgsl`): dst = crop(IFFT(symbol ·
//! FFT(pad(src)))) for data nx × ny, as three dispatches (rows forward, columns, rows inverse)
//! whose FFTs stay in workgroup memory. Its CPU twin is [`super::twin::SpectralTwin`] (the
//! same passes in f64), checked against [`crate::backend::cpu::spectral::SpectralFilter`],
//! whose f64 symbol this filter uploads.

use super::context::GpuContext;
use super::recorder::{groups_grid, module, storage, Kernel, Recorder};
use super::shaders;
use super::slots::NO_SLOT;
use super::traffic;
use crate::backend::cpu::spectral::SpectralFilter;
use crate::backend::{BackendError, Slot};
use wgpu::util::DeviceExt;

/// Values a workgroup of the row or column passes takes when its lines are shorter.
const SHORT_LINES_POINTS: usize = 512;
/// Most lines one workgroup takes (the size of rows_inverse's `nyquist` array).
const LINES_CAP: usize = 256;
/// Workgroup memory the kernels use beside the FFT buffer (bytes): the reduction tree, the
/// Nyquist column, a count.
const OTHER_WORKGROUP_BYTES: u64 = 4096;
/// Values per workgroup of the kernel variants (`POINTS_MAX` of shaders/shared/points_*.wgsl)
/// and their sources.
const VARIANTS: [(usize, &str); 2] = [
    (2048, shaders::SPECTRAL_2048),
    (4096, shaders::SPECTRAL_4096),
];

/// Workgroup memory a variant of `points` values per workgroup needs (bytes): its FFT buffer
/// with one spare cell per eight values, and the rest.
fn workgroup_bytes(points: usize) -> u64 {
    8 * (points + points / 8) as u64 + OTHER_WORKGROUP_BYTES
}

/// The longest FFT line (complex values) that `limits` let one workgroup hold: the longest
/// grid side the backend accepts (0 if not even the smallest variant fits).
pub fn points_max(limits: &wgpu::Limits) -> usize {
    VARIANTS
        .iter()
        .map(|&(p, _)| p)
        .filter(|&p| workgroup_bytes(p) <= limits.max_compute_workgroup_storage_size as u64)
        .max()
        .unwrap_or(0)
}

/// Uniform parameters; must stay in sync with `struct Params` in shaders/spectral.wgsl.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SpectralParams {
    nx: u32,
    ny: u32,
    log_l: u32,
    log_rows: u32,
    log_ny: u32,
    log_cols: u32,
    padded: u32,
    masked: u32,
    dot_slot: u32,
    lines: u32,
    inverse: u32,
    guarded: u32,
}

/// One variant of the spectral kernels (for lines of up to `points` values).
struct Variant {
    points: usize,
    rows_forward: Kernel,
    columns: Kernel,
    rows_inverse: Kernel,
    fft_lines: Kernel,
}

/// The compiled kernels of the spectral module (every variant the adapter's workgroup memory
/// holds) and the twiddle table, shared by every filter of a device.
pub struct SpectralKernels {
    variants: Vec<Variant>,
    twiddle: wgpu::Buffer,
}

/// Entries of the twiddle table e^{−2πik/T} (`TWIDDLE_LEN` in shaders/shared/fft.wgsl).
const TWIDDLE_LEN: usize = 8192;

impl SpectralKernels {
    /// Compile the variants that fit the adapter's workgroup memory and upload the twiddle
    /// table (computed in f64).
    pub fn new(ctx: &GpuContext) -> SpectralKernels {
        let limit = ctx.limits().max_compute_workgroup_storage_size as u64;
        let variants = VARIANTS
            .iter()
            .filter(|&&(p, _)| workgroup_bytes(p) <= limit)
            .map(|&(points, source)| {
                let m = module(ctx, "spectral.wgsl", source);
                let kernel = |entry| {
                    Kernel::new(
                        ctx,
                        &m,
                        entry,
                        shaders::bindings(shaders::SPECTRAL_KERNELS, entry),
                    )
                };
                Variant {
                    points,
                    rows_forward: kernel("rows_forward"),
                    columns: kernel("columns"),
                    rows_inverse: kernel("rows_inverse"),
                    fft_lines: kernel("fft_lines"),
                }
            })
            .collect();
        let table: Vec<[f32; 2]> = (0..TWIDDLE_LEN)
            .map(|k| {
                let a = -2.0 * std::f64::consts::PI * k as f64 / TWIDDLE_LEN as f64;
                [a.cos() as f32, a.sin() as f32]
            })
            .collect();
        SpectralKernels {
            variants,
            twiddle: ctx
                .device()
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("twiddles"),
                    contents: bytemuck::cast_slice(&table),
                    usage: wgpu::BufferUsages::STORAGE,
                }),
        }
    }

    /// The longest line (complex values) the kernels transform: the longest grid side.
    pub fn points_max(&self) -> usize {
        self.variants.iter().map(|v| v.points).max().unwrap_or(0)
    }

    /// The index of the smallest variant for lines of `n` values.
    fn variant_for(&self, n: usize) -> Option<usize> {
        self.variants.iter().position(|v| v.points >= n)
    }

    /// Record the in-place FFT of the `lines` lines of `n` complex values in `buffer`
    /// (`vec2<f32>`, n a power of two in [2, points_max]); the inverse is unnormalised.
    pub fn encode_lines(
        &self,
        ctx: &GpuContext,
        rec: &mut Recorder,
        buffer: &wgpu::Buffer,
        n: usize,
        lines: usize,
        inverse: bool,
    ) -> Result<(), BackendError> {
        let variant = self
            .variant_for(n)
            .filter(|_| n.is_power_of_two() && n >= 2 && lines > 0)
            .ok_or_else(|| {
                BackendError::Unavailable(format!(
                    "FFT lines must have a power-of-two length in [2, {}] (got {n} × {lines})",
                    self.points_max()
                ))
            })?;
        let v = &self.variants[variant];
        let per = (v.points / n).clamp(1, LINES_CAP);
        let params = SpectralParams {
            log_l: n.trailing_zeros(),
            log_rows: per.trailing_zeros(),
            lines: lines as u32,
            inverse: inverse as u32,
            ..bytemuck::Zeroable::zeroed()
        };
        let p = rec.uniform(ctx, &params)?;
        rec.dispatch(
            ctx,
            &v.fft_lines,
            &[(0, &p), (3, buffer), (4, &self.twiddle)],
            groups_grid(ctx, lines.div_ceil(per) as u32),
            2 * 8 * (n * lines) as u64,
        )
    }
}

/// Bytes the largest buffer of a filter needs: the half spectrum, (nx + 1)·ny complex f32
/// values for a padded nx × ny filter.
pub fn largest_buffer_bytes(nx: usize, ny: usize) -> u64 {
    (nx as u64 + 1) * ny as u64 * 8
}

/// A planned filter with its device buffers.
pub struct GpuSpectralFilter {
    nx: usize,
    ny: usize,
    /// Row FFT length L (nx padded, nx/2 periodic).
    l: usize,
    padded: bool,
    spec: wgpu::Buffer,
    symbol: wgpu::Buffer,
    plain: SpectralParams,
    row_groups: u32,
    col_groups: u32,
    /// Which kernel variant (by line length) runs this filter.
    variant: usize,
}

impl GpuSpectralFilter {
    /// Plan the GPU twin of `cpu` (data nx × ny; transform 2nx × 2ny or nx × ny; same symbol)
    /// for `kernels`' device. Refuses sides beyond what one workgroup transforms.
    pub fn new(
        ctx: &GpuContext,
        kernels: &SpectralKernels,
        cpu: &SpectralFilter,
        nx: usize,
        ny: usize,
    ) -> Result<GpuSpectralFilter, BackendError> {
        let (mx, my) = cpu.transform_shape();
        let padded = (mx, my) == (2 * nx, 2 * ny);
        let too_large = |reason: String| BackendError::GridTooLarge {
            nx,
            ny,
            backend: "gpu",
            reason,
        };
        if !padded && (mx, my) != (nx, ny) {
            return Err(too_large(format!(
                "the GPU filter transforms 2nx × 2ny or nx × ny, not {mx} × {my}"
            )));
        }
        if !nx.is_power_of_two() || !ny.is_power_of_two() || nx < 4 || ny < 2 {
            return Err(too_large(
                "the GPU FFT needs power-of-two sides, nx ≥ 4".into(),
            ));
        }
        let l = mx / 2;
        let longest = l.max(ny);
        let variant = kernels.variant_for(longest).ok_or_else(|| {
            too_large(format!(
                "its FFT lines of {longest} values exceed the {} that this adapter's workgroup \
                 memory holds",
                kernels.points_max()
            ))
        })?;
        let points = kernels.variants[variant].points;
        // The CPU symbol carries 1/(mx·my); the GPU round trip needs 1/(L·my) = 2/(mx·my).
        let cpu_symbol = cpu.symbol();
        let columns = l + 1;
        let symbol: Vec<f32> = if padded {
            (0..columns)
                .flat_map(|k| {
                    (0..2).flat_map(move |parity| {
                        (0..ny).map(move |m| (2.0 * cpu_symbol[k * my + 2 * m + parity]) as f32)
                    })
                })
                .collect()
        } else {
            cpu_symbol.iter().map(|&v| (2.0 * v) as f32).collect()
        };
        let device = ctx.device();
        let symbol = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("spectral symbol"),
            contents: bytemuck::cast_slice(&symbol),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let spec = storage(ctx, "half spectrum", (columns * ny) as u64 * 8);
        // Short lines share a workgroup, up to SHORT_LINES_POINTS values (two per thread): enough
        // to keep its threads busy, while small grids still spread over many workgroups.
        let rows_per = (SHORT_LINES_POINTS.min(points) / l).clamp(1, LINES_CAP.min(ny));
        let cols_per = (SHORT_LINES_POINTS.min(points) / ny).clamp(1, LINES_CAP);
        let plain = SpectralParams {
            nx: nx as u32,
            ny: ny as u32,
            log_l: l.trailing_zeros(),
            log_rows: rows_per.trailing_zeros(),
            log_ny: ny.trailing_zeros(),
            log_cols: cols_per.trailing_zeros(),
            padded: padded as u32,
            masked: 0,
            dot_slot: NO_SLOT,
            lines: 0,
            inverse: 0,
            guarded: 0,
        };
        ctx.check()?;
        Ok(GpuSpectralFilter {
            nx,
            ny,
            l,
            padded,
            spec,
            symbol,
            plain,
            row_groups: (ny / rows_per) as u32,
            col_groups: columns.div_ceil(cols_per) as u32,
            variant,
        })
    }

    /// Record dst = crop(IFFT(symbol · FFT(pad(src)))): three dispatches. With `masked`, src
    /// is read as zero off the contact mask and dst written as zero off it. With `dot`
    /// (slot, other), the slot receives Σ dst·other over the grid as a pending sum.
    #[allow(clippy::too_many_arguments)]
    pub fn encode(
        &self,
        ctx: &GpuContext,
        rec: &mut Recorder,
        kernels: &SpectralKernels,
        scalars: &wgpu::Buffer,
        src: &wgpu::Buffer,
        dst: &wgpu::Buffer,
        mask: &wgpu::Buffer,
        masked: bool,
        dot: Option<(Slot, &wgpu::Buffer)>,
    ) -> Result<(), BackendError> {
        self.encode_rows_forward(ctx, rec, kernels, scalars, src, mask, masked)?;
        self.encode_columns(ctx, rec, kernels, scalars)?;
        self.encode_rows_inverse(ctx, rec, kernels, scalars, dst, mask, masked, dot)
    }

    /// Make the filter's next dispatches part of a guarded CG batch (or not): once the batch
    /// has stopped on the device, they return at once.
    pub fn set_guarded(&mut self, guarded: bool) {
        self.plain.guarded = guarded as u32;
    }

    fn params(&self, masked: bool, dot: Option<Slot>) -> SpectralParams {
        SpectralParams {
            masked: masked as u32,
            dot_slot: dot.map_or(NO_SLOT, |s| s.0 as u32),
            ..self.plain
        }
    }

    fn bytes(&self, masked: bool, dot: bool) -> traffic::SpectralBytes {
        traffic::spectral_passes(self.nx, self.ny, self.padded, masked, dot)
    }

    /// Record the first pass: the half spectrum of src's rows into [`Self::spectrum`].
    #[allow(clippy::too_many_arguments)]
    pub fn encode_rows_forward(
        &self,
        ctx: &GpuContext,
        rec: &mut Recorder,
        kernels: &SpectralKernels,
        scalars: &wgpu::Buffer,
        src: &wgpu::Buffer,
        mask: &wgpu::Buffer,
        masked: bool,
    ) -> Result<(), BackendError> {
        let p = rec.storage_params(ctx, &self.params(masked, None))?;
        rec.dispatch(
            ctx,
            &kernels.variants[self.variant].rows_forward,
            &[
                (9, &p),
                (1, src),
                (2, mask),
                (3, &self.spec),
                (4, &kernels.twiddle),
                (8, scalars),
            ],
            groups_grid(ctx, self.row_groups),
            self.bytes(masked, false).rows_forward,
        )
    }

    /// Record the second pass: the columns of [`Self::spectrum`], filtered, in place.
    pub fn encode_columns(
        &self,
        ctx: &GpuContext,
        rec: &mut Recorder,
        kernels: &SpectralKernels,
        scalars: &wgpu::Buffer,
    ) -> Result<(), BackendError> {
        let p = rec.uniform(ctx, &self.params(false, None))?;
        rec.dispatch(
            ctx,
            &kernels.variants[self.variant].columns,
            &[
                (0, &p),
                (3, &self.spec),
                (4, &kernels.twiddle),
                (5, &self.symbol),
                (8, scalars),
            ],
            groups_grid(ctx, self.col_groups),
            self.bytes(false, false).columns,
        )
    }

    /// Record the third pass: dst from [`Self::spectrum`] (and the optional dot product).
    #[allow(clippy::too_many_arguments)]
    pub fn encode_rows_inverse(
        &self,
        ctx: &GpuContext,
        rec: &mut Recorder,
        kernels: &SpectralKernels,
        scalars: &wgpu::Buffer,
        dst: &wgpu::Buffer,
        mask: &wgpu::Buffer,
        masked: bool,
        dot: Option<(Slot, &wgpu::Buffer)>,
    ) -> Result<(), BackendError> {
        let p = rec.uniform(ctx, &self.params(masked, dot.map(|(s, _)| s)))?;
        // Unread when no dot is asked for; the spectrum stands in for it.
        let other = dot.map_or(&self.symbol, |(_, o)| o);
        rec.dispatch(
            ctx,
            &kernels.variants[self.variant].rows_inverse,
            &[
                (0, &p),
                (2, mask),
                (3, &self.spec),
                (4, &kernels.twiddle),
                (6, dst),
                (7, other),
                (8, scalars),
            ],
            groups_grid(ctx, self.row_groups),
            self.bytes(masked, dot.is_some()).rows_inverse,
        )
    }

    /// The half-spectrum buffer between the passes: column k (k ≤ L) holds ny complex f32
    /// values at [k·ny, (k + 1)·ny).
    pub fn spectrum(&self) -> &wgpu::Buffer {
        &self.spec
    }

    /// Row FFT length L.
    pub fn row_length(&self) -> usize {
        self.l
    }

    /// Workgroups of the row passes: the partials of rows_inverse's dot product.
    pub fn row_groups(&self) -> u32 {
        self.row_groups
    }
}
