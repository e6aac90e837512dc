//! The 2-D real FFT of a periodic grid of `nx` × `ny` nodes (row-major, x fastest) and the
//! wavevector of each coefficient.
//!
//! The half spectrum holds the coefficients of `kx` in `0..=nx/2` (the others are their
//! complex conjugates) and every `ky` in `0..ny`, stored column by column: coefficient
//! `(kx, ky)` is element `kx * ny + ky`. Transforms are unnormalised, as rustfft's: a forward
//! then an inverse transform multiplies by `nx * ny`.

use realfft::num_complex::Complex;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::{Fft, FftPlanner};
use std::f64::consts::PI;
use std::sync::Arc;

/// The plans of one grid's forward and inverse 2-D transforms.
pub struct Fft2 {
    /// Nodes along x (a count).
    nx: usize,
    /// Nodes along y (a count).
    ny: usize,
    /// Real-to-complex along x.
    r2c: Arc<dyn RealToComplex<f64>>,
    /// Complex-to-real along x.
    c2r: Arc<dyn ComplexToReal<f64>>,
    /// Forward complex transform along y.
    forward_y: Arc<dyn Fft<f64>>,
    /// Inverse complex transform along y.
    inverse_y: Arc<dyn Fft<f64>>,
}

impl Fft2 {
    /// The plans for `nx` × `ny` nodes (each at least 1).
    pub fn new(nx: usize, ny: usize) -> Self {
        let mut real = RealFftPlanner::<f64>::new();
        let mut complex = FftPlanner::<f64>::new();
        Fft2 {
            nx,
            ny,
            r2c: real.plan_fft_forward(nx),
            c2r: real.plan_fft_inverse(nx),
            forward_y: complex.plan_fft_forward(ny),
            inverse_y: complex.plan_fft_inverse(ny),
        }
    }

    /// Columns of the half spectrum: `nx / 2 + 1`.
    pub fn half(&self) -> usize {
        self.nx / 2 + 1
    }

    /// The half spectrum of `heights` (`nx * ny` values, row-major, x fastest).
    pub fn forward(&self, heights: &[f64]) -> Vec<Complex<f64>> {
        let (nx, ny, half) = (self.nx, self.ny, self.half());
        let mut rows = vec![Complex::new(0.0, 0.0); half * ny];
        let mut row = self.r2c.make_input_vec();
        for (values, out) in heights.chunks_exact(nx).zip(rows.chunks_exact_mut(half)) {
            row.copy_from_slice(values);
            // The lengths are the plan's own, so the transform cannot fail.
            let _ = self.r2c.process(&mut row, out);
        }
        // Row-major (ky, kx) to column-major, cache-blocked.
        let mut spectrum = vec![Complex::new(0.0, 0.0); half * ny];
        transpose::transpose(&rows, &mut spectrum, half, ny);
        self.forward_y.process(&mut spectrum);
        spectrum
    }

    /// The real grid (`nx * ny` values, row-major) whose half spectrum is `spectrum`, times
    /// `nx * ny`. The columns `kx = 0` and, for even `nx`, `kx = nx/2` must be Hermitian in
    /// `ky`; the imaginary parts that rounding leaves there after the transform along y are
    /// dropped.
    pub fn inverse(&self, mut spectrum: Vec<Complex<f64>>) -> Vec<f64> {
        let (nx, ny, half) = (self.nx, self.ny, self.half());
        self.inverse_y.process(&mut spectrum);
        let mut rows = vec![Complex::new(0.0, 0.0); half * ny];
        transpose::transpose(&spectrum, &mut rows, ny, half);
        drop(spectrum);
        let mut heights = vec![0.0; nx * ny];
        for (row, values) in rows
            .chunks_exact_mut(half)
            .zip(heights.chunks_exact_mut(nx))
        {
            row[0].im = 0.0;
            if nx % 2 == 0 {
                row[half - 1].im = 0.0;
            }
            // The lengths are the plan's own and the self-conjugate entries are real.
            let _ = self.c2r.process(row, values);
        }
        heights
    }
}

/// The wavenumber (1/length) of FFT index `k` of `n` nodes at `spacing` (length): `2π k / L`
/// for `k ≤ n/2`, `2π (k − n) / L` above, where `L = n * spacing`.
pub fn wavenumber(k: usize, n: usize, spacing: f64) -> f64 {
    let signed = if 2 * k <= n {
        k as f64
    } else {
        k as f64 - n as f64
    };
    2.0 * PI * signed / (n as f64 * spacing)
}

/// How many coefficients of the full spectrum the half spectrum's column `kx` stands for: 1
/// for `kx = 0` and for `kx = nx/2` of an even `nx` (their own conjugates' columns), else 2.
pub fn weight(kx: usize, nx: usize) -> f64 {
    if kx == 0 || 2 * kx == nx {
        1.0
    } else {
        2.0
    }
}
