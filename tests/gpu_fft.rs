//! The GPU FFT (shaders/fft.wgsl) agrees with rustfft on every power-of-two length from 2 to
//! 4096, forward and inverse, for several batch counts; and the kernel's CPU twin (the same
//! Stockham stages in f64) agrees with rustfft to f64 rounding.
//!
//! Skips with a message when no GPU adapter exists, unless `JKRBEM_REQUIRE_GPU=1`.

use jkrbem::backend::gpu::fft::stockham_twin;
use jkrbem::backend::gpu::{list_adapters, test_context, GpuContext, GpuFft};
use rustfft::num_complex::Complex;
use rustfft::FftPlanner;

/// Deterministic pseudo-random values in [-1, 1) (64-bit LCG, top bits).
fn pseudo_random(len: usize, seed: u64) -> Vec<Complex<f64>> {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..len).map(|_| Complex::new(next(), next())).collect()
}

/// rustfft in f64 on every line of `n` values.
fn reference(data: &[Complex<f64>], n: usize, inverse: bool) -> Vec<Complex<f64>> {
    let mut planner = FftPlanner::new();
    let fft = if inverse {
        planner.plan_fft_inverse(n)
    } else {
        planner.plan_fft_forward(n)
    };
    let mut out = data.to_vec();
    fft.process(&mut out);
    out
}

/// max |x − reference| / max |reference|.
fn relative_error(x: impl Iterator<Item = Complex<f64>>, reference: &[Complex<f64>]) -> f64 {
    let scale = reference.iter().map(|c| c.norm()).fold(0.0, f64::max);
    let diff = x
        .zip(reference)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    diff / scale
}

const LENGTHS_LOG2: std::ops::RangeInclusive<u32> = 1..=12;

#[test]
fn stockham_twin_matches_rustfft_to_f64_rounding() {
    for log2n in LENGTHS_LOG2 {
        let n = 1usize << log2n;
        for shared_max in [2048, 16, 2] {
            for inverse in [false, true] {
                let data = pseudo_random(3 * n, log2n as u64);
                let mut twin = data.clone();
                stockham_twin(&mut twin, n, inverse, shared_max);
                let err = relative_error(twin.into_iter(), &reference(&data, n, inverse));
                assert!(
                    err <= 1e-14 * log2n as f64,
                    "twin n={n} shared_max={shared_max} inverse={inverse}: error {err:e}"
                );
            }
        }
    }
}

#[test]
fn gpu_fft_matches_rustfft_within_f32_rounding_times_log2n() {
    let Some(ctx) = test_context() else { return };
    println!("adapter: {}", ctx.adapter_summary());
    let adapters = list_adapters();
    for line in &adapters {
        println!("  seen: {line}");
    }
    assert!(!adapters.is_empty(), "the adapter in use is listed");
    let fft = GpuFft::new(&ctx, 4096).expect("FFT pipelines build");
    println!(
        "lines up to {} values run in workgroup memory",
        fft.shared_max()
    );
    let start = std::time::Instant::now();
    for log2n in LENGTHS_LOG2 {
        let n = 1usize << log2n;
        let bound = 1e-6 * log2n as f64;
        let mut worst = [0.0f64; 2];
        for batch in [1, 3, 64] {
            for inverse in [false, true] {
                let err = gpu_vs_rustfft(
                    &fft,
                    &ctx,
                    n,
                    batch,
                    inverse,
                    1000 * log2n as u64 + batch as u64,
                );
                assert!(
                    err <= bound,
                    "n={n} batch={batch} inverse={inverse}: error {err:e} > {bound:e}"
                );
                let w = &mut worst[inverse as usize];
                *w = w.max(err);
            }
        }
        println!(
            "n = {n:5}: max relative error forward {:.2e}, inverse {:.2e} (bound {bound:.1e})",
            worst[0], worst[1]
        );
    }
    println!("GPU FFT checks took {:.2?}", start.elapsed());
}

/// Max relative error of the GPU FFT of `batch` lines of `n` pseudo-random values against
/// rustfft applied to exactly the f32 values the GPU sees.
fn gpu_vs_rustfft(
    fft: &GpuFft,
    ctx: &GpuContext,
    n: usize,
    batch: usize,
    inverse: bool,
    seed: u64,
) -> f64 {
    let data32: Vec<Complex<f32>> = pseudo_random(batch * n, seed)
        .iter()
        .map(|c| Complex::new(c.re as f32, c.im as f32))
        .collect();
    let exact: Vec<Complex<f64>> = data32
        .iter()
        .map(|c| Complex::new(c.re as f64, c.im as f64))
        .collect();
    let cpu = reference(&exact, n, inverse);
    let gpu = fft
        .fft_lines(ctx, &data32, n, inverse)
        .expect("GPU FFT runs");
    relative_error(
        gpu.iter().map(|c| Complex::new(c.re as f64, c.im as f64)),
        &cpu,
    )
}

#[test]
fn gpu_fft_global_memory_stages_match_rustfft() {
    let Some(ctx) = test_context() else { return };
    // With 8-value lines in workgroup memory, n = 16 … 4096 run 1 … 9 global stages, so the
    // result ends in the scratch buffer (odd) as well as in place (even).
    let fft = GpuFft::with_shared_max(&ctx, 4096, 8).expect("FFT pipelines build");
    assert_eq!(fft.shared_max(), 8);
    for log2n in LENGTHS_LOG2 {
        let n = 1usize << log2n;
        let bound = 1e-6 * log2n as f64;
        let mut worst = 0.0f64;
        for (batch, inverse) in [(1, false), (5, true)] {
            let err = gpu_vs_rustfft(&fft, &ctx, n, batch, inverse, 77 + log2n as u64);
            assert!(
                err <= bound,
                "global path n={n} batch={batch} inverse={inverse}: error {err:e} > {bound:e}"
            );
            worst = worst.max(err);
        }
        println!("global path n = {n:5}: max relative error {worst:.2e} (bound {bound:.1e})");
    }
}
