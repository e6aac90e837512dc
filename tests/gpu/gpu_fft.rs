//! The GPU spectral kernels against their CPU twins (`jkrbem::backend::gpu::twin`, the same
//! passes in f64, themselves checked against rustfft in the library's unit tests):
//! - `fft_lines` (the workgroup-memory FFT alone) on every power-of-two length from 2 to the
//!   adapter's longest line, forward and inverse, several line counts, against rustfft;
//! - each of the three passes of a spectral filter (rows_forward, columns, rows_inverse),
//!   padded and periodic, masked and not, with the fused dot product, against its twin.
//!
//! Skips with a message when no GPU adapter exists, unless `JKRBEM_REQUIRE_GPU=1`.

use crate::common;

use jkrbem::backend::cpu::spectral::SpectralFilter;
use jkrbem::backend::gpu::recorder::{module, Kernel, Recorder};
use jkrbem::backend::gpu::shaders;
use jkrbem::backend::gpu::slots::{scalars_bytes, value_offset};
use jkrbem::backend::gpu::spectral::{GpuSpectralFilter, SpectralKernels};
use jkrbem::backend::gpu::twin::SpectralTwin;
use jkrbem::backend::gpu::{list_adapters, test_context, GpuContext};
use jkrbem::backend::Slot;
use rustfft::num_complex::Complex;
use rustfft::FftPlanner;
use wgpu::util::DeviceExt;

/// Deterministic pseudo-random values in [-1, 1) (64-bit LCG, top bits).
fn pseudo_random(len: usize, seed: u64) -> Vec<f64> {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (0..len)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

/// A storage buffer holding `data` (f32 values of what is given).
fn buffer_of<T: bytemuck::Pod>(ctx: &GpuContext, data: &[T]) -> wgpu::Buffer {
    ctx.device()
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("test data"),
            contents: bytemuck::cast_slice(data),
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
        })
}

fn read_complex(ctx: &GpuContext, rec: &mut Recorder, b: &wgpu::Buffer) -> Vec<Complex<f64>> {
    let v: Vec<[f32; 2]> = rec.read(ctx, b, 0, b.size()).expect("readback");
    v.into_iter()
        .map(|[re, im]| Complex::new(re as f64, im as f64))
        .collect()
}

fn read_real(ctx: &GpuContext, rec: &mut Recorder, b: &wgpu::Buffer) -> Vec<f64> {
    let v: Vec<f32> = rec.read(ctx, b, 0, b.size()).expect("readback");
    v.into_iter().map(f64::from).collect()
}

/// max |x − reference| / max |reference|.
fn relative_error<'a>(
    x: impl Iterator<Item = &'a Complex<f64>>,
    reference: &[Complex<f64>],
) -> f64 {
    let scale = reference.iter().map(|c| c.norm()).fold(0.0, f64::max);
    let diff = x
        .zip(reference)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    diff / scale
}

fn gpu_line_fft_matches_rustfft_within_f32_rounding_times_log2n() {
    let Some(ctx) = test_context() else { return };
    println!("adapter: {}", ctx.adapter_summary());
    assert!(!list_adapters().is_empty(), "the adapter in use is listed");
    let kernels = SpectralKernels::new(&ctx);
    let longest = kernels.points_max();
    println!("lines up to {longest} values run in workgroup memory");
    let mut rec = Recorder::default();
    for log2n in 1..=longest.trailing_zeros() {
        let n = 1usize << log2n;
        let bound = 1e-6 * log2n as f64;
        let mut worst = [0.0f64; 2];
        for lines in [1, 3, 64] {
            for inverse in [false, true] {
                let re = pseudo_random(2 * n * lines, 1000 * log2n as u64 + lines as u64);
                let data32: Vec<[f32; 2]> =
                    re.chunks(2).map(|c| [c[0] as f32, c[1] as f32]).collect();
                let mut expected: Vec<Complex<f64>> = data32
                    .iter()
                    .map(|c| Complex::new(c[0] as f64, c[1] as f64))
                    .collect();
                let mut planner = FftPlanner::new();
                let fft = if inverse {
                    planner.plan_fft_inverse(n)
                } else {
                    planner.plan_fft_forward(n)
                };
                fft.process(&mut expected);
                let b = buffer_of(&ctx, &data32);
                kernels
                    .encode_lines(&ctx, &mut rec, &b, n, lines, inverse)
                    .expect("FFT recorded");
                let got = read_complex(&ctx, &mut rec, &b);
                let err = relative_error(got.iter(), &expected);
                assert!(
                    err <= bound,
                    "n={n} lines={lines} inverse={inverse}: error {err:e} > {bound:e}"
                );
                worst[inverse as usize] = worst[inverse as usize].max(err);
            }
        }
        println!(
            "n = {n:5}: max relative error forward {:.2e}, inverse {:.2e} (bound {bound:.1e})",
            worst[0], worst[1]
        );
    }
}

/// One filter on both sides: the GPU filter and its twin.
struct Case {
    gpu: GpuSpectralFilter,
    twin: SpectralTwin,
}

fn case(ctx: &GpuContext, kernels: &SpectralKernels, nx: usize, ny: usize, padded: bool) -> Case {
    let (mx, my) = if padded { (2 * nx, 2 * ny) } else { (nx, ny) };
    let mut cpu = SpectralFilter::new(nx, ny, mx, my);
    // Real and even in ky, as the influence kernel's and the stiffness's spectra are.
    let symbol: Vec<f64> = (0..(mx / 2 + 1) * my)
        .map(|i| {
            let (kx, ky) = (i / my, i % my);
            2.0 + (kx as f64 * 0.7).sin()
                * (2.0 * std::f64::consts::PI * ky as f64 / my as f64).cos()
        })
        .collect();
    cpu.set_symbol(&symbol);
    Case {
        gpu: GpuSpectralFilter::new(ctx, kernels, &cpu, nx, ny).expect("filter planned"),
        twin: SpectralTwin::new(nx, ny, padded, cpu.symbol()),
    }
}

fn every_spectral_pass_matches_its_twin_padded_and_periodic_masked_and_not() {
    let Some(ctx) = test_context() else { return };
    let kernels = SpectralKernels::new(&ctx);
    let mut rec = Recorder::default();
    let scalars = ctx.device().create_buffer(&wgpu::BufferDescriptor {
        label: Some("scalars"),
        size: scalars_bytes(),
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let finish = Kernel::new(
        &ctx,
        &module(&ctx, "vector", shaders::VECTOR),
        "finish_slots",
        shaders::bindings(shaders::VECTOR_KERNELS, "finish_slots"),
    );
    for (nx, ny) in [(16, 16), (64, 8), (8, 64), (128, 32), (32, 256), (256, 256)] {
        for padded in [true, false] {
            for masked in [false, true] {
                let c = case(&ctx, &kernels, nx, ny, padded);
                let n = nx * ny;
                let src = pseudo_random(n, (nx * 7 + ny) as u64);
                let other = pseudo_random(n, 5);
                let mask: Vec<bool> = pseudo_random(n, 11).iter().map(|v| *v < 0.4).collect();
                let src32: Vec<f32> = src.iter().map(|&v| v as f32).collect();
                let srcx: Vec<f64> = src32.iter().map(|&v| v as f64).collect();
                let other32: Vec<f32> = other.iter().map(|&v| v as f32).collect();
                let mask32: Vec<u32> = mask.iter().map(|&m| m as u32).collect();
                let (src_b, other_b, mask_b) = (
                    buffer_of(&ctx, &src32),
                    buffer_of(&ctx, &other32),
                    buffer_of(&ctx, &mask32),
                );
                let dst_b = buffer_of(&ctx, &vec![0f32; n]);
                let m = masked.then_some(mask.as_slice());
                let label = format!("{nx}×{ny} padded {padded} masked {masked}");

                // Pass 1 alone.
                c.gpu
                    .encode_rows_forward(
                        &ctx, &mut rec, &kernels, &scalars, &src_b, &mask_b, masked,
                    )
                    .unwrap();
                let spec = read_complex(&ctx, &mut rec, c.gpu.spectrum());
                let mut twin_spec = c.twin.rows_forward(&srcx, m);
                let err = relative_error(spec.iter(), &twin_spec);
                assert!(err < 2e-6, "{label}: rows_forward error {err:e}");

                // Pass 2 alone, from the twin's own input (the GPU's pass-1 output).
                c.gpu
                    .encode_columns(&ctx, &mut rec, &kernels, &scalars)
                    .unwrap();
                let filtered = read_complex(&ctx, &mut rec, c.gpu.spectrum());
                let mut from_gpu = spec.clone();
                c.twin.columns(&mut from_gpu);
                let err = relative_error(filtered.iter(), &from_gpu);
                assert!(err < 2e-6, "{label}: columns error {err:e}");

                // Pass 3 alone, with the fused dot product.
                c.gpu
                    .encode_rows_inverse(
                        &ctx,
                        &mut rec,
                        &kernels,
                        &scalars,
                        &dst_b,
                        &mask_b,
                        masked,
                        Some((Slot::new(3), &other_b)),
                    )
                    .unwrap();
                rec.dispatch(&ctx, &finish, &[(8, &scalars)], (16, 1), 0)
                    .unwrap();
                let dst = read_real(&ctx, &mut rec, &dst_b);
                let expected = c.twin.rows_inverse(&filtered, m);
                let scale = expected.iter().map(|v| v.abs()).fold(0.0, f64::max);
                let err = dst
                    .iter()
                    .zip(&expected)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max)
                    / scale;
                assert!(err < 2e-6, "{label}: rows_inverse error {err:e}");
                let dot: Vec<f32> = rec.read(&ctx, &scalars, value_offset(3), 4).unwrap();
                let expected_dot: f64 = expected
                    .iter()
                    .zip(&other32)
                    .map(|(a, &b)| a * b as f64)
                    .sum();
                let norm: f64 = expected
                    .iter()
                    .zip(&other32)
                    .map(|(a, &b)| (a * b as f64).abs())
                    .sum();
                assert!(
                    (dot[0] as f64 - expected_dot).abs() < 1e-5 * norm,
                    "{label}: fused dot {} vs {expected_dot}",
                    dot[0]
                );

                // The whole filter from the same input, against the twin end to end.
                twin_spec = c.twin.rows_forward(&srcx, m);
                c.twin.columns(&mut twin_spec);
                let whole = c.twin.rows_inverse(&twin_spec, m);
                assert_eq!(whole.len(), n);
                let err = dst
                    .iter()
                    .zip(&whole)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max)
                    / scale;
                assert!(err < 5e-6, "{label}: whole filter error {err:e}");
                if masked {
                    assert!(
                        dst.iter().zip(&mask).all(|(v, &m)| m || *v == 0.0),
                        "{label}: masked output is zero off the contact"
                    );
                }
            }
        }
    }
}

/// This file's tests, for `tests/gpu/main.rs`; `missing`: why there is no GPU adapter.
pub fn trials(missing: Option<&str>) -> Vec<libtest_mimic::Trial> {
    common::gpu_trials(
        "gpu_fft",
        &[
            (
                "gpu_line_fft_matches_rustfft_within_f32_rounding_times_log2n",
                gpu_line_fft_matches_rustfft_within_f32_rounding_times_log2n,
            ),
            (
                "every_spectral_pass_matches_its_twin_padded_and_periodic_masked_and_not",
                every_spectral_pass_matches_its_twin_padded_and_periodic_masked_and_not,
            ),
        ],
        &[],
        &[],
        missing,
    )
}
