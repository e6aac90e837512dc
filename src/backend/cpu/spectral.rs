//! A real 2-D spectral filter on the CPU: dst = crop(IFFT(symbol · FFT(pad(src)))).
//!
//! With a transform of 2nx × 2ny and the influence kernel's spectrum as the symbol, this is
//! the non-periodic convolution u = K ∗ p (physics §4); with nx × ny and the stiffness symbol
//! it is the periodic preconditioner. The zero padding and the cropping are fused into the
//! transforms: only the `ny` occupied rows are transformed along x, and only `ny` rows are
//! transformed back.
//!
//! The transforms run in f64 (the reference) or in f32 ([`Real`]): the data stay f64 outside
//! the filter, rounded to the filter's type as a row is loaded and widened back as it is
//! stored, so an f32 filter differs from an f64 one only in the passes' arithmetic (and the
//! symbol's rounding), at twice the SIMD width.

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftNum, FftPlanner};
use std::sync::Arc;

/// The float type a filter's transforms run in: f64 (the reference) or f32.
pub trait Real: FftNum + Default {
    /// `v` rounded to this type.
    fn round_from(v: f64) -> Self;
    /// This value as f64 (exact).
    fn widen(self) -> f64;
}

impl Real for f64 {
    fn round_from(v: f64) -> Self {
        v
    }
    fn widen(self) -> f64 {
        self
    }
}

impl Real for f32 {
    fn round_from(v: f64) -> Self {
        v as f32
    }
    fn widen(self) -> f64 {
        f64::from(self)
    }
}

/// The fewest rows (or columns) one thread takes in a pass.
const PAR_MIN_ROWS: usize = 8;

/// Rows (or columns) of transform length `len` that one thread takes at the least: at least
/// [`PAR_MIN_ROWS`] and [`super::PAR_MIN`] values, so that a small grid's pass runs on the
/// calling thread (rayon's hand-over to another thread costs more than such a pass).
fn min_rows(len: usize) -> usize {
    (super::PAR_MIN / len.max(1)).max(PAR_MIN_ROWS)
}

/// A planned 2-D real-to-complex filter of transform size mx × my acting on nx × ny data
/// (f64 in and out), its transforms in `T` (f64 unless said).
pub struct SpectralFilter<T: Real = f64> {
    nx: usize,
    ny: usize,
    mx: usize,
    my: usize,
    /// Half-spectrum width mx/2 + 1.
    hx: usize,
    r2c: Arc<dyn RealToComplex<T>>,
    c2r: Arc<dyn ComplexToReal<T>>,
    col_fwd: Arc<dyn Fft<T>>,
    col_inv: Arc<dyn Fft<T>>,
    /// Real symbol, column-major (kx * my + ky), already divided by mx·my.
    symbol: Vec<T>,
    /// Row-pass spectra: ny rows of hx values.
    rows: Vec<Complex<T>>,
    /// Column spectra: hx columns of my values.
    cols: Vec<Complex<T>>,
}

impl<T: Real> SpectralFilter<T> {
    /// The elastic operator u = K p of an nx × ny grid of elements of side `dx` (length) on a
    /// half-space of modulus `e_star` (stress): Love's element kernel, zero-padded to
    /// 2nx × 2ny (an isolated contact), or summed over the periodic images, unpadded
    /// (`periodic`; [`crate::backend::kernel::periodic_symbol`]). The symbol is computed in
    /// f64 and rounded to `T`.
    pub fn influence(nx: usize, ny: usize, dx: f64, e_star: f64, periodic: bool) -> Self {
        use crate::backend::kernel::{padded_kernel, periodic_symbol};
        if periodic {
            let mut f = SpectralFilter::new(nx, ny, nx, ny);
            f.set_symbol(&periodic_symbol(nx, ny, dx, e_star));
            f
        } else {
            let mut f = SpectralFilter::new(nx, ny, 2 * nx, 2 * ny);
            f.set_symbol_from_kernel(&padded_kernel(nx, ny, dx, e_star));
            f
        }
    }

    /// Plan a filter of transform size mx × my for data of nx × ny (nx ≤ mx, ny ≤ my), with
    /// a unit symbol. Set the symbol with [`Self::set_symbol`] or [`Self::set_symbol_from_kernel`].
    pub fn new(nx: usize, ny: usize, mx: usize, my: usize) -> Self {
        assert!(nx <= mx && ny <= my && mx >= 2 && my >= 1);
        let hx = mx / 2 + 1;
        let mut rp = RealFftPlanner::<T>::new();
        let mut cp = FftPlanner::<T>::new();
        let scale = T::round_from(1.0 / (mx * my) as f64);
        SpectralFilter {
            nx,
            ny,
            mx,
            my,
            hx,
            r2c: rp.plan_fft_forward(mx),
            c2r: rp.plan_fft_inverse(mx),
            col_fwd: cp.plan_fft_forward(my),
            col_inv: cp.plan_fft_inverse(my),
            symbol: vec![scale; hx * my],
            rows: vec![Complex::default(); ny * hx],
            cols: vec![Complex::default(); hx * my],
        }
    }

    /// Half-spectrum width mx/2 + 1 (number of columns of a symbol).
    pub fn half_width(&self) -> usize {
        self.hx
    }

    /// The symbol in use (column-major, hx × my), already divided by mx·my.
    pub fn symbol(&self) -> &[T] {
        &self.symbol
    }

    /// Transform size (mx, my).
    pub fn transform_shape(&self) -> (usize, usize) {
        (self.mx, self.my)
    }

    /// Use `symbol` (column-major, hx × my, `kx * my + ky`) as the filter's multiplier
    /// (scaled in f64, then rounded to `T`).
    pub fn set_symbol(&mut self, symbol: &[f64]) {
        assert_eq!(symbol.len(), self.hx * self.my);
        let scale = 1.0 / (self.mx * self.my) as f64;
        for (s, v) in self.symbol.iter_mut().zip(symbol) {
            *s = T::round_from(v * scale);
        }
    }

    /// Use the spectrum of a real, even kernel given on the full mx × my grid (row-major)
    /// as the symbol: the filter then convolves with that kernel. The spectrum is taken in
    /// f64 whatever `T` is.
    pub fn set_symbol_from_kernel(&mut self, kernel: &[f64]) {
        assert_eq!(kernel.len(), self.mx * self.my);
        let mut full = SpectralFilter::<f64>::new(self.mx, self.my, self.mx, self.my);
        full.forward(kernel);
        let spectrum: Vec<f64> = full.cols.iter().map(|c| c.re).collect();
        self.set_symbol(&spectrum);
    }

    /// Forward transform of `src` (nx × ny, zero-padded to mx × my, rounded to `T`) into
    /// `self.cols`.
    fn forward(&mut self, src: &[f64]) {
        let (nx, ny, mx, my, hx) = (self.nx, self.ny, self.mx, self.my, self.hx);
        let r2c = &self.r2c;
        self.rows[..ny * hx]
            .par_chunks_mut(hx)
            .with_min_len(min_rows(mx))
            .zip(src.par_chunks(nx))
            .for_each_init(
                || (r2c.make_input_vec(), r2c.make_scratch_vec()),
                |(buf, scratch), (out, row)| {
                    for (b, &v) in buf.iter_mut().zip(row) {
                        *b = T::round_from(v);
                    }
                    buf[nx..].iter_mut().for_each(|v| *v = T::zero());
                    r2c.process_with_scratch(buf, out, scratch)
                        .expect("row transform sizes are planned together");
                },
            );
        let rows = &self.rows;
        let fwd = &self.col_fwd;
        self.cols
            .par_chunks_mut(my)
            .with_min_len(min_rows(my))
            .enumerate()
            .for_each_init(
                || vec![Complex::default(); fwd.get_inplace_scratch_len()],
                |scratch, (kx, col)| {
                    for (ky, c) in col.iter_mut().enumerate() {
                        *c = if ky < ny {
                            rows[ky * hx + kx]
                        } else {
                            Complex::default()
                        };
                    }
                    fwd.process_with_scratch(col, scratch);
                },
            );
    }

    /// dst = crop(IFFT(symbol · FFT(pad(src)))), both nx × ny row-major (f64; the passes in
    /// `T`).
    pub fn apply(&mut self, src: &[f64], dst: &mut [f64]) {
        let (nx, ny, mx, my, hx) = (self.nx, self.ny, self.mx, self.my, self.hx);
        assert!(src.len() == nx * ny && dst.len() == nx * ny);
        self.forward(src);
        let inv = &self.col_inv;
        let symbol = &self.symbol;
        self.cols
            .par_chunks_mut(my)
            .with_min_len(min_rows(my))
            .zip(symbol.par_chunks(my))
            .for_each_init(
                || vec![Complex::default(); inv.get_inplace_scratch_len()],
                |scratch, (col, sym)| {
                    for (c, &s) in col.iter_mut().zip(sym) {
                        *c = c.scale(s);
                    }
                    inv.process_with_scratch(col, scratch);
                },
            );
        let cols = &self.cols;
        let c2r = &self.c2r;
        dst.par_chunks_mut(nx)
            .with_min_len(min_rows(mx))
            .enumerate()
            .for_each_init(
                || {
                    (
                        c2r.make_input_vec(),
                        c2r.make_output_vec(),
                        c2r.make_scratch_vec(),
                    )
                },
                |(spec, out, scratch), (j, row)| {
                    for (kx, s) in spec.iter_mut().enumerate() {
                        *s = cols[kx * my + j];
                    }
                    // A real result has real DC and Nyquist bins; drop round-off there.
                    spec[0].im = T::zero();
                    spec[hx - 1].im = T::zero();
                    c2r.process_with_scratch(spec, out, scratch)
                        .expect("row transform sizes are planned together");
                    for (r, &v) in row.iter_mut().zip(&out[..nx]) {
                        *r = v.widen();
                    }
                },
            );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_symbol_is_identity() {
        let (nx, ny) = (6, 4);
        let src: Vec<f64> = (0..nx * ny).map(|i| (i as f64).sin()).collect();
        let mut dst = vec![0.0; nx * ny];
        let mut f = SpectralFilter::<f64>::new(nx, ny, 16, 8);
        f.apply(&src, &mut dst);
        for (a, b) in src.iter().zip(&dst) {
            assert!((a - b).abs() < 1e-13);
        }
    }
}
