//! The padded FFT convolution against the direct O(N⁴) influence sum (physics §4).

use crate::common;
use crate::common::flat_setup as setup;

use jkrbem::backend::cpu::CpuBackend;
use jkrbem::backend::kernel::direct_convolution;
use jkrbem::backend::prelude::*;

/// A deterministic pseudo-random pressure field in [−1, 1).
fn pressure(n: usize, seed: u64) -> Vec<f64> {
    common::pseudo_random(n, seed)
}

/// max |a − b| over `scale`.
fn max_relative_difference(a: &[f64], b: &[f64], scale: f64) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// The displacement scale of a signed pressure field: max of K ∗ |p| (random signs cancel in
/// K ∗ p, so its own maximum would understate the magnitudes being summed).
fn magnitude_scale(p: &[f64], nx: usize, ny: usize, dx: f64, e: f64) -> f64 {
    let abs: Vec<f64> = p.iter().map(|v| v.abs()).collect();
    direct_convolution(&abs, nx, ny, dx, e)
        .iter()
        .fold(0.0, |m, v| m.max(*v))
}

#[test]
fn padded_fft_convolution_equals_direct_sum() {
    for &(nx, ny) in &[(16, 16), (32, 16), (16, 32), (8, 64)] {
        let (dx, e) = (0.37, 2.5);
        let p = pressure(nx * ny, (nx * 31 + ny) as u64);
        let direct = direct_convolution(&p, nx, ny, dx, e);
        let mut b = CpuBackend::new(&setup(nx, ny, dx, e)).unwrap();
        let mut u = b.field().unwrap();
        b.convolve(&p, &mut u).unwrap();
        let err = max_relative_difference(&u, &direct, magnitude_scale(&p, nx, ny, dx, e));
        println!("{nx}×{ny}: padded FFT vs direct sum, max relative difference {err:.2e}");
        assert!(err < 1e-12, "{nx}×{ny}: {err:e}");
    }
}
