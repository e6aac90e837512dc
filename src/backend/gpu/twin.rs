//! CPU twins, in f64, of the GPU spectral kernels (`shaders/spectral.wgsl` with
//! `shaders/shared/fft.wgsl`): the same Stockham passes in the same order, the same real-FFT
//! split and merge, the same even/odd column chains and the same buffer layouts, so that a
//! test can compare every GPU pass with its twin, and the twin with rustfft.

use rustfft::num_complex::Complex;
use std::f64::consts::PI;

type C = Complex<f64>;

/// e^{∓2πi k/n} (− forward, + inverse).
fn twiddle(k: usize, n: usize, inverse: bool) -> C {
    let sign = if inverse { 1.0 } else { -1.0 };
    C::from_polar(1.0, sign * 2.0 * PI * k as f64 / n as f64)
}

/// The radix-R DFT of `v` (R = v.len() ∈ {2, 4, 8}).
fn dft(v: &[C], inverse: bool) -> Vec<C> {
    let r = v.len();
    (0..r)
        .map(|k| {
            v.iter()
                .enumerate()
                .map(|(q, &x)| x * twiddle(q * k % r, r, inverse))
                .sum()
        })
        .collect()
}

/// Twin of `fft_lines_in_buf`: transforms every line of `n` values in `data` in place, by
/// radix-8 Stockham passes while three or more factors of two are left, then one radix-4 or
/// radix-2 pass. Unnormalised inverse. Panics unless n is a power of two ≥ 2 dividing
/// `data.len()`.
pub fn fft_lines(data: &mut [C], n: usize, inverse: bool) {
    assert!(n.is_power_of_two() && n >= 2 && data.len().is_multiple_of(n));
    for line in data.chunks_exact_mut(n) {
        let mut ns = 1;
        let mut left = n.trailing_zeros();
        while left > 0 {
            let r = 1usize << left.min(3);
            let src = line.to_vec();
            for j in 0..n / r {
                let m = j % ns;
                let w = twiddle(m, ns * r, inverse);
                let v: Vec<C> = (0..r)
                    .map(|q| src[j + q * n / r] * w.powu(q as u32))
                    .collect();
                let out = (j - m) * r + m;
                for (q, y) in dft(&v, inverse).into_iter().enumerate() {
                    line[out + q * ns] = y;
                }
            }
            ns *= r;
            left -= left.min(3);
        }
    }
}

/// Twin of the three spectral passes for one filter: data nx × ny (row-major), transform
/// 2nx × 2ny (`padded`) or nx × ny, symbol in the GPU's layout and scale (see
/// [`super::spectral::GpuSpectralFilter`]).
pub struct SpectralTwin {
    nx: usize,
    ny: usize,
    padded: bool,
    /// Row FFT length L.
    l: usize,
    /// The symbol in the GPU layout, scaled by 1/(L·my).
    symbol: Vec<f64>,
}

impl SpectralTwin {
    /// The twin of a filter with the CPU filter's symbol `cpu_symbol` (column-major
    /// (mx/2 + 1) × my, scaled by 1/(mx·my), as `SpectralFilter::symbol` gives it).
    pub fn new(nx: usize, ny: usize, padded: bool, cpu_symbol: &[f64]) -> SpectralTwin {
        let l = if padded { nx } else { nx / 2 };
        let my = if padded { 2 * ny } else { ny };
        assert_eq!(cpu_symbol.len(), (l + 1) * my);
        let symbol = if padded {
            (0..=l)
                .flat_map(|k| {
                    (0..2).flat_map(move |parity| {
                        (0..ny).map(move |m| 2.0 * cpu_symbol[k * my + 2 * m + parity])
                    })
                })
                .collect()
        } else {
            cpu_symbol.iter().map(|v| 2.0 * v).collect()
        };
        SpectralTwin {
            nx,
            ny,
            padded,
            l,
            symbol,
        }
    }

    /// Twin of `rows_forward`: the half spectrum, column-major ((L + 1) columns of ny), of
    /// `src` (masked by `mask` where given).
    pub fn rows_forward(&self, src: &[f64], mask: Option<&[bool]>) -> Vec<C> {
        let (nx, ny, l) = (self.nx, self.ny, self.l);
        let mut spec = vec![C::default(); (l + 1) * ny];
        let value = |at: usize| {
            if mask.is_some_and(|m| !m[at]) {
                0.0
            } else {
                src[at]
            }
        };
        for j in 0..ny {
            let mut z: Vec<C> = (0..l)
                .map(|k| {
                    if k < nx / 2 {
                        C::new(value(j * nx + 2 * k), value(j * nx + 2 * k + 1))
                    } else {
                        C::default()
                    }
                })
                .collect();
            fft_lines(&mut z, l, false);
            for k in 0..=l {
                let zk = z[k % l];
                let zc = z[(l - k) % l].conj();
                let e = 0.5 * (zk + zc);
                let d = 0.5 * (zk - zc);
                let o = C::new(d.im, -d.re);
                spec[k * ny + j] = e + twiddle(k, 2 * l, false) * o;
            }
        }
        spec
    }

    /// Twin of `columns`: every column of `spec` filtered along y, in place.
    pub fn columns(&self, spec: &mut [C]) {
        let ny = self.ny;
        for (k, col) in spec.chunks_exact_mut(ny).enumerate() {
            if !self.padded {
                fft_lines(col, ny, false);
                for (m, c) in col.iter_mut().enumerate() {
                    *c *= self.symbol[k * ny + m];
                }
                fft_lines(col, ny, true);
                continue;
            }
            let x = col.to_vec();
            let mut a = Vec::new();
            for parity in 0..2 {
                let mut v: Vec<C> = x
                    .iter()
                    .enumerate()
                    .map(|(m, &xm)| {
                        if parity == 1 {
                            xm * twiddle(m, 2 * ny, false)
                        } else {
                            xm
                        }
                    })
                    .collect();
                fft_lines(&mut v, ny, false);
                for (m, c) in v.iter_mut().enumerate() {
                    *c *= self.symbol[(2 * k + parity) * ny + m];
                }
                fft_lines(&mut v, ny, true);
                if parity == 0 {
                    a = v;
                } else {
                    for m in 0..ny {
                        col[m] = a[m] + twiddle(m, 2 * ny, true) * v[m];
                    }
                }
            }
        }
    }

    /// Twin of `rows_inverse`: the real field from `spec` (zero off `mask` where given).
    pub fn rows_inverse(&self, spec: &[C], mask: Option<&[bool]>) -> Vec<f64> {
        let (nx, ny, l) = (self.nx, self.ny, self.l);
        let mut dst = vec![0.0; nx * ny];
        for j in 0..ny {
            let x: Vec<C> = (0..=l).map(|k| spec[k * ny + j]).collect();
            let mut z: Vec<C> = (0..l)
                .map(|k| {
                    let xk = x[k];
                    let xc = x[l - k].conj();
                    let e = 0.5 * (xk + xc);
                    let o = 0.5 * (xk - xc) * twiddle(k, 2 * l, true);
                    e + C::new(-o.im, o.re)
                })
                .collect();
            fft_lines(&mut z, l, true);
            for (k, zk) in z.iter().take(nx / 2).enumerate() {
                for (i, v) in [(2 * k, zk.re), (2 * k + 1, zk.im)] {
                    let at = j * nx + i;
                    dst[at] = if mask.is_some_and(|m| !m[at]) { 0.0 } else { v };
                }
            }
        }
        dst
    }

    /// The three passes: dst = crop(IFFT(symbol · FFT(pad(src)))).
    pub fn apply(&self, src: &[f64], mask: Option<&[bool]>) -> Vec<f64> {
        let mut spec = self.rows_forward(src, mask);
        self.columns(&mut spec);
        self.rows_inverse(&spec, mask)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backend::cpu::spectral::SpectralFilter;
    use rustfft::FftPlanner;

    #[test]
    fn line_fft_twin_matches_rustfft_for_every_length_to_4096() {
        for log_n in 1..=12 {
            let n = 1usize << log_n;
            for inverse in [false, true] {
                let data: Vec<C> = (0..2 * n)
                    .map(|i| C::new((i as f64 * 0.37).sin(), (i as f64 * 0.11).cos()))
                    .collect();
                let mut twin = data.clone();
                fft_lines(&mut twin, n, inverse);
                let mut planner = FftPlanner::new();
                let fft = if inverse {
                    planner.plan_fft_inverse(n)
                } else {
                    planner.plan_fft_forward(n)
                };
                let mut reference = data;
                fft.process(&mut reference);
                let scale = reference.iter().map(|c| c.norm()).fold(0.0, f64::max);
                let err = twin
                    .iter()
                    .zip(&reference)
                    .map(|(a, b)| (a - b).norm())
                    .fold(0.0, f64::max);
                assert!(err < 1e-12 * scale, "n = {n}, inverse {inverse}: {err}");
            }
        }
    }

    #[test]
    fn spectral_twin_equals_the_rustfft_filter_padded_and_periodic() {
        for (nx, ny) in [(8, 8), (16, 4), (32, 64), (64, 16)] {
            for padded in [true, false] {
                let (mx, my) = if padded { (2 * nx, 2 * ny) } else { (nx, ny) };
                let mut cpu = SpectralFilter::new(nx, ny, mx, my);
                // Real and even in ky, as the kernels' spectra are (the CPU filter drops the
                // imaginary round-off of its DC and Nyquist columns, which that makes exact).
                let symbol: Vec<f64> = (0..(mx / 2 + 1) * my)
                    .map(|i| {
                        let (kx, ky) = (i / my, i % my);
                        2.0 + (kx as f64 * 0.7).sin() * (2.0 * PI * ky as f64 / my as f64).cos()
                    })
                    .collect();
                cpu.set_symbol(&symbol);
                let src: Vec<f64> = (0..nx * ny).map(|i| (i as f64 * 0.3).cos()).collect();
                let mut expected = vec![0.0; nx * ny];
                cpu.apply(&src, &mut expected);
                let twin = SpectralTwin::new(nx, ny, padded, cpu.symbol());
                let got = twin.apply(&src, None);
                let scale = expected.iter().map(|v| v.abs()).fold(0.0, f64::max);
                for (g, e) in got.iter().zip(&expected) {
                    assert!(
                        (g - e).abs() < 1e-12 * scale,
                        "{nx}×{ny} padded {padded}: {g} vs {e}"
                    );
                }
            }
        }
    }
}
